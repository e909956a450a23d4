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

What this does not do: with the y fractional the products phi are free within their bounds,
so the residuals (and the widening) vanish from the linear relaxation; the branch and bound
sees the hook errors only where it has fixed the lugs. See docs/studies.md "The MIP with the
hook tolerance".

Candidates not on one plane of the body, hinged sling hooks, and problems whose pair rows
would pass :data:`~liftplan.planner.search.mip.BOX_SIZE` keep the scenario-by-scenario
hook-error cuts (:class:`~liftplan.planner.search.mip.Cut`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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
