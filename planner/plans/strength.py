"""Lift plans chosen for the hull girder's strength (``[plan] objective = "bending"``,
``"shear"`` or ``"strength"``): the plan object and its search.

The objective is the worst |M| / allowable (``bending``), |Q| / allowable (``shear``) or
w_M x the first + w_Q x the second (``strength``, weights from ``[plan] strength_weights``),
over the heel/trim box (hoist control) or the equilibrium attitudes (force control), the CG
envelope and, for hoist control, the hook errors, with every tension within its limits
(min_tension, the rules' limits of :func:`liftplan.planner.problem.fleet.rule_limits`, the
crane code's margin at level, the boom range). For each lug set the tensions follow from a
linear program (:class:`liftplan.planner.search.strength.StrengthLP`) solved on a growing list
of states and sections (cutting planes: a dense heel x trim grid and the exact maxima along
the body). Over the candidates:

* force control: one mixed-integer program over every candidate (HiGHS) is the problem
  itself, so its optimum is the plan; sections found by the exact check are added and it is
  re-solved until the chosen set's exact value meets the bound;
* hoist control: the held model's tensions depend on the whole set (a 3x3 solve per state),
  which is not linear in the choice. The MIP of the level state (exact: the tensions there
  are T*) with each other state's tensions only statically admissible is a relaxation: its
  optimum is a lower bound on every set. Its set is evaluated exactly, excluded by a no-good
  cut, and the MIP re-solved until the bound meets the best set found (logic-based Benders)
  or the time limit stops it with the gap stated.

With a fleet of unequal cranes (``[[cranes]]``) the MIP chooses the crane on each lug too: a
column per (candidate, crane class) with that class's limits at its radius (chart SWL through
the rules' chain, the code margin, the boom range with its rope) and no two columns whose booms
clash (:func:`clash_columns`); each (set, assignment) it picks is evaluated exactly with its
cranes' ropes, and the no-good cuts exclude one (set, assignment) at a time.

The plan carries the strength-optimal choice beside the spread-optimal one (the same search
with the objective max - min tension), so an engineer sees what each costs the other, and the
rules' design loads per crane (with ``breakout_scene``, the breakout case) as checks.
"""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import PlanInfeasible, SolverFailed
from liftplan.model.scene.objects import Analysis, Attitude, Crane, Lug, Redundant, Scene
from liftplan.model.strength.girder import attitude_matrix
from liftplan.planner.plans.breakout import breakout_json
from liftplan.planner.plans.common import InFileFrame, weight_json
from liftplan.planner.plans.design_loads import (
    CraneDesign,
    DesignBuilder,
    DesignLoads,
    TiltCase,
)
from liftplan.planner.plans.held import Plan as HeldPlan
from liftplan.planner.plans.held import clearance_checks
from liftplan.planner.problem.clearance import clear
from liftplan.planner.problem.fleet import rule_limits
from liftplan.planner.search.evaluator import GapMixin, Interrupted
from liftplan.planner.search.progress import best_bound, progress_bar
from liftplan.planner.search.scenarios import LugSet, Scenario, box_attitudes
from liftplan.planner.search.strength import (
    STABLE_HEIGHT,
    CandidateMIP,
    GirderLoads,
    Peak,
    PointLoads,
    Sections,
    State,
    allowable,
    body_tilt,
    exact_peaks,
    force_attitude,
    section_ratios,
    section_rows,
    strength_lp,
)

#: Share of ``plan.time_limit`` the strength search takes; the spread-optimal partner the rest.
MAIN_SHARE = 0.8
#: The weights (bending ratio, shear ratio, spread) of the spread-optimal plan beside it.
SPREAD_WEIGHTS = (0.0, 0.0, 1.0)
#: Dense heel x trim grid of the exact check (hoist control), per CG vertex.
DENSE = 21
#: A set's value is converged when the exact worst exceeds the LP's by less than this
#: (relative; the LP solver's own accuracy is ~1e-8).
CONVERGED = 1e-6
#: Cutting-plane rounds per set before the search says it did not converge.
ROUNDS = 40
#: Time for the spread-optimal plan beside a strength plan  [s]: it is the comparison, not the
#: plan, and its MIP (min - max over the chosen points) is weak; its gap is stated.
PARTNER_TIME = 30.0
#: How each control's search works, as its stats say.
FORCE_METHOD = "MIP (HiGHS) over every candidate"
HOIST_METHOD = "MIP relaxation (HiGHS) + exact set LP, no-good cuts"


def uses_strength(problem):
    """True when the plan's objective is the hull girder's strength."""
    return problem.goal.girder


def objective_weights(problem):
    """(bending, shear, spread) weights of the problem's objective."""
    goal = problem.goal
    if not goal.girder:
        return SPREAD_WEIGHTS
    return (*(goal.girder_weights or problem.strength_weights), 0.0)


@dataclass(frozen=True)
class StrengthSet:
    """One lug set with its tensions, evaluated over every state.

    Parameters
    ----------
    indices : tuple of int   candidate indices
    names : tuple of str
    cranes : tuple of int   fleet index of the crane on each lug
    crane_names : tuple of str
    preload : (n,)  [t]   level tensions T* (force control: the held forces)
    boom_heights : (n,) or None  [m]   hoist control
    bending, shear : Peak   worst |M| / allowable [t m], |Q| / allowable [t], with the state
    spread : float  [t]   max - min of T*
    worst_spread : float  [t]   over every state (force control: = spread)
    value : float   the objective's value (weights x ratios, or the worst spread)
    bound : float   the set's LP over the states and sections it used (a lower bound)
    states : tuple of dict   the states the peaks name (heel, trim [deg], cog_offset [m])
    tension_range : (float, float)  [t]   lowest and highest tension over the states
    """

    indices: tuple[int, ...]
    names: tuple[str, ...]
    cranes: tuple[int, ...]
    crane_names: tuple[str, ...]
    preload: np.ndarray
    boom_heights: np.ndarray | None
    bending: Peak
    shear: Peak
    spread: float
    worst_spread: float
    value: float
    bound: float
    states: tuple
    tension_range: tuple[float, float]


