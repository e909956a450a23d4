"""The plan's design loads: the rules' chain (liftplan.model.rules) fed by the planner.

One defined design load per crane (the chain's design hook load), one utilisation (design /
chart SWL) in the JSON, console, ranking and report; every worst case with its CG position in
the file's frame; [rules] read from planning files; the tanker fleet by hand.
"""

import dataclasses
import html
import json
import math

import numpy as np
import pytest
from helpers import EXAMPLES
from numpy.testing import assert_allclose
from support.cli import run

from liftplan.model.errors import InvalidScene
from liftplan.model.frames import choi_to_zup
from liftplan.model.rules import Rules
from liftplan.model.scene.file import loads_scene
from liftplan.planner.output.console.summary import summary as plan_table
from liftplan.planner.output.report.held import render_html
from liftplan.planner.plan import plan
from liftplan.planner.plans.design_loads import DesignBuilder
from liftplan.planner.problem.definition import CogEnvelope
from liftplan.planner.problem.file import load_problem, loads_problem
from liftplan.planner.search.scenarios import Scenario

FLEET = EXAMPLES / "tanker_fleet.toml"


@pytest.fixture(scope="module")
def fleet_plan():
    return plan(load_problem(FLEET))


def _by_crane(result):
    return {c.crane: c for c in result.capacity}


# -- the tanker fleet by hand ------------------------------------------------------------------
# Inputs (examples/tanker_fleet.toml, papers' frame -> z-up (x, -z, y)): W = 904 t, CG
# (35.86, -6, 2.5); lugs at z = 6; [rules] inshore, separate vessels, contingency 1.05, rigging
# 8 t per sheerleg and 4 t per crane. The plan puts Crane C on BH1-S (4.2, -12), Sheerleg A on
# BH4-P (28.55, 0), Crane D on BH5-S (40.9, -12) and Sheerleg B on BH8-S (73.6, -12): the best
# set whose booms keep 3 m apart in plan (the best by utilisation alone, Crane C on BH2-S,
# Sheerleg B on BH4-P, Sheerleg A on BH6-P, Crane D on BH6-S, has the sheerlegs' booms crossing).
W = 904.0
DAF = 1.10  # Table 5-1: design weight 904 x 1.05 = 949.2 t, 300 < W <= 1000, inshore (5.5.2)
CONTINGENCY = 1.05
RIGGING = {"Sheerleg A": 8.0, "Crane C": 4.0, "Sheerleg B": 8.0, "Crane D": 4.0}
# Tilt (5.4.4/5.4.5 and the chain's reading for more than two hooks): separate vessels, 5 deg,
# or 1.0 m over the least hook spacing, BH4-P to BH5-S = hypot(12.35, 12) = 17.22 m:
# asin(1 / 17.22) = 3.33 deg < 5 deg, so 5 deg governs.
TILT = 5.0
# Radii, plan distance slew centre -> lug (z-up): C (20, -37) -> (4.2, -12); A (20, 25) ->
# (28.55, 0); D (60, -37) -> (40.9, -12); B (60, 25) -> (73.6, -12); SWL linear in the chart
# (sheerlegs 1000 t at 20 m, 750 t at 30 m, 525 t at 40 m; cranes 450 t at 25 m, 330 t at 32 m).
RADIUS = {
    "Crane C": math.hypot(15.8, 25.0),
    "Sheerleg A": math.hypot(8.55, 25.0),
    "Crane D": math.hypot(19.1, 25.0),
    "Sheerleg B": math.hypot(13.6, 37.0),
}
SWL = {
    "Crane C": 450.0 - 120.0 * (RADIUS["Crane C"] - 25.0) / 7.0,
    "Sheerleg A": 1000.0 - 250.0 * (RADIUS["Sheerleg A"] - 20.0) / 10.0,
    "Crane D": 450.0 - 120.0 * (RADIUS["Crane D"] - 25.0) / 7.0,
    "Sheerleg B": 750.0 - 225.0 * (RADIUS["Sheerleg B"] - 30.0) / 10.0,
}
# The planner's static loads (t) and computed skew factors, as it prints them (the held-preload
# model with unequal stiffness is tested against the elastic solve in test_planner.py; here they
# are the chain's inputs): level T*, worst in the box (hook errors included), at the tilt, skew.
# The worst includes every hook within +-0.02 m (the plan's hook_tolerance), so the chain's
# skew factor is 1 (the computed skew is in the worst already).
STATIC = {
    "Crane C": (135.28, 177.33, 165.93, 1.0),
    "Sheerleg A": (452.00, 484.34, 498.99, 1.0),
    "Crane D": (133.52, 181.94, 148.41, 1.0),
    "Sheerleg B": (183.20, 217.92, 200.67, 1.0),
}
# printed to 2 decimals (0.005 t), skew to 4 (5e-5): through x 1.05 x 1.1 the hand design loads
# carry 0.005 x 1.16 + 5e-5 x 499 x 1.16 = 0.035 t of that rounding at most (the skew is 1 here)
PRINTED = dict(rtol=0.0, atol=0.035)
# closed forms in float64, a handful of operations: agreement to ~1e-12 relative
EXACT = dict(rtol=1e-9, atol=1e-9)


