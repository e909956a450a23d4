"""Three or more cranes on 3- or 4-leg slings: each hook a body-fixed apex, planned by the search.

A 3-leg sling of given leg lengths fixes its apex to the body (trilateration), and so does a
4-leg sling whose legs all reach one apex as made (:mod:`.geometry`). With every leg taut the
crane then acts at a **body-fixed point**, exactly what the held-preload search
(:mod:`liftplan.planner.search`) plans: a vertical hoist line above each lift point. So:

1. every rig the slings can take (:func:`.rigs.crane_rigs`) becomes a candidate lift point at
   its apex (named ``LUG+LUG+LUG``);
2. a derived :class:`PlanProblem` on those apexes, the same cranes without slings (each hoist
   rope now ends at its apex; reach and chart SWL at the apex's radius), is searched by the
   public :func:`~liftplan.planner.search.branch.search` (sets x crane assignments, exact,
   certified gap);
3. sets whose slings would **share a lug** are dropped from the ranking: the search is asked for
   a longer ranking (x 4 each round) until ``top`` sets with disjoint slings are found or the
   ranking runs out. The search's ranking is exact to its length, so the first disjoint set in
   it is the best disjoint set; its certified lower bound holds over all sets, so also over the
   disjoint ones;
4. mapped back: which crane takes which k lugs, hook loads, each leg's tension (the apex's
   statics under the hook load along the world vertical seen from the tilted body, over the
   tolerance box and the CG envelope), sling angles and the rules' lug design loads.

All slings must have the same leg count and length (any crane may take any apex); 2-leg slings
and spreader bars hinge about their pair and are planned for two cranes only.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import InvalidScene, PlanInfeasible
from liftplan.model.frames import rotation_matrix
from liftplan.planner.slings.geometry import leg_split
from liftplan.planner.slings.lift import SlingLift
from liftplan.planner.slings.rigs import crane_rigs

#: Heel x trim points per axis of the grid the leg tensions are taken over (with the CG vertices).
LEG_GRID = 9


def apex_problem(problem):
    """The derived problem whose candidates are the slings' apexes.

    Returns
    -------
    derived : PlanProblem
    rigs : Rigs
        Candidate j of ``derived`` is rig j (its lugs ``rigs.lugs[j]``).
    """
    from liftplan.planner.problem.definition import Candidate

    fleet = problem.fleet
    first = fleet[0].sling
    for crane in fleet:
        sling = crane.sling
        if sling is None or not sling.body_fixed:
            raise InvalidScene(
                f"cranes[{crane.name}].sling: with {len(fleet)} cranes expected a 3- or 4-leg sling "
                "(no spreader) on every crane: a 2-leg sling or a spreader hinges about its lug pair, "
                "so its hook is not a body-fixed point the held-preload search can plan")
        if (sling.legs, sling.length) != (first.legs, first.length):
            raise InvalidScene(
                f"cranes[{crane.name}].sling = {{ legs = {sling.legs}, length = {sling.length:g} }}: "
                f"expected the same legs and length on every crane ({first.legs} legs of "
                f"{first.length:g} m on {fleet[0].name}); any crane may take any apex")
    rigs = crane_rigs(problem, fleet[0], problem.body.weight / len(fleet))
    if len(rigs) < len(fleet):
        causes = "; ".join(f"{n} {text}" for text, n in rigs.ruled_out.items())
        raise PlanInfeasible(f"{len(rigs)} {first.legs}-leg sling rigs among {len(problem.candidates)} "
                             f"candidates for {len(fleet)} cranes "
                             f"({causes or 'no tuples on adjacent groups'})")
    names = problem.names
    candidates = tuple(Candidate(name="+".join(names[i] for i in lugs), at=tuple(map(float, hook)))
                       for lugs, hook in zip(rigs.lugs, rigs.hook))
    bare = tuple(dataclasses.replace(c, sling=None) for c in fleet)
    try:
        derived = dataclasses.replace(problem, candidates=candidates, fleet=bare)
    except InvalidScene as err:
        raise PlanInfeasible(f"the slings' {len(rigs)} apexes as lift points: {err}") from None
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
    """
    from liftplan.planner.plan import Plan
    from liftplan.planner.search.branch import Interrupted, search

    top = top or problem.top
    derived, rigs = apex_problem(problem)
    ask, shared = max(top, 10), 0
    while True:
        try:
            ranking, stats = search(derived, ask)
        except Interrupted:
            raise
        keep = [r for r in ranking if _disjoint(rigs, r.indices)]
        shared = len(ranking) - len(keep)
        if len(keep) >= top or len(ranking) < ask or ask >= stats.rows:
            break
        ask *= 4
    if not keep:
        raise PlanInfeasible(f"every feasible set of apexes shares a lug between two slings "
                             f"({len(ranking)} sets ranked)")
    inner = Plan(problem=derived, ranking=keep[:top], stats=stats)
    ruled_out = {**rigs.ruled_out, "sets sharing a lug (dropped from the ranking)": shared}
    return ApexSlingPlan(problem=problem, inner=inner, rigs=rigs, ruled_out=ruled_out)