@dataclass(frozen=True)
class StrengthStats(GapMixin):
    """How the search went.

    Parameters
    ----------
    method : str   ``"MIP"`` (force control) or ``"MIP relaxation + no-good cuts"`` (hoist)
    lower_bound : float   no lug set does better (over the states and sections used)
    seconds : float  [s]
    rounds : int   MIP solves
    evaluated : int   lug sets evaluated exactly
    stopped : str   ``"proved"``, ``"gap"``, ``"time_limit"``
    certified : bool   False where the bound rests on an approximation (force control with
        candidates at different heights: the attitudes by fixed point)
    """

    method: str
    lower_bound: float
    seconds: float
    rounds: int
    evaluated: int
    stopped: str
    certified: bool = True
    best: float = math.nan


class StrengthContext:
    """What every lug set of a problem shares: loads, envelopes, states, limits.

    The fleet in its classes of interchangeable cranes (:attr:`PlanProblem.crane_classes`;
    one class for equal cranes): the limits are per (candidate, class), from each class's
    chart SWL at its radius to the candidate through the rules' chain (NaN where it cannot
    reach), for the lug choice's columns (:class:`CandidateMIP`).

    With slings (:mod:`liftplan.planner.plans.strength_slings`) the candidates are the slings'
    hooks: their girder loads are their legs' (``slings``), two hooks sharing a lug are a
    clash, and a hinged hook's place in plan moves with the attitude.

    Parameters
    ----------
    problem : PlanProblem
        With slings: the derived problem whose candidates are the hooks.
    slings : SlingLoads, optional
        The hooks' legs (None: single ropes at the candidates).
    """

    def __init__(self, problem, slings=None):
        self.problem = problem
        self.slings = slings
        body = problem.body
        self.loads = GirderLoads(body)
        strength = problem.strength
        self.envelopes = (
            None if strength is None else strength.bending_moment,
            None if strength is None else strength.shear_force,
        )
        self.control = problem.control
        self.points = problem.points
        self.offsets = problem.cog_envelope.offsets()
        stations = self.points[:, 0] if slings is None else slings.stations
        self.sections = Sections.initial(self.loads, stations, self.envelopes)
        self.classes = problem.crane_classes
        self.counts = tuple(len(group) for group in self.classes)
        first = [group[0] for group in self.classes]
        swl = problem.reach[1][:, first]  # (C, K), NaN out of reach
        out = np.isnan(swl)
        # the rules' chain of n ropes (its code margin depends on n): each column as one of n
        tiled = np.repeat(np.where(out, 1.0, swl)[..., None], problem.cranes, axis=-1)
        cranes = np.broadcast_to(np.array(first)[None, :, None], tiled.shape)
        limit, share = (v[..., 0] for v in rule_limits(problem, tiled, cranes))
        #: (C, K) [t]: the largest tension in the box, and at level, of a class on a candidate
        self.limit, self.share = np.where(out, np.nan, limit), np.where(out, np.nan, share)
        fleet = [problem.fleet[j] for j in first]
        #: (K,) [t/m] rope stiffness of each class
        self.stiffness = np.array([c.EA / c.rope_length for c in fleet])
        #: (C, K) [m] boom heights with the rope unstretched at level
        ropes = np.array([c.rope_length for c in fleet])
        self.boom_zero = problem.lift_height + self.points[:, 2][:, None] + ropes
        self.boom_min = np.array([c.boom_min for c in fleet])
        self.boom_max = np.array([c.boom_max for c in fleet])
        self.clashes = clash_columns(problem, self.classes)
        if slings is not None:  # two slings never share a lug
            self.clashes = np.concatenate([self.clashes, slings.shared_columns(len(self.classes))])

    def girder_points(self, indices, scenarios):
        """The girder's point loads of the lift points ``indices`` (None: every candidate) in
        each scenario (:class:`~liftplan.planner.search.strength.PointLoads`): single ropes
        along the vertical, or each sling's legs."""
        if self.slings is not None:
            return self.slings.point_loads(indices, scenarios)
        points = self.points if indices is None else self.points[list(indices)]
        return PointLoads.ropes(points, [State(tuple(self.up(s.heel, s.trim))) for s in scenarios])

    def plan_positions(self, rot):
        """Every lift point's plan position (x, y) with the body turned by ``rot``  [m]: a
        body-fixed point turns with it, a hinged sling hook hangs where its pair puts it."""
        if self.slings is not None:
            return self.slings.plan_positions(rot)
        return (self.points @ rot.T)[:, :2]

    def cranes_of(self, result):
        """Fleet indices of the cranes on a :class:`MIPResult`'s lugs: each class's members
        handed out in candidate order (interchangeable, so any order is the same row)."""
        taken = [list(group) for group in self.classes]
        return tuple(taken[kind].pop(0) for kind in result.kinds)

    def allowable(self, which, x):
        return allowable(self.envelopes[which], x)

    def up(self, heel, trim):
        return attitude_matrix(heel, trim, self.problem.yaw)[2]

    # -- states ---------------------------------------------------------------------------
    def hoist_states(self, dense=False):
        """Scenarios of the held model: the first list (level x CG vertices, the box's corners
        at the nominal CG) or the dense grid x CG vertices."""
        p = self.problem
        if dense:
            grid = box_attitudes(p, DENSE, DENSE)
            return [Scenario(float(h), float(t), tuple(o)) for o in self.offsets for h, t in grid]
        out = [Scenario(0.0, 0.0, tuple(o)) for o in self.offsets]
        corners = {
            (h * p.heel_tolerance + 0.0, t * p.trim_tolerance + 0.0) for h in (-1, 1) for t in (-1, 1)
        } - {(0.0, 0.0)}
        return out + [Scenario(h, t) for h, t in sorted(corners)]

    def centre_floor(self):
        """Force control: the least height of the force centre F_z [m] for every CG vertex to
        hang stable with its equilibrium tilt inside the tolerance box."""
        p, need = self.problem, []
        for dx, dy, dz in self.offsets:
            h = STABLE_HEIGHT
            for off, tol, what in ((dx, p.trim_tolerance, "trim"), (dy, p.heel_tolerance, "heel")):
                if abs(off) > 0.0:
                    if tol <= 0.0:
                        raise PlanInfeasible(
                            f"force control: a CG offset of {abs(off):g} m tilts the body, but "
                            f"plan.tolerance.{what} = 0; expected a tolerance > 0 deg"
                        )
                    h = max(h, abs(off) / math.tan(math.radians(tol)))
            need.append(p.body.cog[2] + dz + h)
        return max(need)


