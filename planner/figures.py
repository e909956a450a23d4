"""Figures of a plan (matplotlib, object API, no pyplot state): each returns a Figure.

Only this module (and the report that embeds its output) imports matplotlib.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

_SPAN = 10.0  # deg: the curves run over +-max(this, 2 x tolerance), as the papers' Figs 7-8


def tension_curves(plan):
    """Tension of every rope against heel (trim 0) and against trim (heel 0).

    The style of Choi & Shin (2003) Figs 7-8, with the plan's preload held; the tolerance
    band is shaded, SWL and min_tension drawn.
    """
    problem = plan.problem
    fig = Figure(figsize=(10, 4), layout="constrained")
    axes = fig.subplots(1, 2, sharey=True)
    for ax, angle, tol in zip(axes, ("heel", "trim"),
                              (problem.heel_tolerance, problem.trim_tolerance)):
        span = max(_SPAN, 2 * tol)
        values = np.linspace(-span, span, 161)
        zero = np.zeros_like(values)
        tensions = plan.tensions_at(values, zero) if angle == "heel" else \
            plan.tensions_at(zero, values)
        for label, column in zip(plan.labels, tensions.T):
            ax.plot(values, column, label=f"{label} ({plan.lugs[label]})")
        ax.axvspan(-tol, tol, color="0.9", label="tolerance")
        ax.axhline(problem.crane.swl, color="k", ls="--", lw=1, label="SWL")
        if problem.min_tension > 0:
            ax.axhline(problem.min_tension, color="k", ls=":", lw=1, label="min tension")
        sign = "starboard down" if angle == "heel" else "bow down"
        ax.set_xlabel(f"{angle} [deg] (+ {sign})")
        ax.grid(True, lw=0.3)
    axes[0].set_ylabel("rope tension [t]")
    axes[1].legend(fontsize=8, loc="best")
    fig.suptitle("Tensions with the plan's preload held")
    return fig


def plan_view(plan):
    """Plan view: hull outline, candidates, CG (and envelope), chosen lugs."""
    problem = plan.problem
    fig = Figure(figsize=(10, 4.5), layout="constrained")
    ax = fig.subplots()
    if problem.outline:
        outline = np.array(problem.outline + problem.outline[:1])
        ax.plot(outline[:, 0], outline[:, 1], color="0.3", lw=1.2, label="hull outline")
    pts = problem.points
    ax.scatter(pts[:, 0], pts[:, 1], s=18, color="0.6", label="candidates", zorder=2)
    for name, (x, y, _) in zip(problem.names, pts):
        ax.annotate(name, (x, y), fontsize=6, color="0.4", xytext=(2, -8),
                    textcoords="offset points")
    chosen = plan.lugset.points
    order = np.r_[_around(chosen, problem.body.cog), _around(chosen, problem.body.cog)[:1]]
    ax.plot(chosen[order, 0], chosen[order, 1], color="tab:blue", lw=1, ls="--")
    ax.scatter(chosen[:, 0], chosen[:, 1], s=70, color="tab:blue", label="chosen lugs", zorder=3)
    for label, (x, y, _) in zip(plan.labels, chosen):
        ax.annotate(f"{label}  H={plan.boom_heights[label]:.2f} m", (x, y), fontsize=8,
                    color="tab:blue", xytext=(4, 5), textcoords="offset points")
    cx, cy = problem.body.cog[:2]
    dx, dy = problem.cog_envelope.half_widths[:2]
    if dx or dy:
        ax.add_patch(_rectangle(cx - dx, cy - dy, 2 * dx, 2 * dy))
    ax.scatter([cx], [cy], marker="x", s=80, color="tab:red", label="CG", zorder=4)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m] (forward)")
    ax.set_ylabel("y [m] (to port)")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    ax.set_title("Plan view (z-up frame)")
    return fig


def spread_map(plan, count=41):
    """Spread (max - min tension) over the tolerance box, worst over the CG envelope."""
    heel, trim, spread = plan.spread_map(count)
    fig = Figure(figsize=(6, 4.5), layout="constrained")
    ax = fig.subplots()
    mesh = ax.pcolormesh(trim, heel, spread, shading="auto", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="spread [t]")
    worst = plan.chosen.worst
    ax.scatter([worst.trim], [worst.heel], marker="*", s=160, color="tab:red",
               label=f"worst {plan.worst_spread:.1f} t")
    ax.set_xlabel("trim [deg] (+ bow down)")
    ax.set_ylabel("heel [deg] (+ starboard down)")
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("Spread over the tolerance box")
    return fig


def _around(points, cog):
    plan = points[:, :2] - np.array(cog[:2])
    return np.argsort(np.arctan2(plan[:, 1], plan[:, 0]))


def _rectangle(x, y, width, height):
    from matplotlib.patches import Rectangle

    return Rectangle((x, y), width, height, fill=False, ec="tab:red", ls=":",
                     label="CG envelope")


def load_curve(curve, swl=None):
    """Crane loads, water and ground forces, and attitude against hoist.

    Parameters
    ----------
    curve : liftplan.model.lift.LoadCurve
    swl : float, optional  [t]
        Drawn as a line on the loads panel.
    """
    fig = Figure(figsize=(8, 9), layout="constrained")
    loads, water, pose = fig.subplots(3, 1, sharex=True)
    for name, column in zip(curve.lugs, curve.tensions.T):
        loads.plot(curve.hoist, column, label=name)
    load, lug, at = curve.max_load
    loads.plot([at], [load], "ko", ms=4)
    loads.annotate(f" max {load:.1f} t ({lug})", (at, load), fontsize=8, va="bottom")
    if swl:
        loads.axhline(swl, color="k", ls="--", lw=1, label="SWL")
    loads.set_ylabel("rope tension [t]")
    loads.legend(fontsize=8, loc="best")
    water.plot(curve.hoist, curve.buoyancy, label="buoyancy (net water force up)")
    water.plot(curve.hoist, curve.ground_reaction, label="ground reaction")
    water.plot(curve.hoist, curve.tensions.sum(axis=1), label="sum of rope tensions")
    water.set_ylabel("force [t]")
    water.legend(fontsize=8, loc="best")
    pose.plot(curve.hoist, curve.heel, label="heel (+ starboard down)")
    pose.plot(curve.hoist, curve.trim, label="trim (+ bow down)")
    pose.set_ylabel("angle [deg]")
    pose.set_xlabel("hoist [m] (every hook raised by this)")
    pose.legend(fontsize=8, loc="best")
    if curve.lift_off is not None:
        for ax in (loads, water, pose):
            ax.axvline(curve.lift_off, color="0.6", lw=0.8, ls=":")
    for ax in (loads, water, pose):
        ax.grid(True, lw=0.3)
    for hoist, _ in curve.failed:
        loads.axvline(hoist, color="r", lw=0.5, alpha=0.5)
    return fig
