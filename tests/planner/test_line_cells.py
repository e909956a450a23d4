"""Coplanar lugs and the cell-by-cell bound (planner/search/coplanar.py, line_cells.py).

The plane model (a scenario is an effective CG) is checked against the held model's set
evaluation; each closed bound the cells use is checked against every set's exact LP (it
must never exceed it); the dynamic programme against brute force over the subsets of a
cell; and the bound against the optimum of a small case found by brute force: it never
exceeds it, and closes to within 1 % of it."""

import dataclasses
import itertools
import math

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.planner.problem.file import load_problem
from liftplan.planner.search.coplanar import PlaneLP, coplanar, corner_scenarios, effective_cogs
from liftplan.planner.search.evaluator import SetEvaluator
from liftplan.planner.search.line_cells import (
    Same,
    _Cells,
    _families,
    _programme,
    _values,
    applies,
    cell_bound,
    layout,
)
from liftplan.planner.search.local import line_starts

STATIONS = (1, 8, 15, 22, 29, 36)  # every 7th frame of the 154 m hull: 25.2 m apart


@pytest.fixture(scope="module")
def hull():
    return load_problem(EXAMPLES / "hull154_plan.toml")


@pytest.fixture(scope="module")
def small(hull):
    """5 lugs among 12 stations on the 154 m hull's two lines (792 sets), 2 000 t hung."""
    keep = [c for c in hull.candidates if int(c.name[1:]) in STATIONS]
    return dataclasses.replace(
        hull, candidates=tuple(keep), cranes=5, body=dataclasses.replace(hull.body, weight=2000.0)
    )


@pytest.fixture(scope="module")
def small_values(small):
    """The exact value (held model, dense box) of every set of the small case."""
    evaluator = SetEvaluator(small)
    plane = PlaneLP(small, evaluator.dense)
    sets = list(itertools.combinations(range(len(small.candidates)), small.cranes))
    return evaluator, {s: plane.value(s) for s in sets}


@pytest.mark.parametrize("objective", ["spread", "utilisation", "reserve"])
def test_plane_lp_is_the_held_model(hull, objective):
    """PlaneLP on the corners of the effective CGs equals the set evaluator (held model, dense
    box and its zoom) to 1e-7 of the value, on the end-of-line starts and random sets."""
    problem = dataclasses.replace(hull, objective=objective)
    evaluator = SetEvaluator(problem)
    plane = PlaneLP(problem, evaluator.dense)
    rng = np.random.default_rng(3)
    sets = line_starts(problem)[:2] + [
        tuple(sorted(rng.choice(80, 26, replace=False).tolist())) for _ in range(2)
    ]
    for indices in sets:
        exact = evaluator.evaluate(indices).worst_value
        assert plane.value(indices) == pytest.approx(exact, rel=1e-7)


def test_a_tilt_is_a_shift_of_the_cog(hull):
    """Effective CGs: level is the CG; a heel moves it across by (z_G - z_L) tan(heel) and a
    trim along by the same lever; the box's corners span every dense scenario's."""
    plane = coplanar(hull)
    assert plane.height == 16.0
    evaluator = SetEvaluator(hull)
    cogs = effective_cogs(hull, plane, evaluator.dense)
    level = [k for k, s in enumerate(evaluator.dense) if s.heel == s.trim == 0 and not any(s.cog_offset)]
    assert np.allclose(cogs[level[0]], hull.body.cog[:2], atol=1e-12)
    lever = hull.body.cog[2] - plane.height
    span = np.ptp(cogs, axis=0)
    lever = abs(lever) + 0.5  # the CG envelope's +/- 0.5 m up
    assert span[0] == pytest.approx(2 * (1.0 + lever * math.tan(math.radians(0.5))), rel=1e-4)
    assert span[1] == pytest.approx(2 * (0.3 + lever * math.tan(math.radians(1.0))), rel=1e-4)
    corners = effective_cogs(hull, plane, corner_scenarios(hull, plane, evaluator.dense))
    assert len(corners) == 4 and np.allclose(np.ptp(corners, axis=0), span)


