"""Benchmark of the planner: the tanker with 16 and with 40 candidates.

Figures (each the median of a few runs in this process, after one warm-up that builds and
compiles the casadi functions):

* ``plan()`` of ``examples/tanker_plan.toml`` (16 candidates, 1 820 sets of 4, CG box);
* the same with 40 candidates (8 bulkheads x 5 deck points, 91 390 sets), with and
  without the CG envelope;
* the peer in the same run: brute force, every set that screening leaves feasible
  evaluated with the same LP and dense search (no pruning), on the 16-candidate case.

Run:  python studies/bench_plan.py      (writes studies/out/bench_plan.json)
"""

from __future__ import annotations

import dataclasses
import json
import math
import platform
import statistics
import time
from pathlib import Path

from liftplan.planner.plan import plan
from liftplan.planner.problem import Candidate, CogEnvelope
from liftplan.planner.problemfile import load_problem
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


def main():
    tanker = load_problem(HERE.parent / "examples" / "tanker_plan.toml")
    wide = dataclasses.replace(tanker, candidates=forty_candidates(tanker))
    wide_nominal = dataclasses.replace(wide, cog_envelope=CogEnvelope())
    rows = {}
    for key, problem, repeats in (("tanker_16", tanker, 5), ("tanker_40_cog_box", wide, 2),
                                  ("tanker_40_nominal_cog", wide_nominal, 3)):
        seconds, result = timed(lambda p=problem: plan(p), repeats)
        rows[key] = {
            "sets": result.stats.sets,
            "evaluated": result.stats.evaluated,
            "screened_out": result.stats.screened_out,
            "pruned": result.stats.pruned,
            "seconds": seconds,
            "lugs": list(result.lugs.values()),
            "worst_spread_t": result.worst_spread,
        }
    seconds, best = timed(lambda: brute_force(tanker), 1)
    rows["tanker_16_brute_force"] = {"seconds": seconds, "worst_spread_t": best}
    rows["speedup_vs_brute_force"] = seconds / rows["tanker_16"]["seconds"]
    rows["same_optimum"] = abs(best - rows["tanker_16"]["worst_spread_t"]) < 1e-6
    rows["machine"] = f"{platform.processor() or platform.machine()}, Python {platform.python_version()}"
    out = HERE / "out" / "bench_plan.json"
    out.write_text(json.dumps(rows, indent=1))
    for key, value in rows.items():
        print(key, value)


if __name__ == "__main__":
    main()
