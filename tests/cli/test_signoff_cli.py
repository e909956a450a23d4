"""A plan an engineer can sign, on the command line (issue 14 items 1, 9, 10).

Failed checks print FAIL lines, carry ``"checks"`` in the JSON and exit 4; unit slips get a
warning; Ctrl-C ends any command with one line and exit 130; every output-path mistake and
every fuzzed input of the issue is one line on stderr with exit 2, found before computing.
"""

import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest
from helpers import EXAMPLES
from support.cli import run

from liftplan.model import Equilibrium, LiftPlanError, Pose, SolverInfo, load_scene
from liftplan.model.scene.plausibility import equilibrium_warnings, scene_warnings
from liftplan.model.solve_checks import equilibrium_checks
from liftplan.planner import load_problem
from liftplan.planner.batch.run import probe_scheduler
from liftplan.planner.cli import main
from liftplan.planner.plans import held
from liftplan.planner.problem.plausibility import problem_warnings

TANKER = EXAMPLES / "tanker_upright.toml"
TANKER_PLAN = EXAMPLES / "tanker_plan.toml"
LIFT = EXAMPLES / "sunken_block_lift.toml"
CHECK_KEYS = {"name", "subject", "value", "limit", "unit", "ok"}


def edited(tmp_path, source, old, new, name="scene.toml"):
    text = source.read_text()
    assert old in text, old  # the edit must hit, or the test would test the example
    path = tmp_path / name
    path.write_text(text.replace(old, new))
    return path


def one_error_line(err):
    lines = err.strip().splitlines()
    return len(lines) == 1 and lines[0].startswith("liftplan: error:") and "Traceback" not in err


# -- item 1: checks, exit code 4, warnings ----------------------------------------------------
def test_weight_in_kg_fails_swl_checks_exit_4_and_warns(tmp_path):
    path = edited(tmp_path, TANKER, "weight = 904.0", "weight = 904000.0")
    # the contract fixes exit 0 for a converged solve: only --strict turns FAIL into exit 4
    assert run("solve", str(path)).returncode == 0
    out = run("solve", str(path), "--strict")
    assert out.returncode == 4
    fails = [line for line in out.stdout.splitlines() if line.startswith("FAIL")]
    assert [line.split()[:3] for line in fails] == [["FAIL", "swl", f"T{i}:"] for i in (1, 2, 3, 4)]
    assert "68029%" in fails[0]  # 272 115 t on a 400 t crane
    assert "4 FAILED" in out.stdout
    err = out.stderr.strip().splitlines()
    assert len(err) == 2 and "Traceback" not in out.stderr
    assert err[0].startswith("liftplan: warning: body.weight = 904000 t") and "kg typed as t" in err[0]
    assert err[1].startswith("liftplan: 4 check(s) failed: swl T1")


def test_json_carries_every_check_and_a_script_can_gate_on_them(tmp_path):
    ok = run("solve", str(TANKER), "--json")
    assert ok.returncode == 0 and ok.stderr == ""
    checks = json.loads(ok.stdout)["checks"]
    assert all(CHECK_KEYS <= set(c) and c["ok"] for c in checks)
    assert {c["name"] for c in checks} == {"swl", "min_tension", "taut"}
    # SWL 250 t: the 272.11 t ropes are at 108.8 %
    over = run("solve", str(edited(tmp_path, TANKER, "swl = 400.0", "swl = 250.0")), "--json", "--strict")
    assert over.returncode == 4
    failed = [c for c in json.loads(over.stdout)["checks"] if not c["ok"]]
    assert {c["subject"] for c in failed} == {"T1", "T4"}
    # the value and limit are the tension and SWL as solved (tensions checked in test_cli)
    assert failed[0]["value"] == pytest.approx(272.11, abs=0.005) and failed[0]["limit"] == 250.0


def test_slack_rope_of_a_grounded_hull_is_a_state_not_a_failure(capsys):
    # the sunken block rests on the seabed at hoist 0, two ropes slack: the ground carries it
    assert main(["solve", str(LIFT), "--json"]) == 0
    checks = json.loads(capsys.readouterr().out)["checks"]
    assert checks and all(c["ok"] for c in checks) and "taut" not in {c["name"] for c in checks}


