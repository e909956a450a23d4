"""Console lines of a plan with the flexible hull or a start in water: which model governed."""

from __future__ import annotations


def hull_water_lines(plan):
    """Which hull governs the plan (and by how much flexibility changes its tensions), the
    start in water (net load, each rope's tension there), and whether the re-ranking is
    certified; empty without ``[hull] EI`` or ``[water]``."""
    search = plan.hull_search
    if search is None:
        return []
    lines = []
    if plan.hull_models:
        model = plan.hull_models[0]
        lines.append(f"hull: {model.reason(plan.labels)}")
        lines.append(
            f"  objective on the rigid hull {model.rigid_value:.4g}, on the flexible hull at the "
            f"plan's {len(model.states)} worst states {model.flexible_value:.4g}; the sets ranked on "
            "the governing hull: " + ", ".join(m.used for m in plan.hull_models)
        )
    case = plan.design_loads.in_water
    if case is not None:
        load = case.loads[0]
        tensions = ", ".join(f"{label} {t:.2f}" for label, t in zip(plan.labels, case.tensions[0]))
        lines.append(
            f"start in water (lift height {plan.problem.in_water.start_lift_height:g} m): W + trapped "
            f"- B = {load.net_weight:.2f} t (buoyancy {load.buoyancy:.2f} t); held tensions {tensions} t; "
            f"objective there {case.value:.4g}"
        )
        governs = [c.label for c in plan.design_loads.cranes if c.governs == "in_water"]
        if governs:
            lines.append(f"  the tension in water governs the design load of {', '.join(governs)}")
    ranked = "; ".join(
        f"{k + 1}. {' '.join(r.lugs)} {v:.4g}" for k, (r, v) in enumerate(zip(plan.ranking, search.values))
    )
    lines.append(
        f"ranked on the governing value (the ranking table below shows the rigid hull's in air): {ranked}"
    )
    lines.append(f"re-ranking on the governing model: {search.note}")
    return lines
