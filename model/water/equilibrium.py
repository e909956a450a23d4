"""Equilibrium of a hull in water: stranded on a ground contact, afloat, or hanging from
vertical crane ropes, with exact (clipped-mesh) buoyancy.

Two methods for the stranded ship:

* ``"newton"`` (default): casadi's Newton root-finder on the exact residual of
  :class:`~liftplan.model.water.afloat.AfloatModel`; its Jacobian is the exact derivative of the
  clipped-mesh sums, so it converges quadratically.
* ``"paper-newton"``: the stranded-ship paper's iteration. The hydrostatic derivative
  matrix D of (F, M_T, M_L) with respect to (immersion, heel, trim) about the body origin
  is built from the waterplane (area, centre, second moments) and the displacement; the
  pivot constraint delta_zo = -y_R delta_heel + x_R delta_trim gives J, and each step solves
  (J^T D J) delta = -J^T f. D leaves out the change of the ground reaction's arm, so the
  convergence is linear, as the paper's 5 and 20 iterations show. Here zo is recomputed
  from the pivot after each step (the pivot stays on the ground exactly).

When the ground reaction of the grounded solution is <= 0 the hull floats free: the
free-floating equilibrium (or hanging, with ropes) is solved instead and ``state`` says so
(:func:`water_state`: grounded, hanging submerged, piercing the surface, clear, afloat).

Breakout (``[ground] breakout``, :mod:`.breakout`): the soil holds a bedded hull down with up
to the breakout force F_b. It acts as a downward force at the ground contact, so it adds to
the weight at that point: grounded (moments about the contact, which it does not enter)
the hull stays put while the ropes carry less than W + trapped water - B + F_b, i.e. while
the soil's pull (the negative part of the ground reaction) stays within F_b; then it breaks
out and hangs with F_b still pulling at the contact (the soil holds on while the hull rises
``clear`` m) and is released above that (:func:`settle`).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import casadi as ca
import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import attitude_angles, rotation_matrix, tilt
from liftplan.model.results import Afloat, Equilibrium, Pose, SolverInfo
from liftplan.model.statics.acceptance import RESIDUAL_TOL
from liftplan.model.statics.vertical import solve_elastic
from liftplan.model.water.afloat import AfloatModel, Layout, buoyancy_weights
from liftplan.model.water.breakout import breakout_force
from liftplan.model.water.hydrostatics import MeshHydrostatics
from liftplan.model.water.state import hull_heights, water_state

# The paper's stopping tolerance: 1 t and 1 t m.
PAPER_TOL = 1.0
PAPER_MAX_ITER = 500
METHODS = ("newton", "paper-newton")
# Reporting at the scene's yaw (see unyaw): near upright the needed turn about the vertical
# is second order in the tilts (0.016 deg on the barge); with the body's trim axis within
# ~25 deg of vertical (|R[2, 1]| > 0.9, heel near 90) only turns up to MAX_TURN deg are made.
MAX_TURN = 5.0
TRIM_AXIS_VERTICAL = 0.9


@dataclass(frozen=True)
class Start:
    """A pose to start from: the body origin's height over the water and the attitude.

    Parameters
    ----------
    zo : float  [m]
    rotation : numpy.ndarray, shape (3, 3)
    """

    zo: float
    rotation: np.ndarray


@dataclass(frozen=True)
class BodyLoads:
    """What the hull carries at one instant besides its own weight (body frame).

    Parameters
    ----------
    trapped : float  [t]
        Water in compartments.
    trapped_centre : tuple of 3 float or None  [m]
        Its centre, body frame (None without water).
    soil : float  [t]
        The soil's downward pull at the ground contact (breakout), 0 without.
    """

    trapped: float
    trapped_centre: tuple[float, float, float] | None
    soil: float = 0.0


class WaterSetup:
    """The casadi model and parameter vector of a scene with a hull in water (built once).

    Parameters
    ----------
    scene : Scene
        With ``hull`` and ``water``; ropes (vertical, above their lugs) and ``ground``
        optional.
    coupling : numpy.ndarray, shape (n, n), optional  [t/m]
        The ropes' coupled stiffness G: tensions T = G (H - h - l0) on the taut set G is
        made for (crane vessels under several cranes, :mod:`liftplan.model.water.vessels`);
        :meth:`couple` changes it.
    """

    def __init__(self, scene, coupling=None):
        if scene.hull is None:
            raise InvalidScene("scene: no [hull] and [water]; expected them for a solve in water")
        self.scene = scene
        water, hull, body = scene.water, scene.hull, scene.body
        tris, kappa, trapped = buoyancy_weights(hull, body.weight, water.density)
        self.trapped = float(sum(w for w, _ in trapped))
        self.trapped_centre = hull.trapped_water(water.density)[1]
        gravity = body.weight + self.trapped
        cog = (body.weight * np.asarray(body.cog) + sum(w * np.asarray(c) for w, c in trapped)) / gravity
        self.gravity, self.cog = gravity, cog
        self.model = AfloatModel(tris, kappa, scene.n, coupled=coupling is not None)
        self.envelope = MeshHydrostatics(hull.triangles)
        a = scene.attitude
        ground = scene.ground
        if ground is not None:
            self.contact_world = np.asarray(ground.contact) + [0.0, 0.0, a.lift_height]
            pivot, self.ground_height = np.asarray(ground.contact), self.contact_world[2] - water.level
        else:
            self.contact_world = None
            pivot, self.ground_height = cog, 0.0
        ropes = []
        if any(c.tip is not None for c in scene.cranes):
            raise InvalidScene(
                "cranes.tip: inclined ropes on a hull in water are not modelled; expected tips "
                "above the lugs (no tip: vertical ropes) for a scene with [hull] and [water]"
            )
        if scene.n:
            model = "hydrostatic (a hull hanging from ropes)"
            hook = [h - water.level for h in scene.crane_values("boom_height", model)]
            ropes = [
                scene.lug_points().ravel(),
                hook,
                scene.crane_values("rope_length", model),
                scene.crane_values("EA", model),
            ]
        self.start = Start(a.lift_height - water.level, rotation_matrix(a.heel, a.trim, a.yaw))
        self.loads = BodyLoads(self.trapped, self.trapped_centre)
        self.breakout = None
        if ground is not None and ground.breakout is not None and scene.n:
            self.breakout = breakout_force(scene)
        self.base = np.concatenate(
            [
                self.start.rotation.ravel(order="F"),
                [gravity],
                cog,
                pivot,
                [self.ground_height, hull.size],
                *ropes,
                [] if coupling is None else np.asarray(coupling, dtype=float).ravel(order="F"),
            ]
        )

    def couple(self, coupling):
        """Set the ropes' coupled stiffness G (n x n, t/m) of a coupled setup."""
        n = self.scene.n
        self.base[self.base.size - n * n :] = np.asarray(coupling, dtype=float).ravel(order="F")

    def gravity_of(self, loads):
        """Total downward force [t] and its body-frame point [m] with ``loads``
        (:class:`BodyLoads`): weight, water in compartments and the soil's pull."""
        body = self.scene.body
        total = body.weight + loads.trapped + loads.soil
        first = body.weight * np.asarray(body.cog, dtype=float)
        if loads.trapped:
            first = first + loads.trapped * np.asarray(loads.trapped_centre, dtype=float)
        if loads.soil:
            first = first + loads.soil * np.asarray(self.scene.ground.contact, dtype=float)
        return total, first / total

    def params(self, rotation, hoist=0.0, loads=None):
        """Parameter vector with start attitude ``rotation``, every hook raised by
        ``hoist``  [m], and the weights of ``loads`` (:class:`BodyLoads`; default the
        scene's: compartments full, no soil)."""
        p = self.base.copy()
        p[:9] = np.asarray(rotation, dtype=float).ravel(order="F")
        if loads is not None:
            gravity, cog = self.gravity_of(loads)
            p[9], p[10:13] = gravity, cog
        if self.scene.n:
            n = self.scene.n
            first = Layout.HOOKS + 3 * n
            p[first : first + n] += hoist
        return p


