"""The stranded barge lifted at its bow: how much the hull's flexibility changes the crane
tensions, the ground reaction and the bending moment (issue 12 item 2, on the ground).

Scene: the stranded-ship paper's box barge (examples/stranded_barge.toml: L 100, B 30, D 10 m,
20 000 t, CG (5, 0, 2)) grounded at the stern's keel (-45, 0, -5), with a weight curve that
carries W at G's x (140 -> 260 t/m), lifted at the bow by four cranes (lugs at x 40 and 48 m,
y +-10 m, on deck), hooks 40 m, ropes 35 m unstretched, EA 50 000 t.

EI assumed 7e8 t m2: a plain box girder of the barge's size, deck and bottom 20 mm, sides 15 mm,
I = 2 x (30 x 0.020) x 5^2 + 2 x 0.015 x 10^3 / 12 = 32.5 m4, E = 2.1e7 t/m2; no longitudinals
(they would stiffen it), no corrosion or damage (they would soften it). The study sweeps EI
from 0.01 to 100 x that.

Gauge: the flexible hull's statics are taken on the undeformed geometry of the frame the beam
is held in (the chord through its ends, what ``solve`` uses); held at the stern instead (w = w'
= 0 there) the same scene gives other forces. ``gauge`` in the JSON has, per EI, both gauges'
ground reaction and crane load from the rigid pose, and the difference over W x (max deflection
/ length): measured ~0.12 for the ground reaction, ~0.09 for the crane load, over the whole EI
range (:data:`liftplan.model.strength.flexible_water.GAUGE_COEFFICIENT`).

Run: ``python studies/flexible_ground.py`` -> studies/out/flexible_ground.json and .png.
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
OUT = HERE / "out"
EXAMPLES = HERE.parent / "examples"
EI = 7e8
SCALES = [0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0]


def scene(ei):
    from liftplan.model.scene.file import loads_scene

    text = (EXAMPLES / "stranded_barge.toml").read_text()
    text = text.replace(
        "cog = [5.0, 0.0, 2.0]", "cog = [5.0, 0.0, 2.0]\nweight_curve = [[-50.0, 140.0], [50.0, 260.0]]"
    )
    text = text.replace("[ground]", f"EI = [[-50.0, {ei!r}]]\n\n[ground]")
    text = text.replace("contact = [30.0, -2.0, -5.0]", "contact = [-45.0, 0.0, -5.0]")
    text += '\n[analysis]\nhull = "flexible"\n'
    for k, (x, y) in enumerate(((40.0, 10.0), (48.0, 10.0), (48.0, -10.0), (40.0, -10.0))):
        text += (
            f'\n[[lugs]]\nname = "B{k + 1}"\nat = [{x}, {y}, 5.0]\n\n[[cranes]]\nlug = "B{k + 1}"\n'
            "boom_height = 40.0\nrope_length = 35.0\nEA = 50000.0\nswl = 2000.0\n"
        )
    return loads_scene(text, base=EXAMPLES)


def run():
    from liftplan.model import solve
    from liftplan.model.strength import hull_girder

    rows, curves = [], {}
    for s in SCALES:
        sc = scene(EI * s)
        begin = time.perf_counter()
        eq = solve(sc)
        seconds = time.perf_counter() - begin
        flex = eq.flexible_hull
        girder = hull_girder(sc, eq)
        rigid_t = np.array(list(flex.rigid_tensions.values()))
        flex_t = np.array(list(flex.flexible_tensions.values()))
        rows.append(
            {
                "scale": s,
                "EI": EI * s,
                "seconds": seconds,
                "rigid_tensions": rigid_t.tolist(),
                "flexible_tensions": flex_t.tolist(),
                "rigid_crane_load": float(rigid_t.sum()),
                "flexible_crane_load": float(flex_t.sum()),
                "rigid_ground_reaction": flex.rigid_ground_reaction,
                "flexible_ground_reaction": flex.flexible_ground_reaction,
                "max_change": flex.max_change,
                "max_change_of": flex.max_change_rope,
                "max_deflection": flex.max_deflection.signed,
                "max_moment": girder.max_moment.signed,
                "max_moment_x": girder.max_moment.x,
                "closure": list(girder.closure),
            }
        )
        if s == 1.0:
            rigid_scene = dataclasses.replace(sc, analysis=dataclasses.replace(sc.analysis, hull="rigid"))
            rigid = solve(rigid_scene)
            rigid_girder = hull_girder(rigid_scene, rigid)
            curves = {
                "x": girder.stations.tolist(),
                "flexible_moment": girder.moment.tolist(),
                "rigid_x": rigid_girder.stations.tolist(),
                "rigid_moment": rigid_girder.moment.tolist(),
                "deflection_x": flex.x.tolist(),
                "deflection": flex.deflection.tolist(),
                "rigid_max_moment": rigid_girder.max_moment.signed,
            }
    return {"EI": EI, "rows": rows, "curves": curves, "gauge": gauge_rows()}


def gauge_rows():
    """Per EI: the chord and the stern gauge's ground reaction and crane load [t], solved from
    the rigid hull's pose, and their differences over W x (max deflection / length)."""
    from liftplan.model import solve
    from liftplan.model.frames import rotation_matrix
    from liftplan.model.strength.flexible_water import water_beam_state

    rows = []
    for s in SCALES:
        sc = scene(EI * s)
        pose = solve(sc.with_analysis(hull="rigid")).pose
        rot = rotation_matrix(pose.heel, pose.trim, pose.yaw)
        out = {}
        for gauge in ("chord", "stern"):
            state = water_beam_state(sc, rot, pose.lift_height - sc.water.level, True, gauge=gauge)
            if not state.accepted:
                raise RuntimeError(f"EI x {s:g}, gauge {gauge}: {state.refusal('grounded')}")
            w, _ = state.bending()
            out[gauge] = (state.reaction, float(state.tensions.sum()), float(np.max(np.abs(w))))
        chord, stern = out["chord"], out["stern"]
        ratio = chord[2] / 100.0  # the barge's length
        weight = sc.body.weight
        rows.append(
            {
                "scale": s,
                "EI": EI * s,
                "deflection_over_length": ratio,
                "chord_ground_reaction": chord[0],
                "stern_ground_reaction": stern[0],
                "chord_crane_load": chord[1],
                "stern_crane_load": stern[1],
                "ground_reaction_change": (stern[0] - chord[0]) / chord[0],
                "crane_load_change": (stern[1] - chord[1]) / chord[1],
                "ground_per_deflection": abs(stern[0] - chord[0]) / (weight * ratio),
                "crane_per_deflection": abs(stern[1] - chord[1]) / (weight * ratio),
            }
        )
    return rows