def clash_columns(problem, classes):
    """Pairs of (candidate, class) columns whose cranes' booms cross in plan or come nearer
    than ``plan.crane_clearance`` (:mod:`liftplan.planner.problem.clearance`), numbered
    candidate x K + class; none without crane positions.

    Returns
    -------
    numpy.ndarray, shape (P, 2), int
    """
    distances, kinds = problem.boom_distances, len(classes)
    out = [np.empty((0, 2), dtype=np.int64)]
    if distances is None:
        return out[0]
    for a in range(kinds):
        for b in range(a, kinds):
            if a == b and len(classes[a]) < 2:
                continue  # one crane of the class: never on two candidates
            ja, jb = classes[a][0], classes[b][1 if a == b else 0]
            first, second = np.nonzero(~clear(distances[:, ja, :, jb], problem.crane_clearance))
            keep = first < second if a == b else first != second
            out.append(np.column_stack([first[keep] * kinds + a, second[keep] * kinds + b]))
    return np.concatenate(out)


# -- one lug set ---------------------------------------------------------------------------------
class StrengthEvaluator:
    """Evaluate lug sets exactly: the LP on growing lists of states and sections.

    Parameters
    ----------
    context : StrengthContext
    """

    def __init__(self, context):
        self.context = context
        self.count = 0

    def evaluate(self, indices, weights, cranes=None):
        """The best tensions for one lug set, with the given crane on each lug, and its exact
        worst values.

        Parameters
        ----------
        indices : sequence of int   candidate indices
        weights : (3,)   bending ratio, shear ratio, spread
        cranes : sequence of int, optional   fleet index of the crane on each lug, in the
            order of ``indices`` (default crane k on the k-th: any order for equal cranes)

        Returns
        -------
        StrengthSet

        Raises
        ------
        PlanInfeasible
            No tensions hold the limits (the message says which).
        SolverFailed
            The cutting planes did not converge in :data:`ROUNDS` rounds.
        """
        self.count += 1
        indices = [int(i) for i in indices]
        cranes = list(range(len(indices))) if cranes is None else [int(j) for j in cranes]
        order = np.argsort(indices)
        indices, cranes = tuple(indices[k] for k in order), tuple(cranes[k] for k in order)
        p = self.context.problem
        swl = p.reach[1][list(indices), list(cranes)]
        if np.any(np.isnan(swl)):
            k = int(np.argmax(np.isnan(swl)))
            raise PlanInfeasible(
                f"crane {p.fleet[cranes[k]].name} cannot reach lug {p.names[indices[k]]} (outside its chart)"
            )
        plan = self.context.points[list(indices), :2]
        if (
            np.linalg.matrix_rank(
                np.column_stack([np.ones(len(plan)), plan - plan.mean(axis=0)]),
                tol=1e-9 * max(np.ptp(plan), 1.0),
            )
            < 3
        ):
            names = ", ".join(self.context.problem.names[i] for i in indices)
            raise PlanInfeasible(f"lugs {names}: on one line in plan; they cannot hold the body")
        if self.context.control == "force":
            return self._force(indices, cranes, weights)
        return self._hoist(indices, cranes, weights)

    # rows of the LP for states whose tensions are P T* + q
    def _rows(self, points, sections, states, gains, offsets, hook):
        ctx = self.context
        allow_m = ctx.allowable(0, sections.x)
        allow_q = ctx.allowable(1, sections.x)
        rows = {"m": ([], [], []), "q": ([], [], [])}
        for k, state in enumerate(states):
            gm, hm, gq, hq = section_rows(ctx.loads, points, sections, state, k)
            for key, g, h, allow in (("m", gm, hm, allow_m), ("q", gq, hq, allow_q)):
                gp = g @ gains[k]
                rows[key][0].append(gp / allow[:, None])
                rows[key][1].append((g @ offsets[k] + h) / allow)
                margin = np.zeros(len(h)) if hook is None else np.abs(g @ hook[0][k]) @ hook[1] / allow
                rows[key][2].append(margin)
        return tuple(tuple(np.concatenate(v) for v in rows[key]) for key in ("m", "q"))

    def _peaks(self, points, tensions, states, hook=None):
        """Exact worst ratio of M and Q over the given states (tensions (k, n))."""
        return exact_peaks(self.context.loads, self.context.envelopes, points, tensions, states, hook)

    def _finish(self, lugset, preload, boom, peaks, spread, worst_spread, weights, bound, states, trange):
        value = weights[0] * peaks[0].ratio + weights[1] * peaks[1].ratio + weights[2] * worst_spread
        return StrengthSet(
            indices=lugset.indices,
            names=lugset.names,
            cranes=lugset.cranes,
            crane_names=lugset.crane_names,
            preload=preload,
            boom_heights=boom,
            bending=peaks[0],
            shear=peaks[1],
            spread=float(np.ptp(preload)),
            worst_spread=float(worst_spread),
            value=float(value),
            bound=float(bound),
            states=tuple(states),
            tension_range=trange,
        )

    def _force(self, indices, cranes, weights):
        ctx, p = self.context, self.context.problem
        points = ctx.points[list(indices)]
        n = len(indices)
        lugset = LugSet(p, indices, cranes)
        a0, b0 = lugset.level_statics
        floor = ctx.centre_floor()
        centre = (points[:, 2] * 1.0, p.body.weight * floor)
        if points[:, 2].max() * p.body.weight < centre[1] - 1e-9:
            raise PlanInfeasible(
                "force control: every lug is too low above the CG for the body to "
                "hang stable within the tolerance box"
            )
        limit, share = lugset.limit, lugset.share_limit  # each jack's own capacity
        tension_rows = (
            np.eye(n)[None],
            np.zeros((1, n)),
            np.zeros((1, n)),
            np.full((1, n), p.min_tension),
            limit[None],
        )
        prange = (np.full(n, p.min_tension), np.minimum(limit, share))
        sections = ctx.sections
        up = force_attitude(points, np.full(n, p.body.weight / n), p.body.weight, p.body.cog, ctx.offsets)[0]
        for _ in range(ROUNDS):
            states = [State(tuple(u), tuple(o)) for u, o in zip(up, ctx.offsets)]
            eye = [np.eye(n)] * len(states)
            zero = [np.zeros(n)] * len(states)
            rows_m, rows_q = self._rows(points, sections, states, eye, zero, None)
            lp = strength_lp(n, len(rows_m[1]), len(rows_q[1]), 1)
            result = lp.solve(weights, rows_m, rows_q, tension_rows, a0, b0, prange, centre)
            new_up, height = force_attitude(points, result.preload, p.body.weight, p.body.cog, ctx.offsets)
            moved = float(np.abs(new_up - up).max())
            up = new_up
            states = [State(tuple(u), tuple(o)) for u, o in zip(up, ctx.offsets)]
            tensions = np.repeat(result.preload[None], len(states), axis=0)
            peaks, xs = self._peaks(points, tensions, states)
            lp_value = weights[0] * result.bending + weights[1] * result.shear + weights[2] * result.spread
            exact = weights[0] * peaks[0].ratio + weights[1] * peaks[1].ratio + weights[2] * result.spread
            if moved < 1e-12 and exact <= lp_value * (1 + CONVERGED) + 1e-12:
                described = [self._describe(s) for s in states]
                return self._finish(
                    lugset,
                    result.preload,
                    None,
                    peaks,
                    result.spread,
                    float(np.ptp(result.preload)),
                    weights,
                    lp_value,
                    described,
                    (float(result.preload.min()), float(result.preload.max())),
                )
            sections = sections.add(np.repeat(xs, 2), np.tile([False, True], len(xs)))
        raise SolverFailed(
            f"strength LP for {', '.join(p.names[i] for i in indices)}: the sections "
            f"and attitudes did not converge in {ROUNDS} rounds"
        )

    @staticmethod
    def _describe(state):
        heel, trim = body_tilt(state.up)
        return {"heel": heel, "trim": trim, "cog_offset": list(state.cog_offset)}

    def _hoist(self, indices, cranes, weights):
        ctx, p = self.context, self.context.problem
        lugset = LugSet(p, indices, cranes)
        n = lugset.n
        hook = lugset.hook_uncertain
        scenarios = ctx.hoist_states()
        dense = ctx.hoist_states(dense=True)
        points = ctx.girder_points(indices, dense)  # the girder's loads in every dense state
        d_gain, d_offset = lugset.affine(dense)
        d_hook = d_gain * lugset.stiffness[None, None, :]
        d_states = [State(tuple(ctx.up(s.heel, s.trim)), s.cog_offset) for s in dense]
        sections = ctx.sections
        a0, b0 = lugset.level_statics
        prange = lugset.preload_range()
        for _ in range(ROUNDS):
            gains, offsets = lugset.affine(scenarios)
            states = [State(tuple(ctx.up(s.heel, s.trim)), s.cog_offset) for s in scenarios]
            hk = (gains * lugset.stiffness[None, None, :], lugset.hook_tolerance) if hook else None
            rows_m, rows_q = self._rows(
                ctx.girder_points(indices, scenarios), sections, states, gains, offsets, hk
            )
            margin = np.zeros((len(scenarios), n)) if hk is None else np.abs(hk[0]) @ hk[1]
            tension_rows = (
                gains,
                offsets,
                margin,
                np.full((len(scenarios), n), p.min_tension),
                np.repeat(lugset.limit[None], len(scenarios), axis=0),
            )
            lp = strength_lp(n, len(rows_m[1]), len(rows_q[1]), len(scenarios))
            result = lp.solve(weights, rows_m, rows_q, tension_rows, a0, b0, prange)
            lp_value = weights[0] * result.bending + weights[1] * result.shear + weights[2] * result.spread
            tensions = d_gain @ result.preload + d_offset
            ratios = self._dense_ratios(
                points, sections, d_states, tensions, (d_hook, lugset.hook_tolerance) if hook else None
            )
            hook_terms = (d_hook, lugset.hook_tolerance) if hook else None
            spread, trange = self._dense_spread(tensions, hook_terms)
            top = np.unique(np.argsort(-ratios[0])[:3].tolist() + np.argsort(-ratios[1])[:3].tolist())
            peaks, xs = self._peaks(
                points.take(top),
                tensions[top],
                [d_states[k] for k in top],
                (d_hook[top], lugset.hook_tolerance) if hook else None,
            )
            peaks = [Peak(pk.ratio, pk.value, pk.x, int(top[pk.state])) for pk in peaks]
            exact = weights[0] * peaks[0].ratio + weights[1] * peaks[1].ratio + weights[2] * spread
            if exact <= lp_value * (1 + CONVERGED) + 1e-12:
                described = [
                    {"heel": s.heel, "trim": s.trim, "cog_offset": list(s.cog_offset)} for s in dense
                ]
                return self._finish(
                    lugset,
                    result.preload,
                    lugset.boom_heights(result.preload),
                    peaks,
                    spread,
                    spread,
                    weights,
                    lp_value,
                    described,
                    trange,
                )
            worst = {pk.state for pk in peaks}
            if weights[2] > 0:  # the state of the largest spread, the hook errors' included
                worst.add(int(np.argmax(self._state_spreads(tensions, hook_terms))))
            scenarios = scenarios + [dense[k] for k in sorted(worst) if dense[k] not in scenarios]
            sections = sections.add(np.repeat(xs, 2), np.tile([False, True], len(xs)))
        raise SolverFailed(
            f"strength LP for {', '.join(p.names[i] for i in indices)}: the states "
            f"and sections did not converge in {ROUNDS} rounds"
        )

    def _dense_ratios(self, points, sections, states, tensions, hook):
        """Worst |M| / allowable and |Q| / allowable at the sections, per dense state, (2, k)."""
        ctx = self.context
        return section_ratios(ctx.loads, ctx.envelopes, points, sections, states, tensions, hook)

    @staticmethod
    def _state_spreads(tensions, hook):
        """Each dense state's spread [t], (k,): max - min tension, with hook errors the largest
        T_i - T_j + |dT_i/dH - dT_j/dH| delta over pairs (exact for independent errors)."""
        if hook is None:
            return np.ptp(tensions, axis=1)
        gain, delta = hook
        n = tensions.shape[1]
        first, second = np.nonzero(~np.eye(n, dtype=bool))
        pair = tensions[:, first] - tensions[:, second] + np.abs(gain[:, first] - gain[:, second]) @ delta
        return pair.max(axis=1)

    @classmethod
    def _dense_spread(cls, tensions, hook):
        """Worst spread [t] and (lowest, highest) tension over dense states (hook errors exact)."""
        margin = 0.0 if hook is None else np.abs(hook[0]) @ hook[1]
        spread = float(cls._state_spreads(tensions, hook).max())
        return spread, (float((tensions - margin).min()), float((tensions + margin).max()))


class StrengthInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`search_strength`: ``best`` the best set evaluated so far (None
    when none was), ``stats`` the search so far (``stopped = "interrupted"``)."""

    def __init__(self, best, stats):
        super().__init__("strength search interrupted")
        self.best, self.stats = best, stats


def _stopped_stats(method, evaluator, started, rounds, bound, best, certified=True):
    """:class:`StrengthStats` of a search Ctrl-C stopped."""
    value = math.nan if best is None else best.value
    return StrengthStats(
        method=method,
        lower_bound=min(bound, value) if best is not None else bound,
        seconds=time.perf_counter() - started,
        rounds=rounds,
        evaluated=evaluator.count,
        stopped="interrupted",
        certified=certified,
        best=value,
    )


def _bar(weights, total=None):
    """The progress line of one strength search (MIP rounds, ``total`` at most; redrawn while
    a MIP runs)."""
    what = "spread-optimal partner" if tuple(weights) == SPREAD_WEIGHTS else "strength search"
    return progress_bar(total, None, desc=f"{what}: MIP rounds", unit="rounds", ticker=True)


def _show(bar, best, bound):
    if bar is not None:
        bar.set_postfix_str(best_bound(None if best is None else best.value, bound), refresh=False)
        bar.update(1)
        bar.refresh()


# -- over the candidates --------------------------------------------------------------------------
def search_strength(problem, weights, context=None, time_limit=None):
    """The best lug set and tensions for the weights (bending, shear, spread).

    Returns
    -------
    best : StrengthSet
    stats : StrengthStats
    """
    started = time.perf_counter()
    ctx = context or StrengthContext(problem)
    evaluator = StrengthEvaluator(ctx)
    limit = time_limit if time_limit is not None else problem.time_limit
    if ctx.control == "force":
        return _search_force(ctx, evaluator, weights, started, limit)
    return _search_hoist(ctx, evaluator, weights, started, limit)


def _mip_rows(ctx, states, sections, scenarios=None):
    """Each state's ratio rows over every candidate; ``scenarios`` (hoist control) the states'
    attitudes, for a sling's legs."""
    allow_m, allow_q = ctx.allowable(0, sections.x), ctx.allowable(1, sections.x)
    points = ctx.points if scenarios is None else ctx.girder_points(None, scenarios)
    out = []
    for k, state in enumerate(states):
        gm, hm, gq, hq = section_rows(ctx.loads, points, sections, state, k)
        out.append(((gm / allow_m[:, None], hm / allow_m), (gq / allow_q[:, None], hq / allow_q)))
    return out