def _disjoint(rigs, indices):
    lugs = np.concatenate([rigs.lugs[i] for i in indices])
    return len(np.unique(lugs)) == len(lugs)


@dataclass(frozen=True)
class ApexSlingPlan(SlingLift):
    """Three or more cranes on 3- or 4-leg slings.

    Parameters
    ----------
    problem : PlanProblem
        As the user wrote it (candidates are lugs).
    inner : Plan
        The held-preload plan on the apexes (``inner.problem`` is the derived problem).
    rigs : Rigs
        Rig j is the derived problem's candidate j.
    ruled_out : dict of str to int
    """

    problem: object
    inner: object
    rigs: object
    ruled_out: dict

    lift_text = "slings with body-fixed apexes"

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
        return self._per_crane(self.inner.chosen.preload)

    @cached_property
    def _design(self):
        return self.inner.design_loads

    @property
    def hook_worst(self):
        """Largest hook load over the box, the CG envelope and the hook errors  [t]."""
        return self._per_crane([c.worst for c in self._design.cranes])

    @property
    def tilt_shares(self):
        return [None if c.tilt is None else float(c.tilt.load)
                for c in (self._design.cranes[k] for k in self._order)]

    @property
    def tilt_note(self):
        return self._design.tilt_note

    @property
    def hook_skews(self):
        return [self._design.cranes[k].skew for k in self._order]

    @property
    def top_legs(self):
        return (None,) * len(self.problem.fleet)

    @property
    def top_angles(self):
        return (None,) * len(self.problem.fleet)

    @cached_property
    def _legs(self):
        """(level legs, worst legs, least leg) per crane from the hook loads on the box grid."""
        problem = self.problem
        heel = np.linspace(-problem.heel_tolerance, problem.heel_tolerance, LEG_GRID)
        trim = np.linspace(-problem.trim_tolerance, problem.trim_tolerance, LEG_GRID)
        hh, tt = (v.ravel() for v in np.meshgrid(heel, trim, indexing="ij"))
        ups = np.array([rotation_matrix(h, t, problem.yaw).T @ [0.0, 0.0, 1.0] for h, t in zip(hh, tt)])
        hooks = np.vstack([self.inner.tensions_at(hh, tt, tuple(o))
                           for o in problem.cog_envelope.offsets()])[:, self._order]
        ups = np.tile(ups, (len(problem.cog_envelope.offsets()), 1))
        level, worst, least = [], [], []
        for c, crane in enumerate(problem.fleet):
            apex, lugs = self.hooks[c], problem.points[list(self.groups[c])]
            stiff = np.full(len(lugs), crane.sling.EA / crane.sling.length)
            level.append(leg_split(apex, lugs, (0.0, 0.0, self.hook_nominal[c]), stiff))
            grid = np.array([leg_split(apex, lugs, load * up, stiff)
                             for load, up in zip(hooks[:, c], ups)])
            # the hook errors raise the hook's worst above the grid's: the legs in proportion
            ratio = max(1.0, self.hook_worst[c] / max(hooks[:, c].max(), 1e-12))
            worst.append(grid.max(axis=0) * ratio)
            least.append(float(grid.min()))
        return tuple(level), tuple(worst), least

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
            out.append(Check.lower("leg_taut", name, self._legs[2][c], 0.0, "t",
                                   note="least leg tension over the box and the CG envelope"))
        return out

    def to_json(self):
        stats = self.stats
        return {
            **self._lift_json(),
            "lower_bound": stats.lower_bound,
            "gap": stats.gap,
            "search": {"stopped": stats.stopped, "rows": stats.rows, "evaluated": stats.evaluated,
                       "apexes": len(self.rigs)},
            "ranking": [{"lugs": [self.problem.names[i] for j in r.indices for i in self.rigs.lugs[j]],
                         "cranes": list(r.crane_names), "worst": r.worst_value}
                        for r in self.ranking],
            "ruled_out": self.ruled_out,
            "checks": [c.to_json() for c in self.checks],
        }
