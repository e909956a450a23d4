"""The tanker's recorded (simulated) lift replayed: the estimate against the truth behind it.

``examples/tanker_lift_readings.csv`` is ``liftplan simulate examples/tanker_plan.toml --errors
hook=0.04,cog=0.1,weight=0.02 --drift 0.003 --seed 3 --steps 30``; the same simulation is run
here to know its truth. Each reading is watched as ``liftplan watch`` does (``Watcher``), and
the estimate (weight, CG x, the hooks' errors about their mean) is written beside the truth,
then drawn with its 2-sigma band, with the tensions against the plan's band and after the
advised moves.

Run:  python studies/watch_replay.py   (writes studies/out/watch_replay.json, then draws
                                         studies/out/watch_replay.png from it)
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
ROOT = HERE.parent
OUT = HERE / "out"

from liftplan.planner.plan import plan  # noqa: E402
from liftplan.planner.plans.watch_basis import watch_basis  # noqa: E402
from liftplan.planner.problem.file import load_problem  # noqa: E402
from liftplan.planner.watch.readings import read_readings  # noqa: E402
from liftplan.planner.watch.simulate import Errors, Noise, simulate  # noqa: E402
from liftplan.planner.watch.update import Watcher  # noqa: E402


def data():
    basis = watch_basis(plan(load_problem(ROOT / "examples" / "tanker_plan.toml")))
    accuracy = basis.accuracy
    noise = Noise(accuracy.load_cell, accuracy.inclinometer, accuracy.hook)
    lift = simulate(basis, Errors(hook=0.04, cog=0.1, weight=0.02), noise, seed=3, steps=30, drift=0.003)
    recorded = read_readings(basis, ROOT / "examples" / "tanker_lift_readings.csv")
    # the example file is this simulation, written to 3 decimals
    assert np.allclose([r.tensions for r in recorded], [r.tensions for r in lift.readings], atol=1e-3)
    watcher = Watcher(basis)
    rows = []
    for reading, truth in zip(recorded, lift.states):
        update = watcher.update(reading)
        e, a = update.estimate, update.advice
        rows.append(
            {
                "time": reading.time,
                "truth": {
                    "weight": truth[0],
                    "cog_x": truth[1],
                    "hooks": (truth[4:] - truth[4:].mean()).tolist(),
                },
                "estimate": {"weight": e.weight, "cog_x": e.cog[0], "hooks": e.hook_errors.tolist()},
                "sigma": {"weight": e.sigma[0], "cog_x": e.sigma[1], "hooks": e.sigma[4:].tolist()},
                "tensions": reading.tensions.tolist(),
                "after": a.tensions.tolist(),
                "moves": a.moves.tolist(),
                "stop": bool(update.stop),
            }
        )
    out = {
        "labels": list(basis.labels),
        "band_low": np.maximum(basis.band_low, basis.min_tension).tolist(),
        "band_high": basis.band_high.tolist(),
        "rows": rows,
    }
    OUT.mkdir(exist_ok=True)
    (OUT / "watch_replay.json").write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    return out


def draw(out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = out["rows"]
    t = np.array([r["time"] for r in rows])
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), constrained_layout=True)
    for ax, key, unit, title in (
        (axes[0, 0], "weight", "t", "weight"),
        (axes[0, 1], "cog_x", "m", "CG x (forward)"),
    ):
        est = np.array([r["estimate"][key] for r in rows])
        sig = np.array([r["sigma"][key] for r in rows])
        ax.fill_between(t, est - 2 * sig, est + 2 * sig, alpha=0.3, label="estimate +- 2 sigma")
        ax.plot(t, est, "o-", ms=3, label="estimate")
        ax.plot(t, [r["truth"][key] for r in rows], "k--", label="truth")
        ax.set(title=title, xlabel="time [s]", ylabel=f"{title} [{unit}]")
        ax.legend(fontsize=8)
    ax = axes[1, 0]
    for k, label in enumerate(out["labels"]):
        est = np.array([r["estimate"]["hooks"][k] for r in rows]) * 100
        sig = np.array([r["sigma"]["hooks"][k] for r in rows]) * 100
        line = ax.plot(t, est, "o-", ms=3, label=f"{label} estimate")[0]
        ax.fill_between(t, est - 2 * sig, est + 2 * sig, color=line.get_color(), alpha=0.15)
        ax.plot(t, [r["truth"]["hooks"][k] * 100 for r in rows], "--", color=line.get_color())
    ax.set(title="hook errors about their mean (dashed: truth)", xlabel="time [s]", ylabel="error [cm]")
    ax.legend(fontsize=7, ncol=2)
    ax = axes[1, 1]
    for k, label in enumerate(out["labels"]):
        line = ax.plot(t, [r["tensions"][k] for r in rows], "-", label=f"{label} read")[0]
        ax.plot(t, [r["after"][k] for r in rows], ":", color=line.get_color())
        ax.axhspan(out["band_low"][k], out["band_high"][k], color=line.get_color(), alpha=0.06)
        ax.axhline(out["band_high"][k], color=line.get_color(), lw=0.6)
        ax.axhline(out["band_low"][k], color=line.get_color(), lw=0.6)
    ax.set(
        title="tensions read (solid), after the moves (dotted), bands",
        xlabel="time [s]",
        ylabel="tension [t]",
    )
    ax.legend(fontsize=7, ncol=2)
    fig.suptitle("Tanker lift replayed (examples/tanker_lift_readings.csv): liftplan watch")
    fig.savefig(OUT / "watch_replay.png", dpi=110)


if __name__ == "__main__":
    draw(json.loads((OUT / "watch_replay.json").read_text()) if "--plot" in sys.argv else data())
