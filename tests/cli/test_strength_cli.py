"""The hull girder on the command line: ``liftplan solve``'s strength block in JSON, a failed
envelope flagged (exit 4 with ``--strict``), the strength figure and its refusals (the girder
itself: tests/model/test_strength.py)."""

from __future__ import annotations

import json

import pytest
from helpers import EXAMPLES

from liftplan.model import solve
from liftplan.model.scene.file import load_scene
from liftplan.model.strength import hull_girder
from liftplan.planner.cli import main

TANKER = (EXAMPLES / "tanker_strength.toml").read_text()


def test_solve_json_strength_block(capsys):
    code = main(["solve", str(EXAMPLES / "tanker_strength.toml"), "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    block = data["strength"]
    for key in ("x", "shear_force", "bending_moment", "max_bending_moment", "max_shear_force"):
        assert key in block
    assert len(block["x"]) == len(block["shear_force"]) == len(block["bending_moment"]) > 200
    assert set(block["max_bending_moment"]) >= {"value", "x"}
    assert block["max_bending_moment"]["value"] == max(abs(m) for m in block["bending_moment"])
    assert {c["name"] for c in data["checks"]} >= {"bending_moment", "shear_force"}
    scene = load_scene(EXAMPLES / "tanker_strength.toml")
    g = hull_girder(scene, solve(scene))
    assert block["max_shear_force"]["value"] == g.max_shear.value
    # the tanker's tensions are the papers' (the weight curve changes nothing of the solve)
    assert data["tensions"]["T1"] == pytest.approx(272.11, abs=0.005)


def test_failed_envelope_is_flagged_and_strict_exits_4(tmp_path, capsys):
    path = tmp_path / "weak.toml"
    path.write_text(TANKER.replace("[20.0, 4000.0], [62.0, 4000.0]", "[20.0, 1500.0], [62.0, 1500.0]"))
    assert main(["solve", str(path)]) == 0  # a converged solve exits 0 ...
    out = capsys.readouterr()
    assert "FAIL bending_moment x = " in out.out and "check(s) failed: bending_moment" in out.err
    assert main(["solve", str(path), "--strict"]) == 4  # ... unless --strict
    capsys.readouterr()
    assert main(["solve", str(path), "--json", "--strict"]) == 4
    checks = json.loads(capsys.readouterr().out)["checks"]
    failed = [c for c in checks if not c["ok"]]
    assert [c["name"] for c in failed] == ["bending_moment"] and failed[0]["unit"] == "t m"


def test_strength_figure_written_and_refused_without_a_curve(tmp_path, capsys):
    figure = tmp_path / "out" / "girder.png"
    assert main(["solve", str(EXAMPLES / "tanker_strength.toml"), "--strength-figure", str(figure)]) == 0
    assert figure.stat().st_size > 10_000
    capsys.readouterr()
    assert main(["solve", str(EXAMPLES / "tanker_upright.toml"), "--strength-figure", str(figure)]) == 2
    err = capsys.readouterr().err
    assert "no [body] weight_curve" in err and len(err.strip().splitlines()) == 1
    assert (
        main(
            [
                "solve",
                str(EXAMPLES / "tanker_strength.toml"),
                "--strength-figure",
                str(tmp_path / "girder.gif"),
            ]
        )
        == 2
    )
    assert "unknown file type" in capsys.readouterr().err
