"""Every headline speed figure, measured in one run, with the peers in the same run.

Figures, each with its peer measured in the same run:

* single elastic 4-rope solve, ``solve()`` median; peers MoorPy (build + solve to
  1e-10 m) and scipy ``root`` (hybr) on a numpy residual;
* batched attitude evaluations, ``paper_elastic_tensions`` on one core; peer numpy, the
  same 3x3 systems stacked into ``np.linalg.solve``;
* tanker plan (16 candidates), ``plan()``; peer brute force (every feasible set, same LP);
* tanker with 4 unequal cranes (``examples/tanker_fleet.toml``: 1 820 sets x 24
  assignments), ``plan()``; peer brute force over every set x every crane permutation with
  each crane in reach, each through ``SetEvaluator.evaluate``, and the same optimum checked
  (issue 11's goal: the plan in at most 2 s);
* 40-candidate plan, CG box;
* stranded barge solve, casadi Newton (full solve, and root-finding alone); peers the
  paper's J^T D J iteration and scipy ``root`` (hybr) on the same residual;
* lift load curve of the sunken block, per step;
* plan evaluations (batch check): cases per second per core, in process and on two Dask
  workers; the goal is 10 000.

The figures are medians of several runs after a warm-up. Before timing, the script waits
(up to QUIET_WAIT) for the one-minute load average to fall to QUIET_LOAD or below (the
machine is shared) and records the load it started at.

Run:  python studies/benchmarks.py    (writes studies/out/benchmarks.json and .md)
      python studies/benchmarks.py --only fleet plans   (re-measure those sections; the
      others are kept from the last run's benchmarks.json)
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import logging
import math
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE))
from bench_core import time_batch, time_elastic, time_moorpy, varied_scenes  # noqa: E402
from bench_plan import brute_force, fleet_brute_force, forty_candidates  # noqa: E402
from speed_accuracy import numpy_residual  # noqa: E402

from liftplan.model import load_scene, paper_elastic_tensions  # noqa: E402
from liftplan.model.lift import load_curve  # noqa: E402
from liftplan.planner.plan import plan  # noqa: E402
from liftplan.planner.problem.file import load_problem  # noqa: E402

EXAMPLES = HERE.parent / "examples"
OUT = HERE / "out"
#: Time only when the one-minute load average is at most this; wait at most this long [s].
QUIET_LOAD, QUIET_WAIT = 1.5, 1200.0


def wait_for_quiet(limit=QUIET_LOAD, wait=QUIET_WAIT, poll=30.0):
    """Wait until the one-minute load average is at most ``limit`` (or ``wait`` has passed).

    Returns
    -------
    float
        The load average when timing starts.
    """
    deadline = time.monotonic() + wait
    load = os.getloadavg()[0]
    while load > limit and time.monotonic() < deadline:
        print(f"load average {load:.2f} > {limit}: waiting", file=sys.stderr)
        time.sleep(poll)
        load = os.getloadavg()[0]
    if load > limit:
        print(f"load average still {load:.2f} after {wait:.0f} s: timing anyway", file=sys.stderr)
    return load


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

    from liftplan.model.statics.model import FastCall, rope_model
    from liftplan.model.statics.vertical import pack_params

    scenes = varied_scenes()
    ours = time_elastic(scenes, repeats=50)
    moorpy = time_moorpy(scenes)
    samples = []
    for scene in scenes:
        residual, _ = numpy_residual(scene)
        start = FastCall(rope_model(scene.n).elastic_start)(pack_params(scene, "elastic"))[0]
        samples.append(median_time(lambda r=residual, s=start: root(r, s, method="hybr"), 5))
    return {
        "liftplan_us": ours * 1e6,
        "moorpy_ms": moorpy * 1e3,
        "scipy_hybr_us": statistics.median(samples) * 1e6,
    }


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
    return {
        "tanker_s": ours,
        "brute_force_s": brute,
        "forty_candidates_s": forty,
        "forty_sets": math.comb(40, 4),
    }


def fleet():
    from liftplan.planner.search.evaluator import tolerance

    problem = load_problem(EXAMPLES / "tanker_fleet.toml")
    ours = median_time(lambda: plan(problem), 9)
    result = plan(problem)
    chosen = result.chosen
    brute = fleet_brute_force(problem)
    # the same optimum: the same evaluation of the same rows, so the agreement asked is the
    # search's own (1 kg, in the objective's unit)
    tol = tolerance(problem) / (1.0 if problem.objective == "spread" else float(np.min(chosen.swl)))
    if (
        result.stats.stopped != "proved"
        or brute.best < chosen.worst_value - tol
        or (not brute.sampled and brute.best > chosen.worst_value + tol)
    ):
        raise RuntimeError(
            f"fleet: the plan ({chosen.worst_value!r}, {result.stats.stopped}) is not "
            f"brute force's optimum ({brute.best!r})"
        )
    sets = math.comb(len(problem.candidates), problem.cranes)
    return {
        "plan_s": ours,
        "objective": problem.objective,
        "sets": sets,
        "assignments": math.factorial(problem.cranes),
        "rows": brute.rows,
        "rows_in_reach": brute.in_reach,
        "planner_rows": result.stats.rows,
        "planner_evaluated": result.stats.evaluated,
        "plan_best": chosen.worst_value,
        "plan_lugs": list(chosen.lugs),
        "plan_cranes": list(chosen.crane_names),
        "brute_force_s": brute.estimated_seconds,
        "brute_force_measured_s": brute.seconds,
        "brute_force_evaluated": brute.evaluated,
        "brute_force_sampled": brute.sampled,
        "brute_force_feasible": brute.feasible,
        "brute_force_collinear": brute.collinear,
        "brute_force_collinear_error": brute.collinear_error,
        "brute_force_best": brute.best,
        "brute_force_best_lugs": [problem.names[i] for i in brute.best_row[0]],
        "brute_force_best_cranes": [problem.fleet[j].name for j in brute.best_row[1]],
        "same_optimum": not brute.sampled,
    }


def stranded():
    from scipy.optimize import root

    from liftplan.model.water import WaterSetup, solve_in_water

    barge = load_scene(EXAMPLES / "stranded_barge.toml")
    setup = WaterSetup(barge)
    newton = median_time(lambda: solve_in_water(barge, method="newton", setup=setup), 20)
    paper = median_time(lambda: solve_in_water(barge, method="paper-newton", setup=setup), 20)
    # scipy on the same casadi residual (grounded: two tilts about the contact)
    from liftplan.model.statics.model import FastCall

    residual = FastCall(setup.model.grounded)
    params = setup.params(setup.start.rotation)
    answer = root(lambda x: residual(x, params)[0], np.zeros(2), method="hybr")
    assert answer.success and np.max(np.abs(residual(answer.x, params)[0])) < 1e-9
    scipy_s = median_time(lambda: root(lambda x: residual(x, params)[0], np.zeros(2), method="hybr"), 20)
    # the root-finding alone, as scipy's: casadi's Newton without the result and its checks
    import casadi as ca

    finder, p_dm = setup.model.grounded_root, ca.DM(params)
    root_only = median_time(lambda: finder(ca.DM.zeros(2), p_dm), 20)
    return {
        "newton_ms": newton * 1e3,
        "paper_newton_ms": paper * 1e3,
        "scipy_hybr_ms": scipy_s * 1e3,
        "newton_root_only_ms": root_only * 1e3,
    }


def lift():
    scene = load_scene(EXAMPLES / "sunken_block_lift.toml")
    curve = load_curve(scene, step=0.25)
    seconds = median_time(lambda: load_curve(scene, step=0.25), 2, warm=0)
    return {"curve_s": seconds, "steps": len(curve.hoist), "per_step_ms": seconds / len(curve.hoist) * 1e3}


def batch_check():
    from dask.distributed import Client, LocalCluster

    from liftplan.planner.batch.check import CheckCases, check_plan
    from liftplan.planner.batch.run import run_study
    from liftplan.planner.batch.study import load_study

    problem = load_problem(EXAMPLES / "tanker_plan.toml")
    chosen = plan(problem).chosen
    rng = np.random.default_rng(5)
    m = 100_000
    cases = CheckCases(
        problem.body.weight * rng.uniform(0.95, 1.05, m),
        np.array(problem.body.cog) + rng.uniform(-1, 1, (m, 3)) * [1.0, 0.5, 0.3],
        np.full(m, 2.0),
        np.full(m, 2.0),
        np.full(m, 20.0),
    )
    one_core = m / median_time(lambda: check_plan(problem, chosen.indices, chosen.preload, cases), 3)
    study = load_study(EXAMPLES / "tanker_check.toml")
    out = OUT / "tmp" / "tanker_check.csv"
    out.parent.mkdir(parents=True, exist_ok=True)
    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, dashboard_address=":0", silence_logs=logging.ERROR
        ) as cluster,
        Client(cluster) as client,
    ):
        summary = run_study(study, client=client, restart=True, progress=False, output=out)
    return {
        "in_process_per_s_per_core": one_core,
        "dask_cases": summary.ran,
        "dask_seconds": summary.seconds,
        "dask_per_s_per_core": summary.rate_per_core,
        "dask_cores": summary.cores,
    }


SECTIONS = {
    "single_solve": single_solve,
    "batched_attitudes": batched_attitudes,
    "plans": plans,
    "fleet": fleet,
    "stranded": stranded,
    "lift": lift,
    "batch_check": batch_check,
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--only",
        nargs="+",
        choices=list(SECTIONS),
        default=list(SECTIONS),
        help="sections to measure (the others are kept from the last run)",
    )
    args = parser.parse_args()
    path = OUT / "benchmarks.json"
    results = json.loads(path.read_text()) if set(args.only) != set(SECTIONS) and path.exists() else {}
    results["machine"] = f"{platform.machine()}, Python {platform.python_version()}"
    results.setdefault("load_average", {})
    for name in args.only:
        start = wait_for_quiet()
        results[name] = SECTIONS[name]()
        results["load_average"][name] = {"start": start, "end": os.getloadavg()[0]}
    OUT.mkdir(exist_ok=True)
    path.write_text(json.dumps(results, indent=1))
    report(path)


def report(path):
    r = json.loads(path.read_text())
    s, b, p, st, lf, bc = (
        r[k] for k in ("single_solve", "batched_attitudes", "plans", "stranded", "lift", "batch_check")
    )
    fl = r.get("fleet")
    rows = [
        (
            "single elastic 4-rope solve, median",
            f"{s['liftplan_us']:.1f} us",
            f"MoorPy {s['moorpy_ms']:.1f} ms ({s['moorpy_ms'] * 1e3 / s['liftplan_us']:.0f}x); "
            f"scipy hybr {s['scipy_hybr_us']:.0f} us ({s['scipy_hybr_us'] / s['liftplan_us']:.1f}x)",
        ),
        (
            "batched attitude evaluations, one core",
            f"{b['liftplan_per_s'] / 1e6:.2f} M/s ({b['backend']})",
            f"numpy stacked solve {b['numpy_per_s'] / 1e6:.2f} M/s "
            f"({b['liftplan_per_s'] / b['numpy_per_s']:.1f}x)",
        ),
        (
            "tanker plan, 16 candidates, CG box",
            f"{p['tanker_s']:.2f} s",
            f"brute force {p['brute_force_s']:.1f} s ({p['brute_force_s'] / p['tanker_s']:.0f}x)",
        ),
        (f"40-candidate plan ({p['forty_sets']:,} sets), CG box", f"{p['forty_candidates_s']:.1f} s", "-"),
    ]
    if fl is not None:
        brute = "brute force" + (" (sampled, extrapolated)" if fl["brute_force_sampled"] else "")
        rows.append(
            (
                f"tanker, 4 unequal cranes, 16 candidates ({fl['sets']:,} sets x {fl['assignments']} "
                f"assignments), objective {fl['objective']}",
                f"{fl['plan_s']:.2f} s ({fl['planner_evaluated']} of {fl['planner_rows']:,} rows in reach "
                "evaluated); goal 2 s",
                f"{brute} over {fl['rows_in_reach']:,} (set, assignment) rows in reach of {fl['rows']:,}: "
                f"{fl['brute_force_s']:.1f} s ({fl['brute_force_s'] / fl['plan_s']:.0f}x)"
                + ("; same optimum" if fl["same_optimum"] else ""),
            )
        )
    rows += [
        (
            "stranded barge solve (case 1), with result and checks",
            f"{st['newton_ms']:.2f} ms",
            f"paper's iteration {st['paper_newton_ms']:.2f} ms "
            f"({st['paper_newton_ms'] / st['newton_ms']:.1f}x)",
        ),
        (
            "stranded barge, root-finding alone",
            f"{st['newton_root_only_ms']:.2f} ms (casadi Newton)",
            f"scipy hybr on the same residual {st['scipy_hybr_ms']:.2f} ms "
            f"({st['scipy_hybr_ms'] / st['newton_root_only_ms']:.1f}x)",
        ),
        (
            f"lift load curve, sunken block ({lf['steps']} steps)",
            f"{lf['curve_s']:.2f} s ({lf['per_step_ms']:.2f} ms/step)",
            "-",
        ),
        (
            "plan evaluations (batch check, 3x3 box), per core",
            f"{bc['in_process_per_s_per_core']:,.0f} /s in process; "
            f"{bc['dask_per_s_per_core']:,.0f} /s on {bc['dask_cores']} Dask workers",
            "goal 10 000 /s",
        ),
    ]
    loads = r.get("load_average", {})
    quiet = (
        " (one-minute load average at the start and end of each section: "
        + ", ".join(f"{k} {v['start']:.2f} / {v['end']:.2f}" for k, v in loads.items())
        + ")"
        if loads
        else ""
    )
    lines = [
        f"Measured on {r['machine']} by `python studies/benchmarks.py`{quiet}.",
        "",
        "| figure | liftplan | peer in the same run (ratio) |",
        "|---|---|---|",
    ]
    lines += [f"| {a} | {b_} | {c} |" for a, b_, c in rows]
    text = "\n".join(lines) + "\n"
    (OUT / "benchmarks.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
