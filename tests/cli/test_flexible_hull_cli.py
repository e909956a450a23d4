"""The flexible hull on the command line: ``liftplan solve`` says which hull it used, with the
deflection and the strength in JSON (the model itself: tests/model/test_flexible_hull.py)."""

from __future__ import annotations

import json

import pytest
from helpers import EXAMPLES

from liftplan.planner.cli import main

FLEXIBLE = EXAMPLES / "tanker_flexible.toml"


def test_cli_json_reports_the_hull_the_deflection_and_the_strength(capsys, tmp_path):
    path = tmp_path / "six.toml"
    text = FLEXIBLE.read_text().replace('hull = "auto"', 'hull = "flexible"')
    path.write_text(text)
    code = main(["solve", str(path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    block = out["flexible_hull"]
    assert block["used"] == "flexible" and block["threshold"] == 0.01
    assert len(block["deflection"]["x"]) == len(block["deflection"]["w"]) > 40
    assert block["twist"] is not None
    assert out["strength"]["max_bending_moment"]["value"] > 0
    assert out["tensions"] == pytest.approx(block["flexible_tensions"], rel=1e-12)


def test_cli_console_says_which_hull(capsys):
    code = main(["solve", str(FLEXIBLE)])
    out = capsys.readouterr().out
    assert code == 0
    assert "hull: rigid (flexibility changes no tension by more than 1 %" in out
    assert "hull deflection from the chord through its ends" in out