def test_fleet_radii_and_chart_swl_by_hand(fleet_plan):
    got = _by_crane(fleet_plan)
    assert {c.crane: c.lug for c in got.values()} == {
        "Crane C": "BH1-S",
        "Sheerleg A": "BH4-P",
        "Crane D": "BH5-S",
        "Sheerleg B": "BH8-S",
    }
    for name in RADIUS:
        assert_allclose(got[name].radius, RADIUS[name], **EXACT)
        assert_allclose(got[name].swl, SWL[name], **EXACT)
    assert_allclose(fleet_plan.design_loads.tilt, TILT, **EXACT)


def _three_hook_tilt_share(weight, lugs, cog, tilt, elevation):
    """The third hook's largest load over every tilt axis (per-direction rule), by Rodrigues'
    rotation and the lever rule about the turned line of the first two hooks: independent of
    TiltGeometry (a scan over psi refined by a bounded scalar search)."""
    from scipy.optimize import minimize_scalar

    lugs, cog = np.array(lugs), np.array(cog)

    def share(psi, sign):
        u = np.array([math.cos(psi), math.sin(psi), 0.0])
        along = lugs[:, :2] @ np.array([-math.sin(psi), math.cos(psi)])
        a = sign * max(math.radians(tilt), math.asin(elevation / np.ptp(along)))
        k = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
        rot = np.eye(3) + math.sin(a) * k + (1 - math.cos(a)) * k @ k
        p, g = lugs @ rot.T, rot @ cog
        line = p[1, :2] - p[0, :2]
        normal = np.array([-line[1], line[0]]) / np.hypot(*line)
        return weight * ((g[:2] - p[0, :2]) @ normal) / ((p[2, :2] - p[0, :2]) @ normal)

    best = 0.0
    for sign in (-1.0, 1.0):
        grid = np.linspace(0.0, math.pi, 3601)
        values = [share(psi, sign) for psi in grid]
        k = int(np.argmax(values))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
        found = minimize_scalar(
            lambda psi, sign=sign: -share(psi, sign),
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": 1e-12},
        )
        best = max(best, values[k], -found.fun)
    return best


