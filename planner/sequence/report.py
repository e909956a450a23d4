"""The sequence report: ``report.html`` (tables, figure, checks) and ``sequence.json``."""

from __future__ import annotations

import html
import json

from liftplan.planner.output.paths import make_parent, replaced
from liftplan.planner.output.report.page import document, figure, one_table
from liftplan.planner.sequence.figure import sequence_figure


def write_sequence_report(result, folder, payload):
    """Write ``report.html`` and ``sequence.json`` into ``folder`` (created if missing).

    Parameters
    ----------
    result : liftplan.model.sequence.SequenceResult
    folder : pathlib.Path
    payload : dict
        The JSON written (the same as ``--json`` prints).

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    folder.mkdir(parents=True, exist_ok=True)
    page, data = folder / "report.html", folder / "sequence.json"
    make_parent(page)
    with replaced(data) as tmp:
        tmp.write_text(json.dumps(payload, indent=1) + "\n", encoding="utf-8")
    with replaced(page) as tmp:
        tmp.write_text(_page(result, payload), encoding="utf-8")
    return [page, data]


def _page(result, payload):
    seq = result.sequence
    esc = html.escape
    parts = [f"<h1>{esc(seq.name or 'Lift sequence')}</h1>"]
    failed = [c for c in result.checks if not c.ok]
    parts.append(
        f'<p class="status{" fail" if failed else ""}">'
        + (
            f"{len(failed)} of {len(result.checks)} checks FAIL: "
            + esc("; ".join(f"{c.name} {c.subject}" for c in failed))
            if failed
            else f"All {len(result.checks)} checks pass."
        )
        + "</p>"
    )
    parts.append(
        "<p>Each state is the body's equilibrium at a held turning angle on plumb ropes (a slack "
        "rope carries nothing, a pivot only pushes); each maximum is the largest over the whole "
        "range of angles, found between the grid points as well. In a move stage the boom tips "
        "move and each state is the body's equilibrium on its elastic ropes; its states and "
        "maxima are at the stage parameter s (0: the start, 1: the end), not at an angle.</p>"
    )
    plan = payload.get("lug_plan")
    if plan is not None:
        rows = [[lug, cand] for lug, cand in plan["lugs"].items()]
        parts.append(
            one_table(
                ["lug", "candidate"],
                rows,
                f"Lugs planned: worst design lug load {plan['worst_design_lug_load']:.2f} t "
                f"({plan['where']}), {plan['options']} assignments, {plan['swept']} swept",
                full=False,
                text_columns=(0, 1),
            )
        )
    parts.append(figure(sequence_figure(result), "hook and lug loads against the turning angle"))
    for stage in result.stages:
        st = stage.stage
        move = st.kind == "move"
        what = "boom tips moved" if move else f"about body {st.axis}"
        at = "s [-]" if move else "angle [deg]"
        parts.append(f"<h2>Stage {esc(st.where)}: {esc(st.kind)} {what}</h2>")
        cranes = list(st.cranes)
        lugs = list(stage.states[0].lug_loads)
        head = [at, "heel / trim [deg]" if move else "tilt [deg]", *[f"{c} [t]" for c in cranes]]
        head += ["ground [t]"] if st.pivot is not None else []
        head += [f"{g} load / out of plane [t]" for g in lugs] + ["note"]
        rows = []
        for s in stage.states:
            tilt = f"{s.heel:.3f} / {s.trim:.3f}" if move else f"{s.tilt:.2f}"
            row = [f"{s.angle:.2f}", tilt, *[f"{s.hook_loads[c]:.2f}" for c in cranes]]
            row += [f"{s.ground_reaction:.2f}"] if st.pivot is not None else []
            row += [f"{s.lug_loads[g].load:.2f} / {s.lug_loads[g].out_of_plane:.2f}" for g in lugs]
            row.append(("" if s.held else "not held ") + ", ".join(s.slack))
            rows.append(row)
        parts.append(one_table(head, rows, "States on the grid", text_columns=(len(head) - 1,)))
        peaks = [[k, f"{p.value:.3f}", f"{p.angle:.4f}", f"{p.bound:.3f}"] for k, p in stage.maxima.items()]
        parts.append(
            one_table(
                ["load", "maximum [t]", f"at {at}", "bound [t]"],
                peaks,
                "Continuous maxima",
                text_columns=(0,),
            )
        )
        ranges = [[r.what, f"{r.start:.4f}", f"{r.stop:.4f}"] for r in (*stage.slack, *stage.not_held)]
        if ranges:
            parts.append(
                one_table(
                    ["what", f"from {at}", f"to {at}"],
                    ranges,
                    "Slack ropes and angles not held",
                    text_columns=(0,),
                )
            )
        design = [
            [
                lug.lug,
                f"{lug.share:.3f}",
                f"{lug.product:.4f}",
                f"{lug.design_load:.3f}",
                f"{lug.out_of_plane:.3f}",
            ]
            for r in stage.design.results
            for lug in r.lugs
        ]
        parts.append(
            one_table(
                ["lug", "largest load [t]", "factors", "design load [t]", "design out of plane [t]"],
                design,
                "The rules' design loads on this stage's maxima",
                text_columns=(0,),
            )
        )
    checks = [
        [c.name, c.subject, f"{c.value:.4g}", f"{c.limit:.4g}", c.unit, "ok" if c.ok else "FAIL", c.note]
        for c in result.checks
    ]
    parts.append("<h2>Checks</h2>")
    parts.append(
        one_table(
            ["check", "on", "value", "limit", "unit", "", "note"], checks, "Checks", text_columns=(0, 1, 5, 6)
        )
    )
    return document(seq.name or "Lift sequence", "\n".join(parts), header=seq.name or "Lift sequence")
