"""Issue 29 item 13, what the fuzzing run left: absurd but valid inputs refused in one line
(exit 2) or warned about, before any long computation, and error paths kept to one line."""

import logging
import warnings

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model.errors import InvalidScene, LiftPlanError
from liftplan.planner import cli
from liftplan.planner.cli import main
from liftplan.planner.plans import held

LIFT = EXAMPLES / "sunken_block_lift.toml"
TANKER_PLAN = EXAMPLES / "tanker_plan.toml"


def one_error_line(err):
    lines = err.strip().splitlines()
    return len(lines) == 1 and lines[0].startswith("liftplan: error:") and "Traceback" not in err


# lift --to 1e308 and --step 5e-324: tests/cli/test_json_output.py


def test_top_beyond_the_lug_sets_is_refused_with_the_count(capsys, monkeypatch):
    def no_search(*args, **kwargs):
        raise AssertionError("the search ran (it took 214 s): --top should be refused first")

    monkeypatch.setattr(held, "search", no_search)
    assert main(["plan", str(TANKER_PLAN), "--top", "1000000000"]) == 2
    err = capsys.readouterr().err
    assert one_error_line(err)
    assert "--top 1000000000: more than the 1820 lug sets there are to rank" in err
    assert "expected at most 1820" in err


@pytest.mark.parametrize(
    "args, fragment",
    [
        (["plan", str(TANKER_PLAN), "--report", ""], "--report '': expected a path"),
        (["lift", str(LIFT), "--figure", ""], "--figure '': expected a path"),
    ],
)
def test_empty_output_paths_are_refused(capsys, args, fragment):
    # was: --report '' wrote no report and --figure '' the default figure, without a word
    assert main(args) == 2
    err = capsys.readouterr().err
    assert one_error_line(err) and fragment in err


def study(tmp_path):
    (tmp_path / "tanker_plan.toml").write_text(TANKER_PLAN.read_text())
    path = tmp_path / "study.toml"
    path.write_text('[study]\nproblem = "tanker_plan.toml"\nkind = "check"\n')
    return path


def test_more_workers_than_cores_warn_and_run_one_per_core(tmp_path, capsys, monkeypatch):
    import liftplan.planner.batch.run as batch

    asked = {}

    def run_study(study, **options):
        asked.update(options)
        raise LiftPlanError("stopped here")

    monkeypatch.setattr(batch, "run_study", run_study)
    monkeypatch.setattr(cli, "_cores", lambda: 2)
    assert main(["batch", str(study(tmp_path)), "--workers", "200"]) == 2
    assert asked["workers"] == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0] == (
        "liftplan: warning: --workers 200: more than the 2 cores this process may use; running 2 "
        "(more workers than cores add memory and start-up, not speed)"
    )


def test_unreachable_scheduler_is_refused_before_the_base_plan(tmp_path, capsys, monkeypatch):
    import liftplan.planner.batch.run as batch

    def no_plan(problem):
        raise AssertionError("the base plan was computed before the scheduler was probed")

    monkeypatch.setattr(batch, "plan", no_plan)
    path = study(tmp_path)
    assert main(["batch", str(path), "--scheduler", "inproc://x"]) == 2
    err = capsys.readouterr().err
    assert one_error_line(err) and "--scheduler inproc://x: an inproc:// scheduler lives inside" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.toml", "tanker_plan.toml"]  # no journal


def test_numpy_warnings_leave_error_messages_one_line(capsys, monkeypatch):
    def overflowing(args):
        np.float64(1e308) * 10.0  # RuntimeWarning: overflow encountered
        warnings.warn("invalid value encountered in divide", RuntimeWarning, stacklevel=1)
        raise InvalidScene("the one line")

    monkeypatch.setattr(cli, "_solve", overflowing)
    assert main(["solve", "scene.toml"]) == 2
    assert capsys.readouterr().err == "liftplan: error: the one line\n"


def test_dask_is_quiet_while_a_cluster_closes():
    from dask.distributed import Client

    from liftplan.planner.batch.run import DASK_LOGGERS, _quiet_close

    before = {name: logging.getLogger(name).level for name in DASK_LOGGERS}
    with (
        _quiet_close() as quiet,
        Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=":0") as client,
    ):
        quiet(client)
        assert all(logging.getLogger(name).level == logging.CRITICAL for name in DASK_LOGGERS)
    assert {name: logging.getLogger(name).level for name in DASK_LOGGERS} == before


@pytest.mark.parametrize(
    "command, name, kind",
    [
        ("solve", "block_turnover.toml", "a scene file"),
        ("view", "block_turnover.toml", "a scene file"),
        ("plan", "block_turnover.toml", "a planning file"),
        ("plan", "block_turnover_plan.toml", "a planning file"),
    ],
)
def test_a_sequence_file_is_sent_to_liftplan_sequence(capsys, command, name, kind):
    # was: "this is a planning scene (candidates, not fixed lugs)" for solve / view, and
    # "candidates[0].normal: unknown key" for plan on a sequence with lug planning
    assert main([command, str(EXAMPLES / name)]) == 2
    err = capsys.readouterr().err
    assert one_error_line(err)
    assert f"[[stages]]: this is a lift sequence file, not {kind}" in err
    assert "expected `liftplan sequence FILE`" in err
