"""A move stage on a pivot: the body on vertical elastic ropes with one point on the ground.

The pivot is a body point resting on the ground, rigid and in compression only. The ropes hang
vertically from the boom tips at heights H_k, each carrying T_k = k_k max(0, H_k - z_k - l0_k)
(k_k = EA_k / l0_k, z_k the lug's height). In contact, the body can only turn about the pivot:
its pose is R = Rx(heel) Ry(trim) about the pivot P (:func:`liftplan.model.frames.rotation` at
yaw 0; the vertical ropes and the vertical reaction exert no moment about z), and the two
moments about the pivot's horizontal axes fix heel and trim::

    sum_k T_k r_k = W r_g,      r = (R (p - P)) in plan,

solved by Newton (a central-difference Jacobian, from the last state's pose). The reaction is
the rest of the weight, W - sum T_k; where it would be negative the body lifts off and hangs on
its ropes alone (:class:`~liftplan.model.sequence.move.MoveModel` then solves it by
``liftplan solve``). Every force is vertical, so the pivot needs no friction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from liftplan.model.errors import EquilibriumNotFound

#: Newton's iterations and its tolerance on the moments (x W x the body's size).
NEWTON_STEPS = 60
MOMENT_TOL = 1e-13
#: Largest Newton step  [rad].
MOST_STEP = 0.2


def attitude(heel, trim):
    """R = Rx(heel) Ry(trim) (radians): :func:`liftplan.model.frames.rotation` at yaw 0."""
    ch, sh, ct, st = math.cos(heel), math.sin(heel), math.cos(trim), math.sin(trim)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, ch, -sh], [0.0, sh, ch]])
    ry = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    return rx @ ry


@dataclass(frozen=True)
class PivotState:
    """The body resting on its pivot.

    Parameters
    ----------
    heel, trim : float  [deg]
        Its attitude from where the stage started (about the pivot).
    rotation : ndarray (3, 3)
    tensions : ndarray (n,)  [t]
    reaction : float  [t]
        The ground's push at the pivot (< 0: the body would lift off; not a state then).
    """

    heel: float
    trim: float
    rotation: np.ndarray
    tensions: np.ndarray
    reaction: float


class OnPivot:
    """The statics of a body on vertical ropes and a pivot, all in the stage's base frame.

    Parameters
    ----------
    weight : float  [t]
    cog : array (3,)  [m]
    lugs : array (n, 3)  [m]
        The ropes' lugs where the stage starts (world).
    pivot : array (3,)  [m]
        The pivot's point where the stage starts: where the ground holds it.
    stiffness, rope_lengths : array (n,)  [t/m], [m]
    """

    def __init__(self, weight, cog, lugs, pivot, stiffness, rope_lengths):
        self.weight = float(weight)
        self.pivot = np.asarray(pivot, dtype=float)
        self.cog = np.asarray(cog, dtype=float) - self.pivot
        self.lugs = np.asarray(lugs, dtype=float) - self.pivot
        self.k = np.asarray(stiffness, dtype=float)
        self.l0 = np.asarray(rope_lengths, dtype=float)
        self.size = max(float(np.ptp(np.vstack([self.lugs, self.cog, [0.0, 0.0, 0.0]]), axis=0).max()), 1.0)
        self._last = np.zeros(2)

    def tensions(self, heights, rot):
        """Each rope's tension at attitude ``rot`` with the tips at ``heights``  [t]."""
        z = self.pivot[2] + self.lugs @ rot[2]
        return self.k * np.maximum(np.asarray(heights, dtype=float) - z - self.l0, 0.0)

    def _moments(self, heights, u):
        rot = attitude(*u)
        t = self.tensions(heights, rot)
        return t @ (self.lugs @ rot[:2].T) - self.weight * (rot[:2] @ self.cog)

    def energy(self, heights, u):
        """Potential energy of the ropes' stretch and the weight at attitude ``u``  [t m]."""
        rot = attitude(*u)
        stretch = np.maximum(
            np.asarray(heights, dtype=float) - self.pivot[2] - self.lugs @ rot[2] - self.l0, 0.0
        )
        return 0.5 * float(self.k @ (stretch * stretch)) + self.weight * float(rot[2] @ self.cog)

    def solve(self, heights, where):
        """The body on its pivot with the tips at ``heights``: :class:`PivotState`.

        Newton from the last state's attitude; where it does not converge (a rope going slack
        or coming taut on the way, the body rolling onto another rope), the least potential
        energy from there (BFGS), polished by Newton.

        Raises
        ------
        EquilibriumNotFound
            The moments about the pivot are not balanced (``where`` names the state).
        """
        u = self._newton(heights, self._last.copy())
        if u is None:
            least = minimize(
                lambda v: self.energy(heights, v), self._last, method="BFGS", options={"gtol": 1e-10}
            )
            u = self._newton(heights, least.x)
        if u is None:
            raise EquilibriumNotFound(
                f"{where}: the body on its pivot: no attitude balances the moments about the pivot; "
                "expected ropes on both sides of the centre of gravity's line through the pivot"
            )
        self._last = u
        rot = attitude(*u)
        t = self.tensions(heights, rot)
        return PivotState(math.degrees(u[0]), math.degrees(u[1]), rot, t, self.weight - float(t.sum()))

    def _newton(self, heights, u):
        """The attitude (rad) where the moments about the pivot balance, from ``u``, or None."""
        tol = MOMENT_TOL * self.weight * self.size
        for _ in range(NEWTON_STEPS):
            f = self._moments(heights, u)
            if np.linalg.norm(f) < tol:
                break
            h = 1e-7
            jac = np.column_stack(
                [
                    (self._moments(heights, u + h * e) - self._moments(heights, u - h * e)) / (2 * h)
                    for e in np.eye(2)
                ]
            )
            try:
                step = np.linalg.solve(jac, -f)
            except np.linalg.LinAlgError:
                step = np.linalg.lstsq(jac, -f, rcond=None)[0]
            scale = max(1.0, float(np.max(np.abs(step))) / MOST_STEP)
            u = u + step / scale
        else:
            return None
        return u

    def height(self, rot, position):
        """The pivot point's height when the body hangs free at ``rot`` with its base-frame
        origin at ``position`` (world)  [m]."""
        return float(position[2] + rot[2] @ (self.pivot))


__all__ = ["OnPivot", "PivotState", "attitude"]
