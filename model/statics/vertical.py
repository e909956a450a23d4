"""The vertical-rope models, all generated from :mod:`liftplan.model.statics.model`.

* ``rigid`` (Choi et al. 2000): attitude given, n - 3 tensions given by the operators; the
  other three follow from the statics. Linear: solved exactly.
* ``paper-elastic`` (Choi & Shin 2003): attitude given; elongations affine in the lugs'
  plan coordinates close the statics. Linear: solved exactly.
* ``elastic`` (forward): boom heights and unstretched lengths given; pose and tensions
  found by casadi's Newton root-finder, with IPOPT on the potential energy as fallback.

A result is returned only when it passes :mod:`liftplan.model.statics.acceptance` (residual,
stability, upright), whichever method found it; otherwise a typed error says why. The
dispatch over every model (these, ``inclined``, ``rigging``, ``hydrostatic``) is
:func:`liftplan.model.solve.solve`.
"""

from __future__ import annotations

import math
import time

import casadi as ca
import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.results import Equilibrium, Pose, SolverInfo
from liftplan.model.scene.objects import name_list
from liftplan.model.statics.acceptance import RESIDUAL_TOL, judge
from liftplan.model.statics.model import BLOCK, rope_model


# -- parameters -----------------------------------------------------------------------------
def pack_params(scene, model, body=None):
    """The flat parameter vector of :class:`~liftplan.model.statics.model.Layout` for a scene.

    ``body``: optional (weight [t], body-frame point [m]) that the ropes carry instead of
    the body's W at G (the net vertical force of a hull in water).
    """
    weight, cog = body if body is not None else (scene.body.weight, scene.body.cog)
    n = scene.n
    ones = [1.0] * n
    boom = scene.crane_values("boom_height", model) if model != "rigid" else ones
    stiffness = scene.crane_values("EA", model) if model != "rigid" else ones
    length = scene.crane_values("rope_length", model) if model == "elastic" else ones
    return np.concatenate(
        [
            [math.radians(scene.attitude.yaw)],
            scene.lug_points().ravel(),
            cog,
            [weight],
            boom,
            length,
            stiffness,
            [scene.plan_diameter],
        ]
    )


def _given_x(scene):
    att = scene.attitude
    return np.array([att.lift_height, math.radians(att.heel), math.radians(att.trim)])


# -- result assembly ------------------------------------------------------------------------
def worst_residual(scene, residual):
    """Largest statics residual  [t]: force, and moments over the lugs' plan diameter."""
    r0, r1, r2 = np.abs(np.asarray(residual, dtype=float).ravel())
    scale = scene.plan_diameter
    worst = max(r0, r1 / scale, r2 / scale)
    return float(worst) if math.isfinite(worst) else math.inf


def equilibrium_of(scene, model, x, tensions, residual, method, seconds, slack=()):
    """Assemble the result, refusing it unless the statics residual (A T - b) is small."""
    worst = worst_residual(scene, residual)
    if not worst <= RESIDUAL_TOL * scene.body.weight:
        raise EquilibriumNotFound(
            f"{model}: equilibrium residual {worst:.3g} t exceeds "
            f"{RESIDUAL_TOL:g} W = {RESIDUAL_TOL * scene.body.weight:.3g} t: no equilibrium found"
        )
    return Equilibrium(
        model=model,
        pose=Pose(
            heel=math.degrees(x[1]),
            trim=math.degrees(x[2]),
            yaw=scene.attitude.yaw,
            lift_height=float(x[0]),
        ),
        tensions=dict(zip(scene.lug_names, np.asarray(tensions, dtype=float).ravel().tolist())),
        weight=scene.body.weight,
        swl={c.lug: c.swl for c in scene.cranes},
        slack=tuple(slack),
        residual=worst,
        solver=SolverInfo(method=method, converged=True, iterations=None, seconds=seconds),
        frame=scene.frame,
    )


def _check_taut(scene, model, tensions):
    negative = [(name, t) for name, t in zip(scene.lug_names, tensions) if t < 0.0]
    if negative:
        negative.sort(key=lambda item: item[1])
        worst = name_list(f"{name} = {t:.2f} t" for name, t in negative)
        att = scene.attitude
        raise EquilibriumNotFound(
            f"{model}: at heel {att.heel:g} deg, trim {att.trim:g} deg the statics need "
            f"compression in {worst}: a rope would go slack, expected an attitude where "
            "every rope pulls"
        )


