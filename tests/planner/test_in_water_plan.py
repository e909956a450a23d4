"""Issue 24 item 3: a plan whose lift starts in water (``[water]``, ``[hull]`` box and
``[plan] start_lift_height`` in a planning file).

A 60 m box barge, 600 t with its CG 4 m forward of its middle, four equal cranes among eight
deck candidates. At the start the hull draws 0.6 m: the buoyancy (443 t at the waterplane's
centre) moves the net load's line 11 m further forward, so the shares change, and the in-water
state becomes one more of the plan's worst states: the best set in air goes slack in water.
The plan must be the brute-force optimum over every set on max(box worst, in-water worst)
among the sets whose ropes stay taut in water; its written scene (with [hull] and [water])
must solve, on the hydrostatic model, to the plan's tensions clear of the water and, lowered
to the start, in it.
"""

from __future__ import annotations

import dataclasses
import itertools
import json

import numpy as np
import pytest

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import load_scene, loads_scene
from liftplan.planner import plan
from liftplan.planner.output.console.summary import summary
from liftplan.planner.output.report.held import plan_scene_toml, render_html
from liftplan.planner.output.report.hull_water import with_water
from liftplan.planner.plans.in_water import in_water_case
from liftplan.planner.problem.file import loads_problem
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.scenarios import LugSet

CANDIDATES = {
    "A1": (4.0, 4.0),
    "A2": (4.0, -4.0),
    "B1": (18.0, 4.0),
    "B2": (20.0, -4.0),
    "C1": (41.0, 4.0),
    "C2": (39.0, -4.0),
    "D1": (56.0, 4.0),
    "D2": (55.0, -4.0),
}


def barge(start=-0.6, extra="", water=True):
    """The planning file, the lift starting at lift height ``start`` [m] (the hull's draft -start)."""
    lines = [
        'name = "barge lifted out of the water"',
        "[body]",
        "weight = 600.0",
        "cog = [34.0, 0.5, 2.0]",
        "[plan]",
        "cranes = 4",
        "tolerance = { heel = 1.0, trim = 1.0 }",
        "cog_tolerance = [0.1, 0.1, 0.05]",
        "min_tension = 10.0",
        "top = 3",
        "[crane]",
        "EA = 20000.0",
        "rope_length = 20.0",
        "swl = 400.0",
        "[attitude]",
        "lift_height = 10.0",
    ]
    if water:
        lines[10:10] = [f"start_lift_height = {start}"]
        lines += [
            "[hull]",
            "box = { min = [0.0, -6.0, 0.0], max = [60.0, 6.0, 4.0] }",
            "[water]",
            "level = 0.0",
        ]
    for name, (x, y) in CANDIDATES.items():
        lines += ["[[candidates]]", f'name = "{name}"', f"at = [{x}, {y}, 4.0]"]
    return "\n".join(lines) + "\n" + extra


@pytest.fixture(scope="module")
def problem():
    return loads_problem(barge())


@pytest.fixture(scope="module")
def planned(problem):
    return plan(problem)


@pytest.fixture(scope="module")
def brute(problem):
    """Every set of 4 of 8 (equal cranes: one assignment each): (result, in-water case)."""
    evaluator = SetEvaluator(problem)
    rows = []
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        try:
            result = evaluator.evaluate(indices)
        except SetInfeasible:
            continue
        lugset = LugSet(problem, result.indices, result.cranes)
        rows.append((result, in_water_case(problem, lugset, result.preload)))
    return rows


def test_plan_is_the_brute_force_optimum_with_the_start_in_water(planned, brute):
    held = [(max(r.worst_value, case.value), r.lugs) for r, case in brute if case.holds]
    value, lugs = min(held)
    assert planned.chosen.lugs == lugs
    assert planned.hull_search.values[0] == pytest.approx(value, rel=1e-9)
    assert planned.hull_search.certified
    # the state in water governs: it moves the choice away from the best set in air
    in_air = min(brute, key=lambda row: row[0].worst_value)[0]
    assert in_air.lugs != planned.chosen.lugs
    assert not next(case for r, case in brute if r.lugs == in_air.lugs).holds  # slack in water
    assert value > planned.chosen.worst_value  # ranked on the value in water, larger than the box's
    order = sorted(held)[: len(planned.ranking)]
    assert [r.lugs for r in planned.ranking][: len(order)] == [lugs for _, lugs in order]
    # the plan's worst spread, bound and gap are on the governing value (in water), not in air
    assert planned.worst_spread == pytest.approx(value, rel=1e-9)
    assert planned.stats.best == planned.stats.lower_bound == planned.worst_spread
    assert planned.stats.gap == 0.0


