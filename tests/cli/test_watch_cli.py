"""``liftplan watch`` and ``liftplan simulate`` as a user runs them: replay, JSON Lines, bad
readings (a one-line error, exit 2, or a flagged row, exit 4), following a growing file, Ctrl-C."""

import json
import signal
import subprocess
import sys

import pytest
from support.watching import plan_json, tanker_basis

from liftplan.planner.cli import main
from liftplan.planner.watch.handlers import _followed
from liftplan.planner.watch.update import Watcher

HEADER = "time,L1,L2,L3,L4,heel,trim\n"
ROW = "{t},237.5,231.0,221.0,214.5,0.0,0.0\n"


@pytest.fixture(scope="module")
def plan_file(tmp_path_factory):
    return plan_json(tmp_path_factory.mktemp("watch"))


def _watch(capsys, plan_file, path, *extra):
    code = main(["watch", str(plan_file), "--readings", str(path), *extra])
    out, err = capsys.readouterr()
    return code, out, err


def test_simulate_then_replay_json_lines(tmp_path, plan_file, capsys):
    readings, truth = tmp_path / "r.csv", tmp_path / "truth.json"
    code = main(
        [
            "simulate",
            str(plan_file),
            "--errors",
            "hook=0.01,cog=0.05,weight=0.01",
            "--seed",
            "4",
            "--steps",
            "5",
        ]
        + ["--output", str(readings), "--truth", str(truth)]
    )
    capsys.readouterr()
    assert code == 0
    assert readings.read_text().splitlines()[0] == "time,L1,L2,L3,L4,heel,trim"
    code, out, _ = _watch(capsys, plan_file, readings, "--json")
    lines = [json.loads(line) for line in out.splitlines()]
    assert len(lines) == 5
    for key in (
        "time",
        "weight",
        "weight_sigma",
        "cog",
        "cog_sigma",
        "hook_errors",
        "advice",
        "stop",
        "reason",
    ):
        assert key in lines[0]
    rows = json.loads(truth.read_text())["rows"]
    for line, row in zip(lines, rows):
        assert abs(line["weight"] - row["weight"]) <= 4 * line["weight_sigma"]
        assert line["cog"][1] is None and "cog.y" in line["unobservable"]  # choi y: the CG height
    assert code in (0, 4)


def test_same_seed_same_file(tmp_path, plan_file, capsys):
    texts = []
    for name in ("a.csv", "b.csv"):
        assert (
            main(
                ["simulate", str(plan_file), "--seed", "9", "--steps", "3", "--output", str(tmp_path / name)]
            )
            == 0
        )
        texts.append((tmp_path / name).read_text())
    capsys.readouterr()
    assert texts[0] == texts[1]


@pytest.mark.parametrize(
    "text, expected",
    [
        ("time,L1,L2,L3\n0,1,2,3\n", "no load-cell column for rope L4"),
        ("time,L1,L2,L3,L4,L9\n0,1,2,3,4,5\n", "column 'L9': no crane or lug 'L9' in the plan"),
        ("time,L1,L2,L3,L4,heel\n0,1,2,3,4,0\n", "heel without trim"),
        ("time,L1,L2,L3,L4,L1\n0,1,2,3,4,5\n", "column 'L1' appears twice"),
        ("", "empty"),
    ],
)
def test_bad_file_one_line_exit_2(tmp_path, plan_file, capsys, text, expected):
    path = tmp_path / "r.csv"
    path.write_text(text)
    code, out, err = _watch(capsys, plan_file, path)
    assert code == 2 and out == ""
    assert expected in err and len(err.strip().splitlines()) == 1, err


@pytest.mark.parametrize(
    "row, expected",
    [
        ("1,237.5,-3.0,221.0,214.5,0.0,0.0\n", "negative tension in L2"),
        ("1,237.5,nan,221.0,214.5,0.0,0.0\n", "L2 = 'nan' is not a finite number"),
        ("1,237.5,,221.0,214.5,0.0,0.0\n", "L2 = '' is not a finite number"),
        ("-1,237.5,231.0,221.0,214.5,0.0,0.0\n", "time -1 s is not after the previous reading's 0 s"),
        ("1,237.5,231.0\n", "3 values, the header has 7"),
    ],
)
def test_bad_row_flagged_exit_4(tmp_path, plan_file, capsys, row, expected):
    path = tmp_path / "r.csv"
    path.write_text(HEADER + ROW.format(t=0) + row + ROW.format(t=2))
    code, out, err = _watch(capsys, plan_file, path, "--json")
    lines = [json.loads(line) for line in out.splitlines()]
    assert code == 4 and len(lines) == 3
    bad = lines[1]
    assert bad["flagged"] and bad["stop"] and expected in bad["reason"], bad["reason"]
    assert bad["weight"] is None and all(v is None for v in bad["hook_errors"].values())
    assert not lines[0]["flagged"] and not lines[2]["flagged"]  # the rows around it are estimated
    assert "1 reading(s) flagged" in err


