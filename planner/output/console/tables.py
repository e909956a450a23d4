"""Plain-text tables for the terminal (no colour, fixed columns, units in every header)."""

from __future__ import annotations

import math

from liftplan.model.lift import EVENT_TOL, PLATEAU_REL
from liftplan.planner.output.console.rope_table import GROUPED_FROM, rope_rows

__all__ = ["batch_table", "equilibrium_table", "load_curve_table"]


def equilibrium_table(scene, eq, girder=None):
    """A readable report of one solve.

    Parameters
    ----------
    scene : Scene
    eq : Equilibrium
    girder : GirderForces, optional
        Shear force and bending moment of the state
        (:func:`liftplan.model.strength.hull_girder`): a strength summary is added.

    Returns
    -------
    str
    """
    title = scene.name or "scene"
    pose = eq.pose
    lines = [
        f"{title}",
        f"model {eq.model} ({eq.solver.method} solve), equilibrium residual {eq.residual:.1e} t",
        f"pose: heel {pose.heel:+.3f} deg (+ starboard down), trim {pose.trim:+.3f} deg "
        f"(+ bow down), lift height {pose.lift_height:.3f} m",
        "",
    ]
    if eq.tide is not None:
        lines.insert(
            -1,
            f"tide: at {eq.tide.time:g} h the water is at {eq.tide.level:.3f} m, {eq.tide.rise:+.3f} m "
            "since the table's first time (the floating cranes' tips and the water rose with it)",
        )
    if eq.tensions and eq.rigging is None and len(eq.tensions) >= GROUPED_FROM:
        lines += rope_rows(scene, eq)  # many ropes: one line per station, port beside starboard
    else:
        lines += _rope_lines(eq)
    if eq.rigging is not None:
        lines += _rigging_lines(eq)
    if eq.afloat is not None:
        lines += _afloat_lines(eq)
    if eq.vessels:
        lines += _vessel_lines(eq)
    if eq.wind is not None:
        lines += _wind_lines(eq.wind)
    if girder is not None:
        lines += _strength_lines(scene, eq, girder)
    return "\n".join(lines)


def _wind_lines(wind):
    """The wind: its force on the body, the CG's downwind shift and each rope's share of it."""
    shift = (wind.cog_shift[0] ** 2 + wind.cog_shift[1] ** 2) ** 0.5
    lines = [
        "",
        f"wind: {wind.body_force:.2f} t on the body, its couple carried as the weight {shift:.3f} m "
        "downwind in plan"
        + "".join(
            f"; boom {k} {f:.2f} t (heel {h:+.3f}, trim {t:+.3f} deg)" for k, (f, h, t) in wind.booms.items()
        ),
    ]
    if wind.load_changes is None:
        lines.append("  the wind's share of each rope's tension: none (no equilibrium in still air)")
    else:
        shares = ", ".join(f"{k} {v:+.2f}" for k, v in wind.load_changes.items())
        lines.append(
            f"  the wind's share of each rope's tension [t] (in the tensions above, SWL checked): {shares}"
        )
    return lines


def _vessel_lines(eq):
    """One line per crane vessel: its load, heave, heel, trim, tip drops and levelling ballast."""
    width = _name_width(eq.vessels, 8)
    lines = [
        "",
        "crane vessels (heave + down; heel + starboard down, trim + bow down, ballast included; tip "
        "drop: the extra hoist as the load comes on):",
        f"{'vessel':<{width}}{'load [t]':>10}{'heave [m]':>11}{'heel [deg]':>12}{'trim [deg]':>12}"
        f"{'tip drop [m]':>14}   levelling ballast [t m] (heel, trim)",
    ]
    for name, v in eq.vessels.items():
        drops = ", ".join(f"{crane} {d:.3f}" for crane, d in v.tip_drops.items())
        lines.append(
            f"{name:<{width}}{v.load:10.1f}{v.heave:11.3f}{round(v.heel, 3) + 0.0:+12.3f}"
            f"{round(v.trim, 3) + 0.0:+12.3f}{v.tip_drop:14.3f}"
            f"   {round(v.levelling_ballast[0]) + 0:+d}, {round(v.levelling_ballast[1]) + 0:+d}"
            + (f"  (tip drops: {drops})" if len(v.tip_drops) > 1 else "")
            + ("" if v.freeboard is None else f"  freeboard {v.freeboard:.3f} m (min {v.min_freeboard:g})")
        )
    return lines