def test_slack_rope_fails_the_taut_check():
    scene = load_scene(TANKER)
    eq = Equilibrium(
        model="elastic",
        pose=Pose(0.0, 0.0, 0.0, -131.0),
        tensions={"T1": 452.0, "T2": 0.0, "T3": 0.0, "T4": 452.0},
        weight=904.0,
        swl={"T1": 400.0, "T2": 400.0, "T3": 400.0, "T4": None},
        slack=("T2", "T3"),
        residual=0.0,
        solver=SolverInfo("newton", True, 3, 0.001),
    )
    checks = {(c.name, c.subject): c for c in equilibrium_checks(scene, eq)}
    assert not checks["swl", "T1"].ok and ("swl", "T4") not in checks  # no SWL given: no check
    assert checks["min_tension", "T2"].ok  # zero is no compression...
    taut = checks["taut", "ropes"]
    assert not taut.ok and taut.value == 2 and taut.limit == 4 and "T2, T3" in taut.note  # ...but slack
    (warning,) = equilibrium_warnings(scene, eq)
    assert "-131 m" in warning and "far below the datum" in warning


#: The tanker's weight is in water, its DAF the in-air table's: warned on every plan of it
#: (tests/planner/test_weight_basis.py); the tests below look at the other warnings.
IN_AIR_DAF = "Table 5-1, which is for lifts in air"


def others(lines):
    return [w for w in lines if IN_AIR_DAF not in w]


def test_plausibility_names_the_key_and_the_slip(tmp_path):
    assert scene_warnings(load_scene(TANKER)) == []
    assert others(problem_warnings(load_problem(TANKER_PLAN))) == []
    low = load_scene(edited(tmp_path, TANKER, "lift_height = 1.0", "lift_height = -150.0"))
    assert any(
        w.startswith("attitude.lift_height = -150 m: far below the datum") for w in scene_warnings(low)
    )
    problem = load_problem(edited(tmp_path, TANKER_PLAN, "hook_tolerance = 0.02", "hook_tolerance = 20.0"))
    assert others(problem_warnings(problem)) == [
        "plan.hook_tolerance = 20 m: more than 0.5 m of hook-height error; mm typed as m?"
    ]
    problem = load_problem(edited(tmp_path, TANKER_PLAN, "heel = 2.0, trim", "heel = 45.0, trim"))
    assert others(problem_warnings(problem))[0].startswith("plan.tolerance.heel = 45 deg")


def test_plan_with_hook_tolerance_in_mm_is_infeasible_and_warned(tmp_path):
    # hook errors are in the worst case: no lug set holds every rope within its limits for
    # independent hook errors of +-20 m; the unit slip is warned, the refusal is one line
    path = edited(tmp_path, TANKER_PLAN, "hook_tolerance = 0.02", "hook_tolerance = 20.0")
    out = run("plan", str(path), "--json")
    assert out.returncode == 1, out.stderr
    assert out.stdout == ""
    lines = others(out.stderr.strip().splitlines())
    assert len(lines) == 2 and "warning: plan.hook_tolerance = 20 m" in lines[0]
    assert lines[1].startswith("liftplan: no feasible plan")


