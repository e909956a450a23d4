"""The report of a plan chosen for the hull girder (:class:`~liftplan.planner.plans.strength.StrengthPlan`):
HTML page (A4 print), the scene file ``liftplan solve`` reads and the girder figures.

The strength-optimal plan is reported beside the spread-optimal plan of the same limits, so an
engineer sees what each costs the other. Every coordinate is in the planning file's frame
(the body's x, along which M and Q are drawn, is the same axis in both frames).
"""

from __future__ import annotations

import html
import json
import math

import numpy as np

from liftplan.model import solve
from liftplan.model.frames import FRAME_TEXT
from liftplan.model.scene.writer import scene_toml
from liftplan.model.strength import hull_girder
from liftplan.planner.output.figures.strength import strength_figure
from liftplan.planner.output.report import page as report_page
from liftplan.planner.output.report import slings as slings_report
from liftplan.planner.output.report.page import FONT_PT, figure_size, range_text
from liftplan.planner.output.report.view import view_section
from liftplan.planner.plans.strength import StrengthContext, objective_weights
from liftplan.planner.search.scenarios import LugSet, Scenario
from liftplan.planner.search.strength import GirderLoads, State, exact_curves, force_attitude

CONTROL = {
    "force": "force (strand jacks: each holds its force; the body hangs where the forces balance it)",
    "hoist": "hoist (boom heights: the level preload held, a tilt from the hooks moving as a plane)",
}
#: Stations per girder curve in the figures (on top of the breakpoints the curves are exact
#: between; a plotted curve, not a check: the peaks are found exactly).
SAMPLES = 700

ASSUMPTIONS = {
    "force": (
        "Each lifting point holds its planned force at every attitude (strand jack, force "
        "control); the body hangs where the forces balance its weight, tilted by atan(d / "
        "(F_z - z_G)) for a CG offset d, F_z the force centre's height.",
        "The states are the CG envelope's vertices, each at its equilibrium attitude; that tilt "
        "must stay within the tolerance box (a constraint on the forces).",
        "The hull's flexibility does not change the jack forces, so M and Q do not depend on EI.",
    ),
    "hoist": (
        "Ropes hang vertically and the body is rigid; the level preload is held by the boom "
        "heights and a heel or trim comes from the hooks moving as a plane (held-preload model).",
        "The states are a 21 x 21 heel-trim grid over the tolerance box for every CG-envelope "
        "vertex; hook errors within +-hook_tolerance enter each peak at its worst sign.",
    ),
    "both": (
        "M and Q are the hull girder's: the weight curve (corrected to close on W and the CG), "
        "the lift forces at their lugs' x, the component along the body of an inclined force "
        "as a couple; M > 0 sagging. The peaks are found exactly along the body (piecewise "
        "cubics), not on a grid.",
        "The spread-optimal plan is searched with the same limits (min_tension, the rules' "
        "limits, the code margin) and the objective max - min tension; its peaks are evaluated "
        "on the same states.",
    ),
}


def _table(headers, rows, caption, **options):
    return report_page.table(headers, rows, caption, **options)


def _xyz(plan, point):
    return ", ".join(f"{v:.2f}" for v in plan.in_file_frame(point))


def _state_text(plan, s, peak):
    state = s.states[peak.state]
    offset = plan.in_file_frame(state["cog_offset"])
    return (f"{state['heel']:+.2f}, {state['trim']:+.2f}", ", ".join(f"{v:+.2f}" for v in offset))


