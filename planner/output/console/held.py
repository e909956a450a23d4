"""The plan's console summary (``liftplan plan`` without ``--json``).

One utilisation: design hook load (the rules' chain, ``docs/design-loads.md``) over the chart
SWL at the crane's radius. Every other figure is named for what it is; every worst case names
its heel, trim and CG position; coordinates are in the planning file's frame, named once.
"""

from __future__ import annotations

import numpy as np

from liftplan.model.frames import FRAME_TEXT
from liftplan.planner.output.console.hull_water import hull_water_lines
from liftplan.planner.output.console.limits import length_lines, limit_lines
from liftplan.planner.output.console.text import GROUP, WIDTH, fold, grouped
from liftplan.planner.plans.common import OBJECTIVE_TEXT
from liftplan.planner.plans.vessel_loads import vessel_lines, wind_lines
from liftplan.planner.search.scenarios import Scenario


def coordinates_line(plan):
    """The console's line naming the frame of every coordinate it prints (the file's)."""
    return (
        f"coordinates: the file's frame, {FRAME_TEXT[plan.frame]}; heel > 0 starboard down, trim > 0 bow down"
    )


def plan_table(plan):
    """A readable summary of a plan.

    Parameters
    ----------
    plan : Plan

    Returns
    -------
    str
    """
    problem, chosen = plan.problem, plan.chosen
    stats = plan.stats
    fleet = (
        ""
        if problem.equal_cranes
        else f" x crane assignments in reach: {stats.rows} pairs ({stats.out_of_reach} out of reach, "
        f"{stats.clashing} with booms crossing or within {problem.crane_clearance:g} m)"
    )
    swl = sorted(set(plan.swl.values()))
    swl_text = f"{swl[0]:g} t" if len(swl) == 1 else "each crane's chart SWL at its radius"
    design = plan.design_loads
    lines = [
        problem.name or "lift plan",
        coordinates_line(plan),
        f"{stats.sets} lug sets of {problem.cranes} among {len(problem.candidates)} candidates"
        f"{fleet}: {stats.screened_out} ruled out by screening, {stats.evaluated} evaluated, "
        f"{stats.pruned} pruned by the bound ({stats.seconds:.2f} s)"
        if stats.summary is None
        else stats.summary,
        *limit_lines(stats, problem, plan.lengths),
        problem.weight_text,
        f"tolerance box: heel +-{problem.heel_tolerance:g} deg, trim +-{problem.trim_tolerance:g}"
        f" deg; tensions {problem.min_tension:g} t to {swl_text}",
        "objective: " + OBJECTIVE_TEXT[plan.objective],
        "",
        f"{'lug':<5}{'candidate':<10}{'crane':<11}{'R':>7}{'SWL':>8}{'H':>9}{'level T':>9}"
        f"{'worst':>9}{'tilt':>9}{'design':>9}{'util.':>7}  check",
        f"{'':<26}{'[m]':>7}{'[t]':>8}{'[m]':>9}{'[t]':>9}{'[t]':>9}{'[t]':>9}{'[t]':>9}{'[%]':>7}",
    ]
    rows = []
    for c in plan.capacity:
        radius = "-" if c.radius is None else f"{c.radius:.1f}"
        tilt = "-" if c.tilt is None else f"{c.tilt.load:.2f}"
        ok = c.design is not None and c.design.check.ok
        computed = c.design is not None and c.design.check.computed  # else "-", not "nan"
        hook_text = f"{c.design_hook_load:.2f}" if computed else "-"
        util_text = f"{100 * c.utilisation:.1f}" if computed else "-"
        rows.append(
            f"{c.label:<5}{c.lug[:9]:<10}{c.crane[:10]:<11}{radius:>7}{c.swl:>8.1f}"
            f"{plan.boom_heights[c.label]:>9.3f}{c.nominal:>9.2f}{c.worst:>9.2f}{tilt:>9}"
            f"{hook_text:>9}{util_text:>7}  {'ok' if ok else 'FAIL'}"
        )
    lines += grouped(rows)
    lines.append(
        "(level T: nominal CG, level; worst: largest in the box over the CG envelope; tilt: at "
        "the rules' tilt; design: the rules' design hook load; util. = design / chart SWL)"
    )
    if plan.lengths is not None:  # the planner chose the rope lengths
        lines += length_lines(plan.lengths)
    lines += _chain_lines(plan, design)
    lines += _breakout_lines(plan, design)
    lines += hull_water_lines(plan)
    lines += vessel_lines(plan.vessels, plan.stats.infeasible)
    lines += wind_lines(plan)
    over = "over the box, the CG envelope and the hook errors"
    if problem.breakout is not None:  # docs/planning.md "What the planner does not plan"
        over += " (not the breakout state: the seabed's hold is not in the planner's girder)"
    lines += girder_lines(plan, plan.girder, over)
    if not chosen.converged:
        lines.append(
            f"WARNING: the worst-case search still exceeded the LP bound by "
            f"{chosen.worst_value - chosen.bound:.4g} after {chosen.rounds} rounds; "
            "the worst shown is the largest found"
        )
    where = _where(plan, chosen.worst)
    if plan.objective == "reserve":
        summary = (
            f"largest T / SWL: nominal {100 * chosen.nominal_value:.1f} %, worst "
            f"{100 * chosen.worst_value:.1f} % at {where}; tension spread: nominal "
            f"{plan.spread:.2f} t, worst {plan.worst_spread:.2f} t"
        )
    elif plan.objective == "utilisation":
        summary = (
            f"utilisation spread (max - min of T / SWL): nominal "
            f"{100 * chosen.nominal_utilisation_spread:.1f} %, worst {100 * chosen.worst_value:.1f} % "
            f"at {where}; tension spread: nominal {plan.spread:.2f} t, "
            f"worst {plan.worst_spread:.2f} t"
        )
    else:
        summary = (
            f"spread: nominal {plan.spread:.2f} t, worst {plan.worst_spread:.2f} t at "
            f"{where} (this set's LP bound {chosen.bound:.2f} t)"
        )
    lines += [
        "",
        summary,
        _hook_line(plan),
        *_crew_lines(plan),
    ]
    lines += _ranking_lines(plan)
    return "\n".join(folded for line in lines for folded in fold(line))