def _statics(ctx, heel, trim, offset):
    p = ctx.problem
    rot = attitude_matrix(heel, trim, p.yaw)
    plan = ctx.plan_positions(rot)
    cog = rot @ (np.asarray(p.body.cog) + np.asarray(offset))
    return np.vstack([np.ones(len(plan)), plan.T]), p.body.weight * np.array([1.0, cog[0], cog[1]])


def _search_force(ctx, evaluator, weights, started, limit):
    p = ctx.problem
    count, n = len(ctx.points), p.cranes
    equal_height = bool(np.ptp(ctx.points[:, 2]) < 1e-9)
    floor = ctx.centre_floor()
    centre = (ctx.points[:, 2].copy(), p.body.weight * floor)
    sections = ctx.sections
    statics = [_statics(ctx, 0.0, 0.0, (0.0, 0.0, 0.0))]
    limits = (np.full(count, p.min_tension), ctx.limit, np.fmin(ctx.limit, ctx.share))
    tensions = np.full(count, p.body.weight / n)
    best, rounds, bound = None, 0, -math.inf
    bar = _bar(weights, ROUNDS)
    try:
        while True:
            # the equilibrium attitudes from the force centre of the last solution (exact when
            # every candidate is at one height: the centre's height is then that height)
            centre_z = ctx.points[:, 2] @ tensions / tensions.sum()
            up, _ = force_attitude(
                np.column_stack([ctx.points[:, :2], np.full(count, centre_z)]),
                tensions,
                tensions.sum(),
                p.body.cog,
                ctx.offsets,
            )
            states = [State(tuple(u), tuple(o)) for u, o in zip(up, ctx.offsets)]
            blocks = _mip_rows(ctx, states, sections)
            stacked = (
                tuple(np.concatenate([b[0][j] for b in blocks]) for j in range(2)),
                tuple(np.concatenate([b[1][j] for b in blocks]) for j in range(2)),
            )
            mip = CandidateMIP(
                count, n, len(stacked[0][1]), len(stacked[1][1]), 1, shared=True, counts=ctx.counts
            )
            remaining = None if limit is None else limit - (time.perf_counter() - started)
            result = mip.solve(
                weights, statics, [stacked], limits, centre, time_limit=remaining, clashes=ctx.clashes
            )
            rounds += 1
            bound = result.value
            current = evaluator.evaluate(result.chosen, weights, ctx.cranes_of(result))
            if best is None or current.value < best.value:
                best = current
            _show(bar, best, bound)
            tensions = result.forces
            done = best.value <= bound * (1 + CONVERGED) + 1e-9
            timed_out = (limit is not None and time.perf_counter() - started > limit) or not result.complete
            if done or timed_out or rounds >= ROUNDS:
                break
            peaks = (current.bending.x, current.shear.x)
            sections = sections.add(np.repeat(peaks, 2), np.tile([False, True], 2))
    except KeyboardInterrupt:
        stats = _stopped_stats(FORCE_METHOD, evaluator, started, rounds, bound, best, equal_height)
        raise StrengthInterrupted(best, stats) from None
    finally:
        if bar is not None:
            bar.close()
    stopped = (
        "proved"
        if best.value <= bound * (1 + CONVERGED) + 1e-9
        else ("time_limit" if timed_out else "rounds")
    )
    return best, StrengthStats(
        method=FORCE_METHOD,
        lower_bound=min(bound, best.value),
        seconds=time.perf_counter() - started,
        rounds=rounds,
        evaluated=evaluator.count,
        stopped=stopped,
        certified=equal_height,
        best=best.value,
    )


