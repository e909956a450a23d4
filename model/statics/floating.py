"""The ``elastic`` model with floating cranes: body and crane vessels in one equilibrium.

A crane on a vessel (``[[cranes]] vessel``) has its boom tip on the vessel, above its lug at
the level pose; under the hook loads the vessel heaves h, heels phi and trims theta (the
small-angle hydrostatics of :mod:`liftplan.model.scene.vessel`) and the tip drops by
h + y_t phi + x_t theta, (x_t, y_t) the tip's offset from the flotation centre in the
vessel's axes (forward, starboard). Each vessel adds three unknowns to the body's
(lift a, heel, trim); the potential energy of the whole system::

    V = W z_c + sum_i EA_i max(0, s_i)^2 / (2 l0_i)
              + sum_v (rho A_wp h^2 + disp GM_T phi^2 + disp GM_L theta^2) / 2

    s_i = H_i - drop_i - h_i - l0_i   (drop_i = 0 for a crane on land)

is stationary at the equilibria and least at the stable ones: its gradient in the vessel's
unknowns is each vessel's own balance (rho A_wp h = sum T_i, disp GM_T phi = sum T_i y_t,
disp GM_L theta = sum T_i x_t over its cranes). Newton solves the statics of the body (the
rows of :mod:`liftplan.model.statics.model`) with the vessels' balances; IPOPT on V is the
fallback, polished by Newton; every answer passes the one acceptance (residual, energy
Hessian positive definite, upright).

With the hydrostatics linear the vessels' unknowns are eliminated exactly: the tips drop by
C T (C the tips' compliance matrix), so over the taut ropes T = (D^-1 + C)^-1 s0 = G s0
(D = EA / l0, s0 the stretch with the tips at rest), and the body's three unknowns are all
Newton solves (:class:`CoupledRopeModel`, :func:`coupled_solver`: one compiled function per
rope and vessel count, G formed inside it). That is what :func:`solve_coupled` does first; the
Newton on body and vessels together is its fallback.

A vessel under one crane is a spring in series with the rope, of compliance
1 / (rho A_wp) + y_t^2 / (disp GM_T) + x_t^2 / (disp GM_L): the tensions equal the rope-only
model's with each rope's stiffness replaced by the series stiffness. A vessel carrying two
cranes couples their tips, and no rope-by-rope stiffness reproduces it.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from functools import cache, cached_property

import casadi as ca
import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.results import VesselState
from liftplan.model.scene.objects import name_list
from liftplan.model.statics.acceptance import judge
from liftplan.model.statics.model import (
    NEWTON_OPTIONS,
    FastCall,
    Layout,
    RopeModel,
    pose_points,
    rope_tensions,
    statics_system,
)
from liftplan.model.statics.vertical import (
    elastic_verdict,
    equilibrium_of,
    pack_params,
    solve_elastic,
    worst_residual,
)


@dataclass(frozen=True)
class Fleet:
    """The vessels of a scene as arrays, in scene order of cranes (``Scene.vessels``).

    Parameters
    ----------
    names : tuple of str
        Vessel names.
    membership : numpy.ndarray, shape (m, n)
        1 where crane i stands on vessel v.
    forward, starboard : numpy.ndarray, shape (n,)  [m]
        Each tip's offset from its vessel's flotation centre (0 on land).
    stiffness : numpy.ndarray, shape (m, 3)
        Each vessel's rho A_wp [t/m], disp GM_T and disp GM_L [t m/rad].
    """

    names: tuple[str, ...]
    membership: np.ndarray
    forward: np.ndarray
    starboard: np.ndarray
    stiffness: np.ndarray

    @property
    def params(self):
        """The vessel block of the parameter vector: (M column-major, x_t, y_t, K row-major)."""
        return np.concatenate(
            [self.membership.ravel(order="F"), self.forward, self.starboard, self.stiffness.ravel()]
        )

    def own_compliance(self):
        """Each tip's drop per unit of its own hook load (C's diagonal)  [m/t]."""
        jac, inverse = self._springs
        return (jac * jac) @ inverse

    def compliance(self):
        """The tips' compliance matrix C, drop = C T  [m/t] (n x n)."""
        jac, inverse = self._springs
        return (jac * inverse) @ jac.T

    @cached_property
    def _springs(self):
        """(J, 1/k): the tips drop by J q, q = (1/k) J^T T the vessels' (heave, heel, trim)."""
        on = self.membership.T
        jac = np.hstack([on, on * self.starboard[:, None], on * self.forward[:, None]])
        return jac, 1.0 / self.stiffness.T.ravel()


