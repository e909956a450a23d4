"""The ``liftplan`` command line.

argparse (standard library) rather than click/typer: four sub-commands with a few options do
not justify three more dependencies, and argparse's errors are already one line.

Start-up matters (``liftplan --help`` and a 3 ms solve should not wait seconds): this module
imports only the standard library and the error classes at the top; each command imports
what it needs (``solve`` never loads cvxpy, Dask or matplotlib).

Exit codes: 0 success; 1 no equilibrium or no feasible plan; 2 bad input (including output
paths, checked before any computation); 3 internal error; 4 solved or planned, but a check
failed (the result is still printed, with a FAIL line per failed check); 130 interrupted
(Ctrl-C); 141 stdout closed early (a broken pipe, as ``| head``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import warnings

from liftplan.model.errors import EquilibriumNotFound, InvalidScene, LiftPlanError, PlanInfeasible
from liftplan.model.extras import MissingExtra

# exit codes
NO_SOLUTION = 1
BAD_INPUT = 2
INTERNAL = 3
CHECK_FAILED = 4
INTERRUPTED = 130
BROKEN_PIPE = 141  # 128 + SIGPIPE, what a shell reports for a writer whose reader went away

#: Largest plan yaw accepted  [deg] (beyond a turn it is a slip, and 1e308 breaks the trig).
MAX_YAW = 360.0


class _Version(argparse.Action):
    """``--version``: argparse's ``action="version"``, but the version is read (from the
    installed metadata, ~25 ms) only when asked for, not for every command."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        from liftplan.model.version import __version__

        print(f"{parser.prog} {__version__}")  # on stdout, as argparse's own
        parser.exit()


class _Parser(argparse.ArgumentParser):
    """argparse with its errors on one line (no usage block), as every other error here; the
    sub-commands' parsers are of this class too (argparse makes them of the parent's)."""

    def error(self, message):
        self.exit(BAD_INPUT, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _parser():
    # start-up: the view's parser set-up imports the standard library and the path rule only
    from liftplan.planner.output.view import command as view_command

    parser = _Parser(
        prog="liftplan",
        description="Multi-crane lift planning for salvage and heavy-block rigging.",
        epilog="exit codes: 0 success, 1 no equilibrium / no feasible plan, 2 bad input, "
        "3 internal error, 4 result printed but a check failed (FAIL lines), "
        "130 interrupted (Ctrl-C), 141 output pipe closed early",
    )
    parser.add_argument("--debug", action="store_true", help="show tracebacks of internal errors")
    parser.add_argument("--version", action=_Version, help="print liftplan's version and exit")
    commands = parser.add_subparsers(dest="command", required=True)
    solve_cmd = commands.add_parser("solve", help="tensions and pose of a scene")
    solve_cmd.add_argument("scene", help="scene file (TOML)")
    solve_cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    solve_cmd.add_argument(
        "--model",
        choices=["elastic", "paper-elastic", "rigid", "hydrostatic", "inclined", "rigging"],
        help="override the scene's [analysis] model",
    )
    solve_cmd.add_argument(
        "--strict",
        action="store_true",
        help=f"exit {CHECK_FAILED} when a check fails (default: a converged solve exits 0 and "
        "flags failed checks with FAIL lines and in the JSON)",
    )
    solve_cmd.add_argument(
        "--method",
        choices=["newton", "paper-newton"],
        default="newton",
        help="stranded hull: casadi Newton (default) or the paper's J^T D J iteration",
    )
    solve_cmd.add_argument(
        "--strength-figure",
        metavar="FILE",
        help="draw weight, buoyancy, lift forces, shear force and bending moment along the body "
        "(needs [body] weight_curve), .png, .pdf or .svg",
    )
    view_command.add_view_option(solve_cmd)
    lift_cmd = commands.add_parser(
        "lift", help="load curve of a lift off the seabed and through the waterline"
    )
    lift_cmd.add_argument("scene", help="scene file with [hull], [water], cranes (and usually [ground])")
    lift_cmd.add_argument(
        "--to", type=float, metavar="M", help="last hoist in m (default: the hull 1 m clear of the water)"
    )
    lift_cmd.add_argument("--step", type=float, default=0.25, metavar="M", help="hoist step in m (0.25)")
    lift_cmd.add_argument(
        "--speed",
        type=float,
        metavar="M/MIN",
        help="hoist speed in m/min: the curve gets a time axis and compartments "
        "with openings drain in time (without it they are carried full)",
    )
    lift_cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    lift_cmd.add_argument(
        "--figure",
        metavar="FILE",
        help="where to save the figure, .png, .pdf or .svg (default: "
        "SCENE_load_curve.png in the current folder)",
    )
    view_command.add_view_option(lift_cmd)
    plan_cmd = commands.add_parser("plan", help="choose lugs and boom heights for a lift")
    plan_cmd.add_argument("scene", help="planning scene file (TOML with [[candidates]], [plan])")
    plan_cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    plan_cmd.add_argument(
        "--report",
        metavar="DIR",
        help="write report.html (and report.pdf with WeasyPrint), "
        "plan_scene.toml and plan.json into DIR (created if missing)",
    )
    plan_cmd.add_argument("--top", type=int, metavar="K", help="rank the best K lug sets")
    view_command.add_view_option(plan_cmd)
    view_command.add_parser(commands)
    batch_cmd = commands.add_parser(
        "batch", help="run a batch study (many plans, or one plan checked many times) on Dask"
    )
    batch_cmd.add_argument("study", help="study file (TOML with [study], [sweep], [sample])")
    batch_cmd.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="a running Dask scheduler, e.g. tcp://10.0.0.5:8786 (default: a local cluster)",
    )
    batch_cmd.add_argument(
        "--workers", type=int, metavar="N", help="local cluster size (default: one per core)"
    )
    batch_cmd.add_argument("--output", metavar="CSV", help="the table to write (default: the study's)")
    batch_cmd.add_argument(
        "--restart", action="store_true", help="discard an interrupted run's rows instead of resuming it"
    )
    batch_cmd.add_argument("--no-progress", action="store_true", help="no progress bar")
    # start-up: the watch options' module imports nothing (its handlers load when a command runs)
    from liftplan.planner.watch.command import add_parser as add_watch

    add_watch(commands)

    from liftplan.planner.sequence.command import add_parser as add_sequence  # start-up: argparse only

    add_sequence(commands)
    return parser


