"""One acceptance for every answer of a rope model, whichever method found it.

An equilibrium of the ``elastic``, ``inclined`` or ``rigging`` model is returned only when

* its statics residual is at most :data:`RESIDUAL_TOL` of the weight (forces) and of W L
  (moments, L the lugs' plan diameter);
* it is stable: the potential energy's Hessian in the solver's unknowns is positive
  definite. A saddle or a maximum of the energy also balances the forces, but the body
  leaves it at the smallest push (a CG high above soft ropes makes one);
* the body is the right way up: |heel| and |trim| below 90 deg.

Newton's answer, IPOPT's on the energy and IPOPT's polished by Newton are judged alike:
the energy fallback once returned a saddle because only Newton's answer was checked for
stability (issue 14, item 11).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Accepted residual as a fraction of W (force; moment over the lugs' plan diameter, or W L
#: for a hull in water), for every model: well above double-precision round-off (~1e-15 W;
#: ~1e-13 for the clipped-hull sums) and well below any physical meaning (1e-9 of 1000 t is
#: 1 g, of a 20 000 t barge 20 g).
RESIDUAL_TOL = 1e-9

# Smallest eigenvalue of the unit-diagonal Hessian taken as stiffness rather than round-off
# of a neutral direction (a free swivel, a slack sling): float64 leaves ~1e-15 there.
_NEUTRAL = 1e-12


@dataclass(frozen=True)
class Verdict:
    """How a candidate equilibrium fares against the acceptance.

    Parameters
    ----------
    residual : float  [-]
        Largest statics residual over W (moments over W L).
    stable : bool
        The energy Hessian is positive definite.
    heel, trim : float  [deg]
    """

    residual: float
    stable: bool
    heel: float
    trim: float

    @property
    def small(self):
        """The residual is within :data:`RESIDUAL_TOL` (NaN is not)."""
        return bool(self.residual <= RESIDUAL_TOL)

    @property
    def upright(self):
        """|heel| and |trim| below 90 deg (NaN is not)."""
        return bool(abs(self.heel) < 90.0 and abs(self.trim) < 90.0)

    @property
    def ok(self):
        """Every test passed: the answer may be returned."""
        return self.small and self.stable and self.upright

    def reason(self):
        """Why the answer is refused, as a clause for a one-line error ('' when accepted)."""
        where = f"heel {self.heel:.1f} deg, trim {self.trim:.1f} deg"
        if not self.small:
            return f"residual {self.residual:.3g} W above {RESIDUAL_TOL:g} W at {where}"
        if not self.upright:
            return f"the body turned over ({where})"
        if not self.stable:
            return (
                f"the equilibrium at {where} is unstable (energy Hessian not positive "
                "definite: the body would leave it at the smallest push)"
            )
        return ""


def judge(residual, heel, trim, *, minors=None, hessian=None):
    """The verdict on a candidate equilibrium.

    Parameters
    ----------
    residual : float  [-]
        Largest statics residual over W (and W L).
    heel, trim : float  [rad]
    minors : array_like, optional
        Leading principal minors of the energy Hessian (all > 0 <=> positive definite,
        Sylvester's criterion).
    hessian : array_like, optional
        The energy Hessian itself, when the minors are not at hand.

    Returns
    -------
    Verdict
    """
    residual = float(residual) if np.isfinite(residual) else math.inf
    if minors is not None:
        stable = bool(np.all(np.asarray(minors, dtype=float) > 0.0))
    else:
        stable = positive_definite(hessian)
    return Verdict(residual, stable, math.degrees(heel), math.degrees(trim))


def positive_definite(hessian):
    """Whether a symmetric matrix of mixed units (m, rad) is positive definite.

    Rows and columns are scaled to a unit diagonal first, so the test is one of signs and
    does not depend on units; a zero or negative diagonal entry (a free point with nothing
    taut on it) is not positive definite.
    """
    h = np.asarray(hessian, dtype=float)
    h = 0.5 * (h + h.T)
    diag = np.diag(h)
    if not (np.all(np.isfinite(h)) and np.all(diag > 0.0)):
        return False
    scale = 1.0 / np.sqrt(diag)
    return bool(np.min(np.linalg.eigvalsh(h * np.outer(scale, scale))) > _NEUTRAL)


def schur_positive_definite(matrix, npose):
    """Whether a symmetric matrix [[pose, coupling], [coupling^T, beam]] is positive definite,
    judged as a pose with a stiff elastic part (the flexible hull): the beam block by Cholesky,
    then its Schur complement on the first ``npose`` unknowns by :func:`positive_definite`
    (scaled to a unit diagonal, so the pose's mixed units do not matter)."""
    k = np.asarray(matrix, dtype=float)
    k = 0.5 * (k + k.T)
    if not np.all(np.isfinite(k)):
        return False
    pose, beam, coupling = k[:npose, :npose], k[npose:, npose:], k[:npose, npose:]
    try:
        factor = np.linalg.cholesky(beam)
    except np.linalg.LinAlgError:
        return False
    half = np.linalg.solve(factor, coupling.T)
    return positive_definite(pose - half.T @ half)
