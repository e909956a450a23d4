"""Where a hull in water is and what state it is in: its height range and the state word.

Plain functions of a solved pose, shared by the clipped-mesh solvers
(:mod:`liftplan.model.water.equilibrium`) and the given-attitude water forces
(:mod:`liftplan.model.water.held`).
"""

from __future__ import annotations

import numpy as np


def hull_heights(hull, rot, zo):
    """Lowest and highest point of the hull envelope above the water plane  [m].

    Parameters
    ----------
    hull : Hull
    rot : numpy.ndarray, shape (3, 3)
        Attitude.
    zo : float  [m]
        Height of the body-frame origin above the water plane.
    """
    z = (np.asarray(rot) @ hull.vertices.T)[2] + zo
    return float(z.min()), float(z.max())


def water_state(grounded, bottom, top, crane_load, weight):
    """The state word of a hull in water (:attr:`Afloat.STATES`).

    Parameters
    ----------
    grounded : bool
        The ground contact carries load.
    bottom, top : float  [m]
        Lowest and highest point of the envelope above the water plane.
    crane_load : float  [t]
        Sum of the rope tensions.
    weight : float  [t]
        Scale: a crane load below 1e-9 of it is none (a slack rope carries exactly 0).
    """
    if grounded:
        return "grounded"
    if bottom >= 0.0:
        return "clear"
    if crane_load <= 1e-9 * weight:
        return "afloat"
    return "hanging submerged" if top < 0.0 else "piercing the surface"
