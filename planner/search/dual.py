"""A certified lower bound on each lug set's preload LP, for many sets at once (numpy).

For a set of n >= 5 ropes the preload LP (:class:`~liftplan.planner.search.bounds.PreloadMinimax`)
restricted to the screening scenarios Theta0 is

    v = min over T*  of  max over k in Theta0, rope pair (i, j) of  s_i T_k,i - s_j T_k,j
        subject to A0 T* = b0,  lo <= T* <= hi,  (tension limits at each scenario),

with T_k = P_k T* + q_k (``objective = "reserve"``: of s_i T_k,i). Solving one LP per set
costs milliseconds; screening needs thousands of sets in a second. Weak duality gives a bound
from *any* weights lambda >= 0 summing to 1 over the rows f_r(T*) = c_r . T* + d_r:

    v >= sum_r lambda_r d_r + min over {lo <= T* <= hi, A0 T* = b0} (sum_r lambda_r c_r) . T*
      >= sum_r lambda_r d_r + c . T_p + sum_i min(r_i (lo_i - T_p,i), r_i (hi_i - T_p,i))

with c = sum_r lambda_r c_r, r = N N^T c its part in the null space of A0 (N orthonormal)
and T_p the least-norm level solution (the equality constraint dualised; any multiplier is
valid, and the one taken makes r match the box's multipliers where it can). The tension
limits L <= s_i T_k,i <= H enter the same way with multipliers nu >= 0: they add
nu+ (s T - H) + nu- (L - s T), still affine in T*. Every step is a valid bound, whatever the
weights: no step of the optimiser below needs to be trusted.

Good weights come from the smoothed problem min_y tau log sum_r exp(f_r(T_p + N y) / tau)
(a soft maximum; its minimiser's softmax weights nearly satisfy N^T c = 0 and lose at most
tau log(rows) to the maximum), solved by damped Newton in the n - 3 null-space coordinates
for all sets together while tau shrinks. For the spread the rows are pairs, and the soft
maximum of V_i - V_j over pairs factors into a soft maximum of V times a soft maximum of
-V per scenario: the cost is O(scenarios x n), not O(scenarios x n^2). The limits enter the
smoothed problem as a soft exact penalty PENALTY x tau log(1 + exp(violation / tau)), whose
derivative gives their multipliers; so does the preload's box (kept exactly in the bound).

Hook-height errors within their tolerance widen each ordered pair by a constant at each
scenario: at a given attitude the tensions are affine in the errors with a slope that does not
depend on the preload (dT/dH = P_k diag(EA / L)), so the worst over the errors' box is exactly
max_ab (s_a T_a - s_b T_b + c_ab), c_ab = sum_m |s_a G_am - s_b G_bm| delta_m (the rows of the
LP the evaluator solves). Those rows no longer factor, but a scenario's soft maximum is still
one sum over its n^2 pairs, sum_ab exp((V_a - V_b + c_ab) / tau), with the row and column
marginals of its pair weights in place of the two factors' weights: O(scenarios x n^2), the
same scenarios as without the errors (not one copy of each per error pattern), and the
certificate adds sum_r lambda_r c_r to its constant (still valid for any weights).
"""

from __future__ import annotations

import numpy as np

from liftplan.planner.search.rows import row_max, row_min, row_spread, row_sum

#: Continuation: tau from TAU_START x the initial worst value, times TAU_FACTOR per stage
#: (STAGES stages, STEPS Newton steps each).
TAU_START, TAU_FACTOR, STAGES, STEPS = 0.05, 0.3, 6, 5
#: Newton steps at the first tau, and halvings of a step before it is given up.
FIRST_STEPS, BACKTRACK = 12, 30
#: Newton steps per tau at most, and the decrement (x tau) below which a set has converged.
MAX_STEPS, DECREMENT = 40, 1e-6
#: With a finite target: each set is first bounded over only its FIRST_ROWS scenarios of
#: widest spread (largest value for ``reserve``) at the least-norm preload - fewer rows, a
#: weaker but valid bound that already passes the target for most sets a search refines -
#: and over all of them only if it falls short.
FIRST_ROWS = 4
#: Weight of the tension limits' penalty (their multipliers stay below it).
PENALTY = 10.0


