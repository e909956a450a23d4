"""Stranded barge: the paper's J^T D J iteration against casadi's Newton root-finder.

For each case and each start attitude, both methods run to the same acceptance (scaled
residual 1e-9, i.e. moments below 1e-9 W L) and, for the paper's method, also to the
paper's own tolerance of 1 t m. Recorded: success, iterations, wall time (median of 5 after
one warm-up, model build excluded) and the pose reached.

Cases: the paper's barge cases 1 and 2 (contact (30, 0, -5) and (30, -2, -5)), a contact
far off the centreline (30, -10, -5), and the barge lying on its side (heel 90).
Starts: the paper's (level) and disturbed ones, to see where each method still converges.

Run:  python studies/stranded_methods.py   (writes studies/out/stranded_methods.json and .md)
"""

from __future__ import annotations

import json
import statistics
import time
from pathlib import Path

from liftplan.model import EquilibriumNotFound
from liftplan.model.frames import rotation_matrix
from liftplan.model.scene.hull import Hull
from liftplan.model.scene.objects import Attitude, Body, Ground, Scene, Water
from liftplan.model.water import Start, WaterSetup, solve_in_water

OUT = Path(__file__).parent / "out"
BOX = Hull.box([-50, -15, -5], [50, 15, 5])
WATER = Water(density=1.0273)
CASES = {
    "case 1 (30, 0, -5)": dict(body=Body(20000.0, (5.0, 0.0, 2.0)), ground=Ground((30.0, 0.0, -5.0))),
    "case 2 (30, -2, -5)": dict(body=Body(20000.0, (5.0, 0.0, 2.0)), ground=Ground((30.0, -2.0, -5.0))),
    "off-centre (30, -10, -5)": dict(body=Body(20000.0, (5.0, 0.0, 2.0)), ground=Ground((30.0, -10.0, -5.0))),
    "on its side (heel 90)": dict(
        body=Body(15000.0, (5.0, -10.0, 0.0)),
        ground=Ground((30.0, -15.0, 0.0)),
        attitude=Attitude(heel=90.0, lift_height=-12.0),
    ),
}
STARTS = [(0.0, 0.0), (5.0, 2.0), (-10.0, -3.0), (20.0, 5.0)]  # (heel, trim) offsets, deg


def run(scene, setup, method, start, paper_tol=None, repeat=5):
    times, eq = [], None
    for _ in range(repeat + 1):
        begin = time.perf_counter()
        try:
            eq = solve_in_water(scene, method=method, setup=setup, start=start, paper_tol=paper_tol)
        except EquilibriumNotFound as err:
            return {"success": False, "reason": str(err)[:160]}
        times.append(time.perf_counter() - begin)
    return {
        "success": True,
        "iterations": eq.solver.iterations,
        "seconds": statistics.median(times[1:]),
        "heel": eq.pose.heel,
        "trim": eq.pose.trim,
        "ground_reaction": eq.afloat.ground_reaction,
    }


def main():
    rows = []
    for name, spec in CASES.items():
        scene = Scene(water=WATER, hull=BOX, **spec)
        setup = WaterSetup(scene)
        a = scene.attitude
        for dh, dt in STARTS:
            start = Start(setup.start.zo, rotation_matrix(a.heel + dh, a.trim + dt, a.yaw))
            for method, tol in (("newton", None), ("paper-newton", None), ("paper-newton", 1.0)):
                result = run(scene, setup, method, start, paper_tol=tol)
                label = method if tol is None else f"{method} (tol 1 t m)"
                rows.append({"case": name, "start": [a.heel + dh, a.trim + dt], "method": label, **result})
    OUT.mkdir(exist_ok=True)
    (OUT / "stranded_methods.json").write_text(json.dumps(rows, indent=1))
    lines = [
        "| case | start heel, trim [deg] | method | converged | iterations | time [ms] | heel, trim [deg] |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r["success"]:
            tail = f"yes | {r['iterations']} | {1e3 * r['seconds']:.2f} | {r['heel']:.3f}, {r['trim']:.3f}"
        else:
            tail = "no | - | - | -"
        lines.append(f"| {r['case']} | {r['start'][0]:g}, {r['start'][1]:g} | {r['method']} | {tail} |")
    (OUT / "stranded_methods.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    ok = {m: [r["success"] for r in rows if r["method"] == m] for m in {r["method"] for r in rows}}
    for m, flags in sorted(ok.items()):
        print(f"{m}: {sum(flags)}/{len(flags)} converged")


if __name__ == "__main__":
    main()
