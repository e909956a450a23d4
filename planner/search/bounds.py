"""Convex sub-study of the tensions (cvxpy, solved by Clarabel): linear programs.

Two problems, each built once per rope count from ``cp.Parameter`` objects (DPP), checked
with ``is_dcp(dpp=True)`` at build time, and re-solved by assigning parameter values:

:class:`AdmissibleTensions`
    At one attitude: every statically admissible tension set, ``A T = b`` with
    ``lower <= T <= upper``. Gives the bounds [T_i min, T_i max] over that set and the least
    achievable spread (max - min tension).
:class:`PreloadMinimax`
    The planner's convex core: tensions at each scenario k (attitude, CG) are affine in the
    level preload T* (see :mod:`liftplan.planner.search.scenarios`): T_k = P_k T* + q_k. Choose T*
    (level statics, boom-height range) to minimise the largest spread over the scenarios,
    with every tension in [min_tension, SWL]. Its value over a finite set of scenarios is a
    lower bound on the worst spread over the whole tolerance box.

Solver statuses are mapped to typed errors: an infeasible problem raises
:class:`~liftplan.model.errors.PlanInfeasible` (the caller words the physical reason); any
other non-optimal status raises :class:`~liftplan.model.errors.SolverFailed`.
"""

from __future__ import annotations

import contextlib
import os
import sys
import warnings
from dataclasses import dataclass

import cvxpy as cp
import numpy as np
from scipy import sparse

from liftplan.model.errors import PlanInfeasible, SolverFailed
from liftplan.planner.problem.objectives import OBJECTIVES

SOLVER = cp.CLARABEL
FALLBACK = cp.HIGHS
_INFEASIBLE = (cp.INFEASIBLE, cp.INFEASIBLE_INACCURATE)


def _run(problem, what):
    """Solve with Clarabel (HiGHS's simplex where Clarabel fails numerically, as it can on
    badly scaled rows); return the optimal value or raise a typed error."""
    failure = None
    for solver in (SOLVER, FALLBACK):
        try:
            with warnings.catch_warnings():  # an inaccurate status is handled below
                warnings.simplefilter("ignore", UserWarning)
                if solver == FALLBACK:
                    with _stdout_silenced():  # HiGHS prints its banner on stdout (JSON)
                        problem.solve(solver=solver)
                else:
                    problem.solve(solver=solver)
        except cp.error.SolverError as err:
            failure = f"{solver} failed ({err})"
            continue
        if problem.status in _INFEASIBLE:
            raise PlanInfeasible(f"{what}: no tension set satisfies the constraints")
        if problem.status == cp.OPTIMAL:
            return float(problem.value)
        failure = f"{solver} ended with status {problem.status!r}"
    raise SolverFailed(f"{what}: {failure}")


def run_highs(problem, what, **options):
    """Solve a cvxpy problem (a MIP) with HiGHS: its banner kept off stdout (the JSON goes
    there), the "inaccurate" warning of a time or gap limit silenced (the caller reads the
    status and the dual bound), a solver error raised as :class:`SolverFailed` naming ``what``."""
    try:
        with _stdout_silenced(), warnings.catch_warnings(), _interruptible_highs():
            warnings.simplefilter("ignore", UserWarning)
            problem.solve(solver=cp.HIGHS, **options)
    except cp.error.SolverError as err:
        raise SolverFailed(f"{what}: HiGHS failed ({err})") from None


#: Seconds between the main thread's looks for Ctrl-C while HiGHS solves in its thread.
WAIT = 0.1


@contextlib.contextmanager
def _interruptible_highs():
    """HiGHS that stops on Ctrl-C within a fraction of a second.

    cvxpy calls ``highspy.Highs().run()``, native code that holds the main thread until the
    solve ends (a MIP at its time limit: 30 s later), so Python sees the Ctrl-C only then.
    Meanwhile ``highspy.Highs`` is a subclass whose ``run`` solves in highspy's own solver
    thread (``startSolve``) while the main thread waits in short steps; on Ctrl-C it asks
    HiGHS to stop (``cancelSolve``: its interrupt callbacks), waits for that, and raises the
    KeyboardInterrupt. Off the main thread (no Ctrl-C arrives there) ``run`` is HiGHS's own.
    """
    import threading

    import highspy

    original = highspy.Highs
    if threading.current_thread() is not threading.main_thread() or getattr(original, "_liftplan", False):
        yield
        return

    class Interruptible(original):
        _liftplan = True

        def run(self):
            if threading.current_thread() is not threading.main_thread():
                return super().run()
            self.HandleUserInterrupt = True
            self.startSolve()
            try:
                while True:
                    done, status = self.wait(WAIT)
                    if done:
                        return status
            except KeyboardInterrupt:
                self.cancelSolve()
                while not self.wait(WAIT)[0]:  # HiGHS stops at its next interrupt check
                    pass
                raise

    highspy.Highs = Interruptible
    try:
        yield
    finally:
        highspy.Highs = original


