"""A synthetic lift with a known truth: what ``liftplan simulate`` writes.

One seeded draw of the lift's errors (a weight error, a CG offset, each hook's height
error), then along the lift each hook's error drifts (a random walk of ``drift`` m per
square-root second: the hoists not quite in step); at every time the plan's
forward model (:mod:`.forward`) gives the tensions and the pose, and each reading gets the
sensor's noise (normal, its standard deviation). The truth is kept beside the readings.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.planner.watch.forward import Forward
from liftplan.planner.watch.readings import HOOK_PREFIX, Reading


@dataclass(frozen=True)
class Errors:
    """Standard deviations of the drawn errors.

    Parameters
    ----------
    hook : float  [m]   each hook's height error
    cog : float or sequence of 3 float  [m]    each CG coordinate's offset (x, y, z; body frame,
        ``z-up``)
    weight : float  [-] the weight error, a fraction of the planned weight
    """

    hook: float = 0.02
    cog: float | tuple = 0.1
    weight: float = 0.02


@dataclass(frozen=True)
class Noise:
    """Standard deviations of the sensors' noise.

    Parameters
    ----------
    load_cell : float  [t]
    inclinometer : float  [deg]
    hook : float  [m]
    """

    load_cell: float = 1.0
    inclinometer: float = 0.05
    hook: float = 0.01


@dataclass(frozen=True)
class SimulatedLift:
    """Readings and the truth behind each.

    Parameters
    ----------
    readings : tuple of Reading
    states : numpy.ndarray (m, 4 + n)
        The true state at each reading: W [t], the CG [m] (body frame, ``z-up``), hook errors [m].
    heel, trim : numpy.ndarray (m,)  [deg]   the true pose
    tensions : numpy.ndarray (m, n)  [t]   the true tensions
    """

    readings: tuple
    states: np.ndarray
    heel: np.ndarray
    trim: np.ndarray
    tensions: np.ndarray


def simulate(
    basis,
    errors=Errors(),
    noise=Noise(),
    seed=0,
    steps=60,
    rate=1.0,
    drift=0.0,
    inclinometer=True,
    hooks=False,
    forward=None,
):
    """A seeded synthetic lift of a plan (:class:`SimulatedLift`).

    Parameters
    ----------
    basis : WatchBasis
    errors : Errors
    noise : Noise
    seed : int
    steps : int   readings
    rate : float  [Hz]   readings per second
    drift : float  [m / s^0.5]   each hook's error's random walk
    inclinometer : bool   write heel and trim
    hooks : bool   write each hook's measured height
    """
    for name, value in (("steps", steps), ("rate", rate)):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
            raise InvalidScene(f"--{name} {value!r}: expected a number > 0")
    for name, value in (
        ("errors.hook", errors.hook),
        ("errors.cog", float(np.min(errors.cog))),
        ("errors.weight", errors.weight),
        ("noise.load_cell", noise.load_cell),
        ("noise.inclinometer", noise.inclinometer),
        ("noise.hook", noise.hook),
        ("drift", drift),
    ):
        if not (math.isfinite(value) and value >= 0):
            raise InvalidScene(f"{name} = {value!r}: expected a standard deviation or speed >= 0")
    rng = np.random.default_rng(seed)
    forward = forward if forward is not None else Forward(basis)
    n = basis.n
    state = forward.nominal
    state[0] *= 1.0 + errors.weight * rng.standard_normal()
    state[1:4] += np.asarray(errors.cog, dtype=float) * rng.standard_normal(3)
    state[4:] += errors.hook * rng.standard_normal(n)
    dt = 1.0 / rate
    readings, states, heel, trim, tensions = [], [], [], [], []
    for k in range(int(steps)):
        if k:
            state = state.copy()
            state[4:] += drift * math.sqrt(dt) * rng.standard_normal(n)
        fs = forward.solve(state)
        measured = fs.tensions + noise.load_cell * rng.standard_normal(n)
        angles = (fs.heel, fs.trim) + noise.inclinometer * rng.standard_normal(2)
        heights = basis.boom_height + state[4:] + noise.hook * rng.standard_normal(n)
        readings.append(
            Reading(
                line=k + 2,
                time=k * dt,
                tensions=np.maximum(measured, 0.0),
                heel=float(angles[0]) if inclinometer else None,
                trim=float(angles[1]) if inclinometer else None,
                hooks=heights if hooks else None,
            )
        )
        states.append(state)
        heel.append(fs.heel)
        trim.append(fs.trim)
        tensions.append(fs.tensions)
    return SimulatedLift(
        tuple(readings), np.array(states), np.array(heel), np.array(trim), np.array(tensions)
    )


def write_csv(basis, lift, handle):
    """Write a simulated lift's readings as a readings CSV (the plan's labels as columns)."""
    first = lift.readings[0]
    header = ["time", *basis.labels]
    if first.has_angles:
        header += ["heel", "trim"]
    if first.hooks is not None:
        header += [f"{HOOK_PREFIX}{label}" for label in basis.labels]
    writer = csv.writer(handle, lineterminator="\n")
    writer.writerow(header)
    for r in lift.readings:
        row = [f"{r.time:.3f}", *(f"{t:.3f}" for t in r.tensions)]
        if r.has_angles:
            row += [f"{r.heel:.4f}", f"{r.trim:.4f}"]
        if r.hooks is not None:
            row += [f"{h:.4f}" for h in r.hooks]
        writer.writerow(row)


def truth_json(basis, lift):
    """The truth behind each reading, as JSON (coordinates ``z-up``, body frame)."""
    return {
        "coordinates": "z-up",
        "labels": list(basis.labels),
        "rows": [
            {
                "time": r.time,
                "weight": float(s[0]),
                "cog": s[1:4].tolist(),
                "hook_errors": dict(zip(basis.labels, s[4:].tolist())),
                "heel": float(h),
                "trim": float(t),
                "tensions": dict(zip(basis.labels, ts.tolist())),
            }
            for r, s, h, t, ts in zip(lift.readings, lift.states, lift.heel, lift.trim, lift.tensions)
        ],
    }
