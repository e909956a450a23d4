"""Crane vessels as hull meshes (``vessel = { box | mesh, displacement, cog, origin }``): the
clipped-mesh hydrostatics of each vessel solved with the body.

A box barge at small angles is the linear vessel with the box's waterplane and metacentric
heights (closed forms); at a large heel the coupled solve equals an independent numpy Newton
written out here (the box's wet volume and its centre in closed form while the waterline
crosses her sides)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import load_scene, loads_scene
from liftplan.model.scene.hull import Hull
from liftplan.model.scene.hullfit import write_stl
from liftplan.model.scene.vessel import Vessel
from liftplan.planner.problem.file import loads_problem

TWIN = EXAMPLES / "tanker_twin_barge.toml"
SIZES = {"T1": (100.0, 30.0, 8.0), "T3": (80.0, 35.0, 7.0), "T4": (80.0, 35.0, 7.0)}


def _box_vessel(linear, size, gm_t=None):
    """A box barge L x B x D centred on the linear vessel's flotation centre, her KG set so her
    GM_T is the linear vessel's (or ``gm_t``): the box's closed forms KB = T / 2, BM = B^2 / (12 T)."""
    length, beam, depth = size
    draft = linear.displacement / (linear.density * length * beam)
    gm_t = linear.gm_t if gm_t is None else gm_t
    kg = draft / 2 + beam**2 / (12 * draft) - gm_t
    hull = Hull.box((-length / 2, -beam / 2, 0.0), (length / 2, beam / 2, depth))
    boxed = Vessel(
        displacement=linear.displacement,
        hull=hull,
        cog=(0.0, 0.0, kg),
        origin=linear.flotation,
        heading=linear.heading,
    )
    gm_l = draft / 2 + length**2 / (12 * draft) - kg
    return boxed, dataclasses.replace(linear, waterplane_area=length * beam, gm_t=gm_t, gm_l=gm_l)


def _scenes(scene, gm_t=None):
    """The scene with every vessel a box barge, and with each one's linear equivalent."""
    boxes, linear = scene, scene
    for lug, size in SIZES.items():
        boxed, flat = _box_vessel(scene.crane(lug).vessel, size, gm_t if lug == "T1" else None)
        boxes, linear = boxes.with_crane(lug, vessel=boxed), linear.with_crane(lug, vessel=flat)
    return boxes, linear


def test_a_box_barge_at_small_angles_is_the_linear_vessel():
    """With the body 1/1000 of the tanker's weight (hook loads ~0.003 % of each displacement) the
    box barges' tensions, heaves, heels, trims and tip drops equal the linear vessels' (waterplane
    L B, GM from the box's closed form) to 1e-3 of their size; the differences are the loads'
    own displacement and their arm at the tips' height as she heels (first order in T / disp,
    shrinking with the load: at the full weight they are ten times as large or more)."""
    light = load_scene(TWIN)
    light = dataclasses.replace(light, body=dataclasses.replace(light.body, weight=light.body.weight / 1000))
    boxes, linear = _scenes(light)
    a, b = solve(boxes), solve(linear)
    w = light.body.weight
    assert a.solver.method == "newton (body and hull vessels)"
    for name in light.lug_names:
        assert a.tensions[name] == pytest.approx(b.tensions[name], abs=1e-4 * w)
    errors = []
    for name, state in b.vessels.items():
        box = a.vessels[name]
        for key in ("heave", "heel", "trim"):
            assert getattr(box, key) == pytest.approx(
                getattr(state, key), abs=1e-3 * abs(getattr(state, key)) + 1e-12
            )
        for lug, drop in state.tip_drops.items():
            assert box.tip_drops[lug] == pytest.approx(drop, rel=1e-3)
            errors.append(abs(box.tip_drops[lug] / drop - 1.0))
    full_boxes, full_linear = _scenes(load_scene(TWIN))
    a, b = solve(full_boxes), solve(full_linear)
    full = [
        abs(a.vessels[n].tip_drops[g] / d - 1.0) for n, s in b.vessels.items() for g, d in s.tip_drops.items()
    ]
    assert max(full) > 10 * max(errors)


def _rot(axis, angle):
    c, s = math.cos(angle), math.sin(angle)
    if axis == "x":
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == "y":
        return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def _wet_box(size, rot, zo):
    """A box (x, y centred, z from 0 to D) cut by the water: wet volume and its centre, her axes,
    in closed form while the waterline crosses her four sides (h(x, y) in (0, D) over her plan)."""
    length, beam, depth = size
    normal = rot[2]  # the world's vertical in her axes: the plane is normal . v + zo = 0
    h0, ax, by = -zo / normal[2], -normal[0] / normal[2], -normal[1] / normal[2]
    corners = [h0 + ax * x + by * y for x in (-length / 2, length / 2) for y in (-beam / 2, beam / 2)]
    inside = 0.0 < min(corners) and max(corners) < depth  # the closed form's range
    ixx, iyy = length**3 * beam / 12, length * beam**3 / 12
    volume = length * beam * h0
    first = np.array([ax * ixx, by * iyy, 0.5 * (length * beam * h0**2 + ax**2 * ixx + by**2 * iyy)])
    return volume, first / volume, inside