def _warn(lines):
    for line in lines:
        print(f"liftplan: warning: {line}", file=sys.stderr)


def _verdict(checks, table, strict=True):
    """Print the failed checks (stdout after the table; a summary on stderr); the exit code:
    :data:`CHECK_FAILED` when one failed and ``strict``, else 0."""
    failed = [c for c in checks if not c.ok]
    if table:
        for check in failed:
            print(check.line())
        if checks:
            print(
                f"checks: {len(checks) - len(failed)} of {len(checks)} met"
                + (f", {len(failed)} FAILED" if failed else "")
            )
    if failed:
        names = ", ".join(f"{c.name} {c.subject}" for c in failed[:5])
        more = f" and {len(failed) - 5} more" if len(failed) > 5 else ""
        code = CHECK_FAILED if strict else 0
        print(f"liftplan: {len(failed)} check(s) failed: {names}{more} (exit {code})", file=sys.stderr)
        return code
    return 0


def _solve(args):
    from liftplan.model.scene.file import load_scene
    from liftplan.model.scene.plausibility import equilibrium_warnings, scene_warnings
    from liftplan.model.solve import solve
    from liftplan.model.solve_checks import equilibrium_checks
    from liftplan.model.statics.rigging import rigging_checks
    from liftplan.model.water.breakout import bed_warnings
    from liftplan.planner.output.console.tables import equilibrium_table

    figure = None
    if args.strength_figure is not None:
        from liftplan.planner.output.paths import FIGURE_TYPES, output_file

        figure = output_file(args.strength_figure, "--strength-figure", FIGURE_TYPES)
    view = _view_file(args)
    scene = load_scene(args.scene)
    if figure is not None and scene.body.weight_curve is None:
        raise InvalidScene(
            f"--strength-figure {figure}: {args.scene} has no [body] weight_curve; "
            "expected a scene with a weight curve (the figure draws its shear force and "
            "bending moment)"
        )
    _warn(scene_warnings(scene) + bed_warnings(scene))
    eq = solve(scene, model=args.model, method=args.method)
    _warn(equilibrium_warnings(scene, eq))
    checks = equilibrium_checks(scene, eq) + rigging_checks(scene, eq)
    girder = None
    if scene.body.weight_curve is not None:
        from liftplan.model.strength import hull_girder, strength_checks

        girder = hull_girder(scene, eq)
        checks += strength_checks(scene, eq, girder)
    unwritten = None
    if figure is not None:
        unwritten = _strength_figure(scene, eq, girder, figure)
    unwritten = _save_view(view, "scene_view", scene, eq) or unwritten
    if args.json:
        out = {**eq.to_json(), "checks": [c.to_json() for c in checks]}
        if girder is not None:
            out["strength"] = girder.to_json()
        print(json.dumps(_stamped(out)))
    else:
        print(equilibrium_table(scene, eq, girder=girder))
        if eq.flexible_hull is not None:  # a hull stiffness: which hull, the change, the deflection
            print("\n".join(["", *eq.flexible_hull.lines()]))
    # CONTRACT: a converged solve exits 0; --strict turns a failed check into exit 4
    code = _verdict(checks, table=not args.json, strict=args.strict)
    return _unwritten(unwritten) or code


