"""Console table of a plan chosen for the hull girder
(:class:`~liftplan.planner.plans.strength.StrengthPlan`): the strength-optimal plan beside the
spread-optimal one."""

from __future__ import annotations

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
    """The plan as text: both plans' peaks and spreads, then the chosen plan's lugs."""
    p, c, o = plan.problem, plan.chosen, plan.spread_plan
    weights = objective_weights(p)
    lines = [
        f"{p.name or 'plan'}: {p.cranes} lifting points of {len(p.candidates)} candidates, "
        f"{plan.control} control",
        p.weight_text,
        f"objective: {p.objective} ({WHAT[p.objective]}"
        + (f"; w_M = {weights[0]:g}, w_Q = {weights[1]:g})" if p.objective == "strength" else ")"),
        "",
        f"{'':28s}{'strength-optimal':>20s}{'spread-optimal':>20s}",
    ]
    rows = [
        ("peak |M| [t m]", c.bending.value, o.bending.value, ".0f"),
        ("peak |M| / allowable", c.bending.ratio, o.bending.ratio, ".3f"),
        ("peak |Q| [t]", c.shear.value, o.shear.value, ".0f"),
        ("peak |Q| / allowable", c.shear.ratio, o.shear.ratio, ".3f"),
        ("level spread [t]", c.spread, o.spread, ".1f"),
        ("worst spread [t]", c.worst_spread, o.worst_spread, ".1f"),
        ("lowest tension [t]", c.tension_range[0], o.tension_range[0], ".1f"),
        ("highest tension [t]", c.tension_range[1], o.tension_range[1], ".1f"),
    ]
    for name, a, b, fmt in rows:
        lines.append(f"{name:28s}{a:>20{fmt}}{b:>20{fmt}}")
    lines.append("")
    lines.append(f"peak |M| at x = {c.bending.x:.2f} m, {_state(plan, c, c.bending)}")
    lines.append(f"peak |Q| at x = {c.shear.x:.2f} m, {_state(plan, c, c.shear)}")
    s = plan.stats
    lines.append(
        f"search: {s.method}; {s.rounds} MIP solve(s), {s.evaluated} set(s) evaluated, "
        f"{s.seconds:.1f} s; lower bound {s.lower_bound:.6g}, gap {s.gap:.3g} "
        f"({100 * s.relative_gap:.4f} %), {s.stopped}"
        + ("" if s.certified else " (not certified: candidates at different heights)")
    )
    t = plan.spread_stats
    lines.append(
        f"spread-optimal plan: {t.seconds:.1f} s, lower bound {t.lower_bound:.4g} t, gap "
        f"{t.gap:.3g} t, {t.stopped}"
    )
    lines.append("")
    heights = plan.boom_heights
    head = f"{'lug':5s}{'candidate':>12s}{'x [m]':>9s}{'tension [t]':>13s}"
    lines.append(head + (f"{'H [m]':>10s}" if heights else ""))
    for k, label in enumerate(plan.labels):
        i = c.indices[k]
        row = f"{label:5s}{c.names[k]:>12s}{p.points[i][0]:>9.2f}{c.preload[k]:>13.1f}"
        lines.append(row + (f"{heights[label]:>10.3f}" if heights else ""))
    lines.append(f"spread-optimal lugs: {' '.join(o.names)}")
    return "\n".join(lines)
