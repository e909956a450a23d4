"""Figures of a plan (matplotlib, object API, no pyplot state): each returns a Figure.

Only this module (and the report that embeds its output) imports matplotlib.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from liftplan.model.frames import zup_to_choi
from liftplan.model.lift import PLATEAU_REL

_SPAN = 10.0  # deg: the curves run over +-max(this, 2 x tolerance), as the papers' Figs 7-8
_MM = 1 / 25.4  # inches per mm: figures are drawn at the size they are printed
_WIDTH = 170.0  # mm: the report's A4 text width
_FONT = 7.5  # pt: lettering at print size
_SMALL = 6.5  # pt: legends, point names


def _style(ax):
    """Print-size lettering on one axes (ticks are made at draw time, so set here)."""
    ax.tick_params(labelsize=_SMALL)
    ax.xaxis.label.set_size(_FONT)
    ax.yaxis.label.set_size(_FONT)
    ax.title.set_size(_FONT + 1)
    ax.grid(True, lw=0.3)


#: Ropes up to which the tension curves carry one legend entry per rope; beyond, each rope
#: is coloured by its station along the body and styled by its side (a colour bar, not a
#: legend of 26 or 64 entries).
LEGEND_ROPES = 16
_SIDE_STYLE = {"port": "-", "starboard": "--", "centre line": ":"}


def rope_sides(plan):
    """Each chosen lug's side in the body (``port``, ``starboard`` or ``centre line``), by its
    y against the middle of the chosen lugs (1 % of their width either side is the centre)."""
    y = plan.lugset.points[:, 1]
    middle, width = 0.5 * (y.max() + y.min()), float(np.ptp(y))
    tol = 0.01 * width
    return ["port" if v > middle + tol else "starboard" if v < middle - tol else "centre line" for v in y]


def tension_curves(plan):
    """Tension of every rope against heel (trim 0) and against trim (heel 0).

    The style of Choi & Shin (2003) Figs 7-8, with the plan's preload held; the tolerance
    band is shaded, SWL and min_tension drawn. Heel and trim are on the horizontal axis, as
    in every figure of the plan; the legend sits below the axes, clear of the lines. With
    more than :data:`LEGEND_ROPES` ropes each rope is coloured by its station x (a colour
    bar) and drawn solid on the port side, dashed on the starboard side, and the highest
    and lowest ropes at each end of the curves are named.
    """
    problem = plan.problem
    many = len(plan.labels) > LEGEND_ROPES
    fig = Figure(figsize=(_WIDTH * _MM, (110 if many else 100) * _MM), layout="constrained")
    axes = fig.subplots(1, 2, sharey=True)
    swl = plan.swl
    equal = len(set(swl.values())) == 1
    if many:
        from matplotlib import colormaps
        from matplotlib.colors import Normalize

        xs, _ = _file_plan(problem, plan.lugset.points[:, :2])
        norm = Normalize(xs[:, 0].min(), xs[:, 0].max() + 1e-9)
        cmap = colormaps["viridis"]
        sides = rope_sides(plan)
    for ax, angle, tol in zip(axes, ("heel", "trim"), (problem.heel_tolerance, problem.trim_tolerance)):
        span = max(_SPAN, 2 * tol)
        values = np.linspace(-span, span, 161)
        zero = np.zeros_like(values)
        tensions = plan.tensions_at(values, zero) if angle == "heel" else plan.tensions_at(zero, values)
        for k, (label, column) in enumerate(zip(plan.labels, tensions.T)):
            extra = "" if equal else f", SWL {swl[label]:.1f} t"
            style = {"lw": 1.3, "label": f"{label} ({plan.lugs[label]}, {plan.cranes[label]}{extra})"}
            if many:
                style = {"lw": 0.9, "color": cmap(norm(xs[k, 0])), "ls": _SIDE_STYLE[sides[k]]}
            (line,) = ax.plot(values, column, **style)
            if not equal:
                ax.axhline(swl[label], color=line.get_color(), ls="--", lw=0.9)
        if many:
            _name_extremes(ax, values, tensions, [f"{k} ({plan.lugs[k]})" for k in plan.labels])
        ax.axvspan(-tol, tol, color="0.9", label=f"tolerance box +-{tol:g} deg")
        if equal:
            ax.axhline(
                next(iter(swl.values())),
                color="k",
                ls="--",
                lw=0.9,
                label=f"SWL {next(iter(swl.values())):.1f} t",
            )
        else:
            ax.plot([], [], color="0.3", ls="--", lw=0.9, label="SWL (dashed, in the rope's colour)")
        if problem.min_tension > 0:
            ax.axhline(
                problem.min_tension, color="k", ls=":", lw=0.9, label=f"min tension {problem.min_tension:g} t"
            )
        sign = "starboard down" if angle == "heel" else "bow down"
        ax.set_xlabel(f"{angle} [deg] (+ {sign})")
        ax.set_xlim(-span, span)
        ax.set_title(f"against {angle} ({'trim' if angle == 'heel' else 'heel'} 0)")
        _style(ax)
    axes[0].set_ylabel("rope tension [t]")
    axes[0].set_ylim(bottom=0.0)
    if many:
        for side in dict.fromkeys(sides):
            axes[0].plot(
                [], [], color="0.3", lw=0.9, ls=_SIDE_STYLE[side], label=f"{side} ropes (colour: station x)"
            )
        from matplotlib.cm import ScalarMappable

        bar = fig.colorbar(
            ScalarMappable(norm=norm, cmap=cmap), ax=axes, location="right", fraction=0.04, pad=0.01
        )
        bar.set_label("rope's station x [m] (forward)", size=_FONT)
        bar.ax.tick_params(labelsize=_SMALL)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(
        handles,
        labels,
        loc="outside lower center",
        ncols=3 if equal or many else 2,
        fontsize=_SMALL,
        frameon=False,
    )
    title = "Rope tensions with the plan's preload held (nominal CG)"
    if many:
        title += f": {len(plan.labels)} ropes, each named in the tables"
    fig.suptitle(title, fontsize=_FONT + 1)
    return fig


def _name_extremes(ax, values, tensions, labels):
    """Name the highest and the lowest rope at both ends of the curves (many ropes)."""
    for end, ha, shift in ((0, "left", 2), (-1, "right", -2)):
        for k, va in ((int(np.argmax(tensions[end])), "bottom"), (int(np.argmin(tensions[end])), "top")):
            ax.annotate(
                labels[k],
                (values[end], tensions[end, k]),
                fontsize=_SMALL,
                ha=ha,
                va=va,
                xytext=(shift, 2 if va == "bottom" else -2),
                textcoords="offset points",
            )


def _file_plan(problem, xy):
    """Plan coordinates (z-up x, y) in the frame of the problem's file, and axis labels."""
    xy = np.asarray(xy, dtype=float)
    if problem.frame == "choi":  # papers' frame: z to starboard = -y (z-up)
        return np.column_stack([xy[..., 0], -xy[..., 1]]), "z [m] (to starboard)"
    return xy, "y [m] (to port)"


