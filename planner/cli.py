"""The ``liftplan`` command line.

argparse (standard library) rather than click/typer: two sub-commands with a few options do
not justify three more dependencies, and argparse's errors are already one line.
"""

from __future__ import annotations

import argparse
import json
import sys

from liftplan.model import EquilibriumNotFound, LiftPlanError, load_scene, solve

from .console import equilibrium_table

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
        choices=["elastic", "paper-elastic", "rigid"],
        help="override the scene's [analysis] model",
    )
    return parser


def _solve(args):
    scene = load_scene(args.scene)
    eq = solve(scene, model=args.model)
    if args.json:
        print(json.dumps(eq.to_json()))
    else:
        print(equilibrium_table(scene, eq))


def main(argv=None):
    """Entry point; returns the exit code (0 converged, 1 no equilibrium, 2 bad input)."""
    args = _parser().parse_args(argv)
    try:
        _solve(args)
    except EquilibriumNotFound as err:
        print(f"liftplan: no equilibrium: {err}", file=sys.stderr)
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
