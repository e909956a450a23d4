"""How long one update of ``liftplan watch`` takes: the estimate and the advice of one reading.

Plans: ``examples/tanker_plan.toml`` (4 cranes) and ``examples/hull154_plan.toml`` (26 lifting
points), each planned once. Readings: ``simulate`` of each plan (seed 0, hook errors 0.06 m,
CG 0.1 m, weight 2 %, drift 0.003 m/sqrt(s), heel and trim read), so the advice has moves to
plan. Measured per reading, once the plan's functions exist (the first reading warms them and
is not counted): the update as ``Watcher.update`` runs it (the fit from the last estimate, then
the advice), and its two parts. Against it, in the same run, today's way of evaluating one
state of the plan: ``liftplan.model.solve(plan.scene)`` (one elastic solve of the plan's
scene, the whole user call); an update does several forward solves with their Jacobians and a
convex problem, so the ratio says how many such solves one update costs.

The machine is shared (2 cores, 5 engineers): the 1-minute load average is recorded with the
numbers; the medians are the figure, the 90th percentiles say how loaded it was.

Run:  python studies/watch_speed.py      (writes studies/out/watch_speed.json)
"""

from __future__ import annotations

import json
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
ROOT = HERE.parent
OUT = HERE / "out"

from liftplan.model.solve import solve  # noqa: E402
from liftplan.planner.plan import plan  # noqa: E402
from liftplan.planner.plans.watch_basis import watch_basis  # noqa: E402
from liftplan.planner.problem.file import load_problem  # noqa: E402
from liftplan.planner.watch.simulate import Errors, Noise, simulate  # noqa: E402
from liftplan.planner.watch.update import Watcher  # noqa: E402

CASES = {"tanker (4 cranes)": "tanker_plan.toml", "hull154 (26 points)": "hull154_plan.toml"}
TARGET_MS = {"tanker (4 cranes)": 50.0, "hull154 (26 points)": 200.0}
READINGS = 60


def _ms(values):
    values = sorted(values)
    return {
        "median": 1e3 * statistics.median(values),
        "p90": 1e3 * values[int(0.9 * (len(values) - 1))],
        "max": 1e3 * values[-1],
    }


def measure(name, file):
    start = time.perf_counter()
    result = plan(load_problem(ROOT / "examples" / file))
    planned = time.perf_counter() - start
    basis = watch_basis(result)
    lift = simulate(
        basis, Errors(hook=0.06, cog=0.1, weight=0.02), Noise(), seed=0, steps=READINGS + 1, drift=0.003
    )
    watcher = Watcher(basis)
    watcher.update(lift.readings[0])  # warms the model's functions and the move problem
    update, fit, advice, stops, moved = [], [], [], 0, 0
    for reading in lift.readings[1:]:
        t0 = time.perf_counter()
        estimate = watcher.estimator.estimate(reading, start=watcher.last)
        t1 = time.perf_counter()
        move = watcher.advisor.advise(estimate)
        t2 = time.perf_counter()
        watcher.last = estimate.raw
        fit.append(t1 - t0)
        advice.append(t2 - t1)
        update.append(t2 - t0)
        stops += move.stop
        moved += bool(np.any(move.moves != 0.0))
    scene = result.scene
    solve(scene)
    solves = []
    for _ in range(200):
        t0 = time.perf_counter()
        solve(scene)
        solves.append(time.perf_counter() - t0)
    out = {
        "ropes": basis.n,
        "plan_seconds": planned,
        "readings": READINGS,
        "stops": stops,
        "with_moves": moved,
        "update_ms": _ms(update),
        "estimate_ms": _ms(fit),
        "advice_ms": _ms(advice),
        "solve_ms": _ms(solves),
        "target_ms": TARGET_MS[name],
    }
    out["update_over_solve"] = out["update_ms"]["median"] / out["solve_ms"]["median"]
    return out


def main():
    results = {"machine": platform.machine(), "python": platform.python_version(), "cases": {}}
    results["load_before"] = os.getloadavg()[0]
    for name, file in CASES.items():
        results["cases"][name] = measure(name, file)
        r = results["cases"][name]
        print(
            f"{name}: update {r['update_ms']['median']:.1f} ms median (p90 {r['update_ms']['p90']:.1f}; "
            f"estimate {r['estimate_ms']['median']:.1f}, advice {r['advice_ms']['median']:.1f}) against "
            f"{r['target_ms']:g} ms; one solve(plan.scene) {r['solve_ms']['median']:.2f} ms "
            f"({r['update_over_solve']:.0f}x); {r['with_moves']} of {READINGS} with moves, "
            f"{r['stops']} stops",
            flush=True,
        )
    results["load_after"] = os.getloadavg()[0]
    OUT.mkdir(exist_ok=True)
    (OUT / "watch_speed.json").write_text(json.dumps(results, indent=1) + "\n", encoding="utf-8")
    print(
        f"load average {results['load_before']:.2f} before, {results['load_after']:.2f} after",
        file=sys.stderr,
    )


if __name__ == "__main__":
    main()