def preload_lp_bound(
    particular, null, alpha, beta, low, high, limits, reserve=False, target=np.inf, pair=None
):
    """Lower bounds on the preload LP of many sets (module docstring).

    As :func:`staged_lp_bound` with nothing deferred: the bound alone.
    """
    return staged_lp_bound(particular, null, alpha, beta, low, high, limits, reserve, target, pair)[0]


def staged_lp_bound(
    particular,
    null,
    alpha,
    beta,
    low,
    high,
    limits,
    reserve=False,
    target=np.inf,
    pair=None,
    defer=False,
):
    """Lower bounds on the preload LP of many sets (module docstring), in two stages.

    Parameters
    ----------
    particular : numpy.ndarray, shape (N, n)  [t]
        Least-norm solution of each set's level statics A0 T* = b0.
    null : numpy.ndarray, shape (N, n, d)
        Orthonormal basis of the null space of A0 (d = n - 3).
    alpha : numpy.ndarray, shape (N, m, n)  [t or -]
        Each scenario's scaled values s_i T_k,i at T* = T_p.
    beta : numpy.ndarray, shape (N, m, n, d)
        Their change per unit of the null-space coordinates y (T* = T_p + N y).
    low, high : numpy.ndarray, shape (N, n)  [t]
        Finite bounds on T* that every admissible preload meets.
    limits : (numpy.ndarray, numpy.ndarray), each broadcastable to (N, m, n)  [t or -]
        L and H with L <= s_i T_k,i <= H at every scenario (finite, or +-inf for none).
    reserve : bool
        The rows are s_i T_k,i (the largest utilisation) instead of the pairs' spread.
    target : float or numpy.ndarray, shape (N,)
        A set whose bound reaches this is left there (the search needs no better).
    pair : numpy.ndarray, shape (N, m, n, n), or PairWidening, optional  [t or -]
        Each ordered pair's widening c_ab >= 0 at each scenario (zero diagonal): the rows are
        then V_a - V_b + c_ab (the hook errors' exact worst; module docstring). Not with
        ``reserve``.
    defer : bool or numpy.ndarray, shape (N,)
        Sets whose bound over their :data:`FIRST_ROWS` widest scenarios falls short of a finite
        target keep that bound (valid, weaker) instead of being bounded over every scenario
        at once: the caller bounds them again later, against what is then its target (lower,
        as a search finds better plans), and most need no more than the first stage then.

    Returns
    -------
    bound : numpy.ndarray, shape (N,)
        A valid lower bound on each set's LP value over these scenarios.
    partial : numpy.ndarray, shape (N,), bool
        The sets deferred: their bound is over their first rows only and below the target.
    """
    if reserve and pair is not None:
        raise ValueError("the reserve objective's rows take no pair widening")
    limits = tuple(np.broadcast_to(v, alpha.shape) for v in limits)
    target = np.broadcast_to(np.asarray(target, dtype=float), alpha.shape[:1])
    m = alpha.shape[1]
    partial = np.zeros(len(target), dtype=bool)
    if not np.any(np.isfinite(target)) or m <= FIRST_ROWS:
        pair = pair.full() if isinstance(pair, PairWidening) else pair
        return _bound(particular, null, alpha, beta, low, high, limits, reserve, target, pair), partial
    # a bound over some of the rows is a bound over all of them (a relaxation); with the hook
    # errors' widening the rows are ranked by its upper estimate c_ab <= u_a + u_b, so that
    # the widening itself is worked out for the rows taken only
    if reserve:
        width = row_max(alpha)
    elif isinstance(pair, PairWidening):
        each = pair.each()
        width = row_max(alpha + each) - row_min(alpha - each)
    else:
        width = _worst_rows(alpha, pair)
    widest = np.argsort(-width, axis=1)

    def stage(index, count):
        """The sets ``index`` bounded over their ``count`` widest scenarios."""
        rows = widest[index, :count]

        def some(v):
            if v is None:
                return None
            if isinstance(v, PairWidening):
                return v.subset(index).at(rows)
            v = v[index]
            return np.take_along_axis(v, rows.reshape(rows.shape + (1,) * (v.ndim - 2)), axis=1)

        return _bound(
            particular[index],
            null[index],
            some(alpha),
            some(beta),
            low[index],
            high[index],
            tuple(some(v) for v in limits),
            reserve,
            target[index],
            some(pair),
            give_up=True,
        )

    bound = stage(np.arange(len(target)), FIRST_ROWS)
    short_mask = bound < target
    partial = short_mask & np.broadcast_to(np.asarray(defer, dtype=bool), short_mask.shape)
    short = np.flatnonzero(short_mask & ~partial)
    if short.size:
        bound[short] = np.maximum(
            bound[short],
            _bound(
                particular[short],
                null[short],
                alpha[short],
                beta[short],
                low[short],
                high[short],
                tuple(v[short] for v in limits),
                reserve,
                target[short],
                pair.subset(short).full() if isinstance(pair, PairWidening) else _pick(pair, short),
            ),
        )
    return bound, partial


