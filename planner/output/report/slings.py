"""The report of a two-crane sling lift: HTML page, scene file and figure.

The held-preload plan's report is :mod:`liftplan.planner.output.report.held`; this module writes the
sling lift's own tables (cranes, slings, legs, checks) in the planning file's frame.
"""

from __future__ import annotations

import html
import json

import numpy as np

from liftplan.model.frames import FRAME_TEXT, zup_to_choi
from liftplan.model.scene.writer import scene_toml
from liftplan.planner.output.console.slings import _ranking
from liftplan.planner.output.figures.plan import _FONT, _SMALL, _cog_envelope, _style, plan_figure
from liftplan.planner.output.report import page as report_page
from liftplan.planner.output.report.lengths import lengths_section
from liftplan.planner.output.report.view import view_section
from liftplan.planner.plans.slings.lift import hook_tolerances
from liftplan.planner.plans.slings.two_crane import SHARED


def _in_file(problem, point):
    return tuple(zup_to_choi(point)) if problem.frame == "choi" else tuple(float(v) for v in point)


def _xyz(problem, point):
    return ", ".join(f"{v:.2f}" for v in _in_file(problem, point))


def _table(headers, rows, caption, **options):
    return report_page.table(headers, rows, caption, **options)


def _png(fig, alt, caption=""):
    return report_page.figure(fig, alt, caption)


def plan_view(plan):
    """Plan view in the file's frame: candidates, CG and its envelope, the chosen pairs,
    hooks and cranes, drawn at the report's print width."""

    problem = plan.problem
    choi = problem.frame == "choi"

    def xy(points):
        points = np.atleast_2d(points)
        return np.column_stack([points[:, 0], -points[:, 1]]) if choi else points[:, :2]

    pts = xy(problem.points)
    seen = [pts] + [xy(np.array([[*c.position, 0.0]])) for c in problem.fleet if c.position is not None]
    seen = np.vstack(seen)
    low, high = seen.min(axis=0), seen.max(axis=0)
    pad = 0.08 * max(high - low) + 1.0
    low, high = low - pad, high + pad
    fig = plan_figure(low, high)
    ax = fig.subplots()
    ax.scatter(pts[:, 0], pts[:, 1], s=10, color="0.6", label="candidates")
    colors = (
        "tab:orange",
        "tab:green",
        "tab:purple",
        "tab:brown",
        "tab:pink",
        "tab:olive",
        "tab:cyan",
        "tab:blue",
    )
    for c, (crane, group) in enumerate(zip(problem.fleet, plan.groups)):
        lugs = xy(problem.points[list(group)])
        hook = xy(plan.hooks[c])[0]
        colors_c = colors[c % len(colors)]
        for lug in lugs:
            ax.plot([hook[0], lug[0]], [hook[1], lug[1]], color=colors_c, lw=1.3)
        ax.scatter(lugs[:, 0], lugs[:, 1], s=40, color=colors_c, zorder=3)
        ax.scatter(
            [hook[0]],
            [hook[1]],
            marker="^",
            s=55,
            color=colors_c,
            zorder=3,
            label=f"{crane.name}: hook {plan.hook_nominal[c]:.1f} t, "
            f"SWL {plan.hook_swl[c]:.1f} t at {plan.hook_radius[c]:.1f} m",
        )
        if crane.position is not None:
            centre = xy(np.array([[*crane.position, 0.0]]))[0]
            ax.scatter([centre[0]], [centre[1]], marker="s", s=40, color=colors_c)
            ax.plot([centre[0], hook[0]], [centre[1], hook[1]], color=colors_c, ls=":", lw=1)
            ax.annotate(
                crane.name,
                centre,
                fontsize=_SMALL,
                color=colors_c,
                xytext=(0, 6),
                textcoords="offset points",
                ha="center",
            )
    for label, name in plan.lugs.items():
        x, y = xy(problem.points[problem.names.index(name)])[0]
        ax.annotate(
            label,
            (x, y),
            fontsize=_FONT,
            fontweight="bold",
            color="0.2",
            ha="left",
            va="bottom",
            xytext=(3, 3),
            textcoords="offset points",
        )
    cog = xy(np.array(problem.body.cog))[0]
    _cog_envelope(ax, problem, cog, high - low)
    ax.scatter([cog[0]], [cog[1]], marker="+", s=50, lw=1.2, color="tab:red", label="CG (nominal)", zorder=4)
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])
    ax.set_aspect("equal")
    if choi:
        ax.invert_yaxis()
    ax.set_xlabel("x [m] (forward)")
    ax.set_ylabel("z [m] (to starboard)" if choi else "y [m] (to port)")
    ax.set_title("Plan view, seen from above: hooks (triangles), cranes (squares)")
    _style(ax)
    fig.legend(fontsize=_SMALL, loc="outside lower center", ncols=2, frameon=False)
    return fig


