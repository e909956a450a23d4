"""How much the least model saves: each simpler model against the fuller one on the same
scene, where both apply (the tests pin that they agree).

* Fully submerged hull hanging from four ropes (the sunken block, hooks 36 m up): constant
  buoyancy (the vertical-rope elastic model with the submerged weight and centre) against
  the clipped hull.
* No water against the clipped hull with the water far below (clear of it).
* Tips above the lugs: the 3-DOF vertical-rope model against the 6-DOF inclined model.

Times: median of 50 solves after a warm-up; model building excluded (both are built once
per scene in a study or a load curve).

Run:  python studies/least_model.py   (writes studies/out/least_model.json)
"""

from __future__ import annotations

import dataclasses
import json
import statistics
import time
from pathlib import Path

import numpy as np

from liftplan.model import load_scene, rotation_matrix, solve_elastic
from liftplan.model.scene.objects import Water
from liftplan.model.statics.inclined import solve_inclined
from liftplan.model.water import WaterSetup, solve_in_water, submerged_scene

HERE = Path(__file__).parent
EXAMPLES = HERE.parent / "examples"


def median_time(call, repeat=50):
    call()
    times = []
    for _ in range(repeat):
        begin = time.perf_counter()
        call()
        times.append(time.perf_counter() - begin)
    return statistics.median(times)


def hanging(hook):
    scene = load_scene(EXAMPLES / "sunken_block_lift.toml")
    cranes = tuple(dataclasses.replace(c, boom_height=hook) for c in scene.cranes)
    return dataclasses.replace(scene, ground=None, cranes=cranes)


def main():
    rows = []
    # 1. fully submerged: constant buoyancy vs clipped
    scene = hanging(36.0)
    setup = WaterSetup(scene)
    rope_scene = submerged_scene(setup)
    simple = median_time(lambda: solve_elastic(rope_scene))
    full = median_time(lambda: solve_in_water(scene, setup=setup))
    a, b = solve_elastic(rope_scene), solve_in_water(scene, setup=setup)
    diff = float(np.max(np.abs(np.subtract(list(a.tensions.values()), list(b.tensions.values())))))
    rows.append(
        {
            "case": "fully submerged: constant buoyancy vs clipped hull",
            "least_s": simple,
            "full_s": full,
            "speedup": full / simple,
            "max_tension_difference_t": diff,
        }
    )
    # 2. no water vs water far below
    high = hanging(60.0)
    low = dataclasses.replace(high, water=Water(density=1.025, level=-1000.0))
    setup_low = WaterSetup(low)
    trapped = setup_low.trapped
    body = high.body
    cog = (body.weight * np.array(body.cog) + trapped * np.array([3.0, 0.0, 1.0])) / (body.weight + trapped)
    dry = dataclasses.replace(
        high,
        water=None,
        hull=None,
        body=dataclasses.replace(body, weight=body.weight + trapped, cog=tuple(cog)),
    )
    simple = median_time(lambda: solve_elastic(dry))
    full = median_time(lambda: solve_in_water(low, setup=setup_low))
    a, b = solve_elastic(dry), solve_in_water(low, setup=setup_low)
    diff = float(np.max(np.abs(np.subtract(list(a.tensions.values()), list(b.tensions.values())))))
    rows.append(
        {
            "case": "no water vs clipped hull clear of the water",
            "least_s": simple,
            "full_s": full,
            "speedup": full / simple,
            "max_tension_difference_t": diff,
        }
    )
    # 3. vertical (3 DOF) vs inclined (6 DOF) with tips above the lugs at the answer
    block = load_scene(EXAMPLES / "symmetric_block.toml").with_body(cog=(1.5, -0.8, 2.5))
    vertical = solve_elastic(block)
    pose = vertical.pose
    lugs = block.lug_points() @ rotation_matrix(pose.heel, pose.trim).T + [0, 0, pose.lift_height]
    tips = np.column_stack([lugs[:, :2], [c.boom_height for c in block.cranes]])
    cranes = tuple(dataclasses.replace(c, tip=tuple(t)) for c, t in zip(block.cranes, tips))
    inclined = dataclasses.replace(block, cranes=cranes).with_analysis(model=None)
    simple = median_time(lambda: solve_elastic(block))
    full = median_time(lambda: solve_inclined(inclined))
    diff = float(
        np.max(
            np.abs(
                np.subtract(
                    list(vertical.tensions.values()), list(solve_inclined(inclined).tensions.values())
                )
            )
        )
    )
    rows.append(
        {
            "case": "tips above the lugs: 3-DOF vertical vs 6-DOF inclined",
            "least_s": simple,
            "full_s": full,
            "speedup": full / simple,
            "max_tension_difference_t": diff,
        }
    )
    (HERE / "out").mkdir(exist_ok=True)
    (HERE / "out" / "least_model.json").write_text(json.dumps(rows, indent=1))
    for r in rows:
        print(
            f"{r['case']}: least {1e6 * r['least_s']:.0f} us, full {1e6 * r['full_s']:.0f} us, "
            f"{r['speedup']:.1f}x faster, max |dT| {r['max_tension_difference_t']:.1e} t"
        )


if __name__ == "__main__":
    main()