def _file_point(problem, point):
    """A z-up vector (x, y, z) in the frame of the problem's file."""

    return tuple(zup_to_choi(point)) if problem.frame == "choi" else tuple(point)


def _plan_extent(problem, plan):
    """(low, high) corners of what the plan view must show, file-frame plan coordinates [m]."""
    pts, _ = _file_plan(problem, problem.points[:, :2])
    seen = [pts]
    if problem.outline:
        seen.append(_file_plan(problem, np.array(problem.outline))[0])
    seen += [_file_plan(problem, np.array([c.position]))[0] for c in problem.fleet if c.position is not None]
    seen = np.vstack(seen)
    return seen.min(axis=0), seen.max(axis=0)


def plan_figure(low, high, legend_rows=2, width=_WIDTH):
    """A Figure sized so an equal-aspect plan of the box low..high fills it (no blank bands).

    Parameters
    ----------
    low, high : (2,) array  [m]
        Corners of the data to show, margins included.
    legend_rows : int
        Rows of the legend drawn below the axes.
    width : float  [mm]
    """
    span = np.maximum(np.asarray(high) - np.asarray(low), 1e-9)
    axes_width = width - 18.0  # the y label and tick labels
    axes_height = float(np.clip(axes_width * span[1] / span[0], 25.0, 190.0))
    height = axes_height + 22.0 + 4.0 * legend_rows  # title, x label, legend
    return Figure(figsize=(width * _MM, height * _MM), layout="constrained")


