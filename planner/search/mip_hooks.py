"""The hook errors' worst case in the lug-choice MIP: rows that hold for the whole hook box.

A hook raised by e_i adds kappa_i e_i to its rope and the hook plane takes up the errors'
plane through the statics. When the candidates' heights are affine in their plan position
(every candidate on one plane of the body: a deck), a scenario's statics rows are an
invertible linear map of the level ones (1, x, y), so the plane taken up is the same at every
attitude: the kappa-weighted least-squares plane of the errors over the chosen lugs S. A row
of the objective, c . T (c = s_a 1_a - s_b 1_b for the pair (a, b) of the spread; c = 1_a for
one rope's low or high side), then changes by

    c . dT = sum_{i in S} kappa_i e_i (c_i - f_i),     f the kappa-weighted plane fit of c over S,

and its worst over the box |e_i| <= delta_i is the constant

    W_c(S) = sum_{i in S} kappa_i delta_i |c_i - f_i|,

which depends on the set but neither on the preload nor on the scenario (the closed form of
the dual bound's pair widening, :mod:`~liftplan.planner.search.dual`). The MIP writes it
exactly for every set at once: the plane's three coefficients mu are variables, the products
phi_i = y_i f_i are exact (McCormick on a binary with the bounds below), and

    sum_i kappa_i a_i (c_i y_i - phi_i) = 0       (the fit's normal equations over S),
    t_i >= |c_i y_i - phi_i|,    W_c = sum_i kappa_i delta_i t_i.

At an integer y the fit is the set's own, so W_c is the set's widening (the minimiser sets
each t_i to its absolute value). Bounds: the fit is a kappa-norm contraction, so at a chosen
lug |f_i| <= B = sqrt(sum kappa c^2 / kappa_min); a plane within B on a set of least plan
width w (:func:`~liftplan.planner.search.mip.least_width`) is within B (1 + 2 reach / w) at
any candidate. No row needs a switch for unchosen lugs: an unchosen column's residual is
zero, so a pair with one lug unchosen has the other's own widening (a valid row against the
mean, :meth:`~liftplan.planner.search.mip.LugMip._box_rows`), and one with none, none. The fit
is linear in c, so a pair's residual is its two lugs' own residuals' difference: the fits are
solved once per lug, not per pair. At an integer y the residuals' diagonal sums to the trace
of the fit's complement, n - 3, a row that holds for every set.

What the fit's rows do not do: with the y fractional the products phi are free within their
bounds, so the residuals (and the widening) vanish from the linear relaxation; the branch and
bound sees the hook errors only where it has fixed the lugs (the tanker's 4 of 16 stayed at its
root bound, 32.34 t against 91.74 t, for 300 s).

**Set-wise rows** (one crane class, at most :data:`~liftplan.planner.search.mip.SET_CAP`
sets; :meth:`~liftplan.planner.search.mip.LugMip._set_rows`). The widenings are set functions
that a fractional y cannot see through a fit, so they are written over the sets themselves:
one continuous x_S >= 0 per set S of n usable candidates (:func:`set_tables`), with

    sum_{S ni i} x_S = Y_i   (Y_i = sum_c y_ic, lug i chosen),

each widening a weighted sum (rope a's own W_a = sum_S x_S W_{e_a}(S); a pair's W_ab =
sum_S x_S W_ab(S), W_ab(S) the pair's own when both are in S, the member's own when one is,
zero when neither, as the fit's rows give), and the bound row

    z >= sum_S x_S L(S)     (L(S) of :func:`set_bounds`).

*Exact at every integer y*: Y is then the indicator of one n-set S*, and the only x >= 0 with
sum_{S ni i} x_S = Y_i puts weight 1 on S* (a set with weight holds only chosen lugs and has n
of them), so every row is S*'s own. *Valid*: each row holds for S* at every preload (the
widenings are its exact closed forms; L(S*) is at most its worst over the whole box, proof at
:func:`set_bounds`). Sets left out of the x_S: those narrower than the sets' least plan
width (:func:`~liftplan.planner.search.mip.least_width`; none of them can beat the cutoff)
and those whose L is infinite (no preload holds the bands at the scenarios with its hook
errors at their worst; a set that beats the cutoff holds them everywhere in the box). *Why it
survives fractional lugs*: with Y fractional x is a mixture of whole sets, and
z >= sum_S x_S L(S) >= the least L over the sets that mixture can use: the relaxation's bound
is the least set bound consistent with the branching so far, not the fit's zero.

The price: the rows enumerate the sets (the tanker's 16 candidates, 4 cranes: 1 820 sets,
each a closed form of its n x 3 rows; the tables take milliseconds). So the proof is a
combinatorial one carried inside the MIP: HiGHS's dual bound over rows that bound every set
by its own closed form. On the tanker every set but the optimum's pair of mirror images has
L above the incumbent, so the root bound meets the incumbent and the proof takes one round.

Weaker rows that need no enumeration, checked and set aside: for four lugs the fit's
residual space is one-dimensional (the affine dependency v of the lugs, kappa-weighted), so
for equal kappa and delta W_ab = kappa delta |v_a - v_b| sum|v| / |v|^2; with the positives
and the negatives of v each summing to P, |v|^2 <= P (max v - min v) and sum|v| = 2P, so
the largest pair widening is at least 2 kappa delta whatever the set (and the worst spread at
least that, whatever the preload). That constant row lifts the tanker's root from 32.34 t to
66.67 t; the branch and bound then stalls there (27 % gap after 60 s). It is implied by the
set-wise bound row (L(S) >= the largest pair widening of S).

Candidates not on one plane of the body, hinged sling hooks, and problems whose pair rows
would pass :data:`~liftplan.planner.search.mip.BOX_SIZE` keep the scenario-by-scenario
hook-error cuts (:class:`~liftplan.planner.search.mip.Cut`); unequal crane classes and more
sets than SET_CAP, the fit's rows. See docs/studies.md "The MIP with the hook tolerance".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import ConvexHull, QhullError

#: Slack [t] on a set's preload interval in :func:`set_bounds` (rounding never cuts off a set).
SLACK = 1e-6
#: Relative margin taken off each set's bound in :func:`set_bounds` (rounding never lifts it).
MARGIN = 1e-9
#: Relative misfit below which the candidates' heights count as affine in plan.
PLANAR = 1e-9


def on_one_plane(problem):
    """True when every candidate's height (body frame) is affine in its plan position."""
    points = problem.points
    basis = np.column_stack([np.ones(len(points)), points[:, :2]])
    coef, *_ = np.linalg.lstsq(basis, points[:, 2], rcond=None)
    scale = max(1.0, float(np.abs(points).max()))
    return bool(np.abs(basis @ coef - points[:, 2]).max() <= PLANAR * scale)


