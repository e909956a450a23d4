"""Inclined lines: the 6-DOF body, free points (hooks, spreader ends) and the lines between.

One casadi model for every scene whose ropes are not vertical: crane tips placed in the
world (the ``inclined`` model: one rope per lug, the pendulum effect) and sling sets with
their hooks and spreader bars (the ``rigging`` model, :mod:`liftplan.model.statics.rigging`). A
scene is a network of

* points: the body's lugs p_k (body frame; at r_k = t + R p_k in the world, R = R(heel, trim,
  yaw) of :mod:`liftplan.model.frames`), fixed crane tips q (world), and free points f
  (world; hooks and spreader-bar ends), each free point optionally carrying a weight;
* members between two points a and b, of unstretched length l0 and stiffness EA, at
  length L = |b - a|: a *line* (rope or sling leg) carries T = EA / l0 max(0, L - l0), tension
  only; a *strut* (spreader bar) carries T = EA / l0 (L - l0), compression when < 0.

Unknowns: the body's position t and attitude (6) and 3 per free point. Equations: force
and moment about the CG on the body, force on each free point. The same forces derive from
the potential V = W z_G + sum w_j z_j + sum EA / (2 l0) s^2 (s = max(0, L - l0) for a line,
L - l0 for a strut), whose stable stationary points are the equilibria the solver may
return (:mod:`liftplan.model.statics.acceptance`). A crane without a ``tip`` has its tip above its
lug's start position (or its lugs' centroid) at its boom height, so tips above the lugs
reduce to the vertical-rope model exactly where the equilibrium keeps the lugs under them
(tested).

Horizontal rope forces are what the vertical model leaves out: they swing the body until
its CG sits where the rope directions balance, and they load the boom sideways.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import cache, cached_property

import casadi as ca
import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import rotation
from liftplan.model.results import Equilibrium, Pose, SolverInfo
from liftplan.model.statics.acceptance import RESIDUAL_TOL, judge

__all__ = ["RESIDUAL_TOL", "Member", "RopeForce", "Topology", "network_model", "solve_inclined"]


@dataclass(frozen=True)
class RopeForce:
    """Force of one rope on its lower end (world frame).

    Parameters
    ----------
    force : tuple of 3 float  [t]
    horizontal : float  [t]
        Magnitude of the horizontal part (the side load on the crane's boom).
    angle : float  [deg]
        Rope inclination from the vertical.
    """

    force: tuple[float, float, float]
    horizontal: float
    angle: float

    @classmethod
    def of(cls, pull):
        """From the pull vector on the lower end  [t]."""
        horizontal = float(math.hypot(pull[0], pull[1]))
        angle = math.degrees(math.atan2(horizontal, pull[2]))  # 0 for a slack rope's zero pull
        return cls(tuple(float(v) for v in pull), horizontal, angle)


@dataclass(frozen=True)
class Member:
    """A line or strut between two points of the network.

    Parameters
    ----------
    kind : {"line", "strut"}
        A line carries tension only; a strut tension and compression.
    a, b : tuple (str, int)
        End points: ``("lug", k)`` body point, ``("tip", k)`` fixed world point,
        ``("free", k)`` free point. The member's force on end ``a`` is reported (towards b).
    """

    kind: str
    a: tuple[str, int]
    b: tuple[str, int]


@dataclass(frozen=True)
class Topology:
    """What is joined to what: the shape of one casadi model (cached per topology).

    Parameters
    ----------
    lugs, tips, free : int
        Numbers of body points, fixed points and free points.
    members : tuple of Member
    """

    lugs: int
    tips: int
    free: int
    members: tuple[Member, ...]

    @property
    def size(self):
        """Length of the parameter vector: [P (3 lugs), tips (3 tips), l0, EA (each per
        member), free-point weights, W, G (3), L]."""
        return 3 * self.lugs + 3 * self.tips + 2 * len(self.members) + self.free + 5

    def pack(self, lug_points, tips, lengths, stiffness, weights, weight, cog, scale):
        """The parameter vector, from arrays in the order of :attr:`size`."""
        return np.concatenate(
            [np.ravel(lug_points), np.ravel(tips), lengths, stiffness, weights, [weight], cog, [scale]]
        ).astype(float)


class NetworkModel:
    """Residual, energy and solvers of one :class:`Topology`. Use :func:`network_model`."""

    def __init__(self, topology):
        self.topology = top = topology
        nl, nt, nf, m = top.lugs, top.tips, top.free, len(top.members)
        x = ca.SX.sym("x", 6 + 3 * nf)
        p = ca.SX.sym("p", top.size)
        k = 0

        def take(count):
            nonlocal k
            part = p[k : k + count]
            k += count
            return part

        lug_points = ca.reshape(take(3 * nl), 3, nl)
        tips = ca.reshape(take(3 * nt), 3, nt)
        length, stiffness, weights = take(m), take(m), take(nf)
        weight, cog, scale = take(1), take(3), take(1)
        rot = rotation(x[3], x[4], x[5])
        centre = x[:3] + ca.mtimes(rot, cog)
        free = ca.reshape(x[6:], 3, nf)
        points = {
            "lug": [x[:3] + ca.mtimes(rot, lug_points[:, i]) for i in range(nl)],
            "tip": [tips[:, i] for i in range(nt)],
            "free": [free[:, i] for i in range(nf)],
        }
        body_force = ca.vertcat(0, 0, -weight)
        body_moment = ca.SX.zeros(3)
        free_force = [ca.vertcat(0, 0, -weights[j]) for j in range(nf)]
        energy = weight * centre[2] + sum((weights[j] * free[2, j] for j in range(nf)), ca.SX(0))
        tensions, pulls, spans = [], [], []
        for i, member in enumerate(top.members):
            a, b = points[member.a[0]][member.a[1]], points[member.b[0]][member.b[1]]
            d = b - a
            span = ca.sqrt(ca.dot(d, d) + 1e-300)  # guard: a zero-length start has no direction
            stretch = span - length[i]
            if member.kind == "line":
                stretch = ca.fmax(0, stretch)
            tension = stiffness[i] / length[i] * stretch
            energy += stiffness[i] * stretch**2 / (2 * length[i])
            pull = tension * d / span  # on end a, towards b
            for end, sign in ((member.a, 1), (member.b, -1)):
                if end[0] == "lug":
                    body_force += sign * pull
                    body_moment += ca.cross(points["lug"][end[1]] - centre, sign * pull)
                elif end[0] == "free":
                    free_force[end[1]] += sign * pull
            tensions.append(tension)
            pulls.append(pull)
            spans.append(span)
        residual = ca.vertcat(
            body_force / weight, body_moment / (weight * scale), *[f / weight for f in free_force]
        )
        energy = energy / (weight * scale)
        self._x, self._p, self._residual, self._energy = x, p, residual, energy
        self.evaluate = ca.Function(
            "network",
            [x, p],
            [residual, ca.vertcat(*tensions), ca.horzcat(*pulls), ca.vertcat(*spans)],
            ["x", "p"],
            ["r", "tension", "pull", "length"],
        )
        self.hessian = ca.Function("network_hessian", [x, p], [ca.hessian(energy, x)[0]])

    @cached_property
    def newton(self):
        # Newton's own failure flag is off (casadi would print and raise); the answer is
        # judged by the acceptance instead.
        return ca.rootfinder(
            "network_root",
            "newton",
            ca.Function("g", [self._x, self._p], [self._residual]),
            {
                "abstol": 1e-13,
                "abstolStep": 1e-15,
                "max_iter": 80,
                "error_on_fail": False,
                "show_eval_warnings": False,
            },
        )

    @cached_property
    def energy_solver(self):
        """IPOPT on the potential energy: the slower, more forgiving fallback."""
        return ca.nlpsol(
            "network_energy",
            "ipopt",
            {"x": self._x, "p": self._p, "f": self._energy},
            {
                "ipopt.print_level": 0,
                "print_time": False,
                "ipopt.tol": 1e-14,
                "ipopt.sb": "yes",
                "ipopt.max_iter": 1000,
                "show_eval_warnings": False,
            },
        )

    def verdict(self, x, p):
        """The acceptance (:func:`liftplan.model.statics.acceptance.judge`) of a candidate state."""
        residual = np.asarray(self.evaluate(x, p)[0]).ravel()
        worst = float(np.max(np.abs(residual))) if np.all(np.isfinite(residual)) else math.inf
        return judge(worst, x[3], x[4], hessian=np.asarray(self.hessian(x, p)))

    def _root(self, x0, p):
        x = np.asarray(self.newton(ca.DM(x0), ca.DM(p))).ravel()
        return x, int(self.newton.stats().get("iter_count", -1))

    def solve(self, x0, p, label):
        """Newton from ``x0``; if its answer is not accepted, IPOPT on the energy from
        ``x0`` polished by Newton. Both answers pass the same acceptance.

        Returns
        -------
        x : numpy.ndarray
        info : SolverInfo

        Raises
        ------
        EquilibriumNotFound
            Neither answer is a stable upright equilibrium (the reason in one line).
        """
        begin = time.perf_counter()
        x, iterations = self._root(x0, p)
        verdict, method = self.verdict(x, p), "newton"
        if not verdict.ok:
            first = verdict
            result = self.energy_solver(x0=ca.DM(x0), p=ca.DM(p))
            x, iterations = self._root(np.asarray(result["x"]).ravel(), p)
            verdict, method = self.verdict(x, p), "energy"
            if not verdict.ok:
                raise EquilibriumNotFound(
                    f"{label}: no stable upright equilibrium found (Newton: {first.reason()}; "
                    f"energy minimisation then Newton: {verdict.reason()}); check tips, lengths "
                    "and the start attitude"
                )
        return x, SolverInfo(method, True, iterations, time.perf_counter() - begin)


@cache
def network_model(topology):
    """The cached :class:`NetworkModel` of a :class:`Topology`."""
    return NetworkModel(topology)


def crane_tips(scene):
    """World tip positions of one-rope cranes, shape (n, 3)  [m]: the given ``tip``, or above
    the lug's start position at the boom height."""
    a = scene.attitude
    start = scene.lug_points() + [0.0, 0.0, a.lift_height]
    tips = []
    for crane, lug in zip(scene.cranes, start):
        if crane.tip is not None:
            tips.append(crane.tip)
        elif crane.boom_height is not None:
            tips.append((lug[0], lug[1], crane.boom_height))
        else:
            raise InvalidScene(f"cranes[{crane.label}]: expected tip = [x, y, z] or boom_height")
    return np.array(tips, dtype=float)


def start_pose(scene):
    """The body's start: origin at (0, 0, lift_height), the scene's attitude  (m, rad)."""
    a = scene.attitude
    return np.array(
        [0.0, 0.0, a.lift_height, math.radians(a.heel), math.radians(a.trim), math.radians(a.yaw)]
    )


def refuse_water(scene, what):
    if scene.hull is not None:
        raise InvalidScene(
            f"{what} on a hull in water are not modelled; expected tips above the lugs "
            "(vertical ropes) and no slings for a scene with [hull] and [water]"
        )


def solve_inclined(scene):
    """6-DOF equilibrium on inclined ropes, one per lug.

    Parameters
    ----------
    scene : Scene
        Cranes with ``rope_length`` and ``EA``, and ``tip`` or ``boom_height``. No hull, no
        slings (those are the ``rigging`` model).

    Returns
    -------
    Equilibrium
        ``model = "inclined"``; ``rope_forces`` holds each rope's force and inclination,
        ``position`` the body origin's world position.
    """
    refuse_water(scene, "cranes.tip: inclined ropes")
    if scene.slings:
        raise InvalidScene(
            "cranes.sling given, but the inclined model hangs one rope per lug; "
            "expected model 'rigging' (or no model: it is picked for slings)"
        )
    n = scene.n
    length, stiffness = scene.crane_values("rope_length", "inclined"), scene.crane_values("EA", "inclined")
    topology = Topology(n, n, 0, tuple(Member("line", ("lug", i), ("tip", i)) for i in range(n)))
    body = scene.body
    p = topology.pack(
        scene.lug_points(),
        crane_tips(scene),
        length,
        stiffness,
        [],
        body.weight,
        body.cog,
        max(scene.plan_diameter, 1.0),
    )
    model = network_model(topology)
    x, info = model.solve(start_pose(scene), p, "inclined")
    _, tensions, pulls, _ = (np.asarray(v) for v in model.evaluate(x, p))
    tensions = tensions.ravel()
    taut = int(np.sum(tensions > 0))
    if taut < 3:
        raise EquilibriumNotFound(
            f"inclined: only {taut} rope(s) taut at the equilibrium found; expected three or more "
            "to hold the body (check tips and lengths)"
        )
    names = scene.lug_names
    residual = np.asarray(model.evaluate(x, p)[0]).ravel()
    return Equilibrium(
        model="inclined",
        pose=Pose(
            heel=math.degrees(x[3]), trim=math.degrees(x[4]), yaw=math.degrees(x[5]), lift_height=float(x[2])
        ),
        tensions=dict(zip(names, tensions.tolist())),
        weight=body.weight,
        swl={c.lug: c.swl for c in scene.cranes},
        slack=tuple(name for name, t in zip(names, tensions) if t <= 0.0),
        residual=float(np.max(np.abs(residual))) * body.weight,
        solver=info,
        rope_forces={name: RopeForce.of(pull) for name, pull in zip(names, pulls.T)},
        position=(float(x[0]), float(x[1]), float(x[2])),
        frame=scene.frame,
    )
