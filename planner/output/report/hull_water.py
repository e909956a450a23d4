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
    return [f"<h3>{heading(plan.problem)}</h3>", f"<p>{body}</p>"]


def heading(problem):
    """The section's title: what the planning file gave (the flexible hull, the start in water
    or both)."""
    flexible, water = problem.hull_stiffness is not None, problem.in_water is not None
    if flexible and water:
        return "Flexible hull and the start in water"
    return "Flexible hull" if flexible else "The start in water"


def with_water(text, in_water):
    """A written scene's text with the planning file's ``[hull]`` geometry and ``[water]`` added
    (``in_water`` None: unchanged): at the plan's lift height ``solve`` (its hydrostatic model)
    finds the hull clear of the water and the plan's tensions; lowered to the start height it
    gives the state in water."""
    if in_water is None:
        return text
    geometry = "\n".join(in_water.hull_lines)
    if "\n[hull]\n" in text:  # the stiffness was written: one [hull] table
        head, tail = text.split("\n[hull]\n", 1)
        keys, rest = (tail.split("\n\n", 1) + [""])[:2]
        text = f"{head}\n[hull]\n{keys}\n{geometry}\n" + (f"\n{rest}" if rest else "")
    else:
        text = text.rstrip("\n") + f"\n\n[hull]\n{geometry}\n"
    water = in_water.water
    return text.rstrip("\n") + f"\n\n[water]\ndensity = {water.density!r}\nlevel = {water.level!r}\n"
