"""Running the command line as a user does: in a separate process."""

import json
import subprocess
import sys


def run(*args):
    return subprocess.run(
        [sys.executable, "-m", "liftplan.planner.cli", *args],
        capture_output=True,
        text=True,
        timeout=120,
    )


HEAVY = ("cvxpy", "dask", "distributed", "matplotlib", "scipy")


def imported_after(code):
    """The heavy modules loaded by ``code`` in a fresh interpreter."""
    probe = f"import sys\n{code}\nprint(__import__('json').dumps([m for m in {HEAVY!r} if m in sys.modules]))"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])