@dataclass(frozen=True)
class Columns:
    """The MIP's (candidate, crane class) columns, candidate-major.

    Parameters
    ----------
    candidate : numpy.ndarray of int, shape (N,)
    stiffness : numpy.ndarray, shape (N,)  [t/m]
    tolerance : numpy.ndarray, shape (N,)  [m]   each column's hook-height tolerance
    level_plan : numpy.ndarray, shape (C, 2)  [m]   the candidates' level plan positions
    cranes : int   ropes in every set
    """

    candidate: np.ndarray
    stiffness: np.ndarray
    tolerance: np.ndarray
    level_plan: np.ndarray
    cranes: int


def residuals(cp, y, columns, coef, width):
    """Each row's residual c y - phi over the columns (module docstring) as MIP expressions.

    Parameters
    ----------
    cp : module
        cvxpy.
    y : cvxpy.Variable, shape (N,)
        The columns' binaries.
    columns : Columns
    coef : numpy.ndarray, shape (R, N)
        Each row's c over the columns (c_i of the column's candidate, at that column's scale).
    width : float  [m]
        A lower bound on the plan width of every set the MIP must keep.

    Returns
    -------
    residual : cvxpy.Expression, shape (R, N)
        At an integer y: c_i - f_i on a chosen column, 0 on the others.
    constraints : list
    """
    coef = np.asarray(coef, dtype=float)
    count = len(columns.level_plan)
    kappa, cand = columns.stiffness, columns.candidate
    # each row's kappa-weighted sum of c^2 at its worst classes: (R,)
    per_candidate = np.zeros((count, len(coef)))
    np.maximum.at(per_candidate, cand, (kappa[None, :] * coef**2).T)
    energy = per_candidate.sum(axis=0)
    on = np.sqrt(energy / float(kappa.min()))  # B: the fit at a chosen lug
    plan = columns.level_plan
    reach = np.sqrt(((plan[:, None, :] - plan[None, :, :]) ** 2).sum(axis=2)).max(axis=1)
    off = on[:, None] * (1.0 + 2.0 * reach[None, :] / width)  # the fit at any candidate (R, C)
    rows = len(coef)
    basis = np.column_stack([np.ones(count), plan])  # (C, 3)
    mu = cp.Variable((rows, 3))
    fit = (mu @ basis.T)[:, cand]  # f at each column's candidate, (R, N)
    phi = cp.Variable((rows, len(cand)))  # y f
    chosen = np.ones((rows, 1)) @ cp.reshape(y, (1, len(cand)), order="C")
    residual = cp.multiply(coef, chosen) - phi
    on_col = on[:, None]
    off_col = off[:, cand]
    constraints = [
        residual @ (kappa[:, None] * basis[cand]) == 0,
        phi <= cp.multiply(on_col, chosen),
        phi >= -cp.multiply(on_col, chosen),
        phi <= fit + cp.multiply(off_col, 1 - chosen),
        phi >= fit - cp.multiply(off_col, 1 - chosen),
    ]
    return residual, constraints


