"""Batch studies: a two-worker Dask cluster, one row per case with failed rows and their
reason, resume after an interruption, and the check of a fixed plan against the planner."""

import csv
import dataclasses
import logging
import shutil

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model import Body, InvalidScene, LiftPlanError
from liftplan.planner import load_problem, plan
from liftplan.planner.batch.check import CheckCases, check_plan
from liftplan.planner.batch.run import run_study
from liftplan.planner.batch.study import load_study
from liftplan.planner.cli import main
from liftplan.planner.search.scenarios import LugSet, Scenario

PLAN_STUDY = """
[study]
problem = "tanker_plan.toml"
kind = "plan"
output = "plan_study.csv"

[sweep]
"plan.cranes" = [4, 3]            # 3: infeasible (SWL)
"plan.min_tension" = [0.0, 240.0]  # 4 x 240 t > 904 t: not a valid scene (3 x 240 t is)
"""

CHECK_STUDY = """
[study]
problem = "tanker_plan.toml"
kind = "check"
output = "check_study.csv"
chunk = 40

[sweep]
"plan.tolerance.heel" = [1.0, 2.0]
"body.weight" = [904.0, 1700.0]  # 1700 t: the ropes go over their SWL

[sample]
count = 50
seed = 3
cog = [1.0, 0.3, 0.5]
"""


