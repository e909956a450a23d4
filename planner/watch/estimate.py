"""What the readings say: the weight, the CG and the hook errors that best explain them.

Weighted least squares on the plan's own forward model (:mod:`.forward`): the state
``theta = [W, x_c, y_c, z_c, e_1 .. e_n]`` minimising::

    sum ((y_k - f_k(theta)) / sigma_k)^2 + sum ((theta_j - theta0_j) / s_j)^2

over the readings y (each load cell's tension, the inclinometer's heel and trim, measured
hook heights), sigma_k each reading's accuracy (``[readings]``), with the plan's own state
theta0 (planned weight and CG, no hook error) as a prior of scale s: W / 20, the CG
envelope's half-widths, each hook's tolerance (at least 1 % of the lugs' plan diameter and
1 cm). Gauss-Newton from the last estimate. The prior is what keeps a direction the readings
do not see at the plan's value instead of a guess, and what makes the uncertainty of a
quantity that the readings see only together with such a direction honest (the CG across the
hull and an unread tilt of the hooks, without an inclinometer): the covariance is
(J^T Sigma^-1 J + S^-2)^-1 at the estimate.

Observability: the weighted, scaled Jacobian's singular directions whose singular value is
below :data:`RESOLVE` (a change of one prior scale moves the readings by less than a tenth of
their accuracy) are what the readings cannot tell apart: said in words
(:attr:`Estimate.directions`), and every quantity with a part along them is reported
unobservable (None in JSON, with its reason) instead of a number.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.planner.plans.watch_basis import WatchBasis, watch_basis
from liftplan.planner.watch.forward import Forward

#: A direction is observed when a change of one scale unit moves the readings by at least this
#: many standard deviations (root of the sum of squares).
RESOLVE = 0.1
#: A quantity whose unit vector has at least this much along an unobserved direction is unobservable.
ALONG = 1e-2
#: Gauss-Newton: at most this many steps; converged when the scaled step is below STEP_TOL.
MAX_STEPS = 30
STEP_TOL = 1e-9

#: The CG's axes in words (body frame, whatever the file's frame).
AXIS_WORDS = ("CG x (forward)", "CG y (to port)", "CG height")


@dataclass(frozen=True)
class Estimate:
    """The state that best explains one reading.

    Parameters
    ----------
    time : float  [s]
    labels : tuple of str
    state : numpy.ndarray (4 + n,)
        W [t], the CG (body frame, ``z-up``) [m], each hook's height error [m] (+ up). Where
        unobservable, the value the fit kept (the start's), which no output shows as a result.
    sigma : numpy.ndarray (4 + n,)
        One standard deviation of each; NaN where unobservable.
    reasons : tuple of str
        Per quantity: why it is unobservable, "" where it is observed.
    directions : tuple of str
        What the readings cannot tell apart, one sentence per direction.
    covariance : numpy.ndarray (4 + n, 4 + n)
        Of the observed part (zero along the unobserved directions).
    heel, trim, lift : float  [deg, deg, m]
        The fitted pose.
    fitted : numpy.ndarray (n,)  [t]
        The model's tensions at the estimate.
    chi2 : float  [-]
        Weighted sum of squared residuals; ``dof`` readings less observed directions.
    dof : int
    steps : int
        Gauss-Newton steps taken.
    gain : numpy.ndarray (n + 2, 4 + n)
        d(T, heel, trim)/d(state) at the estimate (:class:`~.forward.ForwardState`).
    relative : bool
        True when the hooks' common error is unobserved: the hook errors in ``state`` are then
        about their mean (their mean is 0), and ``covariance`` is of those.
    raw : numpy.ndarray (4 + n,)
        The fitted state itself (the model's state; hook errors not shifted): where the next
        fit starts and where hook moves are planned from.
    """

    time: float
    labels: tuple
    state: np.ndarray
    sigma: np.ndarray
    reasons: tuple
    directions: tuple
    covariance: np.ndarray
    heel: float
    trim: float
    lift: float
    fitted: np.ndarray
    chi2: float
    dof: int
    steps: int
    gain: np.ndarray
    relative: bool = False
    raw: np.ndarray | None = None

    @property
    def observable(self):
        return np.array([not r for r in self.reasons])

    @property
    def weight(self):
        return float(self.state[0])

    @property
    def cog(self):
        return self.state[1:4]

    @property
    def hook_errors(self):
        return self.state[4:]


def quantity_names(labels):
    """Names of the state's entries, in words."""
    return ["the weight", *AXIS_WORDS] + [f"hook {label}" for label in labels]


class Estimator:
    """Weighted least squares of one plan's readings (the model built once)."""

    def __init__(self, basis, forward=None):
        self.basis = basis
        self.forward = forward if forward is not None else Forward(basis)
        n = basis.n
        length = basis.plan_diameter
        cog_scale = np.maximum(basis.cog_tolerance, 0.01 * length)
        hook_scale = np.maximum(basis.hook_tolerance, 0.01)
        self.scale = np.concatenate([[0.05 * basis.weight], cog_scale, hook_scale])
        self.names = quantity_names(basis.labels)
        self.n = n

    def _observe(self, reading, state):
        """Readings and model at ``state``: (residual / sigma, Jacobian / sigma, ForwardState)."""
        n, accuracy = self.n, self.basis.accuracy
        fs = self.forward.solve(state)
        rows = [fs.gain[:n]]
        y = [reading.tensions]
        f = [fs.tensions]
        sigma = [np.full(n, accuracy.load_cell)]
        if reading.has_angles:
            rows.append(fs.gain[n:])
            y.append([reading.heel, reading.trim])
            f.append([fs.heel, fs.trim])
            sigma.append(np.full(2, accuracy.inclinometer))
        mask = reading.hook_mask
        if mask.any():
            jac = np.zeros((int(mask.sum()), 4 + n))
            jac[:, 4:][np.arange(int(mask.sum())), np.flatnonzero(mask)] = 1.0
            rows.append(jac)
            y.append(reading.hooks[mask])
            f.append((self.basis.boom_height + state[4:])[mask])
            sigma.append(np.full(int(mask.sum()), accuracy.hook))
        sigma = np.concatenate(sigma)
        residual = (np.concatenate(y) - np.concatenate(f)) / sigma
        jacobian = np.vstack(rows) * self.scale[None, :] / sigma[:, None]
        return residual, jacobian, fs

    def estimate(self, reading, start=None):
        """The :class:`Estimate` of one (unflagged) reading, from ``start`` (a state; default
        the plan's nominal one).

        Raises
        ------
        EquilibriumNotFound
            When the fit leaves the states the ropes can hold, or does not converge.
        """
        prior = self.forward.nominal
        state = np.array(prior if start is None else start, dtype=float)

        def fit(state):
            residual, jacobian, fs = self._observe(reading, state)
            # the plan's own state as a prior of one scale unit: what no reading sees stays there
            full = np.concatenate([residual, (prior - state) / self.scale])
            return full, np.vstack([jacobian, np.eye(state.size)]), residual, jacobian, fs

        current = fit(state)
        steps, size, step = 0, 1.0, np.zeros(state.size)
        while steps < MAX_STEPS:
            steps += 1
            step = np.linalg.lstsq(current[1], current[0], rcond=None)[0]
            cost = current[0] @ current[0]
            size = 1.0
            while True:  # backtrack while the model cannot hold the body or the fit worsens
                trial = state + size * self.scale * step
                try:
                    candidate = fit(trial)
                except EquilibriumNotFound:
                    candidate = None
                if candidate is not None and candidate[0] @ candidate[0] <= cost * (1 + 1e-12) + 1e-18:
                    break
                size *= 0.5
                if size < 1e-4:
                    if np.max(np.abs(step)) < 1e-6:  # at the minimum already
                        candidate, trial = current, state
                        break
                    raise EquilibriumNotFound(
                        f"line {reading.line}: the fit of the readings found no state the ropes can "
                        "hold that explains them better"
                    )
            state, current = trial, candidate
            if np.max(np.abs(size * step)) < STEP_TOL:
                break
        if np.max(np.abs(size * step)) >= STEP_TOL:
            raise EquilibriumNotFound(
                f"line {reading.line}: the fit of the readings did not converge in {MAX_STEPS} steps"
            )
        _, _, residual, jacobian, fs = current
        return self._result(reading, state, residual, jacobian, fs, steps)

    def _result(self, reading, state, residual, jacobian, fs, steps):
        _, singular, vt = np.linalg.svd(jacobian, full_matrices=True)
        values = np.zeros(vt.shape[0])
        values[: singular.size] = singular
        seen = values >= RESOLVE
        null = vt[~seen]
        heave, relative = self._heave(null)
        # what is reported: the state, its hook errors about their mean when a common error is unseen
        report = np.eye(state.size)
        if relative:
            report[4:, 4:] -= 1.0 / self.n
        covariance_scaled = np.linalg.inv(jacobian.T @ jacobian + np.eye(state.size))
        covariance = report @ (covariance_scaled * np.outer(self.scale, self.scale)) @ report.T
        directions = self._directions(null, heave, reading)
        rows = report * self.scale[None, :]  # each reported quantity in scaled units
        rows /= np.linalg.norm(rows, axis=1)[:, None]
        along = np.linalg.norm(rows @ null.T, axis=1) if null.size else np.zeros(state.size)
        reasons = []
        for k, name in enumerate(self.names):
            if along[k] < ALONG:
                reasons.append("")
            else:
                which = [d for d, v in directions if np.linalg.norm(rows[k] @ v.T) >= ALONG]
                reasons.append(f"{name} is not observable from these readings: " + "; ".join(which))
        sigma = np.sqrt(np.maximum(np.diag(covariance), 0.0))
        sigma[along >= ALONG] = np.nan
        return Estimate(
            time=reading.time,
            labels=tuple(self.basis.labels),
            state=report @ state,
            sigma=sigma,
            reasons=tuple(reasons),
            directions=tuple(d for d, _ in directions),
            covariance=covariance,
            heel=fs.heel,
            trim=fs.trim,
            lift=fs.lift,
            fitted=fs.tensions,
            chi2=float(residual @ residual),
            dof=int(residual.size - seen.sum()),
            steps=steps,
            gain=fs.gain,
            relative=relative,
            raw=state,
        )

    def _heave(self, null):
        """The hooks' common error (a unit row, scaled units) and whether it is unobserved."""
        heave = np.concatenate([np.zeros(4), 1.0 / self.scale[4:]])
        heave /= np.linalg.norm(heave)
        return heave, bool(null.size) and np.linalg.norm(null @ heave) > 1.0 - 1e-6

    def _directions(self, null, heave, reading):
        """The unobserved directions as (sentence, rows spanning them in scaled units): the
        hooks' common error first when it is one of them, then the rest as one sentence."""
        if not null.size:
            return []
        out = []
        rest = null
        if np.linalg.norm(null @ heave) > 1.0 - 1e-6:
            seen = (
                "no hook height is read" if not reading.hook_mask.any() else "too few hook heights are read"
            )
            out.append(
                (
                    "all hooks up or down together only moves the lift height, which no reading "
                    f"sees ({seen}): hook errors are given about their mean",
                    heave[None, :],
                )
            )
            projected = null - np.outer(null @ heave, heave)
            u, s, _ = np.linalg.svd(projected.T, full_matrices=False)
            rest = u[:, s > 1e-6].T
        if rest.size:
            out.append((self._sentence(rest, reading), rest))
        return out

    def _sentence(self, rest, reading):
        """What a set of unobserved directions (rows, scaled units) mixes, in words."""
        why = "" if reading.has_angles else " (no inclinometer reading)"
        if rest.shape[0] == 1:
            v = rest[0]
            physical = v * self.scale
            units = ["t"] + ["m"] * (3 + self.n)
            lead = int(np.flatnonzero(np.abs(v) >= 0.25 * np.max(np.abs(v)))[0])
            unit_step = physical / physical[lead]
            parts = [
                f"{self.names[k]} {'+' if unit_step[k] >= 0 else '-'}{abs(unit_step[k]):.3g} {units[k]}"
                for k in np.flatnonzero(np.abs(v) >= 0.05 * np.max(np.abs(v)))
            ]
            if len(parts) == 1:
                k = int(np.argmax(np.abs(v)))
                hint = " (a CG height acts on the ropes only through a tilt of the body)" if k == 3 else ""
                return f"a change of {self.names[k]} alone leaves every reading the same{hint}{why}"
            return f"{', '.join(parts)} together leave every reading the same{why}"
        weight = np.linalg.norm(rest, axis=0)
        names = [self.names[k] for k in np.flatnonzero(weight >= 0.05 * weight.max())]
        return f"{rest.shape[0]} independent changes of {', '.join(names)} leave every reading the same{why}"


def as_basis(plan):
    """A :class:`WatchBasis` from itself or from a plan (:func:`watch_basis`)."""
    return plan if isinstance(plan, WatchBasis) else watch_basis(plan)


def estimate(plan, reading):
    """The weight, CG and hook errors that best explain one reading (:class:`Estimate`).

    Parameters
    ----------
    plan : Plan or WatchBasis
    reading : Reading

    Raises
    ------
    InvalidScene
        For a flagged reading (its flag is the message).
    EquilibriumNotFound
        When no state the ropes can hold explains it.
    """
    if reading.flag is not None:
        raise InvalidScene(reading.flag)
    return Estimator(as_basis(plan)).estimate(reading)