def render_html(plan, today=None):
    """The sling lift's report as one HTML page, laid out for A4 print.

    Parameters
    ----------
    plan : SlingPlan or ApexSlingPlan
    today : datetime.date, optional
        The date printed when ``[report] date`` is not given (default: today).
    """

    problem = plan.problem
    names = plan.crane_names
    name = problem.name or "Lift plan"
    design = plan.design_hook_loads
    chain = None if isinstance(plan.design, str) else plan.design
    legs_of = {n: ", ".join(label for label in plan.labels if plan.cranes[label] == n) for n in names}
    cranes = _table(
        [
            "crane",
            "lugs",
            "hook position x, y, z, body frame at level [m]",
            "radius [m]",
            "chart SWL [t]",
            "boom height H, world [m]",
            "hook load, level [t]",
            "hook load, worst [t]",
            "design hook load [t]",
            "design / SWL [%]",
        ],
        [
            (
                crane,
                legs_of[crane],
                _xyz(problem, plan.hooks[c]),
                f"{plan.hook_radius[c]:.1f}",
                f"{plan.hook_swl[c]:.1f}",
                f"{plan.crane_boom_heights[c]:.3f}",
                f"{plan.hook_nominal[c]:.2f}",
                f"{plan.hook_worst[c]:.2f}",
                f"{design[c]:.2f}",
                f"{100 * design[c] / plan.hook_swl[c]:.1f}",
            )
            for c, crane in enumerate(names)
        ],
        "Recommended slings, cranes and boom heights",
        text_columns=(1,),
    )
    lug_design = {} if chain is None else {lug.lug: lug for r in chain.results for lug in r.lugs}
    angles, level, worst = (
        np.concatenate([np.ravel(a) for a in v])
        for v in (plan.leg_angles, plan.legs_nominal, plan.legs_worst)
    )
    legs = _table(
        [
            "lug",
            "candidate",
            "position x, y, z [m]",
            "crane",
            "sling angle [deg]",
            "leg tension, level [t]",
            "leg tension, worst [t]",
            "lug design load [t]",
        ],
        [
            (
                label,
                plan.lugs[label],
                _xyz(problem, problem.points[problem.names.index(plan.lugs[label])]),
                plan.cranes[label],
                f"{a:.1f}",
                f"{t0:.2f}",
                f"{tw:.2f}",
                f"{lug_design[plan.lugs[label]].design_load:.2f}" if plan.lugs[label] in lug_design else "-",
            )
            for label, a, t0, tw in zip(plan.labels, angles, level, worst)
        ],
        "Sling legs (lug design load: the rules' chain with the sling angle, docs/design-loads.md)",
        text_columns=(1, 3),
    )
    bars = [
        (
            names[c],
            f"{plan.bar_weights[c]:.2f}",
            ", ".join(f"{t:.2f}" for t in top),
            ", ".join(f"{a:.1f}" for a in plan.top_angles[c]),
        )
        for c, top in enumerate(plan.top_legs)
        if top is not None
    ]
    spreaders = (
        _table(
            ["crane", "bar weight on the hook [t]", "top legs, level [t]", "top-leg angles [deg]"],
            bars,
            "Spreader bars",
            text_columns=(0,),
        )
        if bars
        else ""
    )
    factors = ""
    if chain is not None:
        factors = _table(
            [
                "crane",
                # the factors in words, not their JSON keys (weight_contingency)
                *[
                    f"{'DAF' if f.name == 'daf' else f.name.replace('_', ' ')} [-]"
                    for f in chain.results[0].factors
                ],
                "rigging [t]",
                "static hook [t]",
                "design hook [t]",
            ],
            [
                (
                    r.crane,
                    *[f"{f.value:.3f}" for f in r.factors],
                    f"{r.rigging_weight:.2f}",
                    f"{r.static_hook_load:.2f}",
                    f"{r.design_hook_load:.2f}",
                )
                for r in chain.results
            ],
            "The rules' design-load chain per crane (factors with their clauses: docs/design-loads.md)",
            text_columns=(0,),
        )
    checks = _table(
        ["check", "subject", "value", "limit", "unit", "result", "what the value is"],
        [
            (c.title, c.subject, c.shown("value"), c.shown("limit"), c.unit, "ok" if c.ok else "FAIL", c.note)
            for c in plan.checks
        ],
        "Every check of the plan",
        text_columns=(0, 1, 6),
    )
    rows = [
        ("weight W", f"{problem.body.weight:.2f}", "t"),
        ("weight W is", problem.weight_basis_text, "-"),
        ("location (the DAF column of 0027/ND Table 5-1)", problem.rules.location_text, "-"),
        ("CG (nominal)", _xyz(problem, problem.body.cog), "m"),
        (
            "CG envelope half-widths (x, y, z)",
            ", ".join(f"{abs(v):.2f}" for v in _in_file(problem, problem.cog_envelope.half_widths)),
            "m",
        ),
        ("lowest sling angle allowed", f"{problem.min_sling_angle:g}", "deg"),
        (
            "hook-height tolerance per crane",
            ", ".join(f"{n} +-{d:g}" for n, d in zip(plan.crane_names, hook_tolerances(problem))),
            "m",
        ),
        ("what the hook errors do", plan.hook_tilt_text, "-"),
    ]
    if hasattr(plan, "tolerances"):
        rows[3:3] = [
            ("tilt tolerance along the hook line", f"+-{plan.tolerances[0]:g}", "deg"),
            ("roll allowed about the hook line", f"{plan.tolerances[1]:g}", "deg"),
        ]
    else:
        rows[3:3] = [
            ("tolerance box heel, trim", f"+-{problem.heel_tolerance:g}, +-{problem.trim_tolerance:g}", "deg")
        ]
    inputs = _table(["quantity", "value", "unit"], rows, "Inputs", full=False, text_columns=(0,))
    result = ""
    if hasattr(plan, "chosen"):
        chosen = plan.chosen
        dx, dy, dz = _in_file(problem, chosen.worst_cog_offset)
        each = []
        for crane, hook, (tilt, offset) in zip(plan.crane_names, chosen.hook_worst, chosen.hook_worst_at):
            ox, oy, oz = _in_file(problem, offset)
            each.append(
                (
                    f"{crane}: largest hook load {hook:.2f} t at tilt, CG offset (x, y, z)",
                    f"{tilt:+.2f}; {ox:+.2f}, {oy:+.2f}, {oz:+.2f}",
                    "deg; m",
                )
            )
        result = _table(
            ["quantity", "value", "unit"],
            [
                ("roll about the hook line (CG under it)", f"{chosen.roll:.2f}", "deg"),
                ("objective's worst: tilt along the hook line", f"{chosen.worst_tilt:+.2f}", "deg"),
                ("objective's worst: CG offset (x, y, z)", f"{dx:+.2f}, {dy:+.2f}, {dz:+.2f}", "m"),
                *each,
            ],
            "Where the hook-load spread (the objective) and each crane's hook load are worst",
            full=False,
            text_columns=(0,),
        )
        paired = [n for t, n in plan.ruled_out.items() if t not in plan.rig_causes and t != SHARED]
        search_rows = [
            ("pairs of rigs considered (each crane's rigs that pass its own checks)", plan.options, "pairs")
        ]
        # the pairs sharing a lug are dropped before the pairs are considered
        after = [("feasible pairs (considered, less those ruled out)", plan.options - sum(paired), "pairs")]

        def counted(text):
            return "rigs of one crane" if text in plan.rig_causes else "pairs"

        how = (
            "Hook loads by the lever rule along the hook line (each hook where its rig puts it), "
            "checked on the rigging model with free hooks and elastic legs."
        )
        title = "Lift plan: two cranes on slings, lugs chosen by liftplan"
    else:
        stats = plan.stats
        search_rows = [
            (plan.lift_points_text, len(plan.rigs), "-"),
            ("(set, crane assignment) rows", stats.rows, "-"),
            ("evaluated", stats.evaluated, "-"),
            ("search stopped", stats.stopped, "-"),
            ("certified lower bound", f"{stats.lower_bound:.4g}", "objective"),
        ]
        after = []

        def counted(text):
            return "-"

        how = plan.method_text
        title = f"Lift plan: {problem.cranes} cranes on slings, lugs chosen by liftplan"
    search = _table(
        ["quantity", "value", "unit"],
        search_rows
        + [(f"ruled out: {text}", n, counted(text)) for text, n in plan.ruled_out.items()]
        + after,
        "Search",
        full=False,
        text_columns=(0,),
    )
    unit, scale = ("t", 1.0) if plan.objective == "spread" else ("%", 100.0)
    ranking = _table(
        ["rank", f"worst [{unit}]", "slings (crane)"],
        [(k, f"{scale * v:.2f}", "; ".join(texts)) for k, texts, v in _ranking(plan)],
        "Alternatives, best first",
        text_columns=(2,),
    )
    info = problem.report
    body = "\n".join(
        [
            report_page.title_block(info, name, title, today),
            f"<p>All coordinates are in the planning file's frame: {html.escape(FRAME_TEXT[problem.frame])}. "
            f"{how} Forces in t (tonne-force), lengths in m.</p>",
            report_page.status(plan.checks),
            report_page.warnings(plan.problem),
            "<h2>1 Recommendation</h2>",
            cranes,
            legs,
            spreaders,
            result,
            *lengths_section(plan, "hoist"),
            *_breakout_section(plan),
            "<h2>2 Basis of the plan</h2>",
            inputs,
            factors,
            "<h2>3 Checks to hand over</h2>",
            checks,
            "<h2>4 Figures</h2>",
            _png(
                plan_view(plan),
                "plan view",
                "Plan view, seen from above: each crane's lugs, its hook and the CG.",
            ),
            *view_section(plan),
            "<h2>5 Alternatives</h2>",
            ranking,
            '<h2 class="appendix">Engineering appendix</h2>',
            search,
        ]
    )
    return report_page.document(
        name, body, report_page.running_header(info, name), report_page.running_footer(info)
    )


