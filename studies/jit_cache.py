"""What the compile cache saves (liftplan.model.statics.compiled): the first process compiles the
batched casadi maps to C, every later process loads the library.

Measured in fresh processes, each with its own cache, temporary and working folder:

* ``build``: building the 4-rope model's three batched maps in one process (the symbolic
  model, code generation, and the compile or the load), as ``plan`` and ``batch`` workers
  do; import time excluded. Modes: ``cold`` (empty cache: compile), ``warm`` (cache
  filled by an earlier process: load), ``casadi_jit`` (the former path: casadi's own JIT,
  which compiles in every process), ``vm`` (no compiler: casadi's virtual machine).
* ``plan_cli``: wall time of the whole command ``liftplan plan examples/tanker_plan.toml``
  with a cold and with a warm cache.

Also counted: files left in the temporary and working folders, by processes that end
normally and by processes that end without clean-up (``os._exit``, as a Dask worker that
is killed at shutdown), and what the cache holds.
Figures are medians of ``REPEAT`` processes (each process builds once, so every run is a
first call); the machine is shared, so expect a few per cent of noise.

Run:  python studies/jit_cache.py   (about a minute; writes studies/out/jit_cache.json)
"""

from __future__ import annotations

import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

import casadi as ca

from liftplan.model.statics import compiled

HERE = Path(__file__).parent
EXAMPLES = HERE.parent / "examples"
OUT = HERE / "out" / "jit_cache.json"
REPEAT = 5

BUILD = textwrap.dedent("""
    import json, time
    import casadi as ca
    from liftplan.model.statics.model import rope_model
    begin = time.perf_counter()
    model = rope_model(4)
    model.held_block, model.held_columns, model.paper_elastic_block
    print(json.dumps({"seconds": time.perf_counter() - begin, "backend": model.batch_backend}), flush=True)
""")

# The former path (model/statics/model.py before the cache): casadi's JIT compiles each column in
# every process, sources and libraries in a folder of the temporary folder.
CASADI_JIT = textwrap.dedent("""
    import json, tempfile, time
    import casadi as ca
    from liftplan.model.statics.model import BLOCK, rope_model
    begin = time.perf_counter()
    model = rope_model(4)
    folder = tempfile.mkdtemp(prefix="liftplan-jit-") + "/"
    for function, shared in ((model.held, [1]), (model.held, []), (model.paper_elastic, [1])):
        x, p = ca.SX.sym("x", 3), ca.SX.sym("p", model.layout.size)
        column = ca.Function(function.name() + "_jit", [x, p], list(function(x, p)),
                             {"jit": True, "compiler": "shell",
                              "jit_options": {"flags": ["-O2"], "verbose": False, "directory": folder}})
        column.map(function.name() + "_block", "serial", BLOCK, shared, [])
    print(json.dumps({"seconds": time.perf_counter() - begin, "backend": "casadi-jit"}), flush=True)
""")


def run(workspace, args, cc=None):
    """Run one process in ``workspace`` (its cache, tmp and work folders); (wall s, stdout)."""
    env = dict(os.environ, LIFTPLAN_CACHE=str(workspace / "cache"), TMPDIR=str(workspace / "tmp"))
    if cc is not None:
        env["CC"] = cc
    begin = time.perf_counter()
    result = subprocess.run(args, cwd=workspace / "work", env=env, capture_output=True, text=True)
    wall = time.perf_counter() - begin
    if result.returncode != 0:
        raise SystemExit(f"{' '.join(args)} failed: {result.stderr.strip()}")
    return wall, result.stdout


def fresh(root, name):
    workspace = root / name
    shutil.rmtree(workspace, ignore_errors=True)
    for sub in ("cache", "tmp", "work"):
        (workspace / sub).mkdir(parents=True)
    return workspace


def summary(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values), "runs": len(values)}


def leftovers(workspace):
    """Files left in the temporary and working folders after the runs."""
    return sum(1 for sub in ("tmp", "work") for p in (workspace / sub).rglob("*") if p.is_file())


