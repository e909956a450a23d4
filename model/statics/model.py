"""The one casadi model: attitude kinematics, equilibrium of vertical ropes, rope elasticity.

Everything numeric in :mod:`liftplan.model.solve` (linear systems, residuals, Jacobians,
the Newton root-finder, the energy NLP, batched maps) is generated from the expressions
built here, once per rope count n and each on first use, and cached. Nothing limits n: a
64-rope elastic solve costs ~0.1 ms, and building its functions ~13 ms
(``studies/many_points.py``).

Physics (``z-up`` frame, see :mod:`liftplan.model.frames`)
---------------------------------------------------------
Body pose: attitude R(heel, trim, yaw) and height ``a`` of the body-frame origin, which
sits at world plan position (0, 0). A body point p is at world r = R p + (0, 0, a).

Ropes hang vertically (each hook is above its lug), so the weight W (down, at the CG) and
the tensions T_i (up, at the lugs) give three equations; the rest hold identically::

    sum T_i            = W
    sum T_i x_i        = W x_c        (x, y: world plan coordinates of lugs and CG)
    sum T_i y_i        = W y_c

Rope i, boom tip at height H_i, unstretched length l0_i, stiffness EA_i, lug at world
height h_i: stretch s_i = H_i - h_i - l0_i and T_i = EA_i max(0, s_i) / l0_i (a slack
rope carries nothing). The same forces derive from the potential
V = W z_c + sum EA_i max(0, s_i)^2 / (2 l0_i), whose stationary points are the equilibria.

Choi & Shin (2003) close the statics instead with elongations e_i = T_i l_i / EA_i that are
affine in the lugs' plan coordinates (the lug points stay coplanar: no twist preload),
with l_i = H_i - a - z'_i, z'_i the vertical coordinate of R p_i. Substituting
T_i = k_i (c0 + c1 x_i + c2 y_i), k_i = EA_i / l_i, into the statics gives the 3x3 system
(sum k_i phi_i phi_i^T) c = W phi_c with phi = (1, x, y): solved exactly here.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from functools import cache, cached_property

import casadi as ca
import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.frames import rotation, rotation_matrix
from liftplan.model.statics.compiled import compile_cached

#: casadi's Newton rootfinder as every rope model uses it: tight tolerances, and its own
#: failure flag off (with it on, casadi prints the inputs to stdout and raises); callers judge
#: convergence by the returned residual and pose.
NEWTON_OPTIONS = {
    "abstol": 1e-13,
    "abstolStep": 1e-15,
    "max_iter": 60,
    "error_on_fail": False,
    "show_eval_warnings": False,
}


@dataclass(frozen=True)
class Layout:
    """Offsets of each quantity in the flat parameter vector of an n-rope model.

    The vector is ``[yaw, P (3n, column-major: x1 y1 z1 x2 ...), cog (3), W, H (n), l0 (n),
    EA (n), L]``: yaw in rad, lengths in m, forces in t. ``L`` is a length scale [m] used
    only to scale the moment residuals (the lugs' plan diameter).
    """

    n: int

    @property
    def size(self):
        return 6 * self.n + 6

    @property
    def boom(self):
        """Where the boom-tip heights H sit in the vector (a slice)."""
        return slice(3 * self.n + 5, 4 * self.n + 5)

    def split(self, p):
        n = self.n
        k = 0

        def take(m):
            nonlocal k
            part = p[k : k + m]
            k += m
            return part

        yaw = take(1)
        points = ca.reshape(take(3 * n), 3, n)
        cog = take(3)
        weight = take(1)
        boom = take(n)
        length = take(n)
        stiffness = take(n)
        scale = take(1)
        return yaw, points, cog, weight, boom, length, stiffness, scale


@dataclass(frozen=True)
class HingedLayout(Layout):
    """:class:`Layout` with eight more entries per rope APPENDED (so every offset of
    :class:`Layout` holds): ``[..., L, A1 (3), B1 (3), c1, w1, A2 (3), ...]``.

    Rope i's lift point hangs from the lugs A_i, B_i (body frame, m) on a sling that hinges
    about the line A_i B_i (see :class:`HingedRopeModel`): c_i [m] is the drop of a spreader
    bar's parallel bottom legs (0 for a 2-leg sling), w_i [t] the bar's weight (0 without
    one). The rope's ``P`` column is its lift point (the hook) at the level pose. A body-fixed
    point is A = P, c = w = 0 and any B != A.
    """

    @property
    def size(self):
        return 14 * self.n + 6

    def hinges(self, p):
        """(A (3 x n), B (3 x n), c (n), w (n)) from a parameter vector."""
        block = ca.reshape(p[6 * self.n + 6 : 14 * self.n + 6], 8, self.n)
        return block[0:3, :], block[3:6, :], block[6, :].T, block[7, :].T


def fixed_hinges(points):
    """Hinge entries (..., n, 8) that make every lift point of ``points`` (..., n, 3) body-fixed."""
    points = np.asarray(points, dtype=float)
    zeros = np.zeros((*points.shape[:-1], 1))
    return np.concatenate([points, points + [1.0, 0.0, 0.0], zeros, zeros], axis=-1)


def _unit(v):
    return v / ca.repmat(ca.sqrt(ca.sum1(v * v)), v.shape[0], 1)


#: A hinged pair must stay this far from plumb [deg] at every attitude of the tolerance box:
#: the hinge plane is the vertical plane through the pair, which turns by 1 / cos(inclination)
#: per unit of tilt and is undefined at plumb (:func:`hinged_points` divides by the pair's
#: horizontal length); at 80 deg a 1 deg tilt swings it ~6 deg. The sling planner rules such
#: pairs out with the same margin (``planner/plans/slings/rigs.py``, ``PLUMB_MARGIN``).
PLUMB_MARGIN = 10.0


def pair_inclination(a, b):
    """Inclination from the horizontal of each lug pair a -> b ((N, 3), body frame [m])  [deg]."""
    d = np.asarray(b, dtype=float) - np.asarray(a, dtype=float)
    return np.degrees(np.arctan2(np.abs(d[:, 2]), np.hypot(d[:, 0], d[:, 1])))


def box_tilt(heel, trim):
    """The most a tilt of the box |heel| <= heel, |trim| <= trim [deg] turns a line  [deg]:
    the body's tilt at the box's corner, arccos(cos heel cos trim)."""
    return float(np.degrees(np.arccos(np.cos(np.radians(heel)) * np.cos(np.radians(trim)))))


def near_plumb(a, b, heel, trim):
    """Whether each lug pair comes within :data:`PLUMB_MARGIN` of plumb at some attitude of the
    heel/trim box: its inclination plus :func:`box_tilt` reaches 90 deg - :data:`PLUMB_MARGIN`
    (the rule the sling planner rules pairs out by)."""
    return pair_inclination(a, b) + box_tilt(heel, trim) >= 90.0 - PLUMB_MARGIN


def check_hinges(rows, heel, trim, yaw=0.0, names=None, shown=tuple):
    """Refuse hinge rows that :func:`hinged_points` cannot pose everywhere in the heel/trim box.

    A row's lugs A, B must be two points (the sling hinges about the line AB) that stay more
    than :data:`PLUMB_MARGIN` off plumb over the box (:func:`near_plumb`): near plumb the
    hinge plane (the vertical plane through AB) flips and the hooks, tensions and bounds turn
    to NaN. A planning file's slings never reach here with such a pair (the sling planner rules
    them out); a ``PlanProblem(..., hinges=...)`` built from Python does.

    Parameters
    ----------
    rows : array_like, shape (N, 8)
        Hinge rows (:class:`HingedLayout`: A (3), B (3), c, w), body frame ``z-up``  [m, t].
    heel, trim : float  [deg]
        Half-widths of the tolerance box.
    yaw : float  [deg]
        The lift's yaw (the attitude named in the message is evaluated with it).
    names : sequence of str, optional
        Each row's candidate name, for the message.
    shown : callable
        Maps a ``z-up`` point to the frame the user wrote (default: as it is).

    Raises
    ------
    InvalidScene
        One line naming the row, the pair, its inclination and the box's attitude where it is
        steepest.
    """

    rows = np.asarray(rows, dtype=float).reshape(-1, 8)
    a, b = rows[:, 0:3], rows[:, 3:6]

    def where(i):
        name = f" ({names[i]})" if names is not None else ""
        pa, pb = (", ".join(f"{v + 0.0:g}" for v in shown(tuple(p))) for p in (a[i], b[i]))
        return f"hinges[{i}]{name}: the lug pair A ({pa}) B ({pb}) m"

    length = np.linalg.norm(b - a, axis=1)
    short = np.flatnonzero(~(length > 1e-9))
    if short.size:
        raise InvalidScene(
            f"{where(short[0])} is one point: expected two lugs apart (the sling "
            "hinges about the line between them)"
        )
    bad = np.flatnonzero(near_plumb(a, b, heel, trim))
    if not bad.size:
        return
    i = int(bad[0])
    d = (b[i] - a[i]) / length[i]
    # where in the box the pair is steepest (a 41 x 41 grid, edges and corners on it)
    grid = [(h, t) for h in np.linspace(-heel, heel, 41) for t in np.linspace(-trim, trim, 41)]
    steep = [abs(rotation_matrix(h, t, yaw)[2] @ d) for h, t in grid]
    k = int(np.argmax(steep))
    tilt = box_tilt(heel, trim)
    raise InvalidScene(
        f"{where(i)} is {pair_inclination(a[[i]], b[[i]])[0]:.2f} deg from the horizontal and the "
        f"heel/trim box (+-{heel:g}, +-{trim:g} deg) tilts it by up to {tilt:.2f} deg (steepest "
        f"{np.degrees(np.arcsin(min(1.0, steep[k]))):.2f} deg at heel {grid[k][0] + 0.0:.2f}, trim "
        f"{grid[k][1] + 0.0:.2f} deg): within {PLUMB_MARGIN:g} deg of plumb the sling's hinge plane "
        f"flips; expected a pair less than {90.0 - PLUMB_MARGIN - tilt:.2f} deg from the "
        "horizontal, or a smaller plan.tolerance"
    )


def hinged_points(points, hinges, rot, lift):
    """World positions of hinged lift points at a pose, and the bar weights' moment term.

    A sling on lugs A, B (2 legs, or a spreader bar with parallel bottom legs of drop c) is a
    rigid linkage free to swing about the line AB; under a vertical hoist line its hook hangs in
    the vertical plane through AB (the hook's height is greatest there). With A', B' the posed
    lugs, u = (B' - A') / |B' - A'| and n the unit vertical square to u (upward)::

        hook = A' + c e_z + s u + h n

    with (s, h) the hook's fixed place in the sling's plane, taken from the level hook P:
    (s, h) = ((P - A - c e_z) . u0, (P - A - c e_z) . n0). A bar of weight w hangs at the
    middle of its ends A' + c e_z, B' + c e_z, so the body's share T of a hook load T + w acts
    at the hook plus w (hook - bar) / T in plan: the statics' moment rows lose
    sum w (hook - bar) (plan).

    Parameters
    ----------
    points : 3 x n   lift points at level (P), body frame  [m]
    hinges : (A, B, c, w) of :meth:`HingedLayout.hinges`
    rot : 3 x 3   attitude
    lift : scalar   height of the body origin  [m]

    Returns
    -------
    hooks : 3 x n  [m]
    moment : 3   [0, t m, t m], to subtract from the statics' right-hand side
    """
    a, b, drop, bar = hinges
    n = points.shape[1]
    up = ca.repmat(ca.vertcat(0, 0, lift), 1, n)
    e_z = ca.repmat(ca.DM([0.0, 0.0, 1.0]), 1, n)
    posed_a = ca.mtimes(rot, a) + up
    posed_b = ca.mtimes(rot, b) + up
    u = _unit(posed_b - posed_a)
    normal = _unit(e_z - ca.repmat(u[2, :], 3, 1) * u)
    u0 = _unit(b - a)
    n0 = _unit(e_z - ca.repmat(u0[2, :], 3, 1) * u0)
    offset = points - a - e_z * ca.repmat(drop.T, 3, 1)
    along = ca.sum1(offset * u0)
    height = ca.sum1(offset * n0)
    hooks = (
        posed_a
        + e_z * ca.repmat(drop.T, 3, 1)
        + u * ca.repmat(along, 3, 1)
        + normal * ca.repmat(height, 3, 1)
    )
    centre = 0.5 * (posed_a + posed_b) + e_z * ca.repmat(drop.T, 3, 1)
    lever = ca.mtimes(hooks[0:2, :] - centre[0:2, :], bar)
    return hooks, ca.vertcat(0, lever)


def pose_points(points, cog, heel, trim, yaw, lift):
    """World positions of the lugs (3 x n) and of the CG (3) at a pose."""
    rot = rotation(heel, trim, yaw)
    up = ca.vertcat(0, 0, lift)
    lugs = ca.mtimes(rot, points) + ca.repmat(up, 1, points.shape[1])
    return lugs, ca.mtimes(rot, cog) + up


def statics_system(lugs, cog, weight):
    """Equilibrium of vertical forces as A T = b.

    Returns
    -------
    A : 3 x n  rows (1, x_i, y_i) of the lugs' world plan coordinates
    b : 3      W (1, x_c, y_c)
    """
    n = lugs.shape[1]
    a_mat = ca.vertcat(ca.DM.ones(1, n), lugs[0, :], lugs[1, :])
    b_vec = weight * ca.vertcat(1, cog[0], cog[1])
    return a_mat, b_vec


def rope_tensions(boom, lug_height, length, stiffness):
    """Tension of vertical elastic ropes; slack ropes carry nothing  [t]."""
    stretch = boom - lug_height - length
    return stiffness * ca.fmax(0, stretch) / length, stretch


#: Attitudes per call of the batched map: large enough that the call overhead vanishes,
#: small enough that the buffers stay in cache.
BLOCK = 4096


class FastCall:
    """Call a casadi Function on numpy vectors through its zero-copy buffer interface.

    ``Function.call`` converts every float between Python and casadi (about 0.4 us each);
    the buffer binds numpy arrays once, so a 4-rope elastic solve costs about 14 us instead
    of 35. One buffer per thread, because the bound arrays are shared state.
    """

    def __init__(self, function):
        self.function = function
        self._local = threading.local()

    def _state(self):
        state = getattr(self._local, "state", None)
        if state is None:
            fn = self.function
            buffer, evaluate = fn.buffer()
            inputs = [np.zeros(fn.nnz_in(i)) for i in range(fn.n_in())]
            outputs = [np.zeros(fn.nnz_out(i)) for i in range(fn.n_out())]
            for i, array in enumerate(inputs):
                buffer.set_arg(i, memoryview(array))
            for i, array in enumerate(outputs):
                buffer.set_res(i, memoryview(array))
            state = self._local.state = (buffer, evaluate, inputs, outputs)
        return state

    def __call__(self, *args):
        """Evaluate; inputs are flat float arrays (column-major), outputs fresh copies."""
        _, evaluate, inputs, outputs = self._state()
        for target, value in zip(inputs, args, strict=True):
            target[:] = value
        evaluate()
        return [out.copy() for out in outputs]


class RopeModel:
    """Symbolic model and generated functions for n vertical ropes. Use :func:`rope_model`.

    Each function is built on first use, so a solve pays only for what it calls: the
    held-hoist sensitivities (an n x n Jacobian, ~0.1 s to build at n = 64) are not made
    for an elastic or paper-elastic solve.
    """

    layout_class = Layout

    def __init__(self, n):
        self.n = n
        self.layout = self.layout_class(n)
        self.batch_backend = None  # "jit" or "casadi-vm", set when a batch map is built
        p = ca.SX.sym("p", self.layout.size)
        x = ca.SX.sym("x", 3)  # lift a [m], heel [rad], trim [rad]
        yaw, points, cog, weight, boom, length, stiffness, scale = self.layout.split(p)
        lift, heel, trim = x[0], x[1], x[2]
        lugs, cog_w, moment = self._posed(p, points, cog, heel, trim, yaw, lift)
        a_mat, b_vec = statics_system(lugs, cog_w, weight)
        b_vec = b_vec - moment
        self._x, self._p = x, p
        self._parts = (yaw, points, cog, weight, boom, length, stiffness, scale)
        self._pose = (lugs, cog_w, a_mat, b_vec)

    def _posed(self, p, points, cog, heel, trim, yaw, lift):
        """World lift points (3 x n) and CG (3) at a pose, and a term (3) off the statics' b."""
        lugs, cog_w = pose_points(points, cog, heel, trim, yaw, lift)
        return lugs, cog_w, ca.DM.zeros(3)

    # -- given attitude: statics matrix, and the paper's elastic closure -------------------
    @cached_property
    def statics(self):
        """(x, p) -> (A, b, lugs, cog): the statics A T = b at a given pose."""
        lugs, cog_w, a_mat, b_vec = self._pose
        return ca.Function(
            "statics",
            [self._x, self._p],
            [a_mat, b_vec, lugs, cog_w],
            ["x", "p"],
            ["A", "b", "lugs", "cog"],
        )

    @cached_property
    def statics_fast(self):
        """``statics`` for one pose as a :class:`FastCall`: (x, p) -> flat (A, b, lugs, cog)."""
        return FastCall(self.statics)

    @cached_property
    def paper_elastic(self):
        """(x, p) -> (T, l, residual): Choi & Shin (2003)'s closure, a 3x3 normal system."""
        lugs, _, a_mat, b_vec = self._pose
        boom, stiffness = self._parts[4], self._parts[6]
        rope_len = boom - lugs[2, :].T  # l_i = H_i - a - z'_i
        k = stiffness / rope_len
        phi = a_mat.T  # n x 3
        normal = ca.mtimes(phi.T, ca.diag(k) @ phi)
        coeff = ca.solve(normal, b_vec)
        t_paper = k * ca.mtimes(phi, coeff)
        return ca.Function(
            "paper_elastic",
            [self._x, self._p],
            [t_paper, rope_len, ca.mtimes(a_mat, t_paper) - b_vec],
            ["x", "p"],
            ["T", "l", "residual"],
        )

    # -- held hoist: the boom heights set at level, the hooks then moved rigidly -------------
    @cached_property
    def _held(self):
        """Symbolic held-hoist tensions and hook shifts; see :attr:`held`."""
        n = self.n
        yaw, points, cog, _, boom, length, stiffness, _ = self._parts
        lugs, _, a_mat, b_vec = self._pose
        level, _ = pose_points(points, cog, 0, 0, yaw, self._x[0])
        phi0 = ca.horzcat(ca.DM.ones(n, 1), level[0, :].T, level[1, :].T)
        k0 = stiffness / length
        s_set = boom - lugs[2, :].T - length
        coupling = ca.mtimes(a_mat, ca.diag(k0) @ phi0)
        c_hold = ca.solve(coupling, b_vec - ca.mtimes(a_mat, k0 * s_set))
        hook_shift = ca.mtimes(phi0, c_hold)
        return k0 * (s_set + hook_shift), hook_shift

    @cached_property
    def held(self):
        """(x, p) -> (T, dH, dT_dH): tensions with the level preload held; see below.

        A heel or trim deviation comes from hook motions that are a rigid-body motion of
        the level hook pattern: dH_i = c0 + c1 x0_i + c2 y0_i (x0, y0 the lugs' level plan
        positions). Such motions leave the twist (the redundant preload) unchanged. At a
        given pose the statics fix c: linear, exact.
        """
        t_held, hook_shift = self._held
        return ca.Function(
            "held",
            [self._x, self._p],
            [t_held, hook_shift, ca.jacobian(t_held, self._parts[4])],
            ["x", "p"],
            ["T", "dH", "dT_dH"],
        )

    @cached_property
    def held_tensions(self):
        """(x, p) -> (T, dH): :attr:`held` without its n x n sensitivities dT_dH.

        What a check of fixed boom heights needs; at n = 64 its batched map compiles in
        ~1.5 s where :attr:`held`'s takes ~17 s (the Jacobian is n^2 outputs per column).
        """
        t_held, hook_shift = self._held
        return ca.Function("held_tensions", [self._x, self._p], [t_held, hook_shift], ["x", "p"], ["T", "dH"])

    # -- forward elastic model -------------------------------------------------------------
    def _rope_law(self, boom, heights, length, stiffness):
        """The ropes' tensions [t], stretches [m] and elastic energy [t m] with their lugs at
        world ``heights``: each rope on its own, slack ones carrying nothing."""
        tension, stretch = rope_tensions(boom, heights, length, stiffness)
        return tension, stretch, ca.sum1(stiffness * ca.fmax(0, stretch) ** 2 / (2 * length))

    @cached_property
    def _elastic(self):
        """Symbolic tension, stretch, scaled residual and energy of the forward model."""
        x = self._x
        _, _, _, weight, boom, length, stiffness, scale = self._parts
        lugs, cog_w, a_mat, b_vec = self._pose
        row_scale = ca.vertcat(weight, weight * scale, weight * scale)
        tension, stretch, springs = self._rope_law(boom, lugs[2, :].T, length, stiffness)
        residual = (ca.mtimes(a_mat, tension) - b_vec) / row_scale
        # Potential energy; its stationary points are the equilibria (for |heel| < 90 deg),
        # and the stable ones are its minima: leading principal minors of the Hessian > 0.
        energy = (weight * cog_w[2] + springs) / (weight * scale)
        hess = ca.hessian(energy, x)[0]
        minors = ca.vertcat(hess[0, 0], ca.det(hess[:2, :2]), ca.det(hess))
        return tension, stretch, residual, row_scale, energy, minors

    @cached_property
    def elastic_tensions(self):
        """(x, p) -> (T, stretch, residual [t]) of the forward model at a pose."""
        tension, stretch, residual, row_scale, _, _ = self._elastic
        return ca.Function(
            "elastic_tensions",
            [self._x, self._p],
            [tension, stretch, residual * row_scale],
            ["x", "p"],
            ["T", "stretch", "residual"],
        )

    @cached_property
    def elastic_sensitivity(self):
        """(x, p) -> (T, dT_dx, dT_dp, dr_dx, dr_dp) of the forward model at a pose, as a
        :class:`FastCall` (flat outputs, column-major).

        At an equilibrium r(x, p) = 0 (the statics residual [t]), so the pose moves with the
        parameters as dx/dp = -(dr/dx)^-1 dr/dp and the tensions as
        dT/dp + dT/dx dx/dp: what ``liftplan watch`` fits readings and plans hook moves with.
        """
        tension, _, residual, row_scale, _, _ = self._elastic
        residual = residual * row_scale
        x, p = self._x, self._p
        function = ca.Function(
            "elastic_sensitivity",
            [x, p],
            [
                ca.densify(out)
                for out in (
                    tension,
                    ca.jacobian(tension, x),
                    ca.jacobian(tension, p),
                    ca.jacobian(residual, x),
                    ca.jacobian(residual, p),
                )
            ],
        )
        return FastCall(function)

    @cached_property
    def elastic_start(self):
        """p -> x: one Newton step on the all-taut residual from level.

        Exact for the linearised kinematics (the residual is affine in the lift a).
        """
        x, p = self._x, self._p
        _, _, _, _, _, length, stiffness, _ = self._parts
        _, stretch, _, _, _, _ = self._elastic
        _, _, a_mat, b_vec = self._pose
        taut = ca.mtimes(a_mat, stiffness * stretch / length) - b_vec
        x_ref = ca.vertcat(0, 0, 0)
        jac_taut = ca.substitute(ca.jacobian(taut, x), x, x_ref)
        x_start = x_ref - ca.solve(jac_taut, ca.substitute(taut, x, x_ref))
        return ca.Function("elastic_start", [p], [x_start])

    @property
    def _energy(self):
        return self._x, self._p, self._elastic[4]

    @property
    def _residual(self):
        return self._elastic[2]

    @property
    def _minors(self):
        return self._elastic[5]

    @cached_property
    def _newton(self):
        # Newton's own failure flag is off (with it on, casadi prints the inputs to stdout
        # and raises); callers judge convergence by the returned residual and pose instead,
        # which also catches a "converged" point that is not an acceptable equilibrium.
        return ca.rootfinder(
            "elastic_newton",
            "newton",
            {"x": self._x, "p": self._p, "g": self._residual},
            NEWTON_OPTIONS,
        )

    def _newton_function(self, name, with_start):
        p = ca.MX.sym("p", self.layout.size)
        x0 = ca.MX.sym("x0", 3)
        x = self._newton(self.elastic_start(p) if with_start else x0, p)
        tension, stretch, residual = self.elastic_tensions(x, p)
        minors = ca.Function("minors", [self._x, self._p], [self._minors])(x, p)
        inputs = [p] if with_start else [x0, p]
        return FastCall(ca.Function(name, inputs, [x, tension, stretch, residual, minors]))

    @cached_property
    def elastic_solver(self):
        """p -> (x, T, stretch, residual, minors): Newton from :attr:`elastic_start`.

        ``minors`` are the energy Hessian's leading principal minors: all > 0 at a stable
        equilibrium. One fast call.
        """
        return self._newton_function("elastic_solve", with_start=True)

    @cached_property
    def elastic_polish(self):
        """(x0, p) -> (x, T, stretch, residual, minors): Newton from a given start."""
        return self._newton_function("elastic_polish", with_start=False)

    @cached_property
    def energy_solver(self):
        """IPOPT on the potential energy: the slower, more forgiving fallback."""
        x, p, energy = self._energy
        return ca.nlpsol(
            "elastic_energy",
            "ipopt",
            {"x": x, "p": p, "f": energy},
            {
                "ipopt.print_level": 0,
                "print_time": False,
                "ipopt.tol": 1e-14,
                "ipopt.sb": "yes",
                "ipopt.max_iter": 500,
                "show_eval_warnings": False,
            },
        )

    @cached_property
    def paper_elastic_fast(self):
        """``paper_elastic`` for one attitude as a :class:`FastCall`: (x, p) -> (T, l, residual)."""
        return FastCall(self.paper_elastic)

    @cached_property
    def paper_elastic_block(self):
        """``paper_elastic`` mapped over :data:`BLOCK` attitudes (columns of x), p shared,
        as a :class:`FastCall`.

        Compiled to C when a compiler is there (once per machine, then loaded from the user's
        cache: :mod:`liftplan.model.statics.compiled`): about 6.6 M attitudes/s on one core against
        1.4 M/s in casadi's virtual machine, which is the fallback.
        (casadi's "thread" map was slower than serial here, so it is not used.)
        """
        return self._block(self.paper_elastic, shared_p=True)

    @cached_property
    def held_block(self):
        """``held`` over :data:`BLOCK` attitudes (columns of x), p shared: (T, dH, dT_dH)."""
        return self._block(self.held, shared_p=True)

    @cached_property
    def held_columns(self):
        """``held`` over :data:`BLOCK` columns of both x and p (many lug sets at once)."""
        return self._block(self.held, shared_p=False)

    @cached_property
    def held_tensions_columns(self):
        """``held_tensions`` over :data:`BLOCK` columns of both x and p: (T, dH)."""
        return self._block(self.held_tensions, shared_p=False)

    def _block(self, function, shared_p):
        x = ca.SX.sym("x", 3)
        p = ca.SX.sym("p", self.layout.size)
        # the column is compiled to C once per model and machine, then loaded from the user's
        # cache by every later process (see liftplan.model.statics.compiled); casadi's VM without a compiler
        compiled = compile_cached(ca.Function(f"{function.name()}_column", [x, p], list(function(x, p))))
        self.batch_backend = compiled.backend
        # with shared_p, input 1 (p) is shared by every column rather than repeated
        shared = [1] if shared_p else []
        return FastCall(compiled.function.map(f"{function.name()}_block", "serial", BLOCK, shared, []))


class HingedRopeModel(RopeModel):
    """:class:`RopeModel` whose lift points may hang on slings hinged about a lug pair.

    The parameter vector is :class:`HingedLayout` (the plain layout with eight entries per rope
    appended); each lift point is posed by :func:`hinged_points` instead of turning with the
    body, and a spreader bar's weight moves the body's share off the hook in plan. Everything
    else (statics rows from the lift points' plan positions, the rope's stretch from their
    heights, the held preload) is :class:`RopeModel`'s, from the same expressions. Use
    :func:`hinged_model`. Meant for the statics and the held functions (what the planner
    calls); the forward model with free hooks and elastic legs is :mod:`liftplan.model.statics.rigging`.

    With a bar weight w_i, rope i's tension T_i here is the body's share (the hook load is
    T_i + w_i) and H_i the boom height less the bar's own stretch w_i l0_i / EA_i.
    """

    layout_class = HingedLayout

    def _posed(self, p, points, cog, heel, trim, yaw, lift):
        rot = rotation(heel, trim, yaw)
        hooks, moment = hinged_points(points, self.layout.hinges(p), rot, lift)
        cog_w = ca.mtimes(rot, cog) + ca.vertcat(0, 0, lift)
        return hooks, cog_w, moment


@cache
def rope_model(n):
    """The cached :class:`RopeModel` for ``n`` ropes."""
    return RopeModel(n)


@cache
def hinged_model(n):
    """The cached :class:`HingedRopeModel` for ``n`` ropes."""
    return HingedRopeModel(n)