def solve_in_water(
    scene, method="newton", setup=None, start=None, hoist=0.0, paper_tol=None, loads=None, grounded=True
):
    """Equilibrium of a hull in water (stranded, afloat, or hanging from vertical ropes).

    Parameters
    ----------
    scene : Scene
        With ``hull`` and ``water``.
    method : {"newton", "paper-newton"}
        ``paper-newton`` is the stranded-ship paper's iteration (ground contact, no ropes).
    setup : WaterSetup, optional
        Reuse a built model (load curves).
    start : Start, optional
        Pose to start from; default the scene's attitude and lift height.
    hoist : float  [m]
        Every hook raised by this much over the scene's boom heights.
    paper_tol : float, optional  [t m]
        ``paper-newton``'s stopping tolerance on the pivot moments; default the same
        acceptance as Newton's (``RESIDUAL_TOL`` W L). The paper used 1 t m.
    loads : BodyLoads, optional
        Water in compartments and the soil's pull at this instant (default the scene's:
        compartments full, no soil). Grounded, the answer stands while the ground
        reaction with the soil's pull as a weight at the contact is > 0.
    grounded : bool
        False skips the grounded solve (the caller knows the hull is off the ground).

    Returns
    -------
    Equilibrium
        With ``afloat`` filled in.

    Raises
    ------
    EquilibriumNotFound
        No equilibrium found (with the reason), never a number from an unconverged solve.
    """
    if method not in METHODS:
        raise InvalidScene(f"method = {method!r}: expected one of {', '.join(METHODS)}")
    setup = setup or WaterSetup(scene)
    if method == "paper-newton" and (scene.ground is None or scene.n):
        raise InvalidScene(
            "method = 'paper-newton': the paper's iteration is for a stranded hull "
            "(a [ground] contact and no ropes); expected method 'newton' for this scene"
        )
    start = start or setup.start
    if loads is not None and method == "paper-newton":
        raise InvalidScene(
            "method = 'paper-newton': expected the scene's own loads (no breakout, no draining)"
        )
    gravity = setup.gravity if loads is None else setup.gravity_of(loads)[0]
    p = setup.params(start.rotation, hoist, loads)
    zo_start = start.zo
    if scene.ground is not None and grounded:
        begin = time.perf_counter()
        if method == "paper-newton":
            tol = paper_tol if paper_tol is not None else RESIDUAL_TOL * setup.gravity * scene.hull.size
            rot, iterations = paper_newton(setup, start.rotation, tol=tol)
            start, p = Start(start.zo, rot), setup.params(rot, hoist)
            tilts = np.zeros(2)
        else:
            tilts, iterations = _root(setup.model.grounded_root, [0.0, 0.0], p)
        seconds = time.perf_counter() - begin
        residual, force, zo, _ = (np.asarray(v).ravel() for v in setup.model.grounded(tilts, p))
        tol = RESIDUAL_TOL if paper_tol is None else paper_tol / (setup.gravity * scene.hull.size)
        rot = tilted_rotation(tilts, start.rotation)
        if _converged(residual, rot, tol):
            _check_turn(rot, start.rotation, "grounded")
            _check_stable(setup.model.grounded_stiffness(tilts, p), rot, scene.hull.size, "grounded")
            reaction = -float(force[0]) * gravity
            if reaction > 0.0:
                info = SolverInfo(method, True, iterations, seconds)
                return equilibrium_result(setup, float(zo[0]), rot, hoist, info, grounded=True, loads=loads)
            start, zo_start = Start(float(zo[0]), rot), float(zo[0])
            p = setup.params(rot, hoist, loads)
        elif method == "paper-newton":
            raise EquilibriumNotFound(
                f"paper-newton: no grounded equilibrium after {iterations} iterations "
                f"(moment residual {np.max(np.abs(residual)) * setup.gravity * scene.hull.size:.3g} t m)"
            )
    begin = time.perf_counter()
    x, iterations = _root(setup.model.free_root, [zo_start, 0.0, 0.0], p)
    seconds = time.perf_counter() - begin
    residual = np.asarray(setup.model.free(x, p)[0]).ravel()
    rot = tilted_rotation(x[1:], start.rotation)
    if not _converged(residual, rot):
        what = "floating or hanging" if scene.ground is None else "grounded or afloat"
        heel, trim, _ = attitude_angles(rot) if np.all(np.isfinite(rot)) else (math.nan,) * 3
        raise EquilibriumNotFound(
            f"{_label(scene)}: no {what} equilibrium found (residual {np.max(np.abs(residual)):.3g} W, "
            f"heel {heel:.1f} deg, trim {trim:.1f} deg); " + _hint(setup)
        )
    _check_turn(rot, start.rotation, "afloat")
    _check_stable(setup.model.free_stiffness(x, p), rot, scene.hull.size, "afloat")
    if scene.ground is not None:
        # free of the ground only if the contact point is not pushed below it
        below = setup.ground_height - (float((rot @ scene.ground.contact)[2]) + x[0])
        if below > 1e-6 * scene.hull.size:
            raise EquilibriumNotFound(
                f"{_label(scene)}: the grounded solve found no equilibrium and the afloat one puts "
                f"the contact {below:.3g} m below the ground; expected a reachable resting pose"
            )
    info = SolverInfo(
        "newton" if method == "newton" else "newton (afloat after paper-newton)", True, iterations, seconds
    )
    return equilibrium_result(setup, float(x[0]), rot, hoist, info, grounded=False, loads=loads)


