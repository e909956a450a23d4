"""A lift that starts in water: the state with the hull partly submerged, one more worst state.

A planning file's ``[water]``, ``[hull]`` geometry and ``[plan] start_lift_height`` place the
level body at the start of the lift with its hull partly submerged. There the water's forces
are fixed numbers (:func:`liftplan.model.water.held.held_loads`, the given-attitude models'
hydrostatics of the hull cut by the water plane): gravity W at G, trapped water and the
buoyancy B at its centre make one vertical force W + trapped - B on a line through a body
point, at every vertex of the CG envelope. Each rope's share of it follows from the held
preload model the planner uses everywhere (boom heights that dial in the plan's level
preload, hooks moved as a rigid motion of the level pattern to hold the body level: the
breakout case's model, :mod:`liftplan.planner.plans.breakout`, with this force); the hook errors
widen each tension by |dT/dH| x tolerance as in the box. The buoyancy's centre is where the
waterplane is, not where the CG is, so the net force's line moves away from G and some rope's
share can exceed its share in air.

The state enters the plan as one more of its worst states: the objective's value there
(:func:`in_water_value`), the larger of it and the box's ranks the sets again
(:mod:`liftplan.planner.plans.hull_water`), each crane's static input to the design-load chain
is the larger of its worst in the box and in water (:mod:`liftplan.planner.plans.design_loads`),
and the lowest tension in water must reach the plan's ``min_tension`` (and stay above 0: a slack
rope leaves the held model); sets that break it rank after those that hold.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.scene.objects import Attitude, Body, Scene
from liftplan.model.statics.model import rope_model
from liftplan.model.water.held import held_loads
from liftplan.planner.search.evaluator import robust
from liftplan.planner.search.scenarios import pack, run_block


@dataclass(frozen=True)
class WaterLoad:
    """The water's and gravity's one vertical force at the start, at one CG-envelope vertex.

    Parameters
    ----------
    cog_offset : tuple of 3 float  [m]
    net_weight : float  [t]   W + trapped water - B
    point : tuple of 3 float  [m]   a body-frame point on its line of action
    buoyancy : float  [t]
    centre_of_buoyancy : tuple of 3 float or None  [m]   world frame
    """

    cog_offset: tuple
    net_weight: float
    point: tuple
    buoyancy: float
    centre_of_buoyancy: tuple | None


@dataclass(frozen=True)
class InWaterCase:
    """Each rope's load at the start in water, for one lug set.

    Parameters
    ----------
    loads : tuple of WaterLoad
        One per CG-envelope vertex (the nominal CG first).
    cranes, lugs : tuple of str
    tensions : numpy.ndarray, shape (v, n)  [t]   held tension per vertex and rope
    gain : numpy.ndarray, shape (v, n, n)  [t/m]   dT/dH there
    hook_shift : numpy.ndarray, shape (v, n)  [m]
        Each hook's motion from its planned height (besides the whole lift's lowering to the
        start height) that holds the body level there: a rigid motion of the level pattern.
    hook_tolerance : numpy.ndarray, shape (n,)  [m]
    value : float  [t or -]   the objective's worst in water (hook errors at worst)
    min_tension : float  [t]
        The plan's ``min_tension`` (0 where it is lower): the lowest tension in water must
        reach it, as every state of the lift in air must.
    """

    loads: tuple
    cranes: tuple
    lugs: tuple
    tensions: np.ndarray
    gain: np.ndarray
    hook_shift: np.ndarray
    hook_tolerance: np.ndarray
    value: float
    min_tension: float = 0.0

    @property
    def worst(self):
        """Each rope's largest tension in water over the vertices, hook errors at worst  [t]."""
        return (self.tensions + np.abs(self.gain) @ self.hook_tolerance).max(axis=0)

    @property
    def least(self):
        """Each rope's smallest tension in water, hook errors at worst  [t]."""
        return (self.tensions - np.abs(self.gain) @ self.hook_tolerance).min(axis=0)

    @property
    def holds(self):
        """Every rope taut in water and at or above the plan's ``min_tension`` (hook errors at
        worst)."""
        least = float(self.least.min())
        return least > 0.0 and least >= self.min_tension

    @property
    def checks(self):
        """The lowest tension in water >= the plan's ``min_tension`` (and > 0, the held
        model's range)."""
        return [
            Check.lower(
                "in_water_min_tension",
                "all ropes",
                float(self.least.min()),
                self.min_tension,
                "t",
                note="lowest held tension at the start in water, over the CG envelope and the hook "
                "errors at worst, against the plan's min_tension; below 0 a rope goes slack and the "
                "held model no longer holds",
            )
        ]


