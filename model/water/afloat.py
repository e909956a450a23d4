"""The casadi model of a hull in water: gravity, exact buoyancy, vertical elastic ropes and a
ground pivot, and its root-finders.

Pose (``z-up``): attitude R = tilt(a, b) R0, where R0 is a start attitude (a parameter)
and a, b are rotations about the world's x and y axes (:func:`~liftplan.model.frames.tilt`),
and zo, the height of the body-frame origin above the water plane. Positions below are
world offsets from the point o on the water plane above the body-frame origin, so a body
point v is at R v + (0, 0, zo). Every force is vertical:

* gravity W_g at G (the body's weight plus water trapped in compartments),
* buoyancy, the weight of the displaced water: sum over the hull's triangles of
  kappa_t x (wet volume), kappa in t/m3 (:func:`buoyancy_weights`), at the centre of that
  volume (>= 0; a trapped compartment's displacement is in it, its water in W_g),
* rope i: T_i = EA_i / l0_i max(0, H_i - h_i - l0_i), h_i the lug's world height,
* the ground reaction F_R at the pivot c (when grounded): whatever closes the forces.

Residual r(x) = (F, M_x, M_y) / (W, W L, W L): net vertical force without the ground,
and moments about the pivot's current position (about G when there is no pivot; at an
equilibrium the net force is zero and the point does not matter). Grounded: x = (a, b)
and zo follows from the pivot staying on the ground; the moments must vanish
and F_R = -F >= 0. Afloat or hanging: x = (zo, a, b) and all three vanish.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from liftplan.model.frames import tilt
from liftplan.model.water.hydrostatics import wet_parts

ROOT_TOL = 1e-12  # on the scaled residual: 1e-12 W (force) and 1e-12 W L (moments)


def buoyancy_weights(hull, weight, density):
    """Triangles and their buoyancy weights kappa  [t/m3], and the trapped water.

    Parameters
    ----------
    hull : Hull
    weight : float  [t]   the body's weight in air
    density : float  [t/m3]   water

    Returns
    -------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
    kappa : numpy.ndarray, shape (m,)  [t/m3]
    trapped : list of (float, tuple)
        Weight [t] and body-frame centre [m] of water trapped in compartments.

    A compartment's triangles carry kappa = density whatever it holds: watertight, it
    displaces water while submerged. Trapped water is a weight (``trapped``), so
    submerged the two cancel and clear of the water the weight remains.
    """
    if hull.flooding == "intact":
        return hull.triangles, np.full(len(hull.triangles), density), []
    steel = hull.steel_volume(weight, density)
    tris = [hull.triangles]
    kappa = [np.full(len(hull.triangles), density * steel / hull.volume)]
    trapped = []
    for comp in hull.compartments:
        tris.append(comp.triangles)
        kappa.append(np.full(len(comp.triangles), density))
        if comp.contents == "water":
            trapped.append((density * comp.volume, comp.centroid))
    return np.concatenate(tris), np.concatenate(kappa), trapped


@dataclass(frozen=True)
class Layout:
    """The parameter vector of :class:`AfloatModel` with n ropes:
    ``[R0 (9, column-major), W, G (3), c (3), ground height over the water, L, P (3n),
    H - level (n), l0 (n), EA (n)]`` (t, m), and with ``coupled`` the ropes' coupled stiffness
    G (n x n, t/m) appended (crane vessels under several cranes:
    :class:`~liftplan.model.statics.floating.CoupledRopeModel`)."""

    n: int
    coupled: bool = False
    HOOKS = 18  # offset of P; the hooks start at HOOKS + 3n

    @property
    def size(self):
        return 18 + 6 * self.n + (self.n * self.n if self.coupled else 0)

    def split(self, p):
        n = self.n
        parts = [9, 1, 3, 3, 1, 1, 3 * n, n, n, n] + ([n * n] if self.coupled else [])
        out, k = [], 0
        for m in parts:
            out.append(p[k : k + m])
            k += m
        return out


class AfloatModel:
    """Residuals and root-finders of one hull (with its buoyancy weights) and n ropes.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
    kappa : numpy.ndarray, shape (m,)  [t/m3]
    n : int
        Number of vertical ropes (0 for a stranded or floating hull).
    coupled : bool
        The ropes' tensions T = G s0 (G in the parameters, s0 = H - h - l0 with no max(0, .):
        the caller picks the taut set) instead of each rope's EA / l0 max(0, s0).
    """

    def __init__(self, triangles, kappa, n, coupled=False):
        self.n = n
        self.layout = Layout(n, coupled)
        x3 = ca.MX.sym("x", 3)  # zo, a, b
        p = ca.MX.sym("p", self.layout.size)
        zo = x3[0]
        start, weight, cog, pivot, ground, scale, points, hook, length, ea, *coupling = self.layout.split(p)
        start = ca.reshape(start, 3, 3)
        rot = ca.mtimes(tilt(x3[1], x3[2]), start)
        lift = ca.vertcat(0, 0, zo)
        sums = self._weighted(triangles, kappa, rot, zo)
        buoy, moment = sums[0], sums[1:4]
        g = ca.mtimes(rot, cog) + lift
        c = ca.mtimes(rot, pivot) + lift
        force = buoy - weight
        mx = moment[1] - c[1] * buoy - weight * (g[1] - c[1])
        my = -(moment[0] - c[0] * buoy) + weight * (g[0] - c[0])
        tension = ca.MX.zeros(n)
        if n:
            lugs = ca.mtimes(rot, ca.reshape(points, 3, n)) + ca.repmat(lift, 1, n)
            stretch = hook - lugs[2, :].T - length
            if coupled:
                tension = ca.mtimes(ca.reshape(coupling[0], n, n), stretch)
            else:
                tension = ea / length * ca.fmax(0, stretch)
            force += ca.sum1(tension)
            mx += ca.dot(tension, lugs[1, :].T - c[1])
            my -= ca.dot(tension, lugs[0, :].T - c[0])
        scaled = ca.vertcat(force / weight, mx / (weight * scale), my / (weight * scale))
        outputs = [scaled, buoy, moment, tension]
        names = ["r", "buoyancy", "moment", "tension"]
        self.free = ca.Function("free", [x3, p], outputs, ["x", "p"], names)
        # grounded: the pivot stays at its ground height, so zo follows from the angles
        x2 = ca.MX.sym("x", 2)
        rot2 = ca.mtimes(tilt(x2[0], x2[1]), start)
        zo2 = ground - ca.mtimes(rot2[2, :], pivot)
        x_full = ca.vertcat(zo2, x2)
        grounded = self.free.call({"x": x_full, "p": p})
        self.grounded = ca.Function(
            "grounded",
            [x2, p],
            [grounded["r"][1:], grounded["r"][0], zo2, grounded["tension"]],
            ["x", "p"],
            ["r", "force", "zo", "tension"],
        )
        # stiffness in physical units (t/m, t, t m/rad): minus the Jacobian of the forces
        unscale = ca.diag(ca.vertcat(weight, weight * scale, weight * scale))
        free_r = self.free.call([x3, p])[0]
        grounded_r = self.grounded.call([x2, p])[0]
        self.free_stiffness = ca.Function(
            "free_stiffness", [x3, p], [-ca.mtimes(unscale, ca.jacobian(free_r, x3))]
        )
        self.grounded_stiffness = ca.Function(
            "grounded_stiffness", [x2, p], [-ca.mtimes(unscale[1:, 1:], ca.jacobian(grounded_r, x2))]
        )
        self.free_root = self._rootfinder("free_root", x3, p, free_r)
        self.grounded_root = self._rootfinder("grounded_root", x2, p, grounded_r)

    @staticmethod
    def _weighted(triangles, kappa, rot, zo):
        """Buoyancy [t] and its moment about o [t m]: kappa-weighted wet volumes."""
        return ca.mtimes(wet_parts(triangles, rot, zo)[:4, :], ca.DM(kappa))

    @staticmethod
    def _rootfinder(name, x, p, residual):
        problem = ca.Function(name + "_g", [x, p], [residual])
        return ca.rootfinder(
            name,
            "newton",
            problem,
            {
                "abstol": ROOT_TOL,
                "abstolStep": 1e-14,
                "max_iter": 60,
                "error_on_fail": False,
                "show_eval_warnings": False,
            },
        )
