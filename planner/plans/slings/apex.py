"""Three or more cranes on slings: each hook a lift point of the held-preload search.

The held-preload search (:mod:`liftplan.planner.search`) plans a vertical hoist line above each
lift point. A sling's hook is such a point:

* a 3-leg sling of given leg lengths fixes its apex to the body (trilateration), and so does a
  4-leg sling whose legs all reach one apex as made (:mod:`.geometry`): a **body-fixed** point;
* a 2-leg sling, and a spreader bar that spans its pair (bottom legs parallel and vertical),
  swing freely about the lug pair: under the vertical hoist line the hook hangs in the vertical
  plane through the pair whatever the body's attitude (hook = A' + c e_z + s u + h n). That is
  a **hinged** lift point, which the one casadi model poses exactly
  (:class:`~liftplan.model.statics.model.HingedRopeModel`); the derived problem carries each rig's
  hinge (``PlanProblem.hinges``) and the search uses the hinged model throughout.

So:

1. every rig the slings can take (:func:`.rigs.crane_rigs`) becomes a candidate lift point at
   its hook at level (named ``LUG+LUG+...``);
2. a derived :class:`PlanProblem` on those hooks, the same cranes without slings (each hoist
   rope now ends at its hook; reach and chart SWL at the hook's radius; a spreader bar's weight
   as rigging on its hook), is searched by the public
   :func:`~liftplan.planner.search.methods.search` (sets x crane assignments, exact, certified
   gap);
3. sets whose slings would **share a lug** are dropped from the ranking: the search is asked for
   a longer ranking (x 4 each round) until ``top`` sets with disjoint slings are found or the
   ranking runs out. The search's ranking is exact to its length, so the first disjoint set in
   it is the best disjoint set; its certified lower bound holds over all sets, so also over the
   disjoint ones;
4. mapped back: which crane takes which lugs, hook loads (a bar's weight added), each leg's
   tension (each sling's statics under the hook load along the world vertical, the hook where
   the rig puts it at each attitude, over the tolerance box and the CG envelope), sling angles
   and the rules' lug design loads.

All slings must be the same (leg count, length, spreader): any crane may take any rig. A
spreader on three cranes or more takes only pairs it spans (lug spacing = bar length to 1 mm):
a bar of another length is a trapezoid linkage whose sway changes with the tilt, which the held
model does not pose; those pairs are counted as ruled out (two cranes plan any pair).
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import InvalidScene, PlanInfeasible
from liftplan.model.frames import rotation_matrix
from liftplan.planner.plans.breakout import breakout_case
from liftplan.planner.plans.held import Plan
from liftplan.planner.plans.slings.geometry import hinge_rows, hinged_hooks, leg_split, parallel_spreader_legs
from liftplan.planner.plans.slings.lift import SlingLift, hook_tolerances, rules_with_bars
from liftplan.planner.plans.slings.rigs import crane_rigs
from liftplan.planner.problem.definition import Candidate
from liftplan.planner.search.evaluator import Interrupted
from liftplan.planner.search.methods import search
from liftplan.planner.search.scenarios import LugSet, Scenario

#: Heel x trim points per axis of the grid the leg tensions are taken over (with the CG vertices).
LEG_GRID = 9


def apex_problem(problem):
    """The derived problem whose candidates are the slings' hooks.

    Returns
    -------
    derived : PlanProblem
        With ``hinges`` when the slings hinge about their pairs (2 legs, spreader bars).
    rigs : Rigs
        Candidate j of ``derived`` is rig j (its lugs ``rigs.lugs[j]``).
    """

    fleet = problem.fleet
    first = fleet[0].sling
    for crane in fleet:
        sling = crane.sling
        if (sling.legs, sling.length, sling.spreader) != (first.legs, first.length, first.spreader):
            bar = "" if first.spreader is None else " and spreader"
            raise InvalidScene(
                f"cranes[{crane.name}].sling = {{ legs = {sling.legs}, length = {sling.length:g} }}: "
                f"expected the same legs{bar} and length on every crane ({first.legs} legs of "
                f"{first.length:g} m on {fleet[0].name}); any crane may take any rig"
            )
    hinged = not first.body_fixed
    rigs = crane_rigs(problem, fleet[0], problem.body.weight / len(fleet), parallel=hinged)
    what = "spreader" if first.spreader is not None else f"{first.legs}-leg sling"
    if len(rigs) < len(fleet):
        causes = "; ".join(f"{n} {text}" for text, n in rigs.ruled_out.items())
        raise PlanInfeasible(
            f"{len(rigs)} {what} rigs among {len(problem.candidates)} "
            f"candidates for {len(fleet)} cranes "
            f"({causes or 'no tuples on adjacent groups'})"
        )
    names = problem.names
    candidates = tuple(
        Candidate(name="+".join(names[i] for i in lugs), at=tuple(map(float, hook)))
        for lugs, hook in zip(rigs.lugs, rigs.hook)
    )
    bare = tuple(dataclasses.replace(c, sling=None) for c in fleet)
    hinges = ()
    if hinged:
        bar = first.spreader
        hinges = tuple(
            map(
                tuple,
                hinge_rows(
                    problem.points[rigs.lugs[:, 0]],
                    problem.points[rigs.lugs[:, 1]],
                    0.0 if bar is None else first.length,
                    0.0 if bar is None else bar.weight,
                ),
            )
        )
    try:
        derived = dataclasses.replace(
            problem, candidates=candidates, fleet=bare, hinges=hinges, rules=rules_with_bars(problem)
        )
    except InvalidScene as err:
        raise PlanInfeasible(f"the slings' {len(rigs)} hooks as lift points: {err}") from None
    return derived, rigs


def plan_apex_slings(problem, top=None):
    """Plan three or more cranes on 3- or 4-leg slings (see the module docstring).

    Parameters
    ----------
    problem : PlanProblem
    top : int, optional

    Returns
    -------
    ApexSlingPlan

    Raises
    ------
    PlanInfeasible
    Interrupted
        Ctrl-C: ``plan`` the best sets with disjoint slings ranked so far (None when none).
    """

    top = top or problem.top
    derived, rigs = apex_problem(problem)
    started = time.perf_counter()
    tilt = np.zeros(2)  # heel, trim the hook errors add to the box [deg]
    for _ in range(HOOK_ROUNDS):
        widened = _widened(problem, derived, tilt, started)
        plan = _ranked(problem, widened, rigs, top, tuple(tilt))
        need = np.asarray(plan.hook_need)
        if np.all(need <= tilt + 1e-9):
            return plan
        tilt = np.maximum(tilt, need)
    raise PlanInfeasible(
        f"the box widened by the hook errors' tilt did not settle in {HOOK_ROUNDS} searches (heel "
        f"+{tilt[0]:.2f} deg, trim +{tilt[1]:.2f} deg): each best set's hooks tilt the body more; "
        "expected a smaller hook_tolerance"
    )


#: Searches at most, each on the box widened by the previous best set's hook-error tilt.
HOOK_ROUNDS = 4


def hook_error_tilts(hooks, tolerance):
    """The largest heel and trim the crew's hook errors add when three hooks hold the body  [deg].

    Three hooks fix the body: hook errors e_i (|e_i| <= delta_i) tilt it by the plane through
    them, e_i = a + s_x x_i + s_y y_i, so the largest |s_y| (heel) and |s_x| (trim) are the rows
    of that 3 x 3 system's inverse, in absolute value, times the tolerances. More hooks share the
    body's weight by their ropes' stretch: their errors are the held search's hook gains.

    Parameters
    ----------
    hooks : (n, 3)  [m]
        The hooks at level, body frame.
    tolerance : (n,)  [m]
        Each hook's height tolerance.

    Returns
    -------
    numpy.ndarray, shape (2,)  [deg]
        (heel, trim); zeros for other than three hooks or no tolerance; 90 where the hooks
        are (nearly) in one line.
    """
    tolerance = np.asarray(tolerance, dtype=float)
    if len(hooks) != 3 or not np.any(tolerance > 0):
        return np.zeros(2)
    rows = np.column_stack([np.ones(3), np.asarray(hooks, dtype=float)[:, :2]])
    try:
        inverse = np.linalg.inv(rows)
    except np.linalg.LinAlgError:
        return np.full(2, 90.0)
    slope_x, slope_y = np.abs(inverse[1:]) @ tolerance
    return np.degrees(np.arctan([slope_y, slope_x]))


def _widened(problem, derived, tilt, started):
    """The derived problem with its box widened by ``tilt`` (heel, trim) [deg] and what is left
    of ``plan.time_limit`` (each search of :func:`plan_apex_slings` shares it)."""
    if not np.any(tilt):
        return derived
    heel, trim = problem.heel_tolerance + tilt[0], problem.trim_tolerance + tilt[1]
    if max(heel, trim) > 90.0:
        raise PlanInfeasible(
            f"the hook errors tilt the body beyond 90 deg (heel +-{heel:.1f}, trim +-{trim:.1f} deg): "
            "the best set's hooks (nearly) in one line; expected a smaller hook_tolerance"
        )
    left = (
        None
        if problem.time_limit is None
        else max(problem.time_limit - (time.perf_counter() - started), 1e-3)
    )
    return dataclasses.replace(derived, heel_tolerance=heel, trim_tolerance=trim, time_limit=left)


def _ranked(problem, derived, rigs, top, tilt):
    """The held search on ``derived``, sets sharing a lug dropped (the module docstring, step 3)."""
    ask, shared = max(top, 10), 0
    while True:
        try:
            ranking, stats = search(derived, ask)
        except Interrupted as stop:  # the best disjoint sets ranked so far, if any
            keep = [r for r in stop.ranking if _disjoint(rigs, r.indices)]
            if keep:
                inner = Plan(problem=derived, ranking=keep[:top], stats=stop.stats)
                ruled_out = {**rigs.ruled_out, "sets sharing a lug (dropped from the ranking)": shared}
                stop.plan = ApexSlingPlan(
                    problem=problem, inner=inner, rigs=rigs, ruled_out=ruled_out, hook_tilt=tilt
                )
            stop.phase = f"sling plan: {stop.phase}"
            raise
        keep = [r for r in ranking if _disjoint(rigs, r.indices)]
        shared = len(ranking) - len(keep)
        if len(keep) >= top or len(ranking) < ask or ask >= stats.rows:
            break
        ask *= 4
    if not keep:
        raise PlanInfeasible(
            f"every feasible set of apexes shares a lug between two slings ({len(ranking)} sets ranked)"
        )
    if derived.search == "mip" and not _disjoint(rigs, ranking[0].indices):
        # the MIP's ranking is not exact to its length: its next disjoint set is not proved best
        raise PlanInfeasible(
            'search = "mip" proved a set of apexes whose slings share a lug, and its ranking does not '
            'prove the best set without one; expected search = "exact"'
        )
    inner = Plan(problem=derived, ranking=keep[:top], stats=stats)
    ruled_out = {**rigs.ruled_out, "sets sharing a lug (dropped from the ranking)": shared}
    return ApexSlingPlan(problem=problem, inner=inner, rigs=rigs, ruled_out=ruled_out, hook_tilt=tilt)


def _disjoint(rigs, indices):
    lugs = np.concatenate([rigs.lugs[i] for i in indices])
    return len(np.unique(lugs)) == len(lugs)


@dataclass(frozen=True)
class ApexSlingPlan(SlingLift):
    """Three or more cranes on slings (3/4-leg apexes, or 2-leg slings / spreaders hinged
    about their pairs).

    Parameters
    ----------
    problem : PlanProblem
        As the user wrote it (candidates are lugs).
    inner : Plan
        The held-preload plan on the apexes (``inner.problem`` is the derived problem).
    rigs : Rigs
        Rig j is the derived problem's candidate j.
    ruled_out : dict of str to int
    lengths : LengthSearch or None
        How the hoist ropes' lengths were chosen (:mod:`liftplan.planner.plans.lengths`); None
        when every length was given. With it, ``problem`` is the problem at the chosen lengths.
    hook_tilt : tuple of 2 float  [deg]
        The heel and trim the search's box (``inner.problem``) was widened by for the hook
        errors (:func:`hook_error_tilts`; at least :attr:`hook_need`).
    """

    problem: object
    inner: object
    rigs: object
    ruled_out: dict
    lengths: object = None
    hook_tilt: tuple = (0.0, 0.0)

    @property
    def hook_need(self):
        """(heel, trim) the chosen hooks' errors tilt the body by  [deg] (:func:`hook_error_tilts`)."""
        return hook_error_tilts(self.hooks, hook_tolerances(self.problem))

    @property
    def hook_tilt_text(self):
        """What the crew's hook errors do to the plan, one sentence (console and report)."""
        tolerance = hook_tolerances(self.problem)
        if not np.any(tolerance > 0):
            return "hook errors: none (hook tolerance 0 m), no tilt added to the box"
        each = ", ".join(f"{n} +-{d:g} m" for n, d in zip(self.crane_names, tolerance))
        if len(self.problem.fleet) != 3:
            return (
                f"hook errors ({each}): the held search's hook gains (the ropes' stretch shares "
                "them); their tilt is not added to the box"
            )
        heel, trim = self.hook_need
        box = self.inner.problem
        return (
            f"hook errors ({each}) tilt the body up to heel {heel:.2f}, trim {trim:.2f} deg more "
            f"(the plane through the three hooks' errors): every set was searched, and every state "
            f"taken, within heel +-{box.heel_tolerance:.2f}, trim +-{box.trim_tolerance:.2f} deg"
        )

    def hook_tilt_json(self):
        """The hook errors' tilt and the box taken, for the plan JSON's ``hooks``  [deg]."""
        heel, trim = self.hook_need
        box = self.inner.problem
        return {
            "tilt": {"heel": float(heel), "trim": float(trim)},
            "box_taken": {"heel": box.heel_tolerance, "trim": box.trim_tolerance},
        }

    # -- the breakout case and the rope lengths ------------------------------------------------
    @cached_property
    def breakout(self):
        """Each crane's hook at breakout, fleet order: the held model on the chosen hooks (the
        derived problem's, hinged where the slings hinge), the body's share on each hook; None
        without a breakout case."""
        case = self._design.breakout
        return None if case is None else case.ordered(self._order)

    @cached_property
    def ranked_breakouts(self):
        derived, names = self.inner.problem, self.problem.names
        if derived.breakout is None:
            return []
        return [
            (
                ["+".join(names[i] for i in self.rigs.lugs[j]) for j in r.indices],
                breakout_case(derived, LugSet(derived, r.indices, r.cranes), r.preload),
            )
            for r in self.ranking
        ]

    def level_legs(self, c, load):
        """Crane c's lug legs under a vertical hook load ``load`` [t] at level  [t]."""
        return self.sling_legs(c, load, rotation_matrix(0.0, 0.0, self.problem.yaw))[0]

    def with_lengths(self, search, stats=None):
        inner = self.inner if stats is None else dataclasses.replace(self.inner, stats=stats)
        return dataclasses.replace(self, inner=inner, lengths=search)

    @property
    def length_summary(self):
        """(worst value, certified lower bound, lug names, rows evaluated) for the rope-length
        search's trials."""
        chosen, names = self.inner.chosen, self.problem.names
        lugs = tuple(names[i] for g in self.groups for i in g)
        return float(chosen.worst_value), float(self.stats.lower_bound), lugs, int(self.stats.evaluated)

    @property
    def lift_text(self):
        return {
            "fixed": "slings with body-fixed apexes",
            "pair": "2-leg slings hinged about their lug pairs",
            "spreader": "spreader bars hinged about their lug pairs",
        }[self.rigs.kind]

    @property
    def lift_points_text(self):
        """What the search's lift points are, for the console and the report."""
        return (
            "sling apexes (body-fixed lift points)"
            if not self.hinged
            else "sling hooks (lift points hinged about their lug pairs)"
        )

    @property
    def method_text(self):
        """How the plan's hook and leg loads were found, one sentence for the report."""
        if not self.hinged:
            return (
                "Each 3/4-leg sling fixes its hook to the body (an apex); the hooks hold the level "
                "preload over the tolerance box (the held-preload search on the apexes), and the "
                "legs share each hook load by the apex's statics; checked on the rigging model with "
                "free hooks and elastic legs."
            )
        rig = (
            "2-leg sling"
            if self.rigs.kind == "pair"
            else "spreader bar (spanning its pair, bottom legs vertical)"
        )
        return (
            f"Each {rig} swings about its lug pair, so its hook hangs in the vertical plane "
            "through the pair at every heel and trim; the held-preload search poses the hooks so "
            "(the hinged lift points of the one casadi model), the hooks hold the level preload "
            "over the tolerance box, and each sling's legs carry its hook load by its statics at "
            "each attitude; checked on the rigging model with free hooks and elastic legs."
        )

    @property
    def hinged(self):
        """True when the hooks swing about their lug pairs (2-leg slings, spreader bars)."""
        return self.rigs.kind != "fixed"

    @property
    def objective(self):
        return self.problem.objective

    @property
    def stats(self):
        return self.inner.stats

    @property
    def ranking(self):
        return self.inner.ranking

    @cached_property
    def _order(self):
        """Position in the chosen set of each fleet crane."""
        cranes = list(self.inner.chosen.cranes)
        return [cranes.index(j) for j in range(len(self.problem.fleet))]

    def _per_crane(self, values):
        return np.asarray(values, dtype=float)[self._order]

    @property
    def groups(self):
        chosen = self.inner.chosen
        return tuple(tuple(int(v) for v in self.rigs.lugs[chosen.indices[k]]) for k in self._order)

    @property
    def hooks(self):
        return self.rigs.hook[[self.inner.chosen.indices[k] for k in self._order]]

    @property
    def leg_angles(self):
        return tuple(self.rigs.angles[self.inner.chosen.indices[k]] for k in self._order)

    @property
    def hook_radius(self):
        return self._per_crane(self.inner.chosen.radius)

    @property
    def hook_swl(self):
        return self._per_crane(self.inner.chosen.swl)

    @property
    def hook_nominal(self):
        """Hook load at level, nominal CG: the body's share and a spreader bar  [t]."""
        return self._per_crane(self.inner.chosen.preload) + self.bar_weights

    @cached_property
    def _design(self):
        return self.inner.design_loads

    @property
    def hook_worst(self):
        """Largest hook load over the box, the CG envelope and the hook errors  [t]."""
        return self._per_crane([c.worst for c in self._design.cranes]) + self.bar_weights

    @property
    def tilt_shares(self):
        return [
            None if c.tilt is None else float(c.tilt.load)
            for c in (self._design.cranes[k] for k in self._order)
        ]

    @property
    def tilt_note(self):
        missing = self._design.missing
        if missing is not None and any(t is None for t in self.tilt_shares):
            return f"rules' tilt not evaluated: {missing}"
        return self._design.tilt_note

    @property
    def hook_skews(self):
        return [self._design.cranes[k].skew for k in self._order]

    @property
    def top_legs(self):
        """A spreader's two top legs at level, per crane  [t] (None without a bar)."""
        return self._legs[3]

    @property
    def top_angles(self):
        """A spreader's two top legs' angles from the horizontal at level  [deg]."""
        if self.rigs.top_angles is None:
            return (None,) * len(self.problem.fleet)
        return tuple(self.rigs.top_angles[self.inner.chosen.indices[k]] for k in self._order)

    @cached_property
    def _legs(self):
        """(level legs, worst legs, least leg, level top legs) per crane, from the hook loads on
        the box grid: each sling's statics under its hook load along the world vertical, the
        hook where the rig puts it at that attitude."""
        problem = self.problem
        hh, tt = self._box_grid
        offsets = problem.cog_envelope.offsets()
        shares = np.vstack([self.inner.tensions_at(hh, tt, tuple(o)) for o in offsets])[:, self._order]
        rots = [rotation_matrix(h, t, problem.yaw) for h, t in zip(hh, tt)] * len(offsets)
        level_rot = rotation_matrix(0.0, 0.0, problem.yaw)
        level, worst, least, tops = [], [], [], []
        for c in range(len(problem.fleet)):
            hooks = shares[:, c] + self.bar_weights[c]

            def split(load, rot, c=c):
                return self.sling_legs(c, load, rot)

            nominal, top = split(self.hook_nominal[c], level_rot)
            grid = np.array([split(load, rot)[0] for load, rot in zip(hooks, rots)])
            level.append(nominal)
            tops.append(top)
            # the hook errors raise the hook's worst above the grid's: the legs in proportion
            ratio = max(1.0, self.hook_worst[c] / max(hooks.max(), 1e-12))
            worst.append(grid.max(axis=0) * ratio)
            least.append(float(grid.min()))
        return tuple(level), tuple(worst), least, tuple(tops)

    @cached_property
    def _box_grid(self):
        """Heel and trim [deg] of the :data:`LEG_GRID` x :data:`LEG_GRID` grid over the
        tolerance box, flattened (heel major)."""
        box = self.inner.problem  # widened by the hook errors' tilt (three cranes)
        heel = np.linspace(-box.heel_tolerance, box.heel_tolerance, LEG_GRID)
        trim = np.linspace(-box.trim_tolerance, box.trim_tolerance, LEG_GRID)
        return tuple(v.ravel() for v in np.meshgrid(heel, trim, indexing="ij"))

    @property
    def held_poses(self):
        """(CG offset [m], boom shifts [m]) of every state the worst legs are taken over: each
        vertex of the CG envelope at each attitude of the box grid, the hooks moved as the
        held-preload search moves them to bring the body there (the level preload held,
        :meth:`~liftplan.planner.search.scenarios.LugSet.hook_shifts`). The rigging model's
        free hooks and elastic legs hang the body near, not exactly at, that attitude: each
        :class:`~.lift.HungState` carries the solved heel and trim."""
        inner = self.inner
        offsets = [tuple(float(v) for v in o) for o in self.problem.cog_envelope.offsets()]
        scenarios = [Scenario(float(h), float(t), o) for o in offsets for h, t in zip(*self._box_grid)]
        shifts = inner.lugset.hook_shifts(np.asarray(inner.chosen.preload, dtype=float), scenarios)
        return [(s.cog_offset, row) for s, row in zip(scenarios, shifts[:, self._order])]

    @property
    def girder_over(self):
        """The states of the girder's worst, in words."""
        errors = (
            "; hook height errors not included"
            if len(self.problem.fleet) > 3 and self.inner.lugset.hook_uncertain
            else ""
        )
        return f"over the tolerance box and the CG envelope (rigging model){errors}"

    def sling_legs(self, c, load, rot):
        """Crane c's lug legs (and a spreader's top legs, else None) under a vertical hook load
        ``load`` [t] (the body's share and a bar) with the body at attitude ``rot`` (3 x 3)  [t].
        """
        crane = self.problem.fleet[c]
        lugs = self.problem.points[list(self.groups[c])]
        if not self.hinged:  # body-fixed apex: the load along the vertical seen from the body
            stiff = np.full(len(lugs), crane.sling.EA / crane.sling.length)
            return leg_split(self.hooks[c], lugs, load * (rot.T @ [0.0, 0.0, 1.0]), stiff), None
        j = self.inner.chosen.indices[self._order[c]]
        hook = hinged_hooks(self.inner.problem.hinge_rows[[j]], self.rigs.hook[[j]], rot)[0]
        posed = lugs @ rot.T
        bar = crane.sling.spreader
        if bar is None:
            return leg_split(hook, posed, (0.0, 0.0, load)), None
        return parallel_spreader_legs(hook, posed, crane.sling.length, load, bar.weight)

    @property
    def legs_nominal(self):
        return self._legs[0]

    @property
    def legs_worst(self):
        return self._legs[1]

    @property
    def worst_utilisation_spread(self):
        return float(self.inner.worst_utilisation_spread)

    @cached_property
    def checks(self):
        """The rules' chain per crane and lug, sling angles, every leg taut over the box, and
        agreement with the rigging model (1 % of W: the legs' stretch moves the apexes)."""
        out = self._lift_checks()
        for c, name in enumerate(self.crane_names):
            out.append(
                Check.lower(
                    "leg_taut",
                    name,
                    self._legs[2][c],
                    0.0,
                    "t",
                    note="least leg tension over the box and the CG envelope",
                )
            )
        return out

    def to_json(self):
        stats = self.stats
        return {
            **self._lift_json(),
            "lower_bound": stats.lower_bound,
            "gap": stats.gap,
            "search": {
                "method": stats.method,
                "stopped": stats.stopped,
                "rows": stats.rows,
                "evaluated": stats.evaluated,
                "apexes": len(self.rigs),
            },
            "ranking": [
                {
                    "lugs": [self.problem.names[i] for j in r.indices for i in self.rigs.lugs[j]],
                    "cranes": list(r.crane_names),
                    "worst": r.worst_value,
                }
                for r in self.ranking
            ],
            "ruled_out": self.ruled_out,
            "checks": [c.to_json() for c in self.checks],
        }
