"""Many ropes end to end: the 64-point hull through ``solve`` (three models), the batch check
of a 26-rope plan against direct ``solve`` calls, and the plan report at 26 and 64 ropes.

Tolerances: a solve is accepted only with a statics residual within 1e-9 W, so 1e-9 W is
what the models promise (they reach ~1e-12 W). The batch check evaluates the held model in
one batched casadi call; the direct solve reaches the same state through the forward elastic
model with the hooks moved (a Newton solve to 1e-9 W): 1e-6 t between the two is round-off
in either, far below anything a rigger reads (0.01 t).
"""

import csv
import json
import logging
import math
import shutil
import subprocess
import sys

import numpy as np
import pytest
from helpers import EXAMPLES
from numpy.testing import assert_allclose
from support.many_points_peer import rotation

from liftplan.model import load_scene, solve

SCENE64 = EXAMPLES / "hull154_64_points.toml"
MODELS = ["elastic", "paper-elastic", "rigid"]


def run(*args):
    return subprocess.run(
        [sys.executable, "-m", "liftplan.planner.cli", *map(str, args)],
        capture_output=True,
        text=True,
        timeout=120,
    )


# -- 64 ropes through solve ------------------------------------------------------------------
@pytest.mark.parametrize("model", MODELS)
def test_64_point_example_on_the_command_line(model):
    scene = load_scene(SCENE64)
    out = run("solve", SCENE64, "--model", model, "--json")
    assert out.returncode == 0, out.stderr
    result = json.loads(out.stdout)
    tensions = np.array([result["tensions"][name] for name in scene.lug_names])
    assert len(tensions) == 64 and np.all(tensions > 0)
    assert tensions.sum() == pytest.approx(scene.body.weight, abs=1e-9 * scene.body.weight)
    assert all(c["ok"] for c in result["checks"])
    console = run("solve", SCENE64, "--model", model)
    assert console.returncode == 0, console.stderr
    lines = console.stdout.splitlines()
    # one line per station (32), port beside starboard, not 64 rows
    assert any("port" in line and "starboard" in line for line in lines)
    rows = [
        line
        for line in lines
        if line.split()[:1]
        and line.split()[1:2]
        and line.split()[1].startswith("P")
        and line.split()[1][1:].isdigit()
    ]
    assert len(rows) == 32 and all(f"S{k:02d}" in row for k, row in enumerate(rows, start=1))
    assert max(len(line) for line in lines) <= 160


def test_64_elastic_equals_paper_elastic_at_its_own_pose():
    """Equal jacks and cables, coplanar lugs: at the elastic pose both models' tensions are
    affine in the lugs' plan coordinates and close the same three statics equations, so they
    are the same tensions. (paper-elastic's stretched length differs from rope to rope by the
    pose's lug heights, 0.2 m in 110 m: 1e-5 W allows for that; measured 1.0e-6 W.)"""
    scene = load_scene(SCENE64)
    elastic = solve(scene)
    pose = elastic.pose
    paper = solve(
        scene.with_attitude(heel=pose.heel, trim=pose.trim, lift_height=pose.lift_height),
        model="paper-elastic",
    )
    ours, theirs = (np.array([eq.tensions[n] for n in scene.lug_names]) for eq in (elastic, paper))
    assert_allclose(ours, theirs, atol=1e-5 * scene.body.weight)
    assert elastic.residual <= 1e-9 * scene.body.weight


def test_64_rigid_against_numpy_compatibility_solve():
    """rigid with 61 held tensions = numpy's full 64 x 64 solve of [statics; held rows]
    (the model solves the 3 x 3 of the free lugs), and the free lugs are the three named."""
    scene = load_scene(SCENE64)
    eq = solve(scene, model="rigid")
    names = scene.lug_names
    lugs = np.array([lug.at for lug in scene.lugs])
    held = {r.lug: r.tension for r in scene.analysis.redundant}
    assert set(names) - set(held) == {"P01", "P32", "S16"}
    a = np.vstack([np.ones(64), lugs[:, 0], lugs[:, 1]])  # level: world plan = body plan
    rows = np.array([[1.0 if name == lug else 0.0 for name in names] for lug in held])
    lhs = np.vstack([a, rows])
    rhs = np.r_[scene.body.weight * np.array([1.0, *scene.body.cog[:2]]), list(held.values())]
    expected = np.linalg.solve(lhs, rhs)
    assert_allclose([eq.tensions[n] for n in names], expected, atol=1e-9 * scene.body.weight)


