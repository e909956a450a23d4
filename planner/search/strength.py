"""Lift forces chosen for the hull girder's strength: the linear programs.

Read this first. For a body with a weight curve (README "Hull girder"), the bending moment and
shear force at a section x = s of a state with body up-vector u (the world's up in the body
frame) and lug tensions T are (the signs and reference of
:mod:`liftplan.model.strength.girder`: the loads on the part aft of the section)

    Q(s) = u_z (sum_{x_i < s} T_i - W_aft(s))
    M(s) = u_z (sum_{x_i < s} T_i (s - x_i) - M_aft(s)) + u_x (sum_{x_i < s} (z_i - z_G) T_i - dz W_aft(s))

with W_aft, M_aft the weight curve's running integral and moment (corrected to W at the CG's x,
as ``solve`` does, so a CG offset dx moves the curve's linear correction), z_G the nominal CG
height (the sections' reference height) and dz the CG's height offset. For a given lug set and
state both are **linear in the tensions**; and the tensions are linear in the decision:

* hoist control (boom heights): T_k = P_k T* + q_k at scenario k (the held-preload model,
  :meth:`liftplan.planner.search.scenarios.LugSet.affine`), hook errors exact as margins;
* force control (strand jacks): T_k = T* at every state; the attitude follows from equilibrium
  (see :func:`force_attitude`).

With slings the lift points are the hooks and the loads on the girder are the legs': a hook's
tension T splits into leg forces at its lugs, each T times a vector fixed by the sling's statics
at that state, so the rows stay linear in the hooks' tensions (:class:`PointLoads`: one load
per leg, its vertical part and its axial part's couple (z_i - z_G) f_x as above; the ropes'
case is one vertical load per lug).

So choosing T* to minimise the worst |M| / allowable (and |Q| / allowable, and the spread) over
finitely many scenarios and sections is a linear program, :class:`StrengthLP`, built once per
size from ``cp.Parameter`` objects (DPP, checked at build) and re-solved. The candidates'
choice is the mixed-integer version :class:`CandidateMIP` (HiGHS): exact for force control;
for hoist control a relaxation (each scenario's tensions only statically admissible) that
gives the valid lower bound of the search in :mod:`liftplan.planner.plans.strength`.

Sections: finitely many in an LP; between loads M is a cubic, so the exact maxima of a
solution are found with :mod:`liftplan.model.strength.piecewise` and added as cutting planes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cvxpy as cp
import numpy as np
from scipy import sparse

from liftplan.model.errors import PlanInfeasible, SolverFailed
from liftplan.model.scene.objects import curve_totals
from liftplan.model.strength.piecewise import Piecewise, on_breaks
from liftplan.planner.search.bounds import _checked, _run, run_highs

#: Equal steps over the weight curve's span in the first list of sections.
SECTION_GRID = 60
#: Weight of the objective's other parts, so that among equal optima the plan with the
#: lowest other ratios is chosen (an LP returns an arbitrary vertex of its optimal face).
TIE_BREAK = 1e-7
#: Least height of the force centre above the CG under force control  [m]: below it the
#: body hangs unstable (or neutral) on constant forces.
STABLE_HEIGHT = 1e-3
#: HiGHS's relative MIP gap (its default 1e-4 would leave 1e-4 on the table); the MIP's
#: optimum less this fraction is the search's certified lower bound.
MIP_GAP = 1e-8


# -- the girder's loads at sections -------------------------------------------------------------
class GirderLoads:
    """The weight curve of a body as the girder's distributed load, with the CG's x offset.

    Parameters
    ----------
    body : Body
        With ``weight_curve``.

    Notes
    -----
    The curve is corrected by c0 + c1 (x - x_mid) over its span so that it carries W at the
    CG's x exactly (:func:`liftplan.model.strength.girder.hull_girder` does the same); a CG
    offset dx changes c1 by 12 W dx / L^3.
    """

    def __init__(self, body):
        x, w = body.weight_curve_arrays
        self.weight, self.cog = body.weight, np.asarray(body.cog, dtype=float)
        length, middle = x[-1] - x[0], 0.5 * (x[0] + x[-1])
        area, first = curve_totals(x, w)
        c0 = (body.weight - area) / length
        c1 = 12.0 * (body.weight * body.cog[0] - first - c0 * length * middle) / length**3
        h = np.diff(x)
        self.base = Piecewise(
            x, np.stack([w[:-1] + c0 + c1 * (x[:-1] - middle), (w[1:] - w[:-1]) / h + c1], axis=1)
        )
        self.unit = Piecewise(x, np.stack([x[:-1] - middle, np.ones(len(h))], axis=1))
        self.per_offset = 12.0 * body.weight / length**3  # dc1 / ddx  [t/m^2 per m]
        self.span = (float(x[0]), float(x[-1]))
        self.breaks = x
        base_q, unit_q = self.base.integral(), self.unit.integral()
        self._aft = (base_q, base_q.integral(), unit_q, unit_q.integral())

    def curve(self, dx=0.0):
        """The corrected weight per length with the CG's x moved by dx  [t/m]."""
        return Piecewise(self.breaks, self.base.coef + self.per_offset * dx * self.unit.coef)

    def aft(self, s, dx=0.0):
        """Weight aft of each section W_aft(s) [t] and its moment M_aft(s) = int w (s - x) [t m]."""
        wq, wm, uq, um = self._aft
        c = self.per_offset * dx
        return wq(s) + c * uq(s), wm(s) + c * um(s)