def _hook_line(plan):
    """What the plan assumed of the hooks' heights: each hook's own tolerance."""
    if not np.any(plan.lugset.hook_tolerance > 0.0):
        return (
            "hook heights: no hook-height error assumed (hook_tolerance = 0); the worst "
            "case holds every hook at its planned height"
        )
    wind = " (a floating crane's with its boom's wind tip error)" if plan.problem.wind is not None else ""
    text = plan.tolerance_text()
    within = (
        f"every hook within {text.removesuffix(' on every hook')} of its plan{wind}, independently,"
        if text.endswith("on every hook")
        else f"each hook within its own tolerance of its plan{wind}, independently: {text};"
    )
    return (
        f"hook heights: {within} in the worst case and every limit; computed skew factors "
        + ", ".join(f"{'+'.join(s.lugs)} {s.factor:.3f}" for s in plan.skew)
        + f" (Noble Denton's default {plan.default_skew_factor:.2f})"
    )


def _times(plan, factor):
    """Each hook's tolerance times ``factor``, shortly: ``+-0.04 m on every hook`` or ``each
    its own tolerance x 2: L2 (Crane C) +-0.2 m, the others +-0 m``."""
    text = plan.tolerance_text(factor, short=True)
    return text if text.endswith("on every hook") else f"each its own tolerance x {factor:g}: {text}"


def _crew_lines(plan):
    """Tension change per centimetre of each hook (load-cell watchers act on it) and what a
    crew worse than assumed would see."""
    own = np.diag(plan.hook_sensitivity)
    cells = [f"{label} {v:.2f}" for label, v in zip(plan.labels, own)]
    worst = f"worst combination of 1 cm errors: {plan.twist_stiffness:.2f} t/cm"
    if len(cells) <= GROUP:
        lines = [
            "tension change per cm of a hook off its height (own rope, pose held): "
            + ", ".join(cells)
            + f" t/cm; {worst}"
        ]
    else:  # eight hooks a line, aligned
        lines = ["tension change per cm of a hook off its height [t/cm] (own rope, pose held):"]
        width = max(len(label) for label in plan.labels)
        cells = [f"{label:<{width}} {v:>6.2f}" for label, v in zip(plan.labels, own)]
        lines += ["  " + "  ".join(cells[k : k + GROUP]) for k in range(0, len(cells), GROUP)]
        lines.append(worst)
    needed = plan.hook_accuracy_needed
    lines.append(
        "the plan's limits hold for the same hook error on every hook up to "
        + (f"+-{needed:.3f} m" if np.isfinite(needed) else "any size")
        + " (preload held, worst signs)"
    )
    if not np.any(plan.lugset.hook_tolerance > 0.0):
        return lines
    for margin in plan.crew_margin((2.0, 5.0)):
        k = int(np.argmax(margin.rope_max / margin.limit))
        verdict = "within the limits" if margin.within_limits else "EXCEEDS the limits"
        lines.append(
            f"hooks {margin.factor:g}x worse ({_times(plan, margin.factor)}): worst spread "
            f"{margin.worst_spread:.1f} t, {plan.labels[k]} up to {margin.rope_max[k]:.1f} t "
            f"(limit {margin.limit[k]:.1f} t), lowest {margin.lowest:.1f} t: {verdict}"
        )
    return lines