def _search_hoist(ctx, evaluator, weights, started, limit):
    p = ctx.problem
    count, n = len(ctx.points), p.cranes
    scen = ctx.hoist_states()
    states = [State(tuple(ctx.up(s.heel, s.trim)), s.cog_offset) for s in scen]
    sections = ctx.sections
    statics = [_statics(ctx, s.heel, s.trim, s.cog_offset) for s in scen]
    # at level the tensions are T* itself: the code margin and the boom range hold exactly
    level_high = np.minimum(
        np.minimum(ctx.limit, ctx.share), ctx.stiffness[None, :] * (ctx.boom_max[None, :] - ctx.boom_zero)
    )
    level_low = ctx.stiffness[None, :] * (ctx.boom_min[None, :] - ctx.boom_zero)  # the boom range
    limits = (np.full(count, p.min_tension), ctx.limit, level_high, level_low)
    rows = _mip_rows(ctx, states, sections, scen)
    mip = CandidateMIP(
        count, n, len(rows[0][0][1]), len(rows[0][1][1]), len(scen), shared=False, counts=ctx.counts
    )
    best, cuts, rounds, bound, stopped = None, [], 0, -math.inf, "proved"
    bar = _bar(weights)
    try:
        while True:
            remaining = None if limit is None else limit - (time.perf_counter() - started)
            if remaining is not None and remaining <= 0:
                stopped = "time_limit"
                break
            try:
                result = mip.solve(
                    weights, statics, rows, limits, cuts=cuts, time_limit=remaining, clashes=ctx.clashes
                )
            except PlanInfeasible:
                if best is None:
                    raise
                bound = best.value  # every set is cut off: the best found is the optimum
                break
            rounds += 1
            bound = result.value
            if not result.complete:
                stopped = "time_limit"
            if best is not None and bound >= best.value * (1 - p.gap) - 1e-9:
                stopped = "proved" if bound >= best.value - 1e-9 else "gap"
                break
            try:
                current = evaluator.evaluate(result.chosen, weights, ctx.cranes_of(result))
            except PlanInfeasible:
                current = None
            if current is not None and (best is None or current.value < best.value):
                best = current
            _show(bar, best, bound)
            cuts.append(result.columns)
            if not result.complete:
                break
    except KeyboardInterrupt:
        stats = _stopped_stats(HOIST_METHOD, evaluator, started, rounds, bound, best)
        raise StrengthInterrupted(best, stats) from None
    finally:
        if bar is not None:
            bar.close()
    if best is None:
        raise PlanInfeasible("no lug set holds the body within the limits over the box")
    return best, StrengthStats(
        method=HOIST_METHOD,
        lower_bound=min(bound, best.value),
        seconds=time.perf_counter() - started,
        rounds=rounds,
        evaluated=evaluator.count,
        stopped=stopped,
        best=best.value,
    )