def _loads_at(body, in_water, offset, yaw):
    body = dataclasses.replace(
        body, cog=tuple(float(c + d) for c, d in zip(body.cog, offset)), weight_curve=None
    )
    scene = Scene(
        body=body,
        lugs=(),
        cranes=(),
        attitude=Attitude(lift_height=in_water.start_lift_height, yaw=yaw),
        water=in_water.water,
        hull=in_water.hull,
    )
    try:
        held = held_loads(scene)
    except EquilibriumNotFound as err:
        raise InvalidScene(f"plan.start_lift_height = {in_water.start_lift_height:g}: {err}") from None
    return WaterLoad(
        cog_offset=tuple(float(v) for v in offset),
        net_weight=held.net_weight,
        point=held.net_point,
        buoyancy=held.afloat.buoyancy,
        centre_of_buoyancy=held.afloat.centre_of_buoyancy,
    )


def water_loads(problem):
    """The start's :class:`WaterLoad` at every CG-envelope vertex (the nominal CG first).

    Raises
    ------
    InvalidScene
        The hull floats at the start height (the buoyancy exceeds the weight): no rope holds it.
    """
    body = Body(weight=problem.body.weight, cog=tuple(problem.body.cog))
    offsets = [tuple(float(v) for v in o) for o in problem.cog_envelope.offsets()]
    return tuple(_loads_at(body, problem.in_water, o, float(problem.yaw)) for o in offsets)


def in_water_case(problem, lugset, preload):
    """Each rope's held tension at the start in water for one lug set (:class:`InWaterCase`).

    Parameters
    ----------
    problem : PlanProblem
        With ``in_water``.
    lugset : LugSet
    preload : array_like, shape (n,)  [t]
    """
    loads = water_loads(problem)
    boom = lugset.boom_heights(np.asarray(preload, dtype=float))
    level = np.array([[problem.lift_height, 0.0, 0.0]])
    tensions, gains, shifts = [], [], []
    for load in loads:
        params = pack(
            problem,
            lugset.points,
            np.asarray(load.point, dtype=float),
            boom,
            weight=load.net_weight,
            rope_length=lugset.rope_length,
            EA=lugset.EA,
        )
        t, d, g = run_block(rope_model(lugset.n).held_block, lugset.n, level, params)
        tensions.append(t[0])
        shifts.append(d[0])
        gains.append(g[0])
    tensions, gains = np.array(tensions), np.array(gains)
    value = float(robust(tensions, gains, lugset)[0].max())
    return InWaterCase(
        loads=loads,
        cranes=lugset.crane_names,
        lugs=lugset.names,
        tensions=tensions,
        gain=gains,
        hook_shift=np.array(shifts),
        hook_tolerance=np.asarray(lugset.hook_tolerance, dtype=float),
        value=value,
        min_tension=max(float(problem.min_tension), 0.0),
    )


def in_water_json(plan):
    """``{"in_water": {...}}`` of ``plan --json`` (``{}`` without ``[water]``)."""
    case = plan.design_loads.in_water
    if case is None:
        return {}
    nominal = case.loads[0]
    problem = plan.problem
    return {
        "in_water": {
            "start_lift_height": problem.in_water.start_lift_height,
            "water_level": problem.in_water.water.level,
            "net_weight": nominal.net_weight,
            "buoyancy": nominal.buoyancy,
            "point": list(plan.in_file_frame(nominal.point)),
            "frame": plan.frame,
            "tensions": dict(zip(plan.labels, case.tensions[0].tolist())),
            "tensions_with_hook_errors": dict(zip(plan.labels, case.worst.tolist())),
            "lowest": float(case.least.min()),
            "value": case.value,
            "governs": [c.label for c in plan.design_loads.cranes if c.governs == "in_water"],
            "checks": [c.to_json() for c in case.checks],
            "ranking": [
                {"lugs": list(d.in_water.lugs), "value": d.in_water.value, "holds": d.in_water.holds}
                for d in plan.ranked_design
            ],
        }
    }
