"""`liftplan solve` as a user (and outside tests) drive it: a separate process."""

import json

import pytest
from helpers import EXAMPLES
from support.cli import run


def test_solve_json_tanker():
    out = run("solve", str(EXAMPLES / "tanker_upright.toml"), "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["model"] == "paper-elastic" and data["converged"] is True
    assert data["tensions"] == pytest.approx(
        {"T1": 272.11, "T2": 179.89, "T3": 179.89, "T4": 272.11}, abs=0.005
    )
    assert data["heel"] == 0.0 and data["trim"] == 0.0


def test_solve_table_has_units_and_every_lug():
    out = run("solve", str(EXAMPLES / "symmetric_block.toml"))
    assert out.returncode == 0, out.stderr
    for text in ("tension [t]", "share of W [%]", "utilisation [%]", "FP", "AP", "226.00"):
        assert text in out.stdout


@pytest.mark.parametrize(
    ("content", "code", "fragment"),
    [
        ("[body\nweight = 1", 2, "TOML syntax error"),
        ("[body]\nweight = 3.0\ncog = [0, 0, 0]\n", 2, "lugs: 0 given"),
        (None, 2, "no such scene file"),
    ],
)
def test_bad_input_one_line_nonzero_no_traceback(tmp_path, content, code, fragment):
    path = tmp_path / "scene.toml"
    if content is not None:
        path.write_text(content)
    out = run("solve", str(path), "--json")
    assert out.returncode == code
    assert out.stdout == ""
    assert len(out.stderr.strip().splitlines()) == 1 and fragment in out.stderr
    assert "Traceback" not in out.stderr


def test_no_equilibrium_exits_1(tmp_path):
    """Heeled 60 deg with T4 held: a rope would need compression."""
    text = (EXAMPLES / "tanker_upright.toml").read_text()
    text = text.replace("heel = 0.0", "heel = 60.0").replace(
        'model = "paper-elastic"', 'model = "rigid"\nredundant = { lug = "T4", tension = 272.0 }'
    )
    path = tmp_path / "scene.toml"
    path.write_text(text)
    out = run("solve", str(path), "--json")
    assert out.returncode == 1 and out.stdout == ""
    assert len(out.stderr.strip().splitlines()) == 1 and "compression" in out.stderr