def _strength_lines(scene, eq, girder):
    """Largest |M| and |Q| with where they are, against the allowable there."""
    lines = ["", "hull girder (body as a beam along x; Q, M of the part aft of the section, M > 0 sagging):"]
    for name, peak, unit, symbol in (
        ("bending_moment", girder.max_moment, "t m", "M"),
        ("shear_force", girder.max_shear, "t", "Q"),
    ):
        line = f"  max |{symbol}| {peak.value:10.1f} {unit:<3} at x = {peak.x:7.2f} m"
        if symbol == "M" and peak.value > 0.0:
            line += " (sagging)" if peak.signed > 0 else " (hogging)"
        allowable = scene.strength.allowable(name, peak.x) if scene.strength is not None else None
        if allowable is not None:
            line += f"; allowable there {float(allowable):.1f} {unit} ({peak.value / allowable:.0%})"
        lines.append(line)
    added, moved = girder.correction
    if abs(added) > 1e-9 * eq.weight or abs(moved) > 1e-9:
        lines.append(
            f"  weight curve: {added:+.3g} t and its centroid {moved:+.3g} m spread linearly over "
            "its length to carry W at the CG's x"
        )
    return lines


def _name_width(names, least):
    """A text column's width: the longest name + 2 spaces, at least ``least``."""
    return max(least, max(len(str(n)) for n in names) + 2)


def _rope_lines(eq):
    """One line per rope (or per crane with slings), the total and the spread."""
    if not eq.tensions:
        return []
    who = "crane" if eq.rigging is not None else "lug"
    w = _name_width([who, "total", *eq.tensions], 8)
    lines = [f"{who:<{w}}{'tension [t]':>13}{'share of W [%]':>16}{'SWL [t]':>10}{'utilisation [%]':>17}"]
    for name, tension in eq.tensions.items():
        swl = eq.swl[name]
        util = eq.utilisation[name]
        lines.append(
            f"{name:<{w}}{tension:>13.2f}{100 * eq.share[name]:>16.2f}"
            f"{(f'{swl:.1f}' if swl else '-'):>10}"
            f"{(f'{100 * util:.1f}' if util is not None else '-'):>17}"
            + ("  slack" if name in eq.slack else "")
        )
    total = sum(eq.tensions.values())
    lines.append(f"{'total':<{w}}{total:>13.2f}{100 * total / eq.weight:>16.2f}")
    lines.append(f"spread (max - min tension): {eq.spread:.2f} t; weight W = {eq.weight:.2f} t")
    return lines


def _rigging_lines(eq):
    """Hook loads are the crane rows above; here the legs, hooks and spreader bars."""
    r = eq.rigging
    lines = [
        "",
        f"hook loads above are the hoist-rope tensions; sling legs (angle from the horizontal, "
        f"limit {r.min_sling_angle:g} deg):",
    ]
    legs = _name_width(["leg", *r.legs], 16)
    lugs = _name_width(["to lug", *(v or "(bar end)" for v in r.leg_lugs.values())], 10)
    lines.append(f"{'leg':<{legs}}{'to lug':<{lugs}}{'tension [t]':>13}{'angle [deg]':>13}")
    for key, tension in r.legs.items():
        angle = r.sling_angles[key]
        lines.append(
            f"{key:<{legs}}{r.leg_lugs[key] or '(bar end)':<{lugs}}{tension:>13.2f}{angle:>13.2f}"
            + ("  slack" if key in eq.slack else "")
            + ("  BELOW LIMIT" if not angle >= r.min_sling_angle else "")
        )
    frame = f"world, frame {eq.frame}"
    for name, at in r.hook_positions.items():
        lines.append("hook {}: ({:.3f}, {:.3f}, {:.3f}) m ({})".format(name, *eq.file_point(at), frame))
    for name, compression in r.spreader_compression.items():
        lines.append(f"spreader {name}: compression {compression:.2f} t")
    return lines