# -- the plan ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StrengthPlan(InFileFrame):
    """A lift plan chosen for the hull girder, with the spread-optimal plan beside it.

    Parameters
    ----------
    problem : PlanProblem
    chosen : StrengthSet   the strength-optimal set (the plan)
    stats : StrengthStats
    spread_plan : StrengthSet or None   the spread-optimal set (max - min tension), same
        limits; None only in a plan Ctrl-C stopped before the partner found a set
    spread_stats : StrengthStats or None
    """

    kind = "strength"

    problem: object
    chosen: StrengthSet
    stats: StrengthStats
    spread_plan: StrengthSet | None
    spread_stats: StrengthStats | None
    labels: tuple[str, ...] = field(init=False)

    def __post_init__(self):
        object.__setattr__(self, "labels", tuple(f"L{i + 1}" for i in range(len(self.chosen.indices))))

    @property
    def objective(self):
        return self.problem.objective

    @property
    def control(self):
        return self.problem.control

    @property
    def lugs(self):
        return dict(zip(self.labels, self.chosen.names))

    @property
    def tensions(self):
        return dict(zip(self.labels, self.chosen.preload.tolist()))

    @property
    def boom_heights(self):
        if self.chosen.boom_heights is None:
            return {}
        return dict(zip(self.labels, self.chosen.boom_heights.tolist()))

    @property
    def spread(self):
        return self.chosen.spread

    @cached_property
    def scene(self):
        """The strength-optimal plan at level as a :class:`~liftplan.model.scene.objects.Scene`
        for ``solve``: lugs by candidate name, in the planning file's frame (``scene.frame``;
        coordinates z-up), with the body's weight curve and the allowables, so its solve gives
        the girder's peaks and checks at level.

        Force control: the ``rigid`` model, level, every force but three held
        (``analysis.redundant``); the three free ones (the widest triangle in plan,
        :func:`free_three`) follow from the statics, so the solve gives the planned forces
        [t]. Hoist control: the ``elastic`` model with the planned boom heights [m], which hold
        T* at the level pose. Boom heights under force control are the hooks' at level,
        lift height + lug height + rope length [m] (the rigid model does not use them).
        """
        p, c = self.problem, self.chosen
        indices = list(c.indices)
        points, swl = p.points[indices], p.reach[1][indices, list(c.cranes)]
        fleet = [p.fleet[j] for j in c.cranes]
        ropes = np.array([crane.rope_length for crane in fleet])
        heights = c.boom_heights if c.boom_heights is not None else p.lift_height + points[:, 2] + ropes
        if self.control == "force":
            free = free_three(points)
            analysis = Analysis(
                model="rigid",
                redundant=tuple(
                    Redundant(lug=c.names[k], tension=float(c.preload[k]))
                    for k in range(len(c.names))
                    if k not in free
                ),
            )
        else:
            analysis = Analysis(model="elastic")
        return Scene(
            body=p.body,
            lugs=tuple(Lug(name=name, at=tuple(at)) for name, at in zip(c.names, points)),
            cranes=tuple(
                Crane(
                    lug=name,
                    boom_height=float(h),
                    rope_length=crane.rope_length,
                    EA=crane.EA,
                    swl=float(limit),
                    name=crane.name,
                )
                for name, h, limit, crane in zip(c.names, heights, swl, fleet)
            ),
            attitude=Attitude(lift_height=p.lift_height, yaw=p.yaw),
            analysis=analysis,
            name=f"{p.name or 'plan'}: strength-optimal lugs",
            frame=p.frame,
            strength=p.strength,
        )

    @property
    def worst_spread(self):
        return self.chosen.worst_spread

    @cached_property
    def design_loads(self):
        """The rules' design loads of the chosen set, per crane
        (:class:`~liftplan.planner.plans.design_loads.DesignLoads`; ``docs/design-loads.md``).

        Hoist control: the held plans' chain (:class:`~.design_loads.DesignBuilder`): each
        rope's worst over the box, the CG envelope and the hook errors with the planned T*,
        its share at the rules' tilt, and with ``[plan] breakout_scene`` its held tension at
        breakout. Force control: each jack's force, which it holds at every attitude (the
        worst and the share at the tilt are the force itself).
        """
        builder = DesignBuilder(self.problem)
        if self.control == "hoist":
            return builder.build(self.chosen, self.labels)
        return force_design(self.problem, builder, self.chosen, self.labels)

    @property
    def ranked_design(self):
        """The design loads of the plan (a strength plan ranks no other set)."""
        return [self.design_loads]

    #: per planned lug its crane's least plan clearance to another's (the held plans' own)
    clearances = HeldPlan.clearances

    @cached_property
    def checks(self):
        """The strength envelopes at the worst state, the tension limits, the rules' design
        loads per crane (with a breakout case its breakout checks), and with crane positions
        each crane's least plan clearance to the others' booms and hoist lines, as checks."""
        p, c = self.problem, self.chosen
        out = []
        for name, peak, envelope, unit in (
            ("bending_moment", c.bending, p.strength.bending_moment, "t m"),
            ("shear_force", c.shear, p.strength.shear_force, "t"),
        ):
            if envelope is not None:
                out.append(
                    Check.upper(
                        name,
                        f"x = {peak.x:.1f} m",
                        peak.value,
                        peak.value / peak.ratio,
                        unit,
                        note="at the section and state where value / allowable is worst, "
                        "exactly along the body",
                    )
                )
        out.append(
            Check.lower(
                "min_tension",
                "all lugs",
                c.tension_range[0],
                p.min_tension,
                "t",
                note="lowest tension over the states",
            )
        )
        out += list(self.design_loads.checks)
        out += clearance_checks(self.clearances, p.crane_clearance)
        return out

    @property
    def _hook_tolerance(self):
        """Each planned lug's hook-height tolerance  [m]: its crane's own, or the plan's."""
        p = self.problem
        own = [p.fleet[j].hook_tolerance for j in self.chosen.cranes]
        values = [float(p.hook_tolerance if value is None else value) for value in own]
        return dict(zip(self.labels, values))

    def _fleet_json(self):
        """Which crane takes each lug, its radius [m], its chart SWL there [t] and nominal
        T / SWL, as a fleet's held plan says them."""
        p, c = self.problem, self.chosen
        radius, swl = (v[list(c.indices), list(c.cranes)] for v in p.reach)
        return {
            "cranes": dict(zip(self.labels, c.crane_names)),
            "radius": dict(zip(self.labels, radius.tolist())),
            "swl": dict(zip(self.labels, swl.tolist())),
            "utilisation": dict(zip(self.labels, (c.preload / swl).tolist())),
        }

    def _set_json(self, s, stats):
        return {
            "lugs": dict(zip(self.labels, s.names)),
            "tensions": dict(zip(self.labels, s.preload.tolist())),
            "boom_heights": (
                None if s.boom_heights is None else dict(zip(self.labels, s.boom_heights.tolist()))
            ),
        } | strength_set_json(s, stats, self.in_file_frame)

    def to_json(self):
        """``liftplan plan --json`` for a strength objective: the contract's keys (lugs,
        boom_heights, tensions, spread, worst_spread) of the chosen plan, then ``strength``
        (its peaks) and ``spread_optimal`` (the same for the spread-optimal plan)."""
        c = self.chosen
        return {
            "lugs": self.lugs,
            "boom_heights": self.boom_heights,
            "tensions": self.tensions,
            "spread": self.spread,
            "worst_spread": self.worst_spread,
            **self._fleet_json(),
            "objective": self.objective,
            "control": self.control,
            "weight": weight_json(self.problem),
            "strength_weights": {
                "bending": objective_weights(self.problem)[0],
                "shear": objective_weights(self.problem)[1],
            },
            "ranking": [],
            "frame": self.problem.frame,
            "lower_bound": self.stats.lower_bound,
            "gap": self.stats.gap,
            "relative_gap": self.stats.relative_gap,
            "strength": self._set_json(c, self.stats),
            "spread_optimal": (
                None if self.spread_plan is None else self._set_json(self.spread_plan, self.spread_stats)
            ),
            # what the plan held and was allowed, as a held plan's JSON says it (the hook
            # tolerance is in its states; the time limit shared 80/20 with the spread partner)
            "hooks": {"tolerance": self._hook_tolerance},
            "design_loads": self.design_loads.to_json(),
            "checks": [check.to_json() for check in self.checks],
            **breakout_json(self),
            "search": {
                "method": self.stats.method,
                "stopped": self.stats.stopped,
                "limits": {"gap": self.problem.gap, "time_limit": self.problem.time_limit},
            },
        }


