"""Hook and lug loads against the turning angle, each load's maximum marked (matplotlib)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

_MM = 1 / 25.4
#: Width of a label as a share of the panel's span: labels that would overlap are stacked.
LABEL_REACH = 0.2
#: Height of one label (two lines of the small font) as a share of the largest load shown.
LABEL_HEIGHT = 0.15
_FONT = 7.5
_SMALL = 6.5


def sequence_figure(result):
    """One row of two panels per stage: hook loads (and ground reaction) | lug loads.

    Each curve is drawn from the adaptive samples the maxima were searched on; each maximum
    is a marker labelled with its value and angle; grey bands are angles that are not held.

    Parameters
    ----------
    result : liftplan.model.sequence.SequenceResult

    Returns
    -------
    matplotlib.figure.Figure
    """
    rows = len(result.stages)
    fig = Figure(figsize=(170 * _MM, (62 * rows + 8) * _MM), layout="constrained")
    axes = fig.subplots(rows, 2, squeeze=False)
    for (left, right), stage in zip(axes, result.stages):
        curves, st = stage.curves, stage.stage
        move = st.kind == "move"
        angle = curves["angle"]
        for ax, kinds, title in (
            (left, ("hook", "ground"), "hook loads"),
            (right, ("lug", "lug_out"), "lug loads (dashed: out of plane)"),
        ):
            colours, labels = {}, []
            shown = [(k, p) for k, p in stage.maxima.items() if k.split(":")[0] in kinds]
            x_span = float(np.ptp(angle)) or 1.0
            y_span = max([p.value for _, p in shown] + [1.0])
            for key, peak in shown:
                kind, _, name = key.partition(":")
                style = "--" if kind == "lug_out" else "-"
                label = name or "ground reaction"
                line = ax.plot(
                    angle,
                    curves[key],
                    style,
                    lw=1.0,
                    color=colours.get(name),
                    label=label if kind != "lug_out" else None,
                )[0]
                colours.setdefault(name, line.get_color())
                if kind == "lug_out" and peak.value < 0.05:  # would read 0.0 t: no label
                    continue
                ax.plot([peak.angle], [peak.value], "o", ms=3.5, color=line.get_color())
                labels.append((peak, line.get_color()))
            top = _label(ax, labels, float(np.min(angle)), x_span, y_span, move)
            for r in stage.not_held:
                ax.axvspan(r.start, r.stop, color="0.85", lw=0, zorder=0)
            ax.set_title(f"{st.where}: {title}", fontsize=_FONT + 0.5)
            ax.set_xlabel(
                "stage parameter s (boom tips moved) [-]"
                if move
                else f"turning angle about body {st.axis} [deg]",
                fontsize=_FONT,
            )
            ax.set_ylabel("load [t]", fontsize=_FONT)
            ax.tick_params(labelsize=_SMALL)
            ax.grid(True, lw=0.3)
            ax.margins(x=0.1)
            ax.set_ylim(bottom=0.0, top=max(1.0, ax.get_ylim()[1] * 1.22, top))
            ax.legend(fontsize=_SMALL, loc="best")
    return fig


def _label(ax, labels, lo, x_span, y_span, move):
    """Label each maximum with its value and where it is; labels that would overlap are
    stacked upwards (the lowest first). Returns the top of the highest label (data units)."""
    placed, top = [], 0.0
    height = LABEL_HEIGHT * y_span
    for peak, colour in sorted(labels, key=lambda item: item[0].value):
        right = peak.angle > lo + 0.8 * x_span  # near the right edge: the label to the left
        # the label's extent along the axis
        a = peak.angle - (LABEL_REACH * x_span if right else 0.0)
        b = a + LABEL_REACH * x_span
        y = peak.value + 0.02 * y_span
        moved = True
        while moved:
            moved = False
            for a0, b0, y0 in placed:
                if a < b0 and a0 < b and y0 - height < y < y0 + height:
                    y, moved = y0 + height, True
        placed.append((a, b, y))
        top = max(top, y + 1.2 * height)
        ax.annotate(
            f"{peak.value:.1f} t\n@ s = {peak.angle:.2f}"
            if move
            else f"{peak.value:.1f} t\n@ {peak.angle:.1f}°",
            (peak.angle, peak.value),
            xytext=(peak.angle + (-0.01 if right else 0.01) * x_span, y),
            ha="right" if right else "left",
            textcoords="data",
            fontsize=_SMALL - 0.5,
            color=colour,
            va="bottom",
        )
    return top