@dataclass(frozen=True)
class Sections:
    """Sections of the girder: stations and on which side of a point load each is taken.

    Parameters
    ----------
    x : numpy.ndarray  [m]
    right : numpy.ndarray of bool
        True: just forward of a point load at x (it is counted aft); False: just aft.
    """

    x: np.ndarray
    right: np.ndarray

    @staticmethod
    def initial(loads, stations, envelopes, grid=SECTION_GRID):
        """The weight curve's breakpoints, both sides of every station (lug candidates),
        the envelopes' breakpoints and ``grid`` equal steps over the span."""
        lo, hi = loads.span
        plain = np.unique(
            np.concatenate(
                [loads.breaks, np.linspace(lo, hi, grid + 1)]
                + [np.array([p[0] for p in env]) for env in envelopes if env is not None]
            )
        )
        plain = plain[(plain >= lo) & (plain <= hi)]
        stations = np.unique(np.asarray(stations, dtype=float))
        x = np.concatenate([plain, stations, stations])
        right = np.concatenate(
            [np.ones(len(plain), bool), np.zeros(len(stations), bool), np.ones(len(stations), bool)]
        )
        return Sections(x, right)

    def add(self, x, right):
        """These sections with more (repeats dropped)."""
        xs = np.concatenate([self.x, np.atleast_1d(x)])
        rs = np.concatenate([self.right, np.atleast_1d(right)])
        keys = np.round(xs, 9) + 1e6 * rs
        _, first = np.unique(keys, return_index=True)
        first.sort()
        return Sections(xs[first], rs[first])

    def __len__(self):
        return len(self.x)


@dataclass(frozen=True)
class State:
    """One state the plan must hold, for the girder: the body's up-vector and the CG offset.

    Parameters
    ----------
    up : tuple of 3 float
        The world's up direction in the body frame (R^T e_z).
    cog_offset : tuple of 3 float  [m]
    """

    up: tuple[float, float, float]
    cog_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class PointLoads:
    """Where the lift points' tensions load the girder: one point load per lug, per state.

    A single rope pulls its lug along the world vertical: its force is T times the body's
    up-vector. A sling's hook tension T splits into leg forces at its lugs, each along its leg,
    by the sling's statics at that state (:mod:`liftplan.planner.plans.strength_slings`): for a
    given state each leg's force is T times a fixed vector, so the girder stays linear in the
    hooks' tensions. Each point load enters the girder as :mod:`liftplan.model.strength.girder`
    takes it: its body-z component f_z at its x, and its body-x (axial) component as the couple
    (z - z_G) f_x (the axial force itself is not a bending moment or shear force).

    Parameters
    ----------
    x, z : (L,)  [m]
        Each load's point (its lug), body frame.
    owner : (L,) int
        The lift point (tension column, 0..count-1) whose tension it carries.
    normal, axial : (k, L)  [-]
        Its force's body-z and body-x components per unit tension of its owner, in each of
        k states.
    count : int
        Lift points (tension columns).
    """

    x: np.ndarray
    z: np.ndarray
    owner: np.ndarray
    normal: np.ndarray
    axial: np.ndarray
    count: int

    @staticmethod
    def ropes(points, states):
        """Single ropes at ``points`` (n, 3) [m]: each along the world vertical in every state."""
        points = np.asarray(points, dtype=float)
        up = np.array([state.up for state in states], dtype=float).reshape(-1, 3)
        n = len(points)
        return PointLoads(
            x=points[:, 0],
            z=points[:, 2],
            owner=np.arange(n),
            normal=np.repeat(up[:, 2:3], n, axis=1),
            axial=np.repeat(up[:, 0:1], n, axis=1),
            count=n,
        )

    def take(self, rows):
        """The same loads in the states ``rows`` only."""
        rows = np.asarray(rows, dtype=int)
        return PointLoads(self.x, self.z, self.owner, self.normal[rows], self.axial[rows], self.count)

    @property
    def gather(self):
        """(L, count) 0/1: which lift point each load hangs from (rows of loads -> columns)."""
        out = np.zeros((len(self.x), self.count))
        out[np.arange(len(self.x)), self.owner] = 1.0
        return out


