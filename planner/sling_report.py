"""The report of a two-crane sling lift: HTML page, scene file and figure.

The held-preload plan's report is :mod:`liftplan.planner.report`; this module writes the
sling lift's own tables (cranes, slings, legs, checks) in the planning file's frame.
"""

from __future__ import annotations

import html
import json
from datetime import date

import numpy as np

from liftplan.model.frames import zup_to_choi

FRAMES = {"z-up": "z-up (x forward, y to port, z up)",
          "choi": "the papers' frame (x forward, y up, z to starboard)"}


def _in_file(problem, point):
    return tuple(zup_to_choi(point)) if problem.frame == "choi" else tuple(float(v) for v in point)


def _xyz(problem, point):
    return ", ".join(f"{v:.2f}" for v in _in_file(problem, point))


def _table(headers, rows, caption):
    head = "".join(f"<th>{html.escape(h)}</th>" for h in headers)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
                   for row in rows)
    return f"<table><caption>{html.escape(caption)}</caption><tr>{head}</tr>{body}</table>"


def plan_view(plan):
    """Plan view in the file's frame: candidates, CG, the chosen pairs, hooks and cranes."""
    from matplotlib.figure import Figure

    problem, chosen = plan.problem, plan.chosen
    choi = problem.frame == "choi"

    def xy(points):
        points = np.atleast_2d(points)
        return np.column_stack([points[:, 0], -points[:, 1]]) if choi else points[:, :2]

    fig = Figure(figsize=(9, 5.5), layout="constrained")
    ax = fig.subplots()
    pts = xy(problem.points)
    ax.scatter(pts[:, 0], pts[:, 1], s=16, color="0.6", label="candidates")
    colors = ("tab:orange", "tab:green")
    for c, (crane, pair) in enumerate(zip(problem.fleet, chosen.pairs)):
        lugs = xy(problem.points[list(pair)])
        hook = xy(chosen.apex[c])[0]
        for lug in lugs:
            ax.plot([hook[0], lug[0]], [hook[1], lug[1]], color=colors[c], lw=1.5)
        ax.scatter(lugs[:, 0], lugs[:, 1], s=60, color=colors[c], zorder=3)
        ax.scatter([hook[0]], [hook[1]], marker="^", s=80, color=colors[c], zorder=3,
                   label=f"{crane.name}: hook {chosen.hook_nominal[c]:.1f} t, "
                         f"SWL {chosen.swl[c]:.0f} t at {chosen.radius[c]:.1f} m")
        if crane.position is not None:
            centre = xy(np.array([[*crane.position, 0.0]]))[0]
            ax.scatter([centre[0]], [centre[1]], marker="s", s=50, color=colors[c])
            ax.plot([centre[0], hook[0]], [centre[1], hook[1]], color=colors[c], ls=":", lw=1)
            ax.annotate(crane.name, centre, fontsize=8, color=colors[c], xytext=(0, 8),
                        textcoords="offset points", ha="center")
    cog = xy(np.array(problem.body.cog))[0]
    ax.scatter([cog[0]], [cog[1]], marker="x", s=80, color="tab:red", label="CG", zorder=4)
    ax.set_aspect("equal")
    if choi:
        ax.invert_yaxis()
    ax.set_xlabel("x [m] (forward)")
    ax.set_ylabel("z [m] (to starboard)" if choi else "y [m] (to port)")
    ax.grid(True, lw=0.3)
    fig.legend(fontsize=8, loc="outside lower center", ncols=2)
    ax.set_title("Plan view: lug pairs, hooks (triangles) and cranes (squares), seen from above")
    return fig