def tip_plan(scene):
    """World plan positions (n, 2) of the boom tips: above each lug at the level pose  [m]."""
    yaw = math.radians(scene.attitude.yaw)  # R = Rz(yaw) at zero heel and trim
    c, s = math.cos(yaw), math.sin(yaw)
    points = scene.lug_points()
    return np.column_stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]])


def scene_fleet(scene):
    """:class:`Fleet` of a scene with crane vessels (one rope per lug)."""
    vessels = scene.vessels
    n, m = scene.n, len(vessels)
    membership = [[0.0] * n for _ in range(m)]
    forward, starboard = [0.0] * n, [0.0] * n
    tips = tip_plan(scene).tolist()
    for v, (vessel, on) in enumerate(vessels.values()):
        for i in on:
            membership[v][i] = 1.0
            forward[i], starboard[i] = vessel.axes(tips[i])
    stiffness = [(v.heave_stiffness, v.heel_stiffness, v.trim_stiffness) for v, _ in vessels.values()]
    return Fleet(
        tuple(vessels),
        np.array(membership).reshape(m, n),
        np.array(forward),
        np.array(starboard),
        np.array(stiffness).reshape(m, 3),
    )


def vessel_states(scene, fleet, tensions):
    """Each vessel's heave, heel, trim, tip drops and levelling ballast under given tensions.

    Parameters
    ----------
    scene : Scene
    fleet : Fleet
    tensions : array_like, shape (n,)  [t]
        Hook loads in scene order.

    Returns
    -------
    dict of str to VesselState
    """
    t = np.asarray(tensions, dtype=float).ravel()
    member = fleet.membership
    loads = member @ t
    moments = (member @ (t * fleet.starboard), member @ (t * fleet.forward))  # heeling, trimming
    q = np.column_stack([loads, *moments]) / fleet.stiffness  # heave, heel, trim [m, rad]
    drops = (
        member.T @ q[:, 0] + fleet.starboard * (member.T @ q[:, 1]) + fleet.forward * (member.T @ q[:, 2])
    ).tolist()
    labels = [c.label for c in scene.cranes]
    out = {}
    for v, (name, (vessel, on)) in enumerate(scene.vessels.items()):
        heave, heel, trim = q[v].tolist()
        heel_set = heel + vessel.ballast[0] / vessel.heel_stiffness  # with the ballast moment
        trim_set = trim + vessel.ballast[1] / vessel.trim_stiffness
        out[name] = VesselState(
            heave=heave,
            heel=math.degrees(heel_set),
            trim=math.degrees(trim_set),
            tip_drops={labels[i]: drops[i] for i in on},
            load=float(loads[v]),
            levelling_ballast=(0.0 - float(moments[0][v]), 0.0 - float(moments[1][v])),
            max_heel=vessel.max_heel,
            max_trim=vessel.max_trim,
            freeboard=vessel.lowest_freeboard(heave, heel_set, trim_set),
            min_freeboard=vessel.min_freeboard,
        )
    return out


