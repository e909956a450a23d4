"""The load curve on the console with what issue 15 added: the breakout, the water in
compartments with openings, and time when the lift has a hoist speed.

Builds on :func:`liftplan.planner.output.console.tables.load_curve_table`.
"""

from __future__ import annotations

from liftplan.planner.output.console.tables import load_curve_table


def lift_table(scene, curve, rows=25):
    """The load curve's table and summary lines (str)."""
    lines = [load_curve_table(scene, curve, rows=rows)]
    if curve.speed is not None:
        end = curve.time[-1]
        lines.append(
            f"hoist speed {curve.speed:g} m/min: time = hoist / speed, {end:.0f} s to the last hoist"
        )
        timed = [e for e in curve.events if e.time is not None]
        if timed:
            lines.append(
                "  events in time: "
                + ", ".join(f"{e.name}{' ' + e.subject if e.subject else ''} {e.time:.1f} s" for e in timed)
            )
    b = curve.breakout
    if b is not None:
        how = b.describe()
        lines.append(
            f"breakout force F_b = {b.force:.1f} t ({how}); submerged weight at rest "
            f"{b.submerged_weight:.1f} t; held until the contact is {b.clear:g} m off its bed"
        )
        peak, at = curve.peak_crane_load
        event = curve.event("breakout")
        where = f" (breakout at {event.hoist:.4f} m)" if event else " (no breakout within the range)"
        lines.append(f"breakout peak: sum of rope tensions {peak:.1f} t at hoist {at:.4f} m{where}")
    if curve.drainage or curve.drainage_note:
        lines.append(f"compartments with openings: {curve.drainage_note}")
        for t in curve.drainage:
            drain = f"drained at {t.drain_time:.1f} s" if t.drain_time is not None else "not drained"
            lines.append(
                f"  {t.name}: {t.initial:.1f} t -> {t.final:.1f} t, {drain}"
                + (f", water balance error {t.mass_error:.1e}" if t.mass_error else "")
            )
    if curve.vessels:
        lines.append(
            "crane vessels over the curve (each rope in series with its vessel, coupled on a vessel "
            "under several cranes; heel + starboard down, trim + bow down, ballast included; tip drop: "
            "the extra hoist beyond a crane on land):"
        )
        for name, v in curve.vessels.items():
            heel, trim = (f"{_signed(v[k].min())} .. {_signed(v[k].max())}" for k in ("heel", "trim"))
            lines.append(
                f"  {name}: heel {heel} deg, trim {trim} deg, tip drop up to {v['tip_drop'].max():.3f} m"
                + (f", lowest freeboard {v['freeboard'].min():.3f} m" if "freeboard" in v else "")
            )
            lines += [f"    {_limit_line(limit)}" for limit in curve.vessel_limits if limit.vessel == name]
    return "\n".join(lines)


def _limit_line(limit):
    """One vessel limit over the curve: held, or the first hoist where it is broken."""
    what = {"vessel_heel": "|heel| <=", "vessel_trim": "|trim| <=", "vessel_freeboard": "freeboard >="}[
        limit.check
    ]
    worst = f"worst {_signed(limit.worst_signed)} {limit.unit} at hoist {limit.worst_hoist:.4f} m"
    if limit.ok:
        return f"ok   {what} {limit.limit:g} {limit.unit} over the whole curve ({worst})"
    return (
        f"FAIL {what} {limit.limit:g} {limit.unit} broken first at hoist {limit.first_broken:.4f} m "
        f"+- {1e3 * limit.tolerance:.2f} mm ({worst})"
    )


def _signed(value):
    """``value`` to 3 decimals with its sign, never ``-0.000``."""
    return f"{round(float(value), 3) + 0.0:+.3f}"
