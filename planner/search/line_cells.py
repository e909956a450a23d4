"""A lower bound for every lug set on two lines, cell by cell of the lines' lug means.

The two-line bound (:mod:`~liftplan.planner.search.lines`) uses what the statics fix per
line: its total. This one adds what the statics and the rope model fix along the lines,
for lugs at stations of a spacing (frames) on two parallel lines in one body plane, held by
equal ropes (:mod:`~liftplan.planner.search.coplanar`: a scenario is an effective CG g).

Take the lines' along coordinate s and across coordinate t (line j at t_j), n_j lugs on
line j with mean m_j and within-line sum of squares V_j (V = V_0 + V_1), u_i = s_i - m_j.
Solving the statics of a plane of tension changes gives, at any effective CG g,

    T_i(g) = mu_j(g) + rho_i + (W / V) [(g - r)_s - (g - r)_t (m_0 - m_1) / (t_0 - t_1)] u_i

with mu_j(g) = F_j(g) / n_j the line's mean (F_j what the statics give the line), r a
reference CG and rho the preload's deviation, which sums to zero on each line and carries
the moment sum rho_i u_i = W e_r, e_r = r_s - (F_0(r) m_0 + F_1(r) m_1) / W: how far the CG
stands along the lines from where the lines' lugs would hold it evenly. The spread's LP
dual then gives closed lower bounds for any set, in which the preload cancels:

* one scenario g, a line H taken as the upper and L as the lower, weights 1 / n_H - kappa u
  on H's lugs and 1 / n_L + kappa u on L's (kappa keeping every station's weight >= 0):
  spread >= D_g - kappa W e_g, D_g = mu_H(g) - mu_L(g) (kappa = 0 is the two-line bound);
* two scenarios A, B (``same``): those weights shared between them, mass theta to A, each
  line's lugs taken in order along it: theta D_A + (1 - theta) D_B + (W gamma / V) Z -
  kappa W e_r, with r = (A + B) / 2, gamma = (A - r)_s - (A - r)_t (m_0 - m_1) / (t_0 - t_1)
  and Z the sum of weight x u over H's lugs in A's part and L's in B's, less the rest;
* two scenarios and two lugs (``pair``): (Delta_p - Delta_q) / 2 with Delta = T(A) - T(B),
  p and q a line's first or last lug.

A set's bound depends on it through (n_0, m_0, m_1) and sums over its lugs. So the sets are
split into cells of equal counts and index sums on each line (the means m_j are then
fixed); a cell whose one-scenario bound (closed form, all cells at once) reaches the target
is done; in the others a dynamic programme over the stations finds the set that does worst
against a convex combination of the ``same`` and ``pair`` bounds (each one's condition
"bound >= target" is linear in the set's sums once multiplied by V), and a small LP picks
the combination against the sets found so far (column generation), until no set in the
cell falls below the target or the sets found show the cell cannot be closed at it; such a
cell gets its own bound by bisection. No set is missed: every set is in one cell, and in a
cell the programme ranges over every subset of the stations with its counts and sums.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from scipy.optimize import linprog

from liftplan.planner.search.coplanar import coplanar, corner_scenarios, effective_cogs
from liftplan.planner.search.lines import count_bounds, two_lines

#: kappa as fractions of its largest value either way, and theta, of the ``same`` bounds.
KAPPAS = (1.0, 0.7, 0.4, 0.0, -0.4, -0.7, -1.0)
THETAS = (0.0, 0.05, 0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 0.9, 0.95, 1.0)
#: Column-generation rounds per cell, and bisection steps for a cell that fails the target.
ROUNDS, BISECTIONS = 12, 6
#: Cells whose one-scenario bound is evaluated at once.
CHUNK = 200_000
_INF = 1e300


@dataclass(frozen=True)
class Grid:
    """One line's stations: s = offset + spacing k for the integers k  [m].

    Parameters
    ----------
    offset, spacing : float  [m]
    index : numpy.ndarray of int
        k of each station, ascending (from 0).
    candidate : numpy.ndarray of int
        The candidate at each station.
    """

    offset: float
    spacing: float
    index: np.ndarray
    candidate: np.ndarray

    @property
    def s(self):
        """Along coordinate of each station  [m]."""
        return self.offset + self.spacing * self.index

    def sums(self, n):
        """Least and largest index sum of n distinct stations."""
        return int(self.index[:n].sum()), int(self.index[len(self.index) - n :].sum())


@dataclass(frozen=True)
class Layout:
    """Two lines of stations in the body plane, in line coordinates.

    Parameters
    ----------
    grids : tuple of two Grid
    across : tuple of two float  [m]
        Across coordinate t_j of each line.
    axes : numpy.ndarray, shape (2, 2)
        Body plan unit vectors along (s) and across (t) the lines.
    """

    grids: tuple
    across: tuple
    axes: np.ndarray


@dataclass(frozen=True)
class CellBound:
    """The cell-by-cell bound and what it took.

    Parameters
    ----------
    value : float
        No set does better over the scenarios  [objective unit].
    cells : int
        Cells (counts and index sums) the two-line bound left open.
    searched : int
        Cells whose one-scenario bound fell below the target (searched by the programme).
    failed : int
        Searched cells not closed at the target (each bounded by bisection).
    seconds : float
    complete : bool
        False when a deadline or Ctrl-C stopped the search (the open cells then count at
        their one-scenario bound).
    interrupted : bool
        True when it was Ctrl-C.
    """

    value: float
    cells: int
    searched: int
    failed: int
    seconds: float
    complete: bool
    interrupted: bool = False


def layout(problem):
    """:class:`Layout` of the candidates, or None where the bound does not apply: not two
    lines, not one body plane with equal ropes, or stations not at one spacing on a line."""
    lines = two_lines(problem)
    if lines is None or coplanar(problem) is None or abs(lines.direction[2]) > 1e-9:
        return None
    along = np.asarray(lines.direction[:2], dtype=float)
    along = along / np.linalg.norm(along)
    axes = np.array([along, [-along[1], along[0]]])
    plan = np.asarray(problem.points, dtype=float)[:, :2] @ axes.T
    size = max(1.0, float(np.ptp(plan, axis=0).max()))
    grids, across = [], []
    for j in (0, 1):
        members = np.flatnonzero(lines.line == j)
        s = plan[members, 0]
        order = np.argsort(s)
        s, members = s[order], members[order]
        steps = np.diff(s)
        if len(s) < 2 or steps.min() <= 1e-9 * size:
            return None  # one station, or two candidates at one station
        spacing = float(steps.min())
        index = (s - s[0]) / spacing
        if np.max(np.abs(index - np.round(index))) > 1e-6:
            return None  # not at one spacing
        grids.append(Grid(float(s[0]), spacing, np.round(index).astype(int), members))
        across.append(float(plan[members[0], 1]))
    return Layout(tuple(grids), tuple(across), axes)


def applies(problem):
    """True when :func:`cell_bound` can run (the spread, or utilisation with one SWL)."""
    if problem.goal.peak or layout(problem) is None:
        return False
    swl = problem.reach[1]
    return not problem.goal.per_swl or float(np.nanmax(swl)) == float(np.nanmin(swl))


class _Cells:
    """The data one count split shares: corners, line coordinates, scale."""

    def __init__(self, problem, lay, corners, n0):
        self.weight = float(problem.body.weight)
        self.grids = lay.grids
        self.t = np.array(lay.across)
        self.g = corners  # (K, 2) effective CGs in line coordinates (s, t)
        self.n = np.array([n0, problem.cranes - n0])

    def shares(self, g_t):
        """What each line carries at across coordinate(s) g_t  [t], shape (..., 2)."""
        f0 = self.weight * (np.asarray(g_t) - self.t[1]) / (self.t[0] - self.t[1])
        return np.stack([f0, self.weight - f0], axis=-1)

    def means(self, sums):
        """Line means m_j of index sums (..., 2)  [m]."""
        sums = np.asarray(sums, dtype=float)
        return np.stack(
            [
                (self.grids[j].offset * self.n[j] + self.grids[j].spacing * sums[..., j]) / self.n[j]
                for j in (0, 1)
            ],
            axis=-1,
        )

    def kappa_range(self, m, high):
        """Largest kappa >= 0 and |kappa| for kappa <= 0 keeping every station's weight >= 0
        with line ``high`` as H (weights 1/n_H - kappa u) and the other as L (1/n_L + kappa u)."""
        low = 1 - high
        s_lo = np.array([g.s[0] for g in self.grids])
        s_hi = np.array([g.s[-1] for g in self.grids])
        n = self.n

        def cap(span, count):
            with np.errstate(divide="ignore"):
                return np.where(span > 1e-12, 1.0 / (count * np.maximum(span, 1e-300)), np.inf)

        pos = np.minimum(cap(m[..., low] - s_lo[low], n[low]), cap(s_hi[high] - m[..., high], n[high]))
        neg = np.minimum(cap(s_hi[low] - m[..., low], n[low]), cap(m[..., high] - s_lo[high], n[high]))
        return np.minimum(pos, 1e6), np.minimum(neg, 1e6)

    def offset(self, g, m):
        """e_g = g_s - (F_0(g) m_0 + F_1(g) m_1) / W  [m] (broadcast)."""
        share = self.shares(g[..., 1])
        return g[..., 0] - (share[..., 0] * m[..., 0] + share[..., 1] * m[..., 1]) / self.weight

    def one_scenario(self, sums):
        """The one-scenario bound of each cell, shape sums.shape[:-1]."""
        m = self.means(sums)
        best = np.full(m.shape[:-1], -np.inf)
        for g in self.g:
            share = self.shares(g[1])
            mu = share / self.n
            e = self.offset(g, m)
            for high in (0, 1):
                d = mu[high] - mu[1 - high]
                pos, neg = self.kappa_range(m, high)
                best = np.maximum(best, d + self.weight * np.maximum(-pos * e, neg * e))
        return best


class Same(NamedTuple):
    """A two-scenario bound: theta D_A + (1 - theta) D_B - kappa W e_r (``const``, t) plus
    W ``gamma`` Z / V; line ``high`` is H."""

    high: int
    kappa: float
    theta: float
    gamma: float
    const: float


class Pair(NamedTuple):
    """A two-scenario, two-lug bound: ``const`` (t) plus W ``gamma`` (u_p - u_q) / (2 V); p and
    q are (line, 1 for its last lug or 0 for its first)."""

    p: tuple
    q: tuple
    gamma: float
    const: float


def _families(cells, m):
    """The :class:`Same` and :class:`Pair` bounds of one cell (line means m)."""
    weight, h = cells.weight, cells.t[0] - cells.t[1]
    dm = m[0] - m[1]
    out = []
    count = len(cells.g)
    for a in range(count):
        for b in range(a + 1, count):
            ga, gb = cells.g[a], cells.g[b]
            gamma = 0.5 * ((ga[0] - gb[0]) - (ga[1] - gb[1]) * dm / h)
            if gamma < 0:
                ga, gb, gamma = gb, ga, -gamma
            r = 0.5 * (ga + gb)
            e_r = float(cells.offset(r, m))
            mu_a, mu_b = cells.shares(ga[1]) / cells.n, cells.shares(gb[1]) / cells.n
            high = 0 if (mu_a[0] - mu_a[1]) + (mu_b[0] - mu_b[1]) >= 0 else 1
            d_a, d_b = mu_a[high] - mu_a[1 - high], mu_b[high] - mu_b[1 - high]
            pos, neg = cells.kappa_range(m, high)
            for fraction in KAPPAS:
                kappa = fraction * (pos if fraction > 0 else neg)
                if not np.isfinite(kappa):
                    continue
                for theta in THETAS:
                    out.append(
                        Same(
                            high,
                            float(kappa),
                            theta,
                            float(gamma),
                            theta * d_a + (1 - theta) * d_b - kappa * weight * e_r,
                        )
                    )
    for a in range(count):
        for b in range(count):
            if a == b:
                continue
            ga, gb = cells.g[a], cells.g[b]
            gamma = (ga[0] - gb[0]) - (ga[1] - gb[1]) * dm / h
            delta = (cells.shares(ga[1]) - cells.shares(gb[1])) / cells.n  # Delta mu per line
            for p, q in (
                ((0, 1), (1, 0)),
                ((0, 0), (1, 1)),
                ((0, 1), (0, 0)),
                ((1, 1), (1, 0)),
                ((1, 1), (0, 0)),
                ((1, 0), (0, 1)),
            ):  # (line, 1 = last / 0 = first)
                out.append(Pair(p, q, float(gamma), 0.5 * (delta[p[0]] - delta[q[0]])))
    return out


def _values(cells, families, sets, m):
    """Each family's bound for each set (rows: sets), in the objective's unit."""
    weight = cells.weight
    rows = []
    for chosen in sets:
        s = [np.sort(cells.grids[j].s[np.isin(cells.grids[j].index, chosen[j])]) for j in (0, 1)]
        u = [s[j] - m[j] for j in (0, 1)]
        vv = float(sum(np.sum(x * x) for x in u))
        row = np.empty(len(families))
        same = [k for k, f in enumerate(families) if isinstance(f, Same)]
        if same:
            high = np.array([families[k].high for k in same])
            kappa = np.array([families[k].kappa for k in same])
            theta = np.array([families[k].theta for k in same])
            z = np.zeros(len(same))
            for j in (0, 1):
                is_high = high == j
                w = 1.0 / cells.n[j] + np.where(is_high, -kappa, kappa)[:, None] * u[j][None, :]
                split = np.where(is_high, 1 - theta, theta)[:, None]
                before = np.cumsum(w, axis=1) - w
                bottom = np.clip(split - before, 0.0, w)
                z += np.sum(u[j][None, :] * (w - 2 * bottom), axis=1)
            gamma = np.array([families[k].gamma for k in same])
            const = np.array([families[k].const for k in same])
            row[same] = const + weight * gamma * z / vv
        for k, f in enumerate(families):
            if isinstance(f, Pair):
                up = u[f.p[0]][-1 if f.p[1] else 0]
                uq = u[f.q[0]][-1 if f.q[1] else 0]
                row[k] = f.const + weight * f.gamma * (up - uq) / (2 * vv)
        rows.append(row)
    return np.array(rows)


def _programme(cells, j, total, families, lam, target, m):
    """min over sets of line j's stations with n_j lugs and index sum ``total`` of that line's
    part of  sum_f lam_f V (bound_f - target); returns (value, chosen indices) or (-inf, None)
    when a weight is negative at a station (that combination is not a bound here)."""
    grid, n = cells.grids[j], int(cells.n[j])
    weight = cells.weight
    width = total + 1
    c_total, same, first, last = 0.0, [], 0.0, 0.0
    for f, la in zip(families, lam):
        if la <= 0:
            continue
        c_total += la * (target - f.const)
        if isinstance(f, Same):
            sign = -1.0 if j == f.high else 1.0
            split = (1 - f.theta) if j == f.high else f.theta
            same.append((la * weight * f.gamma, sign * f.kappa, split))
            continue
        for (line, end), sign in ((f.p, 1.0), (f.q, -1.0)):
            if line == j:
                if end:
                    last += la * sign * weight * f.gamma / 2
                else:
                    first += la * sign * weight * f.gamma / 2
    sums = np.arange(width)
    table = np.full((len(grid.index) + 1, n + 1, width), _INF)
    table[0, 0, 0] = 0.0
    for step, (k_s, s_s) in enumerate(zip(grid.index, grid.s)):
        table[step + 1] = table[step]
        if k_s > total:
            continue
        u_s = s_s - m[j]
        for count in range(min(n - 1, step), -1, -1):
            source = table[step, count, : width - k_s]
            value = source - c_total * u_s * u_s
            partial = grid.offset * count + grid.spacing * sums[: width - k_s]  # sum of s so far
            for scale, kappa, split in same:
                w = 1.0 / n + kappa * u_s
                if w < -1e-12:
                    return -np.inf, None
                before = count / n + kappa * (partial - count * m[j])
                bottom = np.clip(split - before, 0.0, w)
                value = value + scale * u_s * (w - 2 * bottom)
            if count == 0:
                value = value + first * u_s
            if count == n - 1:
                value = value + last * u_s
            np.minimum(table[step + 1, count + 1, k_s:], value, out=table[step + 1, count + 1, k_s:])
    best = table[-1, n, total]
    if best >= _INF / 2:
        return np.inf, None  # no set of these stations has this index sum
    chosen, count, rest = [], n, total
    for step in range(len(grid.index), 0, -1):
        if table[step, count, rest] == table[step - 1, count, rest]:
            continue
        k_s = int(grid.index[step - 1])
        chosen.append(k_s)
        count, rest = count - 1, rest - k_s
    return float(best), np.array(sorted(chosen))


class _Cell:
    """One cell's bounds and the sets its programme has found (their bounds do not depend on
    the target, so a bisection reuses them)."""

    def __init__(self, cells, sums):
        self.sums = np.asarray(sums)
        self.m = cells.means(self.sums)
        self.families = _families(cells, self.m)
        self.values = []  # each found set's bound under every family

    def combination(self, target):
        """The combination of bounds that does best against the sets found so far, or None
        when some found set is below ``target`` under every combination (a small LP)."""
        count = len(self.families)
        if not self.values:
            first = np.zeros(count)
            first[0] = 1.0
            return first
        table = np.array(self.values) - target
        found = linprog(
            np.r_[np.zeros(count), -1.0],
            A_ub=np.hstack([-table, np.ones((len(table), 1))]),
            b_ub=np.zeros(len(table)),
            A_eq=[np.r_[np.ones(count), 0.0]],
            b_eq=[1.0],
            bounds=[(0, None)] * count + [(None, None)],
            method="highs",
        )
        return None if found.status != 0 or -found.fun < 0 else found.x[:count]


def _closes(cells, cell, target, tolerance):
    """True when no set in the :class:`_Cell` falls below ``target`` (the programme's least
    value at or above -``tolerance``, in t m2: rounding)."""
    for _ in range(ROUNDS):
        lam = cell.combination(target)
        if lam is None:
            return False  # some set found is below the target for every combination
        parts = [_programme(cells, j, int(cell.sums[j]), cell.families, lam, target, cell.m) for j in (0, 1)]
        if any(p[1] is None and p[0] == -np.inf for p in parts):
            return False
        if any(p[0] == np.inf for p in parts) or sum(p[0] for p in parts) >= -tolerance:
            return True
        cell.values.append(_values(cells, cell.families, [[parts[0][1], parts[1][1]]], cell.m)[0])
    return False


def _open_cells(cells, lay, two_line, target):
    """The cells of one count split whose one-scenario bound (at least ``two_line``) is
    below ``target``: (index sums (k, 2), their bounds (k,), cells in all). Evaluated in
    blocks of about CHUNK cells."""
    n0, n1 = int(cells.n[0]), int(cells.n[1])
    first = np.arange(lay.grids[0].sums(n0)[0], lay.grids[0].sums(n0)[1] + 1)
    second = np.arange(lay.grids[1].sums(n1)[0], lay.grids[1].sums(n1)[1] + 1)
    step = max(1, CHUNK // len(second))
    found, bounds = [], []
    for start in range(0, len(first), step):
        block = np.stack(np.meshgrid(first[start : start + step], second, indexing="ij"), axis=-1).reshape(
            -1, 2
        )
        single = np.maximum(cells.one_scenario(block), two_line)
        below = single < target
        found.append(block[below])
        bounds.append(single[below])
    return np.concatenate(found), np.concatenate(bounds), len(first) * len(second)


def cell_bound(problem, scenarios, target, deadline=None, tick=None, work=None):
    """No lug set does better than the returned value over ``scenarios`` (module docstring).

    Parameters
    ----------
    problem : PlanProblem
        Candidates on two lines of stations in one body plane, equal ropes (:func:`applies`).
    scenarios : list of Scenario
        The scenarios the bound holds over (their effective CGs' corners are used).
    target : float  [objective unit]
        The value to close the cells at (a plan's worst value less the gap aimed at): the
        bound is ``target`` when every cell closes, else the least failed cell's own bound.
    deadline : float, optional
        ``time.perf_counter()`` value after which open cells count at their one-scenario bound.
    tick : callable, optional
        Called after each searched cell with (cells searched, cells to search in this count,
        the bound if the search stopped now) [-, -, objective unit].
    work : int, optional
        Cells to search at most (a count, not a time: the same bound on any machine); the
        open cells then count as at the deadline.

    Ctrl-C (KeyboardInterrupt) ends the search like the deadline: the result says it is
    incomplete and counts the open cells at their one-scenario bound.

    Returns
    -------
    CellBound
    """
    if not np.isfinite(target):
        raise ValueError(f"cell_bound: target = {target!r}, expected a finite value")
    started = time.perf_counter()
    lay = layout(problem)
    plane = coplanar(problem)
    corners = corner_scenarios(problem, plane, scenarios)
    g = effective_cogs(problem, plane, corners) @ lay.axes.T
    unit = 1.0 if not problem.goal.per_swl else 1.0 / float(np.nanmax(problem.reach[1]))
    target = target / unit
    lines = two_lines(problem)
    # the two-line bound of each count, over the same corners (in the problem's line order)
    counts = count_bounds(problem, lines, corners) / unit
    n = problem.cranes
    value, total, searched, failed, complete, interrupted = np.inf, 0, 0, 0, True, False
    span = max(float(np.ptp(np.concatenate([grid.s for grid in lay.grids]))), 1.0)
    tolerance = 1e-12 * float(problem.body.weight) * span**2
    for n0 in range(1, n):
        if n0 > len(lay.grids[0].index) or n - n0 > len(lay.grids[1].index):
            continue
        if not complete or not np.isfinite(counts[n0]) or counts[n0] >= target:
            value = min(value, counts[n0])  # stopped: the rest at their two-line bound
            continue
        cells = _Cells(problem, lay, g, n0)
        open_cells, open_single, size = _open_cells(cells, lay, counts[n0], target)
        total += size
        for k, sums in enumerate(open_cells):
            try:
                if (deadline is not None and time.perf_counter() > deadline) or (
                    work is not None and searched >= work
                ):
                    raise TimeoutError
                searched += 1
                cell = _Cell(cells, sums)
                if not _closes(cells, cell, target, tolerance):
                    failed += 1
                    low, high = float(open_single[k]), target
                    for _ in range(BISECTIONS):
                        middle = 0.5 * (low + high)
                        low, high = (
                            (middle, high) if _closes(cells, cell, middle, tolerance) else (low, middle)
                        )
                    value = min(value, low)
            except (TimeoutError, KeyboardInterrupt) as err:  # open cells at their closed form
                complete, interrupted = False, isinstance(err, KeyboardInterrupt)
                value = min(value, float(open_single[k:].min()))
                break
            if tick is not None:
                rest = float(open_single[k + 1 :].min()) if k + 1 < len(open_cells) else np.inf
                tick(k + 1, len(open_cells), min(value, target, rest) * unit)
        value = min(value, target)
    return CellBound(
        value=float(value * unit),
        cells=total,
        searched=searched,
        failed=failed,
        seconds=time.perf_counter() - started,
        complete=complete,
        interrupted=interrupted,
    )
