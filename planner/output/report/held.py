"""The recommendation report: one self-contained HTML file (and a PDF when WeasyPrint is
installed), plus the chosen plan as a scene file that ``liftplan solve`` reads back.

Figures are embedded as base64 PNG, so the HTML file can be mailed on its own. Every
table states its units in its header; every coordinate is in the frame of the planning file,
named once at the top; ``plan_scene.toml`` keeps that frame and the candidate names.
"""

from __future__ import annotations

import html
import json

import numpy as np

from liftplan.model.frames import FRAME_TEXT, zup_to_choi
from liftplan.model.scene.writer import scene_toml
from liftplan.model.version import __version__
from liftplan.planner.batch.montecarlo import hook_monte_carlo
from liftplan.planner.output.console.limits import limit_lines
from liftplan.planner.output.figures import plan as figures
from liftplan.planner.output.report import page as report_page
from liftplan.planner.output.report.hull_water import hull_water_section, with_water
from liftplan.planner.output.report.lengths import lengths_section
from liftplan.planner.output.report.view import view_section
from liftplan.planner.plans.common import OBJECTIVE_TEXT
from liftplan.planner.plans.vessel_loads import wind_json
from liftplan.planner.search.scenarios import Scenario

ASSUMPTIONS = (
    "Ropes hang vertically (each hook above its lug) and the body is rigid.",
    "With four or more cranes the differential hoist dials in any admissible level preload; "
    "a heel or trim deviation comes from hook motions that move the level hook pattern "
    "rigidly, so the twist (preload) is held and the tensions follow the elastic model.",
    "Rope stiffness is EA / l0 (unstretched length); a rope never goes slack inside the "
    "tolerance box (every tension stays above min_tension, checked densely).",
    "The worst spread is searched on a 21 x 21 heel-trim grid for every CG-envelope vertex, "
    "then on finer grids around the worst point; the CG envelope is exact at its vertices "
    "(the spread is convex in the CG position).",
    "Hook heights: every hook within its own tolerance of its planned height (its crane's "
    "hook_tolerance, else the plan's), independently, "
    "is part of the worst case and of every limit (exact: the tensions are affine in the hook "
    "heights at a given attitude while every rope is taut); a rigid body (hull flexibility, "
    "which lowers skew loads, is ignored). With hook_tolerance = 0 no hook error is assumed.",
    "Design load: the design hook load of the lifting rules' chain (GL Noble Denton 0027/ND "
    "Rev 11, docs/design-loads.md): the larger of the worst tension in the box (over the CG "
    "envelope and the hook errors) and the load at the rules' tilt, x weight contingency "
    "(skew 1: the hook errors are in the worst) + rigging weight, x the dynamic amplification "
    "factor; checked against the chart SWL at the crane's radius. Utilisation = design hook "
    "load / chart SWL. Code margin (a separate check): (level share x contingency + rigging) "
    "x (1 + 20 / 33 / 50 % for 2 / 3 / 4+ cranes) <= SWL.",
)


# -- HTML ---------------------------------------------------------------------------------
def _png(fig, alt, caption=""):
    return report_page.figure(fig, alt, caption)


def _table(headers, rows, caption, **options):
    return report_page.table(headers, rows, caption, **options)


def _shown(problem, point):
    """A body-frame point as the scene file wrote it."""
    return zup_to_choi(point) if problem.frame == "choi" else tuple(point)


def _xyz(problem, point):
    return ", ".join(f"{v:.2f}" for v in _shown(problem, point))


def _where(plan, scenario):
    return (
        f"{scenario.heel:+.2f}, {scenario.trim:+.2f}",
        ", ".join(f"{v:.2f}" for v in plan.cog_at(scenario)),
    )


def render_html(plan, today=None):
    """The report as one HTML string, laid out for A4 print.

    Client-facing part first (title block, recommendation, basis, checks, figures,
    alternatives, assumptions), then the engineering appendix (the optimisation's bounds
    and the search) on its own pages: the sections of :data:`SECTIONS`, in order.

    Parameters
    ----------
    plan : Plan
    today : datetime.date, optional
        The date printed when ``[report] date`` is not given (default: today).
    """
    problem = plan.problem
    name = problem.name or "Lift plan"
    info = problem.report
    head = [
        report_page.title_block(
            info,
            name,
            f"Lift plan: {problem.cranes} cranes, lugs chosen by liftplan, preload held by the boom heights",
            today,
        ),
        f"<p>All coordinates are in the planning file's frame: {html.escape(FRAME_TEXT[plan.frame])}. "
        "Angles: heel &gt; 0 starboard down, trim &gt; 0 bow down. Forces in t (tonne-force), "
        "lengths in m.</p>",
        report_page.status(plan.checks),
        report_page.warnings(plan.problem),
    ]
    body = "\n".join(head + [part for section in SECTIONS for part in section(plan)])
    return report_page.document(
        name, body, report_page.running_header(info, name), report_page.running_footer(info)
    )