def _afloat_lines(eq):
    a = eq.afloat

    def xyz(point):
        return "-" if point is None else "({:.2f}, {:.2f}, {:.2f}) m".format(*point)

    lines = [
        f"state: {a.state} ({a.STATES[a.state]}); weight in air W = {eq.weight:.1f} t",
        f"buoyancy B (weight of the displaced water): {a.buoyancy:.1f} t = {a.density:g} t/m3 x "
        f"displaced volume {a.displaced_volume:.1f} m3, centre of buoyancy {xyz(a.centre_of_buoyancy)}",
    ]
    if abs(a.immersed_volume - a.displaced_volume) > 1e-9 * max(a.immersed_volume, 1.0):
        lines.append(
            f"hull envelope below the water plane: {a.immersed_volume:.1f} m3 (flooded: only the "
            "steel and the watertight compartments displace water)"
        )
    if a.trapped_water:
        lines.append(
            f"trapped water (a weight, carried with the hull): {a.trapped_water:.1f} t at "
            f"{xyz(a.centre_of_trapped_water)}"
        )
    lines.append(f"centre of gravity (weight in air): {xyz(a.centre_of_gravity)} (world)")
    if a.ground_reaction is not None:
        lines.append(f"ground reaction F_R: {a.ground_reaction:.1f} t at {xyz(a.contact)}")
    if a.freeing_force is not None:
        lines.append(f"freeing force (friction x ground reaction): {a.freeing_force:.1f} t")
    lines.append(_balance_line(eq))
    if eq.solver.iterations is not None:
        lines.append(f"{eq.solver.iterations} iterations, {1e3 * eq.solver.seconds:.1f} ms")
    return lines


def _balance_line(eq):
    """Why the cranes carry more (trapped water) or less (buoyancy, ground) than W."""
    a = eq.afloat
    terms = f"W {eq.weight:.1f} - B {a.buoyancy:.1f}"
    if a.trapped_water:
        terms += f" + trapped water {a.trapped_water:.1f}"
    reaction = a.ground_reaction or 0.0
    if a.ground_reaction is not None:
        if not eq.tensions:
            return f"ground reaction = {terms} = {a.crane_load(eq.weight) + reaction:.1f} t"
        terms += f" - F_R {reaction:.1f}"
    if not eq.tensions:
        return f"vertical balance: {terms} = {a.crane_load(eq.weight):.1f} t (afloat: 0)"
    total = sum(eq.tensions.values())
    return f"sum of rope tensions {total:.1f} t = {terms} = {a.crane_load(eq.weight):.1f} t"