def test_three_cranes_entirely_by_hand():
    """Three equal cranes on a triangle of lugs: statically determinate, every number of the
    chain by hand (offshore defaults, no rigging, CG envelope +-0.5 m along x)."""
    text = """
name = "three cranes by hand"
[body]
weight = 904.0
cog = [35.86, -6.0, 2.5]
[[candidates]]
name = "P1"
at = [16.2, 0.0, 6.0]
[[candidates]]
name = "P2"
at = [16.2, -12.0, 6.0]
[[candidates]]
name = "P3"
at = [65.6, -6.0, 6.0]
[plan]
cranes = 3
tolerance = { heel = 2.0, trim = 2.0 }
cog_tolerance = [0.5, 0.0, 0.0]
[crane]
EA = 50000.0
rope_length = 30.0
swl = 700.0
"""
    result = plan(loads_problem(text))
    p3 = {c.lug: c for c in result.capacity}["P3"]
    # level, nominal CG: moments about the P1-P2 line, T3 = W (35.86 - 16.2) / (65.6 - 16.2)
    assert_allclose(p3.nominal, W * 19.66 / 49.4, **EXACT)
    # the rules' tilt per direction: about the horizontal axis at psi the body tilts by the
    # worse of 3 deg (one vessel) and asin(1 m / s(psi)), s the hooks' extent along the tilt;
    # T3 is W x (the CG's plan distance from the turned P1-P2 line) / (P3's), CG 0.5 m forward.
    tilt_share = _three_hook_tilt_share(
        W, [(16.2, 0.0, 6.0), (16.2, -12.0, 6.0), (65.6, -6.0, 6.0)], (35.86 + 0.5, -6.0, 2.5), 3.0, 1.0
    )
    assert_allclose(p3.tilt.load, tilt_share, rtol=1e-8)  # both maximise over psi to ~1e-9 deg
    assert_allclose(p3.skew, 1.0, rtol=0, atol=1e-9)  # three ropes: determinate, no skew
    daf = 1.20  # Table 5-1 offshore (the default), 949.2 t design weight
    static = tilt_share * 1.05
    assert_allclose(p3.design.static_hook_load, static, rtol=1e-9)
    assert_allclose(p3.design_hook_load, static * daf, rtol=1e-9)
    assert_allclose(p3.utilisation, static * daf / 700.0, rtol=1e-9)
    # code margin, 3 cranes 33 %: (T3 x 1.05) x 1.33 <= 700
    assert_allclose(p3.design.code_margin.value, W * 19.66 / 49.4 * 1.05 * 1.33, **EXACT)
    assert all(c.ok for c in result.checks)


@pytest.mark.parametrize("name", list(STATIC))
def test_fleet_design_hook_loads_equal_the_hand_calculation(fleet_plan, name):
    c = _by_crane(fleet_plan)[name]
    nominal, worst, tilt, skew = STATIC[name]
    assert_allclose([c.nominal, c.worst, c.tilt.load], [nominal, worst, tilt], rtol=0, atol=0.005)
    assert_allclose(c.skew, skew, rtol=0, atol=5e-5)
    # 4 hooks: indeterminate, the computed skew acts on the hook load; one sling per hook: no yaw
    static = max(worst, tilt) * CONTINGENCY * skew + RIGGING[name]
    assert_allclose(c.design.static_hook_load, static, **PRINTED)
    assert_allclose(c.design_hook_load, static * DAF, **PRINTED)
    # C: 177.33 x 1.05 x 1 + 4 = 190.20 t, x 1.1 = 209.22 t <= 371.6 t
    assert c.design.check.ok == (static * DAF <= SWL[name])
    assert c.design.check.ok
    assert_allclose(c.design.code_margin.value, (nominal * CONTINGENCY + RIGGING[name]) * 1.5, **PRINTED)