@dataclass(frozen=True)
class Settled:
    """An equilibrium in water with what the soil did (:func:`settle`).

    Parameters
    ----------
    eq : Equilibrium
    start : Start
        Its pose (to start the next solve from).
    soil : float  [t]
        The soil's downward pull on the hull: its suction while grounded (the negative part
        of the ground reaction), the breakout force while breaking out, else 0.
    phase : str
        ``"grounded"``, ``"breaking out"`` (risen off the bed, the soil still holding) or
        ``"free"``.
    loads : BodyLoads
        Water in compartments (and the soil's pull, if breaking out) it was solved with.
    """

    eq: Equilibrium
    start: Start
    soil: float
    phase: str
    loads: BodyLoads


def _pose(eq, level):
    pose = eq.pose
    return Start(pose.lift_height - level, rotation_matrix(pose.heel, pose.trim, pose.yaw))


def settle(setup, hoist=0.0, start=None, loads=None):
    """The equilibrium at ``hoist`` with the scene's breakout model, if it has one.

    Without a breakout model this is :func:`solve_in_water`. With one (a ground contact
    and ropes), the breakout force F_b acts as a weight at the contact: the hull stays
    grounded while the ropes carry less than W + water - B + F_b; past that it breaks out
    and hangs with F_b still at the contact while the contact is less than ``clear`` m
    above its bed, and is free above that.

    Parameters
    ----------
    setup : WaterSetup
    hoist : float  [m]
    start : Start, optional
    loads : BodyLoads, optional
        Water in compartments at this instant (default: full); its ``soil`` is ignored.

    Returns
    -------
    Settled
    """
    scene = setup.scene
    loads = loads or setup.loads
    level = scene.water.level
    held = setup.breakout.force if setup.breakout is not None else 0.0
    if held > 0.0:
        bedded = dataclasses.replace(loads, soil=held)
        eq = solve_in_water(scene, setup=setup, start=start, hoist=hoist, loads=bedded)
        pose = _pose(eq, level)
        if eq.afloat.state == "grounded":
            reaction = scene.body.weight + loads.trapped - eq.afloat.buoyancy - sum(eq.tensions.values())
            return Settled(eq, pose, max(0.0, -reaction), "grounded", dataclasses.replace(loads, soil=0.0))
        rise = float((pose.rotation @ scene.ground.contact)[2]) + pose.zo - setup.ground_height
        if rise < setup.breakout.clear:
            return Settled(eq, pose, held, "breaking out", bedded)
        start = pose  # released: the hull springs up from here (off the ground: the ropes
        # carry more than W + water - B + F_b)
    loads = dataclasses.replace(loads, soil=0.0)
    eq = solve_in_water(
        scene,
        setup=setup,
        start=start,
        hoist=hoist,
        loads=None if loads == setup.loads else loads,
        grounded=not held,
    )
    phase = "grounded" if eq.afloat.state == "grounded" else "free"
    return Settled(eq, _pose(eq, level), 0.0, phase, loads)


