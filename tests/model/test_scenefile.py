"""Bad input ends in one clear line naming key, value and what is expected; nothing else."""

import math

import pytest
import tomli_w
from hypothesis import given, settings
from hypothesis import strategies as st

from liftplan.model import InvalidScene, Scene, loads_scene

VALID = {
    "name": "test",
    "frame": "z-up",
    "body": {"weight": 100.0, "cog": [0.0, 0.0, 1.0]},
    "lugs": [
        {"name": "A", "at": [10.0, 5.0, 3.0]},
        {"name": "B", "at": [10.0, -5.0, 3.0]},
        {"name": "C", "at": [-10.0, -5.0, 3.0]},
        {"name": "D", "at": [-10.0, 5.0, 3.0]},
    ],
    "ropes": {"EA": 20000.0},
    "cranes": [{"lug": n, "boom_height": 30.0, "rope_length": 20.0, "swl": 80.0} for n in "ABCD"],
    "analysis": {"model": "elastic"},
}


def mutate(change):
    import copy

    data = copy.deepcopy(VALID)
    change(data)
    return tomli_w.dumps(data)


def error_of(text):
    with pytest.raises(InvalidScene) as info:
        loads_scene(text)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_valid_scene_loads():
    scene = loads_scene(tomli_w.dumps(VALID))
    assert isinstance(scene, Scene)
    assert scene.lug_names == ("A", "B", "C", "D")


CASES = [
    ("unknown key", lambda d: d["body"].update(wieght=3.0), ["body.wieght", "unknown key", "weight"]),
    ("unknown table", lambda d: d.update(extra={"a": 1.0}), ["extra", "unknown key"]),
    ("missing weight", lambda d: d["body"].pop("weight"), ["body.weight", "missing", "number"]),
    ("missing lug name", lambda d: d["lugs"][1].pop("name"), ["lugs[1].name", "missing"]),
    ("duplicate lug", lambda d: d["lugs"][1].update(name="A"), ["'A'", "duplicate"]),
    ("crane on unknown lug", lambda d: d["cranes"][0].update(lug="Z"), ["'Z'", "unknown lug"]),
    ("two cranes on a lug", lambda d: d["cranes"][1].update(lug="A"), ["two cranes"]),
    ("lug without crane", lambda d: d["cranes"].pop(), ["lugs[D]", "no crane"]),
    ("infinite weight", lambda d: d["body"].update(weight=math.inf), ["body.weight", "inf", "finite"]),
    ("nan cog", lambda d: d["body"].update(cog=[0.0, math.nan, 1.0]), ["body.cog", "finite"]),
    ("zero weight", lambda d: d["body"].update(weight=0.0), ["body.weight = 0.0", "> 0"]),
    ("negative EA", lambda d: d["ropes"].update(EA=-5.0), ["EA = -5.0", "> 0"]),
    ("zero rope length", lambda d: d["cranes"][2].update(rope_length=0.0), ["rope_length", "> 0"]),
    ("negative swl", lambda d: d["cranes"][2].update(swl=-1.0), ["swl", "> 0"]),
    (
        "two lugs",
        lambda d: (d["lugs"].pop(), d["lugs"].pop(), d["cranes"].pop(), d["cranes"].pop()),
        ["2 given", "three or more"],
    ),
    ("string weight", lambda d: d["body"].update(weight="heavy"), ["body.weight = 'heavy'", "number"]),
    ("short point", lambda d: d["lugs"][0].update(at=[1.0, 2.0]), ["lugs[0].at"]),
    ("bad frame", lambda d: d.update(frame="y-up"), ["frame = 'y-up'", "z-up", "choi"]),
    ("bad model", lambda d: d["analysis"].update(model="stiff"), ["analysis.model = 'stiff'"]),
    ("heel beyond 90", lambda d: d.update(attitude={"heel": 120.0}), ["attitude.heel", "[-90, 90]"]),
    (
        "collinear lugs",
        lambda d: [lug.update(at=[float(10 * i), 0.0, 3.0]) for i, lug in enumerate(d["lugs"])],
        ["collinear", "singular"],
    ),
    (
        "CG outside",
        lambda d: d["body"].update(cog=[15.0, 0.0, 1.0]),
        ["body.cog", "outside", "edge B-A", "C, D would go slack"],
    ),
]


