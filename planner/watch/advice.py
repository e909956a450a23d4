"""The next hook move: the least motion that brings every tension back into the plan's band.

At the estimated state (weight, CG, hook errors: :mod:`.estimate`) the plan's forward model
gives the tensions T0, the pose and their response G to each hook's move (t per m; the pose
free, as it is). The move m [m, + up] solves the small convex problem (cvxpy, Clarabel; built
once with parameters, each update only sets them)::

    minimise   sum m_i^2 + P sum(slack)
    subject to lo_i - s_lo_i <= T0_i + G_i m <= hi_i + s_hi_i
               |heel + dheel m| <= heel tolerance + s_h,  |trim + dtrim m| <= trim tolerance + s_t

with lo_i the rope's lowest planned tension (and at least the plan's minimum tension), hi_i
the lower of its highest planned tension and the tension at which its crane's design hook load
reaches the chart SWL (the rules' chain at the estimated weight,
:meth:`~liftplan.planner.plans.watch_basis.WatchBasis.design_chain`), each moved inside by
twice the predicted tension's standard deviation (at most a quarter of the band). With P
large the slacks are zero whenever a move exists; when they are not, no move can: the stop
signal is raised with the largest violation as its reason. The move is relinearised in the
forward model until its tensions are in the band (at most :data:`PASSES` passes). The stop
signal is also raised when the estimated CG is outside the plan's envelope by more than
:data:`CONFIDENCE` standard deviations (along an observed axis).
"""

from __future__ import annotations

from dataclasses import dataclass

import cvxpy as cp
import numpy as np

from liftplan.model.errors import EquilibriumNotFound
from liftplan.planner.watch.estimate import AXIS_WORDS

#: Weight of a tonne (or degree) of violation against a square centimetre of hook motion.
PENALTY = 1e4
#: Violation below this counts as none  [t or deg].
SLACK_TOL = 1e-3
#: Relinearisations of the move in the forward model.
PASSES = 4
#: A predicted tension this close outside its target band is in it  [t].
BAND_TOL = 1e-3

#: The CG is outside the envelope when it is more than this many sigma beyond it.
CONFIDENCE = 2.0


@dataclass(frozen=True)
class Advice:
    """The hook moves for one estimate, or the stop signal.

    Parameters
    ----------
    moves : numpy.ndarray (n,)  [m]
        Each hook's move, + up (zeros with ``stop``).
    tensions : numpy.ndarray (n,)  [t]
        The forward model's tensions after the moves, at the estimate.
    low, high : numpy.ndarray (n,)  [t]
        The band the moves aim into (margins included).
    design : numpy.ndarray (n,) or None  [t]
        Each crane's design hook load after the moves (None when the chain could not be built).
    stop : bool
    reason : str
    """

    moves: np.ndarray
    tensions: np.ndarray
    low: np.ndarray
    high: np.ndarray
    design: np.ndarray | None
    stop: bool
    reason: str