# -- the sections ------------------------------------------------------------------------------
def _recommendation(plan):
    """1: the lugs, cranes and boom heights, and the plan's summary."""
    problem, chosen = plan.problem, plan.chosen
    candidates = dict(zip(problem.names, problem.candidates))
    worst = chosen.worst
    positions = {c.name: c.position for c in problem.fleet}
    lugs = _table(
        [
            "lug",
            "candidate (bulkhead)",
            "position x, y, z [m]",
            "crane",
            "radius [m]",
            "chart SWL [t]",
            "boom height H [m]",
            "level tension [t]",
        ],
        [
            (
                label,
                f"{name} ({candidates[name].bulkhead})" if candidates[name].bulkhead else name,
                _xyz(problem, candidates[name].at),
                plan.cranes[label],
                "-" if positions[plan.cranes[label]] is None else f"{plan.radius[label]:.1f}",
                f"{plan.swl[label]:.1f}",
                f"{plan.boom_heights[label]:.3f}",
                f"{plan.tensions[label]:.2f}",
            )
            for label, name in plan.lugs.items()
        ],
        "Recommended lugs, cranes and boom heights",
        text_columns=(1, 3),
    )
    summary = _table(
        ["quantity", "value", "unit"],
        [
            ("tension spread, level with the nominal CG", f"{plan.spread:.2f}", "t"),
            ("worst tension spread over the tolerance box", f"{plan.worst_spread:.2f}", "t"),
            ("... at heel, trim", f"{worst.heel:+.2f}, {worst.trim:+.2f}", "deg"),
            ("... with the CG at (x, y, z)", _where(plan, worst)[1], "m"),
            (
                "... that is, CG offset (x, y, z)",
                ", ".join(f"{v:+.2f}" for v in _shown(problem, worst.cog_offset)),
                "m",
            ),
            (
                "worst utilisation spread (max - min of T / SWL)",
                f"{100 * plan.worst_utilisation_spread:.1f}",
                "%",
            ),
            (
                "tension range over the box",
                f"{chosen.tension_range[0]:.2f} to {chosen.tension_range[1]:.2f}",
                "t",
            ),
            (
                "highest design utilisation (design hook load / chart SWL)",
                "n/a"
                if plan.design_loads.chain is None
                else f"{100 * max(c.design.utilisation for c in plan.capacity):.1f}",
                "%",
            ),
        ],
        "Plan summary",
        full=False,
        text_columns=(0,),
    )
    stopped = [
        f"<p><b>{html.escape(line)}</b></p>" for line in limit_lines(plan.stats, problem, plan.lengths)
    ]
    return ["<h2>1 Recommendation</h2>", *stopped, lugs, _governing(plan), summary]


def _governing(plan):
    """Page 1's loads to sign against: per crane the design hook load and the one utilisation
    (design hook load / chart SWL), what governs it, and the hook accuracy the crew must hold."""
    design = plan.design_loads
    if design.chain is None:
        return f"<p><b>Design loads NOT computed</b>: {html.escape(design.missing)}.</p>"
    rows = []
    for c in plan.capacity:
        r = c.design
        ok = r.check.ok and (r.code_margin is None or r.code_margin.ok)
        rows.append(
            (
                f"{c.label} ({c.crane})",
                f"{c.swl:.1f}",
                f"{r.design_hook_load:.2f}",
                f"{100 * r.utilisation:.1f}",
                _governing_case(c),
                "ok" if ok else "FAIL",
            )
        )
    table = _table(
        [
            "lug (crane)",
            "chart SWL [t]",
            "design hook load [t]",
            "utilisation: design / chart SWL [%]",
            "what governs it",
            "check",
        ],
        rows,
        "The loads to sign against: each crane's design hook load by the rules' chain",
        text_columns=(0, 4),
    )
    needed = plan.hook_accuracy_needed
    within = f"+-{needed:.3f} m" if np.isfinite(needed) else "any error"
    crew = (
        f"The crew must hold every hook within {within} of its planned height (the same error on "
        f"every hook; planned for {plan.tolerance_text()}) for every rope to stay within its limits."
    )
    problem = plan.problem
    basis = (  # what the design loads stand on, where the signer reads them (section 2 has all)
        f"Weight W {problem.body.weight:.2f} t ({problem.weight_basis_text}); location "
        f"{problem.rules.location_text}, the DAF column of 0027/ND Table 5-1."
    )
    return table + f"<p>{crew}</p><p>{html.escape(basis)}</p>"


def _governing_case(capacity):
    """What sets a crane's static hook load: the worst in the box (where), the breakout, or
    the rules' tilt."""
    if capacity.tilt is not None and capacity.tilt.load > capacity.static_input:
        return f"the rules' tilt, {capacity.tilt.tilt:.2f} deg"
    if capacity.governs == "breakout":
        return "breakout from the seabed"
    if capacity.governs == "in_water":
        return "the start in water"
    at = capacity.worst_at
    return f"the box: heel {at.heel:+.2f}, trim {at.trim:+.2f} deg"


def _basis(plan):
    """2: the inputs and the crane fleet."""
    problem = plan.problem
    inputs = _table(
        ["quantity", "value", "unit"],
        [
            ("weight W", f"{problem.body.weight:.2f}", "t"),
            ("weight W is", problem.weight_basis_text, "-"),
            ("location (the DAF column of 0027/ND Table 5-1)", problem.rules.location_text, "-"),
            ("CG (nominal)", _xyz(problem, problem.body.cog), "m"),
            (
                "CG envelope half-widths (x, y, z)",
                ", ".join(f"{abs(v):.2f}" for v in _shown(problem, problem.cog_envelope.half_widths)),
                "m",
            ),
            ("CG envelope shape", problem.cog_envelope.shape, "-"),
            ("cranes", problem.cranes, "-"),
            ("the plan keeps small", OBJECTIVE_TEXT[plan.objective], "-"),
            ("heel tolerance", f"+-{problem.heel_tolerance:g}", "deg"),
            ("trim tolerance", f"+-{problem.trim_tolerance:g}", "deg"),
            ("min tension", f"{problem.min_tension:g}", "t"),
            ("hook-height tolerance (each hook's own)", plan.tolerance_text(unit=""), "m"),
            ("lift height (body origin above datum)", f"{problem.lift_height:g}", "m"),
            ("candidate lug points", len(problem.candidates), "-"),
            *_wind_rows(plan),
        ],
        "Inputs",
        full=False,
        text_columns=(0,),
    )
    floating = any(c.vessel is not None for c in problem.fleet)
    fleet = _table(
        [
            "crane",
            "slew centre x, y, z [m]",
            "load chart (radius m: SWL t)",
            "rope EA [t]",
            *(["effective EA, rope and vessel in series [t]"] if floating else []),
            "rope length l0 [m]",
            "boom height range [m]",
        ],
        _fleet_rows(problem),
        "Crane fleet"
        + (
            " (rope EA: the hoist rope's own, as the file gives it; effective EA: l0 / (l0 / EA + c), "
            "c the vessel's tip compliance at the lug the crane takes; on land the rope's own)"
            if floating
            else ""
        ),
        text_columns=(0, 2),
    )
    return ["<h2>2 Basis of the plan</h2>", inputs, fleet]


