"""The 146 m ro-ro ferry (examples/ferry_strength_plan.toml): lifting points and forces chosen
for the hull girder against an evenly spaced "experience" plan of the same 24 points.

The experience plan takes 12 stations a side spread as evenly as the 16 frame stations allow,
and forces as even as the statics allow (the least max - min force, the rule of thumb "share
the load equally"). Both are evaluated on the same states (the CG envelope's vertices, each at
its equilibrium attitude under force control) with the exact peak of |M| and |Q| along the
body. Also the spread-optimal plan the planner reports beside the strength plan, and the
search's time and gap (the machine was shared with other work: times are indicative).

Writes studies/out/ferry_strength.json (data), then studies/out/ferry_strength.png from it.
Run: ``python studies/ferry_strength.py``.
"""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np

OUT = Path(__file__).parent / "out"
EXAMPLE = Path(__file__).parent.parent / "examples" / "ferry_strength_plan.toml"


def curves(ctx, plan_set):
    """M and Q along the body for each state of a plan (exact curves sampled for the figure)."""
    from liftplan.planner.search.strength import State, exact_curves, force_attitude

    p = ctx.problem
    points = p.points[list(plan_set.indices)]
    ups, _ = force_attitude(points, plan_set.preload, p.body.weight, p.body.cog, ctx.offsets)
    xs = np.linspace(0.0, 146.0, 1461)
    out = []
    for u, o in zip(ups, ctx.offsets):
        shear, moment = exact_curves(ctx.loads, points, plan_set.preload, State(tuple(u), tuple(o)))
        out.append((moment(xs).tolist(), shear(xs).tolist()))
    return xs.tolist(), out


def summary(s):
    return {
        "lugs": list(s.names),
        "x": None,
        "forces": s.preload.tolist(),
        "peak_M": s.bending.value,
        "peak_M_ratio": s.bending.ratio,
        "peak_M_x": s.bending.x,
        "peak_Q": s.shear.value,
        "peak_Q_ratio": s.shear.ratio,
        "peak_Q_x": s.shear.x,
        "spread": s.spread,
        "lowest": s.tension_range[0],
        "highest": s.tension_range[1],
    }


def run():
    from liftplan.planner import load_problem
    from liftplan.planner.plans.strength import (
        SPREAD_WEIGHTS,
        StrengthContext,
        StrengthEvaluator,
        objective_weights,
        search_strength,
    )

    problem = load_problem(EXAMPLE)
    ctx = StrengthContext(problem)
    evaluator = StrengthEvaluator(ctx)
    stations = sorted({int(round(k)) for k in np.linspace(0, 15, 12)})
    experience_set = [2 * k + side for k in stations for side in (0, 1)]
    experience = evaluator.evaluate(experience_set, SPREAD_WEIGHTS)
    started = time.perf_counter()
    strength, stats = search_strength(problem, objective_weights(problem), ctx)
    seconds = time.perf_counter() - started
    started = time.perf_counter()
    spread, spread_stats = search_strength(problem, SPREAD_WEIGHTS, ctx, time_limit=30.0)
    spread_seconds = time.perf_counter() - started
    data = {
        "problem": str(EXAMPLE.name),
        "weight": problem.body.weight,
        "weight_curve": [list(p) for p in problem.body.weight_curve],
        "allowable_M": [list(p) for p in problem.strength.bending_moment],
        "allowable_Q": [list(p) for p in problem.strength.shear_force],
    }
    for name, s in (("experience", experience), ("strength", strength), ("spread", spread)):
        data[name] = summary(s)
        data[name]["x"] = problem.points[list(s.indices)][:, 0].tolist()
        data[name]["y"] = problem.points[list(s.indices)][:, 1].tolist()
        xs, states = curves(ctx, s)
        data[name]["curves"] = {"x": xs, "states": states}
    data["search"] = {
        "seconds": seconds,
        "lower_bound": stats.lower_bound,
        "best": stats.best,
        "gap": stats.gap,
        "relative_gap": stats.relative_gap,
        "stopped": stats.stopped,
        "mip_solves": stats.rounds,
        "method": stats.method,
        "certified": stats.certified,
    }
    data["spread_search"] = {
        "seconds": spread_seconds,
        "lower_bound": spread_stats.lower_bound,
        "gap": spread_stats.gap,
        "stopped": spread_stats.stopped,
    }
    OUT.mkdir(exist_ok=True)
    (OUT / "ferry_strength.json").write_text(json.dumps(data))
    return data