def _numpy_newton(scene):
    """The body on its ropes and each box barge under her hooks, written out: unknowns (a,
    heel, trim) and per barge (zo, heel, trim) with R = Rz(heading) Rx(heel) Ry(trim); residual:
    vertical-rope statics and each barge's force and moments; Newton, central differences."""
    lugs = {g.name: np.array(g.at) for g in scene.lugs}
    barges = [(name, v, on) for name, (v, on) in scene.vessels.items()]
    sizes = [SIZES[scene.cranes[on[0]].lug] for _, _, on in barges]
    w, g = scene.body.weight, np.array(scene.body.cog)
    local = {}
    for (_, v, on), size in zip(barges, sizes):
        draft = v.displacement / (v.density * size[0] * size[1])  # at rest, level (cog on her centreline)
        for i in on:
            c = scene.cranes[i]
            plan = lugs[c.lug][:2] - np.array(v.origin)
            local[i] = _rot("z", -math.radians(v.heading)) @ np.array([*plan, c.boom_height + draft])

    ranges = []

    def residual(z):
        body = _rot("x", z[1]) @ _rot("y", z[2])
        tips = {}
        poses = []
        for k, (_, v, on) in enumerate(barges):
            zo, heel, trim = z[3 + 3 * k : 6 + 3 * k]
            rot = _rot("z", math.radians(v.heading)) @ _rot("x", heel) @ _rot("y", trim)
            poses.append((rot, zo))
            for i in on:
                tips[i] = rot @ local[i] + [0.0, 0.0, zo]  # relative to the point above her origin
        t = []
        for i, c in enumerate(scene.cranes):
            lug = body @ lugs[c.lug] + [0.0, 0.0, z[0]]
            t.append(c.EA / c.rope_length * max(0.0, tips[i][2] - lug[2] - c.rope_length))
        t = np.array(t)
        points = np.array([body @ lugs[c.lug] for c in scene.cranes])
        cg = body @ g
        out = [t.sum() - w, t @ points[:, 0] - w * cg[0], t @ points[:, 1] - w * cg[1]]
        for (_, v, on), size, (rot, zo) in zip(barges, sizes, poses):
            volume, centre, inside = _wet_box(size, rot, zo)
            ranges.append(inside)
            b = v.density * volume
            cb = rot @ centre + [0.0, 0.0, zo]
            cw = rot @ np.array(v.cog) + [0.0, 0.0, zo]
            loads = [(t[i], tips[i]) for i in on]
            out += [
                b - v.displacement - sum(f for f, _ in loads),
                b * cb[1] - v.displacement * cw[1] - sum(f * p[1] for f, p in loads),
                b * cb[0] - v.displacement * cw[0] - sum(f * p[0] for f, p in loads),
            ]
        return np.array(out), t

    z = np.zeros(3 + 3 * len(barges))
    z[0] = scene.attitude.lift_height
    for k, ((_, v, _), size) in enumerate(zip(barges, sizes)):
        z[3 + 3 * k] = -v.displacement / (v.density * size[0] * size[1])
    for _ in range(200):
        f, _ = residual(z)
        jac = np.empty((z.size, z.size))
        for j in range(z.size):
            dz = np.zeros(z.size)
            dz[j] = 1e-7
            jac[:, j] = (residual(z + dz)[0] - residual(z - dz)[0]) / 2e-7
        step = np.linalg.solve(jac, -f)
        z = z + step * min(1.0, 0.05 / np.max(np.abs(step)))  # steps of at most 0.05 m or rad
        if np.max(np.abs(step)) < 1e-13:
            break
    ranges.clear()
    f, t = residual(z)
    assert np.max(np.abs(f)) < 1e-7 * w and all(ranges)
    return dict(zip(scene.lug_names, t)), z


def test_a_barge_at_a_large_heel_against_an_independent_newton():
    """The twin-crane box barge with GM_T 5 m heels about 9 deg under her two hooks: the
    coupled solve equals the numpy Newton (box hydrostatics in closed form) to 1e-6 W in every
    tension and 1e-6 deg in her heel; the linear vessel is off by degrees there."""
    boxes, linear = _scenes(load_scene(TWIN), gm_t=5.0)
    eq = solve(boxes)
    tensions, z = _numpy_newton(boxes)
    worst = max(abs(eq.tensions[name] - tensions[name]) for name in boxes.lug_names)
    assert worst <= 1e-6 * boxes.body.weight
    barge = eq.vessels["Barge"]
    assert abs(barge.heel - math.degrees(z[4])) <= 1e-6 and abs(barge.trim - math.degrees(z[5])) <= 1e-6
    assert abs(barge.heel) > 8.0
    assert abs(solve(linear).vessels["Barge"].heel - barge.heel) > 1.0