def widening(cp, residual, columns):
    """W = sum_i kappa_i delta_i |residual_i| of each row, shape (R,), and its constraints.

    No row needs a switch for unchosen lugs: an unchosen column's residual is zero, so a pair
    with one lug unchosen has the other's own widening, and one with none, none."""
    spread = cp.Variable(residual.shape, nonneg=True)
    return spread @ (columns.stiffness * columns.tolerance), [spread >= residual, spread >= -residual]


def lug_coefficients(scale, candidate, count):
    """Each candidate's c = s_a 1_a over the columns, shape (C, N)."""
    return np.where(candidate[None, :] == np.arange(count)[:, None], scale[None, :], 0.0)


@dataclass(frozen=True)
class SetTables:
    """Each lug set's hook widenings, for the set-wise rows (:func:`set_tables`).

    Parameters
    ----------
    sets : numpy.ndarray of int, shape (S, n)
        The sets (candidate indices, ascending) the MIP may choose.
    own : numpy.ndarray, shape (S, n)  [t]
        Each member's own widening W_{e_a}(S) (one rope's worst change).
    scaled_own : numpy.ndarray, shape (S, n)   the objective's unit
        The same of c = s_a e_a.
    pair : numpy.ndarray, shape (S, n, n)   the objective's unit
        Each pair of members' widening W_{s_a e_a - s_b e_b}(S) (zero on the diagonal).
    """

    sets: np.ndarray
    own: np.ndarray
    scaled_own: np.ndarray
    pair: np.ndarray

    @property
    def largest(self):
        """Each set's largest pair widening, shape (S,)."""
        return self.pair.max(axis=(1, 2))


def set_widths(plan, sets):
    """Each set's least plan width [m] (over every direction): the least, over the pairs of
    its lugs, of the extent across the line through them (a convex hull's width is met across
    one of its edges), shape (S,)."""
    pts = plan[sets]  # (S, n, 2)
    n = sets.shape[1]
    best = np.full(len(sets), np.inf)
    for i in range(n):
        for j in range(i + 1, n):
            edge = pts[:, j] - pts[:, i]
            length = np.linalg.norm(edge, axis=1)
            normal = np.column_stack([-edge[:, 1], edge[:, 0]]) / np.where(length > 0.0, length, 1.0)[:, None]
            across = np.einsum("snd,sd->sn", pts - pts[:, i : i + 1], normal)
            extent = np.where(length > 0.0, across.max(axis=1) - across.min(axis=1), 0.0)
            best = np.minimum(best, extent)
    return best


def set_tables(plan, stiffness, tolerance, scale, cranes, usable, width):
    """The hook widenings of every set of ``cranes`` usable candidates at least ``width``
    wide (narrower sets cannot beat the MIP's cutoff, :func:`~liftplan.planner.search.mip.least_width`).

    With H = B (B' K B)^-1 B' K the set's kappa-weighted plane fit (B the rows (1, x, y) of
    its lugs), a row c's residual is (I - H) c and its widening sum_i kappa_i delta_i
    |((I - H) c)_i| (module docstring).

    Parameters
    ----------
    plan : numpy.ndarray, shape (C, 2)  [m]
    stiffness, tolerance, scale : numpy.ndarray, shape (C,)  [t/m], [m], objective per t
    cranes : int
    usable : numpy.ndarray of bool, shape (C,)
    width : float  [m]

    Returns
    -------
    SetTables
    """
    import itertools

    pool = np.flatnonzero(usable)
    sets = np.array(list(itertools.combinations(pool, cranes)), dtype=np.int64).reshape(-1, cranes)
    if len(sets):
        sets = sets[set_widths(plan, sets) >= width]
    n = cranes
    basis = np.concatenate([np.ones(sets.shape + (1,)), plan[sets]], axis=2)  # (S, n, 3)
    k = stiffness[sets]
    normal = np.einsum("sni,sn,snj->sij", basis, k, basis)
    hat = basis @ np.linalg.solve(normal, np.transpose(basis * k[:, :, None], (0, 2, 1)))  # (S, n, n)
    resid = np.eye(n)[None] - hat  # column a: the residual of e_a
    kd = k * tolerance[sets]  # (S, n)
    own = np.einsum("si,sia->sa", kd, np.abs(resid))
    s = scale[sets]
    scaled = resid * s[:, None, :]  # column a: the residual of s_a e_a
    scaled_own = np.einsum("si,sia->sa", kd, np.abs(scaled))
    pair = np.stack(
        [np.einsum("si,sib->sb", kd, np.abs(scaled[:, :, a : a + 1] - scaled)) for a in range(n)], axis=1
    )
    return SetTables(sets, own, scaled_own, pair)