class FloatingModel:
    """The casadi model of n vertical ropes and m crane vessels. Use :func:`floating_model`.

    Parameter vector: the rope layout's (:class:`~liftplan.model.statics.model.Layout`), then
    :attr:`Fleet.params`. Unknowns: (a [m], heel, trim [rad], then per vessel h [m],
    phi, theta [rad]).
    """

    def __init__(self, n, m):
        self.n, self.m = n, m
        self.layout = Layout(n)
        self.size = self.layout.size + m * n + 2 * n + 3 * m
        p = ca.SX.sym("p", self.size)
        z = ca.SX.sym("z", 3 + 3 * m)
        rope = p[: self.layout.size]
        yaw, points, cog, weight, boom, length, stiffness, scale = self.layout.split(rope)
        k = self.layout.size
        member = ca.reshape(p[k : k + m * n], m, n)
        forward = p[k + m * n : k + m * n + n]
        starboard = p[k + m * n + n : k + m * n + 2 * n]
        springs = ca.reshape(p[k + m * n + 2 * n :], 3, m).T  # m x 3
        q = ca.reshape(z[3:], 3, m).T  # m x 3: heave, heel, trim
        drop = ca.mtimes(member.T, q[:, 0]) + starboard * ca.mtimes(member.T, q[:, 1])
        drop += forward * ca.mtimes(member.T, q[:, 2])
        lugs, cog_w = pose_points(points, cog, z[1], z[2], yaw, z[0])
        a_mat, b_vec = statics_system(lugs, cog_w, weight)
        tension, stretch = rope_tensions(boom - drop, lugs[2, :].T, length, stiffness)
        row_scale = ca.vertcat(weight, weight * scale, weight * scale)
        vessel_scale = ca.repmat(ca.horzcat(weight, weight * scale, weight * scale), m, 1)

        def rows(pull):
            """Statics rows (3) and vessel balances (3 m) under rope tensions ``pull``, scaled."""
            statics = ca.mtimes(a_mat, pull) - b_vec
            balance = ca.horzcat(
                springs[:, 0] * q[:, 0] - ca.mtimes(member, pull),
                springs[:, 1] * q[:, 1] - ca.mtimes(member, starboard * pull),
                springs[:, 2] * q[:, 2] - ca.mtimes(member, forward * pull),
            )
            return (
                statics,
                balance,
                ca.vertcat(statics / row_scale, ca.reshape((balance / vessel_scale).T, 3 * m, 1)),
            )

        statics, balance, residual = rows(tension)
        self._taut = rows(stiffness * stretch / length)[2]
        energy = weight * cog_w[2] + ca.sum1(stiffness * ca.fmax(0, stretch) ** 2 / (2 * length))
        energy += 0.5 * ca.sum1(ca.sum2(springs * q**2))
        energy = energy / (weight * scale)
        self._z, self._p = z, p
        self._residual = residual
        self._energy = energy
        self._out = (tension, stretch, ca.vertcat(statics, ca.reshape(balance.T, 3 * m, 1)))
        self._hessian = ca.hessian(energy, z)[0]

    @cached_property
    def start(self):
        """p -> z: one Newton step on the all-taut residual from level, vessels at rest.

        Exact for the linearised kinematics (the residual is then affine in z).
        """
        z, p = self._z, self._p
        z_ref = ca.DM.zeros(z.shape[0])
        jac = ca.substitute(ca.jacobian(self._taut, z), z, z_ref)
        z_start = z_ref - ca.solve(jac, ca.substitute(self._taut, z, z_ref))
        return ca.Function("floating_start", [p], [z_start])

    @cached_property
    def _newton(self):
        return ca.rootfinder(
            "floating_newton",
            "newton",
            {"x": self._z, "p": self._p, "g": self._residual},
            NEWTON_OPTIONS,
        )

    def _function(self, name, with_start):
        p = ca.MX.sym("p", self.size)
        z0 = ca.MX.sym("z0", 3 + 3 * self.m)
        z = self._newton(self.start(p) if with_start else z0, p)
        outputs = ca.Function("outputs", [self._z, self._p], [*self._out, self._hessian])(z, p)
        inputs = [p] if with_start else [z0, p]
        return FastCall(ca.Function(name, inputs, [z, *outputs]))

    @cached_property
    def solver(self):
        """p -> (z, T, stretch, residual [t, t m], energy Hessian): Newton from :attr:`start`."""
        return self._function("floating_solve", with_start=True)

    @cached_property
    def polish(self):
        """(z0, p) -> as :attr:`solver`, Newton from a given start."""
        return self._function("floating_polish", with_start=False)

    @cached_property
    def energy_solver(self):
        """IPOPT on the potential energy: the fallback."""
        return ca.nlpsol(
            "floating_energy",
            "ipopt",
            {"x": self._z, "p": self._p, "f": self._energy},
            {
                "ipopt.print_level": 0,
                "print_time": False,
                "ipopt.tol": 1e-14,
                "ipopt.sb": "yes",
                "ipopt.max_iter": 500,
                "show_eval_warnings": False,
            },
        )


