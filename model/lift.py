"""Lifting a hull off the seabed and through the waterline: the load curve.

Every hook rises by the hoist s (boom raised or rope hauled in: the same for the rope's
stretch). At each s the equilibrium is solved on the clipped-hull model of
:mod:`liftplan.model.water`, started from the previous step's pose (continuation):
grounded while the contact carries load, hanging once the ground reaction would go
negative (lift-off), then through the surface as the buoyancy is lost. A step that finds
no equilibrium is kept in the curve as a failed step with its reason; it never gets
numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import EquilibriumNotFound, InvalidScene
from .frames import rotation_matrix
from .water import Start, WaterSetup, solve_in_water


@dataclass(frozen=True)
class LoadCurve:
    """Crane loads, attitude and water forces against hoist.

    Parameters
    ----------
    lugs : tuple of str
    hoist : numpy.ndarray, shape (k,)  [m]
        Hoists that solved.
    tensions : numpy.ndarray, shape (k, n)  [t]
    heel, trim : numpy.ndarray, shape (k,)  [deg]
    buoyancy : numpy.ndarray, shape (k,)  [t]
    ground_reaction : numpy.ndarray, shape (k,)  [t]
        0 once lifted off (and without a ground contact).
    state : tuple of str
        ``grounded``, ``afloat`` (in the water, free of the ground) or ``clear``.
    failed : tuple of (float, str)
        Hoists [m] with no equilibrium found, and why.
    weight : float  [t]
    """

    lugs: tuple[str, ...]
    hoist: np.ndarray
    tensions: np.ndarray
    heel: np.ndarray
    trim: np.ndarray
    buoyancy: np.ndarray
    ground_reaction: np.ndarray
    state: tuple[str, ...]
    failed: tuple[tuple[float, str], ...]
    weight: float

    @property
    def max_load(self):
        """(tension [t], lug, hoist [m]) of the largest rope load on the curve."""
        k, i = np.unravel_index(int(np.argmax(self.tensions)), self.tensions.shape)
        return float(self.tensions[k, i]), self.lugs[i], float(self.hoist[k])

    @property
    def lift_off(self):
        """First hoist [m] at which the hull is free of the ground (None if never)."""
        free = [h for h, s in zip(self.hoist, self.state) if s != "grounded"]
        return float(free[0]) if free else None

    def rows(self):
        """One dict per solved hoist (for CSV / JSON)."""
        out = []
        for k, h in enumerate(self.hoist):
            row = {"hoist": float(h)}
            row.update({f"T_{name}": float(t) for name, t in zip(self.lugs, self.tensions[k])})
            row.update(heel=float(self.heel[k]), trim=float(self.trim[k]),
                       buoyancy=float(self.buoyancy[k]), ground_reaction=float(self.ground_reaction[k]),
                       state=self.state[k])
            out.append(row)
        return out

    def to_json(self):
        load, lug, at = self.max_load
        return {
            "lugs": list(self.lugs),
            "weight": self.weight,
            "max_load": {"tension": load, "lug": lug, "hoist": at},
            "lift_off": self.lift_off,
            "curve": self.rows(),
            "failed": [{"hoist": h, "reason": r} for h, r in self.failed],
        }


def default_stop(scene):
    """A hoist that takes the whole hull 1 m clear of the water, from the scene's pose  [m]."""
    rot = rotation_matrix(scene.attitude.heel, scene.attitude.trim, scene.attitude.yaw)
    heights = (rot @ scene.hull.vertices.T)[2] + scene.attitude.lift_height
    return float(scene.water.level - heights.min() + 1.0)


def load_curve(scene, stop=None, step=0.25):
    """The load curve of a lift from the scene's pose.

    Parameters
    ----------
    scene : Scene
        Hull, water, vertical ropes (boom heights, rope lengths, EA at hoist 0), and
        usually a ground contact.
    stop : float, optional  [m]
        Last hoist; default :func:`default_stop`.
    step : float  [m]

    Returns
    -------
    LoadCurve
    """
    if scene.hull is None or not scene.n:
        raise InvalidScene("lift: expected a scene with [hull], [water] and three or more cranes")
    stop = default_stop(scene) if stop is None else float(stop)
    if not (step > 0 and np.isfinite(step)) or not stop > 0:
        raise InvalidScene(f"lift: hoist to {stop:g} m in steps of {step:g} m; expected both > 0")
    count = int(np.floor(stop / step + 1e-9)) + 1
    if count > 100_000:
        raise InvalidScene(f"lift: {count} steps; expected at most 100000 (a larger step)")
    setup = WaterSetup(scene)
    start = None
    rows, failed, states = [], [], []
    for hoist in np.linspace(0.0, step * (count - 1), count):
        try:
            eq = solve_in_water(scene, setup=setup, start=start, hoist=hoist)
        except EquilibriumNotFound as err:
            failed.append((float(hoist), str(err)))
            continue
        a = eq.afloat
        start = Start(eq.pose.lift_height - scene.water.level,
                      rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw))
        rows.append([hoist, *eq.tensions.values(), eq.pose.heel, eq.pose.trim, a.buoyancy,
                     a.ground_reaction or 0.0])
        states.append(a.state)
    if not rows:
        raise EquilibriumNotFound(f"lift: no hoist step solved; first failure: {failed[0][1]}")
    data = np.array(rows)
    n = scene.n
    return LoadCurve(
        lugs=scene.lug_names, hoist=data[:, 0], tensions=data[:, 1 : 1 + n], heel=data[:, 1 + n],
        trim=data[:, 2 + n], buoyancy=data[:, 3 + n], ground_reaction=data[:, 4 + n],
        state=tuple(states), failed=tuple(failed), weight=scene.body.weight,
    )
