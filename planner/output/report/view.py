"""The report's 3D view: the interactive page on screen, two still images in print.

The section carries the same plot and ``liftplan-scene`` element as ``liftplan view`` writes
(:mod:`liftplan.planner.output.view.page`); the PDF (WeasyPrint runs no script) prints the
stills of the same scene instead (:mod:`liftplan.planner.output.view.stills`).
"""

from __future__ import annotations

import html

from liftplan.planner.output.report import page as report_page
from liftplan.planner.output.view.page import fragment
from liftplan.planner.output.view.states import plan_view
from liftplan.planner.output.view.stills import stills

#: On screen the interactive plot, in print the stills.
_STYLE = """<style>
@media print { .view-screen { display: none; } }
@media screen { .view-print { display: none; } }
</style>"""


#: Around the interactive plot: what :func:`for_print` takes out of the page the PDF is made
#: from (WeasyPrint runs no script, and parsing plotly's 4.8 MB of it took it 44 s against 2 s
#: without, once on the shared, loaded machine).
SCREEN_START, SCREEN_END = "<!-- liftplan-view: screen only -->", "<!-- /liftplan-view -->"


def for_print(page):
    """The report page without its interactive plot (what the PDF is made from)."""
    out, start = [], 0
    while (begin := page.find(SCREEN_START, start)) >= 0:
        end = page.find(SCREEN_END, begin)
        if end < 0:
            break
        out.append(page[start:begin])
        start = end + len(SCREEN_END)
    out.append(page[start:])
    return "".join(out)


def view_section(plan):
    """The 3D view of ``plan`` as report HTML (list of parts), under a level-3 heading."""
    view = plan_view(plan)
    states = "; ".join(f"{k + 1}: {html.escape(s.name)}" for k, s in enumerate(view.states))
    still = report_page.figure(
        stills(view),
        "3D view of the rigged lift",
        f"The rigged lift at its level state, from two viewpoints; ropes coloured by "
        f"{view.colour_title}; body: {view.body_source}. The HTML report shows it in 3D"
        + (" with the other states." if len(view.states) > 1 else "."),
    )
    heading = (
        "<h3>3D view</h3>"
        f"<p>The chosen lugs, the cranes' boom tips and the ropes coloured by "
        f"{html.escape(view.colour_title)}, in the planning file's frame. States: {states}.</p>"
    )
    return [
        _STYLE,
        f'{SCREEN_START}<div class="view-screen">{heading}{fragment(view)}</div>{SCREEN_END}',
        # in print the heading stays with its figure
        f'<div class="view-print" style="break-inside: avoid">{heading}{still}</div>',
    ]
