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
        swl = plan.swl
        equal = len(set(swl.values())) == 1
        for label, column in zip(plan.labels, tensions.T):
            line, = ax.plot(values, column, label=f"{label} ({plan.lugs[label]}, {plan.cranes[label]})")
            if not equal:
                ax.axhline(swl[label], color=line.get_color(), ls="--", lw=1,
                           label=f"SWL {label} {swl[label]:.0f} t")
        ax.axvspan(-tol, tol, color="0.9", label="tolerance")
        if equal:
            ax.axhline(next(iter(swl.values())), color="k", ls="--", lw=1, label="SWL")
        if problem.min_tension > 0:
            ax.axhline(problem.min_tension, color="k", ls=":", lw=1, label="min tension")
        sign = "starboard down" if angle == "heel" else "bow down"
        ax.set_xlabel(f"{angle} [deg] (+ {sign})")
        ax.grid(True, lw=0.3)
    axes[0].set_ylabel("rope tension [t]")
    axes[1].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.suptitle("Tensions with the plan's preload held (nominal CG)")
    return fig


def _file_plan(problem, xy):
    """Plan coordinates (z-up x, y) in the frame of the problem's file, and axis labels."""
    xy = np.asarray(xy, dtype=float)
    if problem.frame == "choi":  # papers' frame: z to starboard = -y (z-up)
        return np.column_stack([xy[..., 0], -xy[..., 1]]), "z [m] (to starboard)"
    return xy, "y [m] (to port)"


def _file_point(problem, point):
    """A z-up vector (x, y, z) in the frame of the problem's file."""
    from liftplan.model.frames import zup_to_choi

    return tuple(zup_to_choi(point)) if problem.frame == "choi" else tuple(point)


def plan_view(plan):
    """Plan view in the file's frame: hull outline, candidates, CG and its envelope, chosen
    lugs with their boom heights, and the cranes (slew centre, chart reach, the lug each
    takes, its radius and SWL there)."""
    problem = plan.problem
    fig = Figure(figsize=(10, 6 if _positioned(problem) else 4.5), layout="constrained")
    ax = fig.subplots()
    if problem.outline:
        outline, _ = _file_plan(problem, np.array(problem.outline + problem.outline[:1]))
        ax.plot(outline[:, 0], outline[:, 1], color="0.3", lw=1.2, label="hull outline")
    pts, side = _file_plan(problem, problem.points[:, :2])
    ax.scatter(pts[:, 0], pts[:, 1], s=18, color="0.6", label="candidates", zorder=2)
    mid = np.mean(pts[:, 1])
    for name, (x, y) in zip(problem.names, pts):
        ax.annotate(name, (x, y), fontsize=6, color="0.4", ha="center",
                    xytext=(0, 6 if y >= mid else -10), textcoords="offset points")
    chosen, _ = _file_plan(problem, plan.lugset.points[:, :2])
    (cog, ), _ = _file_plan(problem, np.array([problem.body.cog[:2]]))
    order = _around(chosen, cog)
    order = np.r_[order, order[:1]]
    ax.plot(chosen[order, 0], chosen[order, 1], color="tab:blue", lw=1, ls="--")
    ax.scatter(chosen[:, 0], chosen[:, 1], s=70, color="tab:blue", label="chosen lugs", zorder=3)
    for label, (x, y) in zip(plan.labels, chosen):
        ax.annotate(f"{label}  H={plan.boom_heights[label]:.2f} m", (x, y), fontsize=8,
                    color="tab:blue", xytext=(4, 10 if y >= mid else -16),
                    textcoords="offset points")
    if _positioned(problem):
        _draw_cranes(ax, plan)
        # frame the hull and the slew centres; the reach circles are cut at the edge
        if problem.outline:
            seen_outline = _file_plan(problem, np.array(problem.outline))[0]
        else:
            seen_outline = pts
        seen = [pts, chosen, seen_outline] + [_file_plan(problem, np.array([c.position]))[0]
                                for c in problem.fleet if c.position is not None]
        seen = np.vstack(seen)
        low, high = seen.min(axis=0) - 8.0, seen.max(axis=0) + 8.0
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[1], high[1])
    dx, dy = problem.cog_envelope.half_widths[:2]
    if dx or dy:
        ax.add_patch(_rectangle(cog[0] - dx, cog[1] - dy, 2 * dx, 2 * dy))
    ax.scatter([cog[0]], [cog[1]], marker="x", s=80, color="tab:red", label="CG", zorder=4)
    ax.set_aspect("equal")
    if problem.frame == "choi":
        ax.invert_yaxis()  # seen from above with x to the right, starboard is down
    ax.set_xlabel("x [m] (forward)")
    ax.set_ylabel(side)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    frame = "papers' frame" if problem.frame == "choi" else "z-up frame"
    ax.set_title(f"Plan view ({frame}, seen from above)")
    return fig