def _check_turn(rot, start, what):
    """Refuse an answer whose body z axis turned more than 90 deg from the start's: a flipped
    hull (upside down, hanging under its contact) is another equilibrium of the same
    equations, not the one the scene asks about."""
    if float(rot[:, 2] @ start[:, 2]) <= 0.0:
        heel, trim, _ = attitude_angles(rot)
        raise EquilibriumNotFound(
            f"the {what} solve ended with the hull turned over (heel {heel:.1f} deg, trim {trim:.1f} deg), "
            "more than 90 deg from its start; expected a start attitude nearer the answer"
        )


def _check_stable(stiffness, rot, length, what):
    """Refuse an equilibrium that is not stable: a root of the equations where the hull
    would capsize or roll over given the smallest push (Newton finds those too, from a
    start far off). Stable: the stiffness matrix (symmetric part) is positive definite.
    Its rows and columns are brought to t/m by the hull length first, so the test is one
    of signs and does not depend on units."""
    k = np.asarray(stiffness, dtype=float)
    scale = np.diag([1.0] * (len(k) - 2) + [1.0 / length, 1.0 / length])
    k = scale @ (0.5 * (k + k.T)) @ scale
    low = float(np.min(np.linalg.eigvalsh(k)))
    if not low > -1e-9 * float(np.max(np.abs(k))):
        heel, trim, _ = attitude_angles(rot)
        raise EquilibriumNotFound(
            f"the {what} equilibrium found at heel {heel:.1f} deg, trim {trim:.1f} deg is unstable "
            f"(stiffness eigenvalue {low:.3g} t/m < 0): the hull would not stay there; expected a "
            "start attitude nearer the stable one"
        )


