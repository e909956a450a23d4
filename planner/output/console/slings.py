"""Console summary of a sling lift plan (``liftplan plan`` without ``--json``).

Two cranes (:class:`~liftplan.planner.plans.slings.SlingPlan`) or three and more, on body-fixed apexes
or hooks hinged about their pairs (:class:`~liftplan.planner.plans.slings.apex.ApexSlingPlan`): per
crane its lugs, radius, chart SWL, hook loads and the rules' design hook load; per lug its leg's
sling angle and tension, and the lug's design load from the rules' chain; with a weight curve
and ``[strength]`` the hull girder's worst |M| and |Q| and the state where the body hung.
"""

from __future__ import annotations

import numpy as np

from liftplan.planner.output.console.held import coordinates_line, girder_lines
from liftplan.planner.output.console.limits import length_lines, limit_lines
from liftplan.planner.output.console.text import fold, grouped
from liftplan.planner.plans.slings.two_crane import SHARED

OBJECTIVES = {
    "reserve": "the largest hook load / SWL",
    "utilisation": "max - min of hook load / SWL",
    "spread": "max - min hook load",
}


def _search_lines(plan):
    problem = plan.problem
    causes = ", ".join(f"{n} {text}" for text, n in plan.ruled_out.items()) or "none"
    if hasattr(plan, "inner"):  # three or more cranes: the held search on the apexes
        stats = plan.stats
        sling = problem.fleet[0].sling
        rig = "spreader bars" if sling.spreader is not None else f"{sling.legs}-leg slings"
        return [
            f"{problem.cranes} cranes on {rig}: {len(plan.rigs)} {plan.lift_points_text} "
            f"among {len(problem.candidates)} candidates; {stats.rows} (set, crane "
            f"assignment) rows, {stats.evaluated} evaluated, search {stats.stopped}, lower bound "
            f"{stats.lower_bound:.4g}; ruled out: {causes}",
            *limit_lines(stats, problem, plan.lengths),
            f"tolerance box heel +-{problem.heel_tolerance:g} deg, trim +-{problem.trim_tolerance:g} "
            f"deg, CG envelope; hooks held at the level preload; objective: "
            + OBJECTIVES.get(plan.objective, plan.objective),
            plan.hook_tilt_text,
        ]
    shared = plan.ruled_out.get(SHARED, 0)
    rigs = ", ".join(f"{n} {text}" for text, n in plan.ruled_out.items() if text in plan.rig_causes)
    out = {t: n for t, n in plan.ruled_out.items() if t not in plan.rig_causes and t != SHARED}
    pairs = ", ".join(f"{n} {text}" for text, n in out.items())
    return [
        f"two cranes on slings: rigs of one crane ruled out: {rigs or 'none'}; the others paired "
        f"(both assignments), {shared} pairs sharing a lug dropped, {plan.options} considered: "
        f"ruled out {pairs or 'none'}; {plan.options - sum(out.values())} feasible; {plan.time_text}",
        f"tilt along the hook line within +-{plan.tolerances[0]:g} deg and the hook errors' tilt, "
        "CG envelope; objective: " + OBJECTIVES.get(plan.objective, plan.objective),
        plan.hook_tilt_text,
    ]