# -- item 9: Ctrl-C -----------------------------------------------------------------------
def interrupt(args, ready, tmp_path, after=0.5, loop=None):
    """Start the command in its own process group, wait for ``ready`` on stderr (bounded),
    then send SIGINT to the whole group as a terminal's Ctrl-C does.

    ``loop = (module, name, again)`` makes that function of the command run for real once,
    then print "computing" and either run for real over and over (``again``) or wait in
    Python, so the Ctrl-C always lands while the command is busy, however fast the machine
    is (a command that could finish first would make the test a race). The lift waits in
    Python: a Ctrl-C landing inside one of casadi's solves can be taken by casadi as a failed
    step (README "Left out"), which would make its case a race of another kind."""
    patch = ""
    if loop is not None:
        module, name, again = loop
        body = "        real(*a, **k)\n" if again else "        time.sleep(0.05)\n"
        patch = (
            f"import importlib, time; m = importlib.import_module({module!r}); "
            f"real = m.{name}\n"
            "def looping(*a, **k):\n"
            "    real(*a, **k)\n"
            "    print('computing', file=sys.stderr, flush=True)\n"
            "    while True:\n" + body + f"m.{name} = looping\n"
        )
    code = (
        "import sys\n" + patch + "from liftplan.planner.cli import main\n"
        "print('started', file=sys.stderr, flush=True)\n"
        f"sys.exit(main({[str(a) for a in args]!r}))\n"
    )
    # as from a shell: Ctrl-C at its default in the child, whatever this process inherited (a
    # suite started as a background job of a non-interactive shell ignores SIGINT; that is
    # inherited across exec and Python keeps it: the children then ran on for 60 s)
    proc = subprocess.Popen(
        [sys.executable, "-c", code],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
        cwd=tmp_path,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    os.set_blocking(proc.stderr.fileno(), False)
    seen, deadline = b"", time.monotonic() + 120
    while ready.encode() not in seen and time.monotonic() < deadline and proc.poll() is None:
        seen += proc.stderr.read() or b""
        time.sleep(0.05)
    assert ready.encode() in seen, seen
    time.sleep(after)
    os.killpg(proc.pid, signal.SIGINT)
    os.set_blocking(proc.stderr.fileno(), True)
    try:
        out, err = proc.communicate(timeout=60)
    finally:  # never leave a looping child behind (it would load the machine for hours)
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    return proc.returncode, out.decode(), (seen + err).decode()


@pytest.mark.parametrize(
    ("args", "loop"),
    [
        # the search runs once for real, then waits in Python: a Ctrl-C landing inside one of
        # the search's casadi evaluations can be taken by casadi (as in the lift's case), and
        # the full suite once saw the child run on for its 60 s that way
        (["plan", TANKER_PLAN], ("liftplan.planner.plans.held", "search", False)),
        (["lift", LIFT, "--step", "0.25"], ("liftplan.model.lift", "load_curve", False)),
    ],
    ids=["plan", "lift"],
)
def test_ctrl_c_is_one_line_exit_130(tmp_path, args, loop):
    code, out, err = interrupt(args, "computing", tmp_path, after=0.5, loop=loop)
    assert code == 130, err
    lines = err.strip().splitlines()
    assert lines[0] == "started" and lines[-1].startswith("liftplan: interrupted")
    assert "Traceback" not in err


def test_interrupted_plan_prints_the_best_so_far_marked_as_such(capsys, monkeypatch):
    import importlib

    from liftplan.planner import plan
    from liftplan.planner.search.evaluator import Interrupted

    # (``import liftplan.planner.plan as m`` gives the function, as the package exports it)
    planning = importlib.import_module("liftplan.planner.plan")
    best = plan(load_problem(TANKER_PLAN), top=2)

    def interrupted(problem, top=None):  # the search stopped by Ctrl-C with a plan in hand
        error = Interrupted(best.ranking, best.stats)
        error.plan = best
        raise error

    monkeypatch.setattr(planning, "plan", interrupted)
    assert main(["plan", str(TANKER_PLAN)]) == 130
    captured = capsys.readouterr()
    assert captured.out.startswith("INTERRUPTED: best plan found so far")
    assert " ".join(best.chosen.lugs[:2]) in captured.out
    assert captured.err.strip().splitlines()[-1].startswith("liftplan: interrupted; the plan above")
    assert main(["plan", str(TANKER_PLAN), "--json"]) == 130
    assert json.loads(capsys.readouterr().out)["interrupted"] is True


def test_ctrl_c_inside_casadi_is_still_an_interruption(capsys, monkeypatch):
    import importlib

    from liftplan.model.errors import SolverFailed

    solving = importlib.import_module("liftplan.model.solve")

    def interrupted(scene, **options):
        try:  # what casadi raises for a Ctrl-C during a Function call, wrapped by a caller
            raise RuntimeError("Error in Function::call for 'free_root' [Newton]:\nKeyboardInterrupt")
        except RuntimeError as err:
            raise SolverFailed("Newton stopped") from err

    monkeypatch.setattr(solving, "solve", interrupted)
    assert main(["solve", str(TANKER)]) == 130
    assert capsys.readouterr().err == "liftplan: interrupted\n"


@pytest.mark.slow
def test_ctrl_c_during_batch_is_one_line_exit_130(tmp_path):
    # 600 plans on a local cluster: interrupted at its first finished case, long before the end
    study = tmp_path / "study.toml"
    (tmp_path / "tanker_plan.toml").write_text(TANKER_PLAN.read_text())
    study.write_text(
        '[study]\nproblem = "tanker_plan.toml"\n[sweep]\n"plan.tolerance.heel" = [1.0, 2.0]\n'
        "[sample]\ncount = 300\nweight = [0.95, 1.05]\n"
    )
    code, out, err = interrupt(["batch", study, "--workers", "2"], "case/s", tmp_path, after=0.2)
    assert code == 130, err
    assert err.strip().splitlines()[-1] == (
        "liftplan: interrupted; the finished cases are kept, run the same command to resume"
    )
    for noise in ("Traceback", "CasADi", "distributed.", "KeyboardInterrupt"):
        assert noise not in err
    assert (tmp_path / "study.csv.partial").exists()


def _no_search(*args, **kwargs):
    raise AssertionError("the search ran: the input should have been refused before it")


# -- item 10: output paths ------------------------------------------------------------------
def test_report_naming_an_existing_file_is_refused_before_planning(tmp_path, capsys, monkeypatch):
    target = tmp_path / "report"
    target.write_text("keep me")
    monkeypatch.setattr(held, "search", _no_search)  # refused before the ~2 s plan
    assert main(["plan", str(TANKER_PLAN), "--report", str(target)]) == 2
    err = capsys.readouterr().err
    assert one_error_line(err) and "is a file; expected a folder" in err
    assert target.read_text() == "keep me"


@pytest.mark.parametrize(
    "figure, fragment",
    [
        ("curve.jpg", "unknown file type '.jpg'; expected one of .png, .pdf, .svg"),
        ("curve", "unknown file type '(none)'"),
        ("folder.png/", "is a folder"),
        ("blocker/curve.png", "is a file, not a folder"),
    ],
)
def test_bad_figure_paths_are_refused_before_computing(tmp_path, capsys, figure, fragment):
    (tmp_path / "folder.png").mkdir()
    (tmp_path / "blocker").write_text("")
    assert main(["lift", str(LIFT), "--figure", str(tmp_path / figure)]) == 2
    captured = capsys.readouterr()
    assert one_error_line(captured.err) and fragment in captured.err and captured.out == ""


def test_figure_into_a_missing_folder_creates_it_and_defaults_to_the_current_folder(tmp_path):
    out = subprocess.run(
        [sys.executable, "-m", "liftplan.planner.cli", "lift", str(LIFT), "--json"],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=tmp_path,
    )
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "sunken_block_lift_load_curve.png").stat().st_size > 0
    assert not (EXAMPLES / "sunken_block_lift_load_curve.png").exists()
    assert main(["lift", str(LIFT), "--step", "1", "--figure", str(tmp_path / "new" / "sub" / "c.svg")]) == 0
    assert (tmp_path / "new" / "sub" / "c.svg").read_text().startswith("<?xml")