def tilted_rotation(tilts, start):
    """The attitude after the hydrostatic models' unknown tilts: R = tilt(a, b) R0, numeric.

    Parameters
    ----------
    tilts : array_like, shape (2,)  [rad]
        (a, b) about the world's x and y axes (:func:`liftplan.model.frames.tilt`).
    start : numpy.ndarray, shape (3, 3)
        The start attitude R0 they act on.

    Returns
    -------
    numpy.ndarray, shape (3, 3)
    """
    a, b = (float(v) for v in np.asarray(tilts).ravel())
    return np.asarray(ca.DM(tilt(a, b))) @ start


#: The former private name, kept for the package's export and the scripts that use it.
_rotation = tilted_rotation


def _label(scene):
    return "stranded" if scene.ground is not None and not scene.n else "in water"


def _hint(setup):
    whole = setup.envelope.at(np.eye(3), -1e3 * setup.scene.hull.size).volume * setup.scene.water.density
    if not setup.scene.n and setup.scene.ground is None and setup.gravity > whole:
        return (
            f"the weight {setup.gravity:.6g} t exceeds the buoyancy of the whole hull "
            f"{whole:.6g} t: it sinks; expected a ground contact or ropes"
        )
    return "check the start attitude and that the scene can hold the hull"


def _root(rootfinder, guess, p):
    x = rootfinder(ca.DM(list(guess)), ca.DM(p))
    stats = rootfinder.stats()
    return np.asarray(x).ravel(), int(stats.get("iter_count", -1))


