"""The 3D view (issue 25): its geometry is the solved state's, the page is offline and carries
that geometry, the glTF and the print stills are written. The browser tests are in
tests/cli/test_view_browser.py."""

import json
import re
import tomllib

import numpy as np
import pytest
from helpers import EXAMPLES
from support.cli import run

from liftplan.model.errors import InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.lift import load_curve
from liftplan.model.scene.file import load_scene
from liftplan.model.solve import solve
from liftplan.planner.cli import main
from liftplan.planner.output.view.figure import lift_figure
from liftplan.planner.output.view.page import page
from liftplan.planner.output.view.states import lift_view, scene_view

TOL = 1e-6


def scene_data(html):
    """The ``liftplan-scene`` element's JSON, read as an outside tool would."""
    found = re.search(r'<script type="application/json" id="liftplan-scene">(.*?)</script>', html, re.S)
    assert found, "no liftplan-scene element"
    return json.loads(found.group(1))


def close(a, b, tol=TOL):
    return np.allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=0.0, atol=tol)


def test_solved_slings_scene_carries_the_solve_json(tmp_path, capsys):
    """Every leg's lug, upper end (hook) and tension in the page equal ``solve --json``'s: the
    lug from the JSON's pose and position applied to the file's lug, the hook from
    ``hook_positions``, the tension from ``legs``; the hoist ropes' from ``hook_loads``."""
    path = EXAMPLES / "block_two_slings.toml"
    out = tmp_path / "view.html"
    assert main(["solve", str(path), "--json", "--view", str(out)]) == 0
    solved = json.loads(capsys.readouterr().out)
    data = scene_data(out.read_text(encoding="utf-8"))
    assert data["frame"] == solved["frame"] == "z-up"
    (state,) = data["states"]
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    lugs = {lug["name"]: lug["at"] for lug in raw["lugs"]}
    rot = rotation_matrix(solved["heel"], solved["trim"], solved["yaw"])
    legs = {k: v for k, v in solved["legs"].items() if "/top" not in k}
    assert set(state["tensions"]) == set(legs)
    for key, tension in legs.items():
        crane, lug = key.split("/")
        assert abs(state["tensions"][key] - tension) <= TOL
        assert close(state["lugs"][key], rot @ np.asarray(lugs[lug]) + solved["position"])
        assert close(state["hooks"][key], solved["hook_positions"][crane]) or any(
            close(state["hooks"][key], end) for end in solved["spreaders"].get(crane, {}).get("ends", [])
        )
    hoists = {r["key"]: r for r in state["other_ropes"] if r["role"] == "hoist"}
    for crane, load in solved["hook_loads"].items():
        assert abs(hoists[crane]["tension"] - load) <= TOL
        assert close(hoists[crane]["ends"][0], solved["hook_positions"][crane])


def _planned_lugs(path, planned, level):
    """The level state's lugs where the planning file puts each chosen candidate (yaw and lift
    height applied), each rope's top at its boom height above it, its tension the plan's."""
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    assert raw.get("frame", "z-up") == "z-up"
    candidates = {c["name"]: c["at"] for c in raw["candidates"]}
    attitude = raw.get("attitude", {})
    rot = rotation_matrix(0.0, 0.0, attitude.get("yaw", 0.0))
    lift = np.array([0.0, 0.0, attitude.get("lift_height", 0.0)])
    assert set(level["tensions"]) == set(planned["tensions"])
    for label, tension in planned["tensions"].items():
        assert abs(level["tensions"][label] - tension) <= TOL
        lug = rot @ np.asarray(candidates[planned["lugs"][label]]) + lift
        assert close(level["lugs"][label], lug)
        assert close(level["hooks"][label], [lug[0], lug[1], planned["boom_heights"][label]])


def test_plan_view_carries_the_plan_json(tmp_path, capsys):
    """``plan --json --view FILE``: the page's level state holds the plan JSON's tensions, lugs
    and boom heights; its second state is the worst case the JSON names."""
    path = EXAMPLES / "sunken_block_plan.toml"
    out = tmp_path / "plan.html"
    assert main(["plan", str(path), "--json", "--view", str(out)]) == 0
    planned = json.loads(capsys.readouterr().out)
    level, worst = scene_data(out.read_text(encoding="utf-8"))["states"]
    assert level["name"] == "level" and worst["name"].startswith("worst case")
    _planned_lugs(path, planned, level)
    at = planned["worst_attitude"]
    assert f"heel {at['heel']:+.2f} deg" in worst["name"] and f"trim {at['trim']:+.2f} deg" in worst["name"]
    assert worst["tensions"] != level["tensions"]


