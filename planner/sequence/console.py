"""The console table of a swept sequence: one row per reported angle, then the maxima."""

from __future__ import annotations


def sequence_table(result):
    """The text ``liftplan sequence`` prints.

    Parameters
    ----------
    result : liftplan.model.sequence.SequenceResult
    """
    seq = result.sequence
    lines = [seq.name or "lift sequence", f"weight W = {seq.body.weight:.2f} t; loads in t, angles in deg"]
    for stage in result.stages:
        st = stage.stage
        move = st.kind == "move"
        if move:
            how = "move: " + "; ".join(_move_text(m) for m in st.moves) + f", s = 0 -> 1 in {st.steps} steps"
        else:
            how = f"{st.kind} about body {st.axis}, {st.start:g} -> {st.stop:g} deg by {st.step:g}"
        at = " at s =" if move else " at"
        unit = "" if move else " deg"
        if st.pivot is not None:
            how += f", pivot at [{', '.join(f'{v:g}' for v in st.pivot)}]"
        lines += ["", f"stage {st.where}: {how}; cranes {', '.join(st.cranes)}"]
        cranes = list(st.cranes)
        lugs = list(stage.states[0].lug_loads)
        head = (
            (["s", "heel", "trim"] if move else ["angle", "tilt"])
            + cranes
            + (["ground"] if st.pivot is not None else [])
        )
        head += [f"{lug} (out)" for lug in lugs]
        rows, notes = [], []
        for state in stage.states:
            if move:
                row = [f"{state.angle:.3f}", f"{state.heel:.3f}", f"{state.trim:.3f}"]
            else:
                row = [f"{state.angle:.2f}", f"{state.tilt:.2f}"]
            row += [f"{state.hook_loads[c]:.2f}" for c in cranes]
            if st.pivot is not None:
                row.append(f"{state.ground_reaction:.2f}")
            row += [f"{state.lug_loads[g].load:.1f} ({state.lug_loads[g].out_of_plane:.1f})" for g in lugs]
            note = "" if state.held else "NOT HELD"
            if state.slack:
                note = (note + " slack: " + ", ".join(state.slack)).strip()
            rows.append(row)
            notes.append(note)
        widths = [max(len(h), *(len(r[k]) for r in rows)) + 2 for k, h in enumerate(head)]
        lines.append("".join(f"{h:>{w}}" for h, w in zip(head, widths)) + "  note")
        for row, note in zip(rows, notes):
            lines.append(("".join(f"{v:>{w}}" for v, w in zip(row, widths)) + f"  {note}").rstrip())
        lines.append(f"maxima over the whole stage ({stage.evaluations} equilibria):")
        for key, peak in stage.maxima.items():
            kind, _, name = key.partition(":")
            label = {
                "hook": "hook load",
                "ground": "ground reaction",
                "lug": "lug load",
                "lug_in": "lug load in plane",
                "lug_out": "lug load out of plane",
                "leg": "sling leg",
            }[kind]
            lines.append(
                f"  {label} {name}".rstrip()
                + f": {peak.value:.3f} t{at} {peak.angle:.4f}{unit} (bound {peak.bound:.3f} t)"
            )
        for key, travel in stage.hook_travel.items():
            lines.append(
                f"  hook {key}: rises {travel['rise']:+.2f} m (height {travel['lowest']:.2f} to "
                f"{travel['highest']:.2f} m), travels up to {travel['plan']:.2f} m in plan"
            )
        for r in stage.slack:
            lines.append(
                f"  slack: {r.what} from{at.removeprefix(' at')} {r.start:.4f} to {r.stop:.4f}{unit}"
            )
        for r in stage.not_held:
            lines.append(f"  angle NOT held from {r.start:.4f} to {r.stop:.4f} deg")
    return "\n".join(lines)


def _move_text(move):
    """One crane's move in words."""
    text = f"{move.crane}"
    if move.to is not None:
        text += " to [" + ", ".join(f"{v:g}" for v in move.to) + "] m"
    if move.hoist or move.to is None:
        text += f" hoist {move.hoist:+g} m"
    return text


def lug_plan_lines(plan):
    """The planned lug set: which candidate each lug goes on, and how it was found.

    Parameters
    ----------
    plan : liftplan.model.sequence.lugplan.LugPlan
    """
    best = plan.best
    lines = [
        "lugs planned: " + ", ".join(f"{lug} on {cand}" for lug, cand in best.lugs.items()),
        f"  worst design lug load {best.worst:.2f} t ({best.where}); every check met: "
        f"{'yes' if best.ok else 'NO'}",
        f"  {plan.options} assignments: {plan.swept} swept, {plan.options - plan.refused - plan.swept} "
        f"ruled out by their grid bound, {plan.refused} not a valid sequence; "
        f"{plan.seconds:.1f} s",
    ]
    for k, option in enumerate(plan.ranking[1:], start=2):
        lines.append(
            f"  {k}. "
            + ", ".join(f"{lug} on {cand}" for lug, cand in option.lugs.items())
            + f": {option.worst:.2f} t"
            + ("" if option.ok else " (a check fails)")
        )
    return "\n".join(lines) + "\n"
