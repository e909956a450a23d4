"""The lug-choice MIP (planner/search/mip.py): its tension model against the held model, its
bounds' validity, its optimum against brute force, its gap and time limit, its refusals."""

import dataclasses
import itertools
import math

import numpy as np
import pytest
from helpers import EXAMPLES
from support.fleet import brute_force as fleet_brute_force
from support.fleet import fleet_problem
from support.planning import brute_force, small_problem

from liftplan.model import PlanInfeasible
from liftplan.planner.plan import plan
from liftplan.planner.problem.definition import CogEnvelope
from liftplan.planner.problem.file import load_problem
from liftplan.planner.search.evaluator import SetEvaluator
from liftplan.planner.search.methods import search
from liftplan.planner.search.mip import (
    first_scenarios,
    hook_bounds,
    least_width,
    mirror_map,
    poses,
    tension_band,
)
from liftplan.planner.search.scenarios import LugSet, Scenario, box_attitudes


def mip(problem, **changes):
    return dataclasses.replace(problem, search="mip", **changes)


def held_by_formula(problem, indices, preload, data):
    """T_k = P + kappa (h_k - r_k) with the hook plane h_k from each scenario's statics."""
    lugset = LugSet(problem, indices)
    kappa = lugset.stiffness
    idx = list(indices)
    basis = np.column_stack([np.ones(len(idx)), data.level_plan[idx]])
    out = []
    for a_mat, b_vec, rise in zip(data.a_mat, data.b_vec, data.rise):
        a = a_mat[:, idx]
        # A (P + kappa (basis c - r)) = b  ->  (A kappa basis) c = b - A (P - kappa r)
        c = np.linalg.solve(a @ (kappa[:, None] * basis), b_vec - a @ (preload - kappa * rise[idx]))
        out.append(preload + kappa * (basis @ c - rise[idx]))
    return np.array(out)


def test_tension_model_is_the_held_model():
    """The MIP's per-candidate form gives the held-preload tensions of the casadi model
    exactly (any set, any preload): the set enters only through which columns are summed."""
    problem = load_problem(EXAMPLES / "tanker_plan.toml")
    scenarios = [
        Scenario(h, t, tuple(o))
        for o in problem.cog_envelope.offsets()[:3]
        for h, t in box_attitudes(problem, 3, 3)
    ]
    data = poses(problem, scenarios)
    rng = np.random.default_rng(3)
    for indices in [(0, 3, 11, 14), (1, 4, 6, 9, 12), (0, 2, 5, 7, 10, 15)]:
        problem = dataclasses.replace(problem, cranes=len(indices), fleet=())
        lugset = LugSet(problem, indices)
        a_level, b_level = lugset.level_statics
        # an admissible preload: least-norm level solution plus a null-space twist
        base = np.linalg.lstsq(a_level, b_level, rcond=None)[0]
        null = np.linalg.svd(a_level)[2][3:].T
        preload = base + null @ rng.normal(scale=5.0, size=null.shape[1])
        expected = lugset.tensions(preload, scenarios)
        got = held_by_formula(problem, indices, preload, data)
        np.testing.assert_allclose(got, expected, atol=1e-9 * problem.body.weight)


