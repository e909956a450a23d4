"""Peak crane load against hoist speed: the sunken block's aft tank draining as it rises.

The sunken hull block of ``examples/sunken_block_lift.toml`` with a hole of 0.2 m2 (C_d
0.61) in the floor of its aft tank (6 x 12 x 2 m, 147.6 t of water), lifted to 1 m clear of
the water at several hoist speeds. The faster the hoist, the less water has drained when
the block clears the surface, and the higher the peak. The two limits bound it: a hole of
no area (the water never drains: today's trapped tank) and one of infinite area (it drains
at once: free-flooding). No breakout model here (its peak would hide this one).

Writes ``studies/out/draining.csv`` (one row per speed) and draws
``studies/out/draining.png`` from it. Run: ``python studies/draining.py``.
"""

from __future__ import annotations

import csv
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "studies" / "out"
SPEEDS = (0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0)  # m/min
AREA = 0.2  # m2
STEP = 0.5  # m


def scene_with(area):
    from liftplan.model.scene.file import loads_scene

    text = (ROOT / "examples" / "sunken_block_lift.toml").read_text()
    text = text.replace(
        'contents = "water"', f'contents = "water"\nopenings = [{{ area = {area}, at = [3.0, 0.0, 0.0] }}]'
    )
    return loads_scene(text, base=ROOT / "examples")


def row(label, speed, curve):
    peak, hoist = curve.peak_crane_load
    clear = curve.event("clear")
    k = list(curve.hoist).index(min(curve.hoist, key=lambda h: abs(h - clear.hoist))) if clear else -1
    tank = curve.drainage[0] if curve.drainage else None
    return {
        "case": label,
        "speed_m_per_min": speed if speed is not None else "",
        "peak_crane_load_t": peak,
        "peak_hoist_m": hoist,
        "peak_time_s": curve.hoist_time(hoist) if speed else "",
        "water_at_clear_t": float(curve.water_carried[k]),
        "water_at_end_t": float(curve.water_carried[-1]),
        "mass_error": tank.mass_error if tank else 0.0,
        "failed_steps": len(curve.failed),
    }


def compute():
    from liftplan.model.lift import load_curve

    rows = [row("never drains (area 0)", None, load_curve(scene_with(0.0), step=STEP))]
    for speed in SPEEDS:
        rows.append(
            row(f"{AREA} m2 at {speed:g} m/min", speed, load_curve(scene_with(AREA), step=STEP, speed=speed))
        )
    rows.append(row("drains at once (area inf)", None, load_curve(scene_with("inf"), step=STEP)))
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "draining.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return rows


def draw():
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    with open(OUT / "draining.csv") as f:
        rows = list(csv.DictReader(f))
    timed = [r for r in rows if r["speed_m_per_min"]]
    never, instant = float(rows[0]["peak_crane_load_t"]), float(rows[-1]["peak_crane_load_t"])
    weight = never - float(rows[0]["water_at_end_t"])  # never drains: W + the full tank, clear
    speed = [float(r["speed_m_per_min"]) for r in timed]
    fig = Figure(figsize=(8, 5), layout="constrained")
    ax = fig.subplots()
    ax.plot(
        speed,
        [float(r["peak_crane_load_t"]) for r in timed],
        "o-",
        color="k",
        label=f"peak crane load, {AREA} m2 hole (C_d 0.61)",
    )
    ax.plot(
        speed,
        [float(r["water_at_clear_t"]) + weight for r in timed],
        "s--",
        color="tab:purple",
        ms=4,
        label="W + the water left when the block clears (B = 0 there)",
    )
    ax.axhline(never, color="tab:red", ls=":", label=f"never drains (area 0): {never:.1f} t")
    ax.axhline(instant, color="tab:blue", ls=":", label=f"drains at once (area inf): {instant:.1f} t")
    ax.set_xscale("log")
    ax.set_xlabel("hoist speed [m/min]")
    ax.set_ylabel("sum of rope tensions [t]")
    ax.set_title(
        "Sunken block, aft tank draining through a hole in its floor:\n"
        "peak crane load against hoist speed (lifted to 1 m clear of the water)",
        fontsize=10,
    )
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.savefig(OUT / "draining.png", dpi=120)


if __name__ == "__main__":
    import sys

    if "--draw" not in sys.argv:  # --draw: redraw from the data already written
        for r in compute():
            print(r)
    draw()
    print(f"wrote {OUT / 'draining.csv'} and {OUT / 'draining.png'}")