def _positioned(problem):
    return any(c.position is not None for c in problem.fleet)


def _draw_cranes(ax, plan):
    """Each crane's slew centre, its chart reach, and a line to the lug it takes."""
    from matplotlib.patches import Circle

    problem = plan.problem
    chosen, _ = _file_plan(problem, plan.lugset.points[:, :2])
    lug_of = {name: k for k, name in enumerate(plan.chosen.crane_names)}
    colors = ["tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink", "tab:olive",
              "tab:cyan", "tab:gray"]
    for j, crane in enumerate(problem.fleet):
        if crane.position is None:
            continue
        color = colors[j % len(colors)]
        ((cx, cy), ), _ = _file_plan(problem, np.array([crane.position]))
        ax.scatter([cx], [cy], marker="s", s=60, color=color, zorder=4)
        ax.annotate(crane.name, (cx, cy), fontsize=8, color=color, xytext=(0, 8),
                    textcoords="offset points", ha="center")
        if np.isfinite(crane.reach):
            ax.add_patch(Circle((cx, cy), crane.reach, fill=False, ec=color, ls=":", lw=0.8))
        k = lug_of.get(crane.name)
        if k is not None:
            x, y = chosen[k]
            label = plan.labels[k]
            ax.plot([cx, x], [cy, y], color=color, lw=1.2)
            ax.annotate(f"{label}: {plan.radius[label]:.1f} m, SWL {plan.swl[label]:.0f} t",
                        ((cx + x) / 2, (cy + y) / 2), fontsize=7, color=color, ha="center",
                        bbox={"fc": "white", "ec": "none", "alpha": 0.7, "pad": 0.5})
    ax.plot([], [], color="0.4", ls=":", lw=0.8, label="crane reach (chart)")
    ax.scatter([], [], marker="s", color="0.4", label="crane slew centre")


def spread_map(plan, count=41):
    """The plan's objective (tension spread, or utilisation spread) over the tolerance box,
    at each attitude the worst over the CG envelope."""
    utilisation = plan.objective == "utilisation"
    heel, trim, spread = plan.spread_map(count, utilisation=utilisation)
    fig = Figure(figsize=(6, 4.5), layout="constrained")
    ax = fig.subplots()
    mesh = ax.pcolormesh(trim, heel, spread, shading="auto", cmap="viridis")
    unit = "max - min of T / SWL [-]" if utilisation else "max - min tension [t]"
    fig.colorbar(mesh, ax=ax, label=unit)
    worst = plan.chosen.worst
    dx, dy, dz = _file_point(plan.problem, worst.cog_offset)
    value = f"{plan.chosen.worst_value:.3f}" if utilisation else f"{plan.worst_spread:.1f} t"
    ax.scatter([worst.trim], [worst.heel], marker="*", s=160, color="tab:red",
               label=f"worst {value}\nCG offset ({dx:+.2f}, {dy:+.2f}, {dz:+.2f}) m")
    ax.set_xlabel("trim [deg] (+ bow down)")
    ax.set_ylabel("heel [deg] (+ starboard down)")
    ax.legend(fontsize=8, loc="lower right")
    what = "Utilisation spread" if utilisation else "Tension spread"
    ax.set_title(f"{what} over the tolerance box\n(each point: worst CG of the envelope)",
                 fontsize=10)
    return fig


def _around(points, cog):
    plan = points[:, :2] - np.array(cog[:2])
    return np.argsort(np.arctan2(plan[:, 1], plan[:, 0]))


def _rectangle(x, y, width, height):
    from matplotlib.patches import Rectangle

    return Rectangle((x, y), width, height, fill=False, ec="tab:red", ls=":",
                     label="CG envelope")


_PHASE_COLOURS = {"grounded": "#c9b79c", "hanging submerged": "#9ecae1", "piercing the surface": "#c6dbef",
                  "clear": "#e5f5e0", "afloat": "#fdd0a2"}


def _phases(curve):
    """(state, from, to) [m] along the curve: a change between two steps is placed at the
    event found between them (bisected), else half-way."""
    phases, k = [], 0
    count = len(curve.state)
    begin = float(curve.hoist[0])
    while k < count:
        end = k
        while end + 1 < count and curve.state[end + 1] == curve.state[k]:
            end += 1
        if end + 1 < count:
            lo, hi = curve.hoist[end], curve.hoist[end + 1]
            inside = [e.hoist for e in curve.events if lo <= e.hoist <= hi]
            stop = inside[0] if inside else 0.5 * (lo + hi)
        else:
            stop = float(curve.hoist[-1])
        phases.append((curve.state[k], begin, float(stop)))
        begin, k = float(stop), end + 1
    return phases