@pytest.mark.slow
def test_report_carries_the_view_and_plan_json_views_again(tmp_path):
    """``plan --report DIR``: report.html carries the same element as ``--view``'s page, and
    ``liftplan view DIR/plan.json`` gives the same level state again (solved from
    plan_scene.toml)."""
    path = EXAMPLES / "sunken_block_plan.toml"
    report, out = tmp_path / "report", tmp_path / "plan.html"
    result = run("plan", str(path), "--report", str(report), "--view", str(out))
    assert result.returncode == 0, result.stderr
    planned = json.loads((report / "plan.json").read_text(encoding="utf-8"))
    in_report = scene_data((report / "report.html").read_text(encoding="utf-8"))
    assert in_report == scene_data(out.read_text(encoding="utf-8"))
    _planned_lugs(path, planned, in_report["states"][0])
    again = tmp_path / "again.html"
    result = run("view", str(report / "plan.json"), "--output", str(again), "--no-open")
    assert result.returncode == 0, result.stderr
    (state,) = scene_data(again.read_text(encoding="utf-8"))["states"]
    for label, tension in planned["tensions"].items():
        assert abs(state["tensions"][label] - tension) <= 1e-4 * tension  # solved again from the file
        assert close(state["lugs"][label], in_report["states"][0]["lugs"][label], 1e-4)


@pytest.fixture(scope="module")
def lift():
    scene = load_scene(EXAMPLES / "sunken_block_lift.toml")
    curve = load_curve(scene, step=2.0)
    return scene, curve, lift_view(scene, curve)


def test_lift_states_are_the_curve_rows(lift):
    """Each state of the lift's slider is a row of the load curve: its tensions, and each rope
    vertical from its lug to the boom height; the events each have a state."""
    scene, curve, view = lift
    data = view.scene_json()
    rows = {round(float(h), 9): t for h, t in zip(curve.hoist, curve.tensions)}
    assert data["states"][0]["name"].startswith("start: hoist 0.00 m")
    names = " ".join(s["name"] for s in data["states"])
    for event in curve.events:
        assert event.name in names
    heights = {c.lug: c.boom_height for c in scene.cranes}
    for state in data["states"]:
        assert f"hoist {state['hoist']:.2f} m" in state["name"]
        assert close([state["tensions"][n] for n in curve.lugs], rows[round(state["hoist"], 9)])
        for lug in curve.lugs:
            bottom, top = state["lugs"][lug], state["hooks"][lug]
            assert close(top, [bottom[0], bottom[1], heights[lug]])


def test_lift_state_places_the_body_at_its_solved_cg(lift):
    """The body drawn at a state has its CG where the solve put it (afloat.centre_of_gravity)."""
    scene, curve, view = lift
    for eq in curve.equilibria[:3]:
        state = scene_view(scene, eq).states[0]
        assert close(state.world([scene.body.cog])[0], eq.afloat.centre_of_gravity)
        rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
        assert close(np.asarray(state.rotation), rot)


def test_page_is_offline_and_the_slider_switches_states(lift):
    """One file: plotly's script inlined (no <script src>, no stylesheet or font link), the
    slider's steps show one state's traces each (no reload), view buttons and a label toggle."""
    _, _, view = lift
    html = page(view)
    assert "<script src" not in html and "<link" not in html
    assert 'type="text/javascript">/**\n* plotly.js' in html or "plotly.js v" in html
    fig = lift_figure(view)
    (slider,) = fig.layout.sliders
    assert len(slider.steps) == len(view.states) >= 4
    shown = [step.args[0]["visible"] for step in slider.steps]
    assert all(sum(a) > 0 for a in shown) and len({tuple(a) for a in shown}) == len(shown)
    labels = [b.label for menu in fig.layout.updatemenus for b in menu.buttons]
    assert {"plan view", "elevation (side)", "labels on", "labels off"} <= set(labels)


def test_glb_and_stills(tmp_path, lift):
    """The glTF reads back (trimesh) with the body, one cylinder per rope and the CG; the stills
    are a 3D view and a 2-D elevation to scale, with the ropes' colour bar."""
    import trimesh

    from liftplan.planner.output.view.gltf import glb_bytes
    from liftplan.planner.output.view.stills import stills

    _, _, view = lift
    path = tmp_path / "lift.glb"
    path.write_bytes(glb_bytes(view))
    loaded = trimesh.load(path, file_type="glb")
    names = set(loaded.graph.nodes_geometry)
    assert {"body", "CG"} <= names
    assert {f"rope {r.key}" for r in view.states[0].ropes if r.lower != r.upper} <= names
    fig = stills(view, state=2)
    assert sum(ax.name == "3d" for ax in fig.axes) == 1
    (side,) = [ax for ax in fig.axes if ax.name == "rectilinear" and ax.get_title()]
    assert side.get_aspect() == 1.0 and len(side.collections) >= 2  # to scale; body and ropes
    fig.savefig(tmp_path / "still.png", dpi=60)
    assert (tmp_path / "still.png").stat().st_size > 10_000


