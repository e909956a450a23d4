"""Many ropes: single-solve time against the rope count n = 4 ... 64, for the three rope
models, beside independent peers in the same run.

Scenes: the 154 m hull of ``examples/hull154_26_points.toml`` with n / 2 lifting points a
side spread over the same 132 m (``tests/support/many_points_peer.hull_scene(n // 2, seed=1)``: an
uneven hoist, every rope taut); n = 26 is the example's layout, n = 64 its 64-point
variant. ``rigid`` holds every lug but three (P01, the last port lug, the middle starboard
one) at the paper-elastic tensions rounded to the tonne.

Measured, for liftplan (``solve(scene, model)``, the whole user call: packing, solve,
acceptance, result):

* per solve: median over repeats once the functions for this n exist;
* first call, cold: the first solve in a fresh Python process (liftplan imported and the
  scene made, nothing solved yet): casadi's plugin loading plus this n's functions; median
  over fresh processes;
* first call, build: the first solve at this n in a process that has solved before (the
  per-n cache emptied): building this n's casadi functions alone; median of repeats;
* the batched column maps at each n, compiled to C with an empty cache, then loaded from
  the cache in a fresh process: the paper-elastic map (``paper_elastic_tensions``, with its
  cost per attitude), the held-preload map with its n x n sensitivities dT/dH
  (``held_columns``: planner screening) and without them (``held_tensions_columns``: what a
  check of a fixed plan needs).

Peers (``tests/support/many_points_peer.py``, written from the physics): ``elastic`` against
``scipy.optimize.root`` (MINPACK hybr, finite-difference Jacobian) on a numpy residual and
against MoorPy (build + 6-DOF quasi-static solve to 1e-10 m, as ``tests/support/moorpy_peer.py``);
``paper-elastic`` against numpy least squares on the (n + 3)-unknown system; ``rigid``
against numpy least squares on [A; held rows]. Accuracy: max |T - T_peer| / W.

Timing waits while the 1-minute load average is above 1.5 (the machine is shared) and
records the load.

Run:  python studies/many_points.py            (~3 minutes, more while the load waits;
                                                 writes studies/out/many_points.json, then
                                                 draws studies/out/many_points.png from it)
      python studies/many_points.py --plot     (redraw the figure from the JSON)
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
OUT = HERE / "out"
sys.path.insert(0, str(HERE.parent / "tests"))
from support.many_points_peer import (  # noqa: E402
    held_scene,
    hull_scene,
    numpy_elastic,
    numpy_paper_elastic,
    numpy_rigid,
)

from liftplan.model import paper_elastic_tensions, solve  # noqa: E402
from liftplan.model.statics.model import BLOCK, rope_model  # noqa: E402

COUNTS = [4, 8, 12, 26, 64]
MODELS = ["elastic", "paper-elastic", "rigid"]
COLD_PROCESSES = 5
#: Batched column maps timed (compile, then load): paper-elastic tensions; the held-preload
#: tensions with their n x n sensitivities (planner screening) and without (a plan's check).
BATCH_MAPS = ["paper_elastic_block", "held_columns", "held_tensions_columns"]
MAX_LOAD = 1.5


def scene_for(n, model):
    scene = hull_scene(n // 2, seed=1)
    if model == "rigid":
        paper = solve(scene, model="paper-elastic")
        return held_scene(scene, {k: float(round(t)) for k, t in paper.tensions.items()})
    return scene.with_analysis(model=model)


def wait_for_quiet(log):
    """Sleep while the 1-minute load average is above MAX_LOAD (at most 10 minutes)."""
    waited = 0.0
    while os.getloadavg()[0] > MAX_LOAD and waited < 600.0:
        time.sleep(15.0)
        waited += 15.0
    log.append({"time": time.time(), "load_1min": os.getloadavg()[0], "waited_s": waited})


def median_time(call, budget=0.5, least=5, most=300):
    """Median wall time of ``call`` [s]: repeats until ``budget`` s or ``most`` calls."""
    times, spent = [], 0.0
    while len(times) < least or (spent < budget and len(times) < most):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
        spent += times[-1]
    return statistics.median(times)


def tensions(eq, scene):
    return np.array([eq.tensions[name] for name in scene.lug_names])


# -- first calls -----------------------------------------------------------------------------
def worker_cold(model, n):
    """In a fresh process: seconds of the first solve (printed as JSON)."""
    scene = scene_for(n, model)  # rigid: its held tensions come from a solve before the clock starts
    rope_model.cache_clear()
    start = time.perf_counter()
    solve(scene, model)
    print(json.dumps({"seconds": time.perf_counter() - start}))


def worker_batch(n, stage):
    """In a fresh process (cache folder from $LIFTPLAN_CACHE): make the batched maps."""
    scene = hull_scene(n // 2, seed=1)
    model = rope_model(n)
    seconds = {}
    for name in BATCH_MAPS:
        start = time.perf_counter()
        getattr(model, name)
        seconds[name] = time.perf_counter() - start
    heel = np.linspace(-2.0, 2.0, 4 * BLOCK)
    trim = np.linspace(1.0, -1.0, 4 * BLOCK)
    per_attitude = median_time(lambda: paper_elastic_tensions(scene, heel, trim), least=3) / heel.size
    print(
        json.dumps(
            {
                "stage": stage,
                "seconds": seconds,
                "backend": model.batch_backend,
                "per_attitude_s": per_attitude,
            }
        )
    )


def run_worker(*args, env=None):
    out = subprocess.run(
        [sys.executable, __file__, "--worker", *map(str, args)],
        capture_output=True,
        text=True,
        timeout=600,
        env=env,
        check=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def build_time(model, n):
    """First solve at n in a warm process, the per-n cache emptied: median of 5  [s]."""
    scene = scene_for(n, model)
    times = []
    for _ in range(5):
        rope_model.cache_clear()
        start = time.perf_counter()
        solve(scene, model)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


# -- measurement -------------------------------------------------------------------------------
def peers(model, scene):
    """(name, call returning tensions in lug order, repeats budget) of each peer of a model."""
    if model == "elastic":
        from support.moorpy_peer import moorpy_solve

        eq = solve(scene, model)
        pose = eq.pose
        return [
            ("scipy root", lambda: numpy_elastic(scene)[1], 0.5),
            ("MoorPy", lambda: moorpy_solve(scene, pose.heel, pose.trim, pose.lift_height)[0], 2.0),
        ]
    if model == "paper-elastic":
        return [("numpy lstsq", lambda: numpy_paper_elastic(scene), 0.5)]
    return [("numpy lstsq", lambda: numpy_rigid(scene), 0.5)]


def measure(log):
    rows = []
    for model in MODELS:
        for n in COUNTS:
            wait_for_quiet(log)
            scene = scene_for(n, model)
            eq = solve(scene, model)
            cold = statistics.median(run_worker("cold", model, n)["seconds"] for _ in range(COLD_PROCESSES))
            build = build_time(model, n)
            solve(scene, model)
            per = median_time(lambda scene=scene, model=model: solve(scene, model))
            rows.append(
                {
                    "model": model,
                    "n": n,
                    "method": "liftplan",
                    "per_solve_s": per,
                    "first_cold_s": cold,
                    "first_build_s": build,
                    "max_error_over_W": 0.0,
                    "solver": eq.solver.method,
                    "residual_t": eq.residual,
                }
            )
            ours = tensions(eq, scene)
            for name, call, budget in peers(model, scene):
                theirs = call()
                error = float(np.max(np.abs(ours - theirs)) / scene.body.weight)
                rows.append(
                    {
                        "model": model,
                        "n": n,
                        "method": name,
                        "per_solve_s": median_time(call, budget=budget, least=3),
                        "max_error_over_W": error,
                    }
                )
            print(
                f"{model:>13} n={n:>2}: per solve {1e3 * per:.3f} ms, first cold {cold:.3f} s, "
                f"build {1e3 * build:.1f} ms; peers "
                + ", ".join(
                    f"{r['method']} {1e3 * r['per_solve_s']:.2f} ms (err {r['max_error_over_W']:.1e} W)"
                    for r in rows
                    if r["model"] == model and r["n"] == n and r["method"] != "liftplan"
                ),
                flush=True,
            )
    return rows


def measure_batch(log):
    rows = []
    for n in COUNTS:
        wait_for_quiet(log)
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ, LIFTPLAN_CACHE=cache)
            compiled = run_worker("batch", n, "compile", env=env)
            loaded = run_worker("batch", n, "load", env=env)
        for name in BATCH_MAPS:
            rows.append(
                {
                    "n": n,
                    "map": name,
                    "backend": compiled["backend"],
                    "compile_s": compiled["seconds"][name],
                    "load_s": loaded["seconds"][name],
                }
            )
            print(
                f"batched {name} n={n:>2}: compile {compiled['seconds'][name]:.2f} s, "
                f"load {loaded['seconds'][name]:.3f} s ({compiled['backend']})",
                flush=True,
            )
        rows[-len(BATCH_MAPS)]["per_attitude_s"] = loaded["per_attitude_s"]
        print(
            f"paper_elastic_tensions n={n:>2}: {1e9 * loaded['per_attitude_s']:.0f} ns/attitude", flush=True
        )
    return rows


# -- figure ------------------------------------------------------------------------------------
COLOURS = {"elastic": "tab:blue", "paper-elastic": "tab:orange", "rigid": "tab:green"}
PEER_STYLE = {"scipy root": ("--", "s"), "MoorPy": (":", "^"), "numpy lstsq": ("--", "s")}


def draw(data):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = data["rows"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5), constrained_layout=True)
    for model in MODELS:
        mine = [r for r in rows if r["model"] == model and r["method"] == "liftplan"]
        left.plot(
            [r["n"] for r in mine],
            [1e3 * r["per_solve_s"] for r in mine],
            "-o",
            color=COLOURS[model],
            label=f"{model}: liftplan",
        )
        names = dict.fromkeys(r["method"] for r in rows if r["model"] == model)
        for name in [name for name in names if name != "liftplan"]:
            theirs = [r for r in rows if r["model"] == model and r["method"] == name]
            line, marker = PEER_STYLE[name]
            left.plot(
                [r["n"] for r in theirs],
                [1e3 * r["per_solve_s"] for r in theirs],
                line,
                marker=marker,
                color=COLOURS[model],
                alpha=0.7,
                label=f"{model}: {name}",
            )
        right.plot(
            [r["n"] for r in mine],
            [1e3 * r["first_cold_s"] for r in mine],
            "-o",
            color=COLOURS[model],
            label=f"{model}: first call, fresh process",
        )
        right.plot(
            [r["n"] for r in mine],
            [1e3 * r["first_build_s"] for r in mine],
            "--o",
            color=COLOURS[model],
            alpha=0.7,
            label=f"{model}: building this n's functions",
        )
    for name, colour, label in (
        ("paper_elastic_block", "tab:red", "paper-elastic map"),
        ("held_columns", "tab:purple", "held map with dT/dH"),
        ("held_tensions_columns", "tab:brown", "held map, tensions only"),
    ):
        batch = [r for r in data["batch"] if r["map"] == name]
        right.plot(
            [r["n"] for r in batch],
            [1e3 * r["compile_s"] for r in batch],
            "-D",
            color=colour,
            label=f"batched {label}: C compile (empty cache)",
        )
        right.plot(
            [r["n"] for r in batch],
            [1e3 * r["load_s"] for r in batch],
            "--D",
            color=colour,
            alpha=0.7,
            label=f"batched {label}: load from the cache",
        )
    for ax, title in (
        (left, "per solve (median of repeats)"),
        (right, "first call: construction and compile"),
    ):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks(COUNTS, [str(n) for n in COUNTS])
        ax.minorticks_off()
        ax.set_xlabel("ropes n")
        ax.set_ylabel("wall time [ms]")
        ax.set_title(title)
        ax.grid(True, which="major", alpha=0.3)
        low, high = ax.get_ylim()
        ax.set_ylim(low, high * 30)  # room above the curves for the legend
        ax.legend(fontsize=7, loc="upper left")
    load = max(entry["load_1min"] for entry in data["load"])
    fig.suptitle(
        f"liftplan solve with many ropes (154 m hull), one process on {data['machine']}; "
        f"1-min load average at most {load:.2f} while timing"
    )
    fig.savefig(OUT / "many_points.png", dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plot", action="store_true", help="only redraw the figure from the JSON")
    parser.add_argument("--worker", nargs="+", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        kind, *rest = args.worker
        if kind == "cold":
            worker_cold(rest[0], int(rest[1]))
        else:
            worker_batch(int(rest[0]), rest[1])
        return
    path = OUT / "many_points.json"
    if not args.plot:
        log = []
        rows = measure(log)
        batch = measure_batch(log)
        OUT.mkdir(exist_ok=True)
        data = {
            "machine": f"{platform.machine()}, {os.cpu_count()} cores",
            "counts": COUNTS,
            "rows": rows,
            "batch": batch,
            "load": log,
        }
        path.write_text(json.dumps(data, indent=1))
    draw(json.loads(path.read_text()))


if __name__ == "__main__":
    main()
