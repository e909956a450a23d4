"""Piecewise polynomials along the body's x: exact integration, evaluation, extrema.

A :class:`Piecewise` holds, on each interval [b_k, b_k+1] of sorted breakpoints, a polynomial in
the local coordinate u = x - b_k (ascending coefficients), a value ``head`` before the first
breakpoint and a polynomial ``tail`` in u = x - b_K after the last. Integrating one adds a
degree and may add a jump at every breakpoint (point loads into the shear, point couples into
the moment), so a linear weight curve integrates to a quadratic shear and a cubic moment with
no discretisation. Extrema are found exactly: at the breakpoints (both sides of a jump) and at
the real roots of the derivative inside each interval, all intervals at once (companion
matrices, :func:`unit_roots`).
"""

from __future__ import annotations

from dataclasses import dataclass
from math import comb

import numpy as np

# Coefficients below this fraction of a polynomial's largest (on the unit interval) are
# round-off of a lower-degree polynomial: leaving them in gives spurious far-away roots.
_NEGLIGIBLE = 1e-13


@dataclass(frozen=True)
class Piecewise:
    """A piecewise polynomial along x.

    Parameters
    ----------
    breaks : numpy.ndarray, shape (K + 1,)  [m]
        Strictly increasing breakpoints.
    coef : numpy.ndarray, shape (K, d + 1)
        Ascending coefficients of interval k in u = x - breaks[k].
    head : float
        Value before ``breaks[0]``.
    tail : numpy.ndarray, shape (e + 1,)
        Ascending coefficients in u = x - breaks[-1] after the last breakpoint.
    """

    breaks: np.ndarray
    coef: np.ndarray
    head: float = 0.0
    tail: np.ndarray | None = None

    def __post_init__(self):
        tail = np.zeros(1) if self.tail is None else np.atleast_1d(np.asarray(self.tail, dtype=float))
        object.__setattr__(self, "tail", tail)

    @property
    def span(self):
        """(first, last) breakpoint  [m]."""
        return float(self.breaks[0]), float(self.breaks[-1])

    def __call__(self, x, side="right"):
        """Values at ``x``; at a breakpoint, the value just after it (``side="right"``) or
        just before it (``"left"``)."""
        x = np.asarray(x, dtype=float)
        b = self.breaks
        k = np.searchsorted(b, x, side=side) - 1
        inside = (k >= 0) & (k < len(b) - 1)
        kk = np.clip(k, 0, len(b) - 2)
        out = _horner(self.coef[kk], x - b[kk])
        out = np.where(inside, out, self.head)
        return np.where(k >= len(b) - 1, _horner(self.tail, x - b[-1]), out)

    def integral(self, jumps=None, density=None):
        """The running integral from -inf, plus a jump at each breakpoint.

        Parameters
        ----------
        jumps : numpy.ndarray, shape (K + 1,), optional
            Added at each breakpoint (the value is right-continuous).
        density : Piecewise, optional
            Another piecewise polynomial on the same breakpoints, added to the integrand.

        Returns
        -------
        Piecewise
            Zero before the first breakpoint (the integrand's ``head`` must be 0).
        """
        coef, tail = self.coef, self.tail
        if density is not None:
            coef, tail = _add(coef, density.coef), _add(tail[None, :], density.tail[None, :])[0]
        count, degree = coef.shape
        h = np.diff(self.breaks)
        powers = np.arange(1, degree + 1)
        whole = np.sum(coef * h[:, None] ** powers / powers, axis=1)  # each interval's integral
        jumps = np.zeros(count + 1) if jumps is None else np.asarray(jumps, dtype=float)
        start = np.concatenate([[0.0], np.cumsum(whole)]) + np.cumsum(jumps)
        new = np.empty((count, degree + 1))
        new[:, 0] = start[:-1]
        new[:, 1:] = coef / powers
        new_tail = np.concatenate([[start[-1]], tail / np.arange(1, len(tail) + 1)])
        return Piecewise(self.breaks, new, 0.0, new_tail)

    def end(self):
        """The value just after the last breakpoint (the closure)."""
        return float(self.tail[0])

    def extreme(self):
        """Largest |value| over [first, last breakpoint], found exactly.

        Returns
        -------
        Extreme
        """
        xs, values = self.candidates()
        k = int(np.argmax(np.abs(values)))
        return Extreme(float(abs(values[k])), float(xs[k]), float(values[k]))

    def candidates(self):
        """Every point where |value| can peak: both sides of each breakpoint and the roots of
        the derivative inside each interval; returns (x, value) arrays."""
        b, h = self.breaks, np.diff(self.breaks)
        derivative = self.coef[:, 1:] * np.arange(1, self.coef.shape[1])
        which, t = unit_roots(_scaled(derivative, h))
        x_in = b[which] + t * h[which]
        xs = np.concatenate([b[:-1], b[1:], x_in])
        values = np.concatenate(
            [self.coef[:, 0], _horner(self.coef, h), _horner(self.coef[which], t * h[which])]
        )
        return xs, values

    def worst_ratio(self, envelope):
        """The largest |value| / envelope(x) over [first, last breakpoint], exactly.

        Parameters
        ----------
        envelope : tuple of (float, float)
            A positive piecewise-linear allowable ([x m, value]), its end values held beyond
            its first and last points.

        Returns
        -------
        x : float  [m]
        value : float
            |value| at x.
        limit : float
            The envelope at x.
        """
        ex, ev = (np.array(v, dtype=float) for v in zip(*envelope))
        lo, hi = self.span
        inner = ex[(ex > lo) & (ex < hi)]
        merged = self.refined(inner)
        b, h = merged.breaks, np.diff(merged.breaks)
        a0 = np.interp(b[:-1], ex, ev)
        slope = (np.interp(b[1:], ex, ev) - a0) / h
        # d/du (f / a) = (f' a - f a') / a^2: its numerator has f's degree
        c = merged.coef
        deriv = np.zeros_like(c)
        deriv[:, :-1] = c[:, 1:] * np.arange(1, c.shape[1])
        numer = _add(deriv * a0[:, None], np.hstack([np.zeros((len(c), 1)), deriv[:, :-1]]) * slope[:, None])
        numer = _add(numer, -c * slope[:, None])
        which, t = unit_roots(_scaled(numer, h))
        xs = np.concatenate([b[:-1], b[1:], b[which] + t * h[which]])
        values = np.concatenate([c[:, 0], _horner(c, h), _horner(c[which], t * h[which])])
        limits = np.interp(xs, ex, ev)
        k = int(np.argmax(np.abs(values) / limits))
        return float(xs[k]), float(abs(values[k])), float(limits[k])

    def refined(self, points):
        """The same function on breakpoints with ``points`` (inside the span) added."""
        b = np.union1d(self.breaks, np.asarray(points, dtype=float))
        return Piecewise(b, on_breaks(b, self.breaks, self.coef), self.head, self.tail)