class PairWidening:
    """The hook errors' widening of each ordered rope pair at each scenario of many sets,
    c_ab = sum_j |s_a G_aj - s_b G_bj| delta_j (N, m, n, n), worked out only for the
    scenarios asked (the dual bound's first stage takes a few of each set's).

    Parameters
    ----------
    scaled : numpy.ndarray, shape (N, m, n, n)  [t/m or 1/m]
        s_a G_aj: the objective's scale times dT_a/dH_j at each scenario.
    delta : numpy.ndarray, shape (N, n)  [m]
        Each hook's height tolerance.
    """

    def __init__(self, scaled, delta):
        self.scaled, self.delta = scaled, delta
        self._full = None

    @property
    def shape(self):
        return self.scaled.shape

    def subset(self, index):
        """The widening of the sets ``index`` (an index or a mask over the N sets)."""
        return PairWidening(self.scaled[index], self.delta[index])

    def full(self):
        """Every scenario's widening, (N, m, n, n) (worked out once)."""
        if self._full is None:
            self._full = _symmetric(self.upper_triangle())
        return self._full

    def at(self, rows):
        """The widening at the scenarios ``rows`` (N, r) of each set, (N, r, n, n)."""
        scaled = np.take_along_axis(self.scaled, rows[..., None, None], axis=1)
        return _symmetric(_upper_widening(scaled, self.delta))

    def upper_triangle(self):
        """c_ab for a < b (numpy.triu_indices order), (N, m, n (n - 1) / 2): c is symmetric."""
        if self._full is not None:
            first, second = np.triu_indices(self.scaled.shape[2], 1)
            return self._full[..., first, second]
        return _upper_widening(self.scaled, self.delta)

    def each(self):
        """u_a = sum_j |s_a G_aj| delta_j, (N, m, n): c_ab <= u_a + u_b (the triangle
        inequality), a cheap upper estimate."""
        return np.einsum("kmaj,kj->kma", np.abs(self.scaled), self.delta)


def _upper_widening(scaled, delta):
    """sum_j |s_a G_aj - s_b G_bj| delta_j for a < b, (N, m, pairs): one hook at a time (no
    (N, m, pairs, n) array)."""
    n = scaled.shape[2]
    first, second = np.triu_indices(n, 1)
    upper = np.zeros(scaled.shape[:2] + (len(first),))
    for j in range(scaled.shape[3]):
        column = scaled[..., j]
        upper += np.abs(column[..., first] - column[..., second]) * delta[:, j, None, None]
    return upper


def _symmetric(upper):
    """The (..., n, n) symmetric array with zero diagonal from its upper triangle."""
    pairs = upper.shape[-1]
    n = int(round((1 + np.sqrt(1 + 8 * pairs)) / 2))
    first, second = np.triu_indices(n, 1)
    out = np.zeros(upper.shape[:-1] + (n, n))
    out[..., first, second] = upper
    out[..., second, first] = upper
    return out


