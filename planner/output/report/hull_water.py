"""The report's part on the flexible hull and the start in water: which model governed."""

from __future__ import annotations

import html

from liftplan.planner.output.console.hull_water import hull_water_lines


def hull_water_section(plan):
    """A heading and the console's lines (which hull governs each ranked set, the measured
    change, the start in water, the re-ranking's certificate); empty without ``[hull] EI`` or
    ``[water]``."""
    lines = hull_water_lines(plan)
    if not lines:
        return []
    body = "<br>".join(html.escape(line.strip()) for line in lines)
    return ["<h3>Flexible hull and the start in water</h3>", f"<p>{body}</p>"]