def point_loads(points, states):
    """``points`` as :class:`PointLoads`: given so, or single ropes at (n, 3) positions [m]."""
    return points if isinstance(points, PointLoads) else PointLoads.ropes(points, states)


def section_rows(loads, points, sections, state, index=0):
    """M and Q at sections as affine functions of the tensions at the lift points.

    Parameters
    ----------
    loads : GirderLoads
    points : (n, 3) [m] or PointLoads
        Lug positions, body frame (single ropes), or the lift points' point loads (state
        ``index`` of them is this state's).
    sections : Sections
    state : State
    index : int
        Which state of ``points`` (a :class:`PointLoads`) this is.

    Returns
    -------
    gain_m : (S, n)  [m]    dM / dT
    offset_m : (S,)  [t m]
    gain_q : (S, n)  [-]    dQ / dT
    offset_q : (S,)  [t]
    """
    if not isinstance(points, PointLoads):
        points, index = PointLoads.ropes(points, [state]), 0
    u = np.asarray(state.up, dtype=float)
    dx, _, dz = state.cog_offset
    s, xc = sections.x[:, None], points.x[None, :]
    aft = (xc < s) | ((xc == s) & sections.right[:, None])
    weight_aft, moment_aft = loads.aft(sections.x, dx)
    normal, axial = points.normal[index], points.axial[index]
    per_m = aft * (normal * (s - xc) + axial * (points.z - loads.cog[2]))
    gather = points.gather
    offset_m = -u[2] * moment_aft - u[0] * dz * weight_aft
    return per_m @ gather, offset_m, (aft * normal) @ gather, -u[2] * weight_aft


def exact_curves(loads, points, tensions, state, index=0):
    """Shear force and bending moment of a state as exact piecewise polynomials.

    Parameters
    ----------
    loads : GirderLoads
    points : (n, 3) [m] or PointLoads   as :func:`section_rows`
    tensions : (n,)  [t]
    state : State
    index : int   which state of ``points`` (a PointLoads)

    Returns
    -------
    shear, moment : Piecewise  [t, t m]
    """
    if not isinstance(points, PointLoads):
        points, index = PointLoads.ropes(points, [state]), 0
    u = np.asarray(state.up, dtype=float)
    dx, _, dz = state.cog_offset
    weight = loads.curve(dx)
    breaks = np.union1d(weight.breaks, points.x)
    w = on_breaks(breaks, weight.breaks, weight.coef)
    index_x = np.searchsorted(breaks, points.x)
    carried = np.asarray(tensions, dtype=float)[points.owner]
    forces, couples = np.zeros(len(breaks)), np.zeros(len(breaks))
    np.add.at(forces, index_x, points.normal[index] * carried)
    np.add.at(couples, index_x, points.axial[index] * (points.z - loads.cog[2]) * carried)
    shear = Piecewise(breaks, -u[2] * w).integral(jumps=forces)
    moment = shear.integral(jumps=couples, density=Piecewise(breaks, -u[0] * dz * w))
    return shear, moment


@dataclass(frozen=True)
class Peak:
    """The worst of a curve over the body: its ratio to the allowable and where.

    Parameters
    ----------
    ratio : float  [-]   |value| / allowable (|value| when no envelope is given)
    value : float  [t m or t]   |value| there
    x : float  [m]
    state : int   index of the state it occurs in
    """

    ratio: float
    value: float
    x: float
    state: int


def curve_peak(curve, envelope):
    """(ratio, |value|, x) of a curve's worst point against an envelope, exactly."""
    if envelope is None:
        e = curve.extreme()
        return e.value, e.value, e.x
    x, value, limit = curve.worst_ratio(envelope)
    return value / limit, value, x


def allowable(envelope, x):
    """An allowable envelope [(x, value)] at sections x by linear interpolation (ones when None)."""
    if envelope is None:
        return np.ones(len(x))
    ex, ev = zip(*envelope)
    return np.interp(x, ex, ev)


