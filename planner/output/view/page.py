"""The 3D view as HTML: a stand-alone page, or a section of the report.

The page is offline: plotly's own ``plotly.min.js`` (shipped inside the plotly package) is
inlined, and nothing is fetched when it is opened. The page carries its geometry as JSON in
``<script type="application/json" id="liftplan-scene">`` (:meth:`LiftView.scene_json`).
"""

from __future__ import annotations

import html
import json

import plotly.io as pio

from liftplan.planner.output.view.figure import lift_figure

#: The element id of the plot's ``<div>``.
DIV_ID = "liftplan-view"
#: The element id of the embedded geometry (fixed by the outside contract).
SCENE_ID = "liftplan-scene"
#: plotly's configuration: no logo, images saved as PNG.
CONFIG = {"displaylogo": False, "toImageButtonOptions": {"format": "png"}}


def scene_element(view):
    """The ``<script type="application/json" id="liftplan-scene">`` element of ``view``."""
    text = json.dumps(view.scene_json(), allow_nan=False)
    text = text.replace("<", "\\u003c")  # "</script>" in a name cannot end the element
    return f'<script type="application/json" id="{SCENE_ID}">{text}</script>'


def fragment(view, figure=None):
    """The plot (plotly's script inlined) and the geometry element, to put in a page's body."""
    figure = lift_figure(view) if figure is None else figure
    plot = pio.to_html(
        figure,
        full_html=False,
        include_plotlyjs=True,
        include_mathjax=False,
        div_id=DIV_ID,
        config=CONFIG,
        default_height="720px",
        default_width="100%",
    )
    return f"{plot}\n{scene_element(view)}"


def page(view, figure=None):
    """The stand-alone HTML page of ``view``."""
    title = html.escape(view.title)
    states = "".join(f"<li>{k + 1}: {html.escape(s.name)}</li>" for k, s in enumerate(view.states))
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>{title}</title>
<style>body {{ font-family: sans-serif; margin: 1em; }} p, ul {{ font-size: 10pt; }}</style>
</head>
<body>
<h1 style="font-size: 14pt">{title}</h1>
<p>Coordinates in the file's frame ({html.escape(view.frame)}), lengths in m, forces in t.
Ropes coloured by {html.escape(view.colour_title)}; hover over a rope, lug or crane for its name
and value. States (the slider below the plot):</p>
<ul>{states}</ul>
{fragment(view, figure)}
</body></html>
"""
