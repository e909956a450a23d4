"""The search keeps crane vessels within their limits (issue 27, the planner side).

A set whose worst states (the tolerance box for every CG vertex, each with the hook errors at
their worst), the levelling ballast set for its level tensions, heel a vessel beyond its
``max_heel`` is ruled out with its cause, and the plan is the best set that keeps every vessel
within its limits. Shown on the tanker's floating fleet cut to 10 candidates, one barge made
tender (GM_T 2.5 m, heel limit 0.8 deg): the best set without the limit heels that barge
0.88 deg; every set and crane assignment is evaluated here by brute force and its heel computed
in this file from the vessel's particulars.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model.errors import PlanInfeasible
from liftplan.model.scene.vessel import Vessel
from liftplan.planner.output.console.summary import summary
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem
from liftplan.planner.problem.vessels import VesselWorst, series_problem, vessel_worst
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.scenarios import LugSet
from liftplan.planner.search.screen import FEASIBLE, REASONS, VESSEL_HEEL, screen, set_rows

KEEP = ("BH1-P", "BH1-S", "BH3-P", "BH3-S", "BH5-P", "BH5-S", "BH7-P", "BH7-S", "BH8-P", "BH8-S")
TENDER, LIMIT = "Crane D", 0.8


def _problem(max_heel, keep=KEEP):
    """The tanker's floating fleet on the candidates ``keep``, Crane D's barge tender with
    ``max_heel`` (the other vessels without a heel limit)."""
    given = load_problem(EXAMPLES / "tanker_floating_fleet.toml")
    fleet = []
    for crane in given.fleet:
        vessel = dataclasses.replace(crane.vessel, max_heel=None)
        if crane.name == TENDER:
            vessel = dataclasses.replace(vessel, gm_t=2.5, max_heel=max_heel)
        fleet.append(dataclasses.replace(crane, vessel=vessel))
    candidates = tuple(c for c in given.candidates if c.name in keep)
    return dataclasses.replace(given, candidates=candidates, fleet=tuple(fleet))


def _heel(vessel, point, preload, low, high):
    """The vessel's largest |heel| over a rope's tensions [deg], levelled at ``preload``:
    (T - T0) y_t / (displacement GM_T), y_t the point's offset to starboard of the flotation
    centre in the vessel's axes (heading from +x towards +y; starboard is to the right)."""
    h = math.radians(vessel.heading)
    dx, dy = point[0] - vessel.flotation[0], point[1] - vessel.flotation[1]
    starboard = dx * math.sin(h) - dy * math.cos(h)
    swing = max(abs(high - preload), abs(low - preload))
    return math.degrees(swing * abs(starboard) / (vessel.displacement * vessel.gm_t))


def _brute_force(problem):
    """Every (set, assignment) row the search has (reach and boom clearance), each evaluated with
    its vessels in series at its own lugs and no heel limit: (value, nominal, indices, cranes,
    the tender barge's worst heel [deg]). The rows screening proves infeasible at level (the
    CG outside the lugs, a level tension beyond the SWL, ...) are left out: they have no value."""
    free = _problem(None)
    sets, cranes, _, _ = set_rows(free)
    level = screen(free, sets, cranes).reason
    sets, cranes = sets[level == FEASIBLE], cranes[level == FEASIBLE]
    evaluator = SetEvaluator(free)  # each row with its vessels in series at its own lugs
    rows = []
    for indices, assignment in zip(sets, cranes):
        indices, assignment = tuple(map(int, indices)), tuple(map(int, assignment))
        exact = series_problem(free, indices, assignment)
        try:
            result = evaluator.evaluate(indices, assignment)
        except SetInfeasible:
            continue
        lugset = LugSet(exact, indices, assignment)
        tensions, gain = lugset.tensions_and_gain(result.preload, evaluator.dense)
        margin = np.einsum("mij,j->mi", np.abs(gain), lugset.hook_tolerance)
        low, high = (tensions - margin).min(axis=0), (tensions + margin).max(axis=0)
        k = [exact.fleet[j].name for j in assignment].index(TENDER)
        vessel = exact.fleet[assignment[k]].vessel
        heel = _heel(vessel, exact.plan_points[indices[k]], result.preload[k], low[k], high[k])
        rows.append((result.worst_value, result.nominal_value, indices, assignment, heel))
    return sorted(rows)