def _pick(value, index):
    """``value[index]``, or None for None (no pair widening)."""
    return None if value is None else value[index]


def _pair_rows(values, pair):
    """V_a - V_b + c_ab over every ordered pair, shape (..., n, n)."""
    return values[..., :, None] - values[..., None, :] + pair


def _worst_rows(values, pair):
    """Each scenario's largest row: max - min, or with ``pair`` max_ab (V_a - V_b + c_ab)."""
    if pair is None:
        return row_spread(values)
    rows = _pair_rows(values, pair)
    return rows.reshape(rows.shape[:-2] + (-1,)).max(axis=-1)


def _bound(particular, null, alpha, beta, low, high, limits, reserve, target, pair=None, give_up=False):
    """:func:`preload_lp_bound` over every row given.

    ``give_up``: a set stops as soon as some preload is seen to meet every row given below
    ``target`` (admissible, its worst row under it): the LP over these rows is then below the
    target too, so no certificate from them can reach it (the caller bounds it over more rows)."""
    count, m, n = alpha.shape
    target = np.broadcast_to(np.asarray(target, dtype=float), (count,))
    d = null.shape[2]
    limit_low, limit_high = (np.broadcast_to(v, alpha.shape) for v in limits)
    y = np.zeros((count, d))
    tau = TAU_START * np.maximum(_worst(alpha, reserve, pair), 1e-9 * np.abs(alpha).max(axis=(1, 2)))
    ridge = 1e-12 * np.maximum(np.abs(beta).max(axis=(1, 2, 3)), 1e-300) ** 2
    bound = np.full(count, -np.inf)
    open_ = np.arange(count)
    for stage in range(STAGES + 1):
        if open_.size == 0:
            break
        open_ = _certify(
            y,
            open_,
            tau,
            ridge,
            (alpha, beta, limit_low, limit_high, pair),
            (particular, null, low, high),
            reserve,
            STEPS if stage else FIRST_STEPS,
            MAX_STEPS,
            bound,
            target,
            give_up,
        )
        tau = TAU_FACTOR * tau
    return bound


def _certify(y, open_, tau, ridge, parts, box, reserve, steps, most, bound, target, give_up=False):
    """Newton steps on the sets ``open_`` (y changed in place), then their certificate
    (``bound`` raised in place: every certificate is valid, the best is kept); returns the
    sets still short of ``target`` (with ``give_up``, those whose LP over these rows is not
    yet seen to be below it: :func:`_bound`)."""
    k = open_
    parts = tuple(_pick(v, k) for v in parts)
    box = tuple(v[k] for v in box)
    y[k] = _newton(y[k], tau[k], ridge[k], parts, box, reserve, steps, most)
    values = parts[0] + np.einsum("kmid,kd->kmi", parts[1], y[k])
    weights = _Weights(values, tau[k], reserve, parts[2], parts[3], parts[4])
    box_weights = _box_multipliers(y[k], box, tau[k])
    bound[k] = np.maximum(
        bound[k], weights.certificate(box[0], box[1], parts[0], parts[1], box[2], box[3], box_weights)
    )
    short = bound[k] < target[k]
    if give_up:  # an admissible preload whose worst row is below the target: the LP is too
        preload = box[0] + np.einsum("kid,kd->ki", box[1], y[k])
        admissible = np.all((preload >= box[2]) & (preload <= box[3]), axis=1) & np.all(
            (values >= parts[2]) & (values <= parts[3]), axis=(1, 2)
        )
        short &= ~(admissible & (_worst(values, reserve, parts[4]) < target[k]))
    return k[short]


