"""Planner helpers for :mod:`benchmarks`: the 40-candidate tanker and the brute-force peer
(every set that screening leaves feasible, evaluated with the same LP and dense search, no
pruning). Every figure is printed by ``python studies/benchmarks.py``.
"""

from __future__ import annotations

import math
import statistics
import time
from pathlib import Path

from liftplan.planner.problem import Candidate
from liftplan.planner.screen import screen
from liftplan.planner.search import SetEvaluator, SetInfeasible

HERE = Path(__file__).parent


def forty_candidates(problem):
    """8 bulkheads of the tanker example x 5 deck points across the beam (z-up y)."""
    stations = sorted({c.at[0] for c in problem.candidates})
    return tuple(
        Candidate(f"B{i + 1}-{j}", (x, -3.0 * j, 6.0), bulkhead=f"B{i + 1}")
        for i, x in enumerate(stations) for j in range(5)
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
