"""The rope rows of the ``solve`` table for many ropes: one line per station, port beside
starboard.

With 26 or 64 ropes one row per rope is a column too long to read. Here the lugs are grouped
by side (port: body y > 0, starboard: y < 0, centre line: y = 0; ``z-up`` body frame, so the
same whatever frame the file was written in) and by station (the body x, lugs within
:data:`STATION_TOLERANCE` of each other share a station); each line is one station, aft to
fore, with each side's lugs next to each other, like a plan view turned on its side. A
summary line on top names the largest and smallest tension and the highest utilisation,
with where they are; a total line per side gives the side's share of the weight.
"""

from __future__ import annotations

from itertools import zip_longest

#: Lugs whose body x differ by at most this share a station  [m].
STATION_TOLERANCE = 0.01

#: ``equilibrium_table`` switches to these rows from this many ropes on.
GROUPED_FROM = 9

# side key, heading
_SIDES = (("port", "port"), ("starboard", "starboard"), ("centre", "centre line"))
_CELL = 34  # characters of one side's cell: lug, T, share of W, utilisation, flag
_NAMES_SHOWN = 6


def _side_of(y, tolerance):
    if y > tolerance:
        return "port"
    if y < -tolerance:
        return "starboard"
    return "centre"


def stations(scene):
    """Group the lugs by station and side.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    list of (float, dict of str to list of str)
        Per station, aft to fore: its body x [m] (the mean of its lugs') and the lug names on
        each side (``"port"``, ``"starboard"``, ``"centre"``), innermost (smallest |y|) first.
    """
    points = scene.lug_points()
    tolerance = 1e-6 * max(1.0, scene.plan_diameter)
    order = sorted(range(scene.n), key=lambda i: points[i, 0])
    groups = []
    for i in order:
        if groups and points[i, 0] - points[groups[-1][-1], 0] <= STATION_TOLERANCE:
            groups[-1].append(i)
        else:
            groups.append([i])
    out = []
    for group in groups:
        sides = {key: [] for key, _ in _SIDES}
        for i in sorted(group, key=lambda i: abs(points[i, 1])):
            sides[_side_of(points[i, 1], tolerance)].append(scene.lug_names[i])
        out.append((float(points[group, 0].mean()), sides))
    return out


def _names(names):
    shown = ", ".join(names[:_NAMES_SHOWN])
    return shown if len(names) <= _NAMES_SHOWN else f"{shown} and {len(names) - _NAMES_SHOWN} more"


def _cell(eq, name):
    if name is None:
        return " " * _CELL
    util = eq.utilisation[name]
    flag = "s" if name in eq.slack else "!" if util is not None and util > 1.0 else " "
    return (
        f"{name:<8}{eq.tensions[name]:>9.2f}{100 * eq.share[name]:>7.2f}"
        f"{(f'{100 * util:.1f}' if util is not None else '-'):>9} {flag}"
    )


def rope_rows(scene, eq):
    """Summary and rope rows of one solve, grouped by side and station.

    Parameters
    ----------
    scene : Scene
        One rope per lug (no sling sets).
    eq : Equilibrium
        Its solve; ``eq.tensions`` keyed by the scene's lug names.

    Returns
    -------
    list of str
        A summary line, a heading, one line per station (and per extra lug of a side at a
        station), a total line and, when a flag is shown, its legend.

    Raises
    ------
    ValueError
        The tensions are not keyed by the scene's lugs (a sling set's hook loads).
    """
    if set(eq.tensions) != set(scene.lug_names):
        raise ValueError("rope_rows: expected one rope per lug (tensions keyed by the scene's lugs)")
    groups = stations(scene)
    used = [key for key, _ in _SIDES if any(sides[key] for _, sides in groups)]
    where = {name: (x, key) for x, sides in groups for key in used for name in sides[key]}
    heading = dict(_SIDES)

    def at(name):
        x, key = where[name]
        return f"{name} (x {x:.2f} m, {heading[key]})"

    tensions = eq.tensions
    high = max(tensions, key=tensions.get)
    low = min(tensions, key=tensions.get)
    lines = [
        f"{len(tensions)} ropes, W = {eq.weight:.2f} t: tension max {tensions[high]:.2f} t at "
        f"{at(high)}, min {tensions[low]:.2f} t at {at(low)}, spread {eq.spread:.2f} t"
    ]
    utilisation = {k: u for k, u in eq.utilisation.items() if u is not None}
    if utilisation:
        top = max(utilisation, key=utilisation.get)
        over = [k for k, u in utilisation.items() if u > 1.0]
        lines.append(
            f"utilisation max {100 * utilisation[top]:.1f} % at {at(top)}; over the SWL: "
            + (_names(over) if over else "none")
        )
    else:
        lines.append("utilisation: no SWL given")
    lines.append(f"slack: {_names(list(eq.slack)) if eq.slack else 'none'}")
    lines.append("")
    lines.append(" " * 9 + "".join(f"   {heading[key]:<{_CELL}}" for key in used).rstrip())
    columns = f"{'lug':<8}{'T [t]':>9}{'W [%]':>7}{'SWL [%]':>9}  "
    lines.append(f"{'x [m]':>9}" + "".join(f"   {columns}" for _ in used).rstrip())
    for x, sides in groups:
        for k, names in enumerate(zip_longest(*(sides[key] for key in used))):
            station = f"{x:>9.2f}" if k == 0 else " " * 9
            lines.append(station + "".join(f"   {_cell(eq, name)}" for name in names).rstrip())
    totals = []
    for key in used:
        total = sum(tensions[name] for _, sides in groups for name in sides[key])
        totals.append(f"   {'total':<8}{total:>9.2f}{100 * total / eq.weight:>7.2f}" + " " * 11)
    lines.append(" " * 9 + "".join(totals).rstrip())
    flags = [
        text
        for flag, text in (("s", "s: slack"), ("!", "!: over the SWL"))
        if any(_cell(eq, name).endswith(flag) for name in tensions)
    ]
    if flags:
        lines.append("flags: " + ", ".join(flags))
    return lines
