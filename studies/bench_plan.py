"""Planner helpers for :mod:`benchmarks`: the 40-candidate tanker and the brute-force peers.

* :func:`brute_force`: equal cranes, every set that screening leaves feasible, evaluated with
  the same LP and dense search, no pruning;
* :func:`fleet_brute_force`: an unequal fleet, every set x every permutation of the cranes
  with each crane within its chart's reach, each through the same evaluation
  (``SetEvaluator.evaluate``), no screening, no pruning, no symmetry.

Every figure is printed by ``python studies/benchmarks.py``.
"""

from __future__ import annotations

import itertools
import math
import random
import statistics
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from liftplan.planner.problem.definition import Candidate
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.scenarios import LugSet
from liftplan.planner.search.screen import screen

#: Brute force longer than this is timed on a seeded random sample and extrapolated  [s].
FULL_BRUTE_FORCE_LIMIT = 300.0
#: Rows timed first to estimate the full brute force, and the sample's seed.
PROBE_ROWS, SEED = 100, 11

HERE = Path(__file__).parent


def forty_candidates(problem):
    """8 bulkheads of the tanker example x 5 deck points across the beam (z-up y)."""
    stations = sorted({c.at[0] for c in problem.candidates})
    return tuple(
        Candidate(f"B{i + 1}-{j}", (x, -3.0 * j, 6.0), bulkhead=f"B{i + 1}")
        for i, x in enumerate(stations)
        for j in range(5)
    )


def timed(function, repeats):
    function()  # warm-up: casadi JIT and cvxpy canonicalisation happen once
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples), result


def brute_force(problem):
    screening = screen(problem)
    evaluator = SetEvaluator(problem)
    best = math.inf
    for indices, bound in zip(screening.sets, screening.bound):
        if math.isfinite(bound):
            try:
                best = min(best, evaluator.evaluate(indices).worst_spread)
            except SetInfeasible:
                pass
    return best


@dataclass(frozen=True)
class FleetBruteForce:
    """Brute force over lug sets x crane permutations of an unequal fleet.

    Parameters
    ----------
    rows : int
        Sets x permutations, reach ignored (C(m, n) n!).
    in_reach : int
        Rows with every crane within its chart's reach of its lug.
    evaluated : int
        Rows evaluated: all ``in_reach`` rows, or the sample's size when ``sampled``.
    feasible : int
        Evaluated rows that hold the body (a plan exists for them).
    collinear : int
        Evaluated rows whose lugs are collinear in plan (no statics; see ``collinear_error``).
    collinear_error : str
        What ``SetEvaluator.evaluate`` raised on such a row when it did not raise
        ``SetInfeasible`` (empty if it always did).
    best : float  [t or -]
        Least worst value of the objective over the evaluated rows.
    best_row : tuple
        (candidate indices, fleet indices) of that row.
    seconds : float  [s]
        Wall time of the evaluated rows.
    estimated_seconds : float  [s]
        Time for all ``in_reach`` rows (measured when not sampled, else extrapolated).
    sampled : bool
        True: the full brute force would exceed FULL_BRUTE_FORCE_LIMIT; a seeded random
        sample was timed and extrapolated, and ``best`` is over the sample only.
    """

    rows: int
    in_reach: int
    evaluated: int
    feasible: int
    collinear: int
    collinear_error: str
    best: float
    best_row: tuple
    seconds: float
    estimated_seconds: float
    sampled: bool


def reach_rows(problem):
    """Every (set, permutation) of the fleet, and those with each crane within reach."""
    swl = problem.reach[1]
    n = problem.cranes
    every = [
        (s, p)
        for s in itertools.combinations(range(len(problem.candidates)), n)
        for p in itertools.permutations(range(n))
    ]
    return len(every), [(s, p) for s, p in every if not np.any(np.isnan(swl[list(s), list(p)]))]


def _collinear(problem, indices, cranes):
    a_level, _ = LugSet(problem, indices, cranes).level_statics
    return np.linalg.matrix_rank(a_level) < 3


def fleet_brute_force(problem):
    """Evaluate every in-reach (set, permutation) row with ``SetEvaluator.evaluate``.

    The first PROBE_ROWS rows of a seeded shuffle are timed; if all rows would take longer
    than FULL_BRUTE_FORCE_LIMIT, that sample's time is extrapolated and the result says so.

    Returns
    -------
    FleetBruteForce
    """
    count, rows = reach_rows(problem)
    order = list(range(len(rows)))
    random.Random(SEED).shuffle(order)
    evaluator = SetEvaluator(problem)
    best, best_row, feasible, collinear, error = math.inf, None, 0, 0, ""
    start = time.perf_counter()
    done = 0
    for k in order:
        indices, cranes = rows[k]
        try:
            value = evaluator.evaluate(indices, cranes).worst_value
        except SetInfeasible:
            if _collinear(problem, indices, cranes):
                collinear += 1
            value = math.inf
        except ValueError as err:
            if not _collinear(problem, indices, cranes):
                raise
            collinear, error, value = collinear + 1, f"ValueError: {err}", math.inf
        feasible += math.isfinite(value)
        if value < best:
            best, best_row = value, (tuple(indices), tuple(cranes))
        done += 1
        if done == PROBE_ROWS:
            estimate = (time.perf_counter() - start) * len(rows) / done
            if estimate > FULL_BRUTE_FORCE_LIMIT:
                seconds = time.perf_counter() - start
                return FleetBruteForce(
                    count,
                    len(rows),
                    done,
                    feasible,
                    collinear,
                    error,
                    best,
                    best_row,
                    seconds,
                    estimate,
                    True,
                )
    seconds = time.perf_counter() - start
    return FleetBruteForce(
        count, len(rows), done, feasible, collinear, error, best, best_row, seconds, seconds, False
    )
