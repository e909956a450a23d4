"""The planned lift's forward model as the watch uses it: the elastic rope model of
:mod:`liftplan.model.statics.model`, its parameters set from a :class:`WatchBasis` and an
unknown state, and its sensitivities.

The state a watch estimates is ``theta = [W, x_c, y_c, z_c, e_1 .. e_n]``: the weight [t], the
CG (body frame, ``z-up``) [m] and each hook's height error e_i [m] (the boom tip at H_i + e_i,
H_i the planned height). Hook moves m_i [m] add to the errors. The pose and tensions come
from the model's Newton solve (its energy fallback when Newton's answer is not accepted); the
derivatives of the tensions and of the pose with respect to the state come from the model's
Jacobians through the implicit-function theorem (:attr:`RopeModel.elastic_sensitivity`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import casadi as ca
import numpy as np

from liftplan.model.errors import EquilibriumNotFound
from liftplan.model.statics.acceptance import RESIDUAL_TOL, judge
from liftplan.model.statics.model import rope_model


@dataclass(frozen=True)
class ForwardState:
    """The lift at one state.

    Parameters
    ----------
    lift : float  [m]
        Height of the body-frame origin.
    heel, trim : float  [deg]
    tensions : numpy.ndarray (n,)  [t]
    gain : numpy.ndarray (n + 2, 4 + n)
        d(T [t], heel [deg], trim [deg]) / d(theta): rows the n tensions, heel and trim;
        columns W [t], the CG [m] and the hook errors [m].
    """

    lift: float
    heel: float
    trim: float
    tensions: np.ndarray
    gain: np.ndarray


class Forward:
    """The forward model of one watched lift (built once, solved at many states)."""

    def __init__(self, basis):
        self.basis = basis
        n = basis.n
        self.n = n
        self.model = rope_model(n)
        layout = self.model.layout
        self._p = np.concatenate(
            [
                [math.radians(basis.yaw)],
                np.asarray(basis.points, dtype=float).ravel(),
                basis.cog,
                [basis.weight],
                basis.boom_height,
                basis.rope_length,
                basis.EA,
                [basis.plan_diameter],
            ]
        )
        # where theta sits in the parameter vector: W, the CG, then the boom heights
        cog = 3 * n + 1
        self._columns = np.r_[cog + 3, cog : cog + 3, np.arange(layout.size)[layout.boom]]

    @property
    def nominal(self):
        """The plan's own state: planned weight and CG, no hook error."""
        return np.concatenate([[self.basis.weight], self.basis.cog, np.zeros(self.n)])

    def params(self, theta):
        p = self._p.copy()
        p[self._columns[:4]] = theta[:4]
        p[self._columns[4:]] += theta[4:]
        return p

    def solve(self, theta):
        """The pose, tensions and their sensitivities at ``theta``.

        Raises
        ------
        EquilibriumNotFound
            When the model finds no stable upright equilibrium there.
        """
        theta = np.asarray(theta, dtype=float)
        p = self.params(theta)
        x, tensions, _, residual, minors = self.model.elastic_solver(p)
        if not self._accepted(x, residual, minors, theta[0]):
            start = np.asarray(
                self.model.energy_solver(x0=self.model.elastic_start(ca.DM(p)), p=ca.DM(p))["x"]
            ).ravel()
            x, tensions, _, residual, minors = self.model.elastic_polish(start, p)
            if not self._accepted(x, residual, minors, theta[0]):
                raise EquilibriumNotFound(
                    f"the ropes cannot hold the body at weight {theta[0]:.4g} t, CG "
                    f"({', '.join(f'{v:.3g}' for v in theta[1:4])}) m with those hook errors: no stable "
                    "upright equilibrium"
                )
        n = self.n
        size = self.model.layout.size
        _, dt_dx, dt_dp, dr_dx, dr_dp = self.model.elastic_sensitivity(x, p)
        dt_dx = dt_dx.reshape(3, n).T
        dt_dp = dt_dp.reshape(size, n).T
        dr_dx = dr_dx.reshape(3, 3).T
        dr_dp = dr_dp.reshape(size, 3).T
        cols = self._columns
        dx = -np.linalg.solve(dr_dx, dr_dp[:, cols])  # the pose's response, (3, 4 + n)
        gain = np.vstack([dt_dp[:, cols] + dt_dx @ dx, np.degrees(dx[1:3])])
        return ForwardState(
            lift=float(x[0]),
            heel=math.degrees(x[1]),
            trim=math.degrees(x[2]),
            tensions=np.asarray(tensions, dtype=float),
            gain=gain,
        )

    def _accepted(self, x, residual, minors, weight):
        scale = self.basis.plan_diameter
        r = np.abs(np.asarray(residual, dtype=float))
        worst = max(r[0], r[1] / scale, r[2] / scale)
        if not (math.isfinite(worst) and weight > 0):
            return False
        return judge(worst / weight, x[1], x[2], minors=minors).ok and worst <= RESIDUAL_TOL * weight