# -- the batch check at 26 ropes against direct solves -----------------------------------------
CHECK_STUDY = """
[study]
problem = "hull154_26_given.toml"
kind = "check"
output = "check26.csv"
grid = 3

[sweep]
"plan.tolerance.heel" = [0.5, 2.0]

[sample]
count = 6
seed = 4
weight = [0.9, 1.1]
cog = [2.0, 0.5, 0.5]
"""


@pytest.fixture(scope="module")
def checked26(tmp_path_factory):
    from dask.distributed import Client, LocalCluster

    from liftplan.planner import load_problem, plan
    from liftplan.planner.batch.run import run_study
    from liftplan.planner.batch.study import load_study

    folder = tmp_path_factory.mktemp("check26")
    shutil.copy(EXAMPLES / "hull154_26_given.toml", folder)
    (folder / "study.toml").write_text(CHECK_STUDY, encoding="utf-8")
    with (
        LocalCluster(
            n_workers=1,
            threads_per_worker=1,
            processes=False,
            dashboard_address=":0",
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as client,
    ):
        summary = run_study(load_study(folder / "study.toml"), client=client, progress=False)
    with open(folder / "check26.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    return summary, rows, plan(load_problem(folder / "hull154_26_given.toml"))


def held_by_direct_solve(base, weight, cog, heel, trim):
    """The plan held at (heel, trim) for this weight and CG, by ``solve``: the hook heights
    moved by a rigid-body motion a + b x + c y (which keeps the preload; coplanar lugs) found
    by numpy from the statics at that pose, then the forward elastic model solved with them.

    Returns the tensions [t] in the plan's rope order and the pose found."""
    scene = base.scene
    crane = {c.lug: c for c in scene.cranes}
    names = scene.lug_names
    lugs = np.array([lug.at for lug in scene.lugs])
    k = np.array([crane[n].EA / crane[n].rope_length for n in names])  # t/m
    free = np.array([crane[n].boom_height - crane[n].rope_length for n in names])  # m
    r = rotation(math.radians(heel), math.radians(trim), math.radians(scene.attitude.yaw))
    world = lugs @ r.T
    g = r @ np.asarray(cog)
    base_t = k * (free - scene.attitude.lift_height - world[:, 2])
    basis = np.column_stack([np.ones(len(names)), lugs[:, 0], lugs[:, 1]])  # dh = basis @ (a, b, c)
    statics = np.vstack([np.ones(len(names)), world[:, 0], world[:, 1]])
    coef = np.linalg.solve(
        statics @ (k[:, None] * basis), weight * np.array([1.0, g[0], g[1]]) - statics @ base_t
    )
    dh = basis @ coef
    moved = scene.with_body(weight=weight, cog=tuple(cog))
    for name, shift in zip(names, dh):
        moved = moved.with_crane(name, boom_height=crane[name].boom_height + shift)
    eq = solve(moved)
    return np.array([eq.tensions[n] for n in names]), eq.pose


def test_batch_check_26_rows_equal_direct_solves(checked26):
    summary, rows, base = checked26
    assert summary.ran == 12 and summary.counts == {"ok": 12}
    assert len(rows) == 12 and all(r["status"] == "ok" for r in rows)
    trim_tolerance = base.problem.trim_tolerance
    for row in rows[::5]:  # three cases across both sweep points
        weight = float(row["body.weight"])
        cog = [float(row[f"body.cog.{a}"]) for a in "xyz"]
        heel_tolerance = float(row["plan.tolerance.heel"])
        spreads, low, high = [], np.inf, -np.inf
        for heel in (-heel_tolerance, 0.0, heel_tolerance):
            for trim in (-trim_tolerance, 0.0, trim_tolerance):
                tensions, pose = held_by_direct_solve(base, weight, cog, heel, trim)
                assert pose.heel == pytest.approx(heel, abs=1e-7)
                assert pose.trim == pytest.approx(trim, abs=1e-7)
                spreads.append((np.ptp(tensions), heel, trim))
                low, high = min(low, tensions.min()), max(high, tensions.max())
        worst = max(spreads)
        assert float(row["worst_spread"]) == pytest.approx(worst[0], abs=1e-6)
        assert (float(row["worst_heel"]), float(row["worst_trim"])) == (worst[1], worst[2])
        assert float(row["min_tension"]) == pytest.approx(low, abs=1e-6)
        assert float(row["max_tension"]) == pytest.approx(high, abs=1e-6)
        assert float(row["utilisation"]) == pytest.approx(high / 900.0, abs=1e-9)


def test_batch_check_26_reason_names_rope_and_lug(checked26):
    from liftplan.planner.batch.check import CheckCases, check_plan

    _, _, base = checked26
    problem, chosen = base.problem, base.chosen
    cog = np.array(problem.body.cog)
    result = check_plan(
        problem,
        chosen.indices,
        chosen.preload,
        CheckCases(np.array([9000.0]), cog[None, :], np.array([1.0]), np.array([0.5]), np.array([300.0])),
    )
    assert result.status == ["unsafe"]
    label = result.reason[0].split()[1]
    lug = base.lugs[label]
    assert (
        result.reason[0].startswith(f"rope {label} ({lug}) ")
        and "below min_tension 300 t" in result.reason[0]
    )


# -- the report at 26 and 64 ropes ------------------------------------------------------------
def printed_report(name, tmp_path):
    """The plan report of hull154_<name>_given.toml as PDF pages (PNG) and their text."""
    from support.pdf import render

    from liftplan.planner import load_problem, plan
    from liftplan.planner.output.report.write import write_report

    result = plan(load_problem(EXAMPLES / f"hull154_{name}_given.toml"))
    files = write_report(result, tmp_path)
    assert files.pdf is not None
    images, texts = render(files.pdf, tmp_path)
    return result, files, images, texts


def assert_within_the_page(images, name):
    from support.pdf import A4_WIDTH_MM, EDGE_MM, ink_extent_mm

    from liftplan.planner.output.report.page import MARGINS_MM

    _, right, _, left = MARGINS_MM
    for k, png in enumerate(images, start=1):
        first, last = ink_extent_mm(png)
        assert last <= A4_WIDTH_MM - right + EDGE_MM, f"{name} page {k}: ink at {last:.1f} mm"
        assert first >= left - EDGE_MM, f"{name} page {k}: ink at {first:.1f} mm"


def labels_overlap(fig):
    """Pairs of text labels on the figure's axes whose boxes overlap (drawn at print size)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    boxes = [
        (t.get_text(), t.get_window_extent(renderer))
        for ax in fig.axes
        for t in ax.texts
        if t.get_visible() and t.get_text()
    ]
    assert len(boxes) >= 4, "the figure names nothing: the overlap test would be empty"
    return [(a, b) for i, (a, box) in enumerate(boxes) for b, other in boxes[i + 1 :] if box.overlaps(other)]


def needs_pdf():
    from support.pdf import missing

    if missing():
        pytest.skip(missing())


@pytest.mark.slow  # 8-12 s: the default run keeps under 10 minutes
def test_report_26_ropes_within_the_page(tmp_path):
    needs_pdf()
    result, files, images, texts = printed_report("26", tmp_path)
    assert_within_the_page(images, "26 ropes")
    text = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "crane 1 to crane 26 (26 alike)" in text  # the fleet in one row
    assert "(25 to 26 of 26)" in text  # per-rope tables split in parts of 8
    from liftplan.planner.output.figures import plan as figures

    assert labels_overlap(figures.plan_view(result)) == []
    assert labels_overlap(figures.tension_curves(result)) == []


@pytest.mark.slow  # the 64-rope plan takes ~30 s (its held model over the box and CG envelope)
def test_report_64_ropes_builds_within_the_page(tmp_path):
    needs_pdf()
    result, files, images, texts = printed_report("64", tmp_path)
    assert len(result.labels) == 64
    assert_within_the_page(images, "64 ropes")
    text = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "crane 1 to crane 64 (64 alike)" in text
    assert "(57 to 64 of 64)" in text
    assert len(images) <= 32  # measured 28; was 30 with the fleet at one row per crane
    from liftplan.planner.output.figures import plan as figures

    view = figures.plan_view(result)
    assert labels_overlap(view) == []
    assert "names left out" in view.axes[0].get_title()
    assert labels_overlap(figures.tension_curves(result)) == []