def test_figure_on_a_full_disk_keeps_the_table_and_exits_2(tmp_path, capsys, monkeypatch):
    import errno

    import liftplan.planner.output.figures.plan as figures

    class FullDisk:
        def savefig(self, path, **options):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))

    monkeypatch.setattr(figures, "load_curve", lambda curve, swl=None: FullDisk())
    assert main(["lift", str(LIFT), "--step", "1", "--figure", str(tmp_path / "c.png")]) == 2
    captured = capsys.readouterr()
    assert "hoist [m]" in captured.out  # the computed table is not lost
    assert one_error_line(captured.err) and "No space left on device" in captured.err


@pytest.mark.parametrize(
    "output, fragment",
    [
        ("folder", "is a folder; expected a file name"),
        ("/proc/liftplan/out.csv", "cannot write in /proc"),  # no file can be created under /proc
    ],
)
def test_batch_output_mistakes_are_refused(tmp_path, capsys, output, fragment):
    (tmp_path / "folder").mkdir()
    (tmp_path / "tanker_plan.toml").write_text(TANKER_PLAN.read_text())
    study = tmp_path / "study.toml"
    study.write_text(f'[study]\nproblem = "tanker_plan.toml"\nkind = "check"\noutput = "{output}"\n')
    assert main(["batch", str(study)]) == 2
    err = capsys.readouterr().err
    assert one_error_line(err) and "study.output" in err and fragment in err
    assert main(["batch", str(study), "--output", str(tmp_path / "folder")]) == 2
    assert "--output" in capsys.readouterr().err


