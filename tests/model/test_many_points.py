"""Many lifting points: 26 and 64 ropes through ``solve`` (elastic, paper-elastic, rigid),
checked against independent peers, invariance, the one-line errors, the command line and
the grouped console rows.

Tolerances: every answer is accepted by the model only with a statics residual within
1e-9 W, so 1e-9 W is what the models promise; the peers (numpy/scipy written from the
physics in ``many_points_peer.py``, and MoorPy) and the models both reach ~1e-13 W here, so
a failure means a real difference, not round-off. Invariance: the same sums in another order,
1e-9 relative.
"""

import dataclasses
import json
import subprocess
import sys

import numpy as np
import pytest
from helpers import EXAMPLES
from numpy.testing import assert_allclose
from support.many_points_peer import (
    free_three,
    held_scene,
    hull_scene,
    numpy_elastic,
    numpy_paper_elastic,
    numpy_rigid,
)

from liftplan.model import Body, InvalidScene, Lug, Redundant, load_scene, paper_elastic_tensions, solve
from liftplan.model.statics.model import rope_model
from liftplan.model.statics.vertical import solve_elastic
from liftplan.planner.output.console.rope_table import rope_rows, stations

EXAMPLE = EXAMPLES / "hull154_26_points.toml"


def values(eq, scene):
    return np.array([eq.tensions[name] for name in scene.lug_names])


def tilted(scene):
    """A heeled, trimmed attitude for the given-attitude models."""
    return scene.with_attitude(heel=1.5, trim=-0.8, lift_height=0.3)


@pytest.fixture(scope="module")
def hull26():
    return hull_scene(13, seed=1)


@pytest.fixture(scope="module")
def hull64():
    return hull_scene(32, seed=2)


# -- the example -----------------------------------------------------------------------------
def test_example_is_the_26_point_builder():
    """The file and the code that builds its 64-point variant describe the same hull."""
    from_file, built = load_scene(EXAMPLE), hull_scene(13)
    assert from_file.lugs == built.lugs
    assert from_file.cranes == built.cranes
    assert from_file.body == built.body
    held = {r.lug for r in from_file.analysis.redundant}
    assert len(held) == 23 and set(from_file.lug_names) - held == free_three(from_file)