def _strength_figure(scene, eq, girder, figure):
    """Save the strength figure; the reason it could not be written, or None."""
    from liftplan.planner.output.figures.strength import strength_figure
    from liftplan.planner.output.paths import make_parent, replaced

    try:
        make_parent(figure)
        with replaced(figure) as temporary:  # whole or not at all
            strength_figure(scene, eq, girder).savefig(temporary, dpi=120)
    except OSError as err:  # a full disk, a folder removed meanwhile: the result still prints
        return f"--strength-figure {figure}: cannot write ({err.strerror or err})"
    print(f"liftplan: wrote {figure}", file=sys.stderr)
    return None


def _plan(args):
    from liftplan.planner.output.paths import output_folder

    if args.top is not None and args.top < 1:
        raise InvalidScene(f"--top {args.top}: expected an integer >= 1")
    report = output_folder(args.report, "--report") if args.report is not None else None
    view = _view_file(args)
    from liftplan.planner.problem.file import load_problem
    from liftplan.planner.problem.plausibility import problem_warnings

    problem = load_problem(args.scene)
    if abs(problem.yaw) > MAX_YAW:
        raise InvalidScene(
            f"{args.scene}: attitude.yaw = {problem.yaw!r}: expected a value in "
            f"[-{MAX_YAW:g}, {MAX_YAW:g}] deg"
        )
    if args.top is not None:
        problem.check_top(args.top, "--top")
    _warn(problem_warnings(problem))
    from liftplan.planner.plan import plan
    from liftplan.planner.search.evaluator import Interrupted

    try:
        result = plan(problem, top=args.top)
    except Interrupted as err:
        return _interrupted(err, args)
    return _finish_plan(result, args, report, view)


def _interrupted(err, args):
    """Print the plan a Ctrl-C left (marked INTERRUPTED, with its status); exit code 130."""
    if err.plan is None:  # nothing evaluated yet
        print(f"liftplan: interrupted ({err.phase}) before any plan was found", file=sys.stderr)
        return INTERRUPTED
    from liftplan.planner.search.progress import phase

    try:
        with phase("interrupted: the plan so far (Ctrl-C again to stop at once)", None):
            text = _plan_text(err.plan, args, interrupted=err)
    except KeyboardInterrupt:  # a second Ctrl-C: stop without the plan
        print("liftplan: interrupted", file=sys.stderr)
        return INTERRUPTED
    print(text)
    answer = "the search's answer" if err.finished else "the best found so far, not the search's answer"
    print(f"liftplan: interrupted; the plan above is {answer} ({_where(err)})", file=sys.stderr)
    return INTERRUPTED


def _finish_plan(result, args, report, view=None):
    """Design loads, the report and the plan on stdout; the exit code. The search has
    finished: a Ctrl-C before the plan is printed still prints it, marked INTERRUPTED."""
    from liftplan.planner.search.evaluator import Interrupted
    from liftplan.planner.search.progress import phase

    printed = False
    try:
        unwritten = None
        if report is not None:
            # start-up: matplotlib only when a report is asked for
            from liftplan.planner.output.report.write import write_report

            try:
                with phase("report", None):
                    files = write_report(result, report)
            except OSError as err:  # a full disk, a folder removed meanwhile: the plan still prints
                unwritten = f"--report {report}: cannot write ({err.strerror or err})"
            else:
                written = [files.html, files.pdf, files.scene, files.json]
                print("liftplan: wrote " + ", ".join(str(f) for f in written if f), file=sys.stderr)
                if files.pdf is None:  # the HTML report is always written; the PDF is optional
                    from liftplan.model.extras import missing

                    _warn([f"no report.pdf: {missing('pdf', 'weasyprint') or 'WeasyPrint did not write it'}"])
        unwritten = _save_view(view, "plan_view", result) or unwritten
        with phase("design loads and checks", None):
            text = _plan_text(result, args)
        print(text)
        printed = True
        code = _verdict(result.checks, table=not args.json)
        return _unwritten(unwritten) or code
    except (KeyboardInterrupt, Exception) as err:
        # casadi hands a Ctrl-C back as a RuntimeError naming it (the rigging model's solves)
        if printed or not _interrupt(err):  # the plan is on stdout already, or a real error
            raise
        stop = Interrupted(plan=result, phase="design loads, report and output", finished=True)
        return _interrupted(stop, args)