def plan_view(plan):
    """Plan view in the file's frame: hull outline, candidates (named outside the hull), CG
    and its envelope, chosen lugs, and the cranes (slew centre, chart reach, the lug each
    takes, its radius and SWL there)."""
    problem = plan.problem
    choi = problem.frame == "choi"
    low, high = _plan_extent(problem, plan)
    pad = 0.06 * max(high - low) + 2.0  # room for the names outside the hull
    low, high = low - pad, high + pad
    fig = plan_figure(low, high)
    ax = fig.subplots()
    if problem.outline:
        outline, _ = _file_plan(problem, np.array(problem.outline + problem.outline[:1]))
        ax.plot(outline[:, 0], outline[:, 1], color="0.3", lw=1.0, label="hull outline")
    pts, side = _file_plan(problem, problem.points[:, :2])
    ax.scatter(pts[:, 0], pts[:, 1], s=12, color="0.55", label="candidates", zorder=2)
    (cog,), _ = _file_plan(problem, np.array([problem.body.cog[:2]]))
    centre = np.mean(pts, axis=0)
    chosen, _ = _file_plan(problem, plan.lugset.points[:, :2])
    taken = {plan.lugs[label] for label in plan.labels}
    metres_per_mm = (high[0] - low[0]) / (_WIDTH - 18.0)
    names_shown = _label_rows(problem.names, pts, centre, metres_per_mm)
    for name, (x, y), row in zip(problem.names, pts, names_shown):
        if row is None:
            continue
        # away from the body's middle, on screen (the papers' frame draws its z axis down)
        up = (y >= centre[1]) != choi
        rise = 4 + 7 * row
        ax.annotate(
            name,
            (x, y),
            fontsize=_SMALL - 0.5,
            color="0.25" if name in taken else "0.45",
            ha="center",
            va="bottom" if up else "top",
            xytext=(0, rise if up else -rise),
            textcoords="offset points",
        )
    order = _around(chosen, cog)
    order = np.r_[order, order[:1]]
    ax.plot(chosen[order, 0], chosen[order, 1], color="tab:blue", lw=0.8, ls="--")
    ax.scatter(chosen[:, 0], chosen[:, 1], s=45, color="tab:blue", label="chosen lugs", zorder=3)
    shown = _label_rows(plan.labels, chosen, centre, metres_per_mm, rows=1, size=_FONT)
    for label, (x, y), row in zip(plan.labels, chosen, shown):
        if row is None:
            continue
        inward = (y < centre[1]) != choi  # the lug's name goes inside the hull
        ax.annotate(
            label,
            (x, y),
            fontsize=_FONT,
            color="tab:blue",
            fontweight="bold",
            ha="center",
            va="bottom" if inward else "top",
            xytext=(0, 5 if inward else -5),
            textcoords="offset points",
        )
    thinned = None in shown or None in names_shown
    if _positioned(problem):
        _draw_cranes(ax, plan)
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    _cog_envelope(ax, problem, cog, high - low)
    ax.scatter([cog[0]], [cog[1]], marker="+", s=50, lw=1.2, color="tab:red", label="CG (nominal)", zorder=5)
    ax.set_aspect("equal")
    if choi:
        ax.invert_yaxis()  # seen from above with x to the right, starboard is down
    ax.set_xlabel("x [m] (forward)")
    ax.set_ylabel(side)
    frame = "papers' frame" if choi else "z-up frame"
    ax.set_title(
        f"Plan view ({frame}, seen from above)"
        + ("\nnames left out where they would overlap; the tables name every lug" if thinned else "")
    )
    _style(ax)
    fig.legend(loc="outside lower center", ncols=4, fontsize=_SMALL, frameon=False)
    return fig


def _label_rows(names, points, centre, metres_per_mm, rows=2, size=_SMALL - 0.5):
    """Row (0 .. rows - 1) of each point's name, or None where it is left out: along each
    side of the body (by x), a name that would run into its neighbour's steps out a row, and
    where every row is taken it is not drawn (many points: the figure stays legible and the
    tables name every point). The last point of a side is always named (the one before it
    gives way)."""
    width = [
        len(n) * 0.62 * size * 0.3528 * metres_per_mm + 1.5 * metres_per_mm for n in names
    ]  # [m]: characters x em fraction x pt -> mm -> m, plus a gap
    placed = [None] * len(names)
    for side in (points[:, 1] >= centre[1], points[:, 1] < centre[1]):
        last = {}  # row -> (index, x, half width) of the last name placed in it
        order = sorted(np.flatnonzero(side), key=lambda k: points[k, 0])
        for pos, k in enumerate(order):
            x, half = points[k, 0], width[k] / 2
            free = [r for r in range(rows) if r not in last or x - last[r][1] >= last[r][2] + half]
            if not free and pos == len(order) - 1:  # the side's end: its neighbour gives way
                row = min(last, key=lambda r: last[r][1])
                placed[last[row][0]] = None
                free = [row]
            if free:
                placed[k] = free[0]
                last[free[0]] = (k, x, half)
    return placed