def section_ratios(loads, envelopes, points, sections, states, tensions, hook=None):
    """Worst |M| / allowable and |Q| / allowable at the sections, per state, shape (2, k).

    Parameters
    ----------
    loads : GirderLoads
    envelopes : (bending, shear) allowable envelopes, each [(x m, value)] or None
    points : (n, 3) [m] or PointLoads
        Single ropes at lug positions, or the lift points' point loads in these k states.
    sections : Sections
    states : list of State
    tensions : (k, n)  [t]
    hook : (gain (k, n, n) [t/m], tolerance (n,) [m]), optional
        The hook errors' worst effect is added at every section.
    """
    points = point_loads(points, states)
    allow = (allowable(envelopes[0], sections.x), allowable(envelopes[1], sections.x))
    up = np.array([state.up for state in states], dtype=float)  # (k, 3)
    offsets = np.array([state.cog_offset for state in states], dtype=float)
    # the rows of section_rows, for every state at once: M = sum_l f_z,l (s - x_l) + f_x,l (z_l -
    # z_G) over the loads aft - u_z M_aft - u_x dz W_aft, Q = sum_l f_z,l - u_z W_aft; W_aft and
    # M_aft are affine in the CG's x offset
    s, xc = sections.x[:, None], points.x[None, :]
    aft = ((xc < s) | ((xc == s) & sections.right[:, None])).astype(float)
    arm_x, arm_z = aft * (s - xc), aft * (points.z[None, :] - loads.cog[2])
    w0, m0 = loads.aft(sections.x, 0.0)
    w1, m1 = loads.aft(sections.x, 1.0)
    dx, dz = offsets[:, :1], offsets[:, 2:]
    weight_aft, moment_aft = w0 + dx * (w1 - w0), m0 + dx * (m1 - m0)  # (k, S)
    uz, ux = up[:, 2:], up[:, :1]
    carried = np.asarray(tensions, dtype=float)[:, points.owner]  # (k, L)
    normal, axial = points.normal * carried, points.axial * carried
    moment = normal @ arm_x.T + axial @ arm_z.T - uz * moment_aft - ux * dz * weight_aft
    shear = normal @ aft.T - uz * weight_aft
    moment, shear = np.abs(moment), np.abs(shear)
    if hook is not None:
        gain, tolerance = hook
        per_load = np.asarray(gain, dtype=float)[:, points.owner, :]  # (k, L, n)
        by_normal = points.normal[:, :, None] * per_load
        by_axial = points.axial[:, :, None] * per_load
        by_m = np.einsum("sl,klm->ksm", arm_x, by_normal) + np.einsum("sl,klm->ksm", arm_z, by_axial)
        moment = moment + np.abs(by_m) @ tolerance
        shear = shear + np.abs(np.einsum("sl,klm->ksm", aft, by_normal)) @ tolerance
    return np.stack([(moment / allow[0]).max(axis=1), (shear / allow[1]).max(axis=1)])


def exact_peaks(loads, envelopes, points, tensions, states, hook=None):
    """The exact worst |M| and |Q| ratios over the given states, along the whole body.

    Parameters
    ----------
    loads, envelopes, points, states, hook
        As :func:`section_ratios` (``points`` as PointLoads: in these states); the hook
        errors' worst effect is added at each curve's worst point.
    tensions : (k, n)  [t]

    Returns
    -------
    peaks : list of 2 Peak
        Bending, shear; ``Peak.state`` indexes ``states``.
    worst_x : list of float  [m]
        Each state's worst sections (for cutting planes).
    """
    points = point_loads(points, states)
    best = [None, None]
    worst_x = []
    for k, state in enumerate(states):
        shear, moment = exact_curves(loads, points, tensions[k], state, k)
        for which, curve in ((0, moment), (1, shear)):
            ratio, value, x = curve_peak(curve, envelopes[which])
            if hook is not None:  # the hook errors' largest effect at that section
                sec = Sections(np.array([x]), np.array([True]))
                g = section_rows(loads, points, sec, state, k)[2 * which]
                extra = float((np.abs(g @ hook[0][k]) @ hook[1])[0])
                value, ratio = value + extra, ratio + extra / allowable(envelopes[which], [x])[0]
            worst_x.append(x)
            if best[which] is None or ratio > best[which].ratio:
                best[which] = Peak(ratio=ratio, value=value, x=x, state=k)
    return best, worst_x