def _converged(residual, rot, tol=RESIDUAL_TOL):
    """Finite attitude and a residual below ``tol``."""
    residual = np.asarray(residual, dtype=float)
    return (
        np.all(np.isfinite(residual)) and np.all(np.isfinite(rot)) and float(np.max(np.abs(residual))) <= tol
    )


def paper_newton(setup, start, tol=PAPER_TOL, max_iter=PAPER_MAX_ITER):
    """The stranded-ship paper's iteration: (J^T D J) delta = -J^T f at the pivot.

    Parameters
    ----------
    setup : WaterSetup
        Of a stranded scene (ground contact, no ropes, intact hull).
    start : numpy.ndarray, shape (3, 3)
        Start attitude R0.
    tol : float  [t m]
        Stop when both moments about the pivot are below this (the paper: 1).

    Returns
    -------
    rotation : numpy.ndarray, shape (3, 3)
        The last attitude.
    iterations : int
        Steps taken. If ``max_iter`` is reached the attitude is returned as it is and
        the caller's residual check refuses it.
    """
    scene = setup.scene
    rho, weight = scene.water.density, setup.gravity
    contact = np.asarray(scene.ground.contact)
    rot = np.asarray(start, dtype=float)
    for iteration in range(max_iter + 1):
        c = rot @ contact  # pivot relative to the body origin O
        zo = setup.ground_height - c[2]
        hs = setup.envelope.at(rot, zo)
        g = rot @ setup.cog
        # positions relative to O (the origin sits zo above o on the water plane)
        centre = np.array(hs.centre) - [0.0, 0.0, zo] if hs.volume > 0 else np.zeros(3)
        buoy = rho * hs.volume
        f = np.array([buoy - weight, buoy * centre[1] - weight * g[1], -(buoy * centre[0] - weight * g[0])])
        jac = np.array([[-c[1], c[0]], [1.0, 0.0], [0.0, 1.0]])
        moment = jac.T @ f  # moments about the pivot
        if np.max(np.abs(moment)) <= tol:
            return rot, iteration
        area = hs.waterplane_area
        xf, yf = hs.flotation if hs.flotation else (0.0, 0.0)
        i_t, i_l, i_xy = hs.inertia
        s_yy, s_xx, s_xy = i_t + area * yf**2, i_l + area * xf**2, i_xy + area * xf * yf
        d = rho * np.array(
            [
                [-area, -area * yf, area * xf],
                [-area * yf, -(hs.volume * centre[2] + s_yy), s_xy],
                [area * xf, s_xy, -(hs.volume * centre[2] + s_xx)],
            ]
        )
        d[1, 1] += weight * g[2]
        d[2, 2] += weight * g[2]
        try:
            step = np.linalg.solve(jac.T @ d @ jac, -moment)
        except np.linalg.LinAlgError:
            break
        if not np.all(np.isfinite(step)):
            break
        rot = tilted_rotation(step, rot)  # a rotation about the world's horizontal axes
    return rot, iteration