@dataclass(frozen=True)
class Extreme:
    """The largest absolute value of a curve and where it is.

    Parameters
    ----------
    value : float
        max |f| (>= 0).
    x : float  [m]
    signed : float
        f at x, with its sign.
    """

    value: float
    x: float
    signed: float

    def to_json(self):
        return {"value": self.value, "x": self.x, "signed": self.signed}


def _horner(coef, u):
    """Evaluate ascending coefficients (..., d + 1) at u (broadcast over the leading axes)."""
    coef = np.asarray(coef, dtype=float)
    out = np.zeros(np.broadcast_shapes(coef.shape[:-1], np.shape(u)))
    for j in range(coef.shape[-1] - 1, -1, -1):
        out = out * u + coef[..., j]
    return out


def _add(a, b):
    """Sum of two coefficient arrays (K, *) of possibly different degrees."""
    width = max(a.shape[1], b.shape[1])
    out = np.zeros((a.shape[0], width))
    out[:, : a.shape[1]] += a
    out[:, : b.shape[1]] += b
    return out


def _scaled(coef, h):
    """Coefficients in u to coefficients in t = u / h (t in [0, 1])."""
    return coef * h[:, None] ** np.arange(coef.shape[1])


def unit_roots(coef):
    """Real roots in (0, 1) of many polynomials at once.

    Parameters
    ----------
    coef : numpy.ndarray, shape (K, d + 1)
        Ascending coefficients, one polynomial per row.

    Returns
    -------
    rows : numpy.ndarray of int
    t : numpy.ndarray
        Row index and root of each real root inside (0, 1).
    """
    rows_out, roots_out = [], []
    if coef.shape[1] < 2:
        return np.zeros(0, dtype=int), np.zeros(0)
    size = np.max(np.abs(coef), axis=1)
    significant = np.abs(coef) > _NEGLIGIBLE * size[:, None]
    # effective degree: the highest significant coefficient
    degree = np.where(significant.any(axis=1), coef.shape[1] - 1 - np.argmax(significant[:, ::-1], axis=1), 0)
    for d in range(1, coef.shape[1]):
        rows = np.nonzero(degree == d)[0]
        if not len(rows):
            continue
        c = coef[rows, : d + 1] / coef[rows, d : d + 1]  # monic
        if d == 1:
            roots = -c[:, :1]
        elif d == 2:  # t^2 + p t + r: closed form, the stable way round
            p, r = c[:, 1], c[:, 0]
            disc = 0.25 * p * p - r
            root = np.sqrt(np.maximum(disc, 0.0))
            big = -(0.5 * p + np.where(p >= 0.0, root, -root))
            other = np.divide(r, big, out=np.zeros_like(r), where=big != 0.0)
            roots = np.stack([big, other], axis=1).astype(complex)
            roots.imag[disc < 0.0] = 1.0  # complex pair: no real root
        else:
            companion = np.zeros((len(rows), d, d))
            companion[:, 1:, :-1] = np.eye(d - 1)
            companion[:, :, -1] = -c[:, :d]
            roots = np.linalg.eigvals(companion)
        real = np.abs(roots.imag) <= 1e-9 * np.maximum(1.0, np.abs(roots.real))
        inside = real & (roots.real > 0.0) & (roots.real < 1.0)
        r, j = np.nonzero(inside)
        rows_out.append(rows[r])
        roots_out.append(roots.real[r, j])
    if not rows_out:
        return np.zeros(0, dtype=int), np.zeros(0)
    return np.concatenate(rows_out), np.concatenate(roots_out)


