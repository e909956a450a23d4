"""The one scene writer (model/scene/writer.py, issue 30 item 3): every scene it writes reads
back to itself and solves to the same tensions.

Round trips of every scene file in examples/ (a hull, water or ground is refused in one line),
of the scenes of each kind of plan (held, fleet, two-crane slings, apex slings on 3 and 4
cranes with spreader bars, strength under force and hoist control) through the report's
plan_scene.toml, and of parts no example has (equalised slings, sling diameters, a girder
stiffness, names that need escaping). The strength plan's scene is checked against what it
stands for: the planned forces held (force control) or the planned boom heights (hoist).
"""

from __future__ import annotations

import dataclasses
import functools
import tomllib

import numpy as np
import pytest
from helpers import EXAMPLES
from hypothesis import given
from hypothesis import strategies as st
from support.fleet import fleet_problem
from support.planning import small_problem as held_problem
from support.slings import spreader_problem as _spreader_problem
from support.strength import small_problem as strength_problem

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.frames import zup_to_choi
from liftplan.model.scene.file import PLAN_TABLES, load_scene, loads_scene
from liftplan.model.scene.objects import (
    Analysis,
    Attitude,
    Body,
    Crane,
    GirderStiffness,
    Lug,
    Redundant,
    Scene,
    Strength,
    curve_totals,
)
from liftplan.model.scene.rigging_gear import Leg, RiggingLimits, Sling, Spreader
from liftplan.model.scene.tide import Tide
from liftplan.model.scene.vessel import Vessel
from liftplan.model.scene.wind import Wind, WindArea
from liftplan.model.scene.writer import scene_toml
from liftplan.planner.output.report import held as held_report
from liftplan.planner.output.report import slings as slings_report
from liftplan.planner.output.report import strength as strength_report
from liftplan.planner.plan import plan
from liftplan.planner.plans.strength import free_three
from liftplan.planner.problem.file import load_problem

#: Tensions of a written scene's solve against the original's  [t].
SAME = 1e-9


def _scene_files():
    """Every example that is a scene file (not a planning file or a study)."""
    out = []
    for path in sorted(EXAMPLES.glob("*.toml")):
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
        if "body" in raw and not any(key in raw for key in PLAN_TABLES):
            out.append(path)
    return out


SCENE_FILES = _scene_files()
IN_AIR = [p for p in SCENE_FILES if not {"water", "ground"} & tomllib.loads(p.read_text()).keys()]
IN_WATER = [p for p in SCENE_FILES if p not in IN_AIR]


def assert_round_trip(scene, text=None):
    """``scene`` written (or ``text``) reads back equal and solves to the same tensions."""
    text = scene_toml(scene) if text is None else text
    back = loads_scene(text)
    assert back == scene
    first, second = solve(scene), solve(back)
    assert second.model == first.model
    assert second.tensions.keys() == first.tensions.keys()
    for key, value in first.tensions.items():
        assert second.tensions[key] == pytest.approx(value, abs=SAME)
    return back


def test_the_examples_hold_scenes_in_air_and_in_water():
    assert len(IN_AIR) >= 8 and len(IN_WATER) >= 4
    assert {p.stem for p in IN_AIR} >= {
        "tanker_upright",
        "tanker_flexible",
        "tanker_strength",
        "block_two_slings",
    }


@pytest.mark.parametrize("path", IN_AIR, ids=lambda p: p.stem)
def test_every_example_scene_in_air_round_trips(path):
    scene = load_scene(path)
    assert_round_trip(scene)


@pytest.mark.parametrize("path", IN_WATER, ids=lambda p: p.stem)
def test_a_hull_water_or_ground_is_refused_in_one_line(path):
    scene = load_scene(path)
    with pytest.raises(InvalidScene) as err:
        scene_toml(scene)
    message = str(err.value)
    assert "\n" not in message
    part = "water" if scene.water is not None else "ground" if scene.ground is not None else "hull"
    assert message.startswith(f"[{part}]:") and "expected a body in air" in message


def test_coordinates_are_written_in_the_scenes_frame():
    """A choi scene is written in choi (the file's own numbers come back), every point
    converted, the weight curve's x (the same axis in both frames) as it is."""
    scene = load_scene(EXAMPLES / "tanker_upright.toml")
    assert scene.frame == "choi"
    raw = tomllib.loads(scene_toml(scene))
    original = tomllib.loads((EXAMPLES / "tanker_upright.toml").read_text(encoding="utf-8"))
    assert raw["frame"] == "choi"
    assert tuple(raw["body"]["cog"]) == zup_to_choi(scene.body.cog) == tuple(original["body"]["cog"])
    for lug, written in zip(scene.lugs, raw["lugs"]):
        assert tuple(written["at"]) == zup_to_choi(lug.at)
    zup = loads_scene(scene_toml(dataclasses.replace(scene, frame="z-up")))
    assert zup.frame == "z-up" and zup.lugs == scene.lugs and zup.body == scene.body