def force_attitude(points, tensions, weight, cog, offsets):
    """Body up-vectors of constant lug forces holding the body with each CG offset.

    Constant vertical forces T (summing to W, balancing the nominal CG at level) hold the body
    where the line from its CG G' to the force centre F = sum T_i p_i / W is vertical: the
    body's up-vector is (F - G') / |F - G'|, stable while F is above G'.

    Returns
    -------
    up : (k, 3)
    height : (k,)  [m]   F_z - G'_z (must be > 0)
    """
    centre = (np.asarray(tensions) @ points) / weight
    arm = centre[None, :] - (np.asarray(cog)[None, :] + offsets)
    arm[:, :2] = -offsets[:, :2]  # the level statics put F over the nominal CG exactly
    return arm / np.linalg.norm(arm, axis=1, keepdims=True), arm[:, 2]


def body_tilt(up):
    """(heel, trim) [deg] of a body up-vector, about the body's own axes (at zero yaw the
    README's convention: up = (-cos heel sin trim, sin heel, cos heel cos trim))."""
    u = np.asarray(up, dtype=float)
    return float(np.degrees(np.arcsin(np.clip(u[1], -1, 1)))), float(np.degrees(np.arctan2(-u[0], u[2])))


# -- the per-set linear program -------------------------------------------------------------------
@dataclass(frozen=True)
class LPResult:
    """Optimum of :class:`StrengthLP`.

    Parameters
    ----------
    preload : (n,)  [t]   level tensions T* (force control: the forces)
    bending, shear, spread : float   the worst of each over the rows given  [-, -, t]
    value : float   the objective (weights x the three)
    """

    preload: np.ndarray
    bending: float
    shear: float
    spread: float
    value: float


def _bucket(count, least=16):
    """Row capacity for ``count`` rows: the next power of two (few builds, little padding)."""
    return max(least, 1 << max(0, math.ceil(math.log2(max(count, 1)))))


