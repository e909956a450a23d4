"""Start-up time of the command line (issue 14 item 7): whole process, wall clock, median of 5.

Each command is run as a user runs it (the ``liftplan`` found on PATH, which may be a pyenv
shim: its cost is part of what a user waits for and is measured separately), output to
/dev/null, after one unmeasured warm-up run (the OS file cache, the casadi JIT cache). Also
measured: a bare ``python -c pass`` (interpreter floor) and, from ``python -X importtime``,
the slowest top-level imports left on the ``solve`` path.

Run:  python studies/startup.py        (writes studies/out/startup.json, prints a table;
                                        about 30 s on 2 cores)
"""

from __future__ import annotations

import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).parent
ROOT = HERE.parent
RUNS = 5
#: The goal of issue 14 item 7 for --help and solve  [s].
GOAL = 0.6
COMMANDS = {
    "liftplan --help": ["--help"],
    "liftplan solve examples/tanker_upright.toml": ["solve", "examples/tanker_upright.toml"],
    "liftplan solve examples/tanker_upright.toml --json": ["solve", "examples/tanker_upright.toml", "--json"],
    "liftplan plan examples/tanker_plan.toml": ["plan", "examples/tanker_plan.toml"],
}


def wall(argv, runs=RUNS):
    """Median and all wall times of ``argv`` run ``runs`` times (after one warm-up)  [s]."""
    times = []
    for k in range(runs + 1):
        start = time.perf_counter()
        result = subprocess.run(argv, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        elapsed = time.perf_counter() - start
        if result.returncode != 0:
            raise SystemExit(f"{' '.join(argv)}: exit {result.returncode}")
        if k:
            times.append(elapsed)
    return statistics.median(times), times


def slowest_imports(args, count=8):
    """The ``count`` largest cumulative imports of a command, from ``-X importtime``  [s]."""
    out = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "liftplan.planner.cli", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    rows = []
    for line in out.stderr.splitlines():
        match = re.match(r"import time:\s+\d+ \|\s+(\d+) \|( *)(\S+)", line)
        if match and not match.group(2).strip() and len(match.group(2)) == 1:  # top level only
            rows.append((match.group(3), int(match.group(1)) * 1e-6))
    return sorted(rows, key=lambda r: -r[1])[:count]


def main():
    command = shutil.which("liftplan")
    if command is None:
        raise SystemExit("liftplan is not on PATH: pip install -e . first")
    results = {}
    for name, args in COMMANDS.items():
        median, times = wall([command, *args])
        results[name] = {"median": median, "runs": times}
    floor, floor_runs = wall([sys.executable, "-c", "pass"])
    # a pyenv shim in front of the entry point costs a user ~0.1 s more on every command
    shim_path = Path(os.environ.get("PYENV_ROOT", "~/.pyenv")).expanduser() / "shims" / "liftplan"
    shim = None
    if shim_path.exists() and os.path.realpath(shim_path) != os.path.realpath(command):
        shim = {
            name: wall([str(shim_path), *args])[0] for name, args in COMMANDS.items() if args[0] != "plan"
        }
    data = {
        "command": command,
        "runs": RUNS,
        "goal": GOAL,
        "cpus": os.cpu_count(),
        "python": sys.version.split()[0],
        "commands": results,
        "python_floor": {"median": floor, "runs": floor_runs},
        "through_pyenv_shim": shim,
        "solve_imports": [
            {"module": m, "seconds": s} for m, s in slowest_imports(["solve", "examples/tanker_upright.toml"])
        ],
    }
    (HERE / "out").mkdir(exist_ok=True)
    (HERE / "out" / "startup.json").write_text(json.dumps(data, indent=1) + "\n")

    print(f"wall time, median of {RUNS} (whole process, {command})")
    print(f"{'command':<66}{'median [s]':>12}{'goal':>8}")
    for name, r in results.items():
        goal = f"< {GOAL}" if COMMANDS[name][0] != "plan" else ""
        print(f"{name:<66}{r['median']:>12.3f}{goal:>8}")
    print(f"{'python -c pass':<66}{floor:>12.3f}")
    for name, median in (shim or {}).items():
        print(f"{name + ' (pyenv shim)':<66}{median:>12.3f}{'< ' + str(GOAL):>8}")
    print("\nlargest top-level imports of solve (cumulative):")
    for row in data["solve_imports"]:
        print(f"  {row['module']:<40}{row['seconds']:>8.3f} s")


if __name__ == "__main__":
    main()