@cache
def floating_model(n, m):
    """The cached :class:`FloatingModel` for n ropes and m vessels."""
    return FloatingModel(n, m)


@dataclass(frozen=True)
class CoupledLayout(Layout):
    """:class:`~liftplan.model.statics.model.Layout` with the ropes' coupled stiffness G
    (n x n, column-major, t/m) APPENDED: ``[..., L, G]`` (every offset of Layout holds)."""

    @property
    def size(self):
        return 6 * self.n + 6 + self.n * self.n

    def coupling(self, p):
        """G (n x n) from a parameter vector."""
        return ca.reshape(p[6 * self.n + 6 :], self.n, self.n)


class CoupledRopeModel(RopeModel):
    """The ``elastic`` model with the crane vessels eliminated: T = G s0. Use
    :func:`coupled_rope_model`.

    With the vessels' hydrostatics linear, each vessel's heave, heel and trim are linear in its
    hook loads, and the tips drop by C T (:meth:`Fleet.compliance`). Over a set S of taut ropes
    T_S = D_S (s0_S - C_SS T_S), D = EA / l0, s0 the stretch with the tips at rest, so::

        T_S = G_S s0_S,   G_S = (D_S^-1 + C_SS)^-1            (the slack ropes' rows 0)

    and minimising the potential energy over the vessels' unknowns leaves
    V(x) = W z_c + s0^T G s0 / 2 (Woodbury on the vessels' block, which is positive definite):
    the same equilibria and the same stability on the body's three unknowns, where
    :class:`FloatingModel` carries three more per vessel. G is a parameter (one compiled model
    per rope count, whatever the vessels); :func:`solve_coupled` picks the taut set.
    The ``stretch`` output is s0; the ropes' own stretch is s0 - C T.
    """

    layout_class = CoupledLayout

    def _rope_law(self, boom, heights, length, stiffness):
        """T = G s0, s0 (the stretch with the tips at rest) and s0^T G s0 / 2."""
        free = boom - heights - length
        coupling = self.layout.coupling(self._p)
        tension = ca.mtimes(coupling, free)
        return tension, free, 0.5 * ca.dot(free, tension)

    @cached_property
    def elastic_start(self):
        """p -> x: one Newton step on the residual from level (exact for the linearised
        kinematics, the tensions being linear in the stretches)."""
        x, p = self._x, self._p
        x_ref = ca.vertcat(0, 0, 0)
        residual = self._elastic[2]
        step = ca.solve(ca.substitute(ca.jacobian(residual, x), x, x_ref), ca.substitute(residual, x, x_ref))
        return ca.Function("coupled_start", [p], [x_ref - step])


@cache
def coupled_rope_model(n):
    """The cached :class:`CoupledRopeModel` for n ropes."""
    return CoupledRopeModel(n)