def test_fleet_checks_and_exit_code(tmp_path):
    out = run("plan", str(FLEET), "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["checks"] and all(c["ok"] for c in data["checks"])
    # the 800 t / 400 t classes of the first draft of this example: by the rules' limits no
    # set and assignment can lift her; the reason counts the causes
    weak = (
        FLEET.read_text(encoding="utf-8")
        .replace(
            "[[20.0, 1000.0], [30.0, 750.0], [40.0, 525.0], [50.0, 375.0]]",
            "[[20.0, 800.0], [30.0, 600.0], [40.0, 420.0], [50.0, 300.0]]",
        )
        .replace(
            "[[15.0, 600.0], [25.0, 450.0], [32.0, 330.0]]", "[[15.0, 400.0], [25.0, 300.0], [32.0, 220.0]]"
        )
    )
    path = tmp_path / "weak.toml"
    path.write_text(weak, encoding="utf-8")
    out = run("plan", str(path))
    assert out.returncode == 1 and "code margin" in out.stderr and "DAF" in out.stderr


# -- one utilisation in every output -------------------------------------------------------------
def test_one_utilisation_in_json_console_ranking_and_report(fleet_plan):
    data = json.loads(json.dumps(fleet_plan.to_json()))
    design = {c["crane"]: c for c in data["design_loads"]["cranes"]}
    for row in data["capacity"]:
        chain = design[row["crane"]]
        assert row["utilisation"] == chain["utilisation"] == chain["design_hook_load"] / row["swl"]
        assert row["design_hook_load"] == chain["design_hook_load"]
    # the contract's utilisation stays nominal T / SWL
    for label, value in data["utilisation"].items():
        assert value == data["tensions"][label] / data["swl"][label]
    highest = max(r["utilisation"] for r in data["capacity"])
    assert data["ranking"][0]["design_utilisation"] == highest
    assert "max_utilisation" not in data["ranking"][0]  # named for what it is now
    assert data["ranking"][0]["highest_in_box_load_over_swl"] < highest
    table = plan_table(fleet_plan)
    page = html.unescape(render_html(fleet_plan))
    for row in data["capacity"]:
        shown = f"{100 * row['utilisation']:.1f}"
        assert shown in table and f"<td>{shown}</td>" in page
    assert f"{100 * highest:.1f}" in table  # the ranking's figure


# -- every worst case names its scenario, in the file's frame ------------------------------------
def test_worst_cases_carry_their_cg_position_in_the_file_frame(fleet_plan):
    data = fleet_plan.to_json()
    assert data["frame"] == "choi"
    cog = np.array([35.86, 2.5, 6.0])  # the file's CG (papers' frame)
    worst = data["worst_attitude"]
    assert worst["frame"] == "choi"
    assert_allclose(worst["cog"], cog + np.array(worst["cog_offset"]), rtol=0, atol=1e-12)
    # the offset is in the file's frame: back to z-up it is the search's scenario's
    assert_allclose(choi_to_zup(worst["cog_offset"]), fleet_plan.chosen.worst.cog_offset, atol=1e-12)
    for entry in data["ranking"]:
        assert set(entry["worst_attitude"]) == {"heel", "trim", "cog_offset", "cog", "frame"}
    for row, crane in zip(data["capacity"], fleet_plan.capacity):
        at = row["worst_at"]
        # the scenario named is where the worst occurs: the held tensions there give it
        offset = choi_to_zup(at["cog_offset"])
        # the held tensions there plus the hook errors' worst (+-hook_tolerance per hook)
        lugset = fleet_plan.lugset
        tensions, gain = lugset.tensions_and_gain(
            fleet_plan.chosen.preload, [Scenario(at["heel"], at["trim"], tuple(offset))]
        )
        value = tensions[0] + np.abs(gain[0]) @ lugset.hook_tolerance
        assert_allclose(value[fleet_plan.labels.index(row["lug"])], row["worst"], rtol=1e-12)
        assert_allclose(at["cog"], cog + np.array(at["cog_offset"]), atol=1e-12)
        assert row["tilt_at"]["frame"] == "choi" and len(row["tilt_at"]["axis"]) == 3
        assert crane.worst == row["worst"]
    table = plan_table(fleet_plan)
    x, y, z = worst["cog"]
    assert f"CG ({x:.2f}, {y:.2f}, {z:.2f}) m" in table
    assert table.count("coordinates: the file's frame") == 1


# -- [rules] in files ------------------------------------------------------------------------------
def test_rules_are_read_from_the_planning_file():
    rules = load_problem(FLEET).rules
    assert rules == Rules(
        location="inshore",
        separate_vessels=True,
        weight_contingency=1.05,
        rigging_weight=RIGGING,
        yaw_factor=1.05,
        consequence_factor=1.30,
        lateral_fraction=0.05,
        chart_includes_dynamics=False,
    )
    assert load_problem(EXAMPLES / "tanker_plan.toml").rules == Rules()  # no [rules]: defaults


@pytest.mark.parametrize(
    ("rules", "message"),
    [
        ("daf = 0.9", "rules.daf = 0.9: expected a finite factor >= 1"),
        ('rigging_weight = { "Sheerleg Z" = 5.0 }', "rules.rigging_weight.Sheerleg Z: no such crane"),
        ('locaton = "inshore"', "rules.locaton"),
    ],
)
def test_bad_rules_are_one_line_errors(rules, message):
    text = FLEET.read_text(encoding="utf-8")
    head = text[: text.index("\n[rules]")]
    with pytest.raises(InvalidScene, match=message.replace(".", r"\.")) as err:
        loads_problem(head + "[rules]\n" + rules + "\n")
    assert "\n" not in str(err.value)


def test_a_plain_scene_with_rules_is_refused():
    text = (EXAMPLES / "tanker_upright.toml").read_text(encoding="utf-8")
    text += '\n[rules]\nlocation = "inshore"\n'
    with pytest.raises(InvalidScene, match=r"\[rules\]: this is a planning scene"):
        loads_scene(text)


# -- lug capacity and the missing CoG factor -----------------------------------------------------
def test_lug_capacity_gives_a_lug_design_load_check(fleet_plan):
    problem = fleet_plan.problem
    candidates = tuple(
        dataclasses.replace(c, capacity=350.0) if c.name == "BH4-P" else c for c in problem.candidates
    )
    design = DesignBuilder(dataclasses.replace(problem, candidates=candidates)).build(
        fleet_plan.chosen, fleet_plan.labels
    )
    checks = [c for c in design.checks if c.name == "lug_design_load"]
    assert [c.subject for c in checks] == ["BH4-P"]
    crane = design.crane("L2")
    # vertical rope (90 deg): max(worst, tilt) x 1.05 x DAF x skew x yaw 1, x consequence 1.30
    expected = max(crane.worst, crane.tilt.load) * CONTINGENCY * DAF * crane.skew * 1.30
    assert_allclose(checks[0].value, expected, rtol=1e-12)  # 1.30 x 576.3 = 749 t > 350 t
    assert not checks[0].ok and checks[0].limit == 350.0


def test_no_cog_envelope_needs_a_cog_factor(fleet_plan):
    bare = dataclasses.replace(fleet_plan.problem, cog_envelope=CogEnvelope())
    design = DesignBuilder(bare).build(fleet_plan.chosen, fleet_plan.labels)
    assert design.chain is None and "rules.cog_factor: missing" in design.missing
    [check] = design.checks
    assert not check.ok and check.name == "design_loads"
    rules = dataclasses.replace(bare.rules, cog_factor=1.03)
    design = DesignBuilder(dataclasses.replace(bare, rules=rules)).build(fleet_plan.chosen, fleet_plan.labels)
    factor = {f.name: f.value for f in design.crane("L1").design.factors}
    assert factor["cog"] == 1.03


def test_without_a_breakout_case_the_chain_input_is_the_box_worst(fleet_plan):
    """No ``breakout_scene``: no breakout checks or JSON key; the static input is the box worst."""
    design = fleet_plan.design_loads
    assert design.breakout is None and fleet_plan.problem.breakout is None
    for c in design.cranes:
        assert c.breakout is None and c.governs == "box"
        assert c.static_input == max(c.worst, c.nominal) == c.design.worst
        assert c.static_note.endswith("(no breakout case)")
    assert not any(c.name.startswith("breakout") for c in fleet_plan.checks)
    assert "breakout" not in fleet_plan.to_json()