def study_file(tmp_path, text, name="study.toml"):
    shutil.copy(EXAMPLES / "tanker_plan.toml", tmp_path / "tanker_plan.toml")
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def read_table(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def client():
    """A local Dask cluster of two single-threaded worker processes."""
    from dask.distributed import Client, LocalCluster

    with (
        LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as dask_client,
    ):
        yield dask_client


def test_plan_study_on_two_workers_keeps_failed_rows(tmp_path, client):
    study = load_study(study_file(tmp_path, PLAN_STUDY))
    summary = run_study(study, client=client, progress=False)
    assert summary.cores == 2 and summary.ran == 4
    rows = read_table(tmp_path / "plan_study.csv")
    assert [r["case"] for r in rows] == ["0", "1", "2", "3"]
    assert [r["status"] for r in rows] == ["ok", "invalid", "infeasible", "infeasible"]
    assert summary.counts == {"ok": 1, "infeasible": 2, "invalid": 1}
    assert "crane SWL" in rows[2]["reason"] and "carry more than the weight" in rows[1]["reason"]
    assert rows[2]["worst_spread"] == "" and rows[1]["lugs"] == ""
    # the ok row is the plan of the base scene
    best = plan(load_problem(EXAMPLES / "tanker_plan.toml"))
    assert rows[0]["lugs"] == " ".join(best.chosen.lugs)
    assert float(rows[0]["worst_spread"]) == pytest.approx(best.worst_spread, rel=1e-9)
    assert not (tmp_path / "plan_study.csv.partial").exists()


def test_check_study_on_two_workers(tmp_path, client):
    study = load_study(study_file(tmp_path, CHECK_STUDY))
    assert study.size == 200
    summary = run_study(study, client=client, progress=False)
    rows = read_table(tmp_path / "check_study.csv")
    assert len(rows) == 200 and [int(r["case"]) for r in rows] == list(range(200))
    heavy = [r for r in rows if r["body.weight"] == "1700.0"]
    assert heavy and all(r["status"] == "unsafe" and "over the plan's limit" in r["reason"] for r in heavy)
    light = [r for r in rows if r["body.weight"] == "904.0"]
    assert all(r["status"] == "ok" and r["reason"] == "" for r in light)
    assert sum(summary.counts.values()) == 200
    # the same draws at every grid point (common random numbers)
    assert rows[0]["body.cog.x"] == rows[50]["body.cog.x"] == rows[150]["body.cog.x"]


def test_interrupted_run_resumes_and_gives_the_same_table(tmp_path, client):
    study = load_study(study_file(tmp_path, CHECK_STUDY))
    run_study(study, client=client, progress=False)
    whole = (tmp_path / "check_study.csv").read_text()
    # an interruption: 120 rows in the journal, the last one cut off mid-write
    lines = whole.splitlines(keepends=True)
    journal = tmp_path / "check_study.csv.partial"
    cut = lines[121][: len(lines[121]) // 2]
    journal.write_text(f"# liftplan batch {study.fingerprint}\n" + "".join(lines[:121]) + cut)
    (tmp_path / "check_study.csv").unlink()
    summary = run_study(study, client=client, progress=False)
    assert summary.ran == 80
    assert (tmp_path / "check_study.csv").read_text() == whole
    assert not journal.exists()


def test_journal_of_another_study_is_refused(tmp_path):
    study = load_study(study_file(tmp_path, CHECK_STUDY))
    journal = tmp_path / "check_study.csv.partial"
    journal.write_text("# liftplan batch 0123456789abcdef\ncase\n")
    with pytest.raises(LiftPlanError, match="--restart"):
        run_study(study, progress=False)
    assert journal.exists()  # nothing discarded without --restart


@pytest.mark.parametrize(
    "text, match",
    [
        (PLAN_STUDY.replace('"plan.cranes"', '"plan.cranse"'), "cranse"),
        (
            PLAN_STUDY.replace("[4, 3]", "[4, 3, 65]"),
            r"sweep.'plan.cranes'\[2\] = 65: no case can use it.*3 to 64",
        ),
        (CHECK_STUDY.replace('"body.weight"', '"plan.cranes"'), "a check study keeps the plan's lugs"),
        (PLAN_STUDY.replace("tanker_plan.toml", "missing.toml"), "no such planning file"),
        (CHECK_STUDY.replace("count = 50", "count = 0"), "sample.count"),
        (CHECK_STUDY.replace("cog = [1.0, 0.3, 0.5]", "cog = [1.0, -0.3, 0.5]"), "half-widths"),
        (PLAN_STUDY + '\ncandidates = ["aft"]\n', "sweep.candidates = 'aft'"),
    ],
)
def test_bad_study_files_are_one_line_errors(tmp_path, text, match):
    with pytest.raises(InvalidScene, match=match) as err:
        load_study(study_file(tmp_path, text))
    assert "\n" not in str(err.value)


def test_cli_batch_with_a_local_cluster(tmp_path, capsys):
    path = study_file(tmp_path, CHECK_STUDY)
    assert main(["batch", str(path), "--workers", "2", "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "200 cases" in out and "unsafe" in out and "check_study.csv" in out
    assert main(["batch", str(path), "--workers", "0"]) == 2
    assert "--workers 0" in capsys.readouterr().err
    assert main(["batch", str(path), "--scheduler", "tcp://127.0.0.1:9", "--restart"]) == 2
    assert "cannot connect" in capsys.readouterr().err


# -- the check of a fixed plan ---------------------------------------------------------------
@pytest.fixture(scope="module")
def tanker_plan():
    return plan(load_problem(EXAMPLES / "tanker_plan.toml"))


def cases(problem, weight, cog_offset, tolerance=2.0, min_tension=20.0):
    m = len(weight)
    return CheckCases(
        np.asarray(weight, float),
        np.array(problem.body.cog) + np.asarray(cog_offset),
        np.full(m, tolerance),
        np.full(m, tolerance),
        np.full(m, min_tension),
    )


def test_check_equals_the_plans_held_tensions(tanker_plan):
    problem, chosen = tanker_plan.problem, tanker_plan.chosen
    offset = (0.5, 0.3, -0.2)
    result = check_plan(
        problem, chosen.indices, chosen.preload, cases(problem, [problem.body.weight], [offset]), grid=21
    )
    heel, trim = np.meshgrid(np.linspace(-2, 2, 21), np.linspace(-2, 2, 21), indexing="ij")
    tensions = tanker_plan.tensions_at(heel.ravel(), trim.ravel(), cog_offset=offset)
    assert result.worst_spread[0] == pytest.approx(np.ptp(tensions, axis=1).max(), rel=1e-12)
    assert result.max_tension[0] == pytest.approx(tensions.max(), rel=1e-12)
    # a heavier body: the planner's own model with that weight, same boom heights
    heavy = dataclasses.replace(problem, body=Body(weight=1000.0, cog=problem.body.cog))
    result = check_plan(
        problem, chosen.indices, chosen.preload, cases(problem, [1000.0], [(0, 0, 0)]), grid=3
    )
    box = [Scenario(h, t) for h in (-2, 0, 2) for t in (-2, 0, 2)]
    expected = LugSet(heavy, chosen.indices).tensions(chosen.preload, box)
    assert result.min_tension[0] == pytest.approx(expected.min(), rel=1e-12)
    assert result.max_tension[0] == pytest.approx(expected.max(), rel=1e-12)


def test_check_reports_slack_and_limits_not_numbers(tanker_plan):
    problem, chosen = tanker_plan.problem, tanker_plan.chosen
    result = check_plan(
        problem,
        chosen.indices,
        chosen.preload,
        cases(
            problem,
            [904.0, 904.0, 1700.0, 904.0],
            [(0, 5.9, 20.0), (0, 0, 0), (0, 0, 0), (60.0, 0, 0)],
            min_tension=[20.0, 225.0, 20.0, 20.0],
        ),
    )
    assert result.status == ["failed", "unsafe", "unsafe", "invalid"]
    # a CG 0.1 m inside the edge of the lugs and 16.5 m above them: a rope goes slack in the box
    assert "slack" in result.reason[0] and np.isnan(result.worst_spread[0])
    assert "below min_tension 225 t" in result.reason[1]
    assert (
        "over the plan's limit" in result.reason[2]
        and "chart SWL 400 t" in result.reason[2]
        and result.utilisation[2] > 1.0
    )
    # a CG 60 m forward lies beyond the forward lugs: no scene would accept it
    assert "outside the plan's lugs' support polygon" in result.reason[3]
    assert np.isnan(result.max_tension[3])