def unyaw(rot, yaw):
    """Turn an attitude about the vertical so that its yaw (as in
    :func:`~liftplan.model.frames.attitude_angles`) is ``yaw`` [deg].

    Vertical forces do not see a turn about the vertical, so an equilibrium found by
    tilts is one of a family; this picks the member with the scene's yaw, the attitude
    the contract's angles describe. Near heel 90 deg the body's trim axis is (nearly)
    vertical, a world pitch shows as yaw, and turning the hull round to hide it would
    misdescribe it: there only turns of at most ``MAX_TURN`` are made.
    """
    a, b = rot[0, 1], -rot[1, 1]  # -sin(yaw') = cos(psi) a + sin(psi) b for Rz(psi) rot
    c = -math.sin(math.radians(yaw))
    norm = math.hypot(a, b)
    if norm < abs(c) or norm < 1e-12:
        return rot
    base, spread = math.atan2(b, a), math.acos(max(-1.0, min(1.0, c / norm)))
    candidates = [math.remainder(v, 2 * math.pi) for v in (base + spread, base - spread)]
    turned = [rotation_matrix(0.0, 0.0, math.degrees(psi)) @ rot for psi in candidates]
    # of the two turns, keep the one whose bow points forward (heel within +-90)
    best = max(range(2), key=lambda k: turned[k][1, 1] + turned[k][2, 2])
    if abs(rot[2, 1]) > TRIM_AXIS_VERTICAL and abs(candidates[best]) > math.radians(MAX_TURN):
        return rot
    return turned[best]


def equilibrium_result(setup, zo, rot, hoist, solver, grounded, loads=None):
    """Assemble the Equilibrium (world frame) of a converged pose of a hull in water.

    With ``loads``, the soil's pull is a weight at the contact: the ground reaction
    reported is what the ground pushes up, W + water - B - sum T - soil, at least 0 (the
    soil's pull is :attr:`Settled.soil`).

    Parameters
    ----------
    setup : WaterSetup
    zo : float  [m]
        Height of the body origin over the water plane.
    rot : numpy.ndarray, shape (3, 3)
        Attitude.
    hoist : float  [m]
        Every hook raised by this over the scene's boom heights.
    solver : SolverInfo
    grounded : bool
        Resting on the ground contact (its reaction closes the vertical forces).
    loads : BodyLoads, optional
        The body's weights (default the scene's: compartments full, no soil).

    Returns
    -------
    Equilibrium
        ``model = "hydrostatic"``, with ``afloat``.
    """
    scene = setup.scene
    rot = unyaw(rot, scene.attitude.yaw)
    p = setup.params(rot, hoist, loads)
    trapped = setup.trapped if loads is None else loads.trapped
    trapped_at = setup.trapped_centre if loads is None else loads.trapped_centre
    total_weight = setup.gravity if loads is None else setup.gravity_of(loads)[0]
    out = setup.model.free.call({"x": ca.DM([zo, 0.0, 0.0]), "p": ca.DM(p)})
    residual = np.asarray(out["r"]).ravel()
    tensions = np.asarray(out["tension"]).ravel()
    heel, trim, yaw = attitude_angles(rot)
    level = scene.water.level
    if grounded:
        shift = setup.contact_world[:2] - (rot @ scene.ground.contact)[:2]
    else:
        shift = np.zeros(2)
    origin = np.array([shift[0], shift[1], level])  # world position of o

    def world(q):
        return tuple(float(v) for v in np.asarray(q) + origin)

    hs = setup.envelope.at(rot, zo)
    # the model's buoyancy is the kappa-weighted wet volume: density x displaced volume
    buoyancy = max(0.0, float(np.asarray(out["buoyancy"]).ravel()[0]))
    moment = np.asarray(out["moment"]).ravel()
    density = scene.water.density
    reaction = scene.body.weight + trapped - buoyancy - float(tensions.sum()) if grounded else 0.0
    if loads is not None and loads.soil:
        reaction = max(0.0, reaction)
    friction = scene.ground.friction if scene.ground is not None else None
    lift = np.array([0.0, 0.0, zo])
    gravity = rot @ np.asarray(scene.body.cog) + lift
    bottom, top = hull_heights(scene.hull, rot, zo)
    afloat = Afloat(
        state=water_state(grounded, bottom, top, float(tensions.sum()), total_weight),
        buoyancy=buoyancy,
        displaced_volume=buoyancy / density,
        immersed_volume=hs.volume,
        trapped_water=trapped,
        density=density,
        ground_reaction=reaction if scene.ground is not None else None,
        freeing_force=friction * reaction if friction is not None else None,
        centre_of_buoyancy=world(moment[:3] / buoyancy) if buoyancy > 0.0 else None,
        centre_of_gravity=world(gravity),
        contact=tuple(float(v) for v in setup.contact_world) if scene.ground is not None else None,
        centre_of_trapped_water=world(rot @ np.asarray(trapped_at) + lift) if trapped_at else None,
    )
    # force (closed by the ground reaction when grounded), and moments over L
    worst = float(np.max(np.abs(residual[1:] if grounded else residual))) * total_weight
    names = scene.lug_names
    return Equilibrium(
        model="hydrostatic",
        pose=Pose(heel=heel, trim=trim, yaw=yaw, lift_height=zo + level),
        tensions=dict(zip(names, tensions.tolist())),
        weight=scene.body.weight,
        swl={c.lug: c.swl for c in scene.cranes},
        slack=tuple(name for name, t in zip(names, tensions) if t <= 0.0),
        residual=worst,
        solver=solver,
        afloat=afloat,
    )