# -- given-attitude models (linear, exact) ------------------------------------------------
def solve_rigid(scene, body=None):
    """Choi et al. (2000): tensions from the statics with n - 3 tensions given.

    Parameters
    ----------
    scene : Scene
        ``scene.analysis.redundant`` names n - 3 lugs and their tensions [t].
    body : tuple (float, sequence of 3 float), optional  [t, m]
        The vertical force the ropes carry and a body-frame point on its line, instead of
        W at G (see :func:`pack_params`).

    Returns
    -------
    Equilibrium
    """
    n, red = scene.n, scene.analysis.redundant
    if len(red) != n - 3:
        raise InvalidScene(
            f"analysis.redundant: {len(red)} given, the rigid model with {n} ropes "
            f"expected n - 3 = {n - 3} held tension(s)"
        )
    start = time.perf_counter()
    x = _given_x(scene)
    a_flat, b_vec, _, _ = rope_model(n).statics_fast(x, pack_params(scene, "rigid", body))
    a_mat = a_flat.reshape(n, 3).T  # casadi's column-major 3 x n
    names = scene.lug_names
    given = {r.lug: r.tension for r in red}
    held = np.array([name in given for name in names])
    tensions = np.array([given.get(name, 0.0) for name in names])
    # the three free tensions from the 3x3 statics of their lugs (rows scaled to unit size
    # for the singularity test: (1, x / L, y / L), L the lugs' plan diameter)
    free = a_mat[:, ~held]
    scale = np.array([1.0, scene.plan_diameter, scene.plan_diameter])[:, None]
    if np.linalg.cond(free / scale) > 1e12:
        free_names = [name for name, h in zip(names, held) if not h]
        raise InvalidScene(
            f"analysis.redundant: with {name_list([r.lug for r in red])} held, the free "
            f"lugs {', '.join(free_names)} are collinear in plan and the statics are singular; "
            "expected three free lugs spanning an area"
        )
    tensions[~held] = np.linalg.solve(free, b_vec - a_mat[:, held] @ tensions[held])
    seconds = time.perf_counter() - start
    _check_taut(scene, "rigid", tensions)
    residual = a_mat @ tensions - b_vec
    return equilibrium_of(scene, "rigid", x, tensions, residual, "linear", seconds)


def solve_paper_elastic(scene, body=None):
    """Choi & Shin (2003): statics closed by coplanar lug elongations, attitude given.

    Parameters
    ----------
    scene : Scene
    body : tuple (float, sequence of 3 float), optional  [t, m]
        As in :func:`solve_rigid`.

    Returns
    -------
    Equilibrium
    """
    start = time.perf_counter()
    x = _given_x(scene)
    p = pack_params(scene, "paper-elastic", body)
    tensions, lengths, residual = rope_model(scene.n).paper_elastic_fast(x, p)
    seconds = time.perf_counter() - start
    for name, length in zip(scene.lug_names, lengths):
        if not length > 0.0:
            raise InvalidScene(
                f"cranes[{name}].boom_height: the boom tip is {-length:.3g} m below the lug "
                "at this attitude and lift height; expected it above the lug"
            )
    _check_taut(scene, "paper-elastic", tensions)
    return equilibrium_of(scene, "paper-elastic", x, tensions, residual, "linear", seconds)


