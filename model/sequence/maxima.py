"""The largest value of each load over a continuous range of angles, not only at grid points.

:func:`continuous_maxima` samples the range adaptively and refines every local maximum:

1. the user's grid, each step cut in four;
2. every interval whose midpoint leaves the chord of its ends by more than ``tol`` (in any of
   the loads) is halved, down to ``min_width``: a load that bends or kinks between two
   samples is sampled until it is straight to ``tol`` between them;
3. each local maximum of the samples (a sample at least as high as both neighbours and
   higher than one of them by more than the rounding) is refined by Brent's bounded search
   between its neighbours (scipy), to ``xtol``; the range's ends count as candidates.

A peak narrower than the samples around it can only be missed if it rises and falls between
two samples whose chord its neighbours' midpoints follow to ``tol``; on the loads of a held
angle (ratios of sines of the angle) that needs a peak far narrower than the quarter step.
Every load is one function of the angle through the same equilibrium, so every sample serves
every load (the evaluations are cached by angle).
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

#: Local maxima refined per load (the highest ones; the rest are within ``tol`` of a sample).
REFINED = 6
#: First subdivision of each user step.
SUBSTEPS = 4


@dataclass(frozen=True)
class Peak:
    """The largest value of one load over a range of angles.

    Parameters
    ----------
    value : float
        In the load's unit (t).
    angle : float  [deg]
        Where it occurs.
    bound : float or None
        An upper bound of the load over the whole range (:func:`curvature_bound`), >= value;
        None where no bound was taken (the lug planner's grid maxima).
    """

    value: float
    angle: float
    bound: float | None = None


class Sampler:
    """Cached evaluation of every load at an angle.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(angle) -> (state, dict of str to float)``.
    """

    def __init__(self, evaluate):
        self.evaluate = evaluate
        self.cache = {}

    def __call__(self, angle):
        key = round(float(angle), 12)
        if key not in self.cache:
            self.cache[key] = self.evaluate(key)
        return self.cache[key]

    def values(self, angle):
        return self(angle)[1]

    @property
    def evaluations(self):
        return len(self.cache)


def adaptive_samples(sampler, grid, tol, min_width):
    """Angles (sorted) sampled so that every load is straight to ``tol`` between neighbours."""
    grid = np.asarray(grid, dtype=float)
    starts = []
    for a, b in zip(grid[:-1], grid[1:]):
        starts.extend(np.linspace(a, b, SUBSTEPS + 1)[:-1])
    starts.append(grid[-1])
    for angle in starts:
        sampler(angle)
    stack = list(zip(starts[:-1], starts[1:]))
    while stack:
        a, b = stack.pop()
        if abs(b - a) <= min_width:
            continue
        m = 0.5 * (a + b)
        va, vb, vm = sampler.values(a), sampler.values(b), sampler.values(m)
        dev = max((abs(vm[k] - 0.5 * (va[k] + vb[k])) for k in vm), default=0.0)
        if dev > tol:
            stack += [(a, m), (m, b)]
    return np.array(sorted(sampler.cache))


def continuous_maxima(sampler, angles, names, xtol, noise):
    """The maximum of each load over ``[angles[0], angles[-1]]``.

    Parameters
    ----------
    sampler : Sampler
    angles : array  [deg]
        Sorted samples (:func:`adaptive_samples`).
    names : iterable of str
        The loads.
    xtol : float  [deg]
        Brent's tolerance on the angle.
    noise : float
        Rises smaller than this are rounding, not a maximum.

    Returns
    -------
    dict of str to Peak
    """
    out = {}
    lo, hi = angles[0], angles[-1]
    for name in names:
        v = np.array([sampler.values(a)[name] for a in angles])
        best = int(np.argmax(v))
        peak = Peak(float(v[best]), float(angles[best]))
        inner = [
            i
            for i in range(1, len(v) - 1)
            if v[i] >= v[i - 1] and v[i] >= v[i + 1] and v[i] - min(v[i - 1], v[i + 1]) > noise
        ]
        for i in heapq.nlargest(REFINED, inner, key=lambda k: v[k]):
            a, b = angles[i - 1], angles[i + 1]
            res = minimize_scalar(
                lambda t, n=name: -sampler.values(min(max(t, lo), hi))[n],
                bounds=(a, b),
                method="bounded",
                options={"xatol": xtol},
            )
            for t in (float(res.x), angles[i]):
                val = sampler.values(t)[name]
                if val > peak.value:
                    peak = Peak(float(val), float(t))
        out[name] = Peak(peak.value, peak.angle, max(peak.value, curvature_bound(angles, v)))
    return out


#: The bound takes each interval's curvature as at most this many times the largest second
#: difference of the samples around it.
CURVATURE_SAFETY = 2.0


def curvature_bound(angles, values):
    """An upper bound of a load between its samples, from their curvature.

    On an interval [a, b] where |f''| <= M, f lies below its chord plus M (x - a)(b - x) / 2,
    so below max(f(a), f(b)) + M (b - a)^2 / 8. M is taken as :data:`CURVATURE_SAFETY` times
    the largest second difference of the samples at the interval's ends and their neighbours
    (at a kink, a slack rope's, the second difference is the change of slope over the
    sampling width, and the term is that change times a quarter of the width: the adaptive
    sampling has closed in on it). The bound holds whenever the load's curvature within each
    interval is no more than that; it is not an interval-arithmetic proof.

    Parameters
    ----------
    angles : array (m,)
        Sorted samples.
    values : array (m,)
        The load at them.

    Returns
    -------
    float
    """
    x, v = np.asarray(angles, dtype=float), np.asarray(values, dtype=float)
    if len(x) < 3:
        return float(v.max())
    h = np.diff(x)
    slope = np.diff(v) / h
    second = np.zeros(len(x))
    second[1:-1] = np.abs(2.0 * np.diff(slope) / (h[:-1] + h[1:]))
    second[0], second[-1] = second[1], second[-2]
    near = np.maximum.reduce(
        [second[:-1], second[1:], np.r_[second[0], second[:-2]], np.r_[second[2:], second[-1]]]
    )
    return float(np.max(np.maximum(v[:-1], v[1:]) + CURVATURE_SAFETY * near * h * h / 8.0))
