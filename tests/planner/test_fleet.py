"""Crane fleets: unequal cranes at fixed positions with load charts, and which crane takes
which lug. The search must equal brute force over every lug set and every assignment."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers import EXAMPLES
from numpy.testing import assert_allclose
from support.fleet import brute_force, fleet, fleet_problem

from liftplan.model.errors import InvalidScene, PlanInfeasible
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem, loads_problem
from liftplan.planner.search.methods import search


# five cranes take 15-20 s an objective: the spread in the default run, the others with -m slow
@pytest.mark.parametrize(
    ("cranes", "objective"),
    [
        *((n, o) for n in (3, 4) for o in ("utilisation", "spread", "reserve")),
        (5, "spread"),
        pytest.param(5, "utilisation", marks=pytest.mark.slow),
        pytest.param(5, "reserve", marks=pytest.mark.slow),
    ],
)
def test_search_equals_brute_force_over_sets_and_assignments(cranes, objective):
    problem = fleet_problem(cranes, objective)
    every = brute_force(problem)
    brute = {k: v for k, v in every.items() if v is not None}
    ranking, stats = search(problem)
    best = min(brute.values())
    # brute force on a 7 x 7 grid per CG vertex is coarser than the search (21 x 21 and
    # zoom): the search's worst may exceed it a little, never fall below it. 1e-3 W in
    # tension, 1e-3 in utilisation (0.1 % of an SWL).
    tol = 1e-3 * problem.body.weight if objective == "spread" else 1e-3
    assert ranking[0].worst_value == pytest.approx(best, abs=tol)
    assert ranking[0].worst_value >= best - 1e-6
    winners = {k for k, v in brute.items() if v <= best + tol}
    assert (ranking[0].indices, ranking[0].cranes) in winners
    top = sorted(brute.values())[: len(ranking)]
    assert_allclose([r.worst_value for r in ranking], top, atol=tol)
    # the assignment matters in this fleet: some set is feasible with one assignment in reach
    # and infeasible, or worse, with another
    by_set = {}
    for (s, _), v in every.items():
        by_set.setdefault(s, []).append(np.inf if v is None else v)
    assert any(min(v) < np.inf and np.ptp(v) > 10 * tol for v in by_set.values())


@pytest.mark.parametrize("cranes", [3, 4, 5])
def test_no_crane_beyond_reach_and_no_overload_anywhere_in_the_box(cranes):
    problem = fleet_problem(cranes)
    result = plan(problem)
    for r in result.ranking:
        for radius, j in zip(r.radius, r.cranes):
            assert radius <= problem.fleet[j].reach
    # accepted plan: T / SWL <= 1 on a grid finer than the search's, every CG vertex
    heel, trim = np.meshgrid(np.linspace(-2, 2, 31), np.linspace(-2, 2, 31))
    swl = np.array(list(result.swl.values()))
    for offset in problem.cog_envelope.offsets():
        tensions = result.tensions_at(heel.ravel(), trim.ravel(), offset)
        # 1e-6: the search accepts within 1 kg of the SWL
        assert np.max(tensions / swl) <= 1.0 + 1e-6
        assert np.min(tensions) >= problem.min_tension - 1e-3


def test_unreachable_fleet_names_the_crane():
    # two cranes that both reach only C0: no assignment puts each on its own lug
    cranes = list(fleet(3))
    near = ((5.0, 500.0), (12.0, 400.0))
    cranes[1] = dataclasses.replace(cranes[1], position=(4.2, -8.0), load_chart=near)
    cranes[2] = dataclasses.replace(cranes[2], position=(4.2, -8.0), load_chart=near)
    problem = fleet_problem(3, fleet=tuple(cranes))
    with pytest.raises(PlanInfeasible, match=r"crane (Big fwd|Small aft) reaches 1 of 7"):
        plan(problem)


def test_over_chart_fleet_is_infeasible():
    weak = tuple(
        dataclasses.replace(c, load_chart=tuple((r, s / 4) for r, s in c.load_chart)) for c in fleet(4)
    )
    with pytest.raises(PlanInfeasible, match="more than the crane SWL|exceeds the crane SWL"):
        plan(fleet_problem(4, fleet=weak))


def test_crane_that_reaches_no_candidate():
    cranes = list(fleet(3))
    cranes[2] = dataclasses.replace(cranes[2], position=(200.0, 0.0))
    with pytest.raises(
        InvalidScene,
        match=r"cranes\[Small aft\]: reaches no candidate .*nearest "
        r"candidate C6 at radius 1[23]\d\.\d\d m",
    ):
        fleet_problem(3, fleet=tuple(cranes))


@pytest.mark.parametrize(
    "change, message",
    [
        ({"load_chart": ((20.0, 700.0), (20.0, 600.0))}, "radii .* expected strictly increasing"),
        ({"load_chart": ((20.0, 700.0), (30.0, 0.0))}, "SWL 0 t at radius 30 m: expected > 0"),
        # issue 29 item 13: a chart whose SWL rises with radius was accepted without a word
        (
            {"load_chart": ((20.0, 300.0), (30.0, 450.0))},
            "SWL rises from 300 t at 20 m to 450 t at 30 m; expected an SWL that never rises",
        ),
        ({"load_chart": (), "swl": None}, "expected exactly one of load_chart"),
        ({"swl": 300.0}, "expected exactly one of load_chart"),
        ({"EA": -1.0}, r"cranes\[Big aft\]\.EA = -1.0"),
    ],
)
def test_bad_crane_data(change, message):
    with pytest.raises(InvalidScene, match=message):
        dataclasses.replace(fleet(1)[0], **change)


def test_duplicate_names_and_too_few_candidates():
    cranes = list(fleet(3))
    cranes[1] = dataclasses.replace(cranes[1], name="Big aft")
    with pytest.raises(InvalidScene, match="duplicate"):
        fleet_problem(3, fleet=tuple(cranes))
    with pytest.raises(InvalidScene, match="at least as many candidates as cranes"):
        fleet_problem(3, candidates=fleet_problem(3).candidates[:2])


def test_reordering_the_fleet_gives_the_same_plan():
    problem = fleet_problem(4)
    reordered = dataclasses.replace(problem, fleet=tuple(reversed(problem.fleet)))
    first, second = plan(problem), plan(reordered)
    pairs = lambda p: sorted(zip(p.lugs.values(), p.cranes.values()))  # noqa: E731
    assert pairs(first) == pairs(second)
    # 1e-6 t: the same LP, the same scenarios up to crane order
    assert first.worst_spread == pytest.approx(second.worst_spread, abs=1e-6 * 904)


def test_fleet_file_reads_and_plans():
    problem = load_problem(EXAMPLES / "tanker_fleet.toml")
    assert problem.objective == "utilisation" and len(problem.crane_classes) == 4
    # papers' frame (x, y up, z athwart) -> z-up (x, -z, y): only the plan position is kept
    assert problem.fleet[0].position == (20.0, 25.0)
    result = plan(problem)
    data = result.to_json()
    for key in ("objective", "cranes", "radius", "swl", "utilisation", "worst_utilisation_spread"):
        assert key in data
    assert set(data["cranes"].values()) == {c.name for c in problem.fleet}
    for label, crane in data["cranes"].items():
        j = [c.name for c in problem.fleet].index(crane)
        assert data["radius"][label] <= problem.fleet[j].reach
        assert data["utilisation"][label] == pytest.approx(data["tensions"][label] / data["swl"][label])


BASE = """
[body]
weight = 904.0
cog = [35.86, 0.0, 2.5]
[[candidates]]
name = "A"
at = [10.0, -6.0, 6.0]
[[candidates]]
name = "B"
at = [60.0, -6.0, 6.0]
[[candidates]]
name = "C"
at = [60.0, 6.0, 6.0]
[[candidates]]
name = "D"
at = [10.0, 6.0, 6.0]
[plan]
tolerance = { heel = 1.0, trim = 1.0 }
"""


def crane_table(name, extra=""):
    return f'\n[[cranes]]\nname = "{name}"\nswl = 400.0\nEA = 50000.0\nrope_length = 30.0\n{extra}'


def test_file_objective_defaults():
    equal = loads_problem(BASE + "".join(crane_table(n) for n in "PQRS"))
    assert equal.cranes == 4 and equal.objective == "spread"
    unequal = loads_problem(
        BASE + "".join(crane_table(n) for n in "PQR") + crane_table("S").replace("400.0", "300.0")
    )
    assert unequal.objective == "utilisation"


@pytest.mark.parametrize(
    "text, message",
    [
        (BASE + "cranes = 3\n" + "".join(crane_table(n) for n in "PQRS"), "plan.cranes = 3: 4"),
        (
            BASE + "".join(crane_table(n) for n in "PQRS").replace("swl = 400.0", "", 1),
            r"cranes\[P\]: no load_chart or swl",
        ),
        (
            BASE
            + "".join(crane_table(n) for n in "PQRS").replace(
                "swl = 400.0", "load_chart = [[10.0, 400.0]]\nswl = 400.0", 1
            ),
            "both load_chart and swl",
        ),
        (
            BASE
            + "".join(crane_table(n) for n in "PQRS").replace(
                "swl = 400.0", "load_chart = [[10.0, 400.0]]", 1
            ),
            r"cranes\[P\]\.position: missing",
        ),
        (BASE + 'objective = "evenness"\n' + "".join(crane_table(n) for n in "PQRS"), "objective"),
    ],
)
def test_file_errors(text, message):
    with pytest.raises(InvalidScene, match=message):
        loads_problem(text)


def test_collinear_set_is_refused_with_its_cause():
    from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible

    problem = load_problem(EXAMPLES / "tanker_fleet.toml")
    # BH1-S, BH2-S, BH5-S and BH6-S all lie on the starboard deck edge
    with pytest.raises(SetInfeasible, match="collinear"):
        SetEvaluator(problem).evaluate((1, 3, 7, 9), (0, 2, 1, 3))
