"""Crane vessels under several cranes over a hull in water: the ropes' coupled stiffness.

A vessel under two cranes or more couples their tips (one hook's load drops the other's tip),
so no rope-by-rope series stiffness holds. With the vessels' hydrostatics linear the tips drop
by C T (:meth:`~liftplan.model.statics.floating.Fleet.compliance`), and over a set S of taut
ropes the tensions are T_S = G_S s0_S, G_S = (D_S^-1 + C_SS)^-1 (D = EA / l0, s0 the stretch
with the tips at rest; :class:`~liftplan.model.statics.floating.CoupledRopeModel`): the hull
in water is solved on the clipped-mesh model with those tensions (:class:`WaterSetup` with a
``coupling``), exact, with no unknowns added. The taut set is found around the solve: a rope in
compression is taken slack (one at a time), a slack rope whose own stretch s0 - C T is
positive taken taut, and the hull solved again until the set holds. A hull in water may rest
on the ground or float with fewer than three ropes taut, or none.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from liftplan.model.errors import EquilibriumNotFound
from liftplan.model.frames import rotation_matrix
from liftplan.model.statics.floating import coupled_stiffness, next_taut
from liftplan.model.water.equilibrium import WaterSetup, settle, solve_in_water

#: What the crane values are read for (the messages of a missing one name it).
MODEL = "hydrostatic (a hull hanging from ropes)"


class CoupledWater:
    """A :class:`WaterSetup` whose ropes carry the coupled stiffness of their vessels, and the
    taut set it is made for (kept from one solve to the next: a load curve's hoists).

    Parameters
    ----------
    scene : Scene
        With ``hull``, ``water`` and crane vessels.
    fleet : Fleet
        The scene's (:func:`~liftplan.model.statics.floating.scene_fleet`).
    """

    def __init__(self, scene, fleet):
        dry = dataclasses.replace(
            scene, cranes=tuple(dataclasses.replace(c, vessel=None) for c in scene.cranes)
        )
        self.scene = dry
        self.compliance = fleet.compliance()
        self.length = np.array(dry.crane_values("rope_length", MODEL))
        self.ea = np.array(dry.crane_values("EA", MODEL))
        self.boom = np.array(dry.crane_values("boom_height", MODEL))
        self.taut = np.ones(dry.n)
        self.setup = WaterSetup(dry, coupling=self._coupling())

    def _coupling(self):
        return coupled_stiffness(self.length, self.ea, self.compliance, self.taut > 0.0)

    def stretch(self, eq, hoist):
        """Each rope's own stretch s0 - C T at an equilibrium, the hooks raised by ``hoist``  [m]."""
        pose = eq.pose
        heights = (rotation_matrix(pose.heel, pose.trim, pose.yaw) @ self.scene.lug_points().T)[2]
        free = self.boom + hoist - heights - pose.lift_height - self.length
        return free - self.compliance @ np.array(list(eq.tensions.values()))

    def hold(self, solve, hoist=0.0):
        """``solve()`` (an Equilibrium, or a Settled with its ``eq``) on taut sets until one holds.

        Raises
        ------
        EquilibriumNotFound
            ``solve`` found none, or the taut set did not settle.
        """
        tried = []
        for _ in range(2 * self.scene.n + 2):
            self.setup.couple(self._coupling())
            state = solve()
            eq = getattr(state, "eq", state)
            tensions = np.array(list(eq.tensions.values()))
            now = next_taut(self.taut, tensions, self.stretch(eq, hoist))
            if np.array_equal(now, self.taut):
                return state
            tried.append(self.taut)
            self.taut = now
        names = self.scene.lug_names
        sets = "; ".join(", ".join(n for n, t in zip(names, taut) if t) or "none" for taut in tried[-3:])
        raise EquilibriumNotFound(
            f"crane vessels: the taut ropes did not settle in {len(tried)} sets (last: {sets}); expected "
            "a lift whose ropes can be told taut or slack"
        )


def solve_coupled_in_water(scene, fleet, method="newton"):
    """The hull in water on ropes coupled by their vessels (the ``hydrostatic`` model).

    Returns
    -------
    Equilibrium
        Without the vessels' states (the caller adds them from its tensions).
    """
    water = CoupledWater(scene, fleet)
    setup = water.setup
    if method == "newton" and setup.breakout is not None:
        return water.hold(lambda: settle(setup)).eq
    return water.hold(lambda: solve_in_water(water.scene, method=method, setup=setup))
