"""The tanker's fleet plan with and without its vessels, side by side, and what it costs.

``examples/tanker_fleet.toml`` (the cranes' tips fixed) against
``examples/tanker_floating_fleet.toml`` (the same fleet on its vessels, each in series with its
rope), and the land plan's own lugs and cranes held with the vessels in series (the same set,
evaluated exactly on the floating problem) to separate the vessels' effect on a given set from
the different set the planner picks. Per plan: each rope's level and worst tension, the worst
spread, the twist stiffness (largest tension change of a rope per cm of every hook off its
height, worst signs), the hook accuracy the plan needs (the largest equal hook error every
limit holds), and each vessel's tip drop and worst heel. Then the floating plan again with a
heel limit of HEEL_LIMIT deg on every vessel, below the floating plan's worst heel: the sets
that heel a vessel beyond it are ruled out of the search, and the plan is the best set that
keeps them (its price in the objective, and how many sets the limit ruled out).

Times: each plan made REPEAT times, the two files interleaved, the median wall time of
``plan(problem)`` (the problem read once); the ratio is what is claimed.

Run:  python studies/vessel_plan.py   (writes studies/out/vessel_plan.json and vessel_plan.png)
"""

from __future__ import annotations

import dataclasses
import json
import statistics
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from liftplan.planner.plan import plan  # noqa: E402
from liftplan.planner.plans.held import Plan  # noqa: E402
from liftplan.planner.problem.file import load_problem  # noqa: E402
from liftplan.planner.problem.vessels import series_problem  # noqa: E402
from liftplan.planner.search.evaluator import SetEvaluator  # noqa: E402

HERE = Path(__file__).parent
EXAMPLES = HERE.parent / "examples"
REPEAT = 3
#: deg, on every vessel for the limited plan (the floating plan's worst heel is 0.19 deg)
HEEL_LIMIT = 0.15


def summary(result):
    """The side-by-side numbers of one plan."""
    return {
        "lugs": {label: f"{result.lugs[label]} ({result.cranes[label]})" for label in result.labels},
        "level_tensions": result.tensions,
        "worst_tensions": dict(zip(result.labels, result.chosen.rope_max.tolist())),
        "worst_spread": result.worst_spread,
        "worst_utilisation_spread": result.chosen.worst_utilisation_spread,
        "twist_stiffness_t_per_cm": result.twist_stiffness,
        "hook_accuracy_needed_m": result.hook_accuracy_needed,
        "tip_drop_m": {v.crane: v.tip_drop for v in result.vessels},
        "worst_heel_deg": {v.crane: v.worst_heel for v in result.vessels},
        "ballast_t_m": {v.crane: list(v.ballast) for v in result.vessels},
        "worst_value": result.chosen.worst_value,
        "ruled_out_by_heel": sum(n for text, n in result.stats.infeasible.items() if "max_heel" in text),
    }


def heel_limited(problem, limit):
    """The problem with every vessel's ``max_heel`` at ``limit`` [deg]."""
    fleet = tuple(
        dataclasses.replace(c, vessel=dataclasses.replace(c.vessel, max_heel=limit)) for c in problem.fleet
    )
    return dataclasses.replace(problem, fleet=fleet)


def main():
    land = load_problem(EXAMPLES / "tanker_fleet.toml")
    floating = load_problem(EXAMPLES / "tanker_floating_fleet.toml")
    limited = heel_limited(floating, HEEL_LIMIT)
    times = {"land": [], "vessels": [], "heel limit": []}
    plans = {}
    for _ in range(REPEAT):
        for name, problem in (("land", land), ("vessels", floating), ("heel limit", limited)):
            begin = time.perf_counter()
            plans[name] = plan(problem)
            times[name].append(time.perf_counter() - begin)
    chosen = plans["land"].chosen
    same = series_problem(floating, chosen.indices, chosen.cranes)
    again = SetEvaluator(same).evaluate(chosen.indices, chosen.cranes)
    held = Plan(problem=same, ranking=[again], stats=plans["land"].stats)
    rows = {
        "land plan": summary(plans["land"]),
        "floating plan": summary(plans["vessels"]),
        "land plan's lugs on the vessels": summary(held),
        f"floating plan, heel <= {HEEL_LIMIT:g} deg": summary(plans["heel limit"]),
    }
    speed = {name: statistics.median(t) for name, t in times.items()}
    out = {
        "repeat": REPEAT,
        "plans": rows,
        "median_plan_seconds": speed,
        "ratio": speed["vessels"] / speed["land"],
        "ratio_heel_limit": speed["heel limit"] / speed["land"],
        "heel_limit_deg": HEEL_LIMIT,
    }
    folder = HERE / "out"
    folder.mkdir(exist_ok=True)
    (folder / "vessel_plan.json").write_text(json.dumps(out, indent=2, default=float) + "\n")
    shown = ("land plan", "floating plan", f"floating plan, heel <= {HEEL_LIMIT:g} deg")
    figure({k: rows[k] for k in shown}, folder / "vessel_plan.png")
    for name, row in rows.items():
        print(
            f"{name:<34} worst spread {row['worst_spread']:7.2f} t"
            f"  twist {row['twist_stiffness_t_per_cm']:5.2f} t/cm"
            f"  hook accuracy {row['hook_accuracy_needed_m']:.3f} m  lugs {', '.join(row['lugs'].values())}"
        )
    for name in ("floating plan", f"floating plan, heel <= {HEEL_LIMIT:g} deg"):
        row = rows[name]
        heels = ", ".join(f"{k} {v:.3f}" for k, v in row["worst_heel_deg"].items())
        print(
            f"{name}: objective {row['worst_value']:.4f}, sets ruled out by the heel limit "
            f"{row['ruled_out_by_heel']}, worst heel {heels} deg"
        )
    print(
        f"plan time: land {speed['land']:.2f} s, vessels {speed['vessels']:.2f} s (x{out['ratio']:.2f}), "
        f"heel limit {speed['heel limit']:.2f} s (x{out['ratio_heel_limit']:.2f})"
    )


def figure(rows, path):
    """Level and worst tension of each rope, per plan."""
    fig, axes = plt.subplots(1, len(rows), figsize=(5 * len(rows), 4.6), sharey=True)
    for ax, (name, row) in zip(axes, rows.items()):
        labels = list(row["level_tensions"])
        x = np.arange(len(labels))
        ax.bar(x - 0.2, list(row["level_tensions"].values()), 0.4, label="level, nominal CG")
        ax.bar(x + 0.2, list(row["worst_tensions"].values()), 0.4, label="worst in the box")
        ax.set_xticks(
            x, [f"{k}\n{row['lugs'][k].replace(' (', chr(10)).rstrip(')')}" for k in labels], fontsize=8
        )
        ax.set_title(
            f"{name}: worst spread {row['worst_spread']:.1f} t\n"
            f"twist {row['twist_stiffness_t_per_cm']:.2f} t/cm, "
            f"hook accuracy needed {row['hook_accuracy_needed_m']:.3f} m",
            fontsize=9,
        )
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("rope tension [t]")
    axes[0].legend(fontsize=8)
    fig.suptitle(
        "1500 GT tanker, mixed fleet: cranes with fixed tips, on their vessels, and on their vessels "
        "with a heel limit",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