@cache
def coupled_solver(n, m):
    """(p, taut) -> (x, T, stretch, residual [t, t m], minors, q): the reduced Newton in one call.

    ``p`` is the rope layout's vector then :attr:`Fleet.params`; ``taut`` (n) is 1 on the ropes
    taken taut. One compiled function per rope and vessel count (built once, cached): the
    compliance C = J K^-1 J^T, G = (D^-1 + C)^-1 on the taut set (a linear solve), the Newton of
    :class:`CoupledRopeModel` from its start, each rope's own stretch s0 - C T and the vessels'
    q = K^-1 J^T T (heave, then heel, then trim of each vessel  [m, rad]).
    """
    model = coupled_rope_model(n)
    size = model.layout.size - n * n
    p = ca.MX.sym("p", size + m * n + 2 * n + 3 * m)
    taut = ca.MX.sym("taut", n)
    _, _, _, _, _, length, stiffness, _ = Layout(n).split(p[:size])
    member = ca.reshape(p[size : size + m * n], m, n).T  # n x m
    forward = p[size + m * n : size + m * n + n]
    starboard = p[size + m * n + n : size + m * n + 2 * n]
    springs = ca.reshape(p[size + m * n + 2 * n :], 3, m)  # 3 x m: k_h, k_phi, k_theta
    jac = ca.horzcat(member, member * ca.repmat(starboard, 1, m), member * ca.repmat(forward, 1, m))
    inverse = 1.0 / ca.reshape(springs.T, 3 * m, 1)
    compliance = ca.mtimes(jac * ca.repmat(inverse.T, n, 1), jac.T)
    mask = ca.mtimes(taut, taut.T)
    block = (compliance + ca.diag(length / stiffness)) * mask + ca.diag(1.0 - taut)
    coupling = ca.solve(block, ca.diag(taut), "qr")
    inner = model.elastic_solver.function
    x, tension, free, residual, minors = inner(ca.vertcat(p[:size], ca.reshape(coupling, n * n, 1)))
    stretch = free - ca.mtimes(compliance, tension)
    q = inverse * ca.mtimes(jac.T, tension)
    outputs = [x, tension, stretch, residual, minors, q]
    return FastCall(ca.Function(f"coupled_solve_{n}_{m}", [p, taut], outputs))


def coupled_stiffness(length, ea, compliance, taut):
    """G_S = (D_S^-1 + C_SS)^-1 on the taut ropes S, zero elsewhere  [t/m] (n x n), in numpy
    (what :func:`coupled_solver` forms inside its function).

    Parameters
    ----------
    length, ea : numpy.ndarray, shape (n,)  [m, t]
        Unstretched lengths and EA.
    compliance : numpy.ndarray, shape (n, n)  [m/t]
        The tips' compliance C (:meth:`Fleet.compliance`).
    taut : numpy.ndarray of bool, shape (n,)
    """
    n = len(length)
    out = np.zeros((n, n))
    on = np.flatnonzero(taut)
    if on.size:
        block = np.diag(length[on] / ea[on]) + compliance[np.ix_(on, on)]
        out[np.ix_(on, on)] = np.linalg.inv(block)
    return out


#: Taut sets tried by :func:`solve_coupled` before it hands over to the full Newton.
TAUT_SETS = 8


def check_floating(scene, model):
    """Refuse a scene with crane vessels on a model that does not couple them."""
    if not scene.vessels:
        return
    hulls = [name for name, (v, _) in scene.vessels.items() if v.hull is not None]
    if hulls and (model != "elastic" or scene.hull is not None):
        raise InvalidScene(
            f"cranes.vessel {hulls[0]!r}: a vessel given by her hull (mesh or box) is modelled with the "
            f"elastic model in air; expected model 'elastic' without [hull] and [water] (got {model}), "
            "or her small-angle particulars (waterplane_area, gm_t, gm_l, flotation)"
        )
    if model not in FLOATING_MODELS:
        raise InvalidScene(
            f"cranes.vessel given, but the {model} model holds the boom tips fixed; expected model "
            f"{' or '.join(repr(m) for m in FLOATING_MODELS)} (or no model: elastic is picked when every "
            "crane has boom_height, rope_length and EA)"
        )
    if scene.girder is not None:
        raise InvalidScene(
            "cranes.vessel with hull.EI: a flexible hull on floating cranes is not modelled; "
            "expected one of them"
        )
    shared = [name for name, (_, on) in scene.vessels.items() if len(on) > 1]
    if shared and model not in ("elastic", "hydrostatic"):
        raise InvalidScene(
            f"cranes.vessel: {shared[0]!r} carries {len(scene.vessels[shared[0]][1])} cranes, whose "
            f"coupling the {model} model does not take; expected the elastic or hydrostatic model, "
            "or one crane per vessel"
        )
    slung = [c.label for c in scene.cranes if c.vessel is not None and c.sling is not None]
    if slung:
        raise InvalidScene(
            f"cranes[{slung[0]}].vessel: a crane vessel under a sling set is not modelled; expected "
            "one rope per lug on a floating crane"
        )


