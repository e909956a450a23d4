"""``liftplan sequence FILE [--json] [--figure F] [--report DIR]``: argparse set-up and handler."""

from __future__ import annotations

import json
import sys

#: Exit code when a check failed (the command line's, planner/cli.py).
CHECK_FAILED = 4


def add_parser(commands):
    """Register ``sequence`` on the command line's sub-parsers."""
    cmd = commands.add_parser(
        "sequence", help="turnover and upending: every angle an equilibrium, the worst loads between steps"
    )
    cmd.add_argument("file", help="sequence file (TOML with [sequence] or [[stages]])")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--figure", metavar="F", help="hook and lug loads against the angle, .png, .pdf or .svg")
    cmd.add_argument(
        "--report", metavar="DIR", help="write report.html and sequence.json into DIR (created if missing)"
    )
    cmd.add_argument(
        "--view",
        metavar="FILE",
        help="also write the 3D view, each reported angle a state of its slider, .html or .glb",
    )
    return cmd


def run(args):
    """Run ``liftplan sequence``; returns the exit code (4 when a check failed)."""
    # start-up: this module is imported for the parser (liftplan --help); the rest when it runs
    from liftplan.planner.output import paths  # start-up

    figure = (
        paths.output_file(args.figure, "--figure", paths.FIGURE_TYPES) if args.figure is not None else None
    )
    folder = paths.output_folder(args.report, "--report") if args.report is not None else None
    from liftplan.planner.output.view import command as view_command  # start-up

    view = view_command.checked(args.view)
    from liftplan.model.sequence import run_sequence  # start-up
    from liftplan.model.sequence.file import load_lug_choice  # start-up
    from liftplan.model.sequence.lugplan import plan_lugs  # start-up
    from liftplan.model.sequence.objects import LugChoice, sequence_warnings  # start-up
    from liftplan.model.version import stamped  # start-up
    from liftplan.planner.sequence.console import lug_plan_lines, sequence_table  # start-up

    read = load_lug_choice(args.file)
    plan = None
    if isinstance(read, LugChoice):
        for line in sequence_warnings(read.sequence({n: c[0] for n, c in read.open})):
            print(f"liftplan: warning: {line}", file=sys.stderr)
        plan = plan_lugs(read)
        result = plan.result
    else:
        for line in sequence_warnings(read):
            print(f"liftplan: warning: {line}", file=sys.stderr)
        result = run_sequence(read)
    out = result.to_json()
    if plan is not None:
        out["lug_plan"] = plan.to_json()
    payload = stamped(out)
    if figure is not None:
        from liftplan.planner.sequence.figure import sequence_figure  # start-up: matplotlib

        paths.make_parent(figure)
        with paths.replaced(figure) as temporary:
            sequence_figure(result).savefig(temporary, dpi=130)
        print(f"liftplan: wrote {figure}", file=sys.stderr)
    if folder is not None:
        from liftplan.planner.sequence.report import write_sequence_report  # start-up: matplotlib

        for path in write_sequence_report(result, folder, payload):
            print(f"liftplan: wrote {path}", file=sys.stderr)
    unwritten = None
    if view is not None:
        from liftplan.planner.sequence.view import sequence_view  # start-up: plotly

        unwritten = view_command.save_view(view, lambda: sequence_view(result))
    if args.json:
        print(json.dumps(payload))
    else:
        if plan is not None:
            print(lug_plan_lines(plan))
        print(sequence_table(result))
        for check in result.checks:
            if not check.ok:
                print(check.line())
        failed = sum(not c.ok for c in result.checks)
        print(
            f"checks: {len(result.checks) - failed} of {len(result.checks)} met"
            + (f", {failed} FAILED" if failed else "")
        )
    if unwritten is not None:
        print(f"liftplan: error: {unwritten}", file=sys.stderr)
        return 2
    failed = [c for c in result.checks if not c.ok]
    if failed:
        names = ", ".join(f"{c.name} {c.subject}" for c in failed[:5])
        print(f"liftplan: {len(failed)} check(s) failed: {names} (exit {CHECK_FAILED})", file=sys.stderr)
        return CHECK_FAILED
    return 0