def paper_elastic_tensions(scene, heel, trim):
    """Batched ``paper-elastic`` tensions at many attitudes (casadi ``map`` over blocks).

    Parameters
    ----------
    scene : Scene
    heel, trim : array_like, shape (N,)  [deg]

    Returns
    -------
    numpy.ndarray, shape (N, n)  [t]
        Tensions in scene lug order. No slack or validity check: for screening.
    """
    if scene.hull is not None:
        raise InvalidScene(
            "paper_elastic_tensions: the batched map leaves out the scene's [water] and [hull]; "
            "expected solve(scene, model='paper-elastic') at each attitude for a hull in water"
        )
    heel = np.atleast_1d(np.asarray(heel, dtype=float)).ravel()
    trim = np.broadcast_to(np.asarray(trim, dtype=float), heel.shape).ravel()
    count = heel.size
    block = rope_model(scene.n).paper_elastic_block
    p = pack_params(scene, "paper-elastic")
    # x columns (lift, heel, trim), column-major, padded to whole blocks
    padded = -(-count // BLOCK) * BLOCK
    x = np.zeros((padded, 3))
    x[:, 0] = scene.attitude.lift_height
    x[:count, 1] = np.radians(heel)
    x[:count, 2] = np.radians(trim)
    flat = x.ravel()
    out = np.empty((padded, scene.n))
    for start in range(0, padded, BLOCK):
        tensions = block(flat[3 * start : 3 * (start + BLOCK)], p)[0]
        out[start : start + BLOCK] = tensions.reshape(BLOCK, scene.n)
    return out[:count]


# -- forward elastic model (nonlinear) ------------------------------------------------------
def solve_elastic(scene, method="auto", stiffness=None):
    """Pose and tensions from boom heights, unstretched lengths and EA.

    Parameters
    ----------
    scene : Scene
    method : {"auto", "newton", "energy"}
        ``"auto"``: Newton, and IPOPT on the potential energy (polished by Newton) if
        Newton's answer is not accepted.
    stiffness : array_like, shape (n,), optional  [t]
        EA to use instead of the cranes' own (the series stiffness of a rope on a crane
        vessel: :mod:`liftplan.model.statics.floating`).

    Returns
    -------
    Equilibrium
        Accepted by :func:`liftplan.model.statics.acceptance.judge` (residual, stability, upright),
        whichever method found it.
    """
    if method not in ("auto", "newton", "energy"):
        raise InvalidScene(f"method = {method!r}: expected auto, newton or energy")
    model = rope_model(scene.n)
    p = pack_params(scene, "elastic")
    if stiffness is not None:
        p[5 * scene.n + 5 : 6 * scene.n + 5] = stiffness
    used = "newton"
    start = time.perf_counter()
    if method != "energy":
        x, tensions, stretch, residual, minors = model.elastic_solver(p)
        verdict = elastic_verdict(scene, x, residual, minors)
    if method == "energy" or not verdict.ok:
        if method == "newton":
            raise EquilibriumNotFound(
                f"elastic: Newton did not reach a stable upright equilibrium ({verdict.reason()}); "
                "try method='energy'"
            )
        start = time.perf_counter()
        x, tensions, stretch, residual, minors = _energy_solve(scene, model, p)
        used = "energy"
    seconds = time.perf_counter() - start
    slack = tuple(name for name, s in zip(scene.lug_names, stretch) if s <= 0.0)
    if scene.n - len(slack) < 3:
        raise EquilibriumNotFound(
            f"elastic: only {scene.n - len(slack)} rope(s) taut ({name_list(slack)} slack): "
            "expected three or more to hold the body"
        )
    return equilibrium_of(scene, "elastic", x, tensions, residual, used, seconds, slack=slack)


def elastic_verdict(scene, x, residual, minors):
    """The one acceptance (:mod:`liftplan.model.statics.acceptance`) of a candidate elastic state."""
    return judge(worst_residual(scene, residual) / scene.body.weight, x[1], x[2], minors=minors)


def _energy_solve(scene, model, p):
    """IPOPT on the potential energy from the linear start, then Newton to polish.

    IPOPT's stopping test is on the energy gradient, which can stop short of the residual
    tolerance (or report a tiny search direction at the minimum itself); Newton started
    at its point converges quadratically there. The polished point is judged as Newton's
    own is: residual, stability and upright (IPOPT can end at a saddle).
    """
    solver = model.energy_solver
    p_dm = ca.DM(p)
    result = solver(x0=model.elastic_start(p_dm), p=p_dm)
    x_min = np.asarray(result["x"]).ravel()
    x, tensions, stretch, residual, minors = model.elastic_polish(x_min, p)
    verdict = elastic_verdict(scene, x, residual, minors)
    if not verdict.ok:
        status = solver.stats()["return_status"]
        floor = _rounding_floor(scene)
        if not verdict.small and floor > RESIDUAL_TOL * scene.body.weight:
            raise EquilibriumNotFound(
                f"elastic: the ropes are too stiff for the tolerance (EA/l up to "
                f"{max(c.EA / c.rope_length for c in scene.cranes):.3g} t/m: rounding the heights "
                f"alone moves a tension by ~{floor:.1e} t, above {RESIDUAL_TOL:g} W); expected "
                "model 'paper-elastic' or 'rigid', the stiff-rope limit"
            )
        hint = (
            "a CG high above soft ropes can have no stable upright equilibrium; expected "
            "stiffer ropes, lugs further apart or a lower CG"
            if verdict.small and verdict.upright
            else "check that the boom heights and rope lengths can hold the body with three "
            "or more taut ropes"
        )
        raise EquilibriumNotFound(
            f"elastic: no stable upright equilibrium found (energy minimisation: {status}; after "
            f"Newton: {verdict.reason()}); {hint}"
        )
    return x, tensions, stretch, residual, minors


def _rounding_floor(scene):
    """Tension accuracy float64 allows [t]: a height rounded by eps |H| moves T by k eps |H|."""
    return max(c.EA / c.rope_length * abs(c.boom_height) for c in scene.cranes) * np.finfo(float).eps