# -- the girder along the body ---------------------------------------------------------------
def set_curves(plan, s, girder_points=None):
    """M and Q of a lug set in every state it was checked in.

    Parameters
    ----------
    plan : StrengthPlan
    s : StrengthSet
    girder_points : callable, optional
        ``girder_points(indices, scenarios) -> PointLoads``: the lift points' loads on the
        girder (slings: each hook's legs); default single ropes at the candidates.

    Returns
    -------
    states : list of State
    tensions : (k, n)  [t]   each state's tensions (force control: the held forces)
    curves : list of (shear, moment)   exact piecewise curves [t, t m], hook errors not added
    """

    p = plan.problem
    points = p.points[list(s.indices)]
    offsets = np.array([st["cog_offset"] for st in s.states], dtype=float)
    if plan.control == "force":
        ups = force_attitude(points, s.preload, p.body.weight, p.body.cog, offsets)[0]
        states = [State(tuple(u), tuple(o)) for u, o in zip(ups, offsets)]
        tensions = np.repeat(s.preload[None], len(states), axis=0)
    else:
        ctx = StrengthContext(p)
        scenarios = [Scenario(st["heel"], st["trim"], tuple(st["cog_offset"])) for st in s.states]
        tensions = LugSet(p, s.indices, s.cranes).tensions(s.preload, scenarios)
        states = [State(tuple(ctx.up(sc.heel, sc.trim)), sc.cog_offset) for sc in scenarios]
        if girder_points is not None:
            points = girder_points(s.indices, scenarios)
    loads = GirderLoads(p.body)
    return (
        states,
        tensions,
        [exact_curves(loads, points, t, st, k) for k, (t, st) in enumerate(zip(tensions, states))],
    )


def _level_curves(plan, s, girder_points=None):
    p = plan.problem
    level = State(tuple(StrengthContext(p).up(0.0, 0.0)))
    points = p.points[list(s.indices)]
    if girder_points is not None:
        points = girder_points(s.indices, [Scenario(0.0, 0.0)])
    return exact_curves(GirderLoads(p.body), points, s.preload, level)


def _load_x(plan, s, girder_points=None):
    """Where a set's loads act along the body  [m]: its lugs (slings: its legs' lugs)."""
    if girder_points is None:
        return plan.problem.points[list(s.indices), 0]
    return girder_points(s.indices, [Scenario(0.0, 0.0)]).x


