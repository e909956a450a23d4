"""The continuous sweep of a 0-180 deg block turnover against a brute-force fine grid, and
the lug planning over 20 candidates against sweeping every assignment.

Issue 26 asks for the 0-180 deg turnover of a block on two cranes with 2-leg slings swept
continuously (every hook load, lug load and sling-leg tension at its maximum over the whole
range of angles) in under 2 s. The case is ``examples/block_turnover.toml`` (two crawlers,
2-leg slings, the sling of one moved to other padeyes at 90 deg: two stages, 0-90 and 90-180
deg, 10 deg grid). In the same run, the same maxima are taken from a brute-force grid of
0.001 deg (180 001 equilibria), today's way of being sure between the steps: the ratio of the
two wall times is the figure of merit (seconds depend on the machine and its load; the ratio
much less), and the largest difference of the maxima says how far the continuous search is
from the brute-force grid's answer. Each method is timed REPEAT times, the best kept.

The planning case is ``examples/block_turnover_plan.toml``: crawler B's four padeyes each on
one of five candidates (20 strong points, 625 assignments). The planner sweeps in the order of
the grid bounds and stops when no bound is below its best; the reference sweeps every
assignment in full (each distinct stage once: 25 + 25 stage sweeps) and ranks them the same
way. Both must choose the same padeyes; the ratio of their times is reported.

Run:  python studies/sequence_speed.py        (studies/out/sequence_speed.json, .md)
"""

from __future__ import annotations

import json
import platform
import time
from pathlib import Path

import numpy as np

from liftplan.model.sequence import load_sequence, run_sequence
from liftplan.model.sequence.file import load_lug_choice
from liftplan.model.sequence.lugplan import _rank, assignments, plan_lugs, worst_design_load
from liftplan.model.sequence.sweep import StageModel, run_stage

HERE = Path(__file__).parent
OUT = HERE / "out"
CASE = HERE.parent / "examples" / "block_turnover.toml"
PLANNING = HERE.parent / "examples" / "block_turnover_plan.toml"
#: Brute-force grid  [deg].
FINE = 0.001
#: Timings kept: the best of this many.
REPEAT = 3


def brute_force(sequence):
    """Each stage's maxima from a grid of FINE deg: {stage: {load: (value, angle)}}."""
    out = {}
    for stage in sequence.stages:
        model = StageModel(sequence, stage)
        lo, hi = sorted((stage.start, stage.stop))
        best = {}
        for angle in np.linspace(lo, hi, int(round((hi - lo) / FINE)) + 1):
            for key, value in model(angle)[1].items():
                if key.startswith("_"):
                    continue
                if key not in best or value > best[key][0]:
                    best[key] = (value, float(angle))
        out[stage.where] = best
    return out


def every_assignment(choice):
    """Sweep every assignment (each distinct stage once); the best as the planner ranks."""
    placed = {name for name, _ in choice.open}
    cache, best = {}, None
    for chosen in assignments(choice):
        seq = choice.sequence(chosen)
        stages = []
        for stage in seq.stages:
            held = sorted({g for k in stage.cranes for g in seq.crane(k).lugs} & placed)
            key = (stage.where, tuple(chosen[n] for n in held))
            if key not in cache:
                cache[key] = run_stage(seq, stage)
            stages.append(cache[key])
        worst, _, mine = worst_design_load({s.stage.where: s.design for s in stages}, placed)
        ok = all(c.ok for s in stages for c in s.checks)
        rank = (not ok, *_rank(worst, *mine))
        if best is None or rank < best[0]:
            best = (rank, chosen)
    return best[1], len(cache)


def planning():
    choice = load_lug_choice(PLANNING)
    started = time.perf_counter()
    plan = plan_lugs(choice)
    planned = time.perf_counter() - started
    started = time.perf_counter()
    reference, stage_sweeps = every_assignment(choice)
    exhaustive = time.perf_counter() - started
    return {
        "case": str(PLANNING.relative_to(HERE.parent)),
        "candidates": len(choice.candidates),
        "assignments": plan.options,
        "plan_seconds": planned,
        "plan_swept": plan.swept,
        "plan_lugs": plan.best.lugs,
        "worst_design_lug_load": plan.best.worst,
        "exhaustive_seconds": exhaustive,
        "exhaustive_stage_sweeps": stage_sweeps,
        "exhaustive_lugs": reference,
        "same_choice": reference == plan.best.lugs,
        "ratio": exhaustive / planned,
    }


def main():
    sequence = load_sequence(CASE)
    run_sequence(sequence)  # warm-up: imports, scipy
    sweeps = []
    for _ in range(REPEAT):
        result = run_sequence(sequence)
        sweeps.append(result.seconds)
    started = time.perf_counter()
    grid = brute_force(sequence)
    brute = time.perf_counter() - started
    worst, evaluations = 0.0, 0
    rows = []
    for stage in result.stages:
        evaluations += stage.evaluations
        for key, peak in stage.maxima.items():
            value, angle = grid[stage.stage.where][key]
            worst = max(worst, value - peak.value)
            rows.append([stage.stage.where, key, peak.value, peak.angle, value, angle])
    lugs = planning()
    data = {
        "planning": lugs,
        "case": str(CASE.relative_to(HERE.parent)),
        "machine": f"{platform.machine()}, {platform.python_version()}",
        "sweep_seconds": min(sweeps),
        "sweep_seconds_all": sweeps,
        "sweep_equilibria": evaluations,
        "brute_force_grid_deg": FINE,
        "brute_force_seconds": brute,
        "ratio": brute / min(sweeps),
        "largest_brute_force_excess_t": worst,
        "maxima": rows,
    }
    OUT.mkdir(exist_ok=True)
    (OUT / "sequence_speed.json").write_text(json.dumps(data, indent=1) + "\n")
    lines = [
        "# 0-180 deg block turnover: continuous sweep against a 0.001 deg grid",
        "",
        f"continuous sweep: {min(sweeps):.3f} s ({evaluations} equilibria, best of {REPEAT}); "
        f"brute-force {FINE:g} deg grid: {brute:.1f} s; ratio {brute / min(sweeps):.0f}x; "
        f"largest amount a grid maximum exceeds the sweep's: {worst:.2e} t",
        "",
        "| stage | load | sweep max [t] | at [deg] | grid max [t] | at [deg] |",
        "|---|---|---|---|---|---|",
    ]
    lines += [f"| {r[0]} | {r[1]} | {r[2]:.6f} | {r[3]:.4f} | {r[4]:.6f} | {r[5]:.3f} |" for r in rows]
    lines += [
        "",
        f"# Planning crawler B's padeyes: {lugs['candidates']} candidates, {lugs['assignments']} assignments",
        "",
        f"planned: {lugs['plan_seconds']:.2f} s, {lugs['plan_swept']} swept, lugs {lugs['plan_lugs']}, worst "
        f"design lug load {lugs['worst_design_lug_load']:.3f} t; every assignment swept: "
        f"{lugs['exhaustive_seconds']:.1f} s ({lugs['exhaustive_stage_sweeps']} stage sweeps), lugs "
        f"{lugs['exhaustive_lugs']}; same choice: {lugs['same_choice']}; ratio {lugs['ratio']:.1f}x",
    ]
    (OUT / "sequence_speed.md").write_text("\n".join(lines) + "\n")
    print(lines[2])
    print(lines[-1])


if __name__ == "__main__":
    main()
