"""The rope models: the one casadi model of a body on ropes, and its solvers.

Modules:

* :mod:`.model` - the casadi model: attitude kinematics, equilibrium of vertical ropes, rope
  elasticity, hinged lift points (:func:`~.model.rope_model`).
* :mod:`.vertical` - the vertical-rope models ``rigid``, ``paper-elastic`` and ``elastic``.
* :mod:`.inclined` - inclined ropes: the 6-DOF body with crane tips in the world.
* :mod:`.rigging` - sling sets and spreader bars: the ``rigging`` model.
* :mod:`.acceptance` - the one acceptance every answer passes (residual, stability, upright).
* :mod:`.compiled` - casadi Functions compiled to C once and reused across processes.

The entry that picks among them (and the water models) is :func:`liftplan.model.solve.solve`.
"""