class Advisor:
    """The move problem of one plan, built once (cvxpy parameters)."""

    def __init__(self, basis, forward):
        self.basis, self.forward = basis, forward
        n = basis.n
        self.n = n
        self.t0 = cp.Parameter(n)
        self.gain = cp.Parameter((n, n))  # t per cm
        self.a0 = cp.Parameter(2)
        self.again = cp.Parameter((2, n))  # deg per cm
        self.low = cp.Parameter(n)
        self.high = cp.Parameter(n)
        self.move = cp.Variable(n)  # cm
        self.s_low = cp.Variable(n, nonneg=True)
        self.s_high = cp.Variable(n, nonneg=True)
        self.s_angle = cp.Variable(2, nonneg=True)
        tensions = self.t0 + self.gain @ self.move
        angles = self.a0 + self.again @ self.move
        limits = np.array([basis.heel_tolerance, basis.trim_tolerance])
        self.problem = cp.Problem(
            cp.Minimize(
                cp.sum_squares(self.move)
                + PENALTY * (cp.sum(self.s_low) + cp.sum(self.s_high) + cp.sum(self.s_angle))
            ),
            [
                tensions >= self.low - self.s_low,
                tensions <= self.high + self.s_high,
                cp.abs(angles) <= limits + self.s_angle,
            ],
        )
        assert self.problem.is_dcp(dpp=True)

    def advise(self, estimate):
        """The :class:`Advice` for an :class:`~.estimate.Estimate`."""
        basis, n = self.basis, self.n
        zeros = np.zeros(n)
        outside = self._cog_outside(estimate)
        if outside:
            return Advice(zeros, estimate.fitted, basis.band_low, basis.band_high, None, True, outside)
        chain = basis.design_chain(estimate.fitted, estimate.weight)
        low, high, design_limit = self._band(estimate, chain)
        total = np.zeros(n)
        state = estimate.raw.copy()
        for _ in range(PASSES):
            moved = state.copy()
            moved[4:] += total
            try:
                fs = self.forward.solve(moved)
            except EquilibriumNotFound as err:
                return Advice(
                    zeros,
                    estimate.fitted,
                    low,
                    high,
                    None,
                    True,
                    f"stop: the advised move loses the equilibrium ({err})",
                )
            if (
                np.all(fs.tensions >= low - BAND_TOL)
                and np.all(fs.tensions <= high + BAND_TOL)
                and (abs(fs.heel) <= basis.heel_tolerance and abs(fs.trim) <= basis.trim_tolerance)
            ):
                break
            self.t0.value = fs.tensions
            self.gain.value = fs.gain[:n, 4:] / 100.0
            self.a0.value = np.array([fs.heel, fs.trim])
            self.again.value = fs.gain[n:, 4:] / 100.0
            self.low.value, self.high.value = low, high
            self.problem.solve(solver=cp.CLARABEL)
            if self.problem.status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or self.move.value is None:
                return Advice(
                    zeros,
                    fs.tensions,
                    low,
                    high,
                    None,
                    True,
                    f"stop: the move problem was not solved ({self.problem.status})",
                )
            violation = self._overloaded(fs, estimate.weight) or self._violation(fs, low, high, design_limit)
            if violation:
                planned = basis.weight
                if abs(estimate.weight - planned) > 2.0 * estimate.sigma[0]:
                    violation += (
                        f"; the estimated weight {estimate.weight:.1f} t is "
                        f"{100.0 * (estimate.weight / planned - 1.0):+.1f} % from the planned {planned:.1f} t"
                    )
                return Advice(zeros, estimate.fitted, low, high, None, True, violation)
            total = total + self.move.value / 100.0
        else:
            return Advice(
                zeros,
                estimate.fitted,
                low,
                high,
                None,
                True,
                "stop: the advised move does not converge in the forward model",
            )
        design = None
        if not isinstance(chain, str):
            after = basis.design_chain(fs.tensions, estimate.weight)
            design = np.array([r.design_hook_load for r in after.results])
        return Advice(
            total, fs.tensions, low, high, design, False, self._words(estimate, total, low, high, chain)
        )

    def _cog_outside(self, estimate):
        basis = self.basis
        offset = estimate.cog - basis.cog
        for k in range(3):
            if estimate.reasons[1 + k]:
                continue
            sigma = estimate.sigma[1 + k]
            if abs(offset[k]) > basis.cog_tolerance[k] + CONFIDENCE * sigma:
                return (
                    f"stop: the estimated {AXIS_WORDS[k]} is {offset[k]:+.3f} m (sigma {sigma:.3f} m) "
                    f"from the planned CG, outside the plan's envelope (+-{basis.cog_tolerance[k]:g} m) "
                    f"by more than {CONFIDENCE:g} sigma"
                )
        return ""

    def _band(self, estimate, chain):
        """(low, high, design limit) [t] per rope: the target band, margins in."""
        basis, n = self.basis, self.n
        low = np.maximum(basis.band_low, basis.min_tension)
        design_limit = np.array(basis.swl, dtype=float)
        if not isinstance(chain, str):  # the tension at which each design hook load reaches the SWL
            here = np.array([r.design_hook_load for r in chain.results])
            step = np.maximum(estimate.fitted, 1.0)
            there = basis.design_chain(estimate.fitted + step, estimate.weight)
            slope = (np.array([r.design_hook_load for r in there.results]) - here) / step
            design_limit = estimate.fitted + (basis.swl - here) / np.maximum(slope, 1e-9)
        high = np.minimum(basis.band_high, design_limit)
        gain = estimate.gain[:n]
        spread = np.sqrt(np.maximum(np.einsum("ij,jk,ik->i", gain, estimate.covariance, gain), 0.0))
        margin = np.minimum(2.0 * spread, 0.25 * np.maximum(high - low, 0.0))
        return low + margin, high - margin, design_limit

    def _overloaded(self, fs, weight):
        """The stop reason when a crane's design hook load passes its SWL even after the least
        violating move (the move problem needed a slack), else ""."""
        if max(self.s_low.value.max(), self.s_high.value.max(), self.s_angle.value.max()) <= SLACK_TOL:
            return ""
        predicted = fs.tensions + self.gain.value @ self.move.value
        chain = self.basis.design_chain(predicted, weight)
        if isinstance(chain, str):
            return ""
        loads = np.array([r.design_hook_load for r in chain.results])
        over = loads - self.basis.swl
        if not np.any(over > 0.0):
            return ""
        k = int(np.argmax(over))
        return (
            f"stop: {self.basis.labels[k]} ({self.basis.cranes[k]}): its design hook load at the "
            f"estimated weight {weight:.1f} t is {loads[k]:.1f} t, over its SWL {self.basis.swl[k]:g} t, "
            "whatever the hooks do"
        )

    def _violation(self, fs, low, high, design_limit):
        """The stop reason when the move problem needed a slack, else ""."""
        labels, basis = self.basis.labels, self.basis
        s_low, s_high, s_angle = self.s_low.value, self.s_high.value, self.s_angle.value
        worst = max(s_low.max(), s_high.max(), s_angle.max())
        if worst <= SLACK_TOL:
            return ""
        if s_angle.max() >= max(s_low.max(), s_high.max()):
            k = int(np.argmax(s_angle))
            name, limit = ("heel", basis.heel_tolerance) if k == 0 else ("trim", basis.trim_tolerance)
            return (
                f"stop: no hook move keeps the {name} within the plan's +-{limit:g} deg with every "
                "tension in its band"
            )
        if s_low.max() >= s_high.max():
            k = int(np.argmax(s_low))
            return (
                f"stop: no hook move brings {labels[k]} ({basis.cranes[k]}) up to its band's "
                f"{low[k]:.1f} t (it stays {s_low[k]:.1f} t short) with the others in theirs"
            )
        k = int(np.argmax(s_high))
        if high[k] >= design_limit[k] - 1e-9:
            return (
                f"stop: {labels[k]} ({basis.cranes[k]}): its design hook load at the estimated weight "
                f"would exceed its SWL {basis.swl[k]:g} t (static tension {high[k] + s_high[k]:.1f} t "
                f"against {design_limit[k]:.1f} t allowed) whatever the hooks do"
            )
        return (
            f"stop: no hook move brings {labels[k]} ({basis.cranes[k]}) down into its band's "
            f"{high[k]:.1f} t (it stays {s_high[k]:.1f} t over) with the others in theirs"
        )

    def _words(self, estimate, moves, low, high, chain):
        labels = self.basis.labels
        tensions = estimate.fitted
        out = [
            f"{labels[k]} {'below' if tensions[k] < low[k] else 'above'} its band "
            f"({tensions[k]:.1f} t, band {low[k]:.1f} to {high[k]:.1f} t)"
            for k in range(self.n)
            if tensions[k] < low[k] - BAND_TOL or tensions[k] > high[k] + BAND_TOL
        ]
        if not np.any(np.abs(moves) > 0.0005):
            text = "every tension in its band: no move"
        else:
            biggest = int(np.argmax(np.abs(moves)))
            text = (
                ("; ".join(out) + ": " if out else "")
                + f"the moves bring every tension into its band (largest {labels[biggest]} "
                f"{moves[biggest] * 100:+.1f} cm)"
            )
        if isinstance(chain, str):
            text += f"; design loads not computed ({chain}): the band held against the chart SWL"
        return text
