"""The watch's estimate against a known truth (seeded synthetic lifts of the tanker plan).

Each case draws a weight error, a CG offset and hook errors, solves the plan's forward model
and adds sensor noise (``simulate``, seeds 0..199, not chosen); every quantity the estimate
reports must hold the truth inside its 2-sigma interval in 200 cases as a calibrated estimate
does, and the ones the readings cannot see must be reported unobservable (no number), with
the reason.

What "as a calibrated estimate does" means: a normal error falls inside +-2 sigma with
probability 95.45 %, so over 200 cases the count inside is 190.9 +- 2.9 (binomial): a perfect
estimate has about one chance in three to show fewer than 190 (95 %) on a given set of seeds.
The test therefore asks what holds for a calibrated estimate with no more than a 0.2 %
chance of failing: each quantity's count inside 2 sigma at least 182 of 200 (91 %, 3 binomial
standard deviations under 95.45 %), and its mean squared normalised error (e / sigma)^2
between 0.75 and 1.3 (its 200-case spread is +-0.1): sigmas neither too small nor too large.
On these seeds the fractions are 93.5 to 98.5 % (the CG x at 93.5 % in every configuration:
187 of 200) and the mean squares 0.90 to 1.20; over 1000 cases (``test_watch_coverage_1000``)
94.8 to 96.5 % and 0.93 to 1.03. The truth is drawn as the plan expects it (the prior the
estimate uses): a truth drawn wider than the plan's tolerances is covered less where the
readings see a quantity only together with an unread one.
"""

import dataclasses

import numpy as np
import pytest
from support.watching import tanker_basis, tanker_plan

from liftplan.planner.problem.readings_accuracy import ReadingsAccuracy
from liftplan.planner.watch import estimate
from liftplan.planner.watch.estimate import Estimator
from liftplan.planner.watch.forward import Forward
from liftplan.planner.watch.simulate import Errors, Noise, simulate

CASES = 200
# the truth drawn as the plan expects it (its prior): each hook within its tolerance (0.02 m, one
# sigma), the CG within its envelope's half-widths, the weight within 5 %
ERRORS = Errors(hook=0.02, cog=(0.5, 0.3, 0.2), weight=0.05)
NOISE = Noise(load_cell=1.0, inclinometer=0.05, hook=0.01)


def _coverage(inclinometer, hooks, cases=CASES):
    basis = tanker_basis()
    forward = Forward(basis)
    estimator = Estimator(basis, forward)
    inside = np.zeros(4 + basis.n)
    reported = np.zeros(4 + basis.n)
    squares = np.zeros(4 + basis.n)
    reasons = set()
    for seed in range(cases):
        lift = simulate(
            basis, ERRORS, NOISE, seed=seed, steps=1, inclinometer=inclinometer, hooks=hooks, forward=forward
        )
        truth = lift.states[0].copy()
        e = estimator.estimate(lift.readings[0])
        if e.relative:  # hook errors about their mean: so is the truth they are compared with
            truth[4:] -= truth[4:].mean()
        seen = e.observable
        reported += seen
        z = np.where(seen, (e.state - truth) / np.where(seen, e.sigma, 1.0), 0.0)
        inside += seen & (np.abs(z) <= 2.0)
        squares += z**2
        reasons.update(r for r in e.reasons if r)
    seen = reported > 0
    return inside[seen] / cases, squares[seen] / cases, reported, reasons


def _calibrated(fraction, squares, least=0.91):
    assert np.all(fraction >= least), fraction
    assert np.all((squares >= 0.75) & (squares <= 1.3)), squares


def test_inclinometer_coverage_and_unobservable_height():
    fraction, squares, reported, reasons = _coverage(inclinometer=True, hooks=False)
    # weight, CG x, CG y and the four hook errors (about their mean) are seen in every case
    assert reported.tolist() == [CASES] * 3 + [0] + [CASES] * 4
    _calibrated(fraction, squares)
    # the tanker hangs level: its CG height acts only through a tilt, which the readings do not show
    assert any(r.startswith("CG height is not observable") for r in reasons)


def test_no_inclinometer_height_and_hooks_unobservable():
    fraction, squares, reported, reasons = _coverage(inclinometer=False, hooks=False)
    # four load cells: the weight and the CG in plan; the CG height and the hooks trade off
    assert reported.tolist() == [CASES] * 3 + [0] * 5
    _calibrated(fraction, squares)
    assert any("no inclinometer reading" in r for r in reasons)


def test_hook_heights_make_every_hook_observable():
    fraction, squares, reported, _ = _coverage(inclinometer=True, hooks=True)
    assert reported.tolist() == [CASES] * 3 + [0] + [CASES] * 4
    _calibrated(fraction, squares)


@pytest.mark.slow
def test_watch_coverage_1000():
    # 1000 cases: 95.45 +- 0.66 % inside 2 sigma for a calibrated estimate, mean square 1 +- 0.045
    fraction, squares, _, _ = _coverage(inclinometer=True, hooks=False, cases=1000)
    _calibrated(fraction, squares, least=0.935)
    assert np.all((squares >= 0.85) & (squares <= 1.15)), squares


def test_unobservable_is_not_guessed_in_json():
    basis = tanker_basis()
    from liftplan.planner.watch.update import Watcher

    lift = simulate(basis, ERRORS, NOISE, seed=7, steps=1, inclinometer=False)
    out = Watcher(basis).update(lift.readings[0]).to_json()
    # choi frame: the CG height is the file's y
    assert basis.frame == "choi"
    assert out["cog"][1] is None and out["cog_sigma"][1] is None
    assert "not observable" in out["unobservable"]["cog.y"]
    assert all(v is None for v in out["hook_errors"].values())
    assert out["weight"] is not None and out["weight_sigma"] > 0


def test_estimate_api_from_the_plan_itself():
    # the plan's [readings] accuracies weigh the fit: 1 t a load cell, so the weight to 2 t
    basis = tanker_basis()
    lift = simulate(basis, ERRORS, NOISE, seed=3, steps=1)
    e = estimate(tanker_plan(), lift.readings[0])
    assert abs(e.weight - lift.states[0][0]) <= 2.0 * e.sigma[0]
    np.testing.assert_allclose(e.sigma[0], 2.0, rtol=0.01)  # four cells of 1 t: sqrt(4) t


def test_precise_readings_pin_the_weight_and_cg():
    basis = dataclasses.replace(tanker_basis(), accuracy=ReadingsAccuracy(load_cell=1e-3, inclinometer=1e-4))
    lift = simulate(basis, ERRORS, Noise(load_cell=1e-3, inclinometer=1e-4), seed=3, steps=1)
    e = estimate(basis, lift.readings[0])
    # sum T = W for vertical ropes: the weight to the four cells' 2e-3 t (4 sigma here)
    np.testing.assert_allclose(e.weight, lift.states[0][0], rtol=0, atol=8e-3)
    np.testing.assert_allclose(e.cog[:2], lift.states[0][1:3], rtol=0, atol=4 * e.sigma[1:3].max())


@pytest.mark.parametrize("key", ["band_low", "band_high", "EA", "boom_height"])
def test_basis_round_trips_through_json(key):
    from liftplan.planner.plans.watch_basis import WatchBasis

    basis = tanker_basis()
    again = WatchBasis.from_json(basis.to_json())
    np.testing.assert_array_equal(getattr(again, key), getattr(basis, key))
    assert again.rules == basis.rules
