"""The watch's advice: applied to the true lift in the forward model, the moves bring every
tension into the plan's band, or the stop signal is raised with its reason (seeded cases)."""

import dataclasses

import numpy as np
from support.watching import tanker_basis

from liftplan.planner.watch.forward import Forward
from liftplan.planner.watch.simulate import Errors, Noise, simulate
from liftplan.planner.watch.update import Watcher

CASES = 40
#: Hook errors well past the plan's 0.02 m tolerance, so that most cases need a move.
ERRORS = Errors(hook=0.06, cog=(0.3, 0.15, 0.1), weight=0.03)
NOISE = Noise(load_cell=0.3, inclinometer=0.02)


def _apply(basis, forward, truth, moves):
    moved = truth.copy()
    moved[4:] += moves
    return forward.solve(moved)


def test_moves_bring_every_tension_into_the_band_or_stop():
    basis = tanker_basis()
    forward = Forward(basis)
    low = np.maximum(basis.band_low, basis.min_tension)
    moved = stopped = 0
    for seed in range(CASES):
        lift = simulate(basis, ERRORS, NOISE, seed=seed, steps=1, forward=forward)
        update = Watcher(basis).update(lift.readings[0])
        if update.stop:
            # in this set every stop is the CG: and the true CG is outside the envelope there
            assert "outside the plan's envelope" in update.reason, update.reason
            offset = np.abs(lift.states[0][1:4] - basis.cog)
            assert np.any(offset > basis.cog_tolerance), (seed, offset)
            stopped += 1
            continue
        after = _apply(basis, forward, lift.states[0], update.advice.moves)
        assert np.all(after.tensions >= low - 1e-6) and np.all(after.tensions <= basis.band_high + 1e-6), seed
        assert abs(after.heel) <= basis.heel_tolerance and abs(after.trim) <= basis.trim_tolerance
        out_before = np.any(lift.tensions[0] < low) or np.any(lift.tensions[0] > basis.band_high)
        moved += bool(np.any(update.advice.moves != 0.0)) and out_before
    assert moved >= CASES // 2  # most cases were out of band and brought back
    assert 0 < stopped < CASES // 4


def test_in_band_means_no_move():
    basis = tanker_basis()
    lift = simulate(basis, Errors(hook=0.0, cog=0.0, weight=0.0), NOISE, seed=1, steps=1)
    update = Watcher(basis).update(lift.readings[0])
    assert not update.stop
    np.testing.assert_array_equal(update.advice.moves, 0.0)
    assert update.reason == "every tension in its band: no move"


def test_overweight_stops_on_the_design_load():
    # 60 % heavier than planned: the rules' design hook load passes a crane's SWL whatever the hooks do
    basis = tanker_basis()
    lift = simulate(basis, Errors(hook=0.0, cog=0.0, weight=0.0), NOISE, seed=2, steps=1)
    heavy = dataclasses.replace(lift.readings[0], tensions=lift.readings[0].tensions * 1.6)
    update = Watcher(basis).update(heavy)
    assert update.stop
    assert "design hook load" in update.reason and "SWL" in update.reason
    np.testing.assert_array_equal(update.advice.moves, 0.0)


def test_cg_outside_the_envelope_stops():
    basis = tanker_basis()
    truth_errors = Errors(hook=0.0, cog=0.0, weight=0.0)
    forward = Forward(basis)
    lift = simulate(basis, truth_errors, NOISE, seed=3, steps=1, forward=forward)
    state = lift.states[0].copy()
    state[1] += 1.5  # 1.5 m forward of the planned CG: the envelope is +-0.5 m
    fs = forward.solve(state)
    reading = dataclasses.replace(lift.readings[0], tensions=fs.tensions, heel=fs.heel, trim=fs.trim)
    update = Watcher(basis).update(reading)
    assert update.stop
    assert "CG x (forward)" in update.reason and "envelope" in update.reason