def test_written_scene_reproduces_the_plan_clear_of_and_in_the_water(planned, tmp_path):
    """plan_scene.toml carries [hull] and [water]: ``solve`` of it (the hydrostatic model, the
    body free to find its pose on the elastic ropes) gives the plan's level tensions with the
    hull clear of the water; lowered to the start height, the hooks moved by the case's hook
    shift, the tensions of the state in water."""
    path = tmp_path / "plan_scene.toml"
    path.write_text(plan_scene_toml(planned))
    scene = load_scene(path)
    assert scene.hull is not None and scene.water is not None
    names = [planned.lugs[label] for label in planned.labels]
    clear = solve(scene)
    assert clear.model == "hydrostatic"
    np.testing.assert_allclose([clear.tensions[n] for n in names], planned.chosen.preload, rtol=1e-7)
    case = planned.design_loads.in_water
    start = planned.problem.in_water.start_lift_height
    drop = start - planned.problem.lift_height
    lowered = dataclasses.replace(
        scene,
        cranes=tuple(
            dataclasses.replace(c, boom_height=c.boom_height + drop + float(d))
            for c, d in zip(scene.cranes, case.hook_shift[0])
        ),
        attitude=dataclasses.replace(scene.attitude, lift_height=start),
    )
    eq = solve(lowered)
    assert eq.model == "hydrostatic"
    assert eq.pose.heel == pytest.approx(0.0, abs=1e-7) and eq.pose.trim == pytest.approx(0.0, abs=1e-7)
    np.testing.assert_allclose([eq.tensions[n] for n in names], case.tensions[0], rtol=1e-7)
    assert eq.afloat.buoyancy == pytest.approx(case.loads[0].buoyancy, rel=1e-9)


def test_stiffness_and_geometry_share_one_hull_table():
    """[hull] EI and box in one planning file: the written scene has one [hull] table with both."""
    text = (
        barge()
        .replace("[hull]\n", "[hull]\nEI = [[0.0, 1.0e9], [60.0, 1.0e9]]\n")
        .replace(
            "cog = [34.0, 0.5, 2.0]", "cog = [30.0, 0.5, 2.0]\nweight_curve = [[0.0, 10.0], [60.0, 10.0]]"
        )
    )
    problem = loads_problem(text)
    assert problem.hull_stiffness is not None and problem.in_water is not None
    written = with_water(
        "[body]\nweight = 600.0\n\n[hull]\nEI = [[0, 1e9], [60, 1e9]]\n\n[attitude]\nlift_height = 10.0\n",
        problem.in_water,
    )
    assert written.count("[hull]") == 1 and "EI = " in written and "box = " in written
    assert written.index("box = ") < written.index("[attitude]") < written.index("[water]")


def test_min_tension_holds_in_water_as_in_air(planned, brute):
    """The plan's min_tension (10 t) is a limit at the start in water too (it was 0 there: the
    plan A1 B2 D1 D2 held 2.38 t in water and passed). A set below it there ranks after those
    that reach it, the check's limit is min_tension, and the hook accuracy asked of the crew
    keeps every rope at min_tension in water."""
    least = {r.lugs: float(case.least.min()) for r, case in brute}
    assert 0.0 < least[("A1", "B2", "D1", "D2")] < 10.0
    assert not next(case for r, case in brute if r.lugs == ("A1", "B2", "D1", "D2")).holds
    assert all((value >= 10.0) == case.holds for (r, case), value in zip(brute, least.values()))
    check = planned.design_loads.in_water.checks[0]
    assert check.limit == 10.0 and check.ok and check.value == pytest.approx(least[planned.chosen.lugs])
    water = planned.design_loads.in_water
    e = planned.hook_accuracy_needed
    assert (water.tensions - np.abs(water.gain).sum(axis=2) * e).min() >= 10.0 - 1e-9
    assert (water.tensions - np.abs(water.gain).sum(axis=2) * 1.01 * e).min() < 10.0 or e == 0.0