#: The models that move the boom tips with their vessels (``rigid`` takes the tensions as
#: the operators hold them and reports the vessels' response to them; ``hydrostatic`` takes
#: each rope in series with its vessel, one crane per vessel).
FLOATING_MODELS = ("elastic", "rigid", "hydrostatic")


def solve_floating(scene):
    """Body and crane vessels in one equilibrium (the ``elastic`` model with floating cranes).

    One crane per vessel: the rope in series with its vessel (exact, module docstring), the
    rope-only Newton with the series stiffness; a vessel under two cranes or more:
    :func:`solve_coupled`.

    Parameters
    ----------
    scene : Scene
        Every crane with boom_height, rope_length and EA; some with a ``vessel``.

    Returns
    -------
    Equilibrium
        With ``vessels``: each vessel's heave, heel, trim and tip drops
        (:class:`~liftplan.model.results.VesselState`).

    Raises
    ------
    EquilibriumNotFound
        No accepted equilibrium (residual, stability, upright).
    """
    fleet = scene_fleet(scene)
    if not np.all(fleet.membership.sum(axis=1) == 1.0):
        return solve_coupled(scene, fleet)
    eq = solve_elastic(scene, stiffness=series_stiffness(scene, fleet))
    method = eq.solver.method + " (series with the crane vessels)"
    eq = dataclasses.replace(eq, solver=dataclasses.replace(eq.solver, method=method))
    return with_vessels(eq, vessel_states(scene, fleet, list(eq.tensions.values())))


def solve_coupled(scene, fleet=None, reduced=True):
    """Body and vessels together, any number of cranes per vessel.

    First the body's three unknowns with the vessels eliminated (:class:`CoupledRopeModel`,
    T = G s0), from all ropes taut: a rope found pulling less than nothing is taken slack, a
    slack one found stretched taut, and solved again until the set holds (each answer passes
    the acceptance). If that does not settle in :data:`TAUT_SETS` sets, or ``reduced`` is
    False: Newton on the body's statics and every vessel's balance together
    (:class:`FloatingModel`, the vessels' heave, heel and trim as unknowns), IPOPT on the
    potential energy as its fallback, polished by Newton. Both answer the same equations: the
    tensions agree to the solvers' tolerance (``tests/model/test_vessels.py``). Returns and
    raises as :func:`solve_floating`.
    """
    fleet = scene_fleet(scene) if fleet is None else fleet
    if reduced:
        found = _solve_reduced(scene, fleet)
        if found is not None:
            return found
    model = floating_model(scene.n, len(fleet.names))
    p = np.concatenate([pack_params(scene, "elastic"), fleet.params])
    start = time.perf_counter()
    z, tensions, stretch, residual, hessian = model.solver(p)
    used = "newton"
    verdict = _verdict(scene, z, residual, hessian)
    if not verdict.ok:
        result = model.energy_solver(x0=model.start(ca.DM(p)), p=ca.DM(p))
        z, tensions, stretch, residual, hessian = model.polish(np.asarray(result["x"]).ravel(), p)
        used = "energy"
        verdict = _verdict(scene, z, residual, hessian)
        if not verdict.ok:
            raise EquilibriumNotFound(
                f"elastic with crane vessels: no stable upright equilibrium found ({verdict.reason()}); "
                "check that the boom heights and rope lengths can hold the body with three or more "
                "taut ropes"
            )
    seconds = time.perf_counter() - start
    return _coupled_result(scene, fleet, z[:3], tensions, stretch, residual[:3], used, seconds)


