"""What a plan keeps small: the objectives as one table.

An objective is a shape and a scaling of the tensions over the tolerance box (the heel and
trim box, the CG envelope, the hook errors):

* ``width`` - the largest max - min of s_i T_i over the box;
* ``peak`` - the largest max of s_i T_i;
* ``girder`` - the hull girder's worst |M| and |Q| against their allowables, weighted
  (planned by :mod:`liftplan.planner.plans.strength`);

with s_i = 1 (tonnes) or 1 / SWL_i (each crane's chart SWL at its radius: a fraction). The
search's programs, bounds and screening are written for the shapes and the scaling, never for
an objective's name, so a new objective of a known shape is one row of :data:`OBJECTIVES`
(and its name among ``[plan] objective``'s choices in ``docs/scene-files.md``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SHAPES = ("width", "peak", "girder")


@dataclass(frozen=True)
class Objective:
    """One objective.

    Parameters
    ----------
    name : str
        Its ``[plan] objective`` value.
    shape : {"width", "peak", "girder"}
    per_swl : bool
        Tensions scaled by 1 / SWL_i (``unit`` "-") rather than taken in tonnes ("t").
    text : str
        What it keeps small, in words (console and report).
    girder_weights : (float, float) or None
        (bending, shear) weights of a girder objective; None: the planning file's
        ``strength_weights`` (default (1, 1)).
    """

    name: str
    shape: str
    per_swl: bool
    text: str
    girder_weights: tuple[float, float] | None = None

    @property
    def unit(self):
        """The unit of the objective's value: ``"t"`` or ``"-"``."""
        return "-" if self.per_swl or self.shape == "girder" else "t"

    @property
    def peak(self):
        """The largest scaled tension (not a width)."""
        return self.shape == "peak"

    @property
    def girder(self):
        """Planned for the hull girder's strength."""
        return self.shape == "girder"

    def scale(self, swl):
        """s_i of each rope: ones, or 1 / SWL_i  [1/t or -]."""
        swl = np.asarray(swl, dtype=float)
        return 1.0 / swl if self.per_swl else np.ones_like(swl)


#: ``[plan] objective`` -> the objective.
OBJECTIVES = {
    o.name: o
    for o in (
        Objective("spread", "width", False, "max - min tension (spread)"),
        Objective("utilisation", "width", True, "max - min of T / SWL (utilisation spread)"),
        Objective(
            "reserve", "peak", True, "the largest T / SWL (reserve: load left before the first crane's SWL)"
        ),
        Objective("bending", "girder", False, "the worst |M| / allowable bending moment", (1.0, 0.0)),
        Objective("shear", "girder", False, "the worst |Q| / allowable shear force", (0.0, 1.0)),
        Objective("strength", "girder", False, "w_M x worst |M| / allowable + w_Q x worst |Q| / allowable"),
    )
}
#: The hull girder's objectives.
STRENGTH_OBJECTIVES = tuple(name for name, o in OBJECTIVES.items() if o.girder)
