"""The strength objectives (``bending``, ``shear``, ``strength``) with cranes on slings.

The strength search (:mod:`liftplan.planner.plans.strength`) chooses lift points and their
level tensions T* for the hull girder; the sling planner (:mod:`.slings.apex`) makes each
sling's hook a lift point of the held model (body-fixed for 3/4 legs, hinged about its pair for
2 legs). Together:

1. the candidates are the slings' hooks (:func:`~.slings.apex.apex_problem`: every rig the
   slings can take, its hook at level), the cranes bare on their hooks;
2. the girder's loads are the legs': a hook's tension T splits into leg forces at its lugs by
   the sling's statics at each state (:class:`SlingLoads`). At a given attitude the split is
   fixed by the legs' geometry - a 2-leg sling hinged about its pair hangs in the vertical
   plane through it and is statically determinate, a 3-leg apex is determinate, a 4-leg apex
   shares by the legs' stiffness - so each leg's force is T times a fixed vector and the
   girder's M and Q at every section stay linear in the hooks' tensions: a candidate's column
   in the lug-choice MIP and in each set's LP is the sum of its legs' loads;
3. two hooks whose slings share a lug are a clash in the MIP (never both chosen);
4. the chosen hooks, tensions and boom heights are the sling plan's
   (:class:`~.slings.apex.ApexSlingPlan`): legs, sling angles, the rules' chain per crane and
   per lug, the rigging scene and its hull girder checked on the rigging model (free hooks,
   elastic legs) at every state the plan holds, as every sling plan does.

The legs' horizontal components also push or pull the girder along its axis (an axial force
N). It is not taken: the allowables are for M and Q, and the axial component enters the girder
as :mod:`liftplan.model.strength.girder` takes it, as the couple (z - z_G) f_x about the
reference height (its moment), exactly as ``liftplan solve`` does.

Not planned (refused by :class:`~liftplan.planner.problem.definition.PlanProblem`): force
control (strand jacks) on slings, spreader bars, and two cranes on slings.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.strength.girder import attitude_matrix
from liftplan.planner.plans.held import Plan
from liftplan.planner.plans.slings.apex import ApexSlingPlan, apex_problem
from liftplan.planner.plans.slings.geometry import hinged_hooks, leg_split
from liftplan.planner.plans.strength import (
    StrengthContext,
    StrengthStats,
    objective_weights,
    plan_strength,
    strength_set_json,
)
from liftplan.planner.search.evaluator import SetResult
from liftplan.planner.search.scenarios import LugSet, Scenario
from liftplan.planner.search.strength import PointLoads


def uses_strength_slings(problem):
    """True when a strength objective's cranes carry slings."""
    return problem.goal.girder and any(c.sling is not None for c in problem.fleet)


