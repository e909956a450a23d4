"""Hull girder strength: shear force and bending moment of the body in a solved state.

Read this first. A body with a weight curve (``[body] weight_curve = [[x m, t/m], ...]``,
linear between points) is a beam along its own x axis. In any solved state — the
given-attitude models, ``elastic``, ``inclined``, ``rigging``, hanging in water or grounded —
the loads on that beam are its weight per length, the buoyancy per length of the clipped hull
at the solved attitude, water trapped in compartments, and the rope, sling-leg and ground
forces as point loads. :func:`hull_girder` integrates them exactly into the shear force Q(x)
and bending moment M(x) of the part aft of each section (CONTRACT.md's signs; M > 0 sags),
with their largest absolute values and where they are; :func:`strength_checks` checks them
against the allowable envelopes of ``[strength]``.

Modules, top-down:

* :mod:`.girder` — the loads of a solved state and the result (:class:`GirderForces`): how
  an inclined body is treated, the weight-curve correction, the closure.
* :mod:`.sections` — buoyancy per length of a hull mesh cut by the water plane, exact by
  x-sections (a box's sectional area x density, and any closed mesh).
* :mod:`.piecewise` — piecewise polynomials: exact running integrals with jumps, exact
  extrema (roots of the derivative) and worst ratio to an envelope.
* :mod:`.checks` — the ``bending_moment`` and ``shear_force`` checks.
* :mod:`.beam` — the flexible hull's finite elements (``[hull] EI``, ``GJ``): Hermite bending
  and linear torsion elements, consistent weight loads, the gauge.
* :mod:`.flexible` — the flexible hull on the elastic ropes: solved in the elastic model's
  Newton system (:class:`liftplan.model.strength.flexible_model.FlexibleRopeModel`), the 1 % rule that
  decides whether ``solve`` keeps the rigid hull, and the result (:class:`FlexibleHull`).

The solvers import :mod:`.flexible` only (lazily, for a scene with ``hull.EI``); the command
line calls the rest after a solve.
"""

from liftplan.model.strength.checks import strength_checks
from liftplan.model.strength.flexible import TENSION_CHANGE, FlexibleHull
from liftplan.model.strength.girder import GRID, GirderForces, PointLoad, hull_girder
from liftplan.model.strength.piecewise import Extreme, Piecewise

__all__ = [
    "GRID",
    "TENSION_CHANGE",
    "Extreme",
    "FlexibleHull",
    "GirderForces",
    "Piecewise",
    "PointLoad",
    "hull_girder",
    "strength_checks",
]