def hull_points(beta):
    """The rows of ``beta`` (m, 3) that can be a linear function's largest or least: the
    vertices of their convex hull (all rows when the hull is degenerate)."""
    flat = beta[:, 1:] if np.ptp(beta[:, 0]) <= 1e-12 * max(1.0, float(np.abs(beta[:, 0]).max())) else beta
    try:
        return beta[np.unique(ConvexHull(flat).vertices)]
    except (QhullError, ValueError):
        return beta


def scenario_vectors(a_mat, b_vec, level_plan):
    """Each scenario's beta_k = T_k^-1 b_k [t, t m], shape (m, 3), where T_k maps the level
    statics rows (1, x, y) of the candidates to the scenario's, A_k = T_k A_0 (exact when the
    candidates lie on one plane of the body, :func:`on_one_plane`).

    A set S's tension changes from level to scenario k are then Q_S (beta_k - b_0) whatever
    its preload (:func:`set_bounds`)."""
    level = np.vstack([np.ones(len(level_plan)), level_plan.T])  # (3, C)
    maps = a_mat @ np.linalg.pinv(level)  # (m, 3, 3)
    return np.linalg.solve(maps, b_vec[..., None])[..., 0]


def set_bounds(tables, stiffness, scale, statics, preload, band, peak):
    """A lower bound on every set's worst value over the whole hook box at the scenarios of
    ``statics``, and which sets can hold their bands there, shape (S,) (inf: cannot).

    On one plane of the body a set's level statics B' P = b_0 (B its rows (1, x, y)) fix the
    preload up to its null space, P = P_0 + V t, and the tension change from level to a
    scenario k is Delta_k = K B N^-1 (beta_k - b_0) (N = B' K B, beta_k of
    :func:`scenario_vectors`): A_k = T_k A_0 gives T_k B' (P + K (B c - r_k)) = b_k, the rise
    r_k = B rho_k is affine on the plane, so c - rho_k = N^-1 (beta_k - b_0). Neither depends
    on P. The set's worst is then at least

        min_t max_{a != b in S} [ s_a P_a - s_b P_b + max_k (s_a Delta_ka - s_b Delta_kb) + W_ab(S) ]

    (``peak``: max_a [ s_a P_a + max_k s_a Delta_ka + W_a(S) ]), every row the chosen
    set's own at some scenario with its hook errors at their worst, subject to each P_a
    within ``preload`` and each T_k,a -/+ W_a(S) within ``band``: the MIP's own rows at that
    set. With four lugs t is one number and the minimum is exact (at an end of t's interval or
    where two rows cross); with three P is fixed; with more lugs each pair is taken with its
    own best s_a P_a - s_b P_b (each pair's rows in both orders: their mean), a relaxation.
    A set whose interval of t is empty cannot hold its bands (inf).

    Why it is a lower bound: the plan's preload P* of S satisfies the level statics and,
    if S beats the cutoff, its preload limits and bands at every state of the box (hook errors
    included); at P* the worst over the box is at least each row above (each is one state of
    the box: scenario k, which is in the box, with the errors at the pair's worst, the held
    model being affine in them while taut), so at least their largest, so at least its least
    over every admissible P. Only the largest and least of a linear function of beta_k enter,
    so ``beta`` may be the vertices of the scenarios' hull (:func:`hull_points`). Rounding
    is kept on the safe side: the interval of P widened by :data:`SLACK`, the bound lowered by
    :data:`MARGIN`.

    Parameters
    ----------
    tables : SetTables
    stiffness, scale : numpy.ndarray, shape (C,)  [t/m], objective per t
    statics : tuple
        (level rows (3, C), b_0 (3,), beta (m, 3)): the level statics and the scenarios'.
    preload, band : tuple of numpy.ndarray, shape (C,) each  [t]
        (low, high) of each candidate's preload and of its tensions.
    peak : bool
        The ``reserve`` objective (each rope's own largest scaled tension).

    Returns
    -------
    numpy.ndarray, shape (S,)
    """
    sets = tables.sets
    count, n = sets.shape
    level, b0, beta = statics
    basis = np.transpose(level[:, sets], (1, 2, 0))  # (S, n, 3)
    k = stiffness[sets]
    normal = np.einsum("sni,sn,snj->sij", basis, k, basis)
    gain = k[:, :, None] * (basis @ np.linalg.inv(normal))  # Q: (S, n, 3)
    delta = gain @ (beta - b0).T  # (S, n, m)
    own = tables.own
    s = scale[sets]
    # P_0: the least-norm level preload; V: the null space of B' (n - 3 columns)
    _, _, vt = np.linalg.svd(np.transpose(basis, (0, 2, 1)))  # (S, n, n)
    p0 = np.einsum(
        "sni,si->sn", np.linalg.pinv(np.transpose(basis, (0, 2, 1))), np.broadcast_to(b0, (count, 3))
    )
    null = np.transpose(vt[:, 3:, :], (0, 2, 1))  # (S, n, n - 3)
    # each member's rows P_a in [lo, hi] (preload and, at every scenario, band -/+ its widening)
    lo = np.maximum(preload[0][sets], band[0][sets] + own - delta.min(axis=2)) - SLACK
    hi = np.minimum(preload[1][sets], band[1][sets] - own - delta.max(axis=2)) + SLACK
    if peak:
        const = s * (p0 + delta.max(axis=2)) + tables.scaled_own  # (S, n)
        slope = s[:, :, None] * null  # (S, n, n - 3)
    else:
        a, b = np.nonzero(~np.eye(n, dtype=bool))
        spread = s[:, a, None] * delta[:, a, :] - s[:, b, None] * delta[:, b, :]
        const = s[:, a] * p0[:, a] - s[:, b] * p0[:, b] + spread.max(axis=2) + tables.pair[:, a, b]
        slope = s[:, a, None] * null[:, a, :] - s[:, b, None] * null[:, b, :]
    if n == 3:
        ok = np.all((lo <= p0) & (p0 <= hi), axis=1)
        values = const.max(axis=1)
        return np.where(ok, values - MARGIN * (1.0 + np.abs(values)), np.inf)
    if n > 4:  # each pair with its own best preload difference (its two orders' mean)
        if peak:  # no bound without the preload
            return np.full(count, -np.inf)
        pairs = const.reshape(count, -1)
        values = (0.5 * (pairs + pairs[:, _swap(a, b)])).max(axis=1)
        return values - MARGIN * (1.0 + np.abs(values))
    v = null[:, :, 0]  # (S, n)
    slope = slope[:, :, 0]
    # t's interval from lo <= P0 + t v <= hi
    with np.errstate(divide="ignore", invalid="ignore"):
        first = (lo - p0) / v
        second = (hi - p0) / v
    moving = np.abs(v) > 1e-12 * np.abs(v).max(axis=1, keepdims=True)
    t_lo = np.where(moving, np.minimum(first, second), -np.inf).max(axis=1)
    t_hi = np.where(moving, np.maximum(first, second), np.inf).min(axis=1)
    fixed_ok = np.all(moving | ((lo <= p0) & (p0 <= hi)), axis=1)
    # the least of the rows' upper envelope on [t_lo, t_hi]: at an end or where two rows cross
    i, j = np.triu_indices(const.shape[1], k=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        cross = (const[:, j] - const[:, i]) / (slope[:, i] - slope[:, j])
    points = np.concatenate([cross, t_lo[:, None], t_hi[:, None], np.zeros((count, 1))], axis=1)
    points = np.where(np.isfinite(points), points, 0.0)
    points = np.clip(
        points,
        np.where(np.isfinite(t_lo), t_lo, -np.inf)[:, None],
        np.where(np.isfinite(t_hi), t_hi, np.inf)[:, None],
    )
    values = (const[:, None, :] + points[:, :, None] * slope[:, None, :]).max(axis=2).min(axis=1)
    feasible = fixed_ok & (t_lo <= t_hi)
    return np.where(feasible, values - MARGIN * (1.0 + np.abs(values)), np.inf)


def _swap(a, b):
    """Index of the pair (b, a) in the ordered pairs (a, b)."""
    where = {(int(p), int(q)): m for m, (p, q) in enumerate(zip(a, b))}
    return np.array([where[(int(q), int(p))] for p, q in zip(a, b)])