def girder_figure(plan, girder_points=None):
    """Shear force and bending moment along the body of the strength-optimal plan (its range
    over every state, level with the nominal CG, its worst state) beside the spread-optimal
    plan, each panel with the allowable envelope shaded; drawn at the report's print width.
    ``girder_points`` as :func:`set_curves` (slings: the hooks' legs).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    p = plan.problem
    x0, x1 = p.body.weight_curve[0][0], p.body.weight_curve[-1][0]
    plans = tuple(
        entry
        for entry in (
            ("strength-optimal (the plan)", plan.chosen, "tab:blue"),
            ("spread-optimal", plan.spread_plan, "tab:orange"),
        )
        if entry[1] is not None  # a plan Ctrl-C stopped may have no spread-optimal partner
    )
    at = [_load_x(plan, s, girder_points) for _, s, _ in plans]
    stations = np.union1d(np.linspace(x0, x1, SAMPLES), np.concatenate(at))
    xs = np.sort(np.concatenate([stations - 1e-9, stations + 1e-9]))  # jumps drawn vertical
    fig = Figure(figsize=figure_size(190.0), layout="constrained")
    shear_ax, moment_ax = fig.subplots(2, 1, sharex=True)
    envelopes = {0: p.strength.bending_moment, 1: p.strength.shear_force}
    for name, s, color in plans:
        _, _, curves = set_curves(plan, s, girder_points)
        level = _level_curves(plan, s, girder_points)
        for ax, which, scale in ((moment_ax, 0, 1e3), (shear_ax, 1, 1.0)):
            values = np.array([c[1 - which](xs) for c in curves])
            peak = s.bending if which == 0 else s.shear
            if len(curves) > 1:
                ax.fill_between(
                    xs, values.min(axis=0) / scale, values.max(axis=0) / scale, color=color, alpha=0.25, lw=0
                )
            ax.plot(
                xs,
                level[1 - which](xs) / scale,
                color=color,
                lw=1.2,
                label=f"{name}: level, nominal CG (band: every state)",
            )
            worst = curves[peak.state][1 - which]
            ax.plot(
                xs,
                worst(xs) / scale,
                color=color,
                lw=0.8,
                ls="--",
                label=f"{name}: state of its peak |{'M' if which == 0 else 'Q'}|",
            )
            sides = worst(np.array([peak.x - 1e-9, peak.x + 1e-9]))  # a jump at a lug: either side
            signed = float(sides[np.argmax(np.abs(sides))])
            ax.plot(
                [peak.x],
                [np.copysign(peak.value, signed if signed != 0 else 1.0) / scale],
                "o",
                color=color,
                ms=4,
                label=f"peak {peak.value:.0f} {'t m' if which == 0 else 't'} at x = {peak.x:.1f} m "
                f"({100 * peak.ratio:.0f} % of allowable)"
                if envelopes[which] is not None
                else f"peak {peak.value:.0f} {'t m' if which == 0 else 't'} at x = {peak.x:.1f} m",
            )
    for ax, which, scale, unit in ((moment_ax, 0, 1e3, "1000 t m"), (shear_ax, 1, 1.0, "t")):
        envelope = envelopes[which]
        if envelope is not None:
            ex, ev = np.array(envelope).T
            limit = np.interp(xs, ex, ev) / scale
            ax.fill_between(
                xs, -limit, limit, color="tab:green", alpha=0.10, lw=0, label="allowable (inside the band)"
            )
            ax.plot(xs, limit, color="tab:green", lw=0.7)
            ax.plot(xs, -limit, color="tab:green", lw=0.7)
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_ylabel(
            ("bending moment M" if which == 0 else "shear force Q") + f" [{unit}]", fontsize=FONT_PT
        )
        ax.grid(True, lw=0.3)
        ax.tick_params(labelsize=FONT_PT)
        ax.legend(
            fontsize=FONT_PT - 1.5,
            loc="upper center",
            bbox_to_anchor=(0.5, -0.08 if which == 1 else -0.12),
            ncols=2,
            frameon=False,
        )
    # lifting points of the plan along the bottom axis
    for (_, _, color), xs_loads in zip(plans, at):
        for x in xs_loads:
            moment_ax.axvline(x, color=color, lw=0.4, alpha=0.5, ymax=0.04 if color == "tab:blue" else 0.08)
    moment_ax.set_xlabel("body x [m] (forward); ticks at the bottom: lifting points", fontsize=FONT_PT)
    fig.suptitle(
        "Hull girder: shear force and bending moment of the plan (M > 0 sagging)", fontsize=FONT_PT + 1
    )
    return fig


def forces_figure(plan):
    """The lifting forces along the body, strength-optimal beside spread-optimal (port and
    starboard at one station side by side), over the weight per length."""
    from matplotlib.figure import Figure

    p = plan.problem
    fig = Figure(figsize=figure_size(75.0), layout="constrained")
    ax = fig.subplots()
    wc = np.array(p.body.weight_curve)
    station = np.diff(np.unique(np.round(p.points[:, 0], 6))).min() if len(p.points) > 1 else 1.0
    width = 0.2 * station
    for k, (name, s, color) in enumerate(
        (("strength-optimal", plan.chosen, "tab:blue"), ("spread-optimal", plan.spread_plan, "tab:orange"))
    ):
        pts = p.points[list(s.indices)]
        side = np.where(pts[:, 1] > 0, 1.0, -1.0) if np.ptp(pts[:, 1]) > 0 else np.zeros(len(pts))
        x = pts[:, 0] + (2 * k - 1.5 + 0.5 * (side + 1)) * width
        ax.bar(
            x,
            s.preload,
            width=width,
            color=color,
            alpha=0.85 if k == 0 else 0.6,
            label=f"{name} ({len(pts)} points)",
        )
    ax.set_ylabel("force per lifting point [t]", fontsize=FONT_PT)
    ax.set_xlabel(
        "body x [m] (forward); at each station the left bar of a pair is starboard", fontsize=FONT_PT
    )
    weight = ax.twinx()
    weight.fill_between(wc[:, 0], wc[:, 1], color="0.5", alpha=0.15, lw=0)
    weight.set_ylabel("weight per length [t/m] (grey)", fontsize=FONT_PT)
    weight.set_ylim(0, 3 * wc[:, 1].max())
    for a in (ax, weight):
        a.tick_params(labelsize=FONT_PT)
    ax.grid(True, lw=0.3, axis="y")
    ax.legend(fontsize=FONT_PT - 0.5, loc="upper left", frameon=False)
    return fig


def _columns(entries):
    """Legend columns under a panel at the print width: 2, or 4 for a station key."""
    return 2 if entries <= 6 else 4


def _print_width(fig):
    """The solve's girder figure redrawn at the print width: legends under their panels.

    160 mm tall, and 3.2 mm more per legend row (a station key): with its caption it leaves
    room on its page for the assumptions that follow it (at 215 mm two of them went onto a
    page of their own).
    """

    rows = sum(
        math.ceil(len(legend.get_texts()) / _columns(len(legend.get_texts())))
        for legend in (ax.get_legend() for ax in fig.axes)
        if legend is not None
    )
    fig.set_size_inches(*figure_size(160.0 + 3.2 * rows))
    if fig._suptitle is not None:
        fig._suptitle.set_fontsize(FONT_PT + 1)
    bottom = fig.axes[len(fig.axes) - 2] if len(fig.axes) > 3 else fig.axes[-1]  # the twin axis last
    for ax in fig.axes:
        legend = ax.get_legend()
        ax.tick_params(labelsize=FONT_PT)
        ax.yaxis.label.set_fontsize(FONT_PT)
        ax.xaxis.label.set_fontsize(FONT_PT)
        if legend is not None:
            handles, labels = legend.legend_handles, [t.get_text() for t in legend.get_texts()]
            legend.remove()
            # a station key (stems numbered) takes four columns
            ax.legend(
                handles,
                labels,
                fontsize=FONT_PT - 1,
                loc="upper center",
                ncols=_columns(len(labels)),
                bbox_to_anchor=(0.5, -0.2 if ax is bottom else -0.06),
                frameon=False,
            )
    return fig


# -- the scene file -------------------------------------------------------------------------
def plan_scene_toml(plan):
    """The strength-optimal plan as a scene file for ``liftplan solve``, in the file's frame:
    :attr:`~liftplan.planner.plans.strength.StrengthPlan.scene` (force control: the ``rigid``
    model, all but three forces held; hoist control: the ``elastic`` model at the planned boom
    heights) written by the one scene writer, each crane commented with its planned lug label.
    """
    p = plan.problem
    header = (
        f"Written by liftplan plan: the strength-optimal lugs of {json.dumps(p.name)}.",
        "`liftplan solve` on this file gives the plan's level "
        + (
            "forces (rigid model, all but three held)."
            if plan.control == "force"
            else "tensions (elastic model, the planned boom heights)."
        ),
        f"Coordinates in the planning file's frame: {FRAME_TEXT[p.frame]}.",
    )
    notes = {name: f"planned lug {label}" for label, name in plan.lugs.items()}
    return scene_toml(plan.scene, header=header, crane_notes=notes)


def solved_level(plan):
    """(scene, equilibrium, girder): the plan's scene (:attr:`StrengthPlan.scene`) solved, the
    level state of the plan as ``liftplan solve`` gives it from plan_scene.toml."""
    scene = plan.scene
    eq = solve(scene)
    return scene, eq, hull_girder(scene, eq)


# -- HTML -------------------------------------------------------------------------------------
def _comparison(plan):
    """Rows of the strength-optimal plan beside the spread-optimal one, and a sentence of what
    each costs the other."""
    c, o = plan.chosen, plan.spread_plan
    rows = []

    def row(name, a, b, fmt, unit):
        ratio = "" if not (b and np.isfinite(b)) else f"{a / b:.3f}"
        rows.append((name, format(a, fmt), format(b, fmt), ratio, unit))

    row("peak |M| / allowable", c.bending.ratio, o.bending.ratio, ".3f", "-")
    rows.append(("... at x", f"{c.bending.x:.2f}", f"{o.bending.x:.2f}", "", "m"))
    row("... |M| there", c.bending.value, o.bending.value, ".0f", "t m")
    row("peak |Q| / allowable", c.shear.ratio, o.shear.ratio, ".3f", "-")
    rows.append(("... at x", f"{c.shear.x:.2f}", f"{o.shear.x:.2f}", "", "m"))
    row("... |Q| there", c.shear.value, o.shear.value, ".0f", "t")
    row("tension spread, level (max - min)", c.spread, o.spread, ".1f", "t")
    row("worst tension spread over the states", c.worst_spread, o.worst_spread, ".1f", "t")
    row("lowest tension over the states", c.tension_range[0], o.tension_range[0], ".1f", "t")
    row("highest tension over the states", c.tension_range[1], o.tension_range[1], ".1f", "t")
    weights = objective_weights(plan.problem)
    value_o = weights[0] * o.bending.ratio + weights[1] * o.shear.ratio
    row("objective value (the plan's objective)", c.value, value_o, ".4f", "-")
    rows.append(("lifting points", " ".join(c.names), " ".join(o.names), "", "-"))
    text = (
        f"<p>The strength-optimal plan takes the peak of |M| / allowable to {c.bending.ratio:.3f} "
        f"against {o.bending.ratio:.3f} ({_percent(c.bending.ratio, o.bending.ratio)}) and the "
        f"peak of |Q| / allowable to {c.shear.ratio:.3f} against {o.shear.ratio:.3f} "
        f"({_percent(c.shear.ratio, o.shear.ratio)}), each at the section where the ratio peaks (not "
        f"necessarily where |M| or |Q| is largest); it costs a worst tension spread of "
        f"{c.worst_spread:.1f} t against {o.worst_spread:.1f} t and a highest tension of "
        f"{c.tension_range[1]:.1f} t against {o.tension_range[1]:.1f} t.</p>"
    )
    return rows, text


def _percent(a, b):
    return "n/a" if b == 0 else f"{100 * (a / b - 1):+.0f} %"


def _allowables(problem):
    s = problem.strength
    curves = [c for c in (s.bending_moment, s.shear_force) if c is not None]
    xs = np.unique(np.concatenate([np.array(c)[:, 0] for c in curves]))
    rows = []
    for x in xs:
        cell = []
        for curve in (s.bending_moment, s.shear_force):
            cell.append("-" if curve is None else f"{np.interp(x, *np.array(curve).T):.0f}")
        rows.append((f"{x:.2f}", *cell))
    return _table(
        ["x [m]", "allowable |M| [t m]", "allowable |Q| [t]"],
        rows,
        "Allowable bending moment and shear force (linear between the stations, the end values held beyond)",
        full=False,
    )


def render_html(plan, today=None):
    """The strength plan's report as one HTML page, laid out for A4 print.

    Parameters
    ----------
    plan : StrengthPlan
    today : datetime.date, optional
        The date printed when ``[report] date`` is not given (default: today).
    """
    p, c = plan.problem, plan.chosen
    name = p.name or "Lift plan"
    force = plan.control == "force"
    candidates = dict(zip(p.names, p.candidates))
    swl = p.reach[1][list(c.indices), list(c.cranes)]  # each lug's own crane's chart
    unit = "force" if force else "tension"
    heights = plan.boom_heights
    lugs = _table(
        [
            "lug",
            "candidate (bulkhead)",
            "crane",
            "position x, y, z [m]",
            f"level {unit} [t]",
            *([] if force else ["boom height H [m]"]),
            "SWL [t]",
            "level / SWL [%]",
        ],
        [
            (
                label,
                f"{n} ({candidates[n].bulkhead})" if candidates[n].bulkhead else n,
                c.crane_names[k],
                _xyz(plan, candidates[n].at),
                f"{c.preload[k]:.2f}",
                *([] if force else [f"{heights[label]:.3f}"]),
                f"{swl[k]:.1f}",
                f"{100 * c.preload[k] / swl[k]:.1f}",
            )
            for k, (label, n) in enumerate(plan.lugs.items())
        ],
        "Recommended lifting points and "
        + ("forces (each jack holds its force)" if force else "tensions, held by the boom heights"),
        text_columns=(1, 2),
    )
    heel_m, cog_m = _state_text(plan, c, c.bending)
    heel_q, cog_q = _state_text(plan, c, c.shear)
    summary = _table(
        ["quantity", "value", "unit"],
        [
            ("peak |M| / allowable over the states, exactly along the body", f"{c.bending.ratio:.3f}", "-"),
            ("... at x", f"{c.bending.x:.2f}", "m"),
            ("... |M| there", f"{c.bending.value:.1f}", "t m"),
            ("... in the state heel, trim", heel_m, "deg"),
            ("... with the CG offset (x, y, z)", cog_m, "m"),
            ("peak |Q| / allowable over the states", f"{c.shear.ratio:.3f}", "-"),
            ("... at x", f"{c.shear.x:.2f}", "m"),
            ("... |Q| there", f"{c.shear.value:.1f}", "t"),
            ("... in the state heel, trim", heel_q, "deg"),
            ("... with the CG offset (x, y, z)", cog_q, "m"),
            (f"{unit} spread, level (max - min)", f"{c.spread:.2f}", "t"),
            (f"worst {unit} spread over the states", f"{c.worst_spread:.2f}", "t"),
            (f"{unit} range over the states", f"{c.tension_range[0]:.2f} to {c.tension_range[1]:.2f}", "t"),
        ],
        "Plan summary" + ("" if force else " (hoist control: the peaks include the hook errors)"),
        full=False,
        text_columns=(0,),
    )
    weights = objective_weights(p)
    envelope = p.cog_envelope
    inputs = _table(
        ["quantity", "value", "unit"],
        [
            ("weight W", f"{p.body.weight:.2f}", "t"),
            ("weight W is", p.weight_basis_text, "-"),
            ("CG (nominal)", _xyz(plan, p.body.cog), "m"),
            (
                "CG envelope half-widths (x, y, z)",
                ", ".join(f"{abs(v):.2f}" for v in plan.in_file_frame(envelope.half_widths)),
                "m",
            ),
            ("CG envelope shape", envelope.shape, "-"),
            ("the plan keeps small", f"{p.objective}: {p.goal.text}", "-"),
            *(
                [("weights w_M, w_Q", f"{weights[0]:g}, {weights[1]:g}", "-")]
                if p.objective == "strength"
                else []
            ),
            ("control", CONTROL[plan.control], "-"),
            ("lifting points", p.cranes, "-"),
            ("candidate points", len(p.candidates), "-"),
            (
                "heel tolerance" + (" (a limit on the equilibrium tilt)" if force else ""),
                f"+-{p.heel_tolerance:g}",
                "deg",
            ),
            (
                "trim tolerance" + (" (a limit on the equilibrium tilt)" if force else ""),
                f"+-{p.trim_tolerance:g}",
                "deg",
            ),
            ("min tension", f"{p.min_tension:g}", "t"),
            *(
                []
                if force
                else [
                    ("hook-height tolerance", f"+-{p.hook_tolerance:g}", "m"),
                    *_crane_rows(p),
                ]
            ),
            ("lift height (body origin above datum)", f"{p.lift_height:g}", "m"),
        ],
        "Basis of the plan",
        full=False,
        text_columns=(0, 1),
    )
    rows, cost = _comparison(plan)
    comparison = _table(
        ["quantity", "strength-optimal (the plan)", "spread-optimal", "ratio strength / spread", "unit"],
        rows,
        "The strength-optimal plan beside the spread-optimal plan (same limits, same states)",
        text_columns=(0,),
    )
    checks = _table(
        ["check", "subject", "value", "limit", "unit", "result", "what the value is"],
        [
            (k.title, k.subject, k.shown("value"), k.shown("limit"), k.unit, "ok" if k.ok else "FAIL", k.note)
            for k in plan.checks
        ],
        "Every check of the plan",
        text_columns=(0, 1, 6),
    )
    scene, eq, girder = solved_level(plan)

    level = _print_width(strength_figure(scene, eq, girder))
    figs = [
        report_page.figure(
            forces_figure(plan),
            "lifting forces along the body",
            "The lifting forces along the body: the strength-optimal plan (blue) "
            "and the spread-optimal plan (orange), over the weight per length.",
        ),
        report_page.figure(
            girder_figure(plan),
            "shear force and bending moment",
            "Shear force (top) and bending moment (bottom) along the body: solid, "
            "level with the nominal CG; band, the range over every state the plan "
            "was checked in; dashed, the state of the peak; the allowable "
            "envelope shaded green."
            + ("" if force else " Hook errors are not drawn (they are in the peaks' values)."),
        ),
        report_page.figure(
            level,
            "the plan solved",
            "The plan's scene file (plan_scene.toml) solved by liftplan solve: "
            "loads, shear force and bending moment at level with the nominal CG.",
        ),
    ]
    info = p.report
    assumptions = ASSUMPTIONS[plan.control] + ASSUMPTIONS["both"]
    body = "\n".join(
        [
            report_page.title_block(
                info,
                name,
                f"Lift plan for the hull girder: {p.cranes} of "
                f"{len(p.candidates)} lifting points chosen by liftplan, "
                f"{plan.control} control",
                today,
            ),
            f"<p>All coordinates are in the planning file's frame: {html.escape(FRAME_TEXT[p.frame])}. "
            "Angles: heel &gt; 0 starboard down, trim &gt; 0 bow down. Forces in t (tonne-force), "
            "lengths in m, moments in t m.</p>",
            report_page.status(plan.checks),
            report_page.warnings(plan.problem),
            "<h2>1 Recommendation</h2>",
            lugs,
            summary,
            "<h2>2 Basis of the plan</h2>",
            inputs,
            _allowables(p),
            "<h2>3 Strength-optimal against spread-optimal</h2>",
            cost,
            comparison,
            "<h2>4 Checks to hand over</h2>",
            checks,
            f"<p>The scene file plan_scene.toml solves (liftplan solve) to the level {unit}s above: "
            f"peak |M| {girder.max_moment.value:.1f} t m at x = {girder.max_moment.x:.2f} m, peak |Q| "
            f"{girder.max_shear.value:.1f} t at x = {girder.max_shear.x:.2f} m at level with the "
            "nominal CG (the plan's peaks are the worst over every state).</p>",
            "<h2>5 Figures</h2>",
            *figs,
            *view_section(plan),
            "<h2>6 Assumptions</h2>",
            # one block: never a bullet or two alone on a page
            '<ul style="break-inside: avoid">'
            + "".join(f"<li>{html.escape(a)}</li>" for a in assumptions)
            + "</ul>",
            *_appendix(plan),
        ]
    )
    return report_page.document(
        name, body, report_page.running_header(info, name), report_page.running_footer(info)
    )


def _appendix(plan):
    """The optimality of both searches and where the peaks occur."""
    rows = []
    for label, stats, unit in (
        ("strength-optimal", plan.stats, "-"),
        ("spread-optimal", plan.spread_stats, "t"),
    ):
        fmt = "{:.6g}"
        rows += [
            (f"{label}: best value found", fmt.format(stats.best), unit),
            (f"{label}: lower bound (no lug set does better)", fmt.format(stats.lower_bound), unit),
            (f"{label}: gap", fmt.format(stats.gap), unit),
            (f"{label}: relative gap", f"{100 * stats.relative_gap:.4f}", "%"),
            (f"{label}: why the search ended", stats.stopped, "-"),
            (
                f"{label}: bound certified",
                "yes"
                if stats.certified
                else "no (candidates at different heights: attitudes by fixed point)",
                "-",
            ),
            (f"{label}: method", stats.method, "-"),
            (f"{label}: MIP solves, sets evaluated", f"{stats.rounds}, {stats.evaluated}", "-"),
            (f"{label}: search time", f"{stats.seconds:.2f}", "s"),
        ]
    optimality = _table(
        ["quantity", "value", "unit"],
        rows,
        "Optimality: how far each plan can be from the best of its objective",
        full=False,
        text_columns=(0, 1),
        keep=False,
    )
    c = plan.chosen
    states = (
        _table(
            ["state", "heel [deg]", "trim [deg]", "CG offset x, y, z [m]"],
            [
                (
                    k + 1,
                    f"{st['heel']:+.3f}",
                    f"{st['trim']:+.3f}",
                    ", ".join(f"{v:+.2f}" for v in plan.in_file_frame(st["cog_offset"])),
                )
                for k, st in enumerate(c.states)
            ],
            "The states the plan was checked in"
            + (" (the CG envelope's vertices at their equilibrium tilts)" if plan.control == "force" else ""),
            full=False,
            keep=False,
        )
        if len(c.states) <= 64
        else (
            f"<p>The plan was checked in {len(c.states)} states (a 21 x 21 heel-trim grid over the "
            "tolerance box for each CG-envelope vertex).</p>"
        )
    )
    return [
        '<h2 class="appendix">Engineering appendix</h2>',
        "<p>For the engineer checking the plan: how close each plan is proved to be to the best "
        "of its objective (the lower bound and the gap), and the states it was checked in.</p>",
        optimality,
        states,
    ]


def render(plan):
    """The report page and the scene file of a strength plan: (HTML, TOML) text; the page
    shows the plan's scene (the one the file holds) solved. On slings
    (:class:`~liftplan.planner.plans.strength_slings.StrengthSlingPlan`): the sling plan's page
    and rigging scene, with the strength search's section after the recommendation."""
    if hasattr(plan, "search"):
        page = slings_report.render_html(plan)
        marker = "<h2>2 Basis of the plan</h2>"
        assert page.count(marker) == 1  # the sling page's sections, as slings_report writes them
        page = page.replace(marker, "\n".join(sling_strength_section(plan)) + "\n" + marker)
        return page, slings_report.plan_scene_toml(plan)
    return render_html(plan), plan_scene_toml(plan)


