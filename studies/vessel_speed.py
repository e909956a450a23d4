"""What the crane vessels cost the equilibrium: the coupled solve against today's elastic one.

Two scenes, each against the same scene with every crane on land (today's ``elastic``
solve):

* the tanker on four sheerlegs (``examples/tanker_floating.toml``), one crane per vessel:
  ``solve`` (each rope in series with its vessel), and the coupled solve both ways;
* the tanker with T1 and T2 on one crane barge, T3 and T4 on sheerlegs
  (``examples/tanker_twin_barge.toml``): a vessel under two cranes, which ``solve`` takes to
  the coupled solve.

The coupled solve both ways: the full Newton on body and vessels (``reduced=False``: three
unknowns per vessel, the method before the vessels were eliminated) and the body's three
unknowns with the vessels eliminated (``CoupledRopeModel``: T = G s0, the default). Every
solve is the whole call, from the scene to the ``Equilibrium`` with its vessels' states; the
tensions of the two ways are compared too.

Times: median of 300 solves after a warm-up, all interleaved so that a load on the machine
falls on all of them alike; the ratios are what is claimed.

Run:  python studies/vessel_speed.py   (writes studies/out/vessel_speed.json)
"""

from __future__ import annotations

import dataclasses
import json
import os
import statistics
import time
from pathlib import Path

from liftplan.model import load_scene, solve
from liftplan.model.statics.floating import solve_coupled

HERE = Path(__file__).parent
EXAMPLES = HERE.parent / "examples"
REPEAT = 300


def on_land(scene):
    """The scene with every crane on land (its tip fixed)."""
    return dataclasses.replace(scene, cranes=tuple(dataclasses.replace(c, vessel=None) for c in scene.cranes))


def main():
    tanker = load_scene(EXAMPLES / "tanker_floating.toml")
    twin = load_scene(EXAMPLES / "tanker_twin_barge.toml")
    land = on_land(tanker)
    calls = {
        "elastic, cranes on land": lambda: solve(land),
        "one crane per vessel: solve (series)": lambda: solve(tanker),
        "one crane per vessel: coupled, full Newton (before)": lambda: solve_coupled(tanker, reduced=False),
        "one crane per vessel: coupled, vessels eliminated": lambda: solve_coupled(tanker),
        "two cranes on one vessel: full Newton (before)": lambda: solve_coupled(twin, reduced=False),
        "two cranes on one vessel: solve (vessels eliminated)": lambda: solve(twin),
    }
    weight = tanker.body.weight
    agree = {}
    for name, scene in (("one crane per vessel", tanker), ("two cranes on one vessel", twin)):
        full, reduced = solve_coupled(scene, reduced=False), solve_coupled(scene)
        agree[name] = max(abs(full.tensions[k] - reduced.tensions[k]) for k in full.tensions) / weight
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
    load = os.getloadavg()[0]
    out.write_text(
        json.dumps(
            {"repeat": REPEAT, "load_average": load, "rows": rows, "tension_agreement_W": agree}, indent=2
        )
        + "\n"
    )
    print(f"load average {load:.1f}")
    for row in rows:
        print(f"{row['case']:<56} {row['median_s'] * 1e6:8.1f} us  x{row['ratio_to_land']:.2f}")
    for name, worst in agree.items():
        print(f"{name}: full and eliminated tensions agree to {worst:.1e} W")


if __name__ == "__main__":
    main()
