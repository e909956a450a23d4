"""The ``liftplan`` command line.

argparse (standard library) rather than click/typer: four sub-commands with a few options do
not justify three more dependencies, and argparse's errors are already one line.
"""

from __future__ import annotations

import argparse
import json
import sys

from liftplan.model import (
    EquilibriumNotFound,
    LiftPlanError,
    PlanInfeasible,
    load_scene,
    solve,
)

from .console import batch_table, equilibrium_table, plan_table
from .plan import plan
from .problemfile import load_problem

# exit codes
BAD_INPUT = 2
NO_SOLUTION = 1
INTERNAL = 3


def _parser():
    parser = argparse.ArgumentParser(
        prog="liftplan",
        description="Multi-crane lift planning for salvage and heavy-block rigging.",
    )
    parser.add_argument("--debug", action="store_true", help="show tracebacks of internal errors")
    commands = parser.add_subparsers(dest="command", required=True)
    solve_cmd = commands.add_parser("solve", help="tensions and pose of a scene")
    solve_cmd.add_argument("scene", help="scene file (TOML)")
    solve_cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    solve_cmd.add_argument(
        "--model",
        choices=["elastic", "paper-elastic", "rigid", "hydrostatic", "inclined"],
        help="override the scene's [analysis] model",
    )
    solve_cmd.add_argument(
        "--method", choices=["newton", "paper-newton"], default="newton",
        help="stranded hull: casadi Newton (default) or the paper's J^T D J iteration",
    )
    lift_cmd = commands.add_parser(
        "lift", help="load curve of a lift off the seabed and through the waterline")
    lift_cmd.add_argument("scene", help="scene file with [hull], [water], cranes (and usually [ground])")
    lift_cmd.add_argument("--to", type=float, metavar="M",
                          help="last hoist in m (default: the hull 1 m clear of the water)")
    lift_cmd.add_argument("--step", type=float, default=0.25, metavar="M", help="hoist step in m (0.25)")
    lift_cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    lift_cmd.add_argument("--figure", metavar="PNG",
                          help="where to save the figure (default: SCENE_load_curve.png next to the scene)")
    plan_cmd = commands.add_parser("plan", help="choose lugs and boom heights for a lift")
    plan_cmd.add_argument("scene", help="planning scene file (TOML with [[candidates]], [plan])")
    plan_cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    plan_cmd.add_argument("--report", metavar="DIR",
                          help="write report.html (and report.pdf with WeasyPrint), "
                               "plan_scene.toml and plan.json into DIR")
    plan_cmd.add_argument("--top", type=int, metavar="K", help="rank the best K lug sets")
    batch_cmd = commands.add_parser(
        "batch", help="run a batch study (many plans, or one plan checked many times) on Dask")
    batch_cmd.add_argument("study", help="study file (TOML with [study], [sweep], [sample])")
    batch_cmd.add_argument("--scheduler", metavar="ADDRESS",
                           help="a running Dask scheduler, e.g. tcp://10.0.0.5:8786 "
                                "(default: a local cluster)")
    batch_cmd.add_argument("--workers", type=int, metavar="N",
                           help="local cluster size (default: one per core)")
    batch_cmd.add_argument("--output", metavar="CSV", help="the table to write (default: the study's)")
    batch_cmd.add_argument("--restart", action="store_true",
                           help="discard an interrupted run's rows instead of resuming it")
    batch_cmd.add_argument("--no-progress", action="store_true", help="no progress bar")
    return parser


def _plan(args):
    problem = load_problem(args.scene)
    if args.top is not None and args.top < 1:
        raise LiftPlanError(f"--top {args.top}: expected an integer >= 1")
    result = plan(problem, top=args.top)
    if args.report:
        from .report import write_report  # matplotlib only when a report is asked for

        files = write_report(result, args.report)
        written = [files.html, files.pdf, files.scene, files.json]
        print("liftplan: wrote " + ", ".join(str(f) for f in written if f), file=sys.stderr)
    if args.json:
        print(json.dumps(result.to_json()))
    else:
        print(plan_table(result))


def _lift(args):
    from pathlib import Path

    from liftplan.model.lift import load_curve

    from .console import load_curve_table
    from .figures import load_curve as draw

    scene = load_scene(args.scene)
    curve = load_curve(scene, stop=args.to, step=args.step)
    figure = Path(args.figure) if args.figure else Path(args.scene).with_name(
        Path(args.scene).stem + "_load_curve.png")
    swl = min((c.swl for c in scene.cranes if c.swl), default=None)
    draw(curve, swl=swl).savefig(figure, dpi=120)
    print(f"liftplan: wrote {figure}", file=sys.stderr)
    if args.json:
        print(json.dumps(curve.to_json()))
    else:
        print(load_curve_table(scene, curve))


def _batch(args):
    from .batch import run_study
    from .study import load_study

    if args.workers is not None and args.workers < 1:
        raise LiftPlanError(f"--workers {args.workers}: expected an integer >= 1")
    study = load_study(args.study)
    try:
        summary = run_study(study, scheduler=args.scheduler, workers=args.workers,
                            restart=args.restart, progress=not args.no_progress, output=args.output)
    except KeyboardInterrupt:
        print("liftplan: interrupted; the finished cases are kept, run the same command to resume",
              file=sys.stderr)
        raise SystemExit(130) from None
    print(batch_table(study, summary))


def _solve(args):
    scene = load_scene(args.scene)
    eq = solve(scene, model=args.model, method=args.method)
    if args.json:
        print(json.dumps(eq.to_json()))
    else:
        print(equilibrium_table(scene, eq))


def main(argv=None):
    """Entry point; returns the exit code (0 success, 1 no equilibrium or no feasible plan,
    2 bad input, 3 internal error)."""
    args = _parser().parse_args(argv)
    try:
        {"plan": _plan, "lift": _lift, "solve": _solve, "batch": _batch}[args.command](args)
    except EquilibriumNotFound as err:
        print(f"liftplan: no equilibrium: {err}", file=sys.stderr)
        return NO_SOLUTION
    except PlanInfeasible as err:
        print(f"liftplan: no feasible plan: {err}", file=sys.stderr)
        return NO_SOLUTION
    except LiftPlanError as err:
        print(f"liftplan: error: {err}", file=sys.stderr)
        return BAD_INPUT
    except Exception as err:  # noqa: BLE001 - the command line never shows a traceback
        if args.debug:
            raise
        print(f"liftplan: internal error: {type(err).__name__}: {err} (rerun with --debug)",
              file=sys.stderr)
        return INTERNAL
    return 0


if __name__ == "__main__":
    sys.exit(main())