def measure(root):
    python = [sys.executable, "-c"]
    liftplan = shutil.which("liftplan")
    plan_cmd = ([liftplan] if liftplan else [sys.executable, "-m", "liftplan.planner.cli"]) + [
        "plan",
        str(EXAMPLES / "tanker_plan.toml"),
    ]
    build, plan, backends, left = {}, {}, {}, {}

    def build_times(mode, code, cc=None, cold=False):
        workspace = fresh(root, mode)
        if not cold:  # fill the cache first (and keep the output of that run out of the figures)
            run(workspace, python + [code], cc)
        times = []
        for _ in range(REPEAT):
            if cold:
                shutil.rmtree(workspace / "cache", ignore_errors=True)
            wall, out = run(workspace, python + [code], cc)
            record = json.loads(out)
            times.append(record["seconds"])
            backends[mode] = record["backend"]
        left[mode] = leftovers(workspace)
        return summary(times)

    build["cold"] = build_times("cold", BUILD, cold=True)
    build["warm"] = build_times("warm", BUILD)
    build["casadi_jit"] = build_times("casadi_jit", CASADI_JIT, cold=True)
    build["vm"] = build_times("vm", BUILD, cc="")
    for mode, code in (("cold", BUILD), ("casadi_jit", CASADI_JIT)):
        workspace = fresh(root, f"killed_{mode}")
        run(workspace, python + [code + "import os; os._exit(0)\n"])
        left[f"killed_{mode}"] = leftovers(workspace)

    # cold and warm runs alternate, so that a change in the shared machine's load hits both
    spaces = {mode: fresh(root, f"plan_{mode}") for mode in ("cold", "warm")}
    run(spaces["warm"], plan_cmd)
    times = {"cold": [], "warm": []}
    for _ in range(REPEAT):
        shutil.rmtree(spaces["cold"] / "cache", ignore_errors=True)
        for mode, workspace in spaces.items():
            times[mode].append(run(workspace, plan_cmd)[0])
    for mode, workspace in spaces.items():
        plan[mode] = summary(times[mode])
        left[f"plan_{mode}"] = leftovers(workspace)
    cache = [p for p in (spaces["warm"] / "cache").rglob("*") if p.is_file()]
    held = {
        "files": len(cache),
        "bytes": sum(p.stat().st_size for p in cache),
        "libraries": sorted(p.name for p in cache if p.suffix == ".so"),
    }
    return {
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
        "casadi": ca.__version__,
        "compiler": compiled.compiler(),
        "repeat": REPEAT,
        "command": "liftplan plan examples/tanker_plan.toml",
        "build_seconds": build,
        "backends": backends,
        "plan_cli_seconds": plan,
        "saving": {
            "build_seconds_per_process": build["cold"]["median"] - build["warm"]["median"],
            "build_seconds_vs_casadi_jit": build["casadi_jit"]["median"] - build["warm"]["median"],
            "plan_cli_seconds_per_process": plan["cold"]["median"] - plan["warm"]["median"],
        },
        "files_left_in_temp_and_working_folder": left,
        "cache_after_plan": held,
    }


def main():
    if compiled.compiler() is None:
        raise SystemExit("no C compiler on this machine: nothing to cache")
    with tempfile.TemporaryDirectory(prefix="liftplan-jit-study-") as root:
        result = measure(Path(root))
    OUT.parent.mkdir(exist_ok=True)
    OUT.write_text(json.dumps(result, indent=2) + "\n")
    b, p = result["build_seconds"], result["plan_cli_seconds"]
    print(
        f"build of the 4-rope batched maps (median of {REPEAT} processes): cold cache "
        f"{b['cold']['median']:.3f} s, warm {b['warm']['median']:.3f} s, casadi's JIT every "
        f"process {b['casadi_jit']['median']:.3f} s, VM {b['vm']['median']:.3f} s"
    )
    print(f"{result['command']}: cold cache {p['cold']['median']:.2f} s, warm {p['warm']['median']:.2f} s")
    print(f"files left in temp/working folders: {result['files_left_in_temp_and_working_folder']}")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
