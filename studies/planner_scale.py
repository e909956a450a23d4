"""The planner's speed against its accuracy, on a seeded set of planning problems.

Problems: the 1500 GT tanker's hull with C candidates (C / 2 frame stations between the aft
peak and the collision bulkhead, a port and a starboard candidate on each; the papers' deck
height; the example's CG box, weight, cranes and tolerances; no hook error), n cranes, from 16
to 200 candidates (past 5 million sets the local search only), and 5 and 6 of 16 without
the CG box; and the 154 m hull's 26 of 80
(examples/hull154_plan.toml). Methods, each on every problem it can run:

* ``exact``: every lug set, bounded and pruned (n >= 5: the pair bound refined to the LP's
  dual bound); proves the optimum;
* ``exact, pair bound``: the same without the dual bound (today's method before it);
* ``exact, gap 10 %`` and ``gap 1 %``: stops once the best plan is proved within the gap;
* ``local`` and ``local, gap 1 %``: swaps from an even spread, and on lugs in one plane from
  lugs at both ends of each line too (planner/search/local.py), its lower bound the two-line
  bound refined cell by cell (planner/search/line_cells.py) towards the plan's value (gap 0)
  or 1 % under it; HULL_LIMIT seconds on the 154 m hull, the issue's target;
* ``mip, gap 10 %``, ``1 %``, ``0.1 %`` and ``mip``: the lug-choice MIP (planner/search/mip.py)
  to each gap target within MIP_LIMIT seconds (HULL_LIMIT on the 154 m hull, at 1 %).

Each point: wall time [s] against the excess of the plan's worst spread over the proved
optimum [%] (the exact search's). The Pareto front is drawn. A method that would exceed
LIMIT seconds is stopped there and its best plan and honest gap recorded.

Run:  python studies/planner_scale.py     (writes studies/out/planner_scale.json and .png)
      python studies/planner_scale.py --quick   (the 16-candidate problems only)
      python studies/planner_scale.py --figure-only   (redraw from the JSON)
      python studies/planner_scale.py --only exact local mip   (re-run those methods; the
                                              others' rows are kept, each row dated)
      python studies/planner_scale.py --only mip --problems "154 m hull"   (one problem)
      python studies/planner_scale.py --table   (docs/studies.md's table, from the JSON)
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
OUT = HERE / "out"
ROOT = HERE.parent
LIMIT = 300.0


def tanker_with(candidates, cranes, cog_box=True):
    from liftplan.model.frames import choi_to_zup
    from liftplan.planner import load_problem
    from liftplan.planner.problem.definition import Candidate, CogEnvelope

    base = load_problem(ROOT / "examples" / "tanker_plan.toml")
    if candidates == 16:
        points = base.candidates
    else:
        stations = np.linspace(4.2, 73.6, candidates // 2)
        points = tuple(
            Candidate(f"F{k + 1:02d}-{side}", choi_to_zup((float(x), 6.0, z)))
            for k, x in enumerate(stations)
            for side, z in (("P", 0.0), ("S", 12.0))
        )
    extra = {} if cog_box else dict(cog_envelope=CogEnvelope())
    return dataclasses.replace(
        base, candidates=points, cranes=cranes, hook_tolerance=0.0, fleet=(), top=1, time_limit=LIMIT, **extra
    )


def problems(quick):
    cases = [(16, 4), (16, 5), (16, 6)] + (
        [] if quick else [(16, 8), (24, 5), (40, 4), (40, 5), (100, 4), (200, 4), (40, 12)]
    )
    for candidates, cranes in cases:
        yield f"tanker {cranes} of {candidates}", tanker_with(candidates, cranes)
    for candidates, cranes in [(16, 5), (16, 6)]:  # the CG at its nominal point only
        yield f"tanker {cranes} of {candidates}, no CG box", tanker_with(candidates, cranes, False)
    if not quick:
        from liftplan.planner import load_problem

        yield "154 m hull 26 of 80", load_problem(ROOT / "examples" / "hull154_plan.toml")


#: The MIP's time limit [s] (its local-search incumbent included); on the 154 m hull the
#: issue's target, 60 s.
MIP_LIMIT, HULL_LIMIT = 120.0, 60.0

METHODS = {
    "exact": dict(search="exact", gap=0.0),
    "exact, pair bound": dict(search="exact", gap=0.0),
    "exact, gap 10 %": dict(search="exact", gap=0.10),
    "exact, gap 1 %": dict(search="exact", gap=0.01),
    "local": dict(search="local", gap=0.0),  # the file's own gap set aside
    "local, gap 1 %": dict(search="local", gap=0.01),
    "mip, gap 10 %": dict(search="mip", gap=0.10),
    "mip, gap 1 %": dict(search="mip", gap=0.01),
    "mip, gap 0.1 %": dict(search="mip", gap=0.001),
    "mip": dict(search="mip", gap=0.0),
}


def run(problem, method):
    import liftplan.planner.search.exact as exact
    import liftplan.planner.search.methods as methods

    exact.DUAL_BOUND = method != "exact, pair bound"
    changes = dict(METHODS[method])
    if method.startswith("mip"):
        changes["time_limit"] = HULL_LIMIT if problem.cranes > 20 else MIP_LIMIT
    if method.startswith("local") and problem.cranes > 20:
        changes["time_limit"] = HULL_LIMIT
    started = time.perf_counter()
    ranking, stats = methods.search(dataclasses.replace(problem, **changes), 1)
    return dict(
        method=method,
        seconds=time.perf_counter() - started,
        worst=ranking[0].worst_value,
        lower_bound=stats.lower_bound,
        stopped=stats.stopped,
        lugs=list(ranking[0].lugs),
        evaluated=stats.evaluated,
        run=time.strftime("%Y-%m-%d"),
    )


def chosen_methods(problem, only):
    """The methods run on a problem (``only``: name prefixes to keep)."""
    if problem.set_count > 5_000_000:
        methods = ["local", "local, gap 1 %"]
    else:
        methods = [m for m in METHODS if not m.startswith("mip")]
    if problem.cranes >= 8 or len(problem.candidates) >= 40:
        methods = [m for m in methods if m != "exact, pair bound"]  # hours: not run
    if len(problem.candidates) <= 80:  # the MIP's size grows with the candidates x scenarios
        methods += [m for m in METHODS if m.startswith("mip")]
    if problem.cranes > 20:  # the 154 m hull: the 60 s target at a 1 % gap
        methods = [m for m in methods if not m.startswith("mip") or m == "mip, gap 1 %"]
    if only:
        methods = [m for m in methods if any(m.startswith(p) for p in only)]
    return methods


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--figure-only", action="store_true", help="redraw from the JSON")
    parser.add_argument("--table", action="store_true", help="print docs/studies.md's table from the JSON")
    parser.add_argument(
        "--only",
        nargs="+",
        metavar="PREFIX",
        help="run only the methods named so (e.g. exact local mip); the rows "
        "replace those of the same problem and method in the JSON",
    )
    parser.add_argument(
        "--problems",
        nargs="+",
        metavar="PREFIX",
        help="run only the problems named so (e.g. '154 m hull'); with --only",
    )
    args = parser.parse_args()
    OUT.mkdir(exist_ok=True)
    path = OUT / "planner_scale.json"
    if args.figure_only:
        return figure(json.loads(path.read_text()))
    if args.table:
        return print(table(json.loads(path.read_text())))
    kept = json.loads(path.read_text()) if args.only and path.exists() else []
    rows = []
    for name, problem in problems(args.quick):
        if args.problems and not any(name.startswith(p) for p in args.problems):
            continue
        results = [run(problem, m) for m in chosen_methods(problem, args.only)]
        done = {r["method"] for r in results}
        previous = [r for r in kept if r["problem"] == name and r["method"] not in done]
        proved = [r for r in results + previous if r["method"] == "exact" and r["stopped"] == "proved"]
        optimum = proved[0]["worst"] if proved else None
        for r in results:
            r["excess"] = None if optimum is None else 100.0 * (r["worst"] - optimum) / optimum
            r["problem"] = name
            print(
                f"{name:22s} {r['method']:18s} {r['seconds']:8.2f} s  worst {r['worst']:8.3f}"
                f"  bound {r['lower_bound']:8.3f}  {r['stopped']}"
                + ("" if r["excess"] is None else f"  +{r['excess']:.3f} %"),
                flush=True,
            )
        rows += previous + results
    names = {r["problem"] for r in rows}
    rows += [r for r in kept if r["problem"] not in names]
    path.write_text(json.dumps(rows, indent=1))
    figure(rows)


TABLE = [
    "exact",
    "exact, pair bound",
    "exact, gap 10 %",
    "local",
    "local, gap 1 %",
    "mip, gap 10 %",
    "mip, gap 1 %",
    "mip",
]


def table(rows):
    """docs/studies.md's markdown table: per problem and method, time, accuracy and certified gap."""

    def cell(r):
        if r is None:
            return "-"
        t = r["seconds"]
        ts = f"{t:.2f} s" if t < 10 else f"{t:.0f} s" if t >= 100 else f"{t:.1f} s"
        cert = 100 * (r["worst"] - r["lower_bound"]) / r["worst"] if r["worst"] > 0 else 0.0
        gap = f"{cert:.2f} %" if cert < 10 else f"{cert:.1f} %"
        if r["excess"] is not None:
            if r["stopped"] == "proved":
                return f"{ts}, proved"
            acc = "optimum" if r["excess"] < 1e-3 else f"+{r['excess']:.1f} %"
            return f"{ts}, {acc}" + ("" if cert < 1e-3 else f" (gap {gap})" if cert < 99.99 else " (no gap)")
        return f"{ts}, {r['worst']:.2f} t, " + (f"gap {gap}" if cert < 99.99 else "no gap")

    lines = ["| problem | " + " | ".join(TABLE) + " |", "|" + "---|" * (len(TABLE) + 1)]
    for name in dict.fromkeys(r["problem"] for r in rows):
        by = {r["method"]: r for r in rows if r["problem"] == name}
        lines.append(f"| {name} | " + " | ".join(cell(by.get(c)) for c in TABLE) + " |")
    return "\n".join(lines)