def _chain_lines(plan, design):
    if design.chain is None:
        return ["", f"design loads NOT computed: {design.missing}"]
    lines = [
        "",
        f"design-load chain: tilt {design.tilt_note}",
        f"location: {plan.problem.rules.location_text} (the DAF column of Table 5-1)",
        f"{'crane':<12}{'contingency':>12}{'tilt':>8}{'skew':>8}{'DAF':>7}{'rigging [t]':>12}"
        f"{'static hook [t]':>16}{'code margin [t]':>17}  check",
    ]
    rows = []
    for c in plan.capacity:
        r = c.design
        factor = {f.name: f for f in r.factors}
        skew = factor["skew"].value if factor["skew"].applies_to.startswith("hook") else 1.0
        margin, margin_ok = (
            ("-", True)
            if r.code_margin is None
            else (
                f"{r.code_margin.value:.1f} <= {r.code_margin.limit:.1f}"
                if r.code_margin.ok
                else f"{r.code_margin.value:.1f} > {r.code_margin.limit:.1f}",
                r.code_margin.ok,
            )
        )
        rows.append(
            f"{c.crane[:11]:<12}{factor['weight_contingency'].value:>12.3f}"
            f"{factor['tilt'].value:>8.4f}{skew:>8.4f}{factor['daf'].value:>7.3f}"
            f"{r.rigging_weight:>12.2f}{r.static_hook_load:>16.2f}{margin:>17}  "
            f"{'ok' if margin_ok else 'FAIL'}"
        )
    lines += grouped(rows)
    static = "worst" if design.breakout is None else "max(worst, breakout)"
    lines.append(
        f"(static hook = max({static}, tilt) x contingency x skew + rigging; design = static hook "
        "x DAF; code margin: (level T x contingency + rigging) x (1 + margin) <= SWL)"
    )
    lines += _worst_lines(plan)
    return lines


def _worst_lines(plan):
    """Where each crane's worst load in the box and its load at the rules' tilt occur: two
    tables (the CG and the tilt axis in the file's frame)."""
    width = max(len(c.crane[:14]) for c in plan.capacity) + 2
    lines = [
        "worst in the box (CG in the file's frame):",
        f"  {'lug':<5}{'crane':<{width}}{'worst [t]':>10}{'heel [deg]':>12}{'trim [deg]':>12}"
        f"   CG x, y, z [m]",
    ]
    lines += grouped(
        [
            f"  {c.label:<5}{c.crane[:14]:<{width}}{c.worst:>10.2f}{c.worst_at.heel:>+12.2f}"
            f"{c.worst_at.trim:>+12.2f}   {_xyz(plan.cog_at(c.worst_at))}"
            for c in plan.capacity
        ]
    )
    tilted = [c for c in plan.capacity if c.tilt is not None]
    if not tilted:
        return lines
    lines += [
        "at the rules' tilt (the hoists holding the level tensions; axis and CG in the file's frame):",
        f"  {'lug':<5}{'crane':<{width}}{'tilt [t]':>10}{'tilt [deg]':>12}   "
        f"{'axis x, y, z [-]':<26}CG x, y, z [m]",
    ]
    rows = []
    for c in tilted:
        axis = plan.in_file_frame(c.tilt.axis)
        cog = plan.cog_at(Scenario(0.0, 0.0, c.tilt.cog_offset))
        text = f"({axis[0]:+.3f}, {axis[1]:+.3f}, {axis[2]:+.3f})"
        rows.append(
            f"  {c.label:<5}{c.crane[:14]:<{width}}{c.tilt.load:>10.2f}{c.tilt.tilt:>12.2f}   "
            f"{text:<26}{_xyz(cog)}"
        )
    return lines + grouped(rows)


def _breakout_lines(plan, design):
    """The breakout case: the peak load, each crane's held share, what governs the chain."""
    case = design.breakout
    if case is None:
        return []
    load, force = case.load, case.load.breakout
    model = force.describe()
    lines = [
        "",
        f"breakout from the seabed ({plan.problem.breakout_scene.name or 'breakout scene'}):",
        f"  peak total hook load {load.total:.2f} t = submerged weight "
        f"{force.submerged_weight:.2f} t + breakout force {force.force:.2f} t ({model}), "
        f"{load.weight_factor:.3f} x W, through {_xyz(plan.in_file_frame(load.point))} m",
        "held by each crane at the level attitude, the plan's preload held (the hooks moved "
        "rigidly to hold it level), T at its worst over the hook errors "
        f"(+{_widening(case)} t):",
        f"{'lug':<5}{'crane':<12}{'T breakout [t]':>15}{'+ rigging [t]':>14}{'SWL [t]':>9}"
        f"{'hook shift [m]':>15}  check",
        f"{'':<5}chain's static input",
    ]
    for c, rigging, shift, check in zip(design.cranes, case.rigging, case.hook_shift, case.checks):
        lines.append(
            f"{c.label:<5}{c.crane[:11]:<12}{c.breakout:>15.2f}{rigging:>14.2f}{c.swl:>9.1f}"
            f"{shift:>15.3f}  {'ok' if check.ok else 'FAIL'}"
        )
        lines.append(f"{'':<5}{c.static_note}")
    if case.vessels:
        lines.append(
            "crane vessels at breakout (largest |heel|, |trim| [deg], least freeboard [m]; the "
            "levelling ballast set):"
        )
        for v in case.vessels:
            freeboard = "-" if v.worst.freeboard is None else f"{v.worst.freeboard:.2f}"
            lines.append(
                f"  {v.crane}: heel {v.worst.heel:.2f}, trim {v.worst.trim:.2f}, freeboard {freeboard}"
            )
    return lines


