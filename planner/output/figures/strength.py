"""The hull girder figure of a solved state (matplotlib, object API, no pyplot state).

Three panels against the body's x: the loads (weight and buoyancy per length, trapped water,
the lift and ground forces as stems on their own axis), the shear force and the bending
moment, each with its allowable envelope shaded (+- the allowable) where ``[strength]``
gives one, and the largest values marked.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

_DENSE = 1200  # points per curve on top of the breakpoints


def strength_figure(scene, eq, girder):
    """Weight, buoyancy, lift forces, shear force and bending moment against x.

    Parameters
    ----------
    scene : Scene
        For the envelopes (``scene.strength``) and the title.
    eq : Equilibrium
        The solved state (model and pose, for the title).
    girder : GirderForces
        From :func:`liftplan.model.strength.hull_girder`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = Figure(figsize=(10, 9.5), layout="constrained")
    loads, shear, moment = fig.subplots(3, 1, sharex=True, gridspec_kw={"height_ratios": [1.1, 1, 1]})
    lo, hi = girder.shear_curve.span
    xs = np.union1d(np.linspace(lo, hi, _DENSE), girder.shear_curve.breaks)
    # one-sided values at each breakpoint, so jumps draw vertical
    xx = np.repeat(xs, 2)
    pose = eq.pose
    fig.suptitle(
        f"Hull girder: {scene.name or 'scene'}\n{eq.model} model, heel {pose.heel:+.2f} deg, "
        f"trim {pose.trim:+.2f} deg; Q and M of the part aft of the section (M > 0 sagging)",
        fontsize=11,
    )

    _load_panel(loads, girder, xx, eq.weight)
    for ax, curve, peak, name, unit, symbol in (
        (shear, girder.shear_curve, girder.max_shear, "shear_force", "t", "Q"),
        (moment, girder.moment_curve, girder.max_moment, "bending_moment", "t m", "M"),
    ):
        values = np.ravel(np.column_stack([curve(xs, "left"), curve(xs, "right")]))
        ax.plot(xx, values, color="C0", lw=1.4, label=f"{symbol}(x)")
        envelope = getattr(scene.strength, name) if scene.strength is not None else None
        if envelope is not None:
            limit = scene.strength.allowable(name, xs)
            ax.fill_between(
                xs,
                -limit,
                limit,
                color="C2",
                alpha=0.15,
                lw=0,
                label=f"allowable |{symbol}| (inside the band)",
            )
            ax.plot(xs, limit, color="C2", lw=0.8)
            ax.plot(xs, -limit, color="C2", lw=0.8)
        ax.plot(
            [peak.x],
            [peak.signed],
            "o",
            color="C3",
            ms=5,
            label=f"max |{symbol}| {peak.value:.1f} {unit} at x = {peak.x:.2f} m",
        )
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_ylabel(f"{'shear force Q' if symbol == 'Q' else 'bending moment M'} [{unit}]")
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
        ax.grid(True, lw=0.3)
    moment.set_xlabel("body x [m] (forward)")
    return fig


#: The narrowest the loads panel is drawn  [pt] (10 in wide with the legends on the right,
#: or at the report's print width with the legends below): the labels are laid out for it.
_PANEL_PT = 0.6 * 10.0 * 72.0
#: The shortest the loads panel is drawn  [pt] (at the report's print size).
_PANEL_HEIGHT_PT = 100.0
_LABEL_PT = 7.0  # label font size
_GAP_PT = 3.0  # least white space between two labels


def _text_width(text, size=_LABEL_PT):
    """Width of the widest line of ``text`` at ``size`` points  [pt]."""
    from matplotlib.textpath import TextPath

    return max(TextPath((0.0, 0.0), line or " ", size=size).get_extents().width for line in text.split("\n"))


