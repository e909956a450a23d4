"""Plain-text tables for the terminal (no colour, fixed columns, units in every header)."""

from __future__ import annotations

from .plan_console import plan_table

__all__ = ["batch_table", "equilibrium_table", "load_curve_table", "plan_table"]


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
    ]
    if eq.tensions:
        who = "crane" if eq.rigging is not None else "lug"
        lines.append(f"{who:<8}{'tension [t]':>13}{'share of W [%]':>16}{'SWL [t]':>10}"
                     f"{'utilisation [%]':>17}")
    for name, tension in eq.tensions.items():
        swl = eq.swl[name]
        util = eq.utilisation[name]
        lines.append(
            f"{name:<8}{tension:>13.2f}{100 * eq.share[name]:>16.2f}"
            f"{(f'{swl:.1f}' if swl else '-'):>10}"
            f"{(f'{100 * util:.1f}' if util is not None else '-'):>17}"
            + ("  slack" if name in eq.slack else "")
        )
    if eq.tensions:
        total = sum(eq.tensions.values())
        lines.append(f"{'total':<8}{total:>13.2f}{100 * total / eq.weight:>16.2f}")
        lines.append(f"spread (max - min tension): {eq.spread:.2f} t; weight W = {eq.weight:.2f} t")
    if eq.rigging is not None:
        lines += _rigging_lines(eq)
    if eq.afloat is not None:
        lines += _afloat_lines(eq)
    return "\n".join(lines)


def _rigging_lines(eq):
    """Hook loads are the crane rows above; here the legs, hooks and spreader bars."""
    r = eq.rigging
    lines = ["", f"hook loads above are the hoist-rope tensions; sling legs (angle from the horizontal, "
                 f"limit {r.min_sling_angle:g} deg):",
             f"{'leg':<16}{'to lug':<10}{'tension [t]':>13}{'angle [deg]':>13}"]
    for key, tension in r.legs.items():
        angle = r.sling_angles[key]
        lines.append(f"{key:<16}{r.leg_lugs[key] or '(bar end)':<10}{tension:>13.2f}{angle:>13.2f}"
                     + ("  slack" if key in eq.slack else "")
                     + ("  BELOW LIMIT" if not angle >= r.min_sling_angle else ""))
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
        f"state: {a.state}; weight W = {eq.weight:.1f} t",
        f"buoyancy: {a.buoyancy:.1f} t (displaced volume {a.volume:.1f} m3), "
        f"centre of buoyancy {xyz(a.centre_of_buoyancy)}",
        f"centre of gravity: {xyz(a.centre_of_gravity)} (world)",
    ]
    if a.ground_reaction is not None:
        lines.append(f"ground reaction: {a.ground_reaction:.1f} t at {xyz(a.contact)}")
    if a.freeing_force is not None:
        lines.append(f"freeing force (friction x ground reaction): {a.freeing_force:.1f} t")
    if eq.solver.iterations is not None:
        lines.append(f"{eq.solver.iterations} iterations, {1e3 * eq.solver.seconds:.1f} ms")
    return lines


def load_curve_table(scene, curve, rows=25):
    """The load curve, thinned to about ``rows`` lines, with its maximum and lift-off."""
    title = scene.name or "scene"
    names = curve.lugs
    head = f"{'hoist [m]':>10}" + "".join(f"{'T ' + n + ' [t]':>12}" for n in names) + \
        f"{'heel [deg]':>12}{'trim [deg]':>12}{'buoyancy [t]':>14}{'ground [t]':>12}  state"
    lines = [title, head]
    every = max(1, len(curve.hoist) // rows)
    for k in range(0, len(curve.hoist), every):
        lines.append(
            f"{curve.hoist[k]:>10.2f}" + "".join(f"{t:>12.1f}" for t in curve.tensions[k])
            + f"{curve.heel[k]:>12.2f}{curve.trim[k]:>12.2f}{curve.buoyancy[k]:>14.1f}"
            f"{curve.ground_reaction[k]:>12.1f}  {curve.state[k]}"
        )
    load, lug, at = curve.max_load
    lines.append(f"maximum crane load: {load:.1f} t on {lug} at hoist {at:.2f} m")
    off = curve.lift_off
    lines.append(f"lift-off (ground reaction reaches 0): hoist {off:.2f} m" if off is not None
                 else "no lift-off within the hoist range")
    for hoist, reason in curve.failed:
        lines.append(f"no equilibrium at hoist {hoist:.2f} m: {reason}")
    return "\n".join(lines)


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
        lines.append(f"ran {summary.ran} in {summary.seconds:.2f} s on {summary.cores} cores "
                     f"({summary.rate_per_core:,.0f} cases/s per core)"
                     + (f"; {resumed} were done before (resumed)" if resumed else ""))
    else:
        lines.append("every case was done before (resumed)")
    lines += ["", f"{'status':<12}{'cases':>8}"]
    lines += [f"{status:<12}{count:>8}" for status, count in sorted(summary.counts.items())]
    lines += ["", f"table: {summary.output}"]
    return "\n".join(lines)
