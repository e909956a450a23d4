"""Every headline speed figure, measured in one run, with the peers in the same run.

Figures, each with its peer measured in the same run:

* single elastic 4-rope solve, ``solve()`` median; peers MoorPy (build + solve to
  1e-10 m) and scipy ``root`` (hybr) on a numpy residual;
* batched attitude evaluations, ``paper_elastic_tensions`` on one core; peer numpy, the
  same 3x3 systems stacked into ``np.linalg.solve``;
* tanker plan (16 candidates), ``plan()``; peer brute force (every feasible set, same LP);
* 40-candidate plan, CG box;
* stranded barge solve, casadi Newton (full solve, and root-finding alone); peers the
  paper's J^T D J iteration and scipy ``root`` (hybr) on the same residual;
* lift load curve of the sunken block, per step;
* plan evaluations (batch check): cases per second per core, in process and on two Dask
  workers; the goal is 10 000.

Run:  python studies/benchmarks.py    (writes studies/out/benchmarks.json and .md)
"""

from __future__ import annotations

import dataclasses
import json
import logging
import math
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
from bench_core import time_batch, time_elastic, time_moorpy, varied_scenes  # noqa: E402
from bench_plan import brute_force, forty_candidates  # noqa: E402
from speed_accuracy import numpy_residual  # noqa: E402

from liftplan.model import load_scene, paper_elastic_tensions  # noqa: E402
from liftplan.model.lift import load_curve  # noqa: E402
from liftplan.planner.plan import plan  # noqa: E402
from liftplan.planner.problemfile import load_problem  # noqa: E402

EXAMPLES = HERE.parent / "examples"
OUT = HERE / "out"


def median_time(function, repeats, warm=1):
    for _ in range(warm):
        function()
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)


def single_solve():
    from scipy.optimize import root

    from liftplan.model.solve import pack_params
    from liftplan.model.statics import FastCall, rope_model

    scenes = varied_scenes()
    ours = time_elastic(scenes, repeats=50)
    moorpy = time_moorpy(scenes)
    samples = []
    for scene in scenes:
        residual, _ = numpy_residual(scene)
        start = FastCall(rope_model(scene.n).elastic_start)(pack_params(scene, "elastic"))[0]
        samples.append(median_time(lambda r=residual, s=start: root(r, s, method="hybr"), 5))
    return {"liftplan_us": ours * 1e6, "moorpy_ms": moorpy * 1e3,
            "scipy_hybr_us": statistics.median(samples) * 1e6}


def batched_attitudes():
    rate, backend = time_batch()
    scene = load_scene(EXAMPLES / "tanker_upright.toml")
    count = 200_000
    rng = np.random.default_rng(3)
    heel, trim = np.radians(rng.uniform(-10, 10, count)), np.radians(rng.uniform(-10, 10, count))
    points, cog, weight = scene.lug_points(), np.array(scene.body.cog), scene.body.weight
    boom = np.array([c.boom_height for c in scene.cranes])
    ea = np.array([c.EA for c in scene.cranes])
    lift = scene.attitude.lift_height

    def numpy_batch():
        ch, sh, ct, st = np.cos(heel), np.sin(heel), np.cos(trim), np.sin(trim)
        # R = Rx(heel) Ry(trim): rows of R applied to each lug
        x = ct[:, None] * points[:, 0] + st[:, None] * points[:, 2]
        z_t = -st[:, None] * points[:, 0] + ct[:, None] * points[:, 2]
        y = ch[:, None] * points[:, 1] - sh[:, None] * z_t
        z = sh[:, None] * points[:, 1] + ch[:, None] * z_t
        cx = ct * cog[0] + st * cog[2]
        czt = -st * cog[0] + ct * cog[2]
        cy = ch * cog[1] - sh * czt
        k = ea / (boom - lift - z)
        phi = np.stack([np.ones_like(x), x, y], axis=2)  # (m, n, 3)
        normal = np.einsum("mni,mn,mnj->mij", phi, k, phi)
        coeff = np.linalg.solve(normal, weight * np.stack([np.ones(count), cx, cy], axis=1)[..., None])
        return k * np.einsum("mni,mi->mn", phi, coeff[..., 0])

    ours = paper_elastic_tensions(scene, np.degrees(heel[:1000]), np.degrees(trim[:1000]))
    assert np.allclose(numpy_batch()[:1000], ours, rtol=1e-9)  # the peer computes the same thing
    numpy_rate = count / median_time(numpy_batch, 3)
    return {"liftplan_per_s": rate, "backend": backend, "numpy_per_s": numpy_rate}


def plans():
    tanker = load_problem(EXAMPLES / "tanker_plan.toml")
    wide = dataclasses.replace(tanker, candidates=forty_candidates(tanker))
    ours = median_time(lambda: plan(tanker), 5)
    brute = median_time(lambda: brute_force(tanker), 1, warm=0)
    forty = median_time(lambda: plan(wide), 1)
    return {"tanker_s": ours, "brute_force_s": brute, "forty_candidates_s": forty,
            "forty_sets": math.comb(40, 4)}


