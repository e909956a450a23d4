"""``solve(scene)``: the one entry to every model, and the least model a scene needs.

* ``rigid``, ``paper-elastic``, ``elastic`` (:mod:`liftplan.model.statics.vertical`): vertical
  ropes, all generated from :mod:`liftplan.model.statics.model`.
* ``inclined`` and ``rigging`` (:mod:`liftplan.model.statics.inclined`,
  :mod:`liftplan.model.statics.rigging`): the 6-DOF body with crane tips in the world, hooks
  and spreader bars as free points.
* ``hydrostatic`` (:mod:`liftplan.model.water`): a hull in water. ``rigid`` and
  ``paper-elastic`` take a hull in water too, at the given attitude and lift height
  (:mod:`liftplan.model.water.held`: the buoyancy there is a known force).

A result is returned only when it passes :mod:`liftplan.model.statics.acceptance` (residual,
stability, upright), whichever method found it; otherwise a typed error says why.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.results import Equilibrium
from liftplan.model.scene.objects import MODELS, Scene, name_list
from liftplan.model.scene.tide import apply_tide
from liftplan.model.scene.wind import apply_wind
from liftplan.model.statics.acceptance import Verdict
from liftplan.model.statics.floating import (
    check_floating,
    scene_fleet,
    series_scene,
    solve_floating,
    tip_plan,
    vessel_states,
    with_vessels,
)
from liftplan.model.statics.inclined import solve_inclined
from liftplan.model.statics.rigging import solve_rigging
from liftplan.model.statics.vertical import (
    equilibrium_of,
    pack_params,
    solve_elastic,
    solve_paper_elastic,
    solve_rigid,
    worst_residual,
)
from liftplan.model.strength.flexible import (
    TENSION_CHANGE,
    RigidHullNote,
    flexible_state,
    hull_report,
    tension_change,
)
from liftplan.model.strength.flexible_water import solve_hull_in_water
from liftplan.model.water.equilibrium import solve_hydrostatic
from liftplan.model.water.held import held_loads
from liftplan.model.water.hull_vessels import solve_hull_vessels
from liftplan.model.water.vessels import solve_coupled_in_water


def pick_model(scene):
    """The model a scene asks for, or the least one its data supports.

    Returns ``scene.analysis.model`` if set; otherwise ``"hydrostatic"`` for a hull in water
    (which then picks constant or clipped buoyancy itself), ``"rigging"`` when a crane carries
    a sling set, ``"inclined"`` when a crane's tip is placed in the world, ``"elastic"`` when
    every crane has a boom height, rope length and EA, ``"rigid"`` when redundant tensions
    are given (or n = 3), else ``"paper-elastic"``.
    """
    if scene.analysis.model:
        return scene.analysis.model
    if scene.hull is not None:
        return "hydrostatic"
    if scene.slings:
        return "rigging"
    if any(c.tip is not None for c in scene.cranes):
        return "inclined"
    cranes = scene.cranes
    if all(c.boom_height is not None and c.rope_length is not None and c.EA for c in cranes):
        return "elastic"
    if scene.analysis.redundant or scene.n == 3:
        return "rigid"
    return "paper-elastic"


def solve(scene: Scene, model: str | None = None, method: str = "newton") -> Equilibrium:
    """Solve a scene.

    Parameters
    ----------
    scene : Scene
    model : str, optional
        Overrides :func:`pick_model`.
    method : {"newton", "paper-newton"}
        For a stranded hull: casadi Newton or the paper's iteration
        (:mod:`liftplan.model.water`).

    Returns
    -------
    Equilibrium

    Raises
    ------
    InvalidScene
        The scene lacks data the model needs.
    EquilibriumNotFound
        No equilibrium with all ropes in tension (given-attitude models), or the elastic
        solve did not converge.
    """
    if scene.tide is not None:  # the floating cranes' tips and the water where the tide has them
        scene, tide = apply_tide(scene)
        return dataclasses.replace(solve(scene, model=model, method=method), tide=tide)
    if scene.wind is not None:  # the body's couple and the booms' moments on their vessels
        if (model or pick_model(scene)) in ("inclined", "rigging"):
            raise InvalidScene(
                "wind: modelled for vertical ropes (its couple on the vertical tensions); expected "
                "tips above the lugs, no slings"
            )
        still = dataclasses.replace(scene, wind=None)
        scene, wind = apply_wind(scene, tip_plan(scene))
        eq = solve(scene, model=model, method=method)
        return dataclasses.replace(
            eq, wind=dataclasses.replace(wind, load_changes=_wind_share(eq, still, model, method))
        )
    model = model or pick_model(scene)
    if method != "newton" and model != "hydrostatic":
        raise InvalidScene(f"method = {method!r}: only for a stranded hull; expected 'newton'")
    if scene.hull is not None and model not in ("hydrostatic", *GIVEN_IN_WATER):
        raise InvalidScene(
            f"model = {model!r} leaves out the scene's [water] and [hull]; expected 'hydrostatic', "
            "'rigid' or 'paper-elastic' (or no model: the least model the scene needs is picked)"
        )
    if scene.slings and model != "rigging":
        raise InvalidScene(
            f"cranes.sling given, but the {model} model hangs one rope per lug; expected model "
            "'rigging' (or no model: it is picked when a crane has a sling)"
            if scene.hull is None
            else "cranes.sling: slings on a hull in water are not modelled; expected one rope per lug"
        )
    if (
        model not in ("inclined", "rigging")
        and any(c.tip is not None for c in scene.cranes)
        and scene.hull is None
    ):
        raise InvalidScene(
            f"cranes.tip given, but the {model} model hangs the ropes vertically; expected model "
            "'inclined' (or no model: it is picked when a tip is given)"
        )
    check_floating(scene, model)
    if scene.girder is not None and model not in HULL_STIFFNESS_MODELS:
        return _rigid_hull(scene, model, method)
    try:
        solver = ROPE_MODELS[model]
    except KeyError:
        raise InvalidScene(f"model = {model!r}: expected one of {', '.join(MODELS)}") from None
    return solver(scene, method)


def _wind_share(eq, still, model, method):
    """Each rope's tension in ``eq`` less its tension in the ``still`` scene (no wind)  [t];
    None when the still scene has no equilibrium (the windy one stands: it is the answer)."""
    try:
        calm = solve(still, model=model, method=method)
    except EquilibriumNotFound:
        return None
    return {name: tension - calm.tensions.get(name, 0.0) for name, tension in eq.tensions.items()}


# -- the models ------------------------------------------------------------------------------
def _hydrostatic(scene, method):
    if scene.vessels:  # floating cranes: each rope in series with its vessel (one crane each)
        fleet = scene_fleet(scene)
        if np.all(fleet.membership.sum(axis=1) == 1.0):
            eq = _hydrostatic(series_scene(scene, fleet), method)
        else:  # a vessel under several cranes: the ropes' coupled stiffness
            eq = dataclasses.replace(solve_coupled_in_water(scene, fleet, method), frame=scene.frame)
        return with_vessels(eq, vessel_states(scene, fleet, list(eq.tensions.values())))
    if scene.girder is not None:  # a flexible hull in water
        return solve_hull_in_water(scene, method=method)
    # the water solvers build their results themselves: give them the file's frame here
    return dataclasses.replace(solve_hydrostatic(scene, method=method), frame=scene.frame)


def _elastic(scene, method):
    if any(v.hull is not None for v, _ in scene.vessels.values()):  # vessels as hull meshes
        return solve_hull_vessels(scene)
    if scene.vessels:
        return solve_floating(scene)
    return solve_elastic(scene) if scene.girder is None else solve_hull_on_ropes(scene)


def _rigid(scene, method):
    """``rigid``; with crane vessels, their response to the tensions the operators hold."""
    if scene.hull is not None:
        return _given_in_water(scene, "rigid")
    eq = solve_rigid(scene)
    if not scene.vessels:
        return eq
    return with_vessels(eq, vessel_states(scene, scene_fleet(scene), list(eq.tensions.values())))


def _given_attitude(name, solver):
    """A given-attitude model: in air, or on a hull in water with its water forces."""

    def solve_given(scene, method):
        return _given_in_water(scene, name) if scene.hull is not None else solver(scene)

    return solve_given


#: ``analysis.model`` -> ``solver(scene, method) -> Equilibrium``: the one table of rope
#: models (the names a file may give are :data:`~liftplan.model.scene.objects.MODELS`).
ROPE_MODELS = {
    "rigid": _rigid,
    "paper-elastic": _given_attitude("paper-elastic", solve_paper_elastic),
    "elastic": _elastic,
    "inclined": lambda scene, method: solve_inclined(scene),
    "rigging": lambda scene, method: solve_rigging(scene),
    "hydrostatic": _hydrostatic,
}
#: The models that take a hull's stiffness (``[hull] EI``); the others hold the hull rigid.
HULL_STIFFNESS_MODELS = ("elastic", "hydrostatic")


# -- flexible hull ---------------------------------------------------------------------------
def _rigid_hull(scene, model, method):
    """A scene with a hull stiffness on a model that holds the hull rigid: solved, and said so."""

    if scene.analysis.hull == "flexible":
        raise InvalidScene(
            f'analysis.hull = "flexible": the {model} model holds the hull rigid; expected model '
            "'elastic' (vertical ropes in air) or 'hydrostatic' (in water) for a flexible hull"
        )
    eq = solve(dataclasses.replace(scene, girder=None), model=model, method=method)
    note = RigidHullNote(
        f"the {model} model holds the hull rigid; hull.EI is used by the elastic and hydrostatic models only"
    )
    return dataclasses.replace(eq, flexible_hull=note)


def solve_hull_on_ropes(scene, hull=None):
    """The ``elastic`` model of a scene with a hull stiffness: the least hull it needs.

    The hull is solved rigid (:func:`solve_elastic`) and flexible (the same Newton system
    with the beam's deflections as unknowns, started from the rigid pose:
    :func:`liftplan.model.strength.flexible.flexible_state`); the flexible answer is kept when
    it changes a tension by more than :data:`~liftplan.model.strength.flexible.TENSION_CHANGE`
    of the rigid one, or when ``hull`` (default ``scene.analysis.hull``) is ``"flexible"``.
    ``"rigid"`` skips the flexible solve.

    Returns
    -------
    Equilibrium
        With ``flexible_hull``: which hull, the measured change, the deflection curve.

    Raises
    ------
    EquilibriumNotFound
        Either solve was not accepted (residual, stability, upright), with the reason.
    """

    hull = hull or scene.analysis.hull
    rigid_scene = dataclasses.replace(
        scene, girder=None, analysis=dataclasses.replace(scene.analysis, hull="auto")
    )
    rigid = solve_elastic(rigid_scene)
    if hull == "rigid":
        return dataclasses.replace(rigid, flexible_hull=RigidHullNote('analysis.hull = "rigid"'))
    start = time.perf_counter()
    x_rigid = np.array([rigid.pose.lift_height, math.radians(rigid.pose.heel), math.radians(rigid.pose.trim)])
    state = flexible_state(scene, pack_params(scene, "elastic"), x_rigid)
    seconds = time.perf_counter() - start
    verdict = Verdict(
        max(worst_residual(scene, state.statics) / scene.body.weight, state.beam_residual),
        state.stable,
        math.degrees(state.x[1]),
        math.degrees(state.x[2]),
    )
    if not verdict.ok:
        raise EquilibriumNotFound(f"elastic, flexible hull: no accepted equilibrium ({verdict.reason()})")
    rigid_t = np.array([rigid.tensions[name] for name in scene.lug_names])
    change = tension_change(rigid_t, state.tensions, scene.body.weight)
    used = "flexible" if hull == "flexible" or np.max(change) > TENSION_CHANGE else "rigid"
    report = hull_report(scene, state.mesh, state, rigid_t, used, forced=hull == "flexible")
    if used == "rigid":
        return dataclasses.replace(rigid, flexible_hull=report)
    slack = tuple(name for name, s in zip(scene.lug_names, state.stretch) if s <= 0.0)
    if scene.n - len(slack) < 3:
        raise EquilibriumNotFound(
            f"elastic, flexible hull: only {scene.n - len(slack)} rope(s) taut ({name_list(slack)} "
            "slack): expected three or more to hold the body"
        )
    eq = equilibrium_of(
        scene,
        "elastic",
        state.x,
        state.tensions,
        state.statics,
        "newton (flexible hull)",
        seconds,
        slack=slack,
    )
    return dataclasses.replace(eq, flexible_hull=report)


# -- given-attitude models in water ----------------------------------------------------------
#: The models that take the attitude as given, and with it the water forces.
GIVEN_IN_WATER = ("rigid", "paper-elastic")


def _given_in_water(scene, model):
    """``rigid`` or ``paper-elastic`` on a hull in water, at the scene's attitude and lift height.

    The buoyancy at that pose is a known vertical force (constant when fully submerged,
    from the clipped hull otherwise: :mod:`liftplan.model.water.held`), so the ropes carry
    W + trapped water - B on the line through the forces' combined centre, and the linear
    statics close it as they close W at G in air. A ground contact carries nothing (the
    held pose is the lift-off instant; see :mod:`liftplan.model.water.held`).
    """

    if scene.n < 3:
        raise InvalidScene(f"lugs: {scene.n} given; the {model} model expected three or more ropes")
    if any(c.tip is not None for c in scene.cranes):
        raise InvalidScene(
            "cranes.tip: inclined ropes on a hull in water are not modelled; expected tips "
            "above the lugs (no tip: vertical ropes) for a scene with [hull] and [water]"
        )
    start = time.perf_counter()
    loads = held_loads(scene)
    body = (loads.net_weight, loads.net_point)
    solver = solve_rigid if model == "rigid" else solve_paper_elastic
    eq = solver(scene, body=body)
    seconds = eq.solver.seconds + time.perf_counter() - start
    method = "linear (constant buoyancy)" if loads.constant else "linear (clipped hull)"
    return dataclasses.replace(
        eq, afloat=loads.afloat, solver=dataclasses.replace(eq.solver, method=method, seconds=seconds)
    )