def force_design(problem, builder, chosen, labels):
    """The rules' design loads of a force-controlled set: each jack holds its force F at every
    attitude, so its nominal, its worst over the states and its share at the rules' tilt are
    all F, and no hook error skews it (skew 1).

    Parameters
    ----------
    problem : PlanProblem
    builder : DesignBuilder   for its chain inputs (CG envelope searched, lug capacities)
    chosen : StrengthSet
    labels : tuple of str

    Returns
    -------
    DesignLoads
    """
    lugset = LugSet(problem, chosen.indices, chosen.cranes)
    tilt = problem.rules.design_tilt()[0]
    note = "strand jacks hold their forces at any tilt: the share at the rules' tilt is the force"
    cranes = []
    for k, label in enumerate(labels):
        force = float(chosen.preload[k])
        cranes.append(
            CraneDesign(
                label=label,
                crane=lugset.crane_names[k],
                lug=lugset.names[k],
                radius=None if problem.fleet[lugset.cranes[k]].position is None else float(lugset.radius[k]),
                swl=float(lugset.swl[k]),
                nominal=force,
                worst=force,
                worst_at=Scenario(0.0, 0.0),
                tilt=TiltCase(load=force, tilt=tilt, axis=(1.0, 0.0, 0.0), cog_offset=(0.0, 0.0, 0.0)),
                skewed=force,
            )
        )
    cranes, chain, missing = builder.chained(cranes, note)
    return DesignLoads(cranes=tuple(cranes), tilt=tilt, tilt_note=note, chain=chain, missing=missing)


def free_three(points):
    """The three lugs spanning the largest area in plan, left free in the ``rigid`` model.

    Parameters
    ----------
    points : numpy.ndarray, shape (n, 3)  [m]
        Lug positions, z-up body frame.

    Returns
    -------
    tuple of 3 int
        Indices into ``points``; the first of equal areas.
    """
    best, area = None, -1.0
    for trio in itertools.combinations(range(len(points)), 3):
        a, b, c = points[list(trio), :2]
        value = abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        if value > area:
            best, area = trio, value
    return best


def strength_set_json(s, stats, in_file_frame):
    """A strength search's set in ``plan --json`` after its lugs or hooks: the peaks of |M| and
    |Q| / allowable (each with its state, the CG offset in the file's frame via
    ``in_file_frame``), the spreads, the objective and the search's stats."""

    def peak(pk):
        state = dict(s.states[pk.state])
        state["cog_offset"] = list(in_file_frame(state["cog_offset"]))
        return {"value": pk.value, "ratio": pk.ratio, "x": pk.x, "state": state}

    return {
        "max_bending_moment": peak(s.bending),
        "max_shear_force": peak(s.shear),
        "spread": s.spread,
        "worst_spread": s.worst_spread,
        "objective_value": s.value,
        "tension_range": list(s.tension_range),
        "search": {
            "method": stats.method,
            "lower_bound": stats.lower_bound,
            "gap": stats.gap,
            "relative_gap": stats.relative_gap,
            "stopped": stats.stopped,
            "certified": stats.certified,
            "seconds": stats.seconds,
            "mip_solves": stats.rounds,
            "sets_evaluated": stats.evaluated,
        },
    }


def plan_strength(problem, top=None, context=None, wrap=None):
    """Plan for the hull girder (``objective`` bending / shear / strength).

    Parameters
    ----------
    problem : PlanProblem
    top : int, optional   not used: the search gives the best set, not a ranking
    context : StrengthContext, optional   the problem's (default: single ropes); with slings
        the hooks' (:mod:`liftplan.planner.plans.strength_slings`)
    wrap : callable, optional   ``wrap(StrengthPlan) -> plan``: the plan returned (and kept
        on Ctrl-C) made from the strength plan (default: the StrengthPlan itself)

    Returns
    -------
    StrengthPlan, or what ``wrap`` makes of it

    Raises
    ------
    Interrupted
        Ctrl-C: ``plan`` the best set so far (without the spread-optimal partner when the
        strength search was stopped; with the partner's best so far when it was), or None.
    """
    del top
    started = time.perf_counter()
    context = context or StrengthContext(problem)
    wrap = wrap or (lambda plan: plan)
    # a time limit covers both searches: the plan's gets 80 % of it, the spread-optimal
    # partner what is left (at least the other 20 %)
    total = problem.time_limit
    main_limit = None if total is None else MAIN_SHARE * total
    try:
        chosen, stats = search_strength(problem, objective_weights(problem), context, time_limit=main_limit)
    except StrengthInterrupted as stop:  # the best set so far; no spread-optimal partner searched
        plan = None
        if stop.best is not None:
            plan = wrap(StrengthPlan(problem, stop.best, stop.stats, spread_plan=None, spread_stats=None))
        raise Interrupted([], stop.stats, plan=plan, phase="strength search") from None
    limit = PARTNER_TIME if total is None else min(PARTNER_TIME, total - (time.perf_counter() - started))
    try:
        partner, partner_stats = search_strength(problem, SPREAD_WEIGHTS, context, time_limit=limit)
    except StrengthInterrupted as stop:  # the plan is complete; its partner as far as it got
        partial = None if stop.best is None else stop.stats
        plan = wrap(StrengthPlan(problem, chosen, stats, spread_plan=stop.best, spread_stats=partial))
        phase = "spread-optimal partner search"  # the plan's own search had finished
        raise Interrupted([], stats, plan=plan, phase=phase, finished=True) from None
    # the spread plan's own peaks are reported in the same terms: evaluate it on the
    # strength weights with its tensions as found (its value under the strength objective)
    return wrap(
        StrengthPlan(
            problem=problem, chosen=chosen, stats=stats, spread_plan=partner, spread_stats=partner_stats
        )
    )