def _stamped(out):
    """A JSON object printed by a command, with liftplan's version as its last key."""
    from liftplan.model.version import stamped

    return stamped(out)


def _unwritten(message):
    """Exit code for an output that could not be written (after the result was printed)."""
    if message is None:
        return 0
    print(f"liftplan: error: {message}", file=sys.stderr)
    return BAD_INPUT


def _plan_text(result, args, interrupted=None):
    """The plan as printed: its table, or its JSON with ``--json``; ``interrupted`` the
    :class:`~liftplan.planner.search.evaluator.Interrupted` that left it (marked so)."""
    from liftplan.planner.output.console.summary import summary as plan_table

    if args.json:
        out = {**result.to_json(), "checks": [c.to_json() for c in result.checks]}
        if interrupted is not None:
            out["interrupted"] = True
            out["interrupted_in"] = interrupted.phase
            out["search_finished"] = interrupted.finished
        return json.dumps(_stamped(out))
    table = plan_table(result)
    if interrupted is None:
        return table
    if interrupted.finished:
        head = f"INTERRUPTED: the search's plan ({_where(interrupted)})"
    else:
        head = f"INTERRUPTED: best plan found so far (the search did not finish; {_where(interrupted)})"
    return f"{head}\n{table}"


def _where(interrupted):
    """Where a Ctrl-C landed, for the INTERRUPTED lines."""
    if interrupted.finished:
        return f"the search had finished; Ctrl-C in the {interrupted.phase}"
    return f"Ctrl-C in the {interrupted.phase}"


def _lift(args):
    from pathlib import Path

    from liftplan.planner.output.paths import FIGURE_TYPES, make_parent, output_file, replaced

    for option, value in (("--to", args.to), ("--step", args.step), ("--speed", args.speed)):
        if value is not None and not (math.isfinite(value) and value > 0):
            unit = "m/min" if option == "--speed" else "m"
            raise InvalidScene(f"{option} {value:g}: expected a finite number of {unit} > 0")
    scene_path = Path(args.scene)
    default = f"{scene_path.stem}_load_curve.png"
    figure = output_file(default if args.figure is None else args.figure, "--figure", FIGURE_TYPES)
    view = _view_file(args)
    from liftplan.model.lift import load_curve
    from liftplan.model.scene.file import load_scene
    from liftplan.model.scene.plausibility import scene_warnings
    from liftplan.model.water.breakout import bed_warnings
    from liftplan.planner.output.console.lift import lift_table
    from liftplan.planner.output.figures.lift import lift_figure as draw

    scene = load_scene(scene_path)
    _warn(scene_warnings(scene) + bed_warnings(scene))
    # progress from the first second where someone watches: a slow hoist speed makes the
    # draining's integration minutes long (its work grows as 1 / speed)
    curve = load_curve(scene, stop=args.to, step=args.step, speed=args.speed, progress=sys.stderr.isatty())
    swl = min((c.swl for c in scene.cranes if c.swl), default=None)
    unwritten = None
    try:
        make_parent(figure)
        with replaced(figure) as temporary:  # whole or not at all
            draw(curve, swl=swl).savefig(temporary, dpi=120)
    except OSError as err:  # a full disk, a folder removed meanwhile: the table still prints
        unwritten = f"--figure {figure}: cannot write ({err.strerror or err})"
    else:
        print(f"liftplan: wrote {figure}", file=sys.stderr)
    unwritten = _save_view(view, "lift_view", scene, curve) or unwritten
    if args.json:
        print(json.dumps(_stamped(curve.to_json())))
    else:
        print(lift_table(scene, curve))
    code = _verdict(curve.checks, table=not args.json)  # crane vessels' limits over the curve
    return _unwritten(unwritten) or code


def _view_file(args):
    """``--view FILE`` checked before any computation (None when not given)."""
    # start-up: the standard library and the path rule only
    from liftplan.planner.output.view.command import checked

    return checked(args.view)


def _save_view(path, builder, *result):
    """Write the 3D view of ``result`` (``states.<builder>(*result)``) to ``path`` when asked;
    the reason it could not be written, or None."""
    if path is None:
        return None
    # start-up: plotly and the view's geometry only when a view is asked for
    from liftplan.planner.output.view import states
    from liftplan.planner.output.view.command import save_view

    return save_view(path, lambda: getattr(states, builder)(*result))


def _view(args):
    # start-up: plotly and the solvers only when the view command runs
    from liftplan.planner.output.view.command import run

    return run(args)