def sling_strength_section(plan):
    """The strength search of a plan on slings, as HTML: what it chose among, the chosen hooks'
    peaks beside the spread-optimal hooks', and the girder along the body (each hook's legs
    loading their lugs)."""
    search = plan.search
    stats = search.stats
    if search.spread_plan is None:  # Ctrl-C came before the partner's search found a set
        c = search.chosen
        comparison = (
            f"<p>Peak |M| / allowable {c.bending.ratio:.3f} (|M| {c.bending.value:.0f} t m) at x = "
            f"{c.bending.x:.2f} m, peak |Q| / allowable {c.shear.ratio:.3f} "
            f"(|Q| {c.shear.value:.0f} t) at x = "
            f"{c.shear.x:.2f} m (the planner's model); no spread-optimal hooks to compare (the "
            "search was stopped before).</p>"
        )
        cost = ""
    else:
        rows, cost = _comparison(search)
        comparison = _table(
            ["quantity", "strength-optimal (the plan)", "spread-optimal", "ratio strength / spread", "unit"],
            [(r[0].replace("tension", "hook load"), *r[1:]) for r in rows],
            "The strength-optimal hooks beside the spread-optimal hooks (same limits, same states; "
            "the planner's model: legs of their lengths, hooks where their pairs hang them)",
            text_columns=(0,),
        )
    weights = objective_weights(search.problem)
    what = {
        "bending": "the worst |M| / allowable",
        "shear": "the worst |Q| / allowable",
        "strength": (
            f"{weights[0]:g} x the worst |M| / allowable + {weights[1]:g} x the worst |Q| / allowable"
        ),
    }[plan.objective]
    return [
        "<h2>Hull girder: the strength search</h2>",
        f"<p>The hooks were chosen for the hull girder: objective {html.escape(plan.objective)} "
        f"({html.escape(what)}), over {len(plan.rigs)} sling hooks. Each hook's tension loads "
        "the girder through its legs: at each state the sling's statics split it into leg forces "
        "at the lugs, whose vertical parts load the beam and whose axial parts act as their "
        "moment about the CG height (the axial force itself is not checked: the allowables are "
        "for M and Q). The search is a MIP over the hooks with each set's exact LP "
        f"({html.escape(stats.method)}): {stats.rounds} MIP solve(s), {stats.evaluated} set(s) "
        f"evaluated, lower bound {stats.lower_bound:.6g}, gap {stats.gap:.3g}, "
        f"{html.escape(stats.stopped)}. The plan's girder checks (bending_moment, shear_force in "
        "section 3) are the rigging model's at the states the plan holds, as liftplan solve "
        "gives them from plan_scene.toml.</p>",
        comparison,
        cost.replace("tension", "hook load"),
        report_page.figure(
            girder_figure(search, plan.girder_points),
            "shear force and bending moment",
            "Shear force (top) and bending moment (bottom) along the body, the planner's model: "
            "solid, level with the nominal CG; band, the range over every state the plan was "
            "checked in; dashed, the state of the peak; the allowable envelope shaded green. "
            "Hook errors are not drawn (they are in the peaks' values).",
        ),
    ]


def _crane_rows(problem):
    """The basis rows of the cranes' ropes: one pair for equal cranes, one row per crane of a
    fleet (its own rope, boom range and SWL or chart)."""
    fleet = problem.fleet
    if problem.equal_cranes:
        crane = fleet[0]
        return [
            ("rope EA, length l0", f"{crane.EA:.0f} t, {crane.rope_length:g} m", "-"),
            ("boom height range", range_text(crane.boom_min, crane.boom_max), "m"),
        ]
    rows = []
    for crane in fleet:
        capacity = (
            f"SWL {crane.swl:g} t"
            if crane.swl is not None
            else "chart " + ", ".join(f"{r:g} m: {w:g} t" for r, w in crane.load_chart)
        )
        rows.append(
            (
                f"crane {crane.name}",
                f"EA {crane.EA:.0f} t, l0 {crane.rope_length:g} m, boom "
                f"{range_text(crane.boom_min, crane.boom_max)} m, {capacity}",
                "-",
            )
        )
    return rows