def _station_labels(forces, points, span):
    """Label each station's stem (ropes at one x, port and starboard, share a stem).

    Names and force at the stem where the labels fit side by side on the narrowest panel
    (:data:`_PANEL_PT`); else the station's number at its stem (in two staggered rows where
    even the numbers would touch) and the returned key, one "k: names force" per station,
    for the legend.

    Returns
    -------
    key : list of str
        Empty when the stems carry their names.
    rows : int
        Lines of text above the highest stem (names and force: 2; numbers: 1, staggered 2).
    """
    stations = {}
    for p in points:
        stations.setdefault(round(p.x, 6), []).append(p)
    xs = sorted(stations)
    tops = [max(p.normal for p in stations[x]) for x in xs]
    names = [", ".join(p.name.split(" ", 1)[1] if " " in p.name else p.name for p in stations[x]) for x in xs]
    totals = [sum(p.normal for p in stations[x]) for x in xs]
    full = [f"{n}\n{t:.1f} t" for n, t in zip(names, totals)]
    per_pt = max(span, 1e-9) / _PANEL_PT  # data x per point on the narrowest panel

    def fits(texts):
        widths = [_text_width(t) for t in texts]
        return all(
            (b - a) / per_pt >= 0.5 * (wa + wb) + _GAP_PT
            for a, b, wa, wb in zip(xs, xs[1:], widths, widths[1:])
        )

    if fits(full):
        for x, top, text in zip(xs, tops, full):
            forces.annotate(
                text, (x, top), textcoords="offset points", xytext=(0, 4), ha="center", fontsize=_LABEL_PT
            )
        return [], 2
    numbers = [str(k) for k in range(1, len(xs) + 1)]
    stagger = not fits(numbers)
    for k, (x, top, number) in enumerate(zip(xs, tops, numbers)):
        forces.annotate(
            number,
            (x, top),
            textcoords="offset points",
            xytext=(0, 4 + (_LABEL_PT + 2.0) * (k % 2 if stagger else 0)),
            ha="center",
            fontsize=_LABEL_PT,
            fontweight="bold",
        )
    return [f"{k}: {n}  {t:.1f} t" for k, n, t in zip(numbers, names, totals)], 1 + stagger


def _load_panel(ax, girder, xx, weight):
    """Distributed loads (t/m, left axis) and point loads (t, stems on the right axis)."""
    xs = xx[::2]

    def sided(curve):
        return np.ravel(np.column_stack([curve(xs, "left"), curve(xs, "right")]))

    down = sided(girder.weight)
    ax.fill_between(xx, -down, 0.0, color="0.55", alpha=0.5, lw=0, label="weight per length (down)")
    up = np.zeros(1)
    if girder.buoyancy is not None:
        up = sided(girder.buoyancy)
        ax.fill_between(xx, up, 0.0, color="C0", alpha=0.35, lw=0, label="buoyancy per length (up)")
    if girder.trapped_water is not None:
        trapped = sided(girder.trapped_water)
        down = np.maximum(down, trapped)
        ax.fill_between(
            xx, -trapped, 0.0, color="C9", alpha=0.5, lw=0, label="trapped water per length (down)"
        )
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_ylabel("distributed load [t/m]")
    ax.grid(True, lw=0.3)
    forces = ax.twinx()
    points = [p for p in girder.point_loads if p.normal != 0.0 or p.couple != 0.0]
    for p in points:
        colour = "C1" if p.name.startswith(("rope", "leg")) else "C5"
        forces.plot([p.x, p.x], [0.0, p.normal], color=colour, lw=2.0)
        forces.plot([p.x], [p.normal], "^" if p.normal >= 0 else "v", color=colour, ms=6)
    key, rows = _station_labels(forces, points, float(np.ptp(xs)))
    # both axes' zeros on one line: the distributed loads below, the lift forces above it
    low = -1.3 * max(float(np.max(down)), 1e-9)
    high = max(1.3 * float(np.max(up)), 1.2 * -low)
    ax.set_ylim(low, high)
    peak = max([p.normal for p in points] + [1e-9 * weight])
    bottom = min([p.normal for p in points] + [0.0])
    # above the highest stem, room for its label on the shortest panel drawn: the labels'
    # share of the panel's height is (top - peak) / (top - lowest), lowest = -ratio x top
    ratio = max(-low / high, -1.35 * bottom / peak)
    share = (rows * 1.2 * _LABEL_PT + 6.0) / _PANEL_HEIGHT_PT
    top = peak / max(1.0 - (1.0 + ratio) * share, 1.0 / 3.0)
    forces.set_ylim(min(low / high * top, 1.35 * bottom), top)
    forces.set_ylabel("point forces [t]")
    if any(p.name != "ground" for p in points):
        forces.plot([], [], color="C1", lw=2.0, label="rope / sling-leg force at its lug")
    if any(p.name == "ground" for p in points):
        forces.plot([], [], color="C5", lw=2.0, label="ground reaction")
    handles, labels = ax.get_legend_handles_labels()
    more, more_labels = forces.get_legend_handles_labels()
    if key:  # stations numbered at their stems: the key after the line styles
        blank = Line2D([], [], linestyle="none")
        more, more_labels = more + [blank] * len(key), more_labels + key
    entries = len(labels) + len(more_labels)
    forces.legend(
        handles + more,
        labels + more_labels,
        loc="upper left",
        bbox_to_anchor=(1.13, 1.0),
        fontsize=8 if not key else 7,
        frameon=False,
        ncols=1 if entries <= 18 else 2,
        handlelength=2.0,
    )
