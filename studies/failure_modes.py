"""Where each method fails, and whether the library says so.

Every case is run through every method that applies. An answer is checked here,
independently of the solver, from the result alone: force and moment balance to 1e-6 W,
no rope in compression, body the right way up, and (elastic) each tension equal to
EA x stretch / l0 at the reported pose. Outcomes:

  ok        an answer, and it passes the check
  refused   a one-line LiftPlanError (InvalidScene, EquilibriumNotFound, ...)
  WRONG     an answer that fails the check (must never happen)
  crash     any other exception (must never happen)

Plus the stiff-rope limit: the elastic tensions against EA/l as it goes to infinity, their
distance to the rigid limit (the compatible, equal-stiffness distribution), Newton's
Jacobian condition number, and where the solve is refused.

Run:  python studies/failure_modes.py
      (writes studies/out/failure_modes.json, then .md and stiff_limit.png from it)
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

from liftplan.model import LiftPlanError, load_scene, rotation_matrix, solve
from liftplan.model.scene.objects import Analysis, Attitude, Crane, Lug, Redundant, Scene

HERE = Path(__file__).parent
OUT = HERE / "out"
EXAMPLES = HERE.parent / "examples"
VERTICAL = ("rigid", "paper-elastic", "elastic")


def block():
    return load_scene(EXAMPLES / "symmetric_block.toml")


def with_lugs(scene, points):
    lugs = tuple(Lug(lug.name, tuple(p)) for lug, p in zip(scene.lugs, points))
    return dataclasses.replace(scene, lugs=lugs)


def held(scene):
    """The scene with its last n - 3 tensions held at W / n, for ``rigid``."""
    share = scene.body.weight / scene.n
    return scene.with_analysis(redundant=tuple(Redundant(name, share) for name in scene.lug_names[3:]))


def constructed(scene):
    """A forward elastic scene whose equilibrium is the paper-elastic state at the scene's
    attitude (unstretched lengths chosen to give it)."""
    state = solve(scene, "paper-elastic")
    rot = rotation_matrix(state.pose.heel, state.pose.trim, state.pose.yaw)
    heights = (scene.lug_points() @ rot.T)[:, 2] + state.pose.lift_height
    cranes = tuple(
        Crane(
            c.lug,
            EA=c.EA,
            boom_height=c.boom_height,
            swl=c.swl,
            rope_length=(c.boom_height - h) / (1.0 + t / c.EA),
        )
        for c, h, t in zip(scene.cranes, heights, state.tensions.values())
    )
    return dataclasses.replace(
        scene, cranes=cranes, attitude=Attitude(yaw=scene.attitude.yaw), analysis=Analysis("elastic")
    )


# -- the independent check ---------------------------------------------------------------
def check(scene, eq):
    """None if the answer holds, else what is wrong with it."""
    if eq.afloat is not None:  # hydrostatic: the solver's own residual, recomputed in its result
        return None if abs(eq.residual) <= 1e-6 * scene.body.weight else f"residual {eq.residual:.2e} t"
    rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
    lugs = scene.lug_points() @ rot.T
    cog = rot @ np.array(scene.body.cog)
    t = np.array(list(eq.tensions.values()))
    w, scale = scene.body.weight, scene.plan_diameter
    balance = max(
        abs(t.sum() - w), abs(t @ lugs[:, 0] - w * cog[0]) / scale, abs(t @ lugs[:, 1] - w * cog[1]) / scale
    )
    if not np.isfinite(balance) or balance > 1e-6 * w:
        return f"out of balance by {balance:.2e} t"
    if t.min() < -1e-9 * w:
        return f"rope in compression ({t.min():.3g} t)"
    if not (abs(eq.pose.heel) < 90 and abs(eq.pose.trim) < 90):
        return "upside down"
    if eq.model == "elastic":
        z = lugs[:, 2] + eq.pose.lift_height
        expected = np.array(
            [
                c.EA * max(c.boom_height - h - c.rope_length, 0.0) / c.rope_length
                for c, h in zip(scene.cranes, z)
            ]
        )
        if np.max(np.abs(expected - t)) > 1e-6 * w:
            return "tensions do not match the rope stretch"
    return None


def outcome(run, scene_of_answer):
    try:
        eq = run()
    except LiftPlanError as err:
        text = str(err)
        return {
            "outcome": "refused",
            "detail": f"{type(err).__name__}: {text[:150]}",
            "one_line": "\n" not in text,
        }
    except Exception as err:  # noqa: BLE001 - recorded as a crash
        return {"outcome": "crash", "detail": f"{type(err).__name__}: {str(err)[:150]}"}
    problem = check(scene_of_answer, eq)
    if problem:
        return {"outcome": "WRONG", "detail": problem}
    tensions = ", ".join(f"{v:.1f}" for v in eq.tensions.values())
    detail = f"heel {eq.pose.heel:+.2f}, trim {eq.pose.trim:+.2f} deg; T = {tensions} t"
    if eq.afloat is not None:
        detail = (
            f"{eq.model}, state {eq.afloat.state}; heel {eq.pose.heel:+.2f}, trim "
            f"{eq.pose.trim:+.2f}; buoyancy {eq.afloat.buoyancy:.1f} t"
        )
    return {"outcome": "ok", "detail": detail}


def vertical_runs(scene):
    """(method, run, scene) for the three vertical-rope models."""
    return [
        ("rigid", lambda: solve(held(scene), "rigid"), scene),
        ("paper-elastic", lambda: solve(scene, "paper-elastic"), scene),
        ("elastic", lambda: solve(scene, "elastic"), scene),
    ]


def attitude_runs(scene, heel, trim=0.0):
    """Given-attitude models at the attitude; elastic on a scene built to reach it."""
    tilted = scene.with_attitude(heel=heel, trim=trim)
    runs = vertical_runs(tilted)[:2]
    try:
        forward = constructed(tilted)
    except LiftPlanError as err:
        return runs + [("elastic", _raise(err), tilted)]
    return runs + [("elastic", lambda: solve(forward, "elastic"), forward)]


def _raise(err):
    def run():
        raise err

    return run


def cases():
    """name -> list of (method, run, scene the answer is checked on)."""
    b = block()
    line = np.array([[-20, 0, 6], [-7, 0, 6], [7, 0, 6], [20, 0, 6]], dtype=float)
    nearly = line + np.array([[0, 1e-3, 0], [0, -1e-3, 0], [0, 1e-3, 0], [0, -1e-3, 0]])
    out = {}

    def add(name, build, methods=VERTICAL):
        try:
            out[name] = build()
        except LiftPlanError as err:  # refused when the scene is made
            out[name] = [(m, _raise(err), None) for m in methods]

    add("collinear lugs (4 on a line)", lambda: vertical_runs(with_lugs(b, line)))
    add("nearly collinear (1 mm off the line)", lambda: vertical_runs(with_lugs(b, nearly)))
    add("CG on the support edge (y = 6 m)", lambda: vertical_runs(b.with_body(cog=(0.0, 6.0, 2.5))))
    add("CG 1 m beyond the edge", lambda: vertical_runs(b.with_body(cog=(0.0, 7.0, 2.5))))
    add("CG 5 m off centre, inside", lambda: vertical_runs(b.with_body(cog=(5.0, 3.0, 2.5))))
    for k in (1e7, 1e10, 1e13):
        stiff = b
        for c in b.cranes:
            stiff = stiff.with_crane(c.lug, EA=k * c.rope_length)
        add(
            f"stiff ropes, EA/l = {k:.0e} t/m",
            lambda s=stiff: vertical_runs(s.with_body(cog=(2.0, 1.0, 2.5))),
        )
    for heel in (30.0, 60.0, 85.0, 90.0):
        add(f"heel {heel:g} deg", lambda h=heel: attitude_runs(b, h))
    add("heel 20, trim 20 deg", lambda: attitude_runs(b, 20.0, 20.0))
    capsized = load_scene(EXAMPLES / "tanker_capsized.toml")
    add("capsized tanker, 3.56 m lug spacing", lambda: attitude_runs(capsized, 0.0))
    add("capsized tanker, heel 2 deg", lambda: attitude_runs(capsized, 2.0))
    add("capsized tanker, heel 10 deg", lambda: attitude_runs(capsized, 10.0))
    two = b
    for name in ("FS", "AS"):
        two = two.with_crane(name, boom_height=30.0)  # starboard hooks 10 m low: slack
    add(
        "starboard hooks lowered 10 m (the body heels until 4 ropes pull)",
        lambda: [("elastic", lambda: solve(two, "elastic"), two)],
        ("elastic",),
    )
    out.update(water_cases())
    return out


def water_cases():
    from liftplan.model.frames import rotation_matrix as rot
    from liftplan.model.scene.hull import Hull
    from liftplan.model.scene.objects import Body, Ground, Water
    from liftplan.model.water import Start, WaterSetup, solve_in_water

    out = {}
    box = Hull.box([-50, -15, -5], [50, 15, 5])
    barge = Scene(
        body=Body(20000.0, (5.0, 0.0, 2.0)),
        ground=Ground((30.0, 0.0, -5.0)),
        water=Water(density=1.0273),
        hull=box,
    )
    setup = WaterSetup(barge)
    for offset in (0.0, 10.0, 20.0, 45.0):
        start = Start(setup.start.zo, rot(offset, offset / 4))
        out[f"stranded barge, start {offset:g} deg off"] = [
            (method, lambda m=method, s=start: solve_in_water(barge, method=m, setup=setup, start=s), barge)
            for method in ("newton", "paper-newton")
        ]
    lift = load_scene(EXAMPLES / "sunken_block_lift.toml")
    free = dataclasses.replace(lift, ground=None)
    for label, hoist in (
        ("hanging fully submerged", 0.0),
        ("leaving the water", 17.0),
        ("clear of the water", 30.0),
    ):
        scene = free
        for c in free.cranes:
            scene = scene.with_crane(c.lug, boom_height=c.boom_height + hoist)
        out[f"flooded block {label} (hoist +{hoist:g} m)"] = [
            ("hydrostatic", lambda s=scene: solve(s), scene)
        ]
    return out


# -- the stiff-rope limit ------------------------------------------------------------------
def stiff_limit():
    """Elastic tensions as EA/l grows, against the rigid (compatible) limit."""
    b = block().with_body(cog=(2.0, 1.0, 2.5))
    limit = np.array(list(solve(b, "paper-elastic").tensions.values()))  # equal k, level
    rows = []
    for k in np.logspace(2, 14, 25):
        scene = b
        for c in b.cranes:
            scene = scene.with_crane(c.lug, EA=float(k * c.rope_length))
        # conditioning: a tension moves k dz for a height error dz, and the heights carry
        # float64 rounding eps |H|: the attainable tension accuracy is ~ k |H| eps
        boom = max(c.boom_height for c in scene.cranes)
        row = {
            "stiffness": float(k),
            "sensitivity": float(k * boom / scene.body.weight),
            "rounding_floor": float(k * boom * np.finfo(float).eps),
            "tolerance": 1e-9 * scene.body.weight,
        }
        try:
            eq = solve(scene, "elastic")
            t = np.array(list(eq.tensions.values()))
            row.update(
                outcome="ok", distance=float(np.max(np.abs(t - limit))), heel=eq.pose.heel, trim=eq.pose.trim
            )
        except LiftPlanError as err:
            row.update(outcome="refused", detail=str(err)[:150])
        rows.append(row)
    return {"limit": limit.tolist(), "rows": rows}


# -- data, then the table and figure drawn from it ------------------------------------------
def main():
    table = []
    for name, runs in cases().items():
        for method, run, scene in runs:
            table.append({"case": name, "method": method, **outcome(run, scene)})
    OUT.mkdir(exist_ok=True)
    data = {"cases": table, "stiff_limit": stiff_limit()}
    (OUT / "failure_modes.json").write_text(json.dumps(data, indent=1))
    report(OUT / "failure_modes.json")


def report(path):
    data = json.loads(path.read_text())
    lines = ["| case | method | outcome | detail |", "|---|---|---|---|"]
    for r in data["cases"]:
        lines.append(f"| {r['case']} | {r['method']} | {r['outcome']} | {r['detail']} |")
    counts = {}
    for r in data["cases"]:
        counts[r["outcome"]] = counts.get(r["outcome"], 0) + 1
    lines += ["", "outcomes: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())), ""]
    lines += [
        "Stiff-rope limit (symmetric block, CG (2, 1, 2.5)): elastic tensions against the "
        "rigid compatible limit "
        + ", ".join(f"{v:.3f}" for v in data["stiff_limit"]["limit"])
        + " t. Sensitivity: k H / W, the relative tension change per relative height "
        "change; rounding floor: k H eps, the tension accuracy float64 heights allow, "
        "against the 1e-9 W tolerance.",
        "",
        "| EA/l [t/m] | outcome | max dT to the limit [t] | k H / W | rounding floor [t] |",
        "|---|---|---|---|---|",
    ]
    for r in data["stiff_limit"]["rows"]:
        head = f"| {r['stiffness']:.1e} | {r['outcome']} | "
        tail = f" | {r['sensitivity']:.1e} | {r['rounding_floor']:.1e} |"
        lines.append(head + (f"{r['distance']:.2e}" if r["outcome"] == "ok" else r["detail"][:70]) + tail)
    text = "\n".join(lines) + "\n"
    (OUT / "failure_modes.md").write_text(text)
    print(text)
    draw(data["stiff_limit"], OUT / "stiff_limit.png")


def draw(limit, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ok = [r for r in limit["rows"] if r["outcome"] == "ok"]
    refused = [r for r in limit["rows"] if r["outcome"] != "ok"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    k = np.array([r["stiffness"] for r in ok])
    ax.loglog(k, [max(r["distance"], 1e-16) for r in ok], "o-", label="max |T - T_rigid| [t]")
    every = np.array([r["stiffness"] for r in limit["rows"]])
    ax.loglog(every, [r["rounding_floor"] for r in limit["rows"]], "s-", label="rounding floor k H eps [t]")
    ax.axhline(limit["rows"][0]["tolerance"], color="k", ls=":", label="tolerance 1e-9 W")
    for r in refused:
        ax.axvline(r["stiffness"], color="r", alpha=0.3)
    if refused:
        ax.axvline(refused[0]["stiffness"], color="r", alpha=0.3, label="refused (tolerance unreachable)")
    ax.set_xlabel("rope stiffness EA / l  [t/m]")
    ax.set_title(
        "Elastic model tends to the rigid one as EA/l grows (symmetric block, CG off centre)", fontsize=9
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    main()
