"""Timing helpers of the core model for :mod:`benchmarks` (MoorPy as the peer).

Varied 4-rope scenes, the median ``elastic`` solve through the public API, the same job in
MoorPy (build + solve), and batched ``paper-elastic`` attitude evaluations per second.
Every figure is printed by ``python studies/benchmarks.py``.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import numpy as np

from liftplan.model import load_scene, paper_elastic_tensions, solve
from liftplan.model.statics.model import rope_model

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "tests"))
from support.moorpy_peer import moorpy_solve  # noqa: E402


def varied_scenes(count=50, seed=1):
    """The symmetric block with random hoist differences (up to 0.15 m) and CG offsets."""
    rng = np.random.default_rng(seed)
    base = load_scene(HERE.parent / "examples" / "symmetric_block.toml")
    scenes = []
    for _ in range(count):
        scene = base.with_body(cog=(rng.uniform(-2, 2), rng.uniform(-1, 1), 2.5))
        for name in scene.lug_names:
            scene = scene.with_crane(name, boom_height=40.0 + rng.uniform(-0.15, 0.15))
        scenes.append(scene)
    return scenes


def time_elastic(scenes, repeats=200):
    for scene in scenes:
        solve(scene, "elastic")  # warm: builds the casadi functions once
    samples = []
    for _ in range(repeats):
        for scene in scenes:
            start = time.perf_counter()
            solve(scene, "elastic")
            samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def time_moorpy(scenes):
    build_and_solve = []
    for scene in scenes[:20]:
        eq = solve(scene, "elastic")
        start = time.perf_counter()
        moorpy_solve(scene, eq.pose.heel, eq.pose.trim, eq.pose.lift_height)
        build_and_solve.append(time.perf_counter() - start)
    return statistics.median(build_and_solve)


def time_batch(count=2_000_000, seed=2):
    rng = np.random.default_rng(seed)
    scene = load_scene(HERE.parent / "examples" / "tanker_upright.toml")
    heel, trim = rng.uniform(-10, 10, count), rng.uniform(-10, 10, count)
    paper_elastic_tensions(scene, heel[:10], trim[:10])  # warm: JIT compile
    runs = []
    for _ in range(3):
        start = time.perf_counter()
        paper_elastic_tensions(scene, heel, trim)
        runs.append(time.perf_counter() - start)
    return count / min(runs), rope_model(scene.n).batch_backend