def _newton(y, tau, ridge, parts, box, reserve, steps, most=MAX_STEPS):
    """Damped Newton steps on the smoothed objective at fixed tau, for many sets.

    At least ``steps`` steps for every set, and up to ``most`` for a set whose Newton
    decrement is still above DECREMENT x tau (the sets that converge drop out). The preload's
    box (lo <= T_p + N y <= hi) enters the smoothing as a soft penalty too, so that the weights
    found are those of the box-constrained LP (the certificate itself keeps the box exactly)."""
    y = y.copy()
    live = np.arange(len(y))
    for step_count in range(most):
        if live.size == 0:
            break
        part = tuple(_pick(v, live) for v in parts)
        box_part = tuple(v[live] for v in box)
        decrement = _newton_step(y, live, tau[live], ridge[live], part, box_part, reserve)
        if step_count + 1 >= steps:
            live = live[decrement > DECREMENT * tau[live]]
    return y


def _newton_step(y, live, tau, ridge, parts, box, reserve):
    """One damped Newton step on the sets ``live`` (y changed in place); their decrements."""
    alpha, beta, limit_low, limit_high, pair = parts
    count, m, n, d = beta.shape
    flat = beta.reshape(count, m * n, d)
    x = y[live]
    values = alpha + np.einsum("kmid,kd->kmi", beta, x)
    weights = _Weights(values, tau, reserve, limit_low, limit_high, pair)
    grad, hess = weights.derivatives(beta, flat)
    penalty, grad_box, hess_box = _box_penalty(x, box, tau)
    grad, hess = grad + grad_box, hess + hess_box
    hess += (ridge / tau + 1e-10 * np.abs(hess).max(axis=(1, 2)) + 1e-300)[:, None, None] * np.eye(d)
    try:
        step = -np.linalg.solve(hess, grad[..., None])[..., 0]
    except np.linalg.LinAlgError:  # a flat direction (weights on one rope): least squares
        step = -(np.linalg.pinv(hess) @ grad[..., None])[..., 0]
    # backtracking (Armijo) on each set's smoothed objective, the sets still short of a
    # decrease only
    now = weights.objective + penalty
    slope = np.einsum("kd,kd->k", grad, step)
    size = np.ones(count)
    active = np.arange(count)
    for _ in range(BACKTRACK):
        trial = x[active] + size[active, None] * step[active]
        values = alpha[active] + np.einsum("kmid,kd->kmi", beta[active], trial)
        value = (
            _objective(
                values, tau[active], reserve, limit_low[active], limit_high[active], _pick(pair, active)
            )
            + _box_penalty(trial, tuple(v[active] for v in box), tau[active])[0]
        )
        # (a rounding-level rise is no rise: near the minimum both sides agree)
        worse = value > now[active] + 1e-4 * size[active] * slope[active] + 1e-12 * np.abs(now[active])
        size[active[worse]] *= 0.5
        active = active[worse]
        if active.size == 0:
            break
    size[active] = 0.0  # no decrease found: stay
    y[live] = x + size[:, None] * step
    return np.where(size > 0.0, -slope, 0.0)  # g^T H^-1 g: the Newton decrement squared


def _worst(values, reserve, pair=None):
    if reserve:
        return row_max(values).max(axis=1)
    return _worst_rows(values, pair).max(axis=1)


def _log_sum_exp(x, axis):
    if axis == x.ndim - 1:  # over the ropes: the fast reductions of planner/search/rows.py
        top = row_max(x)
        return np.log(row_sum(np.exp(x - top[..., None]))) + top
    top = x.max(axis=axis, keepdims=True)
    return np.log(np.exp(x - top).sum(axis=axis)) + np.squeeze(top, axis=axis)


#: Below this, log(1 + e^x) (< 4e-18) is taken as 0.
SOFT_FLOOR = -40.0


def _softplus(x):
    """log(1 + e^x), elementwise; 0 where x < SOFT_FLOOR (and for -inf: no limit)."""
    out = np.zeros(x.shape)
    live = x > SOFT_FLOOR
    out[live] = np.logaddexp(0.0, x[live])
    return out


def _box_multipliers(y, box, tau):
    """The box penalty's multipliers at y: PENALTY (sigma(over) - sigma(under)), (N, n)."""
    particular, null, low, high = box
    t = tau[:, None]
    preload = particular + np.einsum("kid,kd->ki", null, y)
    return PENALTY * (_sigmoid((preload - high) / t) - _sigmoid((low - preload) / t))