def test_hull_vessel_keys_read_and_refused():
    """A box vessel from a scene file; one line for what is missing or not modelled."""
    text = TWIN.read_text()
    box = (
        "vessel = { box = { min = [-50.0, 0.0, -15.0], max = [50.0, 8.0, 15.0] }, displacement = 12000.0, "
        "cog = [0.0, 15.0, 0.0], origin = [40.9, 30.0], heading = 0.0 }"
    )
    old = next(line for line in text.splitlines() if line.startswith("vessel = { displacement = 12000.0"))
    scene = loads_scene(text.replace(old, box), base=EXAMPLES)
    barge = scene.crane("T1").vessel
    assert barge.cog == (0.0, 0.0, 15.0) and barge.origin == (40.9, -30.0)  # the papers' frame, in z-up
    corners = np.asarray(barge.hull.triangles).reshape(-1, 3)
    assert corners.min(axis=0).tolist() == [-50.0, -15.0, 0.0] and corners.max(axis=0).tolist() == [
        50.0,
        15.0,
        8.0,
    ]
    with pytest.raises(InvalidScene, match="small-angle vessels with hull vessels"):
        solve(scene)
    with pytest.raises(InvalidScene, match="vessel.gm_t given with the vessel's hull"):
        loads_scene(text.replace(old, box.replace("heading = 0.0", "heading = 0.0, gm_t = 6.0")))
    with pytest.raises(InvalidScene, match="vessel.cog: missing with the vessel's hull"):
        loads_scene(text.replace(old, box.replace("cog = [0.0, 15.0, 0.0], ", "")))
    boxes, _ = _scenes(load_scene(TWIN))
    with pytest.raises(InvalidScene, match="modelled with the elastic model in air"):
        solve(boxes, model="rigid")


def test_a_mesh_file_is_the_box_it_describes(tmp_path):
    """``mesh = "barge.stl"`` (the barge's box written as an ASCII STL, read relative to the
    scene file) solves as ``box`` does: same tensions to 1e-9 W, same heel to 1e-9 deg."""
    text = TWIN.read_text()
    old = next(line for line in text.splitlines() if line.startswith("vessel = { displacement = 12000.0"))
    hull = "box = { min = [-50.0, 0.0, -15.0], max = [50.0, 8.0, 15.0] }"
    rest = "displacement = 12000.0, cog = [0.0, 13.17, 0.0], origin = [40.9, 30.0], heading = 0.0 }"
    boxed = loads_scene(text.replace(old, f"vessel = {{ {hull}, {rest}"), base=tmp_path)
    triangles = np.asarray(boxed.crane("T1").vessel.hull.triangles)
    in_file = triangles[..., [0, 2, 1]] * [1.0, 1.0, -1.0]  # z-up (x, y, z) -> the papers' (x, z, -y)
    write_stl(in_file, tmp_path / "barge.stl", binary=False)
    meshed = loads_scene(text.replace(old, f'vessel = {{ mesh = "barge.stl", {rest}'), base=tmp_path)
    scenes = []
    for scene in (boxed, meshed):  # the sheerlegs as boxes too (one model of vessels per scene)
        for lug in ("T3", "T4"):
            scene = scene.with_crane(lug, vessel=_box_vessel(scene.crane(lug).vessel, SIZES[lug])[0])
        scenes.append(scene)
    a, b = (solve(s) for s in scenes)
    for name in boxed.lug_names:
        assert a.tensions[name] == pytest.approx(b.tensions[name], abs=1e-9 * boxed.body.weight)
    assert a.vessels["Barge"].heel == pytest.approx(b.vessels["Barge"].heel, abs=1e-9)


def test_a_planning_file_refuses_a_hull_vessel():
    """The planner takes small-angle vessels only: a box vessel in a planning file is refused
    in one line naming the key and what is expected."""
    text = (EXAMPLES / "tanker_floating_fleet.toml").read_text()
    old = next(line for line in text.splitlines() if line.startswith("vessel = { displacement"))
    box = (
        "vessel = { box = { min = [-40.0, 0.0, -17.5], max = [40.0, 7.0, 17.5] }, displacement = 9000.0, "
        "cog = [0.0, 28.0, 0.0], origin = [16.2, 52.0], heading = -90.0 }"
    )
    with pytest.raises(
        InvalidScene, match="vessel.box: a vessel given by her hull is solved by liftplan solve"
    ):
        loads_problem(text.replace(old, box, 1), base=EXAMPLES)
