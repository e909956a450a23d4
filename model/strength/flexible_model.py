"""The flexible hull's casadi model: the body as an elastic beam on the elastic ropes.

Kept apart from :mod:`liftplan.model.statics.model` (the rigid-body rope models), whose layout of
the rope parameter vector (:class:`~liftplan.model.statics.model.Layout`) it shares.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache, cached_property

import casadi as ca

from liftplan.model.frames import rotation
from liftplan.model.statics.model import Layout, pose_points, rope_tensions, statics_system


# -- flexible hull: the body as an elastic beam on the elastic ropes -------------------------
@dataclass(frozen=True)
class BeamLayout:
    """Offsets in the flat beam parameter vector of an m-node hull girder on n ropes.

    The vector is ``[K (16 (m - 1): each element's 4 x 4 bending stiffness, column-major),
    G (m - 1: each element's GJ / h, torsion only), f (2 m: consistent weight loads on
    (w_1, w'_1, ...)), S (n m: lug-to-node one-hot matrix, column-major)]``; see
    :mod:`liftplan.model.strength.beam`.
    """

    n: int
    m: int
    torsion: bool

    @property
    def size(self):
        return 16 * (self.m - 1) + (self.m - 1) * self.torsion + 2 * self.m + self.n * self.m

    @property
    def free(self):
        """Beam unknowns after the gauge (w = 0 at both ends; theta_1 + theta_m = 0)."""
        return 2 * self.m - 2 + (self.m - 1) * self.torsion

    def split(self, q):
        n, m = self.n, self.m
        k = 16 * (m - 1)
        bending = [ca.reshape(q[16 * e : 16 * e + 16], 4, 4) for e in range(m - 1)]
        twist = None
        if self.torsion:
            twist = q[k : k + m - 1]
            k += m - 1
        weight = q[k : k + 2 * m]
        select = ca.reshape(q[k + 2 * m : k + 2 * m + n * m], n, m)
        return bending, twist, weight, select


class FlexibleRopeModel:
    """The forward elastic model with the hull as an Euler-Bernoulli beam: one Newton system.

    Unknowns ``z = (a, heel, trim, d)``: the pose of the hull's chord and the free beam
    unknowns d (node deflections w [m] and slopes w' [rad], with torsion twists [rad];
    gauge and element matrices in :mod:`liftplan.model.strength.beam`). Each lug's world
    height is the rigid one plus up . u, u its body-frame displacement from the beam, so its
    rope's tension is EA max(0, H - h - l0) / l0 as in :class:`RopeModel`. Equations:

    * the statics A T = b of the undeformed lugs (small deflections: equilibrium on the
      undeformed geometry, as the girder's shear and moment are computed);
    * the beam's own equilibrium K d = F: the rope forces T up (body components: normal
      force, and the couple of the axial part about the CG's height; the torque about the
      twist axis) and the weight curve's consistent loads times up_z.

    When the statics hold, the loads on the beam are self-equilibrated (a force system in
    equilibrium in the world is in the body frame too), so the gauge's dropped rows hold by
    themselves. Stability: the Hessian of the potential energy (weight, ropes, beam strain)
    in z, judged on its Schur complement on the pose (the beam block is positive definite).
    """

    def __init__(self, n, m, torsion):
        self.layout = Layout(n)
        self.beam = BeamLayout(n, m, torsion)
        p = ca.SX.sym("p", self.layout.size)
        q = ca.SX.sym("q", self.beam.size)
        z = ca.SX.sym("z", 3 + self.beam.free)
        yaw, points, cog, weight, boom, length, stiffness, scale = self.layout.split(p)
        bending, twist_k, loads, select = self.beam.split(q)
        lift, heel, trim = z[0], z[1], z[2]
        free = z[3:]
        lugs, cog_w = pose_points(points, cog, heel, trim, yaw, lift)
        a_mat, b_vec = statics_system(lugs, cog_w, weight)
        up = rotation(heel, trim, yaw)[2, :].T  # world up in body components
        # the full beam vectors, gauge put back
        nb = 2 * m - 2
        bend_full = ca.vertcat(0, free[0 : 2 * m - 3], 0, free[2 * m - 3 : nb])
        w_nodes, slope_nodes = bend_full[0::2], bend_full[1::2]
        if torsion:
            inner = free[nb:]
            twist_nodes = ca.vertcat(inner, -inner[0])
        else:
            twist_nodes = ca.SX.zeros(m, 1)
        dy = (points[1, :] - cog[1]).T
        dz = (points[2, :] - cog[2]).T
        w_lug = ca.mtimes(select, w_nodes)
        slope_lug = ca.mtimes(select, slope_nodes)
        twist_lug = ca.mtimes(select, twist_nodes)
        moved = up[0] * (-dz * slope_lug) + up[1] * (-dz * twist_lug) + up[2] * (w_lug + dy * twist_lug)
        heights = lugs[2, :].T + moved
        tension, stretch = rope_tensions(boom, heights, length, stiffness)
        row_scale = ca.vertcat(weight, weight * scale, weight * scale)
        statics = (ca.mtimes(a_mat, tension) - b_vec) / row_scale
        # beam equilibrium K d - F on the full vectors, then the free rows
        k_d = ca.SX.zeros(2 * m, 1)
        for e, k_e in enumerate(bending):
            k_d[2 * e : 2 * e + 4] += ca.mtimes(k_e, bend_full[2 * e : 2 * e + 4])
        force = ca.SX.zeros(2 * m, 1)
        force[0::2] = ca.mtimes(select.T, tension * up[2])
        force[1::2] = ca.mtimes(select.T, -tension * up[0] * dz)
        force -= up[2] * loads
        bend_rows = k_d - force
        keep = [k for k in range(2 * m) if k not in (0, 2 * m - 2)]
        moment_rows = ca.DM([1.0 if k % 2 else 0.0 for k in keep])
        beam_scale = weight * (1 + (scale - 1) * moment_rows)
        residual = [statics, bend_rows[keep] / beam_scale]
        strain = 0.5 * ca.dot(bend_full, k_d)
        work_weight = up[2] * ca.dot(loads, bend_full)
        if torsion:
            torque = ca.mtimes(select.T, tension * (up[2] * dy - up[1] * dz))
            g_theta = ca.SX.zeros(m, 1)
            for e in range(m - 1):
                g = twist_k[e] * (twist_nodes[e + 1] - twist_nodes[e])
                g_theta[e] -= g
                g_theta[e + 1] += g
            twist_rows = g_theta - torque
            # theta_m = -theta_1: the free theta_1 row takes row 1 minus row m
            rows = ca.vertcat(twist_rows[0] - twist_rows[m - 1], twist_rows[1 : m - 1])
            residual.append(rows / (weight * scale))
            strain += 0.5 * ca.dot(twist_nodes, g_theta)
        self._residual = ca.vertcat(*residual)
        energy = (
            weight * (cog_w[2])
            + ca.sum1(stiffness * ca.fmax(0, stretch) ** 2 / (2 * length))
            + strain
            + work_weight
        ) / (weight * scale)
        self._z, self._p, self._q = z, p, q
        self._outputs = (tension, stretch, ca.mtimes(a_mat, tension) - b_vec, self._residual, energy)

    @cached_property
    def evaluate(self):
        """(z, p, q) -> (T, stretch, statics residual [t], scaled residual, energy Hessian)."""
        tension, stretch, statics, residual, energy = self._outputs
        hess = ca.hessian(energy, self._z)[0]
        return ca.Function(
            "flexible_eval", [self._z, self._p, self._q], [tension, stretch, statics, residual, hess]
        )

    @cached_property
    def solver(self):
        """(z0, p, q) -> z: casadi Newton on the scaled residual (failure judged by the caller)."""
        pq = ca.vertcat(self._p, self._q)
        newton = ca.rootfinder(
            "flexible_newton",
            "newton",
            {"x": self._z, "p": pq, "g": self._residual},
            {
                "abstol": 1e-12,
                "abstolStep": 1e-15,
                "max_iter": 60,
                "error_on_fail": False,
                "show_eval_warnings": False,
            },
        )
        z0 = ca.MX.sym("z0", self._z.shape[0])
        p = ca.MX.sym("p", self.layout.size)
        q = ca.MX.sym("q", self.beam.size)
        return ca.Function("flexible_solve", [z0, p, q], [newton(z0, ca.vertcat(p, q))])


@cache
def flexible_model(n, m, torsion):
    """The cached :class:`FlexibleRopeModel` for n ropes and an m-node hull girder."""
    return FlexibleRopeModel(n, m, bool(torsion))