def _widening(case):
    """What the hook errors add to each breakout tension, as ``a to b``  [t]."""
    low, high = float(case.hook_widening.min()), float(case.hook_widening.max())
    return f"{low:.2f}" if high - low < 0.005 else f"{low:.2f} to {high:.2f}"


def _ranking_lines(plan):
    problem = plan.problem
    unit = "[t]" if plan.objective == "spread" else "[%]"
    scale = 1.0 if plan.objective == "spread" else 100.0
    girder = bool(plan.girder)
    lines = [
        "",
        f"{'rank':<6}{'nominal ' + unit:>13}{'worst ' + unit:>12}{'design util. [%]':>18}"
        + (f"{'girder [%]':>13}" if girder else "")
        + "   lugs (crane)",
    ]
    for k, (r, d, g) in enumerate(zip(plan.ranking, plan.ranked_design, plan.ranked_girder)):
        names = [
            lug if problem.equal_cranes else f"{lug}({crane})" for lug, crane in zip(r.lugs, r.crane_names)
        ]
        util = "n/a" if d.chain is None else f"{100 * d.max_utilisation:.1f}" + ("" if d.ok else " FAIL")
        row = f"{k + 1:<6}{scale * r.nominal_value:>13.2f}{scale * r.worst_value:>12.2f}{util:>18}"
        if girder:
            ratio = max(w.ratio for w in g)
            row += f"{100 * ratio:>8.1f}" + (" FAIL" if ratio > 1.0 else "     ")
        lines += _names_after(row + "   ", names)
        lines.append(f"{'':<6}worst at {_where(plan, r.worst)}")
    lines.append(
        "(nominal / worst: the objective, level and largest in the box; design util.: the highest "
        "design hook load / chart SWL of the set's cranes, FAIL if any design check fails"
        + ("; girder: the hull girder's largest |M| or |Q| / allowable" if girder else "")
        + "; the sets that fail a design check"
        + (" or overload the girder" if girder else "")
        + " ranked after those that meet them)"
    )
    if plan.design_note:
        lines.append(plan.design_note)
    return lines


def girder_lines(plan, worst, over):
    """The hull girder's worst |M| and |Q| against the allowables, each with its state (none
    when the girder is not checked)."""
    if not worst:
        return []
    lines = ["", f"hull girder (body.weight_curve against [strength]), the worst {over}:"]
    for w in worst:
        what = "bending moment |M|" if w.name == "bending_moment" else "shear force |Q|   "
        unit = "t m" if w.name == "bending_moment" else "t"
        lines.append(
            f"  {what} {w.value:>9.1f} {unit:<3} at x = {w.x:.1f} m, allowable {w.allowable:.1f} {unit} "
            f"({100 * w.ratio:.0f} %) {'ok' if w.ratio <= 1.0 else 'FAIL'}, at {_where(plan, w.scenario)}"
        )
    local = getattr(getattr(plan, "stats", None), "method", None) == "local"
    if local and any(w.ratio > 1.0 for w in worst):  # docs/planning.md, the girder in the local search
        lines.append('  the local search reached no set that keeps it (search = "exact" shows if one does)')
    return lines


def _names_after(row, names):
    """``row`` followed by the names, as many a line as fit in :data:`WIDTH`; further lines
    indented to the names' column."""
    lines, line, count = [], row, 0
    for name in names:
        if count and len(line) + len(name) > WIDTH:
            lines.append(line.rstrip())
            line, count = " " * len(row), 0
        line += name + " "
        count += 1
    return lines + [line.rstrip()]


def _where(plan, scenario):
    return f"heel {scenario.heel:+.2f} deg, trim {scenario.trim:+.2f} deg, CG {_xyz(plan.cog_at(scenario))} m"


def _xyz(values):
    return "(" + ", ".join(f"{v:.2f}" for v in values) + ")"
