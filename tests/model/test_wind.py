"""Wind on the body (its couple on the vertical tensions) and on floating cranes' booms."""

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
from liftplan.model.scene.wind import GRAVITY, Wind, WindArea
from liftplan.model.scene.writer import scene_toml
from liftplan.model.solve_checks import equilibrium_checks

FLOATING = EXAMPLES / "tanker_floating.toml"
#: 20 m/s towards starboard: -y in z-up (the file's choi +z)
WIND = Wind(speed=20.0, direction=-90.0, body=WindArea(area=450.0, cd=1.2, height=9.0))


def _pose(eq):
    heel, trim = math.radians(eq.pose.heel), math.radians(eq.pose.trim)
    c, s = math.cos, math.sin
    rx = np.array([[1, 0, 0], [0, c(heel), -s(heel)], [0, s(heel), c(heel)]])
    ry = np.array([[c(trim), 0, s(trim)], [0, 1, 0], [-s(trim), 0, c(trim)]])
    return rx @ ry


def test_the_body_wind_couple_is_carried_by_the_tensions():
    """Cranes on land, 20 m/s on 450 m2 (Cd 1.2) at 9 m: F = 1/2 rho Cd A V^2 = 13.49 t, and the
    solved tensions balance the weight plus the couple F (h - h_lugs) about the lugs' height:
    sum T (x, y) = W (x_c, y_c) + F (h - h_lugs) d, to 1e-4 of the couple (the small pose
    tilts the lever), and the starboard ropes take more."""
    scene = load_scene(FLOATING)
    land = dataclasses.replace(scene, cranes=tuple(dataclasses.replace(c, vessel=None) for c in scene.cranes))
    windy = dataclasses.replace(land, wind=WIND)
    eq = solve(windy)
    force = 0.5 * 1.225e-3 * 1.2 * 450.0 * 20.0**2 / GRAVITY
    assert eq.wind.body_force == pytest.approx(force, rel=1e-12)
    rot = _pose(eq)
    lugs = scene.lug_points() @ rot.T + [0.0, 0.0, eq.pose.lift_height]
    cog = rot @ np.array(scene.body.cog) + [0.0, 0.0, eq.pose.lift_height]
    t = np.array([eq.tensions[n] for n in scene.lug_names])
    couple = force * (9.0 - 6.0)  # the lugs at 6 m
    moment = t @ lugs[:, :2] - scene.body.weight * cog[:2]
    assert moment == pytest.approx([0.0, -couple], abs=1e-4 * couple)
    calm = solve(land)
    assert eq.tensions["T1"] > calm.tensions["T1"] and eq.tensions["T4"] < calm.tensions["T4"]


def test_boom_wind_trims_its_vessel_and_moves_its_tip():
    """The wind on Sheerleg 1's boom (facing +y, the wind towards -y: on her stern) trims her
    by F h / (disp GM_L) stern down; her tip rises by x_t times it, and the rope law closes with
    the tip so moved: T = EA / l0 (H - drop - h - l0), drop the load's and the wind's."""
    scene = load_scene(FLOATING)
    boom = WindArea(area=120.0, cd=1.5, height=50.0, crane="Sheerleg 1")
    windy = dataclasses.replace(scene, wind=Wind(speed=20.0, direction=-90.0, booms=(boom,)))
    eq = solve(windy)
    force = 0.5 * 1.225e-3 * 1.5 * 120.0 * 400.0 / GRAVITY
    vessel = scene.crane("T1").vessel
    wind_trim = -force * 50.0 / vessel.trim_stiffness  # on her stern: stern down
    assert eq.wind.booms["Sheerleg 1"][2] == pytest.approx(math.degrees(wind_trim), rel=1e-12)
    forward, starboard = vessel.axes((16.2, -12.0))
    t = eq.tensions["T1"]
    load_trim = t * forward / vessel.trim_stiffness
    state = eq.vessels["Sheerleg 1"]
    assert state.trim == pytest.approx(math.degrees(load_trim + wind_trim), rel=1e-9)
    drop = t / vessel.heave_stiffness + starboard * t * starboard / vessel.heel_stiffness
    drop += forward * (load_trim + wind_trim)
    crane = scene.crane("T1")
    rot = _pose(eq)
    height = (rot @ np.array(next(g.at for g in scene.lugs if g.name == "T1")))[2] + eq.pose.lift_height
    assert t == pytest.approx(
        crane.EA / crane.rope_length * (crane.boom_height - drop - height - crane.rope_length), rel=1e-9
    )
    assert eq.wind.tip_drops["T1"] == pytest.approx(forward * wind_trim, rel=1e-12)


def test_wind_file_refusals_and_json():
    """The [wind] table reads in the papers' frame and writes back; a boom on land and the
    inclined model are refused in one line; solve --json's object carries "wind"."""
    text = FLOATING.read_text() + (
        "\n[wind]\nspeed = 20.0\ndirection = 90.0\nbody = { area = 450.0, cd = 1.2, height = 9.0 }\n"
        'booms = [{ crane = "Sheerleg 1", area = 120.0, cd = 1.5, height = 50.0 }]\n'
    )
    scene = loads_scene(text)
    assert scene.wind.direction == -90.0  # towards +z (starboard) in the file: -y in z-up
    assert loads_scene(scene_toml(scene)) == scene
    keys = {"body_force", "cog_shift", "booms", "tip_drops", "load_changes"}
    assert set(solve(scene).to_json()["wind"]) == keys
    land = scene.with_crane("T1", vessel=None)
    with pytest.raises(InvalidScene, match=r"wind.booms\[Sheerleg 1\]: the crane stands on land"):
        solve(land)
    tipped = dataclasses.replace(land, wind=WIND).with_crane("T2", vessel=None, tip=(65.6, -12.0, 40.0))
    tipped = dataclasses.replace(
        tipped, cranes=tuple(dataclasses.replace(c, vessel=None) for c in tipped.cranes)
    )
    with pytest.raises(InvalidScene, match="wind: modelled for vertical ropes"):
        solve(tipped.with_analysis(model="inclined"))


def test_the_wind_share_of_each_crane_load_is_shown_and_checked(tmp_path):
    """solve reports each rope's tension less its tension in still air (the same scene solved
    without the wind); the shares sum to zero (the ropes still carry W alone), and the SWL check
    takes the windy tension: an SWL between the still and the windy tension fails, its note
    giving the wind's share. The console and --json show the shares."""
    scene = load_scene(FLOATING)
    windy = dataclasses.replace(scene, wind=WIND)
    eq, calm = solve(windy), solve(scene)
    share = eq.wind.load_changes
    for name, tension in eq.tensions.items():
        assert share[name] == pytest.approx(tension - calm.tensions[name], abs=1e-12)
    assert sum(share.values()) == pytest.approx(0.0, abs=1e-9 * scene.body.weight)
    assert share["T1"] > 0.1  # the starboard ropes take the couple
    swl = 0.5 * (calm.tensions["T1"] + eq.tensions["T1"])
    limited = windy.with_crane("T1", swl=swl)
    checks = {(c.name, c.subject): c for c in equilibrium_checks(limited, solve(limited))}
    assert not checks["swl", "T1"].ok
    assert f"the wind's share {share['T1']:+.2f} t included" in checks["swl", "T1"].note
    still = {
        (c.name, c.subject): c for c in equilibrium_checks(scene, solve(scene.with_crane("T1", swl=swl)))
    }
    assert still["swl", "T1"].ok
    text = (
        FLOATING.read_text()
        + "\n[wind]\nspeed = 20.0\ndirection = 90.0\nbody = { area = 450.0, cd = 1.2, height = 9.0 }\n"
    )
    path = tmp_path / "windy.toml"
    path.write_text(text)
    data = json.loads(run("solve", str(path), "--json").stdout)
    assert data["wind"]["load_changes"]["T1"] == pytest.approx(share["T1"], rel=1e-9)
    console = run("solve", str(path)).stdout
    assert f"T1 {share['T1']:+.2f}" in console and "the wind's share of each rope's tension" in console
