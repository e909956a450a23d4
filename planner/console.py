"""Plain-text tables for the terminal (no colour, fixed columns, units in every header)."""

from __future__ import annotations


def equilibrium_table(scene, eq):
    """A readable report of one solve.

    Parameters
    ----------
    scene : Scene
    eq : Equilibrium

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
        f"{'lug':<8}{'tension [t]':>13}{'share of W [%]':>16}{'SWL [t]':>10}"
        f"{'utilisation [%]':>17}",
    ]
    for name, tension in eq.tensions.items():
        swl = eq.swl[name]
        util = eq.utilisation[name]
        lines.append(
            f"{name:<8}{tension:>13.2f}{100 * eq.share[name]:>16.2f}"
            f"{(f'{swl:.1f}' if swl else '-'):>10}"
            f"{(f'{100 * util:.1f}' if util is not None else '-'):>17}"
            + ("  slack" if name in eq.slack else "")
        )
    total = sum(eq.tensions.values())
    lines.append(f"{'total':<8}{total:>13.2f}{100 * total / eq.weight:>16.2f}")
    lines.append(f"spread (max - min tension): {eq.spread:.2f} t; weight W = {eq.weight:.2f} t")
    return "\n".join(lines)