class StrengthLP:
    """min over T* of  w_M max|M|/M_allow + w_Q max|Q|/Q_allow + w_S max spread  over rows.

    Rows (each padded to its capacity by repeating its last row, which changes nothing):

    * ratio rows r of M and Q: |g_r . T* + h_r| + m_r <= t (g, h divided by the allowable at
      the row's section; m the hook errors' largest effect);
    * tension rows: lower <= G_r . T* + h_r -+ m_r <= upper, in blocks of n per scenario;
    * the level statics A0 T* = b0, the preload's range, and one row a . T* >= c (force
      control: the force centre high enough above the CG; unused rows are 0 >= -1).

    Parameters
    ----------
    n : int
    rows_m, rows_q, scenarios : int   capacities
    """

    def __init__(self, n, rows_m, rows_q, scenarios):
        self.n, self.shape = n, (rows_m, rows_q, scenarios)
        self.weights = cp.Parameter(3, nonneg=True, name="weights")
        blocks = {}
        t = {"m": cp.Variable(name="bending"), "q": cp.Variable(name="shear")}
        preload = cp.Variable(n, name="T_star")
        constraints = []
        for key, rows in (("m", rows_m), ("q", rows_q)):
            g = cp.Parameter((rows, n), name=f"g_{key}")
            h = cp.Parameter(rows, name=f"h_{key}")
            m = cp.Parameter(rows, nonneg=True, name=f"margin_{key}")
            blocks[key] = (g, h, m)
            value = g @ preload + h
            constraints += [value + m <= t[key], -value + m <= t[key]]
        k = scenarios
        self.tg = cp.Parameter((k * n, n), name="P")
        self.th = cp.Parameter(k * n, name="q")
        self.tm = cp.Parameter(k * n, nonneg=True, name="hook_margin")
        self.low = cp.Parameter(k * n, name="tension_low")
        self.high = cp.Parameter(k * n, name="tension_high")
        self.a0 = cp.Parameter((3, n), name="A0")
        self.b0 = cp.Parameter(3, name="b0")
        self.plo = cp.Parameter(n, name="preload_low")
        self.phi = cp.Parameter(n, name="preload_high")
        self.lift_row = cp.Parameter(n, name="centre_row")
        self.lift_low = cp.Parameter(name="centre_low")
        tensions = self.tg @ preload + self.th
        hi, lo, spread = cp.Variable(k, name="hi"), cp.Variable(k, name="lo"), cp.Variable(name="spread")
        block = sparse.kron(sparse.eye(k), np.ones((n, 1)), format="csr")  # rope rows -> scenario
        constraints += [
            self.a0 @ preload == self.b0,
            preload >= self.plo,
            preload <= self.phi,
            tensions - self.tm >= self.low,
            tensions + self.tm <= self.high,
            tensions + self.tm <= block @ hi,
            tensions - self.tm >= block @ lo,
            hi - lo <= spread,
            self.lift_row @ preload >= self.lift_low,
        ]
        objective = (
            self.weights[0] * t["m"]
            + self.weights[1] * t["q"]
            + self.weights[2] * spread
            + TIE_BREAK * (t["m"] + t["q"])
        )
        self.problem = _checked(cp.Problem(cp.Minimize(objective), constraints), "strength LP")
        self.blocks, self.t, self.preload, self.spread = blocks, t, preload, spread

    def solve(self, weights, rows_m, rows_q, tension_rows, a0, b0, preload_range, centre=None):
        """Solve for the rows given.

        Parameters
        ----------
        weights : (3,)   of bending ratio, shear ratio, spread [t]
        rows_m, rows_q : (g (r, n), h (r,), m (r,))   already divided by the allowables
        tension_rows : (G (k, n, n), h (k, n), m (k, n), low (k, n), high (k, n))  [t]
        a0, b0 : level statics
        preload_range : (low (n,), high (n,))  [t]
        centre : (row (n,), low) or None   row . T* >= low

        Returns
        -------
        LPResult

        Raises
        ------
        PlanInfeasible, SolverFailed
        """
        n = self.n
        big = 100.0 * abs(float(b0[0]))
        for key, rows, cap in (("m", rows_m, self.shape[0]), ("q", rows_q, self.shape[1])):
            g, h, m = (np.asarray(v, dtype=float) for v in rows)
            pad = np.r_[np.arange(len(h)), np.full(cap - len(h), len(h) - 1)]
            pg, ph, pm = self.blocks[key]
            pg.value, ph.value, pm.value = g[pad], h[pad], m[pad]
        gain, offset, margin, low, high = (np.asarray(v, dtype=float) for v in tension_rows)
        k = gain.shape[0]
        pad = np.r_[np.arange(k), np.full(self.shape[2] - k, k - 1)]
        self.tg.value = gain[pad].reshape(-1, n)
        self.th.value = offset[pad].ravel()
        self.tm.value = margin[pad].ravel()
        self.low.value = np.clip(low[pad].ravel(), -big, big)
        self.high.value = np.clip(high[pad].ravel(), -big, big)
        self.a0.value, self.b0.value = np.asarray(a0, float), np.asarray(b0, float)
        self.plo.value = np.clip(np.asarray(preload_range[0], float), -big, big)
        self.phi.value = np.clip(np.asarray(preload_range[1], float), -big, big)
        row, floor = centre if centre is not None else (np.zeros(n), -1.0)
        self.lift_row.value, self.lift_low.value = np.asarray(row, float), float(floor)
        self.weights.value = np.asarray(weights, dtype=float)
        value = _run(self.problem, "strength LP")
        return LPResult(
            preload=np.array(self.preload.value),
            bending=float(self.t["m"].value),
            shear=float(self.t["q"].value),
            spread=float(self.spread.value),
            value=value,
        )


_LPS = {}


def strength_lp(n, rows_m, rows_q, scenarios):
    """The :class:`StrengthLP` for these sizes (capacities rounded up; built once each)."""
    key = (n, _bucket(rows_m), _bucket(rows_q), _bucket(scenarios, 1))
    if key not in _LPS:
        _LPS[key] = StrengthLP(*key)
    return _LPS[key]


# -- the candidates: a mixed-integer program --------------------------------------------------------
@dataclass(frozen=True)
class MIPResult:
    """Optimum of :class:`CandidateMIP`.

    Parameters
    ----------
    chosen : tuple of int   candidate indices, ascending
    kinds : tuple of int   the crane class on each chosen candidate (0 for one class)
    forces : (C,)  [t]   the level tensions on every candidate (0 where not chosen)
    value : float   HiGHS's dual bound (at most the optimum less its relative gap): a lower
        bound on every (set, assignment) not cut off
    incumbent : float   the objective of the set returned
    complete : bool   False when HiGHS stopped at its time limit (the set is its best found)
    """

    chosen: tuple[int, ...]
    forces: np.ndarray
    value: float
    incumbent: float = math.nan
    complete: bool = True
    kinds: tuple[int, ...] = ()

    @property
    def columns(self):
        """The chosen (candidate, class) columns as :class:`CandidateMIP` numbers them."""
        return tuple(zip(self.chosen, self.kinds))