def _cog_envelope(ax, problem, cog, span):
    """The CG envelope in plan; drawn enlarged, and said so, when too small to see."""
    from matplotlib.patches import Rectangle

    # half-widths along the plan axes (the papers' z is -y: the same magnitude)
    dx, dy = (abs(float(v)) for v in problem.cog_envelope.half_widths[:2])
    if not (dx or dy):
        return
    size = f"{2 * dx:.2f} x {2 * dy:.2f} m"
    smallest = 0.025 * max(span)  # [m] below this the box is a speck at print size
    scale = max(1.0, smallest / max(dx, dy))
    scale = float(np.ceil(scale)) if scale > 1.0 else 1.0
    label = f"CG envelope {size}" if scale == 1.0 else f"CG envelope {size}, drawn x{scale:g}"
    ax.add_patch(
        Rectangle(
            (cog[0] - scale * dx, cog[1] - scale * dy),
            2 * scale * dx,
            2 * scale * dy,
            fc=(0.84, 0.15, 0.16, 0.15),
            ec="tab:red",
            lw=0.9,
            ls="-" if scale == 1.0 else "--",
            label=label,
            zorder=4,
        )
    )


def _positioned(problem):
    return any(c.position is not None for c in problem.fleet)


def _draw_cranes(ax, plan):
    """Each crane's slew centre (named, with the lug it takes, its radius and SWL there), its
    chart reach, and a line to its lug."""
    from matplotlib.patches import Circle

    problem = plan.problem
    choi = problem.frame == "choi"
    chosen, _ = _file_plan(problem, plan.lugset.points[:, :2])
    centre = np.mean(_file_plan(problem, problem.points[:, :2])[0], axis=0)
    lug_of = {name: k for k, name in enumerate(plan.chosen.crane_names)}
    colors = [
        "tab:orange",
        "tab:green",
        "tab:purple",
        "tab:brown",
        "tab:pink",
        "tab:olive",
        "tab:cyan",
        "tab:gray",
    ]
    for j, crane in enumerate(problem.fleet):
        if crane.position is None:
            continue
        color = colors[j % len(colors)]
        ((cx, cy),), _ = _file_plan(problem, np.array([crane.position]))
        ax.scatter([cx], [cy], marker="s", s=40, color=color, zorder=4)
        if np.isfinite(crane.reach):
            ax.add_patch(Circle((cx, cy), crane.reach, fill=False, ec=color, ls=":", lw=0.7))
        k = lug_of.get(crane.name)
        text = crane.name
        if k is not None:
            x, y = chosen[k]
            label = plan.labels[k]
            ax.plot([cx, x], [cy, y], color=color, lw=1.1)
            _clearance_zone(ax, (cx, cy), (x, y), 0.5 * problem.crane_clearance, color)
            text += f"\n{label}: radius {plan.radius[label]:.1f} m, SWL {plan.swl[label]:.1f} t"
        # the crane's text away from the hull, on screen
        up = (cy >= centre[1]) != choi
        ax.annotate(
            text,
            (cx, cy),
            fontsize=_SMALL,
            color=color,
            ha="center",
            va="bottom" if up else "top",
            xytext=(0, 5 if up else -5),
            textcoords="offset points",
            bbox={"fc": "white", "ec": "none", "alpha": 0.8, "pad": 0.5},
        )
    ax.plot([], [], color="0.4", ls=":", lw=0.7, label="crane reach (chart)")
    ax.scatter([], [], marker="s", color="0.4", label="crane slew centre")
    if plan.clearances and problem.crane_clearance > 0.0:
        least = min(plan.clearances.values(), key=lambda c: c[1])
        ax.fill(
            [], [], color="0.4", alpha=0.15, label=f"boom +- half the clearance {problem.crane_clearance:g} m"
        )
        ax.plot([], [], " ", label=f"least clearance {least[1]:.1f} m ({least[0]} - {least[2]})")


def _clearance_zone(ax, start, end, half, color):
    """A boom's zone in plan: every point within ``half`` of it (two zones that do not overlap
    keep twice ``half`` between their booms)."""
    from matplotlib.patches import Circle, Polygon

    if half <= 0.0:
        return
    p0, p1 = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    along = p1 - p0
    normal = np.array([-along[1], along[0]]) / max(np.linalg.norm(along), 1e-12) * half
    corners = [p0 + normal, p1 + normal, p1 - normal, p0 - normal]
    style = {"color": color, "alpha": 0.15, "lw": 0}
    ax.add_patch(Polygon(corners, closed=True, **style))
    for p in (p0, p1):
        ax.add_patch(Circle(tuple(p), half, **style))


