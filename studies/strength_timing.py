"""Cost of the hull girder of a solved state (issue 12: under 1 ms for a 200-segment curve).

Times :func:`liftplan.model.strength.hull_girder` (loads, exact integration, extrema, output
stations) on a solved state, median of repeats, for a 200-segment weight curve:

* the 1500 GT tanker in air (examples/tanker_strength.toml, its curve resampled at 201
  points and scaled to W, the CG's x moved to the new curve's centroid), paper-elastic;
* the stranded barge (examples/stranded_barge.toml, a box hull in water, grounded) with a
  200-segment curve: buoyancy by x-sections of the clipped box adds to the cost.

Writes studies/out/strength_timing.json. Run on an idle machine (waits for load <= 1.5).
"""

from __future__ import annotations

import dataclasses
import json
import os
import time
from pathlib import Path

import numpy as np

from liftplan.model import load_scene, solve
from liftplan.model.scene.objects import curve_totals
from liftplan.model.strength import hull_girder

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "studies" / "out" / "strength_timing.json"
REPEATS = 2000


def _resampled(scene, start, end, segments=200):
    """The scene with a ``segments``-segment curve over [start, end] (shape from the scene's
    curve, or uniform with a ripple), scaled to W, and the CG's x at its centroid."""
    x = np.linspace(start, end, segments + 1)
    if scene.body.weight_curve is not None:
        w = np.interp(x, *scene.body.weight_curve_arrays)
    else:
        w = 1.0 + 0.2 * np.sin(np.linspace(0.0, 9.0, segments + 1)) ** 2
    area, first = curve_totals(x, w)
    w = w * scene.body.weight / area
    cog = (first / area, *scene.body.cog[1:])
    body = dataclasses.replace(scene.body, cog=cog, weight_curve=tuple(zip(x.tolist(), w.tolist())))
    return dataclasses.replace(scene, body=body, strength=None)


def _median_seconds(scene, eq):
    hull_girder(scene, eq)
    times = []
    for _ in range(REPEATS):
        begin = time.perf_counter()
        hull_girder(scene, eq)
        times.append(time.perf_counter() - begin)
    return float(np.median(times))


def main():
    while os.getloadavg()[0] > 1.5:
        time.sleep(10)
    load = os.getloadavg()[0]
    cases = {
        "tanker in air, paper-elastic": _resampled(
            load_scene(ROOT / "examples/tanker_strength.toml"), 0.0, 82.05
        ),
        "stranded barge, box hull in water, grounded": _resampled(
            load_scene(ROOT / "examples/stranded_barge.toml"), -50.0, 50.0
        ),
    }
    out = {"repeats": REPEATS, "load_average": load, "cases": {}}
    for name, scene in cases.items():
        eq = solve(scene)
        g = hull_girder(scene, eq)
        seconds = _median_seconds(scene, eq)
        out["cases"][name] = {
            "segments": len(scene.body.weight_curve) - 1,
            "median_ms": 1e3 * seconds,
            "stations": len(g.stations),
            "max_bending_moment": g.max_moment.value,
        }
        print(f"{name}: {len(scene.body.weight_curve) - 1} segments, median {1e3 * seconds:.3f} ms")
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps(out, indent=2) + "\n")


if __name__ == "__main__":
    main()