def load_curve_table(scene, curve, rows=25):
    """The load curve, thinned to about ``rows`` lines (event steps kept), with its
    maximum load and plateau, and its events."""

    title = scene.name or "scene"
    names = curve.lugs
    head = (
        f"{'hoist [m]':>10}"
        + "".join(f"{'T ' + n + ' [t]':>12}" for n in names)
        + f"{'sum T [t]':>11}{'heel [deg]':>12}{'trim [deg]':>12}"
        + f"{'buoyancy [t]':>14}{'ground [t]':>12}  state"
    )
    lines = [
        title,
        f"weight in air W = {curve.weight:.1f} t"
        + (f"; trapped water carried {curve.trapped_water:.1f} t" if curve.trapped_water else "")
        + "; buoyancy B = weight of the displaced water",
        "sum T = W - B" + (" + trapped water" if curve.trapped_water else "") + " - ground reaction",
        head,
    ]
    every = max(1, len(curve.hoist) // rows)
    keep = set(range(0, len(curve.hoist), every)) | {len(curve.hoist) - 1}
    for k in range(1, len(curve.hoist)):
        if curve.state[k] != curve.state[k - 1]:  # both sides of a change of state
            keep |= {k - 1, k}
    for k in sorted(keep):
        lines.append(
            f"{curve.hoist[k]:>10.4f}"
            + "".join(f"{t:>12.1f}" for t in curve.tensions[k])
            + f"{curve.crane_load[k]:>11.1f}{curve.heel[k]:>12.2f}{curve.trim[k]:>12.2f}"
            f"{curve.buoyancy[k]:>14.1f}{curve.ground_reaction[k]:>12.1f}  {curve.state[k]}"
        )
    m = curve.max_load
    ranges = ", ".join(f"{a:.3f}-{b:.3f} m" for a, b in m.plateau)
    lines.append(
        f"maximum crane load: {m.tension:.1f} t on {m.lug}, held (within {100 * PLATEAU_REL:g} % = "
        f"{m.tolerance:.2f} t of it) over hoist {ranges}"
        + (" (to the last hoist computed)" if m.to_end else "")
    )
    lines.append(f"events (bisected between steps to {1e3 * EVENT_TOL:g} mm):")
    for e in curve.events:
        lines.append(f"  {e.name}: hoist {e.hoist:.4f} m +- {1e3 * e.tolerance:.2f} mm ({e.description})")
    for name, reason in missing_events(scene, curve):
        lines.append(f"  {name}: none within the range ({reason})")
    for hoist, reason in curve.failed:
        lines.append(f"no equilibrium at hoist {hoist:.2f} m: {reason}")
    return "\n".join(lines)


def _phase(curve, k):
    """The breakout phase at curve step ``k``, as the lift's events test it: "grounded",
    "breaking out" (off the bed, the soil's pull still on) or "free"."""
    if curve.state[k] == "grounded":
        return "grounded"
    return "breaking out" if curve.soil[k] > 0.0 else "free"


def missing_events(scene, curve):
    """Why each event the lift looks for did not happen within the range.

    Parameters
    ----------
    scene : Scene
        For the compartments' openings.
    curve : LoadCurve

    Returns
    -------
    list of (str, str)
        (event name, with the compartment for ``drained``; the reason), for every event
        kind the lift tests (lift-off, surface, clear; breakout and released with a
        breakout force; drained per compartment with openings) that is not on the curve.
    """
    last = f"at the last hoist {curve.hoist[-1]:.4g} m"
    why = {
        "lift-off": "free of the ground from the start"
        if curve.state[0] != "grounded"
        else "still on the ground " + last,
        "surface": "out of the water in part from the start"
        if curve.top[0] >= 0.0
        else "the top stays under water to the last hoist",
        "clear": "clear from the start" if curve.bottom[0] >= 0.0 else "not clear of the water " + last,
    }
    b = curve.breakout
    if b is not None and b.force > 0.0:  # the lift looks for these only with a breakout force
        first, end = _phase(curve, 0), _phase(curve, -1)
        why["breakout"] = (
            "off its bed from the start" if first != "grounded" else "still held by the soil " + last
        )
        why["released"] = (
            f"more than {b.clear:g} m off its bed from the start"
            if first == "free"
            else "still held by the soil " + last
            if end == "grounded"
            else f"broken out, the contact not yet {b.clear:g} m off its bed " + last
        )
    out = [(name, reason) for name, reason in why.items() if curve.event(name) is None]
    drained = {e.subject for e in curve.events if e.name == "drained"}
    for tank in curve.drainage:
        if tank.name in drained:
            continue
        openings = [o for o in scene.openings if o.compartment == tank.name]
        if any(math.isinf(o.area) for o in openings):
            reason = "an opening of infinite area: its water follows the pose at once, no drain time"
        elif not any(o.area * o.discharge > 0.0 for o in openings):
            reason = "no opening can flow (area 0)"
        elif curve.speed is None:
            reason = "no hoist speed (give --speed): carried full, the conservative bound"
        else:
            reason = f"{tank.final:.1f} t of water still in it " + last
        out.append((f"drained ({tank.name})", reason))
    return out


def batch_table(study, summary):
    """What a batch run did: cases per status, time, where the table is.

    Parameters
    ----------
    study : Study
    summary : BatchSummary

    Returns
    -------
    str
    """
    lines = [f"study {study.name} ({study.kind}): {summary.cases} cases"]
    resumed = summary.cases - summary.ran
    if summary.ran:
        lines.append(
            f"ran {summary.ran} in {summary.seconds:.2f} s on {summary.cores} cores "
            f"({summary.rate_per_core:,.0f} cases/s per core)"
            + (f"; {resumed} were done before (resumed)" if resumed else "")
        )
    else:
        lines.append("every case was done before (resumed)")
    lines += ["", f"{'status':<12}{'cases':>8}"]
    lines += [f"{status:<12}{count:>8}" for status, count in sorted(summary.counts.items())]
    lines += ["", f"table: {summary.output}"]
    return "\n".join(lines)