@pytest.mark.parametrize("model", ["elastic", "paper-elastic", "rigid"])
def test_example_on_the_command_line(model):
    out = subprocess.run(
        [sys.executable, "-m", "liftplan.planner.cli", "solve", str(EXAMPLE), "--model", model, "--json"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["model"] == model and data["converged"] is True and len(data["tensions"]) == 26
    # the sum of the tensions is the weight (1e-9 W: the acceptance)
    assert sum(data["tensions"].values()) == pytest.approx(9000.0, abs=9e-6)
    assert data["slack"] == []


# -- accuracy against independent peers ---------------------------------------------------
@pytest.mark.parametrize(
    ("per_side", "seed"), [(13, None), (13, 1), (32, 2)], ids=["26 even", "26 uneven", "64 uneven"]
)
def test_elastic_against_scipy(per_side, seed):
    scene = hull_scene(per_side, seed)
    eq = solve(scene, model="elastic")
    x, theirs, residual = numpy_elastic(scene)
    assert residual < 1e-12  # the peer itself converged
    weight = scene.body.weight
    assert_allclose(values(eq, scene), theirs, rtol=0, atol=1e-9 * weight)
    # the pose, to the accuracy the tensions give it: dT = k dh, k ~ 1.5e3 t/m, so 1e-9 W of
    # tension is ~6e-9 m of height, ~1e-10 rad over the lugs' 66 m half-span
    assert eq.pose.lift_height == pytest.approx(x[0], abs=1e-8)
    assert np.radians(eq.pose.heel) == pytest.approx(x[1], abs=1e-9)
    assert np.radians(eq.pose.trim) == pytest.approx(x[2], abs=1e-9)
    assert eq.slack == ()


def test_elastic_slack_rope_against_scipy(hull26):
    """Two cables 0.6 m too long (the stretch is ~0.24 m): they hang slack, the rest carry W."""
    scene = hull26.with_crane("P07", rope_length=110.4).with_crane("S02", rope_length=110.4)
    eq = solve(scene, model="elastic")
    _, theirs, residual = numpy_elastic(scene)
    assert residual < 1e-12
    assert_allclose(values(eq, scene), theirs, rtol=0, atol=1e-9 * scene.body.weight)
    assert eq.slack == ("P07", "S02")
    assert eq.tensions["P07"] == 0.0 and eq.tensions["S02"] == 0.0


def test_energy_fallback_equals_newton_at_64(hull64):
    """IPOPT on the potential energy (polished by Newton) lands on Newton's answer."""
    newton = solve_elastic(hull64, method="newton")
    energy = solve_elastic(hull64, method="energy")
    assert energy.solver.method == "energy"
    assert_allclose(values(energy, hull64), values(newton, hull64), rtol=0, atol=1e-9 * hull64.body.weight)


def test_elastic_against_moorpy_26(hull26):
    from support.moorpy_peer import moorpy_solve

    eq = solve(hull26, model="elastic")
    theirs, _ = moorpy_solve(hull26, eq.pose.heel, eq.pose.trim, eq.pose.lift_height)
    # MoorPy's lines weigh 1e-9 t/m and it stops at 1e-10 m: ~1e-9 relative (test_moorpy.py)
    assert_allclose(values(eq, hull26), theirs, rtol=1e-6, atol=1e-6 * hull26.body.weight)


@pytest.mark.slow
def test_elastic_against_moorpy_64(hull64):
    from support.moorpy_peer import moorpy_solve

    eq = solve(hull64, model="elastic")
    theirs, _ = moorpy_solve(hull64, eq.pose.heel, eq.pose.trim, eq.pose.lift_height)
    assert_allclose(values(eq, hull64), theirs, rtol=1e-6, atol=1e-6 * hull64.body.weight)


@pytest.mark.parametrize("fixture", ["hull26", "hull64"])
def test_paper_elastic_against_least_squares(fixture, request):
    scene = tilted(request.getfixturevalue(fixture))
    eq = solve(scene, model="paper-elastic")
    assert_allclose(values(eq, scene), numpy_paper_elastic(scene), rtol=0, atol=1e-9 * scene.body.weight)


@pytest.mark.parametrize("fixture", ["hull26", "hull64"])
def test_rigid_against_numpy_statics(fixture, request):
    """n - 3 = 23 or 61 held tensions; the three free ones from the statics."""
    scene = tilted(request.getfixturevalue(fixture))
    rng = np.random.default_rng(7)
    held = {name: float(rng.uniform(100.0, 160.0)) for name in scene.lug_names}
    scene = held_scene(scene, held)
    eq = solve(scene)
    assert eq.model == "rigid"
    assert_allclose(values(eq, scene), numpy_rigid(scene), rtol=0, atol=1e-9 * scene.body.weight)
    for red in scene.analysis.redundant:  # the held ones exactly as given
        assert eq.tensions[red.lug] == red.tension


def test_rigid_holding_paper_elastic_tensions_gives_them_back(hull64):
    """Holding 61 ropes at the paper-elastic answer, the three free ones take its values too."""
    scene = tilted(hull64)
    paper = solve(scene, model="paper-elastic")
    rigid = solve(held_scene(scene, paper.tensions))
    assert_allclose(values(rigid, scene), values(paper, scene), rtol=0, atol=1e-9 * scene.body.weight)


def test_batched_paper_elastic_at_26(hull26):
    """The compiled batch map (planner screening, batch check) equals single solves."""
    heel, trim = [-1.0, 0.0, 2.0], [0.5, 0.0, -1.5]
    batch = paper_elastic_tensions(hull26, heel=heel, trim=trim)
    for k in range(3):
        one = solve(hull26.with_attitude(heel=heel[k], trim=trim[k]), model="paper-elastic")
        assert_allclose(batch[k], values(one, hull26), rtol=0, atol=1e-9 * hull26.body.weight)


# -- invariance at n = 26 ------------------------------------------------------------------
MODELS = ["elastic", "paper-elastic", "rigid"]


def prepared(scene, model):
    if model == "rigid":
        paper = solve(scene, model="paper-elastic")
        return held_scene(scene, {k: round(t) for k, t in paper.tensions.items()})
    return scene.with_analysis(model=model)


@pytest.mark.parametrize("model", MODELS)
def test_reorder_26(hull26, model):
    scene = prepared(hull26.with_attitude(heel=0.7, trim=-0.4), model)
    order = np.random.default_rng(3).permutation(scene.n)
    shuffled = dataclasses.replace(
        scene, lugs=tuple(scene.lugs[i] for i in order), cranes=tuple(reversed(scene.cranes))
    )
    a, b = solve(scene), solve(shuffled)
    assert list(b.tensions) == [scene.lugs[i].name for i in order]
    assert_allclose([b.tensions[k] for k in a.tensions], list(a.tensions.values()), rtol=1e-9)
    assert b.pose.heel == pytest.approx(a.pose.heel, abs=1e-9)
    assert b.pose.trim == pytest.approx(a.pose.trim, abs=1e-9)


@pytest.mark.parametrize("model", MODELS)
def test_mirror_26(hull26, model):
    """y -> -y: port and starboard swap (P07 <-> S07), heel changes sign."""
    scene = prepared(hull26.with_attitude(heel=0.7, trim=-0.4), model)
    swap = {name: ("S" if name[0] == "P" else "P") + name[1:] for name in scene.lug_names}
    cog = scene.body.cog
    mirrored = dataclasses.replace(
        scene,
        lugs=tuple(Lug(swap[lug.name], (lug.at[0], -lug.at[1], lug.at[2])) for lug in scene.lugs),
        cranes=tuple(dataclasses.replace(c, lug=swap[c.lug]) for c in scene.cranes),
        body=Body(scene.body.weight, (cog[0], -cog[1], cog[2])),
        attitude=dataclasses.replace(scene.attitude, heel=-scene.attitude.heel),
        analysis=dataclasses.replace(
            scene.analysis,
            redundant=tuple(Redundant(swap[r.lug], r.tension) for r in scene.analysis.redundant),
        ),
    )
    a, b = solve(scene), solve(mirrored)
    assert_allclose([b.tensions[swap[k]] for k in a.tensions], list(a.tensions.values()), rtol=1e-9)
    assert b.pose.heel == pytest.approx(-a.pose.heel, abs=1e-9)
    assert b.pose.trim == pytest.approx(a.pose.trim, abs=1e-9)


# -- errors: one line, naming the key, the value and what is expected --------------------
def one_line(err):
    text = str(err.value)
    assert "\n" not in text and len(text) < 300, text
    return text


def test_rigid_wrong_count_of_held_tensions(hull26):
    scene = hull26.with_analysis(model="rigid", redundant=(Redundant("P02", 300.0), Redundant("S05", 300.0)))
    with pytest.raises(InvalidScene) as err:
        solve(scene)
    assert "analysis.redundant: 2 given" in one_line(err) and "n - 3 = 23" in one_line(err)


def test_rigid_lug_held_twice(hull26):
    with pytest.raises(InvalidScene) as err:
        hull26.with_analysis(model="rigid", redundant=(Redundant("P02", 300.0), Redundant("P02", 310.0)))
    assert "analysis.redundant.lug = 'P02': held twice" in one_line(err)


def test_rigid_free_lugs_collinear(hull64):
    """Holding all but three lugs of one row leaves a singular 3x3: named, not a crash."""
    free = {"P01", "P02", "P03"}
    held = tuple(Redundant(name, 140.0) for name in hull64.lug_names if name not in free)
    with pytest.raises(InvalidScene) as err:
        solve(hull64.with_analysis(model="rigid", redundant=held))
    text = one_line(err)
    assert "free lugs P01, P02, P03 are collinear" in text and "and 53 more held" in text


def test_unknown_lug_names_a_short_list(hull64):
    with pytest.raises(InvalidScene) as err:
        hull64.with_analysis(redundant=(Redundant("X99", 1.0),))
    assert "unknown lug, expected one of P01, P02" in one_line(err) and "and 56 more" in one_line(err)


def test_solve_builds_only_what_it_uses():
    """An elastic solve does not build the held-hoist model (its n x n Jacobian is the
    costly part at many ropes)."""
    scene = hull_scene(19)  # n = 38: no other test uses it
    solve(scene, model="elastic")
    model = rope_model(38)
    assert "elastic_solver" in vars(model) and "held" not in vars(model)


# -- console rows grouped by side and station ------------------------------------------------
def test_rope_rows_example():
    scene = load_scene(EXAMPLE)
    eq = solve(scene)
    lines = rope_rows(scene, eq)
    high = max(eq.tensions, key=eq.tensions.get)
    low = min(eq.tensions, key=eq.tensions.get)
    assert (high, low) == ("P01", "S13")  # CG aft and to port
    assert lines[0].startswith(
        f"26 ropes, W = 9000.00 t: tension max {eq.tensions['P01']:.2f} t at P01 (x -66.00 m, port)"
    )
    assert f"min {eq.tensions['S13']:.2f} t at S13 (x 66.00 m, starboard)" in lines[0]
    assert lines[1].startswith(f"utilisation max {100 * eq.tensions['P01'] / 900:.1f} % at P01")
    assert lines[2] == "slack: none"
    rows = [line.split() for line in lines if line[:9].strip().lstrip("-").replace(".", "").isdigit()]
    assert len(rows) == 13  # one line per station, port beside starboard
    for k, row in enumerate(rows):
        assert float(row[0]) == pytest.approx(-66.0 + 11.0 * k)
        assert row[1] == f"P{k + 1:02d}" and row[5] == f"S{k + 1:02d}"
        assert float(row[2]) == pytest.approx(eq.tensions[row[1]], abs=0.005)
        assert float(row[6]) == pytest.approx(eq.tensions[row[5]], abs=0.005)
    total = lines[-1].split()
    port = sum(t for k, t in eq.tensions.items() if k[0] == "P")
    assert float(total[1]) == pytest.approx(port, abs=0.005)
    assert float(total[1]) + float(total[4]) == pytest.approx(9000.0, abs=0.01)
    assert max(len(line) for line in lines[3:]) <= 90


def test_rope_rows_64_flags_and_centre_line(hull64):
    """Slack and over-SWL ropes are flagged and listed; lugs on the centre line get a group;
    two lugs of one side at one station take two lines."""
    extra = (Lug("C1", (0.0, 0.0, 16.0)), Lug("P07b", (hull64.lugs[6].at[0], 9.0, 16.0)))
    cranes = tuple(dataclasses.replace(hull64.cranes[0], lug=lug.name, rope_length=109.7) for lug in extra)
    scene = (
        dataclasses.replace(
            hull64,
            lugs=hull64.lugs + extra,
            cranes=hull64.cranes + cranes,
        )
        .with_crane("S10", rope_length=110.5)
        .with_crane("P20", swl=100.0)
    )
    eq = solve(scene)
    assert eq.slack == ("S10",) and eq.utilisation["P20"] > 1.0
    lines = rope_rows(scene, eq)
    assert lines[1].endswith("over the SWL: P20") and lines[2] == "slack: S10"
    assert "centre line" in lines[4]
    assert lines[-1] == "flags: s: slack, !: over the SWL"
    p20 = next(line for line in lines[6:-2] if " P20 " in line)
    s10 = next(line for line in lines[6:-2] if " S10 " in line)
    assert p20.split()[5] == "!" and s10.rstrip().endswith(" s")
    groups = stations(scene)
    assert len(groups) == 32 + 1  # 32 stations and the centre-line lug at x = 0
    x7, sides = next(g for g in groups if "P07" in g[1]["port"])
    assert sides["port"] == ["P07", "P07b"]  # innermost first
    station_lines = [line for line in lines[6:-2] if line[:9].strip()]
    assert len(station_lines) == 33


def test_rope_rows_refuses_hook_loads(hull26):
    eq = solve(hull26)
    with pytest.raises(ValueError, match="one rope per lug"):
        rope_rows(hull26, dataclasses.replace(eq, tensions={"crane A": 9000.0}))


def test_held_tensions_is_held_without_the_jacobian(hull26):
    """The check's map (no n x n sensitivities) gives the planner's held tensions, bit for bit
    uncompiled at n = 26, and through the compiled column maps at n = 4."""
    from liftplan.model.statics.model import BLOCK
    from liftplan.model.statics.vertical import pack_params

    p = pack_params(hull26, "elastic")
    x = np.array([0.1, np.radians(1.0), np.radians(-0.5)])
    model = rope_model(26)
    full, light = model.held(x, p), model.held_tensions(x, p)
    for k in range(2):
        assert np.array_equal(np.asarray(light[k]), np.asarray(full[k]))
    small = hull_scene(2, seed=4)
    model = rope_model(4)
    columns_x = np.tile(x, BLOCK)
    columns_p = np.tile(pack_params(small, "elastic"), BLOCK)
    t_full, dh_full, _ = model.held_columns(columns_x, columns_p)
    t_light, dh_light = model.held_tensions_columns(columns_x, columns_p)
    # two compiled builds of the same expressions: equal to round-off of the 3x3 solve
    assert_allclose(t_light, t_full, rtol=1e-12, atol=1e-12 * small.body.weight)
    assert_allclose(dh_light, dh_full, rtol=1e-12, atol=1e-12)