@pytest.fixture(scope="module")
def rows():
    return _brute_force(_problem(LIMIT))


def test_the_plan_is_the_best_set_within_the_heel_limit_by_brute_force(rows):
    """Without the limit the best set heels the barge beyond 0.8 deg; with it the plan is the
    brute force's best row that keeps it (value to 1e-9), the sets that break it counted under
    their cause, and the plan's heel check passes."""
    free_best = rows[0]
    assert free_best[4] > LIMIT  # the unconstrained optimum breaks the limit
    within = [r for r in rows if r[4] <= LIMIT]
    assert within and within[0] is not free_best
    broken = len(rows) - len(within)
    result = plan(_problem(LIMIT))
    assert (result.chosen.indices, result.chosen.cranes) == within[0][2:4]
    assert result.chosen.worst_value == pytest.approx(within[0][0], rel=1e-9)
    assert result.chosen.worst_value > free_best[0]
    ruled = result.stats.infeasible[REASONS[VESSEL_HEEL]]
    assert 1 <= ruled <= broken  # the rows the search reached, never more than break it
    tender = next(v for v in result.vessels if v.crane == TENDER)
    assert tender.worst_heel == pytest.approx(within[0][4], rel=1e-9)
    heel = [c for c in result.checks if c.name == "vessel_heel"]
    assert [(c.subject, c.ok) for c in heel] == [(TENDER, True)]
    assert result.to_json()["search"]["infeasible"][REASONS[VESSEL_HEEL]] == ruled
    assert "ruled out by a vessel's limit: " in summary(result)
    # without the limit the plan is the unconstrained optimum, its heel check absent
    free = plan(_problem(None))
    assert (free.chosen.indices, free.chosen.cranes) == free_best[2:4]
    assert REASONS[VESSEL_HEEL] not in free.stats.infeasible


def test_no_set_within_the_limit_is_refused_with_its_cause(rows):
    """A heel limit below every set's heel: no plan, the message counts the heel cause (on 6 of
    the candidates, rows among the brute force's)."""
    tight = min(r[4] for r in rows) * 0.5
    with pytest.raises(PlanInfeasible, match=r"sets: a crane vessel heels beyond its max_heel"):
        plan(_problem(tight, ("BH1-P", "BH1-S", "BH3-P", "BH3-S", "BH7-P", "BH7-S")))


def test_each_limit_rules_out_with_its_cause():
    """:meth:`VesselWorst.breach` names the first limit broken (heel, trim, freeboard) and
    keeps a limit met exactly; :func:`vessel_worst` at the rope's ends, levelled at T0."""
    limits = {"max_heel": 1.0, "max_trim": 0.5, "min_freeboard": 1.0}
    vessel = Vessel(5000.0, 2100.0, 25.0, 150.0, (0.0, 0.0), freeboard=2.5, beam=30.0, length=70.0, **limits)
    worst = vessel_worst(vessel, (20.0, 10.0), 300.0, (250.0, 380.0))
    heel = math.degrees(80.0 * 10.0 / (5000.0 * 25.0))
    trim = math.degrees(80.0 * 20.0 / (5000.0 * 150.0))
    assert (worst.heel, worst.trim) == pytest.approx((heel, trim), rel=1e-12)
    low = 2.5 - 250.0 / (1.025 * 2100.0) - 15.0 * 50.0 * 10.0 / 125000.0 - 35.0 * 50.0 * 20.0 / 750000.0
    high = 2.5 - 380.0 / (1.025 * 2100.0) - 15.0 * 80.0 * 10.0 / 125000.0 - 35.0 * 80.0 * 20.0 / 750000.0
    assert worst.freeboard == pytest.approx(min(low, high), rel=1e-12)
    assert worst.breach(vessel) is None
    assert VesselWorst(1.0, 0.5, 1.0).breach(vessel) is None  # limits met exactly
    assert VesselWorst(1.01, 0.6, 0.5).breach(vessel) == "heel"
    assert VesselWorst(0.9, 0.51, 0.5).breach(vessel) == "trim"
    assert VesselWorst(0.9, 0.4, 0.99).breach(vessel) == "freeboard"