# -- the scenes of the plans, through the report's plan_scene.toml -------------------------------
#: The plans whose scenes are written: name -> the problem (helpers of the tests named).
PROBLEMS = {
    "held": lambda: held_problem(4),
    "held, choi frame": lambda: load_problem(EXAMPLES / "tanker_plan.toml"),
    "fleet": lambda: fleet_problem(3),
    "two-crane slings": lambda: load_problem(EXAMPLES / "block_sling_plan.toml"),
    "four cranes, 4-leg apexes": lambda: load_problem(EXAMPLES / "block_four_leg_plan.toml"),
    "three cranes, hinged pairs": lambda: load_problem(EXAMPLES / "block_three_slings_plan.toml"),
    "four cranes, spreader bars": _spreader_problem,
    "strength, force": lambda: strength_problem("force", cranes=5),
    "strength, hoist": lambda: strength_problem("hoist", cranes=4),
}


@functools.cache
def planned(name):
    """The plan of ``PROBLEMS[name]``, planned once per run."""
    return plan(PROBLEMS[name]())


# the hoist-control plan takes 12 s to make (tests/cli/test_strength_report.py solves its
# written scene in the default run too): with -m slow
@pytest.fixture(params=["strength, force", pytest.param("strength, hoist", marks=pytest.mark.slow)])
def strength_plan(request):
    return planned(request.param)


@pytest.mark.parametrize("name", ["held", "held, choi frame", "fleet"])
def test_held_plans_scene_file_round_trips_and_gives_the_plans_tensions(name):
    result = planned(name)
    assert result.kind == "held"
    text = held_report.plan_scene_toml(result)
    back = assert_round_trip(result.named_scene, text)
    # the plan's own scene (labels L1..Ln) under the candidate and crane names, file frame
    assert back.frame == result.frame
    assert back.lug_names == tuple(result.lugs.values())
    assert [c.name for c in back.cranes] == list(result.cranes.values())
    for label, candidate in result.lugs.items():
        mine, theirs = back.crane(candidate), result.scene.crane(label)
        assert dataclasses.replace(mine, lug=label, name=None) == theirs
    eq = solve(back)
    for label, tension in result.tensions.items():
        assert eq.tensions[result.lugs[label]] == pytest.approx(tension, abs=1e-6)
    assert text.startswith("# Written by liftplan plan: the chosen lugs of")
    assert f"(planned lug {result.labels[0]})" in text


@pytest.mark.parametrize(
    "name",
    [
        "two-crane slings",
        "four cranes, 4-leg apexes",
        "three cranes, hinged pairs",
        "four cranes, spreader bars",
    ],
)
def test_sling_plans_scene_file_round_trips_and_gives_the_hook_loads(name):
    result = planned(name)
    assert result.kind == "slings"
    text = slings_report.plan_scene_toml(result)
    back = assert_round_trip(result.scene, text)
    assert back.frame == result.problem.frame and back.slings
    eq = solve(back)
    for crane in result.crane_names:
        assert eq.tensions[crane] == pytest.approx(result.verified.tensions[crane], abs=SAME)
    assert text.startswith("# Written by liftplan plan: the chosen slings of")


def test_the_apex_plans_cover_four_cranes_and_spreader_bars():
    four_leg_plan, three_crane_plan = (
        planned("four cranes, 4-leg apexes"),
        planned("three cranes, hinged pairs"),
    )
    spreader_plan = planned("four cranes, spreader bars")
    assert len(four_leg_plan.scene.cranes) == 4 and len(three_crane_plan.scene.cranes) == 3
    assert all(len(c.sling.legs) == 4 for c in four_leg_plan.scene.cranes)
    assert all(c.sling.spreader is not None for c in spreader_plan.scene.cranes)
    assert len(spreader_plan.scene.cranes) == 4


def test_strength_plans_scene_file_round_trips_and_gives_the_planned_tensions(strength_plan):
    result = strength_plan
    text = strength_report.plan_scene_toml(result)
    back = assert_round_trip(result.scene, text)
    eq = solve(back)
    planned = dict(zip(result.chosen.names, result.chosen.preload.tolist()))
    assert eq.tensions == pytest.approx(planned, abs=1e-6)
    assert back.strength == result.problem.strength and back.body == result.problem.body
    assert f"# planned lug {result.labels[0]}" in text


