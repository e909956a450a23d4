"""The lug-choice MIP with and without the hook tolerance: the tanker's 4 of 16, one run.

Issue 24 item 4 asks that the MIP prove the tanker's 4 of 16 (examples/tanker_plan.toml, CG
box) with its hook_tolerance = 0.02 m. Each case is planned with ``search = "mip"`` in its own
process with ``plan.time_limit = LIMIT`` s, and beside it the exact search's plan of the same
problem (the optimum the MIP must find and prove). Three hook-error formulations of the MIP
are compared at 0.02 m, in the same run: ``sets`` (today's: the set-wise rows of
planner/search/mip_hooks.py, each set's widenings and its own bound weighted by x_S),
``fit`` (the plane fit's rows with McCormick products, each set's exact worst over the whole
hook box at the box scenarios; forced by SET_CAP = 0) and ``cuts`` (one hook-error scenario
per round; forced by treating the candidates as not on one plane).

Run:  python studies/mip_hook.py           (studies/out/mip_hook.json, .md)
      python studies/mip_hook.py --quick   (exact and today's MIP only: no 300 s runs)
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import multiprocessing
import os
import platform
import sys
import time
from pathlib import Path

HERE = Path(__file__).parent
OUT = HERE / "out"
ROOT = HERE.parent
#: Time limit of every plan  [s].
LIMIT = 300.0
CASES = [
    ("exact", 0.0, "box"),
    ("mip", 0.0, "box"),
    ("exact", 0.02, "box"),
    ("mip", 0.02, "sets"),
    ("mip", 0.02, "fit"),
    ("mip", 0.02, "cuts"),
]
#: The formulations before today's (each runs to its time limit).
BEFORE = ("fit", "cuts")


def _run(case, queue):
    from liftplan.planner import load_problem
    from liftplan.planner.search import mip
    from liftplan.planner.search.methods import search

    method, hook, form = case
    if form == "cuts":  # the formulation before the box rows
        mip.on_one_plane = lambda problem: False
    if form == "fit":  # the plane fit's rows, not the set-wise ones
        mip.SET_CAP = 0
    problem = dataclasses.replace(
        load_problem(ROOT / "examples" / "tanker_plan.toml"),
        search=method,
        hook_tolerance=hook,
        time_limit=LIMIT,
    )
    started = time.perf_counter()
    ranking, stats = search(problem, 1)
    queue.put(
        {
            "method": method,
            "hook_tolerance": hook,
            "form": form,
            "seconds": time.perf_counter() - started,
            "stopped": stats.stopped,
            "rounds": stats.refined,
            "lugs": list(ranking[0].lugs),
            "worst": ranking[0].worst_value,
            "lower_bound": stats.lower_bound,
            "relative_gap": stats.relative_gap,
        }
    )


def measure(case):
    """One plan in a fresh process."""
    context = multiprocessing.get_context("spawn")
    queue = context.Queue()
    process = context.Process(target=_run, args=(case, queue))
    process.start()
    out = queue.get()
    process.join()
    return out


def _gap(gap):
    """A relative gap as a percentage, or in full where the percentage would read 0.0 %."""
    return f"{100 * gap:.1f} %" if gap == 0.0 or gap >= 5e-4 else f"{gap:.1e}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="exact and today's MIP only")
    args = parser.parse_args()
    rows = []
    for case in CASES:
        if args.quick and case[2] in BEFORE:
            continue
        row = measure(case)
        row["load"] = os.getloadavg()[0]
        rows.append(row)
        print(json.dumps(row), file=sys.stderr)
    meta = dict(
        date=time.strftime("%Y-%m-%d %H:%M"), machine=platform.machine(), cpus=multiprocessing.cpu_count()
    )
    OUT.mkdir(exist_ok=True)
    (OUT / "mip_hook.json").write_text(json.dumps({"meta": meta, "rows": rows}, indent=1) + "\n")
    lines = [
        f"Command: `python studies/mip_hook.py{' --quick' if args.quick else ''}`; "
        f"{meta['date']}, {meta['cpus']} cores {meta['machine']}; "
        f"every plan in its own process with time_limit {LIMIT:g} s.",
        "",
        "| search | hook tolerance [m] | MIP hook rows | time [s] | stopped | rounds | worst [t] "
        "| lower bound [t] | gap | lugs | load after |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        form = r["form"] if r["method"] == "mip" and r["hook_tolerance"] > 0 else ""
        lines.append(
            f"| {r['method']} | {r['hook_tolerance']:g} | {form} | {r['seconds']:.1f} | {r['stopped']} "
            f"| {r['rounds']} | {r['worst']:.6g} | {r['lower_bound']:.6g} | {_gap(r['relative_gap'])} "
            f"| {' '.join(r['lugs'])} | {r['load']:.1f} |"
        )
    (OUT / "mip_hook.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