def figure(rows):
    """Left: time against the excess over the proved optimum, marker by method, colour by
    problem, each problem's Pareto front. Right: time against the certified gap each method
    states ((worst - lower bound) / worst), every problem."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, gap_ax) = plt.subplots(1, 2, figsize=(15, 6.2))
    markers = dict(zip(METHODS, "osD^vhPXp*"))
    names = list(dict.fromkeys(r["problem"] for r in rows))
    colours = dict(zip(names, plt.cm.tab20.colors))
    for r in rows:
        style = dict(
            marker=markers[r["method"]],
            color=colours[r["problem"]],
            s=40,
            edgecolor="k",
            linewidth=0.4,
            zorder=3,
        )
        certified = max((r["worst"] - r["lower_bound"]) / r["worst"] * 100.0, 1e-3)
        gap_ax.scatter(r["seconds"], certified, **style)
        if r["excess"] is not None:
            ax.scatter(r["seconds"], max(r["excess"], 1e-3), **style)
    for name in names:
        pts = sorted(
            (r["seconds"], max(r["excess"], 1e-3))
            for r in rows
            if r["problem"] == name and r["excess"] is not None
        )
        if not pts:
            continue
        front, best = [], math.inf
        for x, y in pts:
            if y < best:
                front.append((x, y))
                best = y
        ax.step(*zip(*front), where="post", color=colours[name], lw=1.2)
    gap_ax.plot(
        [HULL_LIMIT, HULL_LIMIT, 1e-2],
        [1e-4, 1.0, 1.0],
        color="0.3",
        ls="--",
        lw=1,
        label="the 26-of-80 target: 1 % in 60 s",
    )
    for name in names:
        gap_ax.plot([], [], color=colours[name], lw=3, label=name)
    for method, marker in markers.items():
        gap_ax.scatter([], [], marker=marker, color="0.6", edgecolor="k", label=method)
    for a in (ax, gap_ax):
        a.set_xscale("log")
        a.set_yscale("log")
        a.set_xlabel("wall time [s] (one process on a 2-core machine)")
        a.grid(True, which="both", alpha=0.3)
    gap_ax.set_xlim(ax.get_xlim())
    gap_ax.set_ylim(5e-4, 2e2)
    ax.set_ylabel("worst spread above the proved optimum [%] (1e-3: optimal)")
    ax.set_title("Accuracy: excess over the proved optimum (lines: Pareto fronts)")
    gap_ax.set_ylabel("certified gap the plan states [%] (100: no bound; 1e-3: proved)")
    gap_ax.set_title("What the plan can prove: its certified gap")
    gap_ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside: no data hidden
    fig.tight_layout()
    fig.savefig(OUT / "planner_scale.png", dpi=120)


if __name__ == "__main__":
    sys.exit(main())