class SlingLoads:
    """The girder's loads of the slings' hooks: each leg's force per unit hook tension.

    Parameters
    ----------
    problem : PlanProblem
        As written (candidates are lugs).
    derived : PlanProblem
        Its hooks as candidates (:func:`~.slings.apex.apex_problem`).
    rigs : Rigs
        Rig j is the derived problem's candidate j.
    """

    def __init__(self, problem, derived, rigs):
        self.rigs = rigs
        self.yaw = problem.yaw
        self.lugs = np.asarray(rigs.lugs, dtype=int)  # (R, k)
        self.points = problem.points[self.lugs]  # (R, k, 3) body frame
        self.hooks = np.asarray(rigs.hook, dtype=float)  # (R, 3) at level
        self.hinges = derived.hinge_rows  # None: body-fixed apexes
        sling = problem.fleet[0].sling
        self.stiffness = np.full(self.lugs.shape[1], sling.EA / sling.length)
        #: the lugs' x: where the point loads may be  [m]
        self.stations = np.unique(problem.points[np.unique(self.lugs), 0])

    def shared_columns(self, kinds):
        """(candidate x kinds + class) column pairs of two hooks whose slings share a lug."""
        lugs = self.lugs
        first, second = np.nonzero(
            np.triu((lugs[:, None, :, None] == lugs[None, :, None, :]).any(axis=(2, 3)), 1)
        )
        out = [
            np.column_stack([first * kinds + a, second * kinds + b])
            for a in range(kinds)
            for b in range(kinds)
        ]
        return np.concatenate(out).astype(np.int64) if out else np.empty((0, 2), dtype=np.int64)

    def plan_positions(self, rot):
        """Each hook's plan position (x, y) with the body turned by ``rot``  [m]."""
        if self.hinges is None:
            return (self.hooks @ rot.T)[:, :2]
        return hinged_hooks(self.hinges, self.hooks, rot)[:, :2]

    def unit_forces(self, indices, rot):
        """Each leg's force per unit hook tension, body components, the body at ``rot``.

        Returns
        -------
        (m, k, 3)  [-]
            Hooks ``indices`` (m of them), their k legs.
        """
        points, hooks = self.points[indices], self.hooks[indices]
        if self.hinges is None:  # a body-fixed apex: the vertical load seen from the body
            load = rot[2]
            along = hooks[:, None, :] - points
            along /= np.linalg.norm(along, axis=2, keepdims=True)
            if points.shape[1] == 3:
                tension = np.linalg.solve(
                    np.transpose(along, (0, 2, 1)), np.broadcast_to(load, hooks.shape)[..., None]
                )[..., 0]
            else:
                tension = np.array([leg_split(h, p, load, self.stiffness) for h, p in zip(hooks, points)])
            return tension[..., None] * along
        hook = hinged_hooks(self.hinges[indices], hooks, rot)  # world, body origin at height 0
        posed = points @ rot.T
        along = hook[:, None, :] - posed
        along /= np.linalg.norm(along, axis=2, keepdims=True)
        # the vertical hook load lies in the sling's plane: least squares is exact there
        gram = np.einsum("mid,mjd->mij", along, along)
        tension = np.linalg.solve(gram, along[..., 2:3])[..., 0]
        return (tension[..., None] * along) @ rot  # world -> body components

    def point_loads(self, indices, scenarios):
        """:class:`~liftplan.planner.search.strength.PointLoads` of hooks ``indices`` (None:
        every hook) in each scenario: one load per leg at its lug."""
        indices = np.arange(len(self.lugs)) if indices is None else np.asarray(indices, dtype=int)
        points = self.points[indices]
        m, k = points.shape[:2]
        normal, axial = np.empty((len(scenarios), m * k)), np.empty((len(scenarios), m * k))
        for row, s in enumerate(scenarios):
            force = self.unit_forces(indices, attitude_matrix(s.heel, s.trim, self.yaw))
            normal[row], axial[row] = force[..., 2].ravel(), force[..., 0].ravel()
        return PointLoads(
            x=points[..., 0].ravel(),
            z=points[..., 2].ravel(),
            owner=np.repeat(np.arange(m), k),
            normal=normal,
            axial=axial,
            count=m,
        )


@dataclass(frozen=True)
class SlingSearchStats(StrengthStats):
    """:class:`~.strength.StrengthStats` with the count of (hook set, crane assignment) rows
    the search chose among (as a sling plan's stats say it)."""

    rows: int = 0


def _row(derived, context, chosen):
    """The chosen hooks as the held plan's :class:`SetResult` (its tensions over the dense
    box, the CG envelope and the hook errors), for the sling plan's legs and chain."""
    lugset = LugSet(derived, chosen.indices, chosen.cranes)
    preload = np.asarray(chosen.preload, dtype=float)
    dense = context.hoist_states(dense=True)
    tensions, gain = lugset.tensions_and_gain(preload, dense)
    margin = np.abs(gain) @ lugset.hook_tolerance
    per_swl = tensions / lugset.swl
    state = chosen.states[chosen.bending.state]
    return SetResult(
        lugs=chosen.names,
        indices=chosen.indices,
        cranes=chosen.cranes,
        crane_names=chosen.crane_names,
        radius=lugset.radius,
        swl=lugset.swl,
        preload=preload,
        boom_heights=np.asarray(chosen.boom_heights, dtype=float),
        nominal_spread=float(chosen.spread),
        worst_spread=float(chosen.worst_spread),
        worst=Scenario(float(state["heel"]), float(state["trim"]), tuple(state["cog_offset"])),
        bound=float(chosen.bound),
        screen_bound=float(chosen.bound),
        tension_range=chosen.tension_range,
        rope_max=(tensions + margin).max(axis=0),
        rounds=0,
        converged=True,
        objective="spread",  # what SetResult can say; the strength objective is the plan's
        worst_value=float(chosen.value),
        worst_utilisation_spread=float(np.ptp(per_swl, axis=1).max()),
        nominal_utilisation_spread=float(np.ptp(preload / lugset.swl)),
    )