@pytest.mark.parametrize(("change", "expected"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_input_is_one_clear_line(change, expected):
    message = error_of(mutate(change))
    for fragment in expected:
        assert fragment in message, message


def test_toml_syntax_error_names_the_line():
    text = tomli_w.dumps(VALID).replace("weight = 100.0", "weight = = 100.0")
    line = text.splitlines().index("weight = = 100.0") + 1
    assert f"line {line}" in error_of(text)


def test_water_without_hull_is_refused_clearly():
    text = tomli_w.dumps({**VALID, "water": {"density": 1.025}})
    assert "[water] and [hull] go together" in error_of(text)


@pytest.mark.parametrize(
    "hull, expected",
    [
        ({"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "mesh": "a.stl"}, "exactly one of box"),
        ({}, "exactly one of box"),
        ({"box": {"min": [0, 0, 0], "max": [1, -1, 1]}}, "min < max"),
        ({"mesh": "missing.stl"}, "no such file"),
        ({"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "steel_density": 7.85}, "flooded hull"),
        ({"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "flooding": "sunk"}, "hull.flooding"),
    ],
)
def test_bad_hulls(hull, expected):
    text = tomli_w.dumps({**VALID, "water": {}, "hull": hull})
    assert expected in error_of(text)


def test_choi_frame_hull_box_and_ground_are_converted():
    from liftplan.model import loads_scene

    raw = {
        "frame": "choi",
        "body": {"weight": 100.0, "cog": [2.0, 1.0, 3.0]},
        "water": {},
        "hull": {"box": {"min": [0, 0, 0], "max": [4, 2, 6]}},
        "ground": {"contact": [1.0, 0.0, 5.0]},
    }
    scene = loads_scene(tomli_w.dumps(raw))
    assert scene.hull.bounds[0].tolist() == [0, -6, 0] and scene.hull.bounds[1].tolist() == [4, 0, 2]
    assert scene.ground.contact == (1.0, -5.0, 0.0)
    assert scene.body.cog == (2.0, -3.0, 1.0)


def test_planning_tables_point_to_the_planner():
    text = tomli_w.dumps({**VALID, "plan": {"cranes": 4}})
    assert "liftplan plan" in error_of(text)


def test_choi_frame_converts_points():
    def to_choi(data):
        data["frame"] = "choi"
        for lug in data["lugs"]:
            x, y, z = lug["at"]
            lug["at"] = [x, z, -y]  # choi: x forward, y up, z to starboard
        x, y, z = data["body"]["cog"]
        data["body"]["cog"] = [x, z, -y]

    scene = loads_scene(mutate(to_choi))
    zup = loads_scene(tomli_w.dumps(VALID))
    assert scene.lugs == zup.lugs and scene.body == zup.body


# -- random malformed files: always InvalidScene, never another exception ------------------
junk = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-10, 10),
    st.floats(allow_nan=True),
    st.text(max_size=5),
    st.lists(st.floats(-50, 50), max_size=4),
    st.dictionaries(st.text(max_size=3), st.integers(), max_size=2),
)


def _paths(node, prefix=()):
    yield prefix
    if isinstance(node, dict):
        for key, value in node.items():
            yield from _paths(value, prefix + (key,))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from _paths(value, prefix + (i,))


ALL_PATHS = [p for p in _paths(VALID) if p]


@settings(max_examples=300, deadline=None)
@given(
    edits=st.lists(
        st.tuples(st.sampled_from(ALL_PATHS), st.sampled_from(["set", "delete", "add"]), junk),
        min_size=1,
        max_size=3,
    )
)
def test_random_malformed_files_end_in_the_clear_error(edits):
    import copy

    data = copy.deepcopy(VALID)
    for path, action, value in edits:
        parent = data
        try:
            for key in path[:-1]:
                parent = parent[key]
            last = path[-1]
            if action == "set":
                parent[last] = value
            elif action == "delete":
                del parent[last]
            elif isinstance(parent, dict):
                parent[f"x_{last}"] = value
        except (KeyError, IndexError, TypeError):
            continue
    try:
        text = tomli_w.dumps(data)
    except (TypeError, ValueError):
        return  # not representable in TOML (None): nothing to test
    try:
        loads_scene(text)
    except InvalidScene as err:
        assert "\n" not in str(err) and str(err)


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=200))
def test_random_text_ends_in_the_clear_error(text):
    try:
        loads_scene(text)
    except InvalidScene as err:
        assert "\n" not in str(err)
