"""A hull in water: its hydrostatics, equilibrium, the breakout from the seabed and the water
draining from its compartments as it rises.

Modules, bottom-up (each imports only those above it in this list):

* :mod:`.hydrostatics` - exact hydrostatics of a closed mesh cut by the water plane (casadi).
* :mod:`.afloat` - the casadi model of a hull in water on vertical elastic ropes.
* :mod:`.state` - a pose's height range and state word (clear, afloat, grounded, ...).
* :mod:`.held` - the water forces on a hull held at a given attitude (``rigid``,
  ``paper-elastic`` in water).
* :mod:`.breakout` - the pull beyond the submerged weight that frees a hull bedded in the
  seabed (a factor on the submerged weight, or the soil model of the US Navy's laboratory
  reports), and :func:`~.breakout.breakout_load`, the peak total hook load a planner checks.
* :mod:`.equilibrium` - the stranded, afloat or hanging hull on the clipped-mesh model
  (:func:`solve_in_water`, :func:`settle`), and the least model a scene needs
  (:func:`solve_hydrostatic`).
* :mod:`.draining` - water in compartments with openings: the inside level at a pose and
  the orifice flow (Torricelli) through each opening, integrated in time at a hoist speed.
* :mod:`.vessels` - crane vessels under several cranes: the ropes' coupled stiffness over a
  hull in water, and the taut set found around the solve.
* :mod:`.hull_vessels` - crane vessels given by their hulls: each one's clipped-mesh
  hydrostatics under her hook loads, solved with the body on its ropes (in air).

The load curve that puts them together is :mod:`liftplan.model.lift`.
"""

from liftplan.model.water.equilibrium import (
    BodyLoads,
    Settled,
    Start,
    WaterSetup,
    paper_newton,
    settle,
    solve_hydrostatic,
    solve_in_water,
    submerged_scene,
    unyaw,
)
from liftplan.model.water.state import hull_heights, water_state

__all__ = [
    "BodyLoads",
    "Settled",
    "Start",
    "WaterSetup",
    "hull_heights",
    "paper_newton",
    "settle",
    "solve_hydrostatic",
    "solve_in_water",
    "submerged_scene",
    "unyaw",
    "water_state",
]