def render_html(plan):
    """The sling lift's report as one HTML page."""
    from .report import _png

    problem, chosen = plan.problem, plan.chosen
    names = [c.name for c in problem.fleet]
    cranes = _table(
        ["crane", "lugs", "hook position x, y, z [m]", "radius [m]", "chart SWL [t]",
         "boom height H [m]", "hook load, level [t]", "hook load, worst [t]", "worst / SWL [%]"],
        [(name, " + ".join(problem.names[i] for i in chosen.pairs[c]),
          _xyz(problem, chosen.apex[c]), f"{chosen.radius[c]:.1f}", f"{chosen.swl[c]:.1f}",
          f"{plan.crane_boom_heights[c]:.3f}", f"{chosen.hook_nominal[c]:.2f}",
          f"{chosen.hook_worst[c]:.2f}", f"{100 * chosen.hook_worst[c] / chosen.swl[c]:.1f}")
         for c, name in enumerate(names)],
        "Recommended lug pairs, cranes and boom heights",
    )
    legs = _table(
        ["lug", "candidate", "position x, y, z [m]", "crane", "sling angle [deg]",
         "leg tension, level [t]", "leg tension, worst [t]"],
        [(label, plan.lugs[label], _xyz(problem, problem.points[problem.names.index(plan.lugs[label])]),
          plan.cranes[label], f"{a:.1f}", f"{t0:.2f}", f"{tw:.2f}")
         for label, a, t0, tw in zip(plan.labels, np.ravel(chosen.sling_angles),
                                     np.ravel(chosen.legs_nominal), np.ravel(chosen.legs_worst))],
        "Sling legs",
    )
    checks = _table(
        ["check", "subject", "value", "limit", "unit", "result"],
        [(c.name, c.subject, f"{c.value:.4g}", f"{c.limit:.4g}", c.unit, "ok" if c.ok else "FAIL")
         for c in plan.checks],
        "Checks",
    )
    dx, dy, dz = _in_file(problem, chosen.worst_cog_offset)
    inputs = _table(
        ["quantity", "value", "unit"],
        [("weight W", f"{problem.body.weight:.2f}", "t"),
         ("CG", _xyz(problem, problem.body.cog), "m"),
         ("tilt tolerance along the hook line", f"+-{plan.tolerances[0]:g}", "deg"),
         ("roll allowed about the hook line", f"{plan.tolerances[1]:g}", "deg"),
         ("lowest sling angle allowed", f"{problem.min_sling_angle:g}", "deg"),
         ("roll about the hook line (CG under it)", f"{chosen.roll:.2f}", "deg"),
         ("worst case: tilt along the hook line", f"{chosen.worst_tilt:+.2f}", "deg"),
         ("worst case: CG offset", f"{dx:+.2f}, {dy:+.2f}, {dz:+.2f}", "m"),
         ("pairs of lug pairs considered", plan.options, "-")]
        + [(f"ruled out: {text}", n, "options") for text, n in plan.ruled_out.items()],
        f"Inputs and search (coordinates in {FRAMES[problem.frame]})",
    )
    body = "\n".join([
        f"<h1>{html.escape(problem.name or 'Lift plan')}</h1>",
        f"<p>liftplan recommendation, {date.today().isoformat()}: a two-crane lift on 2-leg "
        f"slings. Coordinates in {html.escape(FRAMES[problem.frame])}. Hook loads by the "
        "lever rule along the hook line (the hooks above the pairs' midpoints), checked on the "
        "rigging model with free hooks and elastic legs.</p>",
        cranes, legs, checks, _png(plan_view(plan), "plan view"), inputs,
    ])
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>{html.escape(problem.name or 'Lift plan')}</title>
<style>
body {{ font-family: sans-serif; max-width: 1000px; margin: 2em auto; color: #222; }}
table {{ border-collapse: collapse; margin: 1em 0; font-size: 0.9em; }}
caption {{ text-align: left; font-weight: bold; padding: 0.3em 0; }}
th, td {{ border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; }}
th {{ background: #eee; }}
img {{ max-width: 100%; display: block; margin: 1em 0; }}
</style></head>
<body>
{body}
</body></html>
"""


def scene_toml(plan):
    """The sling plan as a rigging scene file (``liftplan solve`` reads it), file frame."""
    scene, problem = plan.scene, plan.problem

    def vec(values):
        return "[" + ", ".join(repr(float(v)) for v in values) + "]"

    lines = [
        f"# Written by liftplan plan: the chosen slings of {json.dumps(problem.name)}.",
        "# `liftplan solve` on this file solves the rigging model (free hooks, elastic legs).",
        f"# Coordinates in the planning file's frame: {FRAMES[problem.frame]}.",
        f"name = {json.dumps(scene.name)}",
        f"frame = {json.dumps(problem.frame)}",
        "", "[body]", f"weight = {scene.body.weight!r}",
        f"cog = {vec(_in_file(problem, scene.body.cog))}",
    ]
    for lug in scene.lugs:
        lines += ["", "[[lugs]]", f"name = {json.dumps(lug.name)}",
                  f"at = {vec(_in_file(problem, lug.at))}"]
    for crane in scene.cranes:
        legs = ", ".join(f"{{ lug = {json.dumps(leg.lug)}, length = {leg.length!r}, EA = {leg.EA!r} }}"
                         for leg in crane.sling.legs)
        lines += ["", "[[cranes]]", f"name = {json.dumps(crane.name)}",
                  f"boom_height = {crane.boom_height!r}", f"rope_length = {crane.rope_length!r}",
                  f"EA = {crane.EA!r}", f"swl = {crane.swl!r}",
                  f"tip = {vec(_in_file(problem, crane.tip))}",
                  f"sling = {{ legs = [ {legs} ] }}"]
    att = scene.attitude
    lines += ["", "[attitude]", f"lift_height = {att.lift_height!r}", f"yaw = {att.yaw!r}",
              "", "[rigging]", f"min_sling_angle = {problem.min_sling_angle!r}", ""]
    return "\n".join(lines)