def _checks(plan):
    """3: every check, the design loads, the breakout, the crew's hook accuracy and guidance."""
    skew = _table(
        [
            "rope or diagonal pair",
            "nominal load [t]",
            "skewed load [t]",
            "skew load factor [-]",
            "Noble Denton default [-]",
        ],
        [
            (
                " + ".join(s.lugs),
                f"{s.nominal:.2f}",
                f"{s.skewed:.2f}",
                f"{s.factor:.3f}",
                f"{plan.default_skew_factor:.2f}" if len(s.lugs) == 2 else "-",
            )
            for s in plan.skew
        ],
        f"Skew loads for hook heights each within its own tolerance ({plan.tolerance_text()})",
    )
    own = np.diag(plan.hook_sensitivity)
    crew = plan.crew_margin((1.0, 2.0, 5.0)) if np.any(plan.lugset.hook_tolerance > 0) else []
    hooks = (
        _table(
            [
                "hooks",
                "tolerance [m]",
                "worst spread [t]",
                *(f"{label} largest [t]" for label in plan.labels),
                "lowest [t]",
                "result",
            ],
            [
                (
                    f"{c.factor:g} x as planned",
                    plan.tolerance_text(c.factor, unit="", short=True),
                    f"{c.worst_spread:.1f}",
                    *(f"{v:.1f}" for v in c.rope_max),
                    f"{c.lowest:.1f}",
                    c.verdict(plan.labels),
                )
                for c in crew
            ]
            + [("limit", "", "", *(f"{v:.1f}" for v in plan.lugset.limit), "> 0", "")],
            "Hook accuracy: the plan held, the hooks as planned and worse, "
            + ("in the box and at breakout " if plan.design_loads.breakout is not None else "")
            + "(limits: chart SWL / DAF, less rigging, over contingency)",
            text_columns=(0, 1, 4 + len(plan.labels)),
            ropes=(3, len(plan.labels)),
        )
        if crew
        else "<p>No hook-height error was assumed (hook_tolerance = 0).</p>"
    )
    needed = plan.hook_accuracy_needed
    hooks += (
        "<p>The crew must hold every hook within "
        + (f"+-{needed:.3f} m" if np.isfinite(needed) else "any error")
        + " of its planned height, the same error on every hook, for every rope to stay within "
        "its limits (the plan's preload held; the table above multiplies each hook's own "
        "tolerance instead, so a hook whose own tolerance is larger may go beyond it there and "
        "stay within the limits); the "
        f"worst combination of 1 cm errors moves a rope by {plan.twist_stiffness:.2f} t.</p>"
    )
    hooks += _monte_carlo_table(plan)
    sensitivity = _table(
        ["rope", *(f"{label} [t/cm]" for label in plan.labels)],
        [("tension change per cm of its own hook", *(f"{v:+.2f}" for v in own))],
        f"Load-cell guidance: each rope's change per centimetre of its own hook off its height "
        f"(pose held); the worst combination of 1 cm errors moves a rope by "
        f"{plan.twist_stiffness:.2f} t",
        text_columns=(0,),
        ropes=(1, len(plan.labels)),
    )
    guidance = _table(
        ["step", "from [deg]", "to [deg]", *(f"dT {label} [t]" for label in plan.labels), "note"],
        [
            (
                g.angle,
                f"{g.start:+.0f}",
                f"{g.end:+.0f}",
                *(f"{v:+.2f}" for v in g.change.values()),
                "" if g.within_model else "a rope goes slack: beyond the model",
            )
            for g in plan.guidance
        ],
        "Operator guidance: tension change per step of heel (trim 0) and of trim (heel 0)",
        text_columns=(0, 3 + len(plan.labels)),
        ropes=(3, len(plan.labels)),
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
    return [
        "<h2>3 Checks to hand over</h2>",
        checks,
        _design_table(plan),
        *_design_details(plan),
        *_breakout_section(plan),
        *hull_water_section(plan),
        *_vessel_section(plan),
        hooks,
        sensitivity,
        skew,
        guidance,
    ]


def _figures(plan):
    """4: plan view, tensions against heel and trim, the spread over the box."""
    problem = plan.problem
    figs = [
        _png(
            figures.plan_view(plan),
            "plan view",
            "Plan view, seen from above: the chosen lugs (L1...), the cranes and the CG."
            if any(c.position is not None for c in problem.fleet)
            else "Plan view, seen from above: the chosen lugs (L1...) and the CG; the boom heights "
            "are in the table of section 1.",
        ),
        _png(
            figures.tension_curves(plan),
            "tension against heel and trim",
            "Rope tensions with the plan's preload held, against heel (left) and trim (right); "
            "the tolerance box shaded.",
        ),
        _png(
            figures.spread_map(plan),
            "spread over the tolerance box",
            "The plan's objective over the heel/trim tolerance box, at each point the worst CG "
            "position of the envelope and the worst hook errors; the star marks the worst case.",
        ),
    ]
    return ["<h2>4 Figures</h2>", *figs, *view_section(plan)]


def _girder_cell(worst):
    ratio = max(w.ratio for w in worst)
    return f"{100 * ratio:.1f}" + (" FAIL" if ratio > 1.0 else "")


def _alternatives(plan):
    """5: the ranking of lug sets."""
    unequal = not plan.problem.equal_cranes
    girder = bool(plan.girder)
    governing = plan.hull_search is not None  # [hull] EI or [water]: ranked on another value
    unit = "-" if plan.problem.goal.per_swl or plan.problem.goal.peak else "t"
    ranking = _table(
        [
            "rank",
            "lugs (crane)" if unequal else "lugs",
            "nominal spread [t]",
            "worst spread [t]",
            *([f"value ranked on (governing model) [{unit}]"] if governing else []),
            "worst utilisation spread [%]",
            "worst at heel, trim [deg]",
            "... with the CG at x, y, z [m]",
            "highest in-box load / SWL [%]",
            "design utilisation [%]",
            "design checks",
            *(["hull girder: worst |M| or |Q| / allowable [%]"] if girder else []),
            "boom heights H [m]",
        ],
        [
            (
                k + 1,
                ", ".join(
                    f"{lug} ({crane})" if unequal else lug for lug, crane in zip(r.lugs, r.crane_names)
                ),
                f"{r.nominal_spread:.2f}",
                f"{r.worst_spread:.2f}",
                *([f"{plan.hull_search.values[k]:.4g}"] if governing else []),
                f"{100 * r.worst_utilisation_spread:.1f}",
                *_where(plan, r.worst),
                f"{100 * r.max_utilisation:.1f}",
                "n/a" if d.chain is None else f"{100 * d.max_utilisation:.1f}",
                "ok" if d.ok else "FAIL",
                *([_girder_cell(g)] if girder else []),
                " ".join(f"{h:.3f}" for h in r.boom_heights),
            )
            for k, (r, d, g) in enumerate(zip(plan.ranking, plan.ranked_design, plan.ranked_girder))
        ],
        f"Ranking of lug sets (the best {len(plan.ranking)} of {plan.stats.sets}; rank 1 is the "
        "recommendation; the sets that fail a design check"
        + (" or overload the hull girder" if girder else "")
        + " are ranked after those that meet them"
        + (
            "; the sets are ranked on their value on the model that governs ([hull] EI or "
            "[water]); the spreads beside it are the rigid hull's in air"
            if governing
            else ""
        )
        + ")"
        + (f". {plan.design_note[0].upper()}{plan.design_note[1:]}." if plan.design_note else ""),
        text_columns=(1,),
    )
    return ["<h2>5 Alternatives</h2>", ranking]


#: With ``[hull] EI`` the first and the hook-height assumptions read so (the ranked sets are
#: judged on the flexible hull; the hook errors' widening keeps the rigid hull's sensitivities).
FLEXIBLE = {
    0: "Ropes hang vertically (each hook above its lug). The hull is flexible ([hull] EI, GJ): "
    "every ranked set is solved again on the flexible hull at its worst states and, where a "
    "tension changes by more than 1 %, judged on the flexible hull (section 3).",
    4: ASSUMPTIONS[4].replace(
        "a rigid body (hull flexibility, which lowers skew loads, is ignored)",
        "their effect is taken with the rigid hull's sensitivities (hull flexibility, which "
        "lowers skew loads, is left out of it)",
    ),
}


#: With floating cranes the rope-stiffness assumption reads so.
FLOATING = (
    "Rope stiffness is EA / l0 (unstretched length), and a floating crane's vessel is in series "
    "with its rope: the vessel heels, trims and heaves under the hook load and moves the tip, so "
    "the crane's effective stiffness is 1 / (l0 / EA + c), c the vessel's tip compliance at the "
    "lug it takes (the Crane fleet table gives both EAs); a rope never goes slack inside the "
    "tolerance box (every tension stays above min_tension, checked densely)."
)


def _assumptions(plan):
    """6: what the plan assumes."""
    flexible = plan.problem.hull_stiffness is not None
    items = [FLEXIBLE.get(k, a) if flexible else a for k, a in enumerate(ASSUMPTIONS)]
    if any(c.vessel is not None for c in plan.problem.fleet):
        items[2] = FLOATING
    if plan.problem.wind is not None and plan.problem.wind.booms:
        items[4] = items[4].replace(
            "else the plan's)", "else the plan's; a floating crane's widened by its boom's wind tip error)"
        )
    items += _wind_assumption(plan)
    return [
        "<h2>6 Assumptions</h2>",
        "<ul>" + "".join(f"<li>{html.escape(a)}</li>" for a in items) + "</ul>",
    ]


def _wind_rows(plan):
    """The basis table's rows for ``[wind]`` (none without): its speed and direction, the body's
    force and how far its couple widened the CG envelope, each boom's tip error."""
    data = wind_json(plan).get("wind")
    if data is None:
        return []
    rows = [
        ("wind speed", f"{data['speed']:g}", "m/s"),
        ("wind direction", "any (the worst over the operation)", "-"),
        ("wind force on the body", f"{data['body_force']:.2f}", "t"),
        ("CG envelope widened in plan by the wind's couple", f"{data['cog_widening']:.3f}", "m"),
    ]
    rows += [
        (
            f"wind on {crane}'s boom: force, its tip error added to the hook tolerance",
            f"{v['force']:.2f} t, +-{v['hook_error']:.3f} m",
            "-",
        )
        for crane, v in data["booms"].items()
    ]
    return rows


def _wind_assumption(plan):
    """The assumption the wind adds (none without)."""
    data = wind_json(plan).get("wind")
    if data is None:
        return []
    booms = "; ".join(
        f"on {crane}'s boom {v['force']:.2f} t, heeling and trimming its vessel: its tip moves up to "
        f"+-{v['hook_error']:.3f} m, added to its hook tolerance"
        for crane, v in data["booms"].items()
    )
    return [
        f"Wind {data['speed']:g} m/s from any direction ([wind]): on the body {data['body_force']:.2f} t "
        "at its centre of pressure; its couple moves the weight's line downwind, so the CG envelope "
        f"is widened by {data['cog_widening']:.3f} m in plan (x and y) for every direction"
        + (f"; {booms}" if booms else "")
        + ". The wind's horizontal force itself is carried by the ropes' small inclinations."
    ]


def _fleet_rows(problem):
    """One row per crane; a run of cranes alike in everything but the name is one row
    ("crane 1 to crane 64 (64 alike)": a fleet of strand jacks is one line, not two pages).
    With floating cranes: the rope's own EA and, in a column of its own, the effective EA of
    the rope and the vessel in series at the planned lug (``-`` for a floating crane the plan
    does not use)."""
    rows = []
    floating = any(c.vessel is not None for c in problem.fleet)
    for c in problem.fleet:
        rope = c.rope_EA if c.rope_EA is not None else (c.given.EA if c.given is not None else c.EA)
        if c.vessel is None:
            series = (f"{c.EA:.0f} (on land)",)
        else:
            series = (f"{c.EA:.0f}" if c.rope_EA is not None else "-",)
        values = (
            "-" if c.position is None else _xyz(problem, (*c.position, 0.0)),
            f"{c.swl:g} t at any radius"
            if c.swl is not None
            else ", ".join(f"{r:g}: {w:g}" for r, w in c.load_chart),
            f"{rope:.0f}",
            *(series if floating else ()),
            f"{c.rope_length:.2f}",
            report_page.range_text(c.boom_min, c.boom_max),
        )
        if rows and rows[-1][1] == values and values[0] == "-":
            rows[-1][0].append(c.name)
        else:
            rows.append(([c.name], values))
    return [
        (names[0] if len(names) == 1 else f"{names[0]} to {names[-1]} ({len(names)} alike)", *values)
        for names, values in rows
    ]


#: Monte-Carlo draws per row of the report's hook table (seeded: the report is reproducible).
MONTE_CARLO_DRAWS = 2000


def _monte_carlo_table(plan):
    """Random hook errors solved on the forward elastic model beside the worst case: the
    plan's tolerance and 2x and 5x it (uniform, seeded)."""

    if not np.any(plan.lugset.hook_tolerance > 0):
        return ""
    rows = []
    for factor in (1.0, 2.0, 5.0):
        mc = hook_monte_carlo(
            plan, draws=MONTE_CARLO_DRAWS, tolerance=plan.lugset.hook_tolerance * factor, seed=1
        )
        s = mc.summary()
        rows.append(
            (
                f"{factor:g} x as planned",
                f"{s['spread_p50']:.1f}",
                f"{s['spread_p95']:.1f}",
                f"{s['spread_max']:.1f}",
                f"{100 * s['p_spread_above_plan_worst']:.1f}",
                _percent(s["p_above_design_tension"]),
                _percent(s["p_above_design_load"]),
                f"{100 * s['p_above_swl']:.1f}",
                str(mc.failed),
            )
        )
    return _table(
        [
            "hooks",
            "spread p50 [t]",
            "p95 [t]",
            "max [t]",
            "above the plan's worst [%]",
            "a rope above its design tension [%]",
            "a rope above its design hook load [%]",
            "a rope above its SWL [%]",
            "no equilibrium [-]",
        ],
        rows,
        f"Monte-Carlo check: {MONTE_CARLO_DRAWS} draws of independent hook errors (uniform "
        f"within the tolerance, seed 1), each solved on the forward elastic model; the plan's "
        f"worst spread is {plan.worst_spread:.1f} t. Design tension: the static tension each "
        "crane's design load was built from (like for like with a drawn static tension); the "
        "design hook load carries the contingency and the DAF on top, so exceeding it is rarer "
        "(docs/design-loads.md)",
        text_columns=(0,),
    )


def _percent(share):
    """A share as a percentage; '-' where it is not known (no design load computed)."""
    return "-" if not np.isfinite(share) else f"{100 * share:.1f}"


def _appendix(plan):
    """The engineering appendix: how good the plan is proved to be, the admissible tension
    bounds, and what the search did."""
    stats, chosen = plan.stats, plan.chosen
    unit = plan.problem.goal.unit
    fmt = "{:.4f}" if unit == "-" else "{:.2f}"
    optimality = _table(
        ["quantity", "value", "unit"],
        [
            ("worst value of the plan over the box (the objective)", fmt.format(stats.best), unit),
            (
                "lower bound from the optimisation: no lug set and crane assignment does better"
                + ("" if plan.lengths is None else " at any rope length tried"),
                fmt.format(stats.lower_bound),
                unit,
            ),
            ("gap between the two", fmt.format(stats.gap), unit),
            ("relative gap", f"{100 * stats.relative_gap:.2f}", "%"),
            (
                "why the search ended",
                stats.stopped if plan.lengths is None else f"{stats.stopped} (over the rope lengths tried)",
                "-",
            ),
            ("how the lug sets were searched (plan.search)", stats.method, "-"),
            (
                "least worst value for the recommended lugs (linear programme over the preloads)",
                fmt.format(chosen.bound),
                unit,
            ),
        ],
        "Optimality: how far the recommendation can be from the best plan",
        full=False,
        text_columns=(0,),
    )
    admissible = _table(
        ["heel [deg]", "trim [deg]", "least spread [t]", *(f"{label} range [t]" for label in plan.labels)],
        [
            (
                f"{s.heel:+.2f}",
                f"{s.trim:+.2f}",
                *(
                    (f"{b.least_spread:.2f}", *(f"{lo:.1f} to {hi:.1f}" for lo, hi in zip(b.lower, b.upper)))
                    if b is not None
                    else ["no admissible set"] + [""] * len(plan.labels)
                ),
            )
            for s, b in plan.admissible
        ],
        "Admissible tensions of the recommended lugs: the range of each tension over every "
        "statically admissible set within min_tension and SWL (nominal CG)",
        ropes=(3, len(plan.labels)),
    )
    lengths = plan.lengths
    at = "" if lengths is None else " (at the chosen rope length)"
    search = _table(
        ["quantity", "value", "unit"],
        [
            *(
                ()
                if lengths is None
                else (
                    (
                        "rope lengths tried (each an exact search; the counts below are the chosen length's)",
                        len(lengths.trials),
                        "-",
                    ),
                    ("sets evaluated over every length tried", lengths.evaluated, "-"),
                    ("rope-length trials cut short by the time limit", len(lengths.cut_short), "-"),
                    ("lengths not tried: the time limit had run out", lengths.not_tried, "-"),
                )
            ),
            ("lug sets" + at, report_page.count_text(stats.sets), "-"),
            ("(set, crane assignment) pairs in reach", report_page.count_text(stats.rows), "-"),
            ("pairs with a crane beyond its chart's reach", stats.out_of_reach, "-"),
            (
                f"pairs with two booms crossing or within {plan.problem.crane_clearance:g} m in plan",
                stats.clashing,
                "-",
            ),
            *(
                (
                    ("the MIP's cutting-plane rounds (no set enumerated)", stats.refined, "-"),
                    ("sets evaluated (the first plan's and the MIP's choices)", stats.evaluated, "-"),
                )
                if stats.method == "mip"
                else (
                    ("ruled out by screening", stats.screened_out, "-"),
                    ("evaluated (linear programme + dense search of the box)", stats.evaluated, "-"),
                    ("not evaluated: their bound could not beat the ranked sets", stats.pruned, "-"),
                )
            ),
            *((f"infeasible: {text}", n, "sets") for text, n in stats.infeasible.items()),
            (
                "search time" + ("" if lengths is None else " (every length tried)"),
                f"{stats.seconds:.2f}",
                "s",
            ),
        ],
        "Search",
        full=False,
        text_columns=(0,),
    )
    return [
        '<h2 class="appendix">Engineering appendix</h2>',
        "<p>For the engineer checking the plan: how close the recommendation is proved to be "
        "to the best possible plan, the statically admissible tensions of the recommended "
        "lugs, and what the search did.</p>",
        optimality,
        admissible,
        search,
    ]


def _design_table(plan):
    """The rules' chain per crane, one column per crane (a calculation read top down)."""
    design = plan.design_loads
    if design.chain is None:
        return f"<p><b>Design loads not computed:</b> {html.escape(design.missing)}</p>"
    columns = []
    for c in plan.capacity:
        r = c.design
        factor = {f.name: f for f in r.factors}
        skew = factor["skew"].value if factor["skew"].applies_to.startswith("hook") else 1.0
        margin = (
            "-"
            if r.code_margin is None
            else (f"{r.code_margin.value:.1f} {'<=' if r.code_margin.ok else '>'} {r.code_margin.limit:.1f}")
        )
        ok = r.check.ok and (r.code_margin is None or r.code_margin.ok)
        breakout = [] if design.breakout is None else [f"{c.breakout:.2f}", c.governs]
        columns.append(
            [
                c.crane,
                "-" if c.radius is None else f"{c.radius:.1f}",
                f"{c.swl:.1f}",
                f"{c.nominal:.2f}",
                f"{c.worst:.2f}",
                *breakout,
                f"{c.tilt.load:.2f}",
                f"{factor['weight_contingency'].value:.3f}",
                f"{skew:.4f}",
                f"{r.rigging_weight:.2f}",
                f"{r.static_hook_load:.2f}",
                f"{factor['daf'].value:.3f}",
                f"{r.design_hook_load:.2f}",
                f"{100 * r.utilisation:.1f}",
                margin,
                "ok" if ok else "FAIL",
            ]
        )
    breakout = (
        []
        if design.breakout is None
        else ["at breakout, held level [t]", "static input: box worst or breakout"]
    )
    quantities = [
        "crane",
        "radius [m]",
        "chart SWL [t]",
        "level tension [t]",
        "worst in the box [t]",
        *breakout,
        "at the rules' tilt [t]",
        "x weight contingency [-]",
        "x skew on the hook [-]",
        "+ rigging [t]",
        "= static hook load [t]",
        "x DAF [-]",
        "= design hook load [t]",
        "utilisation: design / chart SWL [%]",
        "code margin: share x (1 + margin) vs SWL [t]",
        "check",
    ]
    rows = [(q, *(col[k] for col in columns)) for k, q in enumerate(quantities[1:], start=1)]
    return _table(
        ["quantity", *(f"{c.label} ({col[0]})" for c, col in zip(plan.capacity, columns))],
        rows,
        "Design loads per crane (0027/ND chain; utilisation = design hook load / chart SWL; "
        f"tilt {design.tilt_note})",
        text_columns=(0,),
        ropes=(1, len(columns)),
    )


def _breakout_section(plan):
    """The breakout case: the peak load from the seabed scene and each crane's held share."""
    design = plan.design_loads
    case = design.breakout
    if case is None:
        return []
    load, force = case.load, case.load.breakout
    problem = plan.problem
    model = force.describe()
    text = (
        f"<p>The hull rests on the seabed as in the scene &ldquo;"
        f"{html.escape(problem.breakout_scene.name)}&rdquo;. Breaking it out takes a peak total "
        f"hook load of <b>{load.total:.2f} t</b> ({load.weight_factor:.3f} x W): the submerged "
        f"weight {force.submerged_weight:.2f} t (weight, trapped water, less buoyancy) and the "
        f"breakout force {force.force:.2f} t ({html.escape(model)}), held until the hull is "
        f"{force.clear:g} m clear of its bed, on a line through ({_xyz(problem, load.point)}) m. "
        "Each crane's share is its tension with the plan's preload held and the body level, "
        "the hooks moved together as a rigid pattern by the hook shift below, at its worst "
        "over every hook within the plan's hook tolerance (the same closed form as in the "
        "box: what the errors add is in the table); the larger of it "
        "and the worst in the box is the crane's static input to the design-load chain above. "
        "The breakout hook load (tension + rigging, no dynamic factor) is checked against the "
        "chart SWL.</p>"
    )
    rows = [
        (
            c.label,
            c.crane,
            f"{c.breakout:.2f}",
            f"{w:.2f}",
            f"{r:.2f}",
            f"{h:.2f}",
            f"{c.swl:.1f}",
            f"{100 * h / c.swl:.1f}",
            f"{d:+.3f}",
            f"{max(c.worst, c.nominal):.2f}",
            c.governs,
            "ok" if check.ok else "FAIL",
        )
        for c, w, r, h, d, check in zip(
            design.cranes, case.hook_widening, case.rigging, case.hook_loads, case.hook_shift, case.checks
        )
    ]
    table = _table(
        [
            "lug",
            "crane",
            "tension at breakout [t]",
            "of it, hook errors [t]",
            "rigging [t]",
            "breakout hook load [t]",
            "chart SWL [t]",
            "hook load / SWL [%]",
            "hook shift [m]",
            "worst in the box [t]",
            "static input",
            "check",
        ],
        rows,
        "Breakout from the seabed: each crane's held share of the peak load",
        text_columns=(1, 10, 11),
    )
    return ["<h3>Breakout from the seabed</h3>", text, table]


def _vessel_section(plan):
    """The floating cranes: each vessel's heel, trim, tip drop and the ballast to set."""
    if not plan.vessels:
        return []
    text = (
        "<p>Each floating crane's vessel heaves, heels and trims under its hook load (small-angle "
        "hydrostatics); the planner puts it in series with the rope, so the tensions, the worst "
        "case and the hook tolerance above are those of the coupled stiffness. The tip drop is the "
        "extra hoist the crane needs as the load comes on. The levelling ballast (heeling, "
        "trimming moment; + heels starboard down, + trims bow down) set before the lift leaves the "
        "vessel level at the planned load; the worst heel and trim are over the tolerance box, "
        "the CG envelope and the hook errors with that ballast set, as is the freeboard of the lowest "
        "deck corner (heave, heel and trim; where the vessel gives its freeboard and size).</p>"
    )
    rows = [
        (
            v.label,
            v.crane,
            f"{v.offset[0]:.1f}, {v.offset[1]:.1f}",
            f"{v.load:.2f}",
            f"{v.heave:.3f}",
            f"{v.heel:+.3f}",
            f"{v.trim:+.3f}",
            f"{v.tip_drop:.3f}",
            f"{v.ballast[0]:+.0f}, {v.ballast[1]:+.0f}",
            f"{v.worst_heel:.3f}" + ("" if v.max_heel is None else f" / {v.max_heel:g}"),
            f"{v.worst_trim:.3f}" + ("" if v.max_trim is None else f" / {v.max_trim:g}"),
            "-" if v.freeboard is None else f"{v.freeboard:.3f} / {v.min_freeboard:g}",
        )
        for v in plan.vessels
    ]
    table = _table(
        [
            "lug",
            "crane",
            "tip offset x, y [m]",
            "level tension [t]",
            "heave [m]",
            "heel [deg]",
            "trim [deg]",
            "tip drop [m]",
            "levelling ballast [t m]",
            "worst heel / limit [deg]",
            "worst trim / limit [deg]",
            "worst freeboard / minimum [m]",
        ],
        rows,
        "Crane vessels at the level tension (tip offset: forward, to starboard of the flotation centre)",
        text_columns=(1, 2, 8, 9, 10, 11),
    )
    return ["<h3>Crane vessels</h3>", text, table]


def _design_details(plan):
    """Where each crane's worst cases occur, the chain's factors with their sources, lug loads."""
    design = plan.design_loads
    if design.chain is None:
        return []
    worst = _table(
        [
            "lug",
            "crane",
            "worst in box [t]",
            "heel, trim [deg]",
            "CG x, y, z [m]",
            "at the rules' tilt [t]",
            "tilt [deg]",
            "tilt axis x, y, z [-]",
            "CG at tilt x, y, z [m]",
        ],
        [
            (
                c.label,
                c.crane,
                f"{c.worst:.2f}",
                *_where(plan, c.worst_at),
                f"{c.tilt.load:.2f}",
                f"{c.tilt.tilt:.2f}",
                ", ".join(f"{v:+.3f}" for v in plan.in_file_frame(c.tilt.axis)),
                _where(plan, Scenario(0.0, 0.0, c.tilt.cog_offset))[1],
            )
            for c in plan.capacity
        ],
        "Where each crane's worst static load occurs (CG position in the file's frame)",
        text_columns=(1,),
    )
    results = [c.design for c in plan.capacity]
    factors = _table(
        ["factor", *(f"{r.crane} [-]" for r in results), "applies to", "source"],
        [
            (
                f.name.replace("_", " "),
                *(f"{r.factors[k].value:.4f}" for r in results),
                f.applies_to,
                f.source,
            )
            for k, f in enumerate(results[0].factors)
        ],
        "Design-load factors and where they come from",
        text_columns=(0, len(results) + 1, len(results) + 2),
        ropes=(1, len(results)),
    )
    lugs = _table(
        [
            "lug",
            "crane",
            "static share [t]",
            "vertical design [t]",
            "sling angle [deg]",
            "leg load [t]",
            "lug design load [t]",
            "lug capacity [t]",
            "check",
        ],
        [
            (
                lug.lug,
                lug.crane,
                f"{lug.share:.2f}",
                f"{lug.vertical:.2f}",
                f"{lug.sling_angle:.1f}",
                f"{lug.leg_load:.2f}",
                f"{lug.design_load:.2f}",
                "-" if lug.check is None else f"{lug.check.limit:.1f}",
                "not given" if lug.check is None else ("ok" if lug.check.ok else "FAIL"),
            )
            for r in results
            for lug in r.lugs
        ],
        "Lug design loads (leg load x consequence factor; checked where the candidate gives a capacity)",
        text_columns=(1,),
    )
    return [worst, factors, lugs]


# -- scene file of the chosen plan ---------------------------------------------------------
def plan_scene_toml(plan):
    """The chosen plan as a scene file for ``liftplan solve``, in the planning file's frame:
    :attr:`~liftplan.planner.plans.held.Plan.named_scene` written by the one scene writer.

    Lugs carry their candidate names and each crane table names its crane (and, in a comment,
    the planned lug label the report uses); ``liftplan solve`` on it gives the plan's level
    tensions (keyed by candidate name).
    """
    problem = plan.problem
    header = (
        f"Written by liftplan plan: the chosen lugs of {json.dumps(problem.name)}.",
        "`liftplan solve` on this file gives the plan's level tensions.",
        f"Coordinates in the planning file's frame: {FRAME_TEXT[plan.frame]}.",
    )
    notes = {plan.lugs[label]: f"{plan.cranes[label]} (planned lug {label})" for label in plan.labels}
    return with_water(scene_toml(plan.named_scene, header=header, crane_notes=notes), problem.in_water)


def render(plan):
    """The report page and the plan's scene file of a held-preload plan: (HTML, TOML) text."""
    return render_html(plan), plan_scene_toml(plan)


def _reproducing(plan):
    """How to get this plan again: the software, the search asked for and what ended it."""
    problem, stats = plan.problem, plan.stats
    machine_bound = stats.stopped in ("time_limit", "interrupted")
    rows = [
        ("software", f"liftplan {__version__}", "-"),
        ("search asked for ([plan] search)", problem.search, "-"),
        ("search that ran", stats.method, "-"),
        ("relative gap asked for ([plan] gap)", f"{100 * problem.gap:g}", "%"),
        (
            "time limit ([plan] time_limit)",
            "none" if problem.time_limit is None else f"{problem.time_limit:g}",
            "s",
        ),
        (
            "work limit ([plan] work_limit)",
            "none" if problem.work_limit is None else f"{problem.work_limit:d}",
            "-",
        ),
        ("what ended the search", stats.stopped, "-"),
        ("rules code ([rules] code)", problem.rules.code_title, "-"),
    ]
    table = _table(
        ["quantity", "value", "unit"], rows, "Reproducing this plan", full=False, text_columns=(0, 1)
    )
    # a work limit is refused with rope-length ranges (the outer search takes a time limit only)
    work = (
        " A work limit ([plan] work_limit) instead of the time limit gives the same plan on any machine."
        if plan.lengths is None
        else " Rope-length ranges take no work limit: no time limit gives the same plan on any machine."
    )
    why = (
        "The search ended at its time limit (or was interrupted): the same file on a faster or "
        "slower machine, or under another load, may end at another point and give another plan "
        "and gap." + work
        if machine_bound
        else "The search ended on its own terms (the optimum proved, the gap met, the local "
        "search's end, or its work limit): the same planning file with this liftplan version "
        "gives this plan again."
    )
    return [table, f"<p>{why}</p>"]


#: The held plan's report, section by section (after the title block and the status line):
#: each ``section(plan) -> list of HTML``. A new section is one function and one row here.
SECTIONS = (
    _recommendation,
    _basis,
    lengths_section,
    _checks,
    _figures,
    _alternatives,
    _assumptions,
    _appendix,
    _reproducing,
)
