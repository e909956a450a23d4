"""How much the hull's flexibility changes the tensions and the skew loads on the tanker.

The 1500 GT tanker of ``examples/tanker_flexible.toml`` (EI = 5.3e7 t m2 from the class rules'
minimum section modulus, GJ = 5.2e7 t m2 from Bredt's formula for her single-cell section;
the derivation is in the example's header), lifted on the forward elastic model:

* "4 lugs": the papers' layout, two lugs at each of two stations (x 16.2 and 65.6 m);
* "6 lugs": the same with a third pair amidships (x 40.9 m), the same ropes.

Both stiffnesses are scaled together by s from 1e-3 to 1e4 (s = 1 is the assumed tanker).
For each s the flexible and the rigid hull are solved, each with the hooks level and with
each hook moved by +-1 mm (central differences, exact to ~1e-9 here: the tensions are linear
in the hook heights while every rope is taut):

* the largest tension change flexibility makes with level hooks, |T_flex - T_rigid| / T_rigid;
* the computed skew load factor, as the planner computes it (``planner/plans/design_loads.py``):
  SKL_i = (T_i + delta sum_j |dT_i / dH_j|) / T_i with the hook tolerance delta = 0.02 m of
  ``examples/tanker_plan.toml``; the largest over the ropes is reported;
* the stiffness scale at which the rigid hull is within 1 % (tensions, and skew loads
  T_i + delta sum_j |dT_i/dH_j|), found by bisection on log s of the measured change.

Writes studies/out/flexible_hull.json and draws studies/out/flexible_hull.png from it.

Run:  python studies/flexible_hull.py
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np

from liftplan.model import load_scene
from liftplan.model.scene.objects import Crane, GirderStiffness, Lug
from liftplan.model.solve import solve_hull_on_ropes

HERE = Path(__file__).parent
OUT = HERE / "out"
EXAMPLE = HERE.parent / "examples" / "tanker_flexible.toml"
EI, GJ = 5.3e7, 5.2e7  # t m2, the example's assumption (s = 1)
HOOK_TOLERANCE = 0.02  # m, examples/tanker_plan.toml
STEP = 1e-3  # m, central-difference hook step
SCALES = 10.0 ** np.arange(-3.0, 4.01, 0.5)


def layouts():
    """The two lug layouts, z-up, as scenes (4 and 6 lugs)."""
    four = load_scene(EXAMPLE)
    middle = 0.5 * (four.lugs[0].at[0] + four.lugs[1].at[0])
    extra = [Lug(f"T{5 + k}", (middle, lug.at[1], lug.at[2])) for k, lug in enumerate(four.lugs[1:3])]
    template = four.cranes[0]
    cranes = [dataclasses.replace(template, lug=lug.name) for lug in extra]
    six = dataclasses.replace(four, lugs=four.lugs + tuple(extra), cranes=four.cranes + tuple(cranes))
    assert all(isinstance(c, Crane) for c in six.cranes)
    return {"4 lugs": four, "6 lugs": six}


def scaled(scene, s):
    return dataclasses.replace(scene, girder=GirderStiffness(EI=((0.0, s * EI),), GJ=((0.0, s * GJ),)))


def both(scene):
    """(flexible, rigid) tensions in lug order  [t]."""
    eq = solve_hull_on_ropes(scene, hull="flexible")
    names = scene.lug_names
    return (
        np.array([eq.tensions[n] for n in names]),
        np.array([eq.flexible_hull.rigid_tensions[n] for n in names]),
        eq,
    )


def measure(scene):
    """Tensions, hook gains and skew factors of one scene, flexible and rigid."""
    flexible, rigid, eq = both(scene)
    gains = {"flexible": np.zeros((scene.n, scene.n)), "rigid": np.zeros((scene.n, scene.n))}
    for j, crane in enumerate(scene.cranes):
        up = both(scene.with_crane(crane.lug, boom_height=crane.boom_height + STEP))
        down = both(scene.with_crane(crane.lug, boom_height=crane.boom_height - STEP))
        gains["flexible"][:, j] = (up[0] - down[0]) / (2 * STEP)
        gains["rigid"][:, j] = (up[1] - down[1]) / (2 * STEP)
    out = {"flexible": flexible, "rigid": rigid}
    row = {"tension_change": float(np.max(np.abs(flexible - rigid) / rigid))}
    for hull in ("flexible", "rigid"):
        skewed = out[hull] + HOOK_TOLERANCE * np.abs(gains[hull]).sum(axis=1)
        row[f"tensions_{hull}"] = out[hull].tolist()
        row[f"skewed_{hull}"] = skewed.tolist()
        row[f"skew_factor_{hull}"] = float(np.max(skewed / out[hull]))
    row["skewed_change"] = float(
        np.max(np.abs(np.array(row["skewed_flexible"]) - row["skewed_rigid"]) / np.array(row["skewed_rigid"]))
    )
    row["max_deflection_mm"] = 1000 * eq.flexible_hull.max_deflection.signed
    return row, eq


def within_one_percent(scene, key):
    """The stiffness scale s where the measured change ``key`` falls to 1 % (bisection on log s)."""
    lo, hi = -4.0, 6.0
    if measure(scaled(scene, 10.0**lo))[0][key] <= 0.01:
        return 10.0**lo
    if measure(scaled(scene, 10.0**hi))[0][key] > 0.01:
        return math.inf
    for _ in range(20):  # to 1e-5 decades
        mid = 0.5 * (lo + hi)
        if measure(scaled(scene, 10.0**mid))[0][key] > 0.01:
            lo = mid
        else:
            hi = mid
    return 10.0**hi


def run():
    data = {"EI": EI, "GJ": GJ, "hook_tolerance": HOOK_TOLERANCE, "layouts": {}}
    for name, scene in layouts().items():
        rows = []
        for s in SCALES:
            row, _ = measure(scaled(scene, float(s)))
            rows.append({"scale": float(s), **row})
        _, eq = measure(scaled(scene, 1.0))
        flex = eq.flexible_hull
        data["layouts"][name] = {
            "lugs": list(scene.lug_names),
            "sweep": rows,
            "at_assumed": next(r for r in rows if r["scale"] == 1.0),
            "deflection": {"x": flex.x.tolist(), "w_mm": (1000 * flex.deflection).tolist()},
            "scale_within_1pct_tensions": within_one_percent(scene, "tension_change"),
            "scale_within_1pct_skewed": within_one_percent(scene, "skewed_change"),
        }
    OUT.mkdir(exist_ok=True)
    (OUT / "flexible_hull.json").write_text(json.dumps(data, indent=1))
    return data


def draw(data):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    fig = Figure(figsize=(13, 4.4), layout="constrained")
    ax_t, ax_s, ax_w = fig.subplots(1, 3)
    colours = {"4 lugs": "tab:blue", "6 lugs": "tab:orange"}
    for name, layout in data["layouts"].items():
        rows = layout["sweep"]
        s = np.array([r["scale"] for r in rows])
        c = colours[name]
        change = np.array([r["tension_change"] for r in rows])
        skewed = np.array([r["skewed_change"] for r in rows])
        ax_t.loglog(s, np.maximum(change, 1e-12), "o-", color=c, label=f"{name}: level hooks")
        ax_t.loglog(
            s,
            skewed,
            "s--",
            color=c,
            mfc="none",
            label=f"{name}: skew load (hooks +-{100 * data['hook_tolerance']:.0f} cm)",
        )
        ax_s.semilogx(s, [r["skew_factor_flexible"] for r in rows], "o-", color=c, label=f"{name}: flexible")
        ax_s.axhline(rows[0]["skew_factor_rigid"], color=c, ls=":", label=f"{name}: rigid hull")
        d = layout["deflection"]
        ax_w.plot(d["x"], d["w_mm"], color=c, label=name)
        for lug_x in sorted({round(x, 3) for x in _lug_x(name)}):
            ax_w.axvline(lug_x, color=c, lw=0.6, ls=":")
    ax_t.axhline(0.01, color="k", lw=0.8)
    ax_t.text(SCALES[0], 0.012, "1 %", fontsize=8)
    for ax in (ax_t, ax_s):
        ax.axvline(1.0, color="grey", lw=0.8, ls="--")
        ax.set_xlabel(f"stiffness scale s (EI = s x {EI:.2g}, GJ = s x {GJ:.2g} t m2)")
    ax_t.set_ylabel("largest |T_flexible - T_rigid| / T_rigid [-]")
    ax_t.set_ylim(1e-7, 2)
    ax_t.set_title("Tension change from flexibility")
    ax_t.legend(fontsize=7, loc="lower left")
    ax_s.set_ylabel("computed skew load factor, largest rope [-]")
    ax_s.set_title(f"Skew load factor (hook tolerance {100 * data['hook_tolerance']:.0f} cm)")
    ax_s.legend(fontsize=7)
    ax_w.axhline(0.0, color="k", lw=0.6)
    ax_w.set_xlabel("body x [m] (dotted: lug stations)")
    ax_w.set_ylabel("deflection from the chord [mm] (> 0 up)")
    ax_w.set_title("Deflection at s = 1, level hooks")
    ax_w.legend(fontsize=7)
    fig.suptitle("1500 GT tanker on elastic ropes: flexible against rigid hull (s = 1: the assumed EI, GJ)")
    fig.savefig(OUT / "flexible_hull.png", dpi=110)


def _lug_x(name):
    return [lug.at[0] for lug in layouts()[name].lugs]


if __name__ == "__main__":
    result = run()
    draw(result)
    for name, layout in result["layouts"].items():
        a = layout["at_assumed"]
        print(
            f"{name}: at the assumed EI/GJ: tension change {a['tension_change']:.3%}, skew factor "
            f"{a['skew_factor_flexible']:.4f} flexible vs {a['skew_factor_rigid']:.4f} rigid, skewed loads "
            f"change {a['skewed_change']:.3%}, deflection {a['max_deflection_mm']:+.1f} mm; "
            f"rigid within 1 % from s = {layout['scale_within_1pct_tensions']:.3g} (tensions), "
            f"{layout['scale_within_1pct_skewed']:.3g} (skew loads)"
        )