def taylor_shift(coef, delta):
    """Coefficients of p(u + delta) from those of p(u), row-wise.

    Parameters
    ----------
    coef : numpy.ndarray, shape (K, d + 1)
    delta : numpy.ndarray, shape (K,)
    """
    degree = coef.shape[1] - 1
    out = np.zeros_like(coef)
    for j in range(degree + 1):
        for m in range(j + 1):
            out[:, m] += comb(j, m) * coef[:, j] * delta ** (j - m)
    return out


def on_breaks(breaks, own_breaks, own_coef):
    """A piecewise polynomial (``own_breaks``, ``own_coef``, zero outside) re-expressed on
    ``breaks`` (which must include every one of ``own_breaks`` inside their span).

    Returns
    -------
    numpy.ndarray, shape (len(breaks) - 1, d + 1)
    """
    breaks = np.asarray(breaks, dtype=float)
    middle = 0.5 * (breaks[:-1] + breaks[1:])
    j = np.searchsorted(own_breaks, middle, side="right") - 1
    inside = (j >= 0) & (j < len(own_breaks) - 1)
    jj = np.clip(j, 0, len(own_breaks) - 2)
    shifted = taylor_shift(own_coef[jj], breaks[:-1] - own_breaks[jj])
    return np.where(inside[:, None], shifted, 0.0)
