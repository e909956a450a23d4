"""Issue 24 item 3: the flexible hull in a plan (``[hull] EI`` / ``GJ`` in a planning file).

A 60 m barge, 600 t on a uniform weight curve, four equal cranes among six candidates, a hull
soft enough (EI 1.0e6 t m2) that flexibility changes the tensions by more than 1 % in every
feasible set. The search's best set on the rigid hull (A1 A2 D1 D2, lugs paired at the ends)
is not the best on the flexible hull: the plan must be the brute-force optimum over every set
on the governing model, its numbers must be those ``liftplan solve`` gives for the plan's
written scene, and the bound that certifies the re-ranking must hold on every set.
"""

from __future__ import annotations

import itertools
import json
import math
import re

import numpy as np
import pytest
from support.cli import run

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import load_scene
from liftplan.planner import plan
from liftplan.planner.output.console.summary import summary
from liftplan.planner.output.report.held import plan_scene_toml, render_html
from liftplan.planner.plans.design_loads import DesignBuilder
from liftplan.planner.plans.flexible import change_bound, deflection_bounds, evaluate_flexible
from liftplan.planner.plans.girder import moved_body
from liftplan.planner.problem.file import loads_problem
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible, robust
from liftplan.planner.search.scenarios import LugSet

CANDIDATES = {
    "A1": (4.0, 4.0),
    "A2": (4.0, -4.0),
    "B1": (18.0, 4.0),
    "C1": (41.0, 4.0),
    "D1": (56.0, 4.0),
    "D2": (55.0, -4.0),
}