def sling_table(plan):
    """A readable summary of a sling plan.

    Returns
    -------
    str
    """
    problem = plan.problem
    names = plan.crane_names
    design = plan.design_hook_loads
    lines = [
        problem.name or "lift plan",
        coordinates_line(plan),
        problem.weight_text,
        *_search_lines(plan),
        "",
        f"{'crane':<13}{'lugs (below)':<17}{'R [m]':>7}{'SWL [t]':>8}{'H [m]':>8}"
        f"{'hook [t]':>9}{'worst [t]':>10}{'design [t]':>11}{'util. [%]':>10}  check",
    ]
    chain = None if isinstance(plan.design, str) else plan.design
    rows = []
    for c, name in enumerate(names):
        lugs = ",".join(label for label in plan.labels if plan.cranes[label] == name)
        ok = chain is not None and chain.results[c].check.ok
        rows.append(
            f"{name[:12]:<13}{lugs[:16]:<17}{plan.hook_radius[c]:>7.1f}{plan.hook_swl[c]:>8.1f}"
            f"{plan.crane_boom_heights[c]:>8.3f}{plan.hook_nominal[c]:>9.2f}"
            f"{plan.hook_worst[c]:>10.2f}{design[c]:>11.2f}{100 * design[c] / plan.hook_swl[c]:>10.1f}"
            f"  {'ok' if ok else 'FAIL'}"
        )
    lines += grouped(rows)
    lines.append(
        "(hook = level, nominal CG; worst = largest over the tolerance and the CG envelope; "
        "design = the rules' chain, docs/design-loads.md; util. = design / chart SWL)"
    )
    lines.append(f"location: {plan.problem.rules.location_text} (the DAF column of Table 5-1)")
    lines += _length_lines(plan)
    lines += _breakout_lines(plan)
    if chain is None:
        lines.append(f"design loads not computed: {plan.design}")
    lug_design = {} if chain is None else {lug.lug: lug for r in chain.results for lug in r.lugs}
    lines += [
        "",
        f"{'lug':<5}{'candidate':<12}{'crane':<14}{'angle [deg]':>12}{'leg, level [t]':>15}"
        f"{'leg, worst [t]':>15}{'lug design [t]':>15}",
    ]
    angles, level, worst = (
        np.concatenate([np.ravel(a) for a in v])
        for v in (plan.leg_angles, plan.legs_nominal, plan.legs_worst)
    )
    rows = []
    for k, label in enumerate(plan.labels):
        lug = plan.lugs[label]
        value = lug_design[lug].design_load if lug in lug_design else float("nan")
        rows.append(
            f"{label:<5}{lug[:11]:<12}{plan.cranes[label][:13]:<14}{angles[k]:>12.1f}"
            f"{level[k]:>15.2f}{worst[k]:>15.2f}{value:>15.2f}"
        )
    lines += grouped(rows)
    for c, top in enumerate(plan.top_legs):
        if top is not None:
            lines.append(
                f"{names[c]}: spreader bar {plan.bar_weights[c]:g} t on the hook; top legs "
                + ", ".join(f"{t:.2f} t at {a:.1f} deg" for t, a in zip(top, plan.top_angles[c]))
            )
    solved = plan.verified
    lines += [
        "",
        "rigging model (free hooks, elastic legs) at level: hook loads "
        + ", ".join(f"{n} {solved.tensions[n]:.2f} t" for n in names),
    ]
    if hasattr(plan, "chosen"):
        chosen = plan.chosen
        dx, dy, dz = plan.in_file_frame(chosen.worst_cog_offset)  # the file's frame
        lines += [
            f"roll about the hook line (CG under it): up to {chosen.roll:.2f} deg over the CG envelope",
            f"worst at a tilt of {chosen.worst_tilt:+.2f} deg along the hook line with CG offset "
            f"({dx:+.2f}, {dy:+.2f}, {dz:+.2f}) m",
        ]
    over = plan.girder_over
    if plan.breakout is not None:  # docs/planning.md "What the planner does not plan"
        over += " (not the breakout state: the seabed's hold is not in the planner's girder)"
    lines += girder_lines(plan, plan.girder, over)
    unit, scale = ("[t]", 1.0) if plan.objective == "spread" else ("[%]", 100.0)
    lines += ["", f"{'rank':<6}{'worst ' + unit:>12}  slings (crane)"]
    for k, slings, value in _ranking(plan):
        lines.append(f"{k:<6}{scale * value:>12.2f}  {slings[0]}")
        lines += [f"{'':<20}{text}" for text in slings[1:]]
    return "\n".join(folded for line in lines for folded in fold(line))


def _length_lines(plan):
    """The hoist rope lengths the planner chose (cranes with a ``rope_length`` range)."""
    if plan.lengths is None:
        return []
    return length_lines(plan.lengths, "hoist rope length", " (tip to hook)")


def _breakout_lines(plan):
    """The breakout case on the hooks: the peak load, each crane's share, what governs."""
    case = plan.breakout
    if case is None:
        return []
    load, force = case.load, case.load.breakout
    x, y, z = plan.in_file_frame(load.point)
    how = (
        "by the lever rule along the hook line, the hook errors tilting it"
        if hasattr(plan, "chosen")
        else "held at the level attitude with the plan's preload held (the hooks moved rigidly)"
    )
    lines = [
        "",
        f"breakout from the seabed ({plan.problem.breakout_scene.name or 'breakout scene'}):",
        f"  peak total hook load {load.total:.2f} t = submerged weight {force.submerged_weight:.2f} t "
        f"+ breakout force {force.force:.2f} t ({force.describe()}), {load.weight_factor:.3f} x W, "
        f"through ({x:.3f}, {y:.3f}, {z:.3f}) m",
        f"each hook's share {how}, at its worst over the hook errors:",
        f"{'crane':<13}{'T breakout [t]':>15}{'hook errors [t]':>16}{'+ rigging [t]':>14}"
        f"{'SWL [t]':>9}{'box worst [t]':>14}  governs  check",
    ]
    for c, name in enumerate(case.cranes):
        box = float(plan.box_shares[c])
        governs = "breakout" if case.worst[c] > box else "box"
        lines.append(
            f"{name[:12]:<13}{case.worst[c]:>15.2f}{case.hook_widening[c]:>16.2f}"
            f"{case.rigging[c]:>14.2f}{case.swl[c]:>9.1f}{box:>14.2f}  {governs:<8} "
            f"{'ok' if case.checks[c].ok else 'FAIL'}"
        )
    lines.append(
        "(the larger of breakout and box worst is the crane's static input to the design chain; "
        "its legs at breakout enter the lug design loads; the check: T + rigging <= chart SWL)"
    )
    return lines


def _ranking(plan):
    """(rank, one text per sling, worst value) of each ranked option."""
    problem, names = plan.problem, plan.crane_names
    if hasattr(plan, "inner"):
        for k, r in enumerate(plan.ranking):
            texts = [
                f"{'+'.join(problem.names[i] for i in plan.rigs.lugs[j])} ({crane})"
                for j, crane in zip(r.indices, r.crane_names)
            ]
            yield k + 1, texts, r.worst_value
        return
    for k, option in enumerate(plan.ranking):
        texts = [
            f"{'+'.join(problem.names[i] for i in group)} ({name})"
            for group, name in zip(option.pairs, names)
        ]
        yield k + 1, texts, option.worst_value