def submerged_scene(setup):
    """The rope-only scene equivalent to the hull while fully submerged, or None.

    Fully submerged, the buoyancy is constant in magnitude and fixed in the body (the
    centre of the displaced volume), and every force is vertical: weight W at G and
    buoyancy B at C make one force W - B at (W G - B C) / (W - B) at any attitude. So the
    vertical-rope ``elastic`` model with that weight and CG is exact there. None when
    W - B <= 0 (the hull would float up).
    """
    scene = setup.scene
    deep = 1e3 * scene.hull.size
    out = setup.model.free.call({"x": ca.DM([-deep, 0, 0]), "p": ca.DM(setup.params(np.eye(3)))})
    buoy = float(out["buoyancy"])
    centre = np.asarray(out["moment"]).ravel() / buoy + [0.0, 0.0, deep]
    net = setup.gravity - buoy
    if net <= 1e-9 * setup.gravity:
        return None
    cog = (setup.gravity * setup.cog - buoy * centre) / net
    rope_scene = dataclasses.replace(
        scene,
        water=None,
        hull=None,
        ground=None,
        body=dataclasses.replace(scene.body, weight=net, cog=cog, weight_curve=None),
        analysis=dataclasses.replace(scene.analysis, model="elastic"),
    )
    return rope_scene


def solve_hydrostatic(scene, method="newton"):
    """Solve a scene with a hull in water with the least model it needs.

    * ropes, no ground, hull fully submerged at the answer: constant buoyancy (the
      vertical-rope ``elastic`` model with the submerged weight and centre,
      :func:`submerged_scene`); the answer is checked on the clipped model's residual.
    * otherwise the clipped hull (:func:`solve_in_water`).

    Returns
    -------
    Equilibrium
        ``model`` is ``"submerged"`` or ``"hydrostatic"``.
    """

    setup = WaterSetup(scene)
    start = None
    if scene.n and scene.ground is None and method == "newton":
        try:
            rope_scene = submerged_scene(setup)
        except InvalidScene:  # e.g. the submerged centre lies outside the lugs
            rope_scene = None
        if rope_scene is not None:
            try:
                eq = solve_elastic(rope_scene)
            except EquilibriumNotFound:
                eq = None
            if eq is not None:
                pose = eq.pose
                zo = pose.lift_height - scene.water.level
                rot = rotation_matrix(pose.heel, pose.trim, pose.yaw)
                top = zo + float(np.max((rot @ scene.hull.vertices.T)[2]))
                if top < 0.0:
                    info = dataclasses.replace(eq.solver, method="newton (constant buoyancy)")
                    result = equilibrium_result(setup, zo, rot, 0.0, info, grounded=False)
                    if result.residual <= 1e-7 * setup.gravity:
                        return dataclasses.replace(result, model="submerged")
                start = Start(zo, rot)
    if method == "newton" and setup.breakout is not None:
        return settle(setup, start=start).eq
    return solve_in_water(scene, method=method, setup=setup, start=start)