def test_broken_pipe_closes_quietly():
    proc = subprocess.Popen(
        [sys.executable, "-m", "liftplan.planner.cli", "solve", str(TANKER)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    proc.stdout.close()  # the reader is gone before the first line is written
    err = proc.stderr.read()
    assert proc.wait(timeout=120) == 141 and err == b""


class Server:
    """A loopback TCP server that is no Dask scheduler: silent (an HTTP server waiting for a
    request) or talking (an HTTP answer at once)."""

    def __init__(self, greeting):
        self.sock = socket.create_server(("127.0.0.1", 0))
        self.address = f"tcp://127.0.0.1:{self.sock.getsockname()[1]}"
        self.greeting, self.held = greeting, []
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self):
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            conn.sendall(self.greeting)
            self.held.append(conn)  # kept open: the client must give up on its own

    def close(self):
        for conn in self.held:
            conn.close()
        self.sock.close()


def test_scheduler_that_is_not_dask_is_one_line_naming_it(tmp_path, capsys):
    server = Server(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")
    try:
        (tmp_path / "tanker_plan.toml").write_text(TANKER_PLAN.read_text())
        study = tmp_path / "study.toml"
        study.write_text('[study]\nproblem = "tanker_plan.toml"\n')
        assert main(["batch", str(study), "--scheduler", server.address]) == 2
        err = capsys.readouterr().err
        assert one_error_line(err) and server.address in err and "not a Dask scheduler" in err
    finally:
        server.close()


def test_silent_scheduler_times_out_naming_it():
    server = Server(b"")
    try:
        start = time.perf_counter()
        with pytest.raises(LiftPlanError, match=f"{server.address}: no Dask handshake within 1 s"):
            probe_scheduler(server.address, timeout=1.0)
        assert time.perf_counter() - start < 30.0  # at its 1 s timeout, not hanging (wide: no chance)
    finally:
        server.close()


# -- item 10: fuzzed inputs, each one line and exit 2 -------------------------------------
def deep_toml(path):
    path.write_text("a = " + "[" * 50_000 + "]" * 50_000 + "\n")
    return path


def plan_with(tmp_path, old, new):
    return edited(tmp_path, TANKER_PLAN, old, new, name="tanker_plan.toml")


def study(tmp_path, text, problem="tanker_plan.toml"):
    if not (tmp_path / "tanker_plan.toml").exists():
        (tmp_path / "tanker_plan.toml").write_text(TANKER_PLAN.read_text())
    path = tmp_path / "study.toml"
    path.write_text(f'[study]\nproblem = "{problem}"\nkind = "check"\n{text}')
    return path


CASES = {
    "toml nested 50 000 deep": (lambda t: ["solve", deep_toml(t / "deep.toml")], "nested too deeply"),
    "lift --to inf": (lambda t: ["lift", LIFT, "--to", "inf"], "--to inf: expected a finite"),
    "lift --step nan": (lambda t: ["lift", LIFT, "--step", "nan"], "--step nan: expected a finite"),
    "plan yaw 1e308": (
        lambda t: ["plan", plan_with(t, "[attitude]", "[attitude]\nyaw = 1e308")],
        "attitude.yaw = 1e+308: expected a value in [-360, 360] deg",
    ),
    "study problem a folder": (lambda t: ["batch", study(t, "", problem="sub")], "study.problem = 'sub'"),
    "study problem binary": (lambda t: ["batch", study(t, "", problem="blob.bin")], "not a text file"),
    "study problem empty": (lambda t: ["batch", study(t, "", problem="")], "study.problem = ''"),
    "study problem /dev/null": (lambda t: ["batch", study(t, "", problem="/dev/null")], "not a regular file"),
    "study problem empty file": (lambda t: ["batch", study(t, "", problem="empty.toml")], "body: missing"),
    "sample weight inf": (
        lambda t: ["batch", study(t, "[sample]\ncount = 3\nweight = [1.0, inf]\n")],
        "sample.weight = [1.0, inf]: expected finite factors",
    ),
    "sweep string": (
        lambda t: ["batch", study(t, '[sweep]\n"plan.tolerance.heel" = ["2"]\n')],
        "sweep.'plan.tolerance.heel'[0] = '2': no case can use it",
    ),
    "sweep cg with two components": (
        lambda t: ["batch", study(t, '[sweep]\n"body.cog" = [[35.0, 2.5]]\n')],
        "sweep.'body.cog'[0] = [35.0, 2.5]: no case can use it",
    ),
    "check sweep nan weight": (
        lambda t: ["batch", study(t, '[sweep]\n"body.weight" = [904.0, nan]\n')],
        "sweep.'body.weight'[1] = nan: no case can use it",
    ),
    "check sweep negative weight": (
        lambda t: ["batch", study(t, '[sweep]\n"body.weight" = [-904.0]\n')],
        "expected a number > 0",
    ),
    "check sweep 200 deg tolerance": (
        lambda t: ["batch", study(t, '[sweep]\n"plan.tolerance.heel" = [200.0]\n')],
        "expected 0 to 90 deg",
    ),
    "check sweep negative min_tension": (
        lambda t: ["batch", study(t, '[sweep]\n"plan.min_tension" = [-5.0]\n')],
        "expected >= 0 t",
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_fuzzed_input_is_one_line_exit_2(tmp_path, capsys, case):
    (tmp_path / "sub").mkdir()
    (tmp_path / "blob.bin").write_bytes(bytes(range(256)) * 4)
    (tmp_path / "empty.toml").write_text("")
    make_args, fragment = CASES[case]
    args = [str(a) for a in make_args(tmp_path)]
    assert main(args) == 2
    captured = capsys.readouterr()
    assert one_error_line(captured.err), captured.err
    assert fragment in captured.err and captured.out == ""


def test_fuzz_cases_run_as_a_user_runs_them_exit_2_no_traceback(tmp_path):
    # the deepest case in its own process too: the recursion limit is not the test runner's
    out = run("solve", str(deep_toml(tmp_path / "deep.toml")))
    assert out.returncode == 2 and one_error_line(out.stderr)


def test_scene_path_that_is_a_fifo_is_refused_not_waited_on(tmp_path):
    fifo = tmp_path / "scene.toml"
    os.mkfifo(fifo)
    out = subprocess.run(
        [sys.executable, "-m", "liftplan.planner.cli", "solve", str(fifo)],
        capture_output=True,
        text=True,
        timeout=60,
    )  # a hang fails here
    assert out.returncode == 2 and one_error_line(out.stderr) and "not a regular file" in out.stderr


def test_check_study_with_a_cg_far_away_gives_invalid_rows(tmp_path):
    from dask.distributed import Client

    from liftplan.planner.batch.run import run_study
    from liftplan.planner.batch.study import load_study

    path = study(tmp_path, '[sweep]\n"body.cog" = [[35.86, 2.5, 6.0], [1.0e6, 2.5, 6.0]]\n')
    with Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=":0") as client:
        summary = run_study(load_study(path), client=client, progress=False)
    rows = (tmp_path / "study.csv").read_text().splitlines()
    assert summary.counts == {"ok": 1, "invalid": 1}
    assert "outside the plan's lugs' support polygon" in rows[2] and rows[2].startswith("1,")
