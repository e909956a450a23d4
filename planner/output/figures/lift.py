"""The load-curve figure with what issue 15 added: the breakout, the soil's pull, the water
draining from compartments, and a time axis when the lift has a hoist speed.

It draws on :func:`liftplan.planner.output.figures.plan.load_curve` (crane loads, water and
ground forces, attitude, events and phases against hoist) and adds to it.
"""

from __future__ import annotations

from liftplan.planner.output.figures import plan as figures


def lift_figure(curve, swl=None):
    """The load curve's figure (matplotlib Figure).

    Parameters
    ----------
    curve : liftplan.model.lift.LoadCurve
    swl : float, optional  [t]

    Notes
    -----
    Every event (lift-off, breakout, released, surface, clear, drained) is a line on every
    panel, named with its hoist (and its time, with a speed); the top axis reads time
    [s] = hoist / speed.
    """
    from matplotlib.transforms import blended_transform_factory

    fig = figures.load_curve(curve, swl=swl)  # looked up when called: it can be replaced
    if len(getattr(fig, "axes", ())) < 4:  # not the four panels drawn there: nothing to add to
        return fig
    strip, loads, water, pose = fig.axes[:4]
    if curve.soil_force is not None and curve.soil_force.any():
        water.plot(
            curve.hoist,
            curve.soil_force,
            color="tab:brown",
            label="soil's pull on the hull\n(suction; breakout force)",
        )
    breakout, released = curve.event("breakout"), curve.event("released")
    if breakout is not None:
        _breakout_inset(water, curve, breakout, released)
    if curve.water is not None:
        water.plot(
            curve.hoist,
            curve.water,
            color="tab:purple",
            ls="-.",
            label=f"water in compartments\n({curve.drainage_note})"
            if curve.drainage_note
            else "water in compartments",
        )
    if curve.time is not None:
        speed = curve.speed
        top = strip.secondary_xaxis("top", functions=(lambda h: h * 60.0 / speed, lambda t: t * speed / 60.0))
        top.set_xlabel(f"time [s] at a hoist speed of {speed:g} m/min", fontsize=9)
        top.tick_params(labelsize=8)
        for event in curve.events:
            if event.time is not None:
                pose.annotate(
                    f"{event.time:.0f} s",
                    (event.hoist, 0.0),
                    xycoords=blended_transform_factory(pose.transData, pose.transAxes),
                    xytext=(3, 3),
                    textcoords="offset points",
                    rotation=90,
                    fontsize=7,
                    color="tab:green",
                )
    water.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    if curve.vessel_limits:
        _vessel_limits(fig.axes[:4], pose, curve)
    return fig


def _vessel_limits(panels, pose, curve):
    """Each crane vessel's limited angle against hoist on the attitude panel (dashed, its limit
    dotted), and the first hoist where a limit is broken as a red line on every panel."""
    colours = iter(["tab:red", "tab:purple", "tab:olive", "tab:cyan", "tab:pink", "tab:gray"])
    for limit in curve.vessel_limits:
        if limit.check == "vessel_freeboard":
            continue
        colour = next(colours, "k")
        key = "heel" if limit.check == "vessel_heel" else "trim"
        pose.plot(
            curve.hoist,
            curve.vessels[limit.vessel][key],
            ls="--",
            color=colour,
            lw=1.0,
            label=f"vessel {limit.vessel} {key} (limit +-{limit.limit:g} deg)",
        )
        for sign in (1.0, -1.0):
            pose.axhline(sign * limit.limit, ls=":", color=colour, lw=0.8)
    for limit in curve.vessel_limits:
        if limit.ok:
            continue
        for ax in panels:
            ax.axvline(limit.first_broken, color="red", lw=1.0)
        _hoist_label(
            pose,
            f"{limit.vessel}: {limit.check.removeprefix('vessel_')} limit {limit.limit:g} {limit.unit} "
            f"broken from {limit.first_broken:.3f} m",
            (limit.first_broken, 0.95),
            "red",
            va="top",
        )
    pose.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))


def _hoist_label(ax, text, at, colour, va="center"):
    """A label written up a hoist line: ``at`` is (hoist [m], height as a fraction of the axes)."""
    ax.annotate(
        text,
        at,
        xycoords=("data", "axes fraction"),
        rotation=90,
        va=va,
        ha="right",
        fontsize=7,
        color=colour,
        bbox={"fc": "w", "ec": "none", "pad": 0.5},
    )


def _breakout_inset(ax, curve, breakout, released):
    """A zoom on the first hoists, where lift-off, breakout and release crowd together."""
    first = min(e.hoist for e in curve.events)
    last = (released or breakout).hoist
    pad = max(0.5 * (last - first), 0.02)
    lo, hi = max(curve.hoist[0], first - pad), last + pad
    inset = ax.inset_axes([0.3, 0.4, 0.36, 0.48])
    keep = (curve.hoist >= lo) & (curve.hoist <= hi)
    inset.plot(curve.hoist[keep], curve.crane_load[keep], color="k", lw=1.2)
    inset.plot(curve.hoist[keep], curve.soil[keep], color="tab:brown", lw=1.0)
    inset.plot(curve.hoist[keep], curve.ground_reaction[keep], color="tab:orange", lw=1.0)
    for event in curve.events:
        if lo <= event.hoist <= hi:
            inset.axvline(event.hoist, color="tab:green", lw=0.8, ls="-.")
            when = f", {event.time:.1f} s" if event.time is not None else ""
            _hoist_label(inset, f"{event.name} {event.hoist:.3f} m{when}", (event.hoist, 0.5), "tab:green")
    inset.set_xlim(lo, hi)
    peak = curve.peak_crane_load[0]
    inset.set_title(
        f"breakout, zoomed: peak {peak:.1f} t = W + water - B + F_b (black: sum of rope "
        "tensions,\nbrown: soil's pull, orange: ground reaction) [t] against hoist [m]",
        fontsize=7,
    )
    inset.tick_params(labelsize=7)
    inset.grid(True, lw=0.3)