def test_strength_plans_scene_is_the_plan(strength_plan):
    """Force control: rigid, every force but the widest triangle's three held at its planned
    value; hoist control: elastic at the planned boom heights. Lugs by candidate name in the
    file's frame, every crane at its SWL there, level at the plan's lift height."""
    result = strength_plan
    p, c, scene = result.problem, result.chosen, result.scene
    points = p.points[list(c.indices)]
    assert scene.frame == p.frame and scene.lug_names == c.names
    assert np.array_equal(scene.lug_points(), points)
    assert scene.attitude == Attitude(lift_height=p.lift_height, yaw=p.yaw)
    assert [cr.swl for cr in scene.cranes] == p.reach[1][list(c.indices), 0].tolist()
    if result.control == "force":
        free = free_three(points)
        held = [k for k in range(len(c.names)) if k not in free]
        assert scene.analysis == Analysis(
            model="rigid", redundant=tuple(Redundant(c.names[k], float(c.preload[k])) for k in held)
        )
    else:
        assert scene.analysis == Analysis(model="elastic")
        assert [cr.boom_height for cr in scene.cranes] == c.boom_heights.tolist()


def test_free_three_is_the_widest_triangle_in_plan():
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 5.0], [10.0, 0.0, 0.0], [5.0, 4.0, 0.0], [5.0, -6.0, 0.0]])
    assert free_three(points) == (0, 2, 4)


# -- parts no example has -------------------------------------------------------------------------
def _sling_scene(frame="z-up", name="block", lug_names=("F-P", "F-S", "A-P", "A-S")):
    """Two cranes: an equalised 2-leg sling (legs by diameter) and a spreader bar with its own
    EA (one top leg by diameter, one by EA), the aft tip given; the weight curve, the
    allowables, a girder stiffness, ``analysis.hull``, the rigging limit and the attitude off
    their defaults. It solves (rigging model) when the girder is left out."""
    fp, fs, ap, as_ = lug_names
    lugs = (
        Lug(fp, (6.0, 4.0, 0.0)),
        Lug(fs, (6.0, -4.0, 0.0)),
        Lug(ap, (-6.0, 4.0, 0.5)),
        Lug(as_, (-6.0, -4.0, 0.0)),
    )
    front = Sling(legs=(Leg(fp, 9.0, diameter=56.0), Leg(fs, 9.0, diameter=56.0)), equalised=True)
    bar = Spreader(
        length=8.0, top=(Leg(None, 6.0, diameter=48.0), Leg(None, 6.0, EA=21000.0)), weight=2.5, EA=5e5
    )
    aft = Sling(legs=(Leg(ap, 3.0, EA=20000.0, end=1), Leg(as_, 3.1, EA=20000.0, end=2)), spreader=bar)
    cranes = (
        Crane(name="FWD", boom_height=33.2, rope_length=20.0, EA=40000.0, swl=300.0, sling=front),
        Crane(
            name="AFT",
            boom_height=31.0,
            rope_length=18.0,
            EA=40000.0,
            swl=300.0,
            sling=aft,
            tip=(-6.0, 0.0, 31.0),
        ),
    )
    curve = ((-8.0, 10.0), (8.0, 15.0))
    weight, moment = curve_totals(*zip(*curve))
    return Scene(
        body=Body(weight=weight, cog=(moment / weight, 0.2, -1.0), weight_curve=curve),
        lugs=lugs,
        cranes=cranes,
        attitude=Attitude(lift_height=5.0, heel=0.5, trim=-0.25),
        analysis=Analysis(model="rigging", hull="rigid"),
        rigging=RiggingLimits(min_sling_angle=55.0),
        strength=Strength(
            bending_moment=((-8.0, 900.0), (8.0, 800.0)), shear_force=((-8.0, 300.0), (8.0, 300.0))
        ),
        girder=GirderStiffness(EI=((-8.0, 5e6), (8.0, 4e6)), GJ=((-8.0, 3e6), (8.0, 3e6))),
        name=name,
        frame=frame,
    )


@pytest.mark.parametrize("frame", ["z-up", "choi"])
def test_equalised_slings_diameters_spreaders_tips_and_the_girder_round_trip(frame):
    scene = _sling_scene(frame)
    text = scene_toml(scene)
    assert loads_scene(text) == scene
    raw = tomllib.loads(text)
    assert raw["cranes"][0]["sling"]["equalised"] is True
    assert raw["cranes"][0]["sling"]["legs"][0]["diameter"] == 56.0
    assert raw["hull"] == {"EI": [[-8.0, 5e6], [8.0, 4e6]], "GJ": [[-8.0, 3e6], [8.0, 3e6]]}
    assert raw["analysis"] == {"model": "rigging", "hull": "rigid"}