def stranded():
    from scipy.optimize import root

    from liftplan.model.water import WaterSetup, solve_in_water

    barge = load_scene(EXAMPLES / "stranded_barge.toml")
    setup = WaterSetup(barge)
    newton = median_time(lambda: solve_in_water(barge, method="newton", setup=setup), 20)
    paper = median_time(lambda: solve_in_water(barge, method="paper-newton", setup=setup), 20)
    # scipy on the same casadi residual (grounded: two tilts about the contact)
    from liftplan.model.statics import FastCall

    residual = FastCall(setup.model.grounded)
    params = setup.params(setup.start.rotation)
    answer = root(lambda x: residual(x, params)[0], np.zeros(2), method="hybr")
    assert answer.success and np.max(np.abs(residual(answer.x, params)[0])) < 1e-9
    scipy_s = median_time(lambda: root(lambda x: residual(x, params)[0], np.zeros(2), method="hybr"), 20)
    # the root-finding alone, as scipy's: casadi's Newton without the result and its checks
    import casadi as ca

    finder, p_dm = setup.model.grounded_root, ca.DM(params)
    root_only = median_time(lambda: finder(ca.DM.zeros(2), p_dm), 20)
    return {"newton_ms": newton * 1e3, "paper_newton_ms": paper * 1e3, "scipy_hybr_ms": scipy_s * 1e3,
            "newton_root_only_ms": root_only * 1e3}


def lift():
    scene = load_scene(EXAMPLES / "sunken_block_lift.toml")
    curve = load_curve(scene, step=0.25)
    seconds = median_time(lambda: load_curve(scene, step=0.25), 2, warm=0)
    return {"curve_s": seconds, "steps": len(curve.hoist), "per_step_ms": seconds / len(curve.hoist) * 1e3}


def batch_check():
    from dask.distributed import Client, LocalCluster

    from liftplan.planner.batch import run_study
    from liftplan.planner.check import CheckCases, check_plan
    from liftplan.planner.study import load_study

    problem = load_problem(EXAMPLES / "tanker_plan.toml")
    chosen = plan(problem).chosen
    rng = np.random.default_rng(5)
    m = 100_000
    cases = CheckCases(problem.body.weight * rng.uniform(0.95, 1.05, m),
                       np.array(problem.body.cog) + rng.uniform(-1, 1, (m, 3)) * [1.0, 0.5, 0.3],
                       np.full(m, 2.0), np.full(m, 2.0), np.full(m, 20.0))
    one_core = m / median_time(lambda: check_plan(problem, chosen.indices, chosen.preload, cases), 3)
    study = load_study(EXAMPLES / "tanker_check.toml")
    out = OUT / "tmp" / "tanker_check.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=":0",
                      silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        summary = run_study(study, client=client, restart=True, progress=False, output=out)
    return {"in_process_per_s_per_core": one_core, "dask_cases": summary.ran,
            "dask_seconds": summary.seconds, "dask_per_s_per_core": summary.rate_per_core,
            "dask_cores": summary.cores}


def main():
    results = {"machine": f"{platform.machine()}, Python {platform.python_version()}",
               "single_solve": single_solve(), "batched_attitudes": batched_attitudes(),
               "plans": plans(), "stranded": stranded(), "lift": lift(), "batch_check": batch_check()}
    OUT.mkdir(exist_ok=True)
    (OUT / "benchmarks.json").write_text(json.dumps(results, indent=1))
    report(OUT / "benchmarks.json")


def report(path):
    r = json.loads(path.read_text())
    s, b, p, st, lf, bc = (r[k] for k in ("single_solve", "batched_attitudes", "plans", "stranded",
                                          "lift", "batch_check"))
    rows = [
        ("single elastic 4-rope solve, median", f"{s['liftplan_us']:.1f} us",
         f"MoorPy {s['moorpy_ms']:.1f} ms ({s['moorpy_ms'] * 1e3 / s['liftplan_us']:.0f}x); "
         f"scipy hybr {s['scipy_hybr_us']:.0f} us ({s['scipy_hybr_us'] / s['liftplan_us']:.1f}x)"),
        ("batched attitude evaluations, one core", f"{b['liftplan_per_s'] / 1e6:.2f} M/s ({b['backend']})",
         f"numpy stacked solve {b['numpy_per_s'] / 1e6:.2f} M/s "
         f"({b['liftplan_per_s'] / b['numpy_per_s']:.1f}x)"),
        ("tanker plan, 16 candidates, CG box", f"{p['tanker_s']:.2f} s",
         f"brute force {p['brute_force_s']:.1f} s ({p['brute_force_s'] / p['tanker_s']:.0f}x)"),
        (f"40-candidate plan ({p['forty_sets']:,} sets), CG box", f"{p['forty_candidates_s']:.1f} s", "-"),
        ("stranded barge solve (case 1), with result and checks", f"{st['newton_ms']:.2f} ms",
         f"paper's iteration {st['paper_newton_ms']:.2f} ms "
         f"({st['paper_newton_ms'] / st['newton_ms']:.1f}x)"),
        ("stranded barge, root-finding alone", f"{st['newton_root_only_ms']:.2f} ms (casadi Newton)",
         f"scipy hybr on the same residual {st['scipy_hybr_ms']:.2f} ms "
         f"({st['scipy_hybr_ms'] / st['newton_root_only_ms']:.1f}x)"),
        (f"lift load curve, sunken block ({lf['steps']} steps)", f"{lf['curve_s']:.2f} s "
         f"({lf['per_step_ms']:.2f} ms/step)", "-"),
        ("plan evaluations (batch check, 3x3 box), per core",
         f"{bc['in_process_per_s_per_core']:,.0f} /s in process; "
         f"{bc['dask_per_s_per_core']:,.0f} /s on {bc['dask_cores']} Dask workers", "goal 10 000 /s"),
    ]
    lines = [f"Measured on {r['machine']} by `python studies/benchmarks.py`.", "",
             "| figure | liftplan | peer in the same run (ratio) |", "|---|---|---|"]
    lines += [f"| {a} | {b_} | {c} |" for a, b_, c in rows]
    text = "\n".join(lines) + "\n"
    (OUT / "benchmarks.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