def test_lug_layout_of_the_hull(hull, small):
    assert applies(hull) and applies(small)
    lay = layout(hull)
    assert [len(g.index) for g in lay.grids] == [40, 40]
    assert lay.grids[0].spacing == pytest.approx(3.6) and abs(lay.across[0] - lay.across[1]) == 12
    tanker = load_problem(EXAMPLES / "tanker_plan.toml")  # frames not at one spacing
    assert layout(tanker) is None
    block = load_problem(EXAMPLES / "block_8_points_plan.toml")  # not two lines
    assert not applies(block)


def _cells_of(problem, sets):
    """Each set's cell: (count on line 0, index sums), and the line stations it takes."""
    lay = layout(problem)
    out = []
    for indices in sets:
        chosen = [np.sort(g.index[np.isin(g.candidate, indices)]) for g in lay.grids]
        out.append(((len(chosen[0]), int(chosen[0].sum()), int(chosen[1].sum())), chosen))
    return lay, out


def test_every_closed_bound_is_below_every_sets_value(small, small_values):
    """The one-scenario, same-role and pair bounds of every family, for every one of the 792
    sets, never exceed the set's exact value (the LP duality the cells rest on)."""
    evaluator, values = small_values
    plane = coplanar(small)
    lay, cells = _cells_of(small, list(values))
    corners = effective_cogs(small, plane, corner_scenarios(small, plane, evaluator.dense)) @ lay.axes.T
    worst = -np.inf
    for (key, chosen), value in zip(cells, values.values()):
        if not np.isfinite(value) or key[0] in (0, small.cranes):
            continue
        data = _Cells(small, lay, corners, key[0])
        m = data.means(np.array(key[1:], dtype=float))
        families = _families(data, m)
        bounds = _values(data, families, [chosen], m)[0]
        single = float(data.one_scenario(np.array([key[1:]]))[0])
        worst = max(worst, max(bounds.max(), single) - value)
    assert worst <= 1e-7


def test_programme_is_brute_force_over_a_cell(small):
    """The dynamic programme's least value over a cell equals the least over every subset
    of the line's stations with that count and index sum, for a random combination."""
    evaluator = SetEvaluator(small)
    plane = coplanar(small)
    lay = layout(small)
    corners = effective_cogs(small, plane, corner_scenarios(small, plane, evaluator.dense)) @ lay.axes.T
    rng = np.random.default_rng(0)
    data = _Cells(small, lay, corners, 3)
    for sums in ((5, 4), (7, 2), (9, 5)):
        m = data.means(np.array(sums, dtype=float))
        families = _families(data, m)
        lam = np.zeros(len(families))
        pick = rng.choice(len(families), 4, replace=False)
        lam[pick] = rng.random(4)
        for j in (0, 1):
            n = int(data.n[j])
            least, chosen = _programme(data, j, sums[j], families, lam, 80.0, m)
            brute = np.inf
            for subset in itertools.combinations(lay.grids[j].index, n):
                if sum(subset) != sums[j]:
                    continue
                brute = min(brute, _line_part(data, j, np.array(subset), families, lam, 80.0, m))
            assert least == pytest.approx(brute, rel=1e-9, abs=1e-6)
            assert sum(chosen) == sums[j] and len(chosen) == n


def _line_part(data, j, subset, families, lam, target, m):
    """Line j's part of sum_f lam_f V (bound_f - target), summed directly over its lugs."""
    s = np.sort(data.grids[j].offset + data.grids[j].spacing * subset)
    u = s - m[j]
    weight, n = data.weight, int(data.n[j])
    total = 0.0
    for f, la in zip(families, lam):
        if la <= 0:
            continue
        total -= la * (target - f.const) * np.sum(u * u)
        if isinstance(f, Same):
            sign = -1.0 if j == f.high else 1.0
            split = (1 - f.theta) if j == f.high else f.theta
            w = 1.0 / n + sign * f.kappa * u
            before = np.cumsum(w) - w
            bottom = np.clip(split - before, 0.0, w)
            total += la * weight * f.gamma * np.sum(u * (w - 2 * bottom))
        else:
            for (line, end), sign in ((f.p, 1.0), (f.q, -1.0)):
                if line == j:
                    total += la * sign * weight * f.gamma / 2 * (u[-1] if end else u[0])
    return total


