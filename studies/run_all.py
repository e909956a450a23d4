"""Run every study in order; each writes its data to studies/out/ first, then its summary.

Run:  python studies/run_all.py            (about 55 minutes on 2 cores, 15 of them combinations)
      python studies/run_all.py --skip report_screenshot   (no Chromium on this machine)
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).parent
#: In order: stranded_methods feeds speed_accuracy's hydrostatics panel.
STUDIES = [
    "table3",
    "stranded_methods",
    "least_model",
    "vessel_speed",
    "vessel_plan",
    "speed_accuracy",
    "failure_modes",
    "fleet_objectives",
    "many_points",
    "strength_timing",
    "vlcc_fitted",
    "flexible_hull",
    "flexible_ground",
    "draining",
    "tilt_per_direction",
    "rope_lengths",
    "hook_montecarlo",
    "ferry_strength",
    "combinations",
    "planner_scale",
    "local_girder",
    "many_ropes_timing",
    "benchmarks",
    "jit_cache",
    "watch_speed",
    "watch_replay",
    "sequence_speed",
    "report_screenshot",
]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skip", nargs="*", default=[], choices=STUDIES, help="studies to leave out")
    args = parser.parse_args()
    failed = []
    for name in STUDIES:
        if name in args.skip:
            continue
        start = time.perf_counter()
        result = subprocess.run([sys.executable, str(HERE / f"{name}.py")], stdout=subprocess.DEVNULL)
        print(
            f"{name}: {'ok' if result.returncode == 0 else 'FAILED'} ({time.perf_counter() - start:.0f} s)",
            file=sys.stderr,
        )
        if result.returncode:
            failed.append(name)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