def table(data):
    e, s, o = data["experience"], data["strength"], data["spread"]
    rows = [
        ("peak |M| [t m]", "peak_M", ".0f"),
        ("peak |M| / allowable", "peak_M_ratio", ".3f"),
        ("peak |Q| [t]", "peak_Q", ".0f"),
        ("peak |Q| / allowable", "peak_Q_ratio", ".3f"),
        ("force spread [t]", "spread", ".1f"),
        ("lowest force [t]", "lowest", ".1f"),
        ("highest force [t]", "highest", ".1f"),
    ]
    lines = [f"{'':24s}{'experience':>12s}{'strength':>12s}{'spread-opt':>12s}{'change':>9s}"]
    for name, key, fmt in rows:
        change = "" if key not in ("peak_M", "peak_Q") else f"{100 * (s[key] / e[key] - 1):+.1f} %"
        lines.append(f"{name:24s}{e[key]:>12{fmt}}{s[key]:>12{fmt}}{o[key]:>12{fmt}}{change:>9s}")
    g = data["search"]
    lines.append(
        f"strength search: {g['seconds']:.1f} s, gap {g['gap']:.2g} ({g['stopped']}, "
        f"{g['mip_solves']} MIP solves)"
    )
    return "\n".join(lines)


def figure(data):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(
        4, 1, figsize=(9, 11), sharex=True, gridspec_kw={"height_ratios": [1.1, 1, 1, 1.1]}
    )
    wc = np.array(data["weight_curve"])
    styles = {
        "experience": ("tab:red", "experience: 12 even stations a side, even forces"),
        "strength": ("tab:blue", "strength-optimal (bending)"),
        "spread": ("tab:green", "spread-optimal"),
    }
    # at each station six bars side by side: the three plans, each starboard (hatched) then
    # port (solid), so no bar hides another
    stations = np.unique(np.round(np.concatenate([data[n]["x"] for n in styles]), 6))
    width = 0.8 * np.diff(stations).min() / 6
    for k, name in enumerate(styles):
        d, (color, label) = data[name], styles[name]
        x, y, f = (np.array(d[key]) for key in ("x", "y", "forces"))
        for j, (side, hatch) in enumerate(((y < 0, "////"), (y > 0, None))):
            shift = (2 * k + j - 2.5) * width
            axes[0].bar(
                x[side] + shift,
                f[side],
                width=width,
                color=color if hatch is None else "white",
                edgecolor=color,
                hatch=hatch,
                lw=0.6,
                label=f"{label}, {'starboard' if hatch else 'port'}",
            )
    axes[0].set_ylabel("force per point [t]")
    axes[0].legend(fontsize=6.5, loc="upper left", ncols=3, frameon=False)
    top = max(max(data[n]["forces"]) for n in styles)
    axes[0].set_ylim(0, 1.45 * top)
    weight = axes[0].twinx()
    weight.fill_between(wc[:, 0], wc[:, 1], color="0.5", alpha=0.15, lw=0)
    weight.set_ylim(0, 3.0 * wc[:, 1].max())
    weight.set_ylabel("weight per length [t/m] (grey)", fontsize=8)
    for name in ("experience", "strength", "spread"):
        d, (color, label) = data[name], styles[name]
        xs = np.array(d["curves"]["x"])
        m = np.array([st[0] for st in d["curves"]["states"]])
        q = np.array([st[1] for st in d["curves"]["states"]])
        axes[1].fill_between(xs, m.min(axis=0) / 1e3, m.max(axis=0) / 1e3, color=color, alpha=0.35, lw=0)
        axes[1].plot(xs, m[0] / 1e3, color=color, lw=1.2, label=f"{label}: peak {d['peak_M']:.0f} t m")
        axes[2].fill_between(xs, q.min(axis=0), q.max(axis=0), color=color, alpha=0.35, lw=0)
        axes[2].plot(xs, q[0], color=color, lw=1.2, label=f"{label}: peak {d['peak_Q']:.0f} t")
        ratio_m = np.abs(m).max(axis=0) / np.interp(xs, *np.array(data["allowable_M"]).T)
        axes[3].plot(xs, ratio_m, color=color, lw=1.2, label=f"|M| / allowable, {name}")
    for ax, key, scale in ((axes[1], "allowable_M", 1e3), (axes[2], "allowable_Q", 1.0)):
        env = np.array(data[key])
        ax.plot(env[:, 0], env[:, 1] / scale, "k--", lw=0.8, label="allowable")
        ax.plot(env[:, 0], -env[:, 1] / scale, "k--", lw=0.8)
        ax.axhline(0, color="0.5", lw=0.5)
    axes[0].set_title(
        "forces at the 16 frame stations: each plan's starboard (hatched) and port "
        "(solid) bars side by side; weight per length in grey",
        fontsize=8,
    )
    axes[1].set_ylabel("bending moment [1000 t m]")
    axes[2].set_ylabel("shear force [t]")
    axes[3].set_ylabel("worst |M| / allowable")
    axes[3].set_xlabel("x from the stern [m]")
    for ax in axes[1:]:
        ax.legend(fontsize=7)
    axes[1].set_title(
        "shaded: the range over the CG envelope's states (each at its equilibrium tilt)", fontsize=8
    )
    fig.suptitle(
        "146 m ro-ro ferry on 24 of 32 strand-jack points: experience plan against the strength-optimal plan",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(OUT / "ferry_strength.png", dpi=120)


if __name__ == "__main__":
    result = run()
    print(table(result))
    figure(result)
    print(f"wrote {OUT / 'ferry_strength.json'} and {OUT / 'ferry_strength.png'}")