def draw(data):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows, c = data["rows"], data["curves"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    scale = np.array([r["scale"] for r in rows])
    ground = np.array([abs(r["flexible_ground_reaction"] / r["rigid_ground_reaction"] - 1) for r in rows])
    crane = np.array([abs(r["flexible_crane_load"] / r["rigid_crane_load"] - 1) for r in rows])
    left.loglog(scale, 100 * ground, "o-", label="ground reaction")
    left.loglog(scale, 100 * crane, "s--", label="crane load (sum of 4)")
    left.axhline(1.0, color="grey", lw=0.8)
    left.text(scale[0], 1.1, "1 %: solve keeps the rigid hull below", fontsize=8, color="grey")
    left.axvline(1.0, color="k", lw=0.6, ls=":")
    left.set_xlabel("EI / assumed 7e8 t m$^2$")
    left.set_ylabel("change flexibility makes [%]")
    left.set_title("Stranded barge, bow lifted: rigid vs flexible")
    left.legend(fontsize=8)
    right.plot(c["rigid_x"], np.array(c["rigid_moment"]) / 1e3, color="grey", label="rigid hull")
    right.plot(c["x"], np.array(c["flexible_moment"]) / 1e3, color="C0", label="flexible, EI 7e8 t m$^2$")
    right.axhline(0.0, color="k", lw=0.5)
    right.set_xlabel("x [m] (contact at -45, lugs at 40 and 48)")
    right.set_ylabel("bending moment [1000 t m] (> 0 sags)")
    right.set_title("Bending moment along the barge")
    right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "flexible_ground.png", dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.path.insert(0, str(HERE.parent))
    data = run()
    OUT.mkdir(exist_ok=True)
    (OUT / "flexible_ground.json").write_text(json.dumps(data, indent=1))
    draw(data)
    for r in data["rows"]:
        print(
            f"EI x {r['scale']:<5g} R {r['flexible_ground_reaction']:9.2f} "
            f"(rigid {r['rigid_ground_reaction']:.2f}) "
            f"cranes {r['flexible_crane_load']:8.2f} (rigid {r['rigid_crane_load']:.2f}) "
            f"max change {100 * r['max_change']:.3g} % ({r['max_change_of']}) "
            f"defl {1000 * r['max_deflection']:+.1f} mm  M {r['max_moment']:.0f} t m "
            f"at {r['max_moment_x']:.1f} "
            f"[{r['seconds']:.2f} s]"
        )
    print("rigid max M", data["curves"]["rigid_max_moment"])
    print("gauge: stern-end vs chord (what solve uses), from the rigid pose")
    print(
        f"{'EI x':>6} {'defl/L':>8} {'R chord':>9} {'R stern':>9} {'dR':>8} {'dR/(W d/L)':>10} "
        f"{'cranes chord':>12} {'dC':>8} {'dC/(W d/L)':>10}"
    )
    for g in data["gauge"]:
        print(
            f"{g['scale']:>6g} {g['deflection_over_length']:8.2e} {g['chord_ground_reaction']:9.2f} "
            f"{g['stern_ground_reaction']:9.2f} {100 * g['ground_reaction_change']:+7.3f}% "
            f"{g['ground_per_deflection']:10.3f} {g['chord_crane_load']:12.2f} "
            f"{100 * g['crane_load_change']:+7.3f}% {g['crane_per_deflection']:10.3f}"
        )