@contextlib.contextmanager
def _stdout_silenced():
    """Send what native code writes to the process's stdout (fd 1) to /dev/null meanwhile."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def _checked(problem, name):
    if not problem.is_dcp(dpp=True):  # a build error, not a user error
        raise SolverFailed(f"{name}: the problem is not DPP-compliant; it would re-canonicalise")
    return problem


@dataclass(frozen=True)
class TensionBounds:
    """Bounds of each tension over the admissible set at one attitude.

    Parameters
    ----------
    lower, upper : numpy.ndarray, shape (n,)  [t]
        Smallest and largest value T_i takes over all statically admissible sets.
    least_spread : float  [t]
        The smallest max - min tension any admissible set achieves.
    even : numpy.ndarray, shape (n,)  [t]
        A tension set achieving it.
    """

    lower: np.ndarray
    upper: np.ndarray
    least_spread: float
    even: np.ndarray


class AdmissibleTensions:
    """LPs over {T : A T = b, lower <= T <= upper} for n ropes, built once.

    Parameters
    ----------
    n : int
        Number of ropes.
    """

    def __init__(self, n):
        self.n = n
        self.a_mat = cp.Parameter((3, n), name="A")
        self.b_vec = cp.Parameter(3, name="b")
        self.lower = cp.Parameter(n, name="lower")
        self.upper = cp.Parameter(n, name="upper")
        self.direction = cp.Parameter(n, name="direction")
        tension = cp.Variable(n, name="T")
        admissible = [
            self.a_mat @ tension == self.b_vec,
            tension >= self.lower,
            tension <= self.upper,
        ]
        self._extreme = _checked(
            cp.Problem(cp.Minimize(self.direction @ tension), admissible), "tension bound"
        )
        low, high = cp.Variable(name="low"), cp.Variable(name="high")
        self._even = _checked(
            cp.Problem(cp.Minimize(high - low), [*admissible, tension >= low, tension <= high]),
            "least spread",
        )
        self.tension = tension

    def bounds(self, a_mat, b_vec, lower, upper):
        """Bounds and least spread at one attitude.

        Parameters
        ----------
        a_mat : array_like, shape (3, n)
            Rows (1, x_i, y_i): the lugs' world plan coordinates [m].
        b_vec : array_like, shape (3,)
            W (1, x_c, y_c)  [t, t m].
        lower, upper : array_like, shape (n,)  [t]
            Tension limits (min_tension and SWL).

        Returns
        -------
        TensionBounds

        Raises
        ------
        PlanInfeasible
            No admissible tension set within the limits.
        """
        self.a_mat.value = np.asarray(a_mat, dtype=float)
        self.b_vec.value = np.asarray(b_vec, dtype=float)
        self.lower.value = np.asarray(lower, dtype=float)
        self.upper.value = np.asarray(upper, dtype=float)
        spread = _run(self._even, "least spread")
        even = np.array(self.tension.value)
        low, high = np.empty(self.n), np.empty(self.n)
        for i in range(self.n):
            unit = np.zeros(self.n)
            unit[i] = 1.0
            self.direction.value = unit
            low[i] = _run(self._extreme, f"lower bound of T{i + 1}")
            self.direction.value = -unit
            high[i] = -_run(self._extreme, f"upper bound of T{i + 1}")
        return TensionBounds(lower=low, upper=high, least_spread=spread, even=even)


def hook_margins(count, n, scale, hook, objective="spread"):
    """Largest effect of hook-height errors within their tolerance, per scenario.

    Parameters
    ----------
    count, n : int
    scale : (n,)   the objective's s_i
    hook : (G, delta) or None   G (count, n, n) [t/m], delta (n,) [m]

    Returns
    -------
    margin : (count, n)  [t]   sum_m |G_im| delta_m
    pair_margin : (count, n (n - 1))  [t or -]   sum_m |s_i G_im - s_j G_jm| delta_m for
        every ordered pair i != j (the order of :class:`PreloadMinimax`); for the ``reserve``
        objective (count, n): s_i sum_m |G_im| delta_m
    """
    first, second = np.nonzero(~np.eye(n, dtype=bool))
    peak = OBJECTIVES[objective].peak
    rows = n if peak else len(first)
    if hook is None:
        return np.zeros((count, n)), np.zeros((count, rows))
    gain, delta = np.asarray(hook[0], dtype=float), np.asarray(hook[1], dtype=float)
    margin = np.abs(gain) @ delta
    if peak:
        return margin, margin * scale
    scaled = gain * scale[None, :, None]
    pair_margin = np.abs(scaled[:, first] - scaled[:, second]) @ delta
    return margin, pair_margin


@dataclass(frozen=True)
class MinimaxResult:
    """Optimal level preload of :class:`PreloadMinimax`.

    Parameters
    ----------
    preload : numpy.ndarray, shape (n,)  [t]
        Level tensions T* to dial in.
    worst_spread : float  [t or -]
        Largest spread (of s_i T_i) over the scenarios given (a lower bound over the whole box).
    nominal_spread : float  [t or -]
        Spread of s_i T*_i at the level attitude.
    """

    preload: np.ndarray
    worst_spread: float
    nominal_spread: float


class PreloadMinimax:
    """min over T* of max over scenarios of (max_i - min_i) of s_i T_k,i, T_k = P_k T* + q_k
    (``objective = "reserve"``: of max_i s_i T_k,i).

    Parameters
    ----------
    n : int
        Number of ropes.
    slots : int
        Number of scenarios the problem holds. Fewer may be passed: the last is repeated,
        which changes nothing (a scenario counted twice).
    objective : {"spread", "utilisation", "reserve"}
    separable : bool
        No hook errors will be passed: the spread is written with each scenario's highest and
        lowest value (O(n) rows) instead of every ordered pair (O(n^2)); the same LP, and what
        keeps 26 or 64 ropes small.

    Notes
    -----
    The nominal spread enters the objective with weight :attr:`TIE_BREAK`, so among
    preloads with the same worst spread the most even level state is chosen (the LP would
    otherwise return an arbitrary vertex of the optimal face).
    """

    TIE_BREAK = 1e-3

    def __init__(self, n, slots, objective="spread", separable=False):
        self.n, self.slots, self.objective = n, slots, objective
        m = slots
        # separable (no hook errors): each scenario's spread as its highest minus its lowest
        # value, O(n) rows; the hook errors' pair terms need every ordered pair, O(n^2)
        peak = OBJECTIVES[objective].peak
        self.separable = separable and not peak
        first, second = np.nonzero(~np.eye(n, dtype=bool))  # ordered pairs i != j
        # reserve: the largest s_i T_i itself, one row per rope; otherwise every ordered pair
        pairs = n if peak or self.separable else len(first)
        self.gain = cp.Parameter((m * n, n), name="P")
        self.offset = cp.Parameter(m * n, name="q")
        # the objective's rows: s_i T_i (s = 1 for the spread, 1 / SWL_i for utilisation)
        self.spread_gain = cp.Parameter((m * n, n), name="SP")
        self.spread_offset = cp.Parameter(m * n, name="Sq")
        # hook-height errors within the tolerance: each tension's largest rise / fall and each
        # ordered pair's largest rise of s_i T_i - s_j T_j (exact: the tensions are affine in
        # the errors at a given attitude)
        self.margin = cp.Parameter(m * n, nonneg=True, name="hook_margin")
        self.pair_margin = cp.Parameter(m * pairs, nonneg=True, name="pair_margin")
        self.level_scale = cp.Parameter((n, n), name="S0")
        self.a_level = cp.Parameter((3, n), name="A0")
        self.b_level = cp.Parameter(3, name="b0")
        self.preload_low = cp.Parameter(n, name="preload_low")
        self.preload_high = cp.Parameter(n, name="preload_high")
        self.tension_low = cp.Parameter(m * n, name="tension_low")
        self.tension_high = cp.Parameter(m * n, name="tension_high")
        preload = cp.Variable(n, name="T_star")
        worst = cp.Variable(name="worst")
        nominal_high, nominal_low = cp.Variable(), cp.Variable()
        difference = np.zeros((pairs, n))
        if peak or self.separable:
            difference[np.arange(n), np.arange(n)] = 1.0
        else:
            difference[np.arange(pairs), first] = 1.0
            difference[np.arange(pairs), second] = -1.0
        pair_rows = sparse.kron(sparse.eye(m), difference, format="csr")  # scenario k's pairs
        tensions = self.gain @ preload + self.offset
        scaled = self.spread_gain @ preload + self.spread_offset
        if self.separable:
            high, low = cp.Variable(m), cp.Variable(m)
            each = sparse.kron(sparse.eye(m), np.ones((n, 1)), format="csr")  # scenario k's rows
            spread_rows = [scaled <= each @ high, scaled >= each @ low, high - low <= worst]
        else:
            spread_rows = [pair_rows @ scaled + self.pair_margin <= worst]
        constraints = [
            self.a_level @ preload == self.b_level,
            preload >= self.preload_low,
            preload <= self.preload_high,
            tensions - self.margin >= self.tension_low,
            tensions + self.margin <= self.tension_high,
            *spread_rows,
            self.level_scale @ preload <= nominal_high,
            self.level_scale @ preload >= nominal_low,
        ]
        objective = cp.Minimize(worst + self.TIE_BREAK * (nominal_high - nominal_low))
        self.problem = _checked(cp.Problem(objective, constraints), "preload minimax")
        self._preload, self._worst = preload, worst
        self._nominal = (nominal_high, nominal_low)
        self._pairs = (first, second)

    def solve(self, gains, offsets, a_level, b_level, preload_range, tension_range, scale=None, hook=None):
        """Solve for the scenarios given.

        Parameters
        ----------
        gains : array_like, shape (k, n, n)
            P_k, k <= slots  [-].
        offsets : array_like, shape (k, n)
            q_k  [t].
        a_level, b_level : array_like, shapes (3, n) and (3,)
            Level statics: A0 T* = b0  [-, m; t, t m].
        preload_range : tuple of two arrays, shape (n,)  [t]
            Bounds on T* (from the boom-height range).
        tension_range : tuple of two arrays, shape (k, n)  [t]
            min_tension and SWL per scenario and rope.
        scale : array_like, shape (n,), optional
            What the spread is taken of: s_i T_i (default 1: tension spread [t];
            1 / SWL_i: utilisation spread [-]).
        hook : (array_like, array_like), optional
            ``(G, delta)``: dT/dH at each scenario, shape (k, n, n) [t/m], and each hook's
            height tolerance, shape (n,) [m]. The worst over the hook errors is then exact:
            T_i +- sum_m |G_im| delta_m against the limits, and for each pair
            s_i T_i - s_j T_j + sum_m |s_i G_im - s_j G_jm| delta_m in the spread.

        Returns
        -------
        MinimaxResult

        Raises
        ------
        PlanInfeasible
            No preload keeps every scenario's tensions within range.
        """
        gains = np.asarray(gains, dtype=float)
        count = gains.shape[0]
        if not 1 <= count <= self.slots:
            raise ValueError(f"{count} scenarios given, expected 1 to {self.slots}")
        pad = np.r_[np.arange(count), np.full(self.slots - count, count - 1)]
        n = self.n
        # "no limit" (inf) becomes 100 W: Clarabel needs finite data, and no admissible
        # tension comes near 100 W
        big = 100.0 * abs(float(b_level[0]))

        def clip(values):
            return np.clip(np.asarray(values, dtype=float), -big, big)

        tension_range = (clip(tension_range[0]), clip(tension_range[1]))
        preload_range = (clip(preload_range[0]), clip(preload_range[1]))
        scale = np.ones(n) if scale is None else np.asarray(scale, dtype=float)
        margin, pair_margin = hook_margins(gains.shape[0], n, scale, hook, self.objective)
        self.margin.value = margin[pad].ravel()
        if self.separable:
            if hook is not None:
                raise ValueError("a separable preload minimax takes no hook errors")
        else:
            self.pair_margin.value = pair_margin[pad].ravel()
        self.gain.value = gains[pad].reshape(self.slots * n, n)
        self.offset.value = np.asarray(offsets, dtype=float)[pad].ravel()
        rows = np.tile(scale, self.slots)
        self.spread_gain.value = rows[:, None] * self.gain.value
        self.spread_offset.value = rows * self.offset.value
        self.level_scale.value = np.diag(scale)
        self.tension_low.value = np.asarray(tension_range[0], dtype=float)[pad].ravel()
        self.tension_high.value = np.asarray(tension_range[1], dtype=float)[pad].ravel()
        self.a_level.value = np.asarray(a_level, dtype=float)
        self.b_level.value = np.asarray(b_level, dtype=float)
        self.preload_low.value = np.asarray(preload_range[0], dtype=float)
        self.preload_high.value = np.asarray(preload_range[1], dtype=float)
        _run(self.problem, "preload minimax")
        preload = np.array(self._preload.value)
        high, low = self._nominal
        return MinimaxResult(
            preload=preload,
            worst_spread=float(self._worst.value),
            nominal_spread=float(high.value - low.value),
        )
