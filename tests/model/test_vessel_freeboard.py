"""A crane vessel's freeboard: the lowest deck corner under heave, heel and trim.

The closed form of ``model/scene/vessel.py``: freeboard - heave - beam |heel| / 2 - length
|trim| / 2 (small angles, the ballast moment included), checked against ``min_freeboard``.
"""

from __future__ import annotations

import dataclasses
import json
import math

import pytest
from helpers import EXAMPLES
from support.cli import run

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import load_scene, loads_scene
from liftplan.model.scene.vessel import Vessel
from liftplan.model.scene.writer import scene_toml
from liftplan.model.solve_checks import equilibrium_checks

FLOATING = EXAMPLES / "tanker_floating.toml"
SHEERLEG = {"displacement": 9000.0, "waterplane_area": 2800.0, "gm_t": 6.0, "gm_l": 180.0}
DECK = {"freeboard": 3.0, "beam": 40.0, "length": 90.0}


def _one_afloat(**deck):
    """The tanker with Sheerleg 1 alone afloat (T1 40 m ahead and 10 m to port of its
    flotation centre), its deck as given, a ballast moment set."""
    scene = load_scene(FLOATING)
    cranes = []
    for c in scene.cranes:
        if c.lug == "T1":
            vessel = dataclasses.replace(c.vessel, flotation=(26.2, -52.0), ballast=(800.0, -500.0), **deck)
            cranes.append(dataclasses.replace(c, vessel=vessel))
        else:
            cranes.append(dataclasses.replace(c, vessel=None))
    return dataclasses.replace(scene, cranes=tuple(cranes))


def test_lowest_deck_corner_closed_form():
    """The reported freeboard is the closed form of the hook load to 1e-9, the ballast moment
    in the heel and trim; the check passes above min_freeboard and is flagged below it."""
    scene = _one_afloat(**DECK, min_freeboard=1.0)
    eq = solve(scene)
    t = eq.tensions["T1"]
    forward, starboard = 40.0, -10.0
    heave = t / (1.025 * 2800.0)
    heel = (t * starboard + 800.0) / (9000.0 * 6.0)
    trim = (t * forward - 500.0) / (9000.0 * 180.0)
    expected = 3.0 - heave - 20.0 * abs(heel) - 45.0 * abs(trim)
    state = eq.vessels["Sheerleg 1"]
    assert state.heel == pytest.approx(math.degrees(heel), rel=1e-9)
    assert state.freeboard == pytest.approx(expected, rel=1e-9)
    assert 1.0 < state.freeboard < 3.0 - heave
    check = {(c.name, c.subject): c for c in equilibrium_checks(scene, eq)}["vessel_freeboard", "Sheerleg 1"]
    assert check.ok and check.kind == "min" and check.limit == 1.0 and check.unit == "m"
    tight = _one_afloat(**DECK, min_freeboard=expected + 0.01)
    failed = {(c.name, c.subject): c for c in equilibrium_checks(tight, solve(tight))}
    assert not failed["vessel_freeboard", "Sheerleg 1"].ok
    # without min_freeboard the deck edge must stay out of the water
    assert _one_afloat(**DECK).crane("T1").vessel.min_freeboard == 0.0
    assert solve(_one_afloat()).vessels["Sheerleg 1"].freeboard is None


def test_json_exit_code_written_back_and_refusals(tmp_path):
    """solve --json carries vessels.NAME.freeboard and a freeboard below its minimum exits 4
    with --strict; the writer writes the keys back; a partial deck is refused in one line."""
    deck = "freeboard = 2.5, beam = 40.0, length = 90.0, min_freeboard = 2.4, max_heel"
    path = tmp_path / "deck.toml"
    path.write_text(FLOATING.read_text().replace("max_heel", deck))
    out = run("solve", str(path), "--json", "--strict")
    assert out.returncode == 4, out.stderr
    data = json.loads(out.stdout)
    state = data["vessels"]["Sheerleg 1"]
    assert state["freeboard"] < 2.4
    failed = {(c["name"], c["subject"]) for c in data["checks"] if not c["ok"]}
    assert ("vessel_freeboard", "Sheerleg 1") in failed
    console = run("solve", str(path))
    assert f"freeboard {state['freeboard']:.3f} m (min 2.4)" in console.stdout
    assert "vessel_freeboard Sheerleg 1" in console.stderr
    scene = load_scene(path)
    assert loads_scene(scene_toml(scene)) == scene
    with pytest.raises(InvalidScene, match="vessel.freeboard given without beam and length"):
        Vessel(**SHEERLEG, flotation=(0.0, 0.0), freeboard=3.0)
    with pytest.raises(InvalidScene, match="vessel.min_freeboard given without freeboard"):
        Vessel(**SHEERLEG, flotation=(0.0, 0.0), min_freeboard=1.0)
    with pytest.raises(InvalidScene, match=r"vessel.beam = -1.0: expected a number > 0"):
        Vessel(**SHEERLEG, flotation=(0.0, 0.0), freeboard=3.0, beam=-1.0, length=90.0)