def test_min_tension_zero_keeps_only_the_slack_rule():
    planned = plan(loads_problem(barge().replace("min_tension = 10.0", "min_tension = 0.0")))
    assert planned.chosen.lugs == ("A1", "B2", "D1", "D2")  # 2.38 t in water: taut, so it holds
    assert planned.design_loads.in_water.checks[0].limit == 0.0


def test_design_loads_take_the_larger(planned):
    for crane, worst in zip(planned.capacity, planned.design_loads.in_water.worst):
        assert crane.in_water == pytest.approx(worst, rel=1e-12)
        assert crane.static_input == pytest.approx(max(crane.worst, crane.nominal, worst), rel=1e-12)


def test_a_larger_tension_in_water_governs(planned):
    """Where a rope's tension in water exceeds its worst in the box, it is the chain's static
    input and the plan says so (the example's are below: a crane with 1.5 x its box worst)."""
    crane = planned.capacity[0]
    larger = dataclasses.replace(crane, in_water=1.5 * crane.worst)
    assert larger.governs == "in_water" and larger.static_input == 1.5 * crane.worst
    assert "in water at the start" in larger.static_note and "governs" in larger.static_note
    assert crane.governs == "box" and "governs over in water at the start" in crane.static_note


def test_outputs_name_the_state_in_water(planned):
    out = planned.to_json()
    assert out["in_water"]["net_weight"] == pytest.approx(600.0 - 1.025 * 60 * 12 * 0.6, rel=1e-9)
    assert out["in_water"]["checks"][0]["name"] == "in_water_min_tension"
    assert all("value_in_water" in r and "governing_value" in r for r in out["ranking"])
    assert "in_water_min_tension" in [c.name for c in planned.checks]
    json.dumps(out, allow_nan=False)
    assert "start in water (lift height -0.6 m): W + trapped - B = 157.20 t" in summary(planned)
    assert "start in water" in render_html(planned)
    assert "<h3>The start in water</h3>" in render_html(planned)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (barge().replace("start_lift_height = -0.6\n", ""), r"plan.start_lift_height: missing"),
        (barge(start=-2.0), r"plan.start_lift_height = -2: .*buoyancy .* exceeds"),
        (
            barge().replace("[water]\nlevel = 0.0\n", ""),
            r"plan.start_lift_height = -0.6: given without \[water\]",
        ),
        (
            barge().replace("[water]\nlevel = 0.0\n", "").replace("start_lift_height = -0.6\n", ""),
            r"hull: box or mesh given without \[water\]",
        ),
        (
            barge().replace("box = { min = [0.0, -6.0, 0.0], max = [60.0, 6.0, 4.0] }\n", ""),
            r"water: given without the hull's geometry",
        ),
        (
            barge().replace("rope_length = 20.0", "rope_length = { min = 15.0, max = 25.0 }"),
            r"\[water\]: planned at fixed rope lengths",
        ),
        (
            barge().replace("weight = 600.0", 'weight = 600.0\nweight_basis = "water"', 1),
            r'body.weight_basis = "water" with \[water\]: the plan subtracts',
        ),
    ],
)
def test_refused_in_one_line(text, message):
    with pytest.raises(InvalidScene, match=message):
        plan(loads_problem(text))


@pytest.mark.slow  # a third plan of its own, flexible and in water together
def test_flexible_hull_and_water_together_written_scene_agrees():
    """[hull] EI with the box and [water]: the plan's written scene, solved by ``solve`` (the
    hydrostatic model with the flexible hull, clear of the water), gives the plan's flexible level
    tensions."""
    text = barge().replace("[hull]\n", "[hull]\nEI = [[0.0, 1.0e6], [60.0, 1.0e6]]\n")
    text = text.replace(
        "cog = [34.0, 0.5, 2.0]", "cog = [30.0, 0.5, 2.0]\nweight_curve = [[0.0, 10.0], [60.0, 10.0]]"
    )
    both = plan(loads_problem(text))
    assert both.hull_models[0].used == "flexible" and both.design_loads.in_water is not None
    eq = solve(loads_scene(plan_scene_toml(both)))
    names = [both.lugs[label] for label in both.labels]
    assert eq.flexible_hull.used == "flexible"
    np.testing.assert_allclose([eq.tensions[n] for n in names], both.hull_models[0].flexible[0], rtol=1e-7)