def barge(ei=1.0e6, extra="", cog="[0.05, 0.05, 0.05]"):
    """The planning file: the barge, its hull's stiffness ``ei`` [t m2] and ``extra`` lines."""
    lines = [
        'name = "barge, flexible hull"',
        "[body]",
        "weight = 600.0",
        "cog = [30.0, 0.0, 2.0]",
        "weight_curve = [[0.0, 10.0], [60.0, 10.0]]",
        "[plan]",
        "cranes = 4",
        "tolerance = { heel = 1.0, trim = 1.0 }",
        f"cog_tolerance = {cog}",
        "min_tension = 10.0",
        "top = 3",
        "[crane]",
        "EA = 20000.0",
        "rope_length = 20.0",
        "swl = 400.0",
        "[attitude]",
        "lift_height = 10.0",
        "[hull]",
        f"EI = [[0.0, {ei}], [60.0, {ei}]]",
        f"GJ = [[0.0, {ei}], [60.0, {ei}]]",
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
    """Every set of 4 of the 6 candidates: the search's exact evaluation on the rigid hull,
    then the flexible hull at its worst states (equal cranes: one assignment per set)."""
    dense = DesignBuilder(problem).dense
    evaluator = SetEvaluator(problem)
    bounds = deflection_bounds(problem)
    rows = []
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        try:
            result = evaluator.evaluate(indices)
        except SetInfeasible:
            continue
        rows.append((result, evaluate_flexible(problem, result, dense, bounds)))
    return rows


def test_plan_is_the_brute_force_optimum_on_the_flexible_hull(planned, brute):
    best_result, best_model = min(brute, key=lambda row: row[1].value)
    rigid_result, rigid_model = min(brute, key=lambda row: row[0].worst_value)
    assert planned.chosen.lugs == best_result.lugs == ("A2", "B1", "C1", "D2")
    assert planned.hull_search.values[0] == pytest.approx(best_model.value, rel=1e-9)
    assert planned.hull_models[0].used == "flexible"
    # the rigid hull's best set is another, and the flexible hull makes it worse than the plan
    assert rigid_result.lugs == ("A1", "A2", "D1", "D2") != planned.chosen.lugs
    assert rigid_model.used == "flexible" and rigid_model.value > best_model.value
    assert rigid_result.worst_value < best_result.worst_value
    # the reported ranking is the brute force's order on the governing values
    order = sorted(brute, key=lambda row: row[1].value)[: len(planned.ranking)]
    assert [r.lugs for r in planned.ranking] == [row[0].lugs for row in order]
    assert planned.hull_search.certified
    # every set evaluated on the governing hull: the plan's value, bound and gap are that hull's
    # (the rigid search's bound, 10.37 t, is not a bound on the flexible values)
    assert planned.worst_spread == pytest.approx(best_model.value, rel=1e-9)
    assert planned.stats.best == planned.stats.lower_bound == planned.worst_spread
    assert planned.stats.gap == 0.0


def test_each_set_keeps_solves_one_percent_rule(brute):
    """A set is flexible exactly when a tension changes by more than 1 % at one of its states."""
    for _, model in brute:
        change = np.abs(model.flexible - model.rigid) / model.rigid
        assert model.max_change == pytest.approx(change.max(), rel=1e-12)
        assert (model.used == "flexible") == (change.max() > 0.01)


def test_the_bound_holds_on_every_set(problem, brute):
    """The flexible correction's bound (the beam's deflection bounded whatever the lugs) holds
    on every set: per set, and the one over all sets that certifies the re-ranking."""
    overall = change_bound(problem, deflection_bounds(problem))
    for result, model in brute:
        lugset = LugSet(problem, result.indices, result.cranes)
        rigid = robust(model.rigid, model.gain, lugset)[0]
        flexible = robust(model.flexible, model.gain, lugset)[0]
        assert np.all(np.abs(flexible - rigid) <= model.bound)
        assert model.bound <= overall * (1 + 1e-12)
        assert rigid.max() == pytest.approx(result.worst_value, rel=1e-6)  # the rigid worst is a state


def _written_scene(planned, tmp_path):
    """plan_scene.toml as the report writes it (:func:`plan_scene_toml`), read back."""
    path = tmp_path / "plan_scene.toml"
    path.write_text(plan_scene_toml(planned))
    text = path.read_text()
    assert "[hull]" in text and "EI = " in text and "GJ = " in text
    return load_scene(path)


def test_written_scene_solves_to_the_plans_flexible_tensions(planned, tmp_path):
    scene = _written_scene(planned, tmp_path)
    eq = solve(scene)
    model = planned.hull_models[0]
    names = [planned.lugs[label] for label in planned.labels]
    flexible = [eq.flexible_hull.flexible_tensions[name] for name in names]
    rigid = [eq.flexible_hull.rigid_tensions[name] for name in names]
    np.testing.assert_allclose(flexible, model.flexible[0], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(rigid, model.rigid[0], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(rigid, planned.chosen.preload, rtol=1e-7)
    # the design loads' level input is the flexible hull's, the tension solve gives, and the
    # chain is built on it (skew 1: the hook errors are in the worst)
    np.testing.assert_allclose([c.nominal for c in planned.capacity], flexible, rtol=1e-9)
    assert planned.design_loads.missing is None and planned.design_loads.ok
    assert all(c.skew == pytest.approx(1.0, abs=1e-12) for c in planned.capacity)


def test_written_scene_posed_at_each_state_gives_the_plans_numbers(planned, tmp_path):
    """The written scene, its hooks moved as the held preload moves them and its CG moved,
    solved at each of the plan's worst states: the flexible tensions the plan ranked on."""
    scene = _written_scene(planned, tmp_path)
    model = planned.hull_models[0]
    names = [planned.lugs[label] for label in planned.labels]
    for k, state in enumerate(model.states):
        shift = planned.lugset.hook_shifts(planned.chosen.preload, [state])[0]
        posed = scene.__class__(
            **{
                **{f: getattr(scene, f) for f in scene.__dataclass_fields__},
                "body": moved_body(scene.body, state.cog_offset),
                "cranes": tuple(
                    c.__class__(
                        **{
                            **{f: getattr(c, f) for f in c.__dataclass_fields__},
                            "boom_height": c.boom_height + float(d),
                        }
                    )
                    for c, d in zip(scene.cranes, shift)
                ),
            }
        )
        report = solve(posed).flexible_hull
        # the rigid hull's tensions there are the planner's at that state (the state is posed)
        rigid = [report.rigid_tensions[name] for name in names]
        np.testing.assert_allclose(
            rigid, planned.tensions_at(state.heel, state.trim, state.cog_offset)[0], rtol=1e-7
        )
        flexible = [report.flexible_tensions[name] for name in names]
        np.testing.assert_allclose(flexible, model.flexible[k], rtol=1e-8)


def test_stiff_hull_keeps_the_rigid_plan():
    """A hull 1000 x stiffer changes no tension by 1 %: the rigid plan stands, and says so."""
    stiff = plan(loads_problem(barge(ei=1.0e9)))
    assert stiff.chosen.lugs == ("A1", "A2", "D1", "D2")
    assert all(m.used == "rigid" for m in stiff.hull_models)
    assert stiff.hull_search.values[0] == stiff.chosen.worst_value


def test_json_console_and_report_say_which_hull_governed(planned, tmp_path):
    out = planned.to_json()
    assert out["flexible_hull"]["used"] == "flexible"
    assert out["flexible_hull"]["max_tension_change"] > 0.01
    assert out["flexible_hull"]["certified"] is True
    assert [r["hull_model"] for r in out["ranking"]] == ["flexible"] * 3
    assert all(r["max_tension_change"] > 0.01 for r in out["ranking"])
    json.dumps(out, allow_nan=False)
    text = summary(planned)
    assert re.search(
        r"hull: flexibility changes L\d by [\d.]+ %, more than 1 %: the flexible hull governs", text
    )
    page = render_html(planned)
    assert "flexible hull governs" in page
    # its section is named for what the file gave (it read "... and the start in water")
    assert "<h3>Flexible hull</h3>" in page and "start in water" not in page
    # the Alternatives table shows the value each set is ranked on, not only the rigid spreads
    assert (
        "value ranked on (governing model) [t]" in page
        and f"{out['ranking'][1]['governing_value']:.4g}" in page
    )
    # the assumptions say the hull is flexible, not "the body is rigid"
    assert "The hull is flexible ([hull] EI, GJ)" in page and "the body is rigid" not in page
    assert "left out of it" in page and "hull flexibility, which lowers skew loads, is ignored" not in page


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ("", None),
        ("[ground]\ncontact = [0.0, 0.0, 0.0]\n", r"\[ground\]: not in a planning file"),
    ],
)
def test_ground_stays_refused(extra, message):
    if message is None:
        assert loads_problem(barge(extra=extra)).hull_stiffness is not None
    else:
        with pytest.raises(InvalidScene, match=message):
            loads_problem(barge(extra=extra))


def test_refusals_in_one_line():
    no_curve = barge().replace("weight_curve = [[0.0, 10.0], [60.0, 10.0]]\n", "")
    with pytest.raises(InvalidScene, match=r"hull.EI: .*expected body.weight_curve"):
        loads_problem(no_curve)
    ranged = barge().replace("rope_length = 20.0", "rope_length = { min = 15.0, max = 25.0 }")
    with pytest.raises(InvalidScene, match=r"\[hull\] EI: planned at fixed rope lengths"):
        loads_problem(ranged)
    strength = barge().replace("top = 3", 'top = 3\nobjective = "bending"') + (
        "[strength]\nbending_moment = [[0.0, 5000.0], [60.0, 5000.0]]\n"
    )
    with pytest.raises(InvalidScene, match=r"\[hull\] EI: planned with the spread"):
        loads_problem(strength)


@pytest.mark.slow  # the whole plan again in its own process: the JSON keys are tested above
def test_cli_exit_and_json(tmp_path):
    path = tmp_path / "barge.toml"
    path.write_text(barge())
    done = run("plan", str(path), "--json")
    assert done.returncode in (0, 4), done.stderr
    out = json.loads(done.stdout)
    assert out["flexible_hull"]["used"] == "flexible"
    assert math.isfinite(out["ranking"][0]["governing_value"])