def load_curve(curve, swl=None):
    """Crane loads, water and ground forces, and attitude against hoist, with the curve's
    events (lift-off, surface, clear) marked and named on every panel, the phases (the
    state words) on a strip above, and the maximum load's plateau shaded.

    Parameters
    ----------
    curve : liftplan.model.lift.LoadCurve
    swl : float, optional  [t]
        Drawn as a line on the loads panel.
    """
    from matplotlib.transforms import blended_transform_factory

    from liftplan.model.lift import PLATEAU_REL

    fig = Figure(figsize=(11, 10), layout="constrained")
    strip, loads, water, pose = fig.subplots(4, 1, sharex=True,
                                             gridspec_kw={"height_ratios": [0.35, 3, 3, 2]})
    span = max(float(curve.hoist[-1] - curve.hoist[0]), 1e-9)
    for state, a, b in _phases(curve):
        strip.axvspan(a, b, color=_PHASE_COLOURS.get(state, "0.9"), lw=0)
        narrow = b - a < 0.08 * span
        strip.text(a if narrow else 0.5 * (a + b), 0.5, f" {state}", ha="left" if narrow else "center",
                   va="center", fontsize=8, style="italic", transform=blended_transform_factory(
                       strip.transData, strip.transAxes))
    strip.set_yticks([])
    strip.set_title(f"Load curve: {curve.name or 'lift'}\ncrane loads, water and ground forces, attitude "
                    "against hoist; the hull's state on this strip", fontsize=11)
    for name, column in zip(curve.lugs, curve.tensions.T):
        loads.plot(curve.hoist, column, label=name)
    m = curve.max_load
    for k, (a, b) in enumerate(m.plateau):
        label = (f"max {m.tension:.1f} t ({m.lug}),\nwithin {100 * PLATEAU_REL:g} % "
                 f"({m.tolerance:.2f} t) over\n" + ", ".join(f"{lo:.3f}-{hi:.3f} m" for lo, hi in m.plateau)
                 + (" (to the end)" if m.to_end else "")) if k == 0 else None
        loads.axvspan(a, b, color="0.85", lw=0, label=label)
        loads.plot([a, b], [m.tension, m.tension], color="k", lw=2.5, alpha=0.6)
    if swl:
        loads.axhline(swl, color="k", ls="--", lw=1, label=f"SWL {swl:g} t")
    loads.set_ylabel("rope tension [t]")
    water.plot(curve.hoist, curve.crane_load, color="k", label="sum of rope tensions")
    water.plot(curve.hoist, curve.buoyancy, label="buoyancy B\n(weight of displaced water)")
    water.plot(curve.hoist, curve.ground_reaction, label="ground reaction")
    water.axhline(curve.weight, color="0.4", ls="--", lw=1, label=f"weight in air W\n{curve.weight:.1f} t")
    if curve.trapped_water:
        water.axhline(curve.weight + curve.trapped_water, color="tab:purple", ls=":", lw=1.2,
                      label=f"W + trapped water\n{curve.weight:.1f} + {curve.trapped_water:.1f} t")
    water.set_ylabel("force [t]")
    pose.plot(curve.hoist, curve.heel, label="heel\n(+ starboard down)")
    pose.plot(curve.hoist, curve.trim, label="trim (+ bow down)")
    pose.set_ylabel("angle [deg]")
    pose.set_xlabel("hoist [m] (every hook raised by this)")
    for hoist, _ in curve.failed:
        for ax in (loads, water, pose):
            ax.axvline(hoist, color="r", lw=0.5, alpha=0.5)
    if curve.failed:
        loads.plot([], [], color="r", lw=0.5, label=f"no equilibrium\n({len(curve.failed)} steps)")
    for event in curve.events:
        for ax in (strip, loads, water, pose):
            ax.axvline(event.hoist, color="tab:green", lw=1, ls="-.")
        loads.annotate(f"{event.name} {event.hoist:.3f} m", (event.hoist, 1.0),
                       xycoords=blended_transform_factory(loads.transData, loads.transAxes),
                       xytext=(3, -4), textcoords="offset points", rotation=90, va="top",
                       fontsize=8, color="tab:green")
    for ax in (loads, water, pose):
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig
