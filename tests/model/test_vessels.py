"""Floating cranes: the boom tip moves with its vessel under the hook load.

Closed forms of one vessel (heave, heel, trim, tip drop, and the rope law they close), the
series-stiffness equivalence of four vessels each under one crane, and an independent numpy
Newton for a vessel under two cranes, where no rope-by-rope stiffness reproduces the
coupling.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from helpers import EXAMPLES
from support.cli import run

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import load_scene, loads_scene
from liftplan.model.scene.vessel import Vessel
from liftplan.model.scene.writer import scene_toml
from liftplan.model.solve_checks import equilibrium_checks
from liftplan.model.statics.floating import solve_coupled

FLOATING = EXAMPLES / "tanker_floating.toml"
SHEERLEG = {"displacement": 9000.0, "waterplane_area": 2800.0, "gm_t": 6.0, "gm_l": 180.0}


def _tanker():
    return load_scene(FLOATING)


def _on_land(scene, keep=()):
    """The scene with every crane but those in ``keep`` (lug names) on land."""
    return dataclasses.replace(
        scene,
        cranes=tuple(c if c.lug in keep else dataclasses.replace(c, vessel=None) for c in scene.cranes),
    )


def _lug_height(scene, eq, lug):
    """World height of a lug at the solved pose, from docs/conventions.md (R = Rx Rz Ry)."""
    heel, trim, yaw = (math.radians(v) for v in (eq.pose.heel, eq.pose.trim, eq.pose.yaw))
    c, s = math.cos, math.sin
    rx = np.array([[1, 0, 0], [0, c(heel), -s(heel)], [0, s(heel), c(heel)]])
    rz = np.array([[c(yaw), -s(yaw), 0], [s(yaw), c(yaw), 0], [0, 0, 1]])
    ry = np.array([[c(trim), 0, s(trim)], [0, 1, 0], [-s(trim), 0, c(trim)]])
    at = np.array(next(g.at for g in scene.lugs if g.name == lug))
    return float((rx @ rz @ ry @ at)[2] + eq.pose.lift_height)


def test_one_vessel_closed_form():
    """Sheerleg 1 alone afloat (the others on land): its heave, heel, trim and tip drop are the
    small-angle closed forms of its hook load to 1e-9, with the signs of docs/conventions.md,
    and the tip so dropped closes the rope law T = EA / l0 (H - drop - h - l0)."""
    scene = dataclasses.replace(
        _on_land(_tanker(), keep=("T1",)),
        cranes=tuple(
            dataclasses.replace(c, vessel=dataclasses.replace(c.vessel, flotation=(26.2, -52.0)))
            if c.lug == "T1"
            else c
            for c in _on_land(_tanker(), keep=("T1",)).cranes
        ),
    )
    eq = solve(scene)
    state = eq.vessels["Sheerleg 1"]
    t = eq.tensions["T1"]
    # z-up: T1 at plan (16.2, -12), the flotation centre at (26.2, -52), the bow heading +y
    # (the file's -90 deg from +x towards starboard). Facing +y the vessel's starboard is +x:
    # the tip is 40 m ahead of the flotation centre and 10 m to port of it.
    forward, starboard = 40.0, -10.0
    assert scene.crane("T1").vessel.axes((16.2, -12.0)) == pytest.approx((forward, starboard), abs=1e-12)
    heave = t / (1.025 * 2800.0)
    heel = t * starboard / (9000.0 * 6.0)
    trim = t * forward / (9000.0 * 180.0)
    assert state.heave == pytest.approx(heave, rel=1e-9)
    assert state.heel == pytest.approx(math.degrees(heel), rel=1e-9)
    assert state.trim == pytest.approx(math.degrees(trim), rel=1e-9)
    assert state.heel < 0.0 < state.trim  # the hook to port and ahead: port side down, bow down
    drop = heave + starboard * heel + forward * trim
    assert state.tip_drop == pytest.approx(drop, rel=1e-9)
    crane = scene.crane("T1")
    stretch = crane.boom_height - drop - _lug_height(scene, eq, "T1") - crane.rope_length
    assert t == pytest.approx(crane.EA / crane.rope_length * stretch, rel=1e-9)
    # the cranes on land keep their fixed tips
    land = scene.crane("T2")
    stretch = land.boom_height - _lug_height(scene, eq, "T2") - land.rope_length
    assert eq.tensions["T2"] == pytest.approx(land.EA / land.rope_length * stretch, rel=1e-9)


def _series(scene):
    """The rope-only scene with each rope's EA replaced by its series stiffness with its
    vessel, from the closed forms written out here."""
    cranes = []
    for crane in scene.cranes:
        v = crane.vessel
        lug = next(g.at for g in scene.lugs if g.name == crane.lug)
        h = math.radians(v.heading)
        dx, dy = lug[0] - v.flotation[0], lug[1] - v.flotation[1]
        x_t, y_t = dx * math.cos(h) + dy * math.sin(h), dx * math.sin(h) - dy * math.cos(h)
        c = 1.0 / (v.density * v.waterplane_area) + y_t**2 / (v.displacement * v.gm_t)
        c += x_t**2 / (v.displacement * v.gm_l)
        ea = crane.rope_length / (crane.rope_length / crane.EA + c)
        cranes.append(dataclasses.replace(crane, vessel=None, EA=ea))
    return dataclasses.replace(scene, cranes=tuple(cranes))


def test_four_vessels_equal_the_series_stiffness():
    """Four equal vessels on the tanker: the tensions of body and vessels solved together
    (Newton on 15 unknowns) equal the rope-only model's with each rope's stiffness replaced
    by the series stiffness, to 1e-9 W; the default solve (which uses the equivalence) too."""
    scene = _tanker()
    coupled = solve_coupled(scene)
    series = solve(_series(scene))
    default = solve(scene)
    w = scene.body.weight
    for name in scene.lug_names:
        assert coupled.tensions[name] == pytest.approx(series.tensions[name], abs=1e-9 * w)
        assert default.tensions[name] == pytest.approx(coupled.tensions[name], abs=1e-9 * w)
    assert coupled.pose.lift_height == pytest.approx(series.pose.lift_height, abs=1e-9)
    # the vessels matter: on land the same cranes share the weight differently
    land = solve(_on_land(scene))
    assert land.pose.lift_height - coupled.pose.lift_height > 0.3
    assert coupled.solver.method.startswith("newton (body and crane vessels)")


def _twin_scene():
    """T1 and T2 on one crane barge (a twin-crane vessel off the starboard side), T3 and T4 on
    sheerlegs (``examples/tanker_twin_barge.toml``); the barge heels by degrees (both hooks
    18 m to port of her centreline)."""
    return load_scene(EXAMPLES / "tanker_twin_barge.toml")


def _numpy_newton(scene):
    """The same physics written out independently: unknowns (a, heel, trim) and per vessel
    (heave, heel, trim); residual: vertical-rope statics and each vessel's balance; Newton with
    a central-difference Jacobian."""
    lugs = {g.name: np.array(g.at) for g in scene.lugs}
    names = list(lugs)
    vessels = {}
    for c in scene.cranes:
        if isinstance(c.vessel, Vessel):
            vessels[c.name or c.lug] = c.vessel
    order = list(vessels)
    where = {}
    for c in scene.cranes:
        if c.vessel is not None:
            owner = c.vessel if isinstance(c.vessel, str) else (c.name or c.lug)
            v = vessels[owner]
            h = math.radians(v.heading)
            dx, dy = lugs[c.lug][0] - v.flotation[0], lugs[c.lug][1] - v.flotation[1]
            where[c.lug] = (
                order.index(owner),
                dx * math.cos(h) + dy * math.sin(h),
                dx * math.sin(h) - dy * math.cos(h),
            )
    w, g = scene.body.weight, np.array(scene.body.cog)

    def rot(heel, trim):
        c, s = math.cos, math.sin
        rx = np.array([[1, 0, 0], [0, c(heel), -s(heel)], [0, s(heel), c(heel)]])
        ry = np.array([[c(trim), 0, s(trim)], [0, 1, 0], [-s(trim), 0, c(trim)]])
        return rx @ ry

    def residual(z):
        a, heel, trim = z[:3]
        q = z[3:].reshape(-1, 3)
        r = rot(heel, trim)
        tensions, points = [], []
        for c in scene.cranes:
            p = r @ lugs[c.lug] + [0.0, 0.0, a]
            drop = 0.0
            if c.lug in where:
                v, x_t, y_t = where[c.lug]
                drop = q[v, 0] + y_t * q[v, 1] + x_t * q[v, 2]
            s = c.boom_height - drop - p[2] - c.rope_length
            tensions.append(c.EA / c.rope_length * max(0.0, s))
            points.append(p)
        t, pts = np.array(tensions), np.array(points)
        cg = r @ g + [0.0, 0.0, a]
        out = [t.sum() - w, t @ pts[:, 0] - w * cg[0], t @ pts[:, 1] - w * cg[1]]
        for k, name in enumerate(order):
            v = vessels[name]
            on = [i for i, c in enumerate(scene.cranes) if c.lug in where and where[c.lug][0] == k]
            out += [
                v.density * v.waterplane_area * q[k, 0] - sum(t[i] for i in on),
                v.displacement * v.gm_t * q[k, 1] - sum(t[i] * where[scene.cranes[i].lug][2] for i in on),
                v.displacement * v.gm_l * q[k, 2] - sum(t[i] * where[scene.cranes[i].lug][1] for i in on),
            ]
        return np.array(out), t

    z = np.zeros(3 + 3 * len(order))
    z[0] = scene.attitude.lift_height
    for _ in range(50):
        f, _ = residual(z)
        jac = np.empty((z.size, z.size))
        for j in range(z.size):
            step = 1e-7 * max(1.0, abs(z[j]))
            dz = np.zeros(z.size)
            dz[j] = step
            jac[:, j] = (residual(z + dz)[0] - residual(z - dz)[0]) / (2 * step)
        dz = np.linalg.solve(jac, -f)
        z = z + dz
        if np.max(np.abs(dz)) < 1e-13:
            break
    f, t = residual(z)
    assert np.max(np.abs(f)) < 1e-6 * w
    return dict(zip(names, t)), z


def test_a_vessel_under_two_cranes_against_an_independent_newton():
    """Two cranes on one barge heeling by degrees: the coupled solve equals a numpy Newton of
    the same physics written out in the test to 1e-6 W (tensions) and 1e-6 deg (the barge's
    heel); no rope-by-rope series stiffness gives these tensions (off by more than 1e-3 W)."""
    scene = _twin_scene()
    eq = solve(scene)
    tensions, z = _numpy_newton(scene)
    w = scene.body.weight
    for name in scene.lug_names:
        assert eq.tensions[name] == pytest.approx(tensions[name], abs=1e-6 * w)
    barge = eq.vessels["Barge"]
    assert barge.heel == pytest.approx(math.degrees(z[4]), abs=1e-6)
    assert abs(barge.heel) > 2.0  # a large heel: the two hooks on one side of the barge
    assert set(barge.tip_drops) == {"T1", "T2"}
    # each rope in series with its own share of the barge: not the coupled answer
    own = dataclasses.replace(
        scene,
        cranes=tuple(
            dataclasses.replace(c, vessel=dataclasses.replace(scene.crane("T1").vessel))
            if c.lug == "T2"
            else c
            for c in scene.cranes
        ),
    )
    separate = solve(own)
    assert max(abs(separate.tensions[n] - eq.tensions[n]) for n in scene.lug_names) > 1e-3 * w


def test_levelling_ballast_and_heel_limit():
    """The levelling ballast set before the lift leaves each vessel level under the load; a
    heel beyond max_heel is a failed check."""
    scene = _twin_scene()
    eq = solve(scene)
    barge = eq.vessels["Barge"]
    ballasted = scene.with_crane(
        "T1",
        vessel=dataclasses.replace(scene.crane("T1").vessel, ballast=barge.levelling_ballast, max_heel=1.0),
    )
    level = solve(ballasted)
    assert level.tensions == pytest.approx(eq.tensions, abs=1e-9)  # ballast leaves the tips alone
    assert level.vessels["Barge"].heel == pytest.approx(0.0, abs=1e-9)
    assert level.vessels["Barge"].trim == pytest.approx(0.0, abs=1e-9)
    checks = {(c.name, c.subject): c for c in equilibrium_checks(ballasted, level)}
    assert checks["vessel_heel", "Barge"].ok
    limited = scene.with_crane("T1", vessel=dataclasses.replace(scene.crane("T1").vessel, max_heel=1.0))
    failed = {(c.name, c.subject): c for c in equilibrium_checks(limited, solve(limited))}
    assert not failed["vessel_heel", "Barge"].ok
    assert failed["vessel_heel", "Barge"].value == pytest.approx(abs(barge.heel))


def test_json_exit_code_and_refusals(tmp_path):
    """solve --json carries the contract's vessels block, and with --strict a vessel beyond its
    trim limit exits 4; models that hold the tips fixed, and a shared vessel no crane carries,
    are refused in one line."""
    path = tmp_path / "tight.toml"
    path.write_text(FLOATING.read_text().replace("max_trim = 1.0", "max_trim = 0.3"))
    out = run("solve", str(path), "--json", "--strict")
    assert out.returncode == 4, out.stderr
    data = json.loads(out.stdout)
    assert set(data["vessels"]) == {"Sheerleg 1", "Sheerleg 2", "Sheerleg 3", "Sheerleg 4"}
    assert {"heave", "heel", "trim", "tip_drop"} <= set(data["vessels"]["Sheerleg 1"])
    failed = {(c["name"], c["subject"]) for c in data["checks"] if not c["ok"]}
    assert failed == {("vessel_trim", "Sheerleg 1"), ("vessel_trim", "Sheerleg 4")}
    with pytest.raises(InvalidScene, match="paper-elastic model holds the boom tips fixed"):
        solve(_tanker(), model="paper-elastic")
    lines = FLOATING.read_text().splitlines()
    k = lines.index('name = "Sheerleg 2"')
    lines[k + 4] = 'vessel = "Nobody"'
    with pytest.raises(InvalidScene, match="'Nobody': no crane of that name carries a vessel table"):
        loads_scene("\n".join(lines))


def test_written_in_either_frame_reads_back():
    """The scene writer writes each vessel back in the file's frame: the z-up copy of the
    papers'-frame example solves to the same vessels."""
    scene = _tanker()
    zup = dataclasses.replace(scene, frame="z-up")
    back = loads_scene(scene_toml(zup))
    assert back == zup
    a, b = solve(scene), solve(back)
    for name in a.vessels:
        assert b.vessels[name].heel == pytest.approx(a.vessels[name].heel, abs=1e-12)
        assert b.vessels[name].trim == pytest.approx(a.vessels[name].trim, abs=1e-12)
