"""Crane fleets: unequal cranes at fixed positions with load charts, and which crane takes
which lug. The search must equal brute force over every lug set and every assignment."""

from __future__ import annotations

import dataclasses
import itertools
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import linprog

from liftplan.model.errors import InvalidScene, PlanInfeasible
from liftplan.model.frames import choi_to_zup
from liftplan.model.scene.objects import Body
from liftplan.planner.plan import plan
from liftplan.planner.problem.definition import Candidate, CogEnvelope, PlanProblem
from liftplan.planner.problem.file import load_problem, loads_problem
from liftplan.planner.problem.fleet import FleetCrane
from liftplan.planner.search.methods import search
from liftplan.planner.search.scenarios import LugSet, Scenario, box_attitudes

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

#: Seven deck points of the tanker (papers' frame, as in test_planner).
POINTS = [
    (4.2, 6, 0),
    (16.2, 6, 12),
    (28.55, 6, 0),
    (40.9, 6, 12),
    (53.25, 6, 6),
    (65.6, 6, 0),
    (73.6, 6, 12),
]


def fleet(count):
    """Unequal cranes round the hull (z-up plan), charts short enough that reach matters."""
    specs = [
        ("Big aft", (10.0, -30.0), ((20.0, 700.0), (35.0, 450.0), (45.0, 300.0)), 80000.0, 40.0),
        ("Big fwd", (65.0, -30.0), ((20.0, 700.0), (35.0, 450.0), (45.0, 300.0)), 80000.0, 40.0),
        ("Small aft", (20.0, 22.0), ((15.0, 420.0), (30.0, 260.0), (40.0, 180.0)), 40000.0, 30.0),
        ("Small fwd", (60.0, 22.0), ((15.0, 420.0), (30.0, 260.0), (40.0, 180.0)), 40000.0, 30.0),
        ("Mid", (38.0, 30.0), ((20.0, 500.0), (40.0, 300.0), (48.0, 240.0)), 60000.0, 35.0),
    ]
    return tuple(
        FleetCrane(name=n, position=p, load_chart=c, EA=ea, rope_length=l0, boom_min=30.0, boom_max=70.0)
        for n, p, c, ea, l0 in specs[:count]
    )


def fleet_problem(count, objective="utilisation", **changes):
    problem = PlanProblem(
        body=Body(904.0, choi_to_zup((35.86, 2.5, 6.0))),
        candidates=tuple(Candidate(f"C{i}", choi_to_zup(p)) for i, p in enumerate(POINTS)),
        cranes=count,
        crane=None,
        fleet=fleet(count),
        objective=objective,
        heel_tolerance=2.0,
        trim_tolerance=2.0,
        min_tension=5.0,
        lift_height=1.0,
        cog_envelope=CogEnvelope((0.3, 0.2, 0.0)),
        top=3,
    )
    return dataclasses.replace(problem, **changes)


def linprog_minimax(lugset, scenarios):
    """The preload minimax of one set and assignment as a scipy LP (HiGHS): T* (n), high_k,
    low_k, worst; per-rope SWL at the crane's radius; the spread of s_i T_i."""
    problem = lugset.problem
    gains, offsets = lugset.affine(scenarios)
    if not (np.all(np.isfinite(gains)) and np.all(np.isfinite(offsets))):
        return None  # collinear lugs
    n, m = lugset.n, len(scenarios)
    size = n + 2 * m + 1
    rows, rhs = [], []
    reserve = problem.objective == "reserve"
    for k in range(m):
        for i in range(n):
            g = np.zeros(size)
            g[:n] = gains[k, i]
            s = lugset.scale[i]
            if reserve:  # the largest s_i T_i itself: s_i T_i - worst <= 0
                up = s * g
                up[-1] = -1.0
                rows.append(up), rhs.append(-s * offsets[k, i])
            else:
                up = s * g
                up[n + k] = -1.0
                rows.append(up), rhs.append(-s * offsets[k, i])
                down = -s * g
                down[n + m + k] = 1.0
                rows.append(down), rhs.append(s * offsets[k, i])
            rows.append(g), rhs.append(lugset.limit[i] - offsets[k, i])
            rows.append(-g), rhs.append(offsets[k, i] - problem.min_tension)
        if not reserve:
            spread = np.zeros(size)
            spread[n + k], spread[n + m + k], spread[-1] = 1.0, -1.0, -1.0
            rows.append(spread), rhs.append(0.0)
    a_level, b_level = lugset.level_statics
    a_eq = np.hstack([a_level, np.zeros((3, size - n))])
    low, high = lugset.preload_range()
    bounds = list(zip(low, high)) + [(None, None)] * (2 * m + 1)
    cost = np.zeros(size)
    cost[-1] = 1.0
    result = linprog(
        cost, A_ub=np.array(rows), b_ub=rhs, A_eq=a_eq, b_eq=b_level, bounds=bounds, method="highs"
    )
    return result.fun if result.status == 0 else None


def brute_force(problem, grid=7):
    """Every set and EVERY permutation of the cranes on it (no reach pruning, no symmetry)."""
    scenarios = [
        Scenario(h, t, tuple(o))
        for o in problem.cog_envelope.offsets()
        for h, t in box_attitudes(problem, grid, grid)
    ]
    swl = problem.reach[1]
    best = {}
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        for perm in itertools.permutations(range(problem.cranes)):
            if np.any(np.isnan(swl[list(indices), list(perm)])):
                continue  # a crane beyond its chart's reach
            best[(indices, perm)] = linprog_minimax(LugSet(problem, indices, perm), scenarios)
    return best


@pytest.mark.parametrize("objective", ["utilisation", "spread", "reserve"])
@pytest.mark.parametrize("cranes", [3, 4, 5])
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
