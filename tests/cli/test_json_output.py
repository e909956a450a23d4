"""Every JSON liftplan writes is strict JSON (issue 29 item 13): a NaN or an infinity is
written as null, with what it was listed under "not_finite"; absurd lift extents are refused
in one line instead of ending in an OverflowError."""

from __future__ import annotations

import json
import math

import pytest
from helpers import EXAMPLES

from liftplan.model.version import NOT_FINITE_KEY, VERSION_KEY, stamped
from liftplan.planner.cli import main


def _strict(text):
    def refuse(constant):
        raise ValueError(f"not JSON: {constant}")

    return json.loads(text, parse_constant=refuse)


def test_non_finite_values_become_null_with_the_reason_beside():
    out = stamped({"a": 1.0, "b": {"u": math.inf, "v": [0.5, -math.inf, math.nan]}, "c": "x"})
    assert out["b"] == {"u": None, "v": [0.5, None, None]}
    assert out[NOT_FINITE_KEY] == {"b.u": "Infinity", "b.v[1]": "-Infinity", "b.v[2]": "NaN"}
    assert list(out)[-2:] == [NOT_FINITE_KEY, VERSION_KEY]
    assert _strict(json.dumps(out)) == out
    clean = stamped({"a": 1.0})
    assert NOT_FINITE_KEY not in clean and list(clean) == ["a", VERSION_KEY]


def test_a_solve_with_an_infinite_utilisation_writes_strict_json(tmp_path, capsys):
    scene = tmp_path / "tiny_swl.toml"
    text = (EXAMPLES / "tanker_upright.toml").read_text(encoding="utf-8")
    scene.write_text(text.replace("swl = 400.0", "swl = 1e-320"), encoding="utf-8")
    main(["solve", str(scene), "--json"])
    out = _strict(capsys.readouterr().out)
    assert out["utilisation"]["T1"] is None
    assert out[NOT_FINITE_KEY]["utilisation.T1"] == "Infinity"


@pytest.mark.parametrize(
    ("option", "value", "fragment"),
    [
        # --to beyond the shortest rope: the option and its range (was "is inf steps")
        ("--to", "1e308", "--to 1e+308 m: expected a hoist in (0, 44] m"),
        ("--step", "5e-324", "expected at most 100000 (--step at least 0.00021 m, or a lower --to)"),
    ],
)
def test_a_lift_too_long_to_compute_is_refused_in_one_line(option, value, fragment, tmp_path, capsys):
    figure = tmp_path / "curve.png"
    scene = EXAMPLES / "sunken_block_lift.toml"
    assert main(["lift", str(scene), option, value, "--figure", str(figure)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("liftplan: error:") and fragment in err[0]
    assert not figure.exists()


@pytest.mark.parametrize(
    "argv",
    [["plan"], ["solve", "--model", "nope", "x.toml"], ["frob"], ["lift", "x.toml", "--step", "abc"]],
)
def test_command_line_mistakes_are_one_line(argv, capsys):
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and ": error: " in err[0] and err[0].endswith("--help)")