def _box_penalty(y, box, tau):
    """Soft penalty of the preload's box at T* = T_p + N y: (value, gradient, Hessian)."""
    particular, null, low, high = box
    t = tau[:, None]
    preload = particular + np.einsum("kid,kd->ki", null, y)
    over, under = (preload - high) / t, (low - preload) / t
    value = PENALTY * tau * (np.logaddexp(0.0, over) + np.logaddexp(0.0, under)).sum(axis=1)
    s_over, s_under = _sigmoid(over), _sigmoid(under)
    grad = PENALTY * np.einsum("ki,kid->kd", s_over - s_under, null)
    curve = PENALTY * (s_over * (1 - s_over) + s_under * (1 - s_under)) / t
    hess = (null * curve[..., None]).transpose(0, 2, 1) @ null
    return value, grad, hess


def _objective(values, tau, reserve, limit_low, limit_high, pair=None):
    """tau log sum_r exp(f_r / tau) plus the limits' soft penalty, per set."""
    t = tau[:, None, None]
    if pair is not None:  # each scenario's soft maximum over its ordered pairs
        log_k = _pair_soft_max(values, pair, tau, weights=False)[0]
    else:
        log_k = _log_sum_exp(values / t, 2)
        if not reserve:
            log_k = log_k + _log_sum_exp(-values / t, 2)
    with np.errstate(invalid="ignore"):
        soft = _softplus((values - limit_high) / t) + _softplus((limit_low - values) / t)
    return tau * _log_sum_exp(log_k, 1) + PENALTY * tau * soft.sum(axis=(1, 2))


def _sigmoid(x):
    return 0.5 * (1.0 + np.tanh(0.5 * x))


def _pair_soft_max(values, pair, tau, weights=True):
    """Each scenario's log sum_ab exp((V_a - V_b + c_ab) / tau), shape (N, m), and (with
    ``weights``) the pairs' softmax weights lambda_ab, shape (N, m, n, n), summing to 1 per
    scenario (in place of one array: the reductions of planner/search/rows.py)."""
    t = tau[:, None, None]
    scaled = values / t
    rows = pair * (1.0 / t)[..., None]
    rows += scaled[..., :, None]
    rows -= scaled[..., None, :]
    top = row_max(row_max(rows))
    rows -= top[..., None, None]
    np.exp(rows, out=rows)
    total = rows.reshape(rows.shape[:2] + (-1,)) @ np.ones(rows.shape[2] * rows.shape[3])
    if weights:
        rows /= total[..., None, None]
    return np.log(total) + top, rows


