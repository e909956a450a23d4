"""Console summary of a two-crane sling lift plan (``liftplan plan`` without ``--json``)."""

from __future__ import annotations

import numpy as np


def sling_table(plan):
    """A readable summary of a :class:`~liftplan.planner.slings.SlingPlan`.

    Returns
    -------
    str
    """
    problem, chosen = plan.problem, plan.chosen
    names = [c.name for c in problem.fleet]
    lines = [
        problem.name or "lift plan",
        f"two cranes on 2-leg slings: {plan.options} pairs of lug pairs considered "
        f"(both assignments); ruled out: "
        + (", ".join(f"{n} {text}" for text, n in plan.ruled_out.items()) or "none"),
        "tilt along the hook line within the tolerance, CG envelope; objective: "
        + ("the larger hook load / SWL" if plan.objective == "reserve" else
           "max - min of hook load / SWL" if plan.objective == "utilisation"
           else "max - min hook load"),
        "",
        f"{'crane':<16}{'lugs':<22}{'radius [m]':>11}{'SWL [t]':>9}{'H [m]':>9}"
        f"{'hook [t]':>10}{'worst [t]':>11}{'util. [%]':>11}",
    ]
    for c, name in enumerate(names):
        lugs = " + ".join(problem.names[i] for i in chosen.pairs[c])
        lines.append(
            f"{name[:15]:<16}{lugs[:21]:<22}{chosen.radius[c]:>11.1f}{chosen.swl[c]:>9.1f}"
            f"{plan.crane_boom_heights[c]:>9.3f}{chosen.hook_nominal[c]:>10.2f}"
            f"{chosen.hook_worst[c]:>11.2f}{100 * chosen.hook_worst[c] / chosen.swl[c]:>11.1f}"
        )
    lines.append("(worst = largest hook load over the tilt tolerance and the CG envelope; "
                 "util. = worst / SWL)")
    lines += ["", f"{'lug':<6}{'candidate':<14}{'crane':<16}{'sling angle [deg]':>18}"
                  f"{'leg, level [t]':>16}{'leg, worst [t]':>16}"]
    angles, level, worst = (np.ravel(v) for v in (chosen.sling_angles, chosen.legs_nominal,
                                                   chosen.legs_worst))
    for k, label in enumerate(plan.labels):
        lines.append(f"{label:<6}{plan.lugs[label]:<14}{plan.cranes[label][:15]:<16}"
                     f"{angles[k]:>18.1f}{level[k]:>16.2f}{worst[k]:>16.2f}")
    dx, dy, dz = chosen.worst_cog_offset
    solved = plan.verified
    lines += [
        "",
        f"roll about the hook line (CG under it): up to {chosen.roll:.2f} deg over the CG envelope",
        f"worst at a tilt of {chosen.worst_tilt:+.2f} deg along the hook line with CG offset "
        f"({dx:+.2f}, {dy:+.2f}, {dz:+.2f}) m",
        "rigging model (free hooks, elastic legs) at level: hook loads "
        + ", ".join(f"{n} {solved.tensions[n]:.2f} t" for n in names),
    ]
    unit = "[t]" if plan.objective == "spread" else "[%]"
    scale = 1.0 if plan.objective == "spread" else 100.0
    lines += ["", f"{'rank':<6}{'lug pairs (crane)':<64}{'worst ' + unit:>12}"]
    for k, option in enumerate(plan.ranking):
        text = "  ".join(f"{'+'.join(problem.names[i] for i in pair)} ({name})"
                         for pair, name in zip(option.pairs, names))
        lines.append(f"{k + 1:<6}{text[:63]:<64}{scale * option.worst_value:>12.2f}")
    return "\n".join(lines)