def test_bound_never_exceeds_the_optimum_and_closes_within_one_percent(small, small_values):
    """Small case, optimum by brute force over its 792 sets: a target above the optimum
    returns a bound at or below it; a target 1 % below closes (every cell)."""
    evaluator, values = small_values
    optimum = min(values.values())
    assert np.isfinite(optimum)
    above = cell_bound(small, evaluator.dense, 1.05 * optimum)
    assert above.complete and above.value <= optimum + 1e-9 and above.failed > 0
    below = cell_bound(small, evaluator.dense, 0.99 * optimum)
    assert below.value == pytest.approx(0.99 * optimum) and below.failed == 0


def test_deadline_keeps_a_valid_bound(small, small_values):
    """A deadline already passed: the open cells count at their one-scenario bound, which
    is still below the optimum; the result says it is incomplete."""
    evaluator, values = small_values
    optimum = min(values.values())
    early = cell_bound(small, evaluator.dense, optimum, deadline=0.0)
    assert not early.complete and early.value <= optimum + 1e-9 and early.searched == 0


def test_ctrl_c_keeps_a_valid_bound_and_the_plan(small, small_values, monkeypatch):
    """Ctrl-C in the cells: cell_bound returns what it has (the open cells at their closed
    form, below the optimum, flagged interrupted); the local search's plan is kept with that
    bound (Interrupted, stopped "interrupted")."""
    import liftplan.planner.search.line_cells as line_cells
    from liftplan.planner.search.evaluator import Interrupted
    from liftplan.planner.search.methods import search

    evaluator, values = small_values
    optimum = min(values.values())
    calls = []
    closes = line_cells._closes

    def interrupted_later(*args):
        calls.append(1)
        if len(calls) > 1:
            raise KeyboardInterrupt
        return closes(*args)

    monkeypatch.setattr(line_cells, "_closes", interrupted_later)
    ticks = []
    early = cell_bound(small, evaluator.dense, 0.99 * optimum, tick=lambda *t: ticks.append(t))
    assert early.interrupted and not early.complete and early.value <= optimum + 1e-9
    assert [t[0] for t in ticks] == list(range(1, len(ticks) + 1)) and ticks
    assert all(t[2] <= optimum + 1e-9 for t in ticks)
    calls.clear()
    with pytest.raises(Interrupted) as caught:
        search(dataclasses.replace(small, search="local"), 1)
    stats = caught.value.stats
    assert stats.stopped == "interrupted" and caught.value.ranking
    assert 0 < stats.lower_bound <= optimum + 1e-9 <= caught.value.ranking[0].worst_value + 1e-9


def test_local_plan_bound_against_a_proved_optimum():
    """The tanker's 40 frame candidates (one spacing, one deck plane), 4 cranes: the local
    plan's bound, raised by the cells well above the two-line bound, stays at or below the
    optimum the exact search proves."""
    import sys

    from helpers import ROOT

    from liftplan.planner.search.lines import line_bound
    from liftplan.planner.search.methods import search

    sys.path.insert(0, str(ROOT / "studies"))
    from planner_scale import tanker_with

    problem = dataclasses.replace(tanker_with(40, 4), time_limit=None)
    assert applies(problem)
    exact, proved = search(problem, 1)
    assert proved.stopped == "proved"
    local, stats = search(dataclasses.replace(problem, search="local"), 1)
    optimum = exact[0].worst_value
    lines = line_bound(problem, SetEvaluator(problem).dense)
    assert lines < 0.9 * stats.lower_bound  # the cells, not the two-line bound
    assert stats.lower_bound <= optimum * (1 + 1e-9) <= local[0].worst_value * (1 + 1e-9)


@pytest.mark.slow
def test_hull_plan_is_certified_within_one_percent(hull):
    """The 154 m hull's 26 of 80 with gap = 0.01 and no time limit (deterministic): a plan
    whose certified gap is at most 1 %."""
    from liftplan.planner.search.methods import search

    ranking, stats = search(dataclasses.replace(hull, gap=0.01, time_limit=None), 1)
    assert stats.stopped == "local" and 0.0 < stats.relative_gap <= 0.01
    assert stats.lower_bound <= ranking[0].worst_value
