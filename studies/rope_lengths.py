"""The planner choosing rope lengths on the tanker with +-0.05 m hook errors.

Plans examples/tanker_lengths.toml (payout 25 to 55 m, boom tips at most 60 m) and, beside
it, today's fixed 30 m ropes (examples/tanker_plan.toml's) at the same +-0.05 m, and
today's plan (made for +-0.02 m) held under +-0.05 m. Keeps every length tried with its
worst spread, lugs, twist stiffness and why the infeasible ones are, then draws worst
spread against rope length from that data.

    python studies/rope_lengths.py      # -> studies/out/rope_lengths.json, .png

Times are of a shared 2-core machine.
"""

from __future__ import annotations

import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "studies" / "out"


def run():
    from liftplan.model.errors import PlanInfeasible
    from liftplan.planner import load_problem, plan
    from liftplan.planner.plans.held import Plan
    from liftplan.planner.plans.lengths import with_lengths

    problem = load_problem(ROOT / "examples" / "tanker_lengths.toml")
    chosen = plan(problem)
    classes = ((0, 1, 2, 3),)
    trials = []
    for t in chosen.lengths.trials:
        cause = (
            "" if t.value is not None else "boom range" if "boom-height range" in t.reason else "rope limits"
        )
        entry = {
            "length": t.lengths[0],
            "worst_spread": t.value,
            "lugs": list(t.lugs),
            "cause": cause,
            "reason": t.reason,
        }
        if t.value is not None:
            at = plan(with_lengths(problem, classes, t.lengths))
            entry["twist_stiffness"] = at.twist_stiffness
            entry["boom_heights"] = list(at.boom_heights.values())
        trials.append(entry)
    today = plan(load_problem(ROOT / "examples" / "tanker_plan.toml"))
    fixed = with_lengths(problem, classes, (30.0,))
    try:
        plan(fixed)
        fixed_feasible = True
    except PlanInfeasible:
        fixed_feasible = False
    held = Plan(problem=fixed, ranking=[today.chosen], stats=today.stats).crew_margin((1.0,))[0]
    data = {
        "chosen": {
            "lugs": chosen.lugs,
            "rope_lengths": chosen.rope_lengths,
            "worst_spread": chosen.worst_spread,
            "twist_stiffness": chosen.twist_stiffness,
            "boom_heights": chosen.boom_heights,
            "lower_bound": chosen.stats.lower_bound,
            "seconds": chosen.stats.seconds,
            "trials": len(trials),
        },
        "today_30m_at_0.05_feasible": fixed_feasible,
        "today_plan": {
            "lugs": today.lugs,
            "worst_spread_at_0.02": today.worst_spread,
            "twist_stiffness": today.twist_stiffness,
            "held_at_0.05": {
                "worst_spread": held.worst_spread,
                "rope_max": held.rope_max.tolist(),
                "limit": held.limit.tolist(),
                "lowest": held.lowest,
                "within_limits": held.within_limits,
            },
        },
        "trials": trials,
        "machine": "2 cores shared with other work",
    }
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "rope_lengths.json").write_text(json.dumps(data, indent=1))
    return data


def draw(data):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    trials = sorted(data["trials"], key=lambda t: t["length"])
    good = [t for t in trials if t["worst_spread"] is not None]
    bad = [t for t in trials if t["worst_spread"] is None]
    fig, ax = plt.subplots(figsize=(7.5, 4.0), layout="constrained")
    ax.plot(
        [t["length"] for t in good],
        [t["worst_spread"] for t in good],
        "o-",
        color="tab:blue",
        label="exact plan at that length (+-0.05 m hooks)",
    )
    held = data["today_plan"]["held_at_0.05"]
    top = max(held["worst_spread"], *(t["worst_spread"] for t in good)) * 1.1
    for k, t in enumerate(bad):
        ax.plot(t["length"], top, "x", color="tab:red", markersize=9)
        ax.annotate(
            f"no plan:\n{t['cause']}",
            (t["length"], top),
            textcoords="offset points",
            xytext=(0, -24 - 18 * (k % 2)),
            ha="center",
            fontsize=7,
            color="tab:red",
        )
    best = data["chosen"]
    length = best["rope_lengths"]["L1"]
    ax.plot(
        length,
        best["worst_spread"],
        "*",
        color="tab:green",
        markersize=14,
        label=f"chosen: {length:g} m, worst {best['worst_spread']:.1f} t",
    )
    ax.plot(
        30.0,
        held["worst_spread"],
        "s",
        color="k",
        label=f"today's 30 m plan held at +-0.05 m: {held['worst_spread']:.1f} t, over its limits",
    )
    ax.set_xlabel("rope length l0 (every crane) [m]")
    ax.set_ylabel("worst spread over box, CG, hooks [t]")
    ax.set_ylim(0, top * 1.12)
    ax.set_title("Tanker, payout 25-55 m, boom tips at most 60 m: lengths the planner tried", fontsize=10)
    ax.legend(fontsize=8, loc="lower left")
    fig.savefig(OUT / "rope_lengths.png", dpi=110)


if __name__ == "__main__":
    draw(run())
