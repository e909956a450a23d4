"""What the crane vessels cost the equilibrium: the coupled solve against today's elastic one.

The tanker on four sheerlegs (``examples/tanker_floating.toml``) solved by ``solve`` (each
rope in series with its vessel: the rope-only Newton with the series stiffness, then the
vessels' states), and by the Newton on body and vessels together (15 unknowns,
``solve_coupled``: what a vessel under two cranes needs), against the same scene with the
cranes on land (today's ``elastic`` solve). Every solve is the whole ``solve(scene)`` call.

Times: median of 300 solves after a warm-up, the three interleaved so that a load on the
machine falls on all of them alike; the ratios are what is claimed.

Run:  python studies/vessel_speed.py   (writes studies/out/vessel_speed.json)
"""

from __future__ import annotations

import dataclasses
import json
import statistics
import time
from pathlib import Path

from liftplan.model import load_scene, solve
from liftplan.model.statics.floating import solve_coupled

HERE = Path(__file__).parent
EXAMPLES = HERE.parent / "examples"
REPEAT = 300


def main():
    scene = load_scene(EXAMPLES / "tanker_floating.toml")
    land = dataclasses.replace(scene, cranes=tuple(dataclasses.replace(c, vessel=None) for c in scene.cranes))
    calls = {
        "elastic, cranes on land": lambda: solve(land),
        "elastic with vessels (series)": lambda: solve(scene),
        "elastic with vessels (Newton on body and vessels)": lambda: solve_coupled(scene),
    }
    times = {name: [] for name in calls}
    for call in calls.values():
        call()
    for _ in range(REPEAT):
        for name, call in calls.items():
            begin = time.perf_counter()
            call()
            times[name].append(time.perf_counter() - begin)
    base = statistics.median(times["elastic, cranes on land"])
    rows = [
        {"case": name, "median_s": statistics.median(t), "ratio_to_land": statistics.median(t) / base}
        for name, t in times.items()
    ]
    out = HERE / "out" / "vessel_speed.json"
    out.parent.mkdir(exist_ok=True)
    out.write_text(json.dumps({"repeat": REPEAT, "rows": rows}, indent=2) + "\n")
    for row in rows:
        print(f"{row['case']:<52} {row['median_s'] * 1e6:8.1f} us  x{row['ratio_to_land']:.2f}")


if __name__ == "__main__":
    main()