def _coupled_result(scene, fleet, x, tensions, stretch, residual, used, seconds, how=""):
    slack = tuple(name for name, s in zip(scene.lug_names, stretch) if s <= 0.0)
    if scene.n - len(slack) < 3:
        raise EquilibriumNotFound(
            f"elastic: only {scene.n - len(slack)} rope(s) taut ({name_list(slack)} slack): "
            "expected three or more to hold the body"
        )
    eq = equilibrium_of(
        scene, "elastic", x, tensions, residual, used + " (body and crane vessels)" + how, seconds, slack
    )
    return with_vessels(eq, vessel_states(scene, fleet, tensions))


def _solve_reduced(scene, fleet):
    """:func:`solve_coupled` on the body's unknowns (:func:`coupled_solver`); None when no taut
    set settles with an accepted answer (the caller goes on to the full Newton)."""
    solver = coupled_solver(scene.n, len(fleet.names))
    p = np.concatenate([pack_params(scene, "elastic"), fleet.params])
    taut = np.ones(scene.n)
    start = time.perf_counter()
    for _ in range(TAUT_SETS):
        x, tensions, stretch, residual, minors, _ = solver(p, taut)
        if not elastic_verdict(scene, x, residual, minors).ok:
            return None
        now = next_taut(taut, tensions, stretch)
        if np.array_equal(now, taut):
            seconds = time.perf_counter() - start
            how = " on the ropes' coupled stiffness"
            return _coupled_result(scene, fleet, x, tensions, stretch, residual, "newton", seconds, how)
        if now.sum() < 3:
            return None
        taut = now
    return None


def next_taut(taut, tensions, stretch):
    """The next taut set: the rope pulling least (a compression) taken slack, one at a time
    (dropping every rope in compression at once can leave fewer than three), and every slack
    rope found stretched taken taut; ``taut`` itself when it holds."""
    now = np.where(stretch > 0.0, 1.0, 0.0)
    pushed = (taut > 0.0) & (stretch <= 0.0)
    if pushed.any():
        now = np.where(taut > 0.0, 1.0, now)
        now[int(np.argmin(np.where(pushed, tensions, np.inf)))] = 0.0
    return now


def series_stiffness(scene, fleet):
    """Each rope's EA with its vessel in series: l0 / (l0 / EA + c), c the tip's compliance  [t].

    Exact for a vessel under one crane (a crane on land keeps its EA); see the module docstring.
    """
    length = np.array(scene.crane_values("rope_length", "elastic"))
    ea = np.array(scene.crane_values("EA", "elastic"))
    return length / (length / ea + fleet.own_compliance())


def series_scene(scene, fleet=None):
    """The scene with each floating crane's rope in series with its own vessel: its EA the
    series stiffness, its vessel dropped (one crane per vessel; any vertical-rope model)."""
    fleet = scene_fleet(scene) if fleet is None else fleet
    ea = series_stiffness(scene, fleet)
    cranes = tuple(dataclasses.replace(c, EA=float(e), vessel=None) for c, e in zip(scene.cranes, ea))
    return dataclasses.replace(scene, cranes=cranes)


def with_vessels(eq, states):
    """``eq`` carrying its vessels' states."""
    return dataclasses.replace(eq, vessels=states)


def _verdict(scene, z, residual, hessian):
    """The acceptance, on the body's statics and the vessels' balances together."""
    m = (len(z) - 3) // 3
    body = worst_residual(scene, residual[:3]) / scene.body.weight
    balance = np.abs(np.asarray(residual[3:], dtype=float)).reshape(m, 3) if m else np.zeros((0, 3))
    scale = np.array([1.0, scene.plan_diameter, scene.plan_diameter])
    worst = max([body, *(balance / scale).max(axis=1, initial=0.0) / scene.body.weight]) if m else body
    size = len(z)
    return judge(worst, z[1], z[2], hessian=np.asarray(hessian, dtype=float).reshape(size, size))