def test_view_refusals(tmp_path, capsys):
    """Each refused in one line, exit 2, before anything is solved."""
    json_only = tmp_path / "plan.json"
    json_only.write_text(json.dumps({"lugs": {"L1": "A"}}), encoding="utf-8")
    cases = [
        (["view", str(json_only), "--output", str(tmp_path / "a.html")], "no plan_scene.toml beside it"),
        (["view", str(tmp_path / "missing.toml")], "no such file"),
        (
            ["solve", str(EXAMPLES / "symmetric_block.toml"), "--view", str(tmp_path / "v.png")],
            "expected one of .html, .glb",
        ),
        (["view", str(json_only), "--lift"], "expected a scene file"),
    ]
    for args, words in cases:
        assert main(args) == 2
        err = capsys.readouterr().err
        assert words in err and len(err.strip().splitlines()) == 1, err


@pytest.mark.slow
def test_hull154_page_under_five_megabytes(tmp_path):
    """The 26-point hull's plan as one page: under 5 MB (plotly's script is 4.8 MB of it)."""
    out = tmp_path / "hull154.html"
    result = run("view", str(EXAMPLES / "hull154_plan.toml"), "--output", str(out), "--no-open")
    assert result.returncode == 0, result.stderr
    size = out.stat().st_size
    assert size < 5_000_000, size
    data = scene_data(out.read_text(encoding="utf-8"))
    assert len(data["states"][0]["tensions"]) == 26


def test_python_api_returns_the_figure(tmp_path):
    """``view_figure`` gives the plotly Figure (what a notebook shows), ``write_view`` the file."""
    import plotly.graph_objects as go

    from liftplan.planner import view_figure, write_view

    scene = load_scene(EXAMPLES / "block_two_slings.toml")
    eq = solve(scene)
    fig = view_figure(eq, scene)
    assert isinstance(fig, go.Figure)
    axes = [getattr(fig.layout.scene, f"{a}axis").range for a in "xyz"]
    ratio = fig.layout.scene.aspectratio
    sides = [hi - lo for lo, hi in axes]
    assert close([ratio.x, ratio.y, ratio.z], np.array(sides) * ratio.x / sides[0])  # true proportions
    assert fig.layout.scene.zaxis.title.text == "z [m], up"
    path = write_view(eq, tmp_path / "slings.html", scene)
    (state,) = scene_data(path.read_text(encoding="utf-8"))["states"]
    assert state["tensions"] == {k: v for k, v in eq.rigging.legs.items() if "/top" not in k}
    with pytest.raises(InvalidScene, match="expected its scene too"):
        view_figure(eq)
    with pytest.raises(InvalidScene, match="expected one of .html, .glb"):
        write_view(eq, tmp_path / "x.png", scene)


def test_64_ropes_stay_readable():
    """At 64 ropes the lug labels start hidden (a button shows them), every rope still names
    itself on hover, and the plan and elevation buttons turn the camera."""
    scene = load_scene(EXAMPLES / "hull154_64_points.toml")
    view = scene_view(scene, solve(scene))
    fig = lift_figure(view)
    lugs = [t for t in fig.data if t.name == "lugs (chosen)"]
    assert len(lugs) == 1 and lugs[0].mode == "markers" and len(lugs[0].text) == 64
    (labels,) = [m for m in fig.layout.updatemenus if m.buttons[0].label == "labels on"]
    index = fig.data.index(lugs[0])
    assert labels.buttons[0].args[0] == {"mode": "markers+text"} and list(labels.buttons[0].args[1]) == [
        index
    ]
    (ropes,) = [t for t in fig.data if t.name.startswith("ropes")]
    named = {h.split(" ")[0] for h in ropes.hovertext if h}
    assert named == set(scene.lug_names)
    cameras = {b.label: b.args[0]["scene.camera"] for b in fig.layout.updatemenus[0].buttons}
    assert cameras["plan view"]["eye"]["z"] > 0 and cameras["plan view"]["up"]["y"] == 1.0
    assert cameras["elevation (side)"]["eye"]["y"] < 0 and cameras["elevation (side)"]["up"]["z"] == 1.0
