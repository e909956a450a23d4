"""Console table of a plan chosen for the hull girder
(:class:`~liftplan.planner.plans.strength.StrengthPlan`): the strength-optimal plan beside the
spread-optimal one."""

from __future__ import annotations

from liftplan.planner.output.console.limits import limit_lines
from liftplan.planner.output.console.slings import sling_table
from liftplan.planner.plans.strength import objective_weights

WHAT = {
    "bending": "the worst |M| / allowable",
    "shear": "the worst |Q| / allowable",
    "strength": "w_M |M| / M_allow + w_Q |Q| / Q_allow (worst of each)",
}


def _state(plan, s, peak):
    state = s.states[peak.state]
    offset = plan.in_file_frame(state["cog_offset"])
    return (
        f"heel {state['heel']:+.2f} trim {state['trim']:+.2f} deg, CG offset "
        f"({offset[0]:+.2f}, {offset[1]:+.2f}, {offset[2]:+.2f}) m"
    )


def strength_table(plan):
    """The plan as text: both plans' peaks and spreads, then the chosen plan's lugs (with
    slings: the sling plan's table, then the strength search's)."""
    if hasattr(plan, "search"):  # cranes on slings: planner/plans/strength_slings.py
        return sling_strength_table(plan)
    p, c, o = plan.problem, plan.chosen, plan.spread_plan
    lines = [
        f"{p.name or 'plan'}: {p.cranes} lifting points of {len(p.candidates)} candidates, "
        f"{plan.control} control",
        p.weight_text,
        *_comparison(plan, plan),
    ]
    heights = plan.boom_heights
    fleet = not p.equal_cranes  # which crane takes each lug
    design = plan.design_loads  # the rules' design hook load per crane over its chart SWL
    head = f"{'lug':5s}{'candidate':>12s}{'x [m]':>9s}{'tension [t]':>13s}"
    head += f"{'H [m]':>10s}" if heights else ""
    lines.append(head + f"{'design/SWL':>12s}" + ("  crane" if fleet else ""))
    for k, label in enumerate(plan.labels):
        i = c.indices[k]
        row = f"{label:5s}{c.names[k]:>12s}{p.points[i][0]:>9.2f}{c.preload[k]:>13.1f}"
        row += f"{heights[label]:>10.3f}" if heights else ""
        row += f"{design.cranes[k].utilisation:>12.3f}"
        lines.append(row + (f"  {c.crane_names[k]}" if fleet else ""))
    lines.append(f"spread-optimal lugs: {'-' if o is None else ' '.join(o.names)}")
    return "\n".join(lines)


def sling_strength_table(plan):
    """A strength plan on slings: the sling plan's table (cranes, hooks, legs, the rules' chain,
    the girder on the rigging model), then the strength search's peaks beside the
    spread-optimal hooks'."""
    search = plan.search
    lines = [
        sling_table(plan),
        "",
        f"strength search on the sling hooks ({len(plan.rigs)} hooks, each hook's girder loads its "
        "legs' at their lugs, the legs' axial pull as its moment about the CG height):",
        *_comparison(plan, search, tension="hook load"),
        f"strength-optimal hooks: {' '.join(search.chosen.names)}",
        f"spread-optimal hooks: {'-' if search.spread_plan is None else ' '.join(search.spread_plan.names)}",
    ]
    return "\n".join(lines)


def _comparison(plan, search, tension="tension"):
    """The objective, both plans' peaks and spreads, where the peaks are, how the search went."""
    p, c, o = search.problem, search.chosen, search.spread_plan
    weights = objective_weights(p)
    lines = [
        f"objective: {p.objective} ({WHAT[p.objective]}"
        + (f"; w_M = {weights[0]:g}, w_Q = {weights[1]:g})" if p.objective == "strength" else ")"),
        "",
        f"{'':28s}{'strength-optimal':>20s}{'spread-optimal':>20s}",
    ]

    def values(s):  # a plan Ctrl-C stopped may have no spread-optimal partner
        if s is None:
            return (None,) * 8
        return (
            s.bending.ratio,
            s.bending.value,
            s.shear.ratio,
            s.shear.value,
            s.spread,
            s.worst_spread,
            s.tension_range[0],
            s.tension_range[1],
        )

    names = (
        ("peak |M| / allowable", ".3f"),
        ("|M| there [t m]", ".0f"),
        ("peak |Q| / allowable", ".3f"),
        ("|Q| there [t]", ".0f"),
        ("level spread [t]", ".1f"),
        ("worst spread [t]", ".1f"),
        (f"lowest {tension} [t]", ".1f"),
        (f"highest {tension} [t]", ".1f"),
    )
    for (name, fmt), a, b in zip(names, values(c), values(o)):
        other = "-" if b is None else format(b, fmt)
        lines.append(f"{name:28s}{a:>20{fmt}}{other:>20s}")
    lines.append("")
    lines.append(f"peak |M| / allowable at x = {c.bending.x:.2f} m, {_state(plan, c, c.bending)}")
    lines.append(f"peak |Q| / allowable at x = {c.shear.x:.2f} m, {_state(plan, c, c.shear)}")
    lines.append(
        "(|M|, |Q| there: at the section where the ratio peaks, not necessarily where |M| or |Q| is largest)"
    )
    s = search.stats
    lines.append(
        f"search: {s.method}; {s.rounds} MIP solve(s), {s.evaluated} set(s) evaluated, "
        f"{s.seconds:.1f} s; lower bound {s.lower_bound:.6g}, gap {s.gap:.3g} "
        f"({100 * s.relative_gap:.4f} %), {s.stopped}"
        + ("" if s.certified else " (not certified: candidates at different heights)")
    )
    lines += limit_lines(s, p)
    t = search.spread_stats
    if t is None:
        lines.append("spread-optimal plan: none (Ctrl-C came before its search found one)")
    else:
        lines.append(
            f"spread-optimal plan: {t.seconds:.1f} s, lower bound {t.lower_bound:.4g} t, gap "
            f"{t.gap:.3g} t, {t.stopped}"
        )
    lines.append("")
    return lines