class CandidateMIP:
    """Choose n of C candidates, the crane class on each, and their level tensions (HiGHS
    branch and bound).

    A binary per (candidate, crane class) column says that a crane of that class takes that
    candidate: each class places as many cranes as it has, a candidate takes one crane at
    most, and a tension's limits are those of the class on it (each crane's chart SWL at its
    radius to that candidate through the rules' chain; a column a crane cannot reach, or whose
    booms would clash, is excluded). One class (equal cranes) is the plain choice of n
    candidates.

    Scenario 0 is the level state with the nominal CG, its tensions the plan's T* under
    either control. Scenarios 1.. are, for force control, the same tensions (``shared``) and,
    for hoist control, tension vectors of their own that need only be statically admissible
    and within the limits at that scenario (a relaxation of the held model: the optimum is a
    lower bound on every lug set's value). Unchosen candidates carry no tension.

    Parameters
    ----------
    count, n : int   candidates, lugs to choose
    rows_m, rows_q : int   ratio rows per scenario
    scenarios : int
    shared : bool   force control (one tension vector for every scenario)
    counts : sequence of int, optional   cranes of each class (default: one class of n)
    """

    def __init__(self, count, n, rows_m, rows_q, scenarios, shared, counts=None):
        c, k = count, scenarios
        counts = (n,) if counts is None else tuple(int(v) for v in counts)
        kinds = len(counts)
        self.shape = (count, n, rows_m, rows_q, scenarios, shared, kinds)
        self.weights = cp.Parameter(3, nonneg=True, name="weights")
        z = cp.Variable(c * kinds, boolean=True, name="chosen")  # candidate-major columns
        # each candidate's columns summed: 1 where it is chosen
        per_candidate = sparse.kron(sparse.eye(c), np.ones((1, kinds)), format="csr")
        per_class = sparse.kron(np.ones((1, c)), sparse.eye(kinds), format="csr")
        used = per_candidate @ z
        tensions = [cp.Variable(c, name="T0")]
        tensions += [tensions[0]] * (k - 1) if shared else [cp.Variable(c, name=f"T{j}") for j in range(1, k)]
        t_m, t_q, spread = cp.Variable(name="bending"), cp.Variable(name="shear"), cp.Variable(name="spread")
        self.low = cp.Parameter(c, nonneg=True, name="low")
        self.high = cp.Parameter(c * kinds, nonneg=True, name="high")
        self.level_high = cp.Parameter(c * kinds, nonneg=True, name="level_high")
        self.level_low = cp.Parameter(c * kinds, nonneg=True, name="level_low")
        self.usable = cp.Parameter(c * kinds, nonneg=True, name="usable")
        self.big = cp.Parameter(nonneg=True, name="big")
        self.statics = [(cp.Parameter((3, c), name=f"A{j}"), cp.Parameter(3, name=f"b{j}")) for j in range(k)]
        self.rows = []
        self.centre_row = cp.Parameter(c, name="centre_row")
        self.centre_low = cp.Parameter(name="centre_low")
        constraints = [
            per_class @ z == np.array(counts, dtype=float),
            used <= 1,
            z <= self.usable,
            tensions[0] <= per_candidate @ cp.multiply(self.level_high, z),
            tensions[0] >= per_candidate @ cp.multiply(self.level_low, z),
            self.centre_row @ tensions[0] >= self.centre_low,
        ]
        for j in range(k):
            tj = tensions[j]
            a, b = self.statics[j]
            hi, lo = cp.Variable(name=f"hi{j}"), cp.Variable(name=f"lo{j}")
            constraints += [
                a @ tj == b,
                tj >= cp.multiply(self.low, used),
                tj <= per_candidate @ cp.multiply(self.high, z),
                tj <= hi,
                tj + self.big * (1 - used) >= lo,
                hi - lo <= spread,
            ]
            block = []
            for key, rows, t in (("m", rows_m, t_m), ("q", rows_q, t_q)):
                g = cp.Parameter((rows, c), name=f"g_{key}{j}")
                h = cp.Parameter(rows, name=f"h_{key}{j}")
                constraints += [g @ tj + h <= t, -(g @ tj + h) <= t]
                block.append((g, h))
            self.rows.append(block)
            if shared:
                break  # every scenario's rows act on the same tensions: stack them in block 0
        objective = (
            self.weights[0] * t_m + self.weights[1] * t_q + self.weights[2] * spread + TIE_BREAK * (t_m + t_q)
        )
        self.constraints, self.objective = constraints, objective
        self.z, self.tensions = z, tensions

    def solve(self, weights, statics, rows, limits, centre=None, cuts=(), time_limit=None, clashes=()):
        """Solve.

        Parameters
        ----------
        weights : (3,)
        statics : list of (A (3, C), b (3,))   per scenario (shared: only the first is used)
        rows : list of ((g_m, h_m), (g_q, h_q))   per scenario block, padded here
        limits : (low (C,), high (C, K), level_high (C, K)[, level_low (C, K)])  [t]   per
            column; NaN (or a level range empty) where a class cannot take the candidate; (C,)
            arrays for one class. ``level_low`` (default ``low``): the least level tension (the
            boom range's)
        centre : (row (C,), low) or None
        cuts : sequence of tuples of (candidate, class)   (set, assignment) rows to exclude
            (no-good cuts; :attr:`MIPResult.columns`)
        time_limit : float or None  [s]
        clashes : (P, 2) int   column pairs (candidate x K + class) that may not both be chosen

        Returns
        -------
        MIPResult
        """
        count, n, rows_m, rows_q, k, shared, kinds = self.shape
        for j, block in enumerate(self.rows):
            for (g, h), (gv, hv), cap in zip(block, rows[j], (rows_m, rows_q)):
                gv, hv = np.asarray(gv, float), np.asarray(hv, float)
                pad = np.r_[np.arange(len(hv)), np.full(cap - len(hv), len(hv) - 1)]
                g.value, h.value = gv[pad], hv[pad]
        for j, (a, b) in enumerate(self.statics):
            a.value, b.value = (np.asarray(v, float) for v in statics[min(j, len(statics) - 1)])
        low = np.asarray(limits[0], float)
        high, level_high = (np.asarray(v, float).reshape(count, kinds) for v in limits[1:3])
        level_low = np.broadcast_to(low[:, None], high.shape)
        if len(limits) > 3:
            level_low = np.fmax(level_low, np.asarray(limits[3], float).reshape(count, kinds))
        usable = ~np.isnan(high) & ~np.isnan(level_high) & (np.minimum(level_high, high) >= level_low)
        high = np.where(usable, high, 0.0)
        level_high = np.where(usable, np.minimum(level_high, high), 0.0)
        self.low.value = low
        self.high.value, self.level_high.value = high.ravel(), level_high.ravel()
        self.level_low.value = np.where(usable, level_low, 0.0).ravel()
        self.usable.value = usable.ravel().astype(float)
        self.big.value = float(max(np.max(high), np.max(low), 0.0))
        row, floor = centre if centre is not None else (np.zeros(count), -1.0)
        self.centre_row.value, self.centre_low.value = np.asarray(row, float), float(floor)
        self.weights.value = np.asarray(weights, float)
        extra = []
        for cut in cuts:
            cols = [int(i) * kinds + int(kind) for i, kind in cut]
            extra.append(cp.sum(self.z[cols]) <= n - 1)
        clashes = np.asarray(clashes, dtype=np.int64).reshape(-1, 2)
        if len(clashes):
            extra.append(self.z[clashes[:, 0]] + self.z[clashes[:, 1]] <= 1)
        problem = cp.Problem(cp.Minimize(self.objective), self.constraints + extra)
        options = {"mip_rel_gap": MIP_GAP}
        if time_limit is not None:
            options["time_limit"] = float(max(time_limit, 1.0))
        run_highs(problem, "lug choice (MIP)", **options)
        if problem.status in (cp.INFEASIBLE, cp.INFEASIBLE_INACCURATE):
            raise PlanInfeasible("lug choice (MIP): no lug set, cranes and tensions satisfy the limits")
        complete = problem.status == cp.OPTIMAL
        if (
            self.z.value is None
            or problem.value is None
            or not (complete or problem.status in (cp.OPTIMAL_INACCURATE, cp.USER_LIMIT))
        ):
            raise SolverFailed(f"lug choice (MIP): HiGHS ended with status {problem.status!r} and no lug set")
        picked = np.nonzero(np.asarray(self.z.value) > 0.5)[0]
        value = float(problem.value)
        info = problem.solver_stats.extra_stats
        dual = getattr(info, "mip_dual_bound", None)
        bound = value - MIP_GAP * abs(value)
        if dual is not None and np.isfinite(dual):
            bound = min(bound, float(dual))
        elif not complete:
            bound = -math.inf  # stopped with no bound known: no gap is claimed
        return MIPResult(
            chosen=tuple(int(i) for i in picked // kinds),
            kinds=tuple(int(i) for i in picked % kinds),
            forces=np.array(self.tensions[0].value),
            value=bound,
            incumbent=value,
            complete=complete,
        )