def test_hook_plane_bounds_hold_for_sets_that_beat_the_cutoff():
    """Every set whose worst spread is below the cutoff has its hook plane inside the bounds
    at every candidate (chosen or not) and is at least as wide as least_width."""
    problem = dataclasses.replace(small_problem(4), top=40)
    ranking, _ = search(problem, top=40)
    cutoff = ranking[len(ranking) // 2].worst_value
    scenarios = first_scenarios(problem)
    data = poses(problem, scenarios)
    low, high = tension_band(problem, np.full(len(problem.candidates), 600.0), cutoff)
    change = float(np.max(high - low))
    kappa = LugSet(problem, range(4)).stiffness
    centre, half = hook_bounds(problem, data, change, kappa)
    width = least_width(problem, data, change)
    assert width > 0.0
    checked = 0
    for result in ranking:
        if result.worst_value >= cutoff:
            continue
        idx = list(result.indices)
        tensions = held_by_formula(problem, result.indices, result.preload, data)
        assert np.all(tensions >= low[0] - 1e-6) and np.all(tensions <= high[0] + 1e-6)
        plan_xy = data.level_plan[idx]
        # the hook plane through the chosen lugs (exact: h = r + (T - P) / kappa there)
        shift = data.rise[:, idx] + (tensions - result.preload) / kappa[0]
        basis = np.column_stack([np.ones(len(idx)), plan_xy])
        coef = np.linalg.lstsq(basis, shift.T, rcond=None)[0]
        everywhere = (np.column_stack([np.ones(len(data.level_plan)), data.level_plan]) @ coef).T
        assert np.all(np.abs(everywhere - centre) <= half + 1e-9)
        angles = np.linspace(0, np.pi, 360)
        widths = [np.ptp(plan_xy @ [np.cos(a), np.sin(a)]) for a in angles]
        assert min(widths) >= width
        checked += 1
    assert checked >= 5


@pytest.mark.parametrize(
    "cranes", [3, pytest.param(4, marks=pytest.mark.slow), pytest.param(5, marks=pytest.mark.slow)]
)  # 4: 11 s, 5: 8 s+
def test_mip_finds_the_brute_force_optimum(cranes):
    problem = small_problem(cranes)
    brute = brute_force(problem)
    best = min(brute.values())
    ranking, stats = search(mip(problem))
    # brute force on a 9 x 9 grid: the MIP's plan (dense 21 x 21 and zoom) may be a little
    # above it, never below
    assert ranking[0].worst_spread == pytest.approx(best, abs=1e-3 * problem.body.weight)
    assert stats.stopped == "proved" and stats.method == "mip"
    assert 0.0 <= stats.gap <= 1e-6 * problem.body.weight
    assert stats.lower_bound <= best + 1e-6 * problem.body.weight


@pytest.mark.parametrize("objective", ["utilisation", "reserve"])
def test_mip_assigns_unequal_cranes_as_brute_force(objective):
    """Four unequal cranes with load charts and reach on seven candidates: the MIP's plan
    (set and which crane on each lug) equals brute force over every set and permutation."""
    problem = fleet_problem(4, objective)
    brute = {k: v for k, v in fleet_brute_force(problem).items() if v is not None}
    best = min(brute.values())
    ranking, stats = search(mip(problem))
    # brute force on a 7 x 7 grid: the MIP's worst (dense 21 x 21 and zoom) may be a
    # little above it, never below; 1e-3 in utilisation (0.1 % of an SWL)
    assert ranking[0].worst_value == pytest.approx(best, abs=1e-3)
    assert ranking[0].worst_value >= best - 1e-6
    winners = {k for k, v in brute.items() if v <= best + 1e-3}
    assert (ranking[0].indices, ranking[0].cranes) in winners
    assert stats.stopped == "proved" and stats.lower_bound <= best + 1e-6


@pytest.mark.slow  # 11 s: the default run keeps under 10 minutes
def test_gap_target_and_an_independent_dense_check():
    """With gap = 10 % the reported gap is >= 0 and within it; the plan's worst case,
    re-checked on a grid the search never used, never exceeds the reported worst, and the
    lower bound never exceeds the brute-force optimum."""
    problem = small_problem(4)
    best = min(brute_force(problem).values())
    result = plan(mip(problem, gap=0.10))
    stats = result.stats
    assert 0.0 <= stats.relative_gap <= 0.10
    assert stats.lower_bound <= best + 1e-6 * problem.body.weight
    chosen = result.chosen
    lugset = LugSet(problem, chosen.indices, chosen.cranes)
    grid = [
        Scenario(h, t, tuple(o))
        for o in problem.cog_envelope.offsets()
        for h, t in box_attitudes(problem, 33, 33)
    ]  # 33: not the search's 21 nor 9
    tensions = lugset.tensions(chosen.preload, grid)
    assert np.ptp(tensions, axis=1).max() <= chosen.worst_spread + 1e-6 * problem.body.weight
    assert stats.lower_bound <= chosen.worst_spread


@pytest.mark.slow  # 8-12 s: the default run keeps under 10 minutes
def test_time_limit_returns_an_honest_gap():
    problem = small_problem(5)
    best = min(brute_force(problem).values())
    early = plan(mip(problem, time_limit=1e-3))
    stats = early.stats
    assert stats.stopped in ("time_limit", "proved")
    assert stats.lower_bound <= best + 1e-6 * problem.body.weight
    assert early.worst_spread >= best - 1e-6 * problem.body.weight
    assert stats.gap == pytest.approx(early.worst_spread - stats.lower_bound, abs=1e-9)
    data = early.to_json()
    assert data["search"]["method"] == "mip"
    assert data["lower_bound"] == stats.lower_bound and data["gap"] == stats.gap


def test_mirror_symmetry_is_found_only_where_it_holds():
    tanker = load_problem(EXAMPLES / "tanker_plan.toml")
    image = mirror_map(tanker)
    assert image is not None and np.all(image[image] == np.arange(len(image)))
    names = tanker.names
    assert all(names[i][:-1] == names[j][:-1] and names[i] != names[j] for i, j in enumerate(image))
    # the 154 m hull's CG is 0.3 m to port: no mirror symmetry
    assert mirror_map(load_problem(EXAMPLES / "hull154_plan.toml")) is None


def test_hook_tolerance_fits_the_same_formulation(monkeypatch):
    """Hook-height errors as cuts (the chosen set's worst errors at its worst scenario; the
    box rows set aside by taking the candidates as off one plane): the MIP's plan equals the
    exact search's with the same tolerance, for equal cranes and for four unequal cranes with
    charts (set, crane on each lug), and the MIP proves it (its first plan's own bound is set
    aside, so the proof is the MIP's)."""
    import liftplan.planner.search.mip as lug_mip

    monkeypatch.setattr(lug_mip, "on_one_plane", lambda problem: False)
    first = lug_mip._incumbent

    def unproved(problem, started):
        ranking, stats = first(problem, started)
        return ranking, dataclasses.replace(stats, lower_bound=0.0)

    monkeypatch.setattr(lug_mip, "_incumbent", unproved)
    for problem in (
        small_problem(4, hook_tolerance=0.02),
        dataclasses.replace(fleet_problem(4, "utilisation"), hook_tolerance=0.02),
    ):
        exact, _ = search(dataclasses.replace(problem, search="exact"), 1)
        ranking, stats = search(mip(problem), 1)
        assert ranking[0].worst_value == pytest.approx(exact[0].worst_value, rel=1e-6)
        assert (ranking[0].indices, ranking[0].cranes) == (exact[0].indices, exact[0].cranes)
        assert stats.stopped == "proved" and stats.refined > 1  # the errors came in as cuts
        assert stats.lower_bound <= exact[0].worst_value * (1 + 1e-9)


def test_rounds_run_out_with_an_honest_gap(monkeypatch):
    """With one cutting-plane round where the proof needs more (the hook errors as cuts), the
    MIP says its rounds ran out (not a time limit it was never given) and its bound is still
    below the optimum."""
    import liftplan.planner.search.mip as lug_mip

    monkeypatch.setattr(lug_mip, "on_one_plane", lambda problem: False)
    first = lug_mip._incumbent

    def unproved(problem, started):
        ranking, stats = first(problem, started)
        return ranking, dataclasses.replace(stats, lower_bound=0.0)

    monkeypatch.setattr(lug_mip, "_incumbent", unproved)
    monkeypatch.setattr(lug_mip, "MAX_ROUNDS", 1)
    problem = small_problem(4, hook_tolerance=0.02)
    exact, _ = search(dataclasses.replace(problem, search="exact"), 1)
    ranking, stats = search(mip(problem), 1)
    assert stats.stopped == "rounds" and problem.time_limit is None
    assert "cutting-plane rounds" in stats.summary
    assert stats.lower_bound <= exact[0].worst_value * (1 + 1e-9) <= ranking[0].worst_value * (1 + 1e-9)


def test_refusals_name_what_is_wrong():
    level = small_problem(4, heel_tolerance=0.0, trim_tolerance=0.0, cog_envelope=CogEnvelope())
    with pytest.raises(PlanInfeasible, match=r"needs the CG envelope or the tilt tolerance"):
        plan(mip(level))


def test_evaluator_agrees_with_the_mip_value():
    """The MIP's optimum over its final scenario list equals the evaluator's LP value of the
    chosen set (the same physics in two formulations), within the solvers' tolerance."""
    problem = small_problem(4)
    ranking, stats = search(mip(problem))
    again = SetEvaluator(problem).evaluate(ranking[0].indices)
    assert again.worst_value == pytest.approx(ranking[0].worst_value, abs=1e-6 * problem.body.weight)
    assert math.isfinite(stats.lower_bound)
    assert len(list(itertools.islice(first_scenarios(problem), 3))) == 3