def _breakout_section(plan):
    """The breakout case on the hooks: the peak load, each crane's share, what governs."""
    case = plan.breakout
    if case is None:
        return []
    problem = plan.problem
    load, force = case.load, case.load.breakout
    how = (
        "by the lever rule along the hook line; the crew's hook errors tilt the body along it, "
        "and the share is taken at its worst over them"
        if hasattr(plan, "chosen")
        else "held at the level attitude with the plan's preload held (the hooks moved together "
        "as a rigid pattern), at its worst over every hook within the hook tolerance"
    )
    text = (
        f"<p>The hull rests on the seabed as in the scene &ldquo;"
        f"{html.escape(problem.breakout_scene.name)}&rdquo;. Breaking it out takes a peak total "
        f"hook load of <b>{load.total:.2f} t</b> ({load.weight_factor:.3f} x W): the submerged "
        f"weight {force.submerged_weight:.2f} t and the breakout force {force.force:.2f} t "
        f"({html.escape(force.describe())}), on a line through ({_xyz(problem, load.point)}) m. "
        f"Each hook's share is found {how}; the larger of it and the share's worst in the box is "
        "the crane's static input to the design-load chain, and each sling's legs at breakout "
        "enter its lug design loads. The breakout hook load (share + rigging, no dynamic factor) "
        "is checked against the chart SWL.</p>"
    )
    rows = []
    for c, name in enumerate(case.cranes):
        box = float(plan.box_shares[c])
        legs = ", ".join(f"{t:.2f}" for t in plan.breakout_legs[c])
        rows.append(
            (
                name,
                f"{case.worst[c]:.2f}",
                f"{case.hook_widening[c]:.2f}",
                f"{case.rigging[c]:.2f}",
                f"{case.hook_loads[c]:.2f}",
                f"{case.swl[c]:.1f}",
                f"{box:.2f}",
                "breakout" if case.worst[c] > box else "box",
                legs,
                "ok" if case.checks[c].ok else "FAIL",
            )
        )
    table = _table(
        [
            "crane",
            "share at breakout [t]",
            "of it, hook errors [t]",
            "rigging [t]",
            "breakout hook load [t]",
            "chart SWL [t]",
            "share, worst in the box [t]",
            "static input",
            "legs at breakout [t]",
            "check",
        ],
        rows,
        "Breakout from the seabed: each hook's share of the peak load",
        text_columns=(0, 7, 8, 9),
    )
    return ["<h3>Breakout from the seabed</h3>", text, table]


def plan_scene_toml(plan):
    """The sling plan as a rigging scene file (``liftplan solve`` reads it), file frame: its
    :attr:`~liftplan.planner.plans.slings.lift.SlingLift.scene` written by the one scene writer."""
    problem = plan.problem
    header = (
        f"Written by liftplan plan: the chosen slings of {json.dumps(problem.name)}.",
        "`liftplan solve` on this file solves the rigging model (free hooks, elastic legs).",
        f"Coordinates in the planning file's frame: {FRAME_TEXT[problem.frame]}.",
    )
    return scene_toml(plan.scene, header=header)


def render(plan):
    """The report page and the rigging scene file of a sling plan: (HTML, TOML) text."""
    return render_html(plan), plan_scene_toml(plan)
