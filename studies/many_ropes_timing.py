"""Single-solve times of the many-point examples, as a user meets them: the 154 m hull on
26 strand jacks (examples/hull154_26_points.toml) and on 64 (hull154_64_points.toml), with
``elastic``, ``paper-elastic`` and ``rigid``.

Per example and model:

* command: ``liftplan solve FILE --model M --json`` as a whole process (Python start,
  imports, reading the file, building the casadi functions, the solve, the output): wall
  time, median of 5 processes;
* cold, in a fresh process (median of 5 processes): importing liftplan and reading the
  scene (``load_scene``), then the first ``solve`` -- building this n's casadi model
  (symbolic graph, functions, Newton root-finder) and solving once;
* warm: ``solve`` again in that process, the model built: median of repeats (at least 50
  calls or 0.5 s).

studies/many_points.py measures the same models on seeded scenes for n = 4 ... 64 beside
independent peers; this script is the examples' user-facing view (command and cold start).

    python studies/many_ropes_timing.py     # prints the table; studies/out/many_ropes_timing.json

Wall times on a shared 2-core machine: read them as upper figures.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "studies" / "out"
EXAMPLES = {
    26: ROOT / "examples" / "hull154_26_points.toml",
    64: ROOT / "examples" / "hull154_64_points.toml",
}
MODELS = ["elastic", "paper-elastic", "rigid"]
PROCESSES = 5


def worker(path, model):
    """In a fresh process: seconds to import and read, of the first solve, and warm median."""
    start = time.perf_counter()
    from liftplan.model import load_scene, solve

    scene = load_scene(path)
    loaded = time.perf_counter() - start
    start = time.perf_counter()
    eq = solve(scene, model)
    first = time.perf_counter() - start
    times = []
    while len(times) < 50 or sum(times) < 0.5:
        start = time.perf_counter()
        solve(scene, model)
        times.append(time.perf_counter() - start)
    print(
        json.dumps(
            {
                "load_s": loaded,
                "first_solve_s": first,
                "warm_s": statistics.median(times),
                "warm_calls": len(times),
                "residual_t": eq.residual,
                "n": scene.n,
            }
        )
    )


def in_process(path, model):
    out = subprocess.run(
        [sys.executable, __file__, "--worker", str(path), model],
        check=True,
        capture_output=True,
        text=True,
        timeout=300,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def command(path, model):
    start = time.perf_counter()
    subprocess.run(
        ["liftplan", "solve", str(path), "--model", model, "--json"],
        check=True,
        capture_output=True,
        timeout=300,
    )
    return time.perf_counter() - start


def measure():
    rows = []
    for n, path in EXAMPLES.items():
        for model in MODELS:
            runs = [in_process(path, model) for _ in range(PROCESSES)]
            row = {
                "n": n,
                "model": model,
                "example": path.name,
                "command_s": statistics.median(command(path, model) for _ in range(PROCESSES)),
                **{
                    key: statistics.median(r[key] for r in runs)
                    for key in ("load_s", "first_solve_s", "warm_s")
                },
                "residual_t": max(r["residual_t"] for r in runs),
            }
            rows.append(row)
            print(f"n={n} {model}: done", file=sys.stderr, flush=True)
    return rows


def table(rows):
    lines = [
        "| ropes | model | `liftplan solve` (process) | import + read | first solve (model build) "
        "| solve, built |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['n']} | {r['model']} | {r['command_s']:.2f} s | {r['load_s']:.2f} s | "
            f"{1e3 * r['first_solve_s']:.1f} ms | {1e3 * r['warm_s']:.3f} ms |"
        )
    return "\n".join(lines)


def main():
    if sys.argv[1:2] == ["--worker"]:
        worker(sys.argv[2], sys.argv[3])
        return
    rows = measure()
    OUT.mkdir(parents=True, exist_ok=True)
    data = {
        "machine": f"{os.cpu_count()} cores, shared with other work (upper figures)",
        "load_1min_after": os.getloadavg()[0],
        "processes": PROCESSES,
        "rows": rows,
    }
    (OUT / "many_ropes_timing.json").write_text(json.dumps(data, indent=1))
    print(table(rows))
    print(
        f"(median of {PROCESSES} processes each; 1-min load average at the end "
        f"{data['load_1min_after']:.2f} on {data['machine']})"
    )


if __name__ == "__main__":
    main()