def plan_strength_slings(problem, top=None):
    """Plan for the hull girder with cranes on slings (see the module docstring).

    Returns
    -------
    StrengthSlingPlan

    Raises
    ------
    PlanInfeasible
    Interrupted
        Ctrl-C: ``plan`` the best sling plan so far (None when none).
    """
    derived, rigs = apex_problem(problem)
    context = StrengthContext(derived, SlingLoads(problem, derived, rigs))
    return plan_strength(
        derived, top, context=context, wrap=lambda search: sling_plan(problem, rigs, context, search)
    )


def sling_plan(problem, rigs, context, search):
    """The :class:`StrengthSlingPlan` of a strength plan on the hooks.

    Parameters
    ----------
    problem : PlanProblem   as written (candidates are lugs)
    rigs : Rigs   the derived problem's candidates
    context : StrengthContext   the hooks' (``context.problem`` the derived problem)
    search : StrengthPlan   on the derived problem

    Returns
    -------
    StrengthSlingPlan
    """
    derived = context.problem
    rows = (
        math.comb(len(rigs), problem.cranes)
        * math.factorial(problem.cranes)
        // math.prod(math.factorial(len(group)) for group in derived.crane_classes)
    )
    stats = SlingSearchStats(**dataclasses.asdict(search.stats), rows=rows)
    inner = Plan(problem=derived, ranking=[_row(derived, context, search.chosen)], stats=stats)
    return StrengthSlingPlan(
        problem=problem, inner=inner, rigs=rigs, ruled_out=dict(rigs.ruled_out), search=search
    )


@dataclass(frozen=True)
class StrengthSlingPlan(ApexSlingPlan):
    """A sling plan whose hooks were chosen for the hull girder.

    Everything a sling plan says (legs, sling angles, the rules' chain, the rigging scene and
    its girder checks) from :class:`~.slings.apex.ApexSlingPlan`; the strength search's own
    results (the objective's peaks on the planning model, its bound and gap, the
    spread-optimal hooks beside it) from ``search``.

    Parameters
    ----------
    search : StrengthPlan
        The strength plan on the hooks (``search.problem`` is the derived problem).
    """

    kind = "strength"

    search: object = None

    @property
    def objective(self):
        return self.problem.objective

    @property
    def control(self):
        return self.problem.control

    @cached_property
    def _loads(self):
        return SlingLoads(self.problem, self.search.problem, self.rigs)

    def girder_points(self, indices, scenarios):
        """The girder's loads of hooks ``indices`` in each scenario (:class:`SlingLoads`)."""
        return self._loads.point_loads(indices, scenarios)

    @cached_property
    def checks(self):
        """The sling plan's checks and the hooks' least tension over the states."""
        c = self.search.chosen
        return super().checks + [
            Check.lower(
                "min_tension",
                "all hooks",
                c.tension_range[0],
                self.problem.min_tension,
                "t",
                note="lowest hook load over the states (box, CG envelope, hook errors)",
            )
        ]

    def _set_json(self, s, stats):
        return {
            "hooks": {crane: name.split("+") for crane, name in zip(s.crane_names, s.names)},
            "hook_tensions": dict(zip(s.crane_names, np.asarray(s.preload, dtype=float).tolist())),
            "boom_heights": dict(zip(s.crane_names, np.asarray(s.boom_heights, dtype=float).tolist())),
        } | strength_set_json(s, stats, self.in_file_frame)

    def to_json(self):
        """The sling plan's JSON, then the strength search's: ``objective``, ``control``,
        ``strength_weights``, ``strength`` (the chosen hooks' peaks on the planning model, hook
        loads split into the legs as above) and ``spread_optimal``."""
        search, weights = self.search, objective_weights(self.search.problem)
        return super().to_json() | {
            "objective": self.objective,
            "control": self.control,
            "strength_weights": {"bending": weights[0], "shear": weights[1]},
            "strength": self._set_json(search.chosen, search.stats),
            "spread_optimal": (
                None
                if search.spread_plan is None
                else self._set_json(search.spread_plan, search.spread_stats)
            ),
        }