class _Weights:
    """Softmax weights of the rows and the limits' multipliers at one point."""

    def __init__(self, values, tau, reserve, limit_low, limit_high, pair=None):
        t = tau[:, None, None]
        self.tau, self.reserve = tau, reserve
        self.limit_low, self.limit_high = limit_low, limit_high
        #: each scenario's pair weights (N, m, n, n) where they do not factor, else None
        self.pairs, self.pair = None, pair
        if pair is not None:  # the hook errors' pair widening: one soft maximum over pairs
            log_k, self.pairs = _pair_soft_max(values, pair, tau)
            self.p, self.q = row_sum(self.pairs), row_sum(self.pairs.swapaxes(2, 3))  # row, column
        else:
            up = values / t
            top = row_max(up)[..., None]
            e_up = np.exp(up - top)
            s_up = row_sum(e_up)
            self.p = e_up / s_up[..., None]
            log_k = np.log(s_up) + top[..., 0]  # log sum_i exp(V_k,i / tau)
            self.q = np.zeros_like(values)
        if pair is None and not reserve:  # times sum_j exp(-V_k,j / tau): the pairs' factors
            down = -values / t
            bottom = row_max(down)[..., None]
            e_down = np.exp(down - bottom)
            s_down = row_sum(e_down)
            self.q = e_down / s_down[..., None]
            log_k = log_k + np.log(s_down) + bottom[..., 0]
        shift = log_k.max(axis=1, keepdims=True)
        pi = np.exp(log_k - shift)
        total = pi.sum(axis=1, keepdims=True)
        self.pi = pi / total
        #: the smoothed objective: tau log sum_r exp(f_r / tau) + the limits' soft penalty
        self.objective = tau * (shift[:, 0] + np.log(total[:, 0]))
        with np.errstate(invalid="ignore"):  # inf - inf never occurs: values are finite
            over = _sigmoid((values - limit_high) / t)
            under = _sigmoid((limit_low - values) / t)
        self.over, self.under = PENALTY * over, PENALTY * under
        with np.errstate(invalid="ignore"):
            soft = _softplus((values - limit_high) / t) + _softplus((limit_low - values) / t)
        self.objective = self.objective + PENALTY * tau * soft.sum(axis=(1, 2))
        self.curvature = PENALTY * (over * (1.0 - over) + under * (1.0 - under)) / t

    def derivatives(self, beta, flat):
        """Gradient (N, d) and Hessian (N, d, d) of the smoothed objective in y."""
        count, m, n, d = beta.shape
        tau = self.tau[:, None]
        b_up = np.einsum("kmi,kmid->kmd", self.p, beta)  # (N, m, d)
        b_down = np.einsum("kmi,kmid->kmd", self.q, beta)
        grad = np.einsum("km,kmd->kd", self.pi, b_up - b_down)
        # second moments of the rows' slopes under the weights, and the limits' curvature,
        # in one product: flat^T diag(w) flat
        share = self.p if self.reserve else self.p + self.q
        weight = (self.pi[..., None] * share).reshape(count, m * n) / tau + self.curvature.reshape(
            count, m * n
        )
        hess = (flat * weight[..., None]).transpose(0, 2, 1) @ flat
        if self.pairs is None:  # sum_k pi_k beta_k^T p_k q_k^T beta_k
            cross = (b_up * self.pi[..., None]).transpose(0, 2, 1) @ b_down
        else:  # sum_k pi_k beta_k^T Lambda_k beta_k
            mixed = (self.pairs @ beta) * self.pi[..., None, None]
            cross = flat.transpose(0, 2, 1) @ mixed.reshape(count, m * n, d)
        hess -= (cross + cross.transpose(0, 2, 1) + grad[:, :, None] * grad[:, None, :]) / tau[..., None]
        penalty = (self.over - self.under).reshape(count, m * n)
        grad = grad + np.einsum("kr,krd->kd", penalty, flat)
        return grad, hess

    def certificate(self, particular, null, alpha, beta, low, high, box_weights=None):
        """Weak-duality bound from these weights (valid for any weights).

        ``box_weights`` v (N, n): the box's multipliers the smoothing found; the equality's
        multiplier is then chosen so that the reduced cost is -v where it can be,
        r = -v + N N^T (c + v), which keeps N^T r = N^T c (any such r is valid)."""
        # the rows' weights on each value, and the limits' multipliers (finite limits only)
        w = self.pi[..., None] * (self.p - self.q)
        over = np.where(np.isfinite(self.limit_high), self.over, 0.0)
        under = np.where(np.isfinite(self.limit_low), self.under, 0.0)
        w = w + over - under
        constant = (
            np.einsum("kmi,kmi->k", w, alpha)
            + (0.0 if self.pairs is None else np.einsum("km,kmab,kmab->k", self.pi, self.pairs, self.pair))
            - np.einsum("kmi,kmi->k", over, np.where(over > 0, self.limit_high, 0.0))
            + np.einsum("kmi,kmi->k", under, np.where(under > 0, self.limit_low, 0.0))
        )
        slope = np.einsum("kmi,kmid->kd", w, beta)  # N^T c
        if box_weights is None:
            residual = np.einsum("kid,kd->ki", null, slope)  # r = N N^T c
        else:
            shift = slope + np.einsum("kid,ki->kd", null, box_weights)
            residual = -box_weights + np.einsum("kid,kd->ki", null, shift)
        span_low, span_high = low - particular, high - particular
        return constant + np.minimum(residual * span_low, residual * span_high).sum(axis=1)
