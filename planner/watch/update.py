"""One update of a watched lift: a reading, its estimate and the advice (the API).

:class:`Watcher` holds one plan's forward model, estimator and move problem (each built once)
and turns readings into :class:`Update` objects, each fit starting from the last estimate;
:func:`~.estimate.estimate` and :func:`advise` are the one-reading forms.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import EquilibriumNotFound
from liftplan.planner.plans.watch_basis import WatchBasis
from liftplan.planner.watch.advice import Advice, Advisor
from liftplan.planner.watch.estimate import Estimate, Estimator, as_basis
from liftplan.planner.watch.forward import Forward
from liftplan.planner.watch.readings import Reading


@dataclass(frozen=True)
class Update:
    """What one reading gives: its estimate and advice, or why it gives nothing.

    Parameters
    ----------
    reading : Reading
    estimate : Estimate or None
        None for a flagged reading or a fit that failed.
    advice : Advice or None
    reason : str
        The stop reason, the flag, or the advice in words.
    """

    basis: WatchBasis
    reading: Reading
    estimate: Estimate | None
    advice: Advice | None
    reason: str

    @property
    def stop(self):
        return self.advice is None or self.advice.stop

    @property
    def flagged(self):
        return self.estimate is None

    def to_json(self):
        """One JSON Lines object (CONTRACT keys first; coordinates in the plan file's frame)."""
        basis, e, a = self.basis, self.estimate, self.advice
        labels = basis.labels
        frame = basis.frame
        time = self.reading.time if np.isfinite(self.reading.time) else None
        out = {"time": time}
        if e is None:
            out.update(
                weight=None,
                weight_sigma=None,
                cog=[None] * 3,
                cog_sigma=[None] * 3,
                hook_errors=dict.fromkeys(labels),
                advice=dict.fromkeys(labels, 0.0),
                stop=True,
                reason=self.reason,
                flagged=True,
                line=self.reading.line,
            )
            return out
        cog, cog_sigma, unobservable = file_frame(e, frame)
        hook = {
            label: (None if e.reasons[4 + k] else float(e.state[4 + k])) for k, label in enumerate(labels)
        }
        for k, label in enumerate(labels):
            if e.reasons[4 + k]:
                unobservable[f"hook_errors.{label}"] = e.reasons[4 + k]
        out.update(
            weight=None if e.reasons[0] else e.weight,
            weight_sigma=None if e.reasons[0] else float(e.sigma[0]),
            cog=cog,
            cog_sigma=cog_sigma,
            hook_errors=hook,
            advice=dict(zip(labels, a.moves.tolist())),
            stop=bool(a.stop),
            reason=self.reason,
            flagged=False,
            line=self.reading.line,
            frame=frame,
            hook_errors_sigma={
                label: (None if e.reasons[4 + k] else float(e.sigma[4 + k])) for k, label in enumerate(labels)
            },
            hook_errors_about_mean=bool(e.relative),
            unobservable=unobservable,
            directions=list(e.directions),
            heel=e.heel,
            trim=e.trim,
            tensions=dict(zip(labels, self.reading.tensions.tolist())),
            fitted=dict(zip(labels, e.fitted.tolist())),
            after_advice=dict(zip(labels, a.tensions.tolist())),
            band={label: [float(lo), float(hi)] for label, lo, hi in zip(labels, a.low, a.high)},
            design_hook_loads=None if a.design is None else dict(zip(labels, a.design.tolist())),
            chi2=e.chi2,
            dof=e.dof,
        )
        return out


def file_frame(e, frame):
    """The CG and its sigma in the file's frame (None where unobservable) and the reasons."""
    value = [None if e.reasons[1 + k] else float(e.cog[k]) for k in range(3)]
    sigma = [None if e.reasons[1 + k] else float(e.sigma[1 + k]) for k in range(3)]
    reasons = [e.reasons[1 + k] for k in range(3)]
    if frame == "choi":  # z-up (x, y, z) is choi (x, z, -y): a permutation with one sign
        order = (0, 2, 1)
        value = [value[0], value[2], None if value[1] is None else -value[1]]
        sigma = [sigma[k] for k in order]
        reasons = [reasons[k] for k in order]
    unobservable = {f"cog.{axis}": r for axis, r in zip("xyz", reasons) if r}
    return value, sigma, unobservable


class Watcher:
    """Readings to estimates and advice for one plan (a :class:`WatchBasis`, or a plan)."""

    def __init__(self, plan):
        self.basis = as_basis(plan)
        self.forward = Forward(self.basis)
        self.estimator = Estimator(self.basis, self.forward)
        self.advisor = Advisor(self.basis, self.forward)
        self.last = None

    def update(self, reading):
        """The :class:`Update` of one reading (a flagged one gives its flag and a stop)."""
        if reading.flag is not None:
            return Update(self.basis, reading, None, None, f"flagged: {reading.flag}")
        try:
            estimate = self.estimator.estimate(reading, start=self.last)
        except EquilibriumNotFound as err:
            return Update(self.basis, reading, None, None, f"flagged: {err}")
        self.last = estimate.raw
        advice = self.advisor.advise(estimate)
        return Update(self.basis, reading, estimate, advice, advice.reason)


def advise(plan, estimate):
    """The hook moves (or the stop signal) for an :class:`Estimate` (:class:`Advice`)."""
    basis = as_basis(plan)
    return Advisor(basis, Forward(basis)).advise(estimate)
