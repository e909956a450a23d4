"""The plan's console summary (``liftplan plan`` without ``--json``)."""

from __future__ import annotations


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
    worst = chosen.worst
    stats = plan.stats
    fleet = "" if problem.equal_cranes else \
        f" x crane assignments in reach: {stats.rows} pairs ({stats.out_of_reach} out of reach)"
    swl = sorted(set(plan.swl.values()))
    swl_text = f"{swl[0]:g} t" if len(swl) == 1 else "each crane's chart SWL at its radius"
    lines = [
        problem.name or "lift plan",
        f"{stats.sets} lug sets of {problem.cranes} among {len(problem.candidates)} candidates"
        f"{fleet}: {stats.screened_out} ruled out by screening, {stats.evaluated} evaluated, "
        f"{stats.pruned} pruned by the bound ({stats.seconds:.2f} s)",
        f"tolerance box: heel +-{problem.heel_tolerance:g} deg, trim +-{problem.trim_tolerance:g}"
        f" deg; tensions {problem.min_tension:g} t to {swl_text}",
        "objective: " + ("max - min of T / SWL (utilisation spread)" if plan.objective ==
                         "utilisation" else "max - min tension (spread)"),
        "",
        f"{'lug':<5}{'candidate':<12}{'crane':<14}{'radius [m]':>11}{'SWL [t]':>9}"
        f"{'H [m]':>9}{'level T [t]':>12}{'worst [t]':>11}{'design [t]':>12}{'util. [%]':>11}",
    ]
    for cap in plan.capacity:
        label = cap.label
        lines.append(
            f"{label:<5}{plan.lugs[label]:<12}{cap.crane[:13]:<14}{cap.radius:>11.1f}{cap.swl:>9.1f}"
            f"{plan.boom_heights[label]:>9.3f}{plan.tensions[label]:>12.2f}{cap.worst:>11.2f}"
            f"{cap.design:>12.2f}{100 * cap.utilisation:>11.1f}"
        )
    lines.append("(design = worst in the box and CG envelope + hook-tolerance twist; "
                 "util. = design / SWL)")
    if not chosen.converged:
        lines.append(f"WARNING: the worst-case search still exceeded the LP bound by "
                     f"{chosen.worst_value - chosen.bound:.4g} after {chosen.rounds} rounds; "
                     "the worst shown is the largest found")
    offset = _file_vector(problem, worst.cog_offset)
    where = (f"heel {worst.heel:+.2f} deg, trim {worst.trim:+.2f} deg, CG offset "
             f"({offset[0]:+.2f}, {offset[1]:+.2f}, {offset[2]:+.2f}) m")
    if plan.objective == "utilisation":
        summary = (f"utilisation spread: nominal {100 * chosen.nominal_utilisation_spread:.1f} %, "
                   f"worst {100 * chosen.worst_value:.1f} % at {where}; tension spread: nominal "
                   f"{plan.spread:.2f} t, worst {plan.worst_spread:.2f} t")
    else:
        summary = (f"spread: nominal {plan.spread:.2f} t, worst {plan.worst_spread:.2f} t at "
                   f"{where} (convex bound {chosen.bound:.2f} t)")
    lines += [
        "",
        summary,
        "skew load factors (hook tolerance +-" f"{problem.hook_tolerance:g} m): "
        + ", ".join(f"{'+'.join(s.lugs)} {s.factor:.3f}" for s in plan.skew)
        + f" (Noble Denton default {plan.default_skew_factor:.2f})",
    ]
    unit = "[%]" if plan.objective == "utilisation" else "[t]"
    lines += ["", f"{'rank':<6}{'lugs (crane)':<64}{'nominal ' + unit:>14}{'worst ' + unit:>12}"]
    for k, r in enumerate(plan.ranking):
        scale = 100.0 if plan.objective == "utilisation" else 1.0
        names = " ".join(lug if problem.equal_cranes else f"{lug}({crane})"
                         for lug, crane in zip(r.lugs, r.crane_names))
        lines.append(f"{k + 1:<6}{names:<64}{scale * r.nominal_value:>14.2f}"
                     f"{scale * r.worst_value:>12.2f}")
    return "\n".join(lines)


def _file_vector(problem, vector):
    """A z-up vector in the frame of the problem's file."""
    from liftplan.model.frames import zup_to_choi

    return tuple(zup_to_choi(vector)) if problem.frame == "choi" else tuple(vector)