def spread_map(plan, count=41):
    """The plan's objective (tension spread, utilisation spread, or largest T / SWL) over the
    tolerance box, at each attitude the worst over the CG envelope and the hook errors (the
    plan's own worst case, so the map's top is the starred worst); heel on the horizontal
    axis as in the tension curves."""
    goal = plan.problem.goal
    utilisation, largest = goal.per_swl, goal.peak
    heel, trim, spread = plan.spread_map(count)
    fig = Figure(figsize=(125 * _MM, 100 * _MM), layout="constrained")
    ax = fig.subplots()
    mesh = ax.pcolormesh(heel, trim, spread.T, shading="auto", cmap="viridis")
    unit = (
        ("largest T / SWL [-]" if largest else "max - min of T / SWL [-]")
        if utilisation
        else "max - min tension [t]"
    )
    bar = fig.colorbar(mesh, ax=ax)
    bar.set_label(unit, size=_FONT)
    bar.ax.tick_params(labelsize=_SMALL)
    worst = plan.chosen.worst
    dx, dy, dz = _file_point(plan.problem, worst.cog_offset)
    value = f"{plan.chosen.worst_value:.3f}" if utilisation else f"{plan.worst_spread:.1f} t"
    ax.scatter(
        [worst.heel],
        [worst.trim],
        marker="*",
        s=120,
        color="tab:red",
        edgecolors="white",
        linewidths=0.6,
        label=f"worst {value} at heel {worst.heel:+.2f}, trim "
        f"{worst.trim:+.2f} deg, CG offset ({dx:+.2f}, {dy:+.2f}, "
        f"{dz:+.2f}) m",
    )
    ax.set_xlabel("heel [deg] (+ starboard down)")
    ax.set_ylabel("trim [deg] (+ bow down)")
    what = ("Largest T / SWL" if largest else "Utilisation spread") if utilisation else "Tension spread"
    hooks = " and hook errors" if plan.lugset.hook_uncertain else ""
    ax.set_title(f"{what} over the tolerance box\n(each point: worst CG of the envelope{hooks})")
    _style(ax)
    ax.grid(False)
    fig.legend(loc="outside lower center", fontsize=_SMALL, frameon=False)
    return fig


def _around(points, cog):
    plan = points[:, :2] - np.array(cog[:2])
    return np.argsort(np.arctan2(plan[:, 1], plan[:, 0]))


_PHASE_COLOURS = {
    "grounded": "#c9b79c",
    "hanging submerged": "#9ecae1",
    "piercing the surface": "#c6dbef",
    "clear": "#e5f5e0",
    "afloat": "#fdd0a2",
}


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

    fig = Figure(figsize=(11, 10), layout="constrained")
    strip, loads, water, pose = fig.subplots(
        4, 1, sharex=True, gridspec_kw={"height_ratios": [0.35, 3, 3, 2]}
    )
    span = max(float(curve.hoist[-1] - curve.hoist[0]), 1e-9)
    for state, a, b in _phases(curve):
        strip.axvspan(a, b, color=_PHASE_COLOURS.get(state, "0.9"), lw=0)
        narrow = b - a < 0.08 * span
        strip.text(
            a if narrow else 0.5 * (a + b),
            0.5,
            f" {state}",
            ha="left" if narrow else "center",
            va="center",
            fontsize=8,
            style="italic",
            transform=blended_transform_factory(strip.transData, strip.transAxes),
        )
    strip.set_yticks([])
    strip.set_title(
        f"Load curve: {curve.name or 'lift'}\ncrane loads, water and ground forces, attitude "
        "against hoist; the hull's state on this strip",
        fontsize=11,
    )
    for name, column in zip(curve.lugs, curve.tensions.T):
        loads.plot(curve.hoist, column, label=name)
    m = curve.max_load
    for k, (a, b) in enumerate(m.plateau):
        label = (
            (
                f"max {m.tension:.1f} t ({m.lug}),\nwithin {100 * PLATEAU_REL:g} % "
                f"({m.tolerance:.2f} t) over\n"
                + ", ".join(f"{lo:.3f}-{hi:.3f} m" for lo, hi in m.plateau)
                + (" (to the end)" if m.to_end else "")
            )
            if k == 0
            else None
        )
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
        water.axhline(
            curve.weight + curve.trapped_water,
            color="tab:purple",
            ls=":",
            lw=1.2,
            label=f"W + trapped water\n{curve.weight:.1f} + {curve.trapped_water:.1f} t",
        )
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
        loads.annotate(
            f"{event.name} {event.hoist:.3f} m",
            (event.hoist, 1.0),
            xycoords=blended_transform_factory(loads.transData, loads.transAxes),
            xytext=(3, -4),
            textcoords="offset points",
            rotation=90,
            va="top",
            fontsize=8,
            color="tab:green",
        )
    for ax in (loads, water, pose):
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig
