"""``liftplan watch`` and ``liftplan simulate``: their options (the handlers, loaded when a
command runs, are in :mod:`.handlers`).

``watch PLAN --readings FILE``: PLAN is a planning file (the plan is made first) or a plan
JSON (``liftplan plan --json``, or ``plan.json`` of ``--report``, which carries the plan's
``"watch"`` object). One line per reading on stdout (JSON Lines with ``--json``); with
``--follow`` the file is followed as it grows (a data logger's) until Ctrl-C (exit 130) or
``--idle`` seconds without a new line. Exit 0, or 4 when a row was flagged or the stop
signal was raised (every line is printed).

``simulate PLAN --output readings.csv``: a seeded synthetic lift (:mod:`.simulate`).
"""

from __future__ import annotations


def add_parser(commands):
    """Register ``watch`` and ``simulate`` on the command line's sub-parsers."""
    watch = commands.add_parser(
        "watch", help="estimate weight, CG and hook errors from readings; advise hook moves"
    )
    watch.add_argument("plan", help="planning file (TOML; planned first) or a plan JSON (plan --json)")
    watch.add_argument(
        "--readings", required=True, metavar="FILE", help="readings CSV or JSON, one reading a line"
    )
    watch.add_argument("--json", action="store_true", help="one JSON object per reading (JSON Lines)")
    watch.add_argument("--follow", action="store_true", help="follow the file as it grows (Ctrl-C stops)")
    watch.add_argument(
        "--idle",
        type=float,
        metavar="S",
        help="with --follow: stop after S seconds without a new line (default: never)",
    )
    simulate = commands.add_parser(
        "simulate", help="a seeded synthetic lift of a plan: readings with a known truth"
    )
    simulate.add_argument("plan", help="planning file (TOML; planned first) or a plan JSON (plan --json)")
    simulate.add_argument("--output", required=True, metavar="CSV", help="the readings file to write")
    simulate.add_argument(
        "--errors",
        default="",
        metavar="K=V,...",
        help="standard deviations of the drawn errors: hook=M (0.02), cog=M per axis (0.1), "
        "weight=FRACTION (0.02)",
    )
    simulate.add_argument(
        "--noise",
        default="",
        metavar="K=V,...",
        help="sensor noise: load_cell=T, inclinometer=DEG, hook=M (default: the plan's [readings] "
        "accuracies)",
    )
    simulate.add_argument("--seed", type=int, default=0, help="random seed (0)")
    simulate.add_argument("--steps", type=int, default=60, help="readings (60)")
    simulate.add_argument("--rate", type=float, default=1.0, metavar="HZ", help="readings per second (1)")
    simulate.add_argument(
        "--drift",
        type=float,
        default=0.0,
        metavar="M",
        help="each hook error's random walk, m per sqrt(s) (0)",
    )
    simulate.add_argument("--no-inclinometer", action="store_true", help="no heel and trim columns")
    simulate.add_argument(
        "--hook-heights", action="store_true", help="hook:NAME columns of measured hook heights"
    )
    simulate.add_argument("--truth", metavar="JSON", help="also write the truth behind each reading here")


def run_watch(args):
    """``liftplan watch``: the exit code."""
    # start-up: the watch's modules (cvxpy, the planner) load only when it runs
    from liftplan.planner.watch.handlers import watch

    return watch(args)


def run_simulate(args):
    """``liftplan simulate``: the exit code."""
    # start-up: the simulation's modules load only when it runs
    from liftplan.planner.watch.handlers import simulate_lift

    return simulate_lift(args)
