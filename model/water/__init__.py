"""A hull in water: its equilibrium, the breakout from the seabed and the water draining
from its compartments as it rises.

* :mod:`.equilibrium` - the stranded, afloat or hanging hull on the clipped-mesh model
  (:func:`solve_in_water`, :func:`settle`), and the least model a scene needs
  (:func:`solve_hydrostatic`).
* :mod:`.breakout` - the pull beyond the submerged weight that frees a hull bedded in the
  seabed (a factor on the submerged weight, or the soil model of the US Navy's laboratory
  reports), and :func:`~.breakout.breakout_load`, the peak total hook load a planner checks.
* :mod:`.draining` - water in compartments with openings: the inside level at a pose and
  the orifice flow (Torricelli) through each opening, integrated in time at a hoist speed.

The load curve that puts them together is :mod:`liftplan.model.lift`.
"""

from liftplan.model.water.equilibrium import (  # noqa: F401 - the package's public names (and two the tests use)
    BodyLoads,
    Settled,
    Start,
    WaterSetup,
    _root,
    _rotation,
    hull_heights,
    paper_newton,
    settle,
    solve_hydrostatic,
    solve_in_water,
    submerged_scene,
    unyaw,
    water_state,
)
