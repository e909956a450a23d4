"""``liftplan sequence`` on a move stage: the JSON of a move (its parameter, not an angle), exit 4
when a check fails, exit 1 when the ropes cannot hold the body, and the report and 3D view."""

import json

from helpers import EXAMPLES

from liftplan.planner.cli import main

EXAMPLE = str(EXAMPLES / "four_crane_hoist.toml")


def test_the_example_reports_parameters_slack_and_its_failed_checks(capsys):
    assert main(["sequence", EXAMPLE, "--json"]) == 4
    out = json.loads(capsys.readouterr().out)
    states = out["states"]
    assert [s["param"] for s in states] == [k / 10 for k in range(11)]
    assert all(s["angle"] is None for s in states)
    assert states[0]["hook_loads"]["A"] < states[-1]["hook_loads"]["A"]
    peak = out["maxima"]["hook_loads"]["A"]
    assert peak == {
        "value": states[-1]["hook_loads"]["A"],
        "angle": None,
        "param": 1.0,
        "stage": "sequence",
        "bound": peak["bound"],
    }
    assert peak["bound"] >= peak["value"]  # the samples' curvature bound (docs/sequences.md)
    (slack,) = out["slack"]
    assert slack["what"] == "D" and 0.9 < slack["from_param"] < 0.95 and slack["to_param"] == 1.0
    failed = {(c["name"], c["subject"]) for c in out["checks"] if not c["ok"]}
    assert ("design_hook_load", "A (sequence)") in failed
    assert out["stages"][0]["moves"][1] == {"crane": "C", "hoist": 0.0, "to": [-12.6, -6.0, 42.0]}


def test_too_few_taut_ropes_stop_the_command_naming_the_parameter(tmp_path, capsys):
    lowered = '{ crane = "B", hoist = -1.0 }, { crane = "D", hoist = -1.0 },'
    text = (EXAMPLES / "four_crane_hoist.toml").read_text().replace("moves = [", "moves = [" + lowered)
    path = tmp_path / "m.toml"
    path.write_text(text)
    assert main(["sequence", str(path)]) == 1
    err = capsys.readouterr().err
    assert "no equilibrium: sequence at s = " in err and "taut" in err


def test_report_and_view_of_a_move(tmp_path, capsys):
    view = tmp_path / "v.html"
    assert main(["sequence", EXAMPLE, "--report", str(tmp_path / "r"), "--view", str(view)]) == 4
    page = (tmp_path / "r" / "report.html").read_text()
    assert "boom tips moved" in page and "at s [-]" in page
    assert "sequence: s = 0.5" in view.read_text()