def _batch(args):
    from liftplan.planner.batch.run import run_study
    from liftplan.planner.batch.study import load_study
    from liftplan.planner.output.console.tables import batch_table
    from liftplan.planner.output.paths import output_file

    if args.workers is not None and args.workers < 1:
        raise InvalidScene(f"--workers {args.workers}: expected an integer >= 1")
    workers = args.workers
    cores = _cores()
    if workers is not None and args.scheduler is None and workers > cores:
        # accepted, with as many workers as cores: each local worker is a process running one
        # CPU-bound case at a time, so more of them than cores only add memory (a Python
        # process with casadi each) and start-up (each warms up its solvers), never speed
        _warn(
            [
                f"--workers {workers}: more than the {cores} cores this process may use; "
                f"running {cores} (more workers than cores add memory and start-up, not speed)"
            ]
        )
        workers = cores
    if args.output is not None:
        output_file(args.output, "--output")
    study = load_study(args.study)
    if args.output is None:
        output_file(study.output, "study.output")
    try:
        summary = run_study(
            study,
            scheduler=args.scheduler,
            workers=workers,
            restart=args.restart,
            progress=not args.no_progress,
            output=args.output,
        )
    except KeyboardInterrupt:
        print(
            "liftplan: interrupted; the finished cases are kept, run the same command to resume",
            file=sys.stderr,
        )
        return INTERRUPTED
    print(batch_table(study, summary))


def _sequence(args):
    from liftplan.planner.sequence.command import run  # start-up: loaded when the command runs

    return run(args)


def _cores():
    """CPU cores this process may run on (its affinity where the system tells it)."""
    try:
        return len(os.sched_getaffinity(0)) or 1
    except AttributeError:  # not on macOS or Windows
        return os.cpu_count() or 1


def _interrupt(err):
    """Whether ``err`` is a Ctrl-C in disguise: casadi turns the KeyboardInterrupt raised
    inside its calls into a RuntimeError naming it (and callers may wrap that in turn)."""
    seen = set()
    while err is not None and id(err) not in seen:
        seen.add(id(err))
        if isinstance(err, KeyboardInterrupt) or "KeyboardInterrupt" in str(err):
            return True
        err = err.__cause__ or err.__context__
    return False


def _watch(args):
    # start-up: the watch commands' modules load only when they run
    from liftplan.planner.watch.command import run_simulate, run_watch

    return run_watch(args) if args.command == "watch" else run_simulate(args)


def _run(args):
    command = {
        "plan": _plan,
        "lift": _lift,
        "solve": _solve,
        "batch": _batch,
        "view": _view,
        "watch": _watch,
        "simulate": _watch,
        "sequence": _sequence,
    }[args.command]
    try:
        try:
            # numpy's RuntimeWarnings (an overflow in a trial step, 0/0 in a row the search
            # then rules out, matplotlib's ticks on a huge axis) are not for the user: every
            # result the command prints is checked as finite or said to be missing, and the
            # warnings turned one-line error messages into several lines (issue 29 item 13)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                return command(args) or 0
        except Exception as err:
            if _interrupt(err):
                raise KeyboardInterrupt from None
            raise
    except EquilibriumNotFound as err:
        print(f"liftplan: no equilibrium: {err}", file=sys.stderr)
        return NO_SOLUTION
    except PlanInfeasible as err:
        print(f"liftplan: no feasible plan: {err}", file=sys.stderr)
        return NO_SOLUTION
    except MissingExtra as err:  # an optional part not installed: which extra to install
        print(f"liftplan {args.command}: {err}", file=sys.stderr)
        return BAD_INPUT
    except LiftPlanError as err:
        print(f"liftplan: error: {err}", file=sys.stderr)
        return BAD_INPUT


def main(argv=None):
    """Entry point; returns the exit code (see the module docstring)."""
    args = _parser().parse_args(argv)
    try:
        code = _run(args)
        sys.stdout.flush()  # a closed pipe shows here, not at exit
        return code
    except KeyboardInterrupt:
        print("liftplan: interrupted", file=sys.stderr)
        return INTERRUPTED
    except BrokenPipeError:
        # the reader went away (``| head``): nothing more to say; stop Python's own flush at
        # exit from failing on the same pipe
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return BROKEN_PIPE
    except Exception as err:  # noqa: BLE001 - the command line never shows a traceback
        if args.debug:
            raise
        print(f"liftplan: internal error: {type(err).__name__}: {err} (rerun with --debug)", file=sys.stderr)
        return INTERNAL


if __name__ == "__main__":
    sys.exit(main())