def test_the_sling_scene_solves_the_same_from_its_file():
    assert_round_trip(dataclasses.replace(_sling_scene(), girder=None, analysis=Analysis(model="rigging")))


def test_defaults_are_left_out_and_read_back():
    """A plain scene: no name, no analysis, no rigging limits written; it reads back equal."""
    scene = Scene(
        body=Body(weight=100.0, cog=(0.0, 0.0, 1.0)),
        lugs=(Lug("A", (1.0, 1.0, 0.0)), Lug("B", (-1.0, 1.0, 0.0)), Lug("C", (0.0, -1.0, 0.0))),
        cranes=(Crane(lug="A"), Crane(lug="B"), Crane(lug="C")),
    )
    text = scene_toml(scene)
    raw = tomllib.loads(text)
    assert set(raw) == {"frame", "body", "lugs", "cranes", "attitude"}
    assert raw["cranes"] == [{"lug": "A"}, {"lug": "B"}, {"lug": "C"}]
    assert loads_scene(text) == scene


def test_the_header_and_crane_notes_are_comments_on_their_lines():
    scene = _sling_scene()
    header = ("first line", 'second "quoted"\nthird\r\nfourth with \x00 a NUL', "")
    text = scene_toml(scene, header=header, crane_notes={"FWD": "the forward crane\nof two", "nobody": "x"})
    lines = text.splitlines()
    assert lines[:5] == ["# first line", '# second "quoted"', "# third", "# fourth with   a NUL", "#"]
    assert "[[cranes]]                   # the forward crane of two" in lines
    assert "nobody" not in text
    assert loads_scene(text) == scene


NAMES = st.text(st.characters(blacklist_categories=("Cs",)), min_size=1).filter(lambda s: s.strip())


@given(st.lists(NAMES, min_size=6, max_size=6, unique=True))
def test_any_names_are_escaped_and_read_back(names):
    """Quotes, backslashes, control characters, DEL and any Unicode in scene, lug and crane
    names: written as TOML basic strings, read back the same."""
    scene = _sling_scene(name=names[4], lug_names=tuple(names[:4]))
    assert loads_scene(scene_toml(scene)) == scene


def test_a_name_that_is_not_unicode_is_refused_in_one_line():
    scene = _sling_scene(name="bad \ud800 name")
    with pytest.raises(InvalidScene, match="not writable as UTF-8 text"):
        scene_toml(scene)


#: Every field of the scene's dataclasses, as the writer writes it (or refuses it): a field
#: added to a scene part must be read (model/scene/file.py), written (model/scene/writer.py)
#: and listed here.
WRITTEN = {
    Scene: {
        "name",
        "frame",
        "body",
        "lugs",
        "cranes",
        "attitude",
        "analysis",
        "rigging",
        "strength",
        "girder",
        "tide",
        "wind",
    },
    Tide: {"table", "time"},
    Wind: {"speed", "direction", "body", "booms", "density"},
    WindArea: {"area", "cd", "height", "crane"},
    Body: {"weight", "cog", "weight_curve"},
    Lug: {"name", "at", "capacity", "capacity_out_of_plane", "normal"},
    Crane: {"lug", "EA", "boom_height", "rope_length", "swl", "tip", "name", "sling", "vessel"},
    Vessel: {
        "displacement",
        "waterplane_area",
        "gm_t",
        "gm_l",
        "flotation",
        "heading",
        "density",
        "max_heel",
        "max_trim",
        "ballast",
        "freeboard",
        "min_freeboard",
        "beam",
        "length",
        "hull",  # with cog and origin: a vessel's hull, refused by the writer as [hull] is
        "cog",
        "origin",
    },
    Sling: {"legs", "spreader", "equalised"},
    Leg: {"lug", "length", "EA", "diameter", "end"},
    Spreader: {"length", "top", "weight", "EA"},
    Attitude: {"heel", "trim", "yaw", "lift_height"},
    Analysis: {"model", "redundant", "hull"},
    Redundant: {"lug", "tension"},
    RiggingLimits: {"min_sling_angle"},
    Strength: {"bending_moment", "shear_force"},
    GirderStiffness: {"EI", "GJ"},
}
#: ... and the parts it refuses (a body in water or on the ground).
REFUSED = {"water", "hull", "ground", "openings"}


@pytest.mark.parametrize("part", list(WRITTEN), ids=lambda c: c.__name__)
def test_every_field_of_a_scene_part_is_written_or_refused(part):
    fields = {f.name for f in dataclasses.fields(part)}
    known = WRITTEN[part] | (REFUSED if part is Scene else set())
    assert fields == known, (
        f"{part.__name__}: fields {sorted(fields - known)} not written by model/scene/writer.py "
        f"(or {sorted(known - fields)} gone); write them there and list them here"
    )