def test_crane_and_lug_names_and_json_readings(tmp_path, plan_file, capsys):
    basis = tanker_basis()
    names = [basis.cranes[0], basis.candidates[1], "L3", "L4"]
    rows = [dict(zip(["time", *names], [t, 237.5, 231.0, 221.0, 214.5])) for t in (0, 1)]
    path = tmp_path / "r.jsonl"
    path.write_text("\n".join(json.dumps(r) for r in rows) + "\n")
    code, out, _ = _watch(capsys, plan_file, path, "--json")
    lines = [json.loads(line) for line in out.splitlines()]
    assert code == 0 and len(lines) == 2
    assert abs(lines[0]["weight"] - basis.weight) < 0.1  # the plan's own tensions: its weight


def test_console_line_per_reading(tmp_path, plan_file, capsys):
    path = tmp_path / "r.csv"
    path.write_text(HEADER + ROW.format(t=0) + ROW.format(t=1))
    code, out, _ = _watch(capsys, plan_file, path)
    assert code == 0
    lines = out.splitlines()
    assert len(lines) == 2 and all("every tension in its band: no move" in line for line in lines)


def test_follow_reads_lines_as_they_come(tmp_path):
    path = tmp_path / "r.csv"
    path.write_text(HEADER + ROW.format(t=0))
    updates = _followed(Watcher(tanker_basis()), path, idle=None)
    assert next(updates).reading.time == 0.0
    with open(path, "a") as handle:
        handle.write("1,237.5,231.0,")  # a logger's half-written line waits for its end
        handle.flush()
        handle.write("221.0,214.5,0.0,0.0\n")
    assert next(updates).reading.time == 1.0


def test_follow_stops_after_idle(tmp_path):
    path = tmp_path / "r.csv"
    path.write_text(HEADER + ROW.format(t=0))
    updates = list(_followed(Watcher(tanker_basis()), path, idle=0.2))  # nothing more comes
    assert [u.reading.time for u in updates] == [0.0]


def test_follow_ctrl_c_exits_130(tmp_path, plan_file):
    path = tmp_path / "r.csv"
    path.write_text(HEADER + ROW.format(t=0))
    command = [sys.executable, "-m", "liftplan.planner.cli", "watch", str(plan_file), "--readings", str(path)]
    process = subprocess.Popen(
        [*command, "--follow"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        first = process.stdout.readline()  # the first reading's line: the follow loop is running
        assert "no move" in first
        process.send_signal(signal.SIGINT)
        _, err = process.communicate(timeout=60)
    finally:
        process.kill()
    assert process.returncode == 130
    assert "interrupted" in err


def test_simulate_refuses_bad_options(tmp_path, plan_file, capsys):
    code = main(["simulate", str(plan_file), "--errors", "hooks=1", "--output", str(tmp_path / "r.csv")])
    _, err = capsys.readouterr()
    assert code == 2 and "expected KEY=VALUE with KEY one of hook, cog, weight" in err


def test_plan_json_without_watch_object(tmp_path, capsys):
    path = tmp_path / "plan.json"
    path.write_text('{"lugs": {}}')
    other = tmp_path / "r.csv"
    other.write_text(HEADER)
    code, _, err = _watch(capsys, path, other)
    assert code == 2 and 'no "watch" object' in err


def test_hook_height_columns_make_the_hooks_absolute(tmp_path, plan_file, capsys):
    readings, truth = tmp_path / "r.csv", tmp_path / "truth.json"
    argv = ["simulate", str(plan_file), "--hook-heights", "--seed", "5", "--steps", "3"]
    assert main([*argv, "--output", str(readings), "--truth", str(truth)]) == 0
    capsys.readouterr()
    assert readings.read_text().splitlines()[0].endswith("hook:L1,hook:L2,hook:L3,hook:L4")
    code, out, _ = _watch(capsys, plan_file, readings, "--json")
    lines = [json.loads(line) for line in out.splitlines()]
    rows = json.loads(truth.read_text())["rows"]
    for line, row in zip(lines, rows):
        assert line["hook_errors_about_mean"] is False  # a common error is read: no mean taken off
        for label, value in line["hook_errors"].items():
            assert abs(value - row["hook_errors"][label]) <= 4 * line["hook_errors_sigma"][label]


@pytest.mark.parametrize(
    "extra, expected", [(["--idle", "1"], "only with --follow"), (["--follow", "--idle", "0"], "> 0")]
)
def test_idle_option_refused(tmp_path, plan_file, capsys, extra, expected):
    path = tmp_path / "r.csv"
    path.write_text(HEADER)
    code, _, err = _watch(capsys, plan_file, path, *extra)
    assert code == 2 and expected in err
