"""``liftplan sequence`` on the command line: the JSON the contract fixes, exit 4 on a lug loaded
out of its plane beyond its capacity, the figure and the report."""

import json

import pytest
from helpers import EXAMPLES

from liftplan.planner.cli import main

TAILING = """
name = "tailing"
[body]
weight = 100.0
cog = [20.0, 0.0, 0.0]
[[lugs]]
name = "A"
at = [40.0, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
{capacity}
[[cranes]]
name = "Head"
lug = "A"
[sequence]
kind = "upend"
axis = "y"
from = 0.0
to = 60.0
step = 10.0
pivot = [0.0, 0.0, 0.0]
plumb = true
"""


def test_json_states_and_maxima_have_the_contract_keys(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(TAILING.format(capacity=""))
    assert main(["sequence", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [s["angle"] for s in out["states"]] == [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0]
    for state in out["states"]:
        assert state["hook_loads"]["Head"] == pytest.approx(50.0, abs=1e-9)
        assert state["ground_reaction"] == pytest.approx(50.0, abs=1e-9)
        assert set(state["lug_loads"]["A"]) >= {"load", "in_plane", "out_of_plane"}
    assert out["maxima"]["hook_loads"]["Head"]["value"] == pytest.approx(50.0, abs=1e-9)
    # normal x: the vertical rope is out of the plate's plane by the angle; largest at 60 deg
    peak = out["maxima"]["lug_out_of_plane"]["A"]
    assert peak["angle"] == pytest.approx(60.0) and peak["value"] == pytest.approx(50.0 * 3**0.5 / 2)
    assert set(out["maxima"]["lug_loads"]["A"]) >= {"value", "angle"}


def test_a_lug_loaded_out_of_plane_beyond_its_capacity_exits_4(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(TAILING.format(capacity="capacity = 500.0\ncapacity_out_of_plane = 30.0"))
    assert main(["sequence", str(path)]) == 4
    captured = capsys.readouterr()
    assert "FAIL lug_out_of_plane A" in captured.out
    assert "lug_out_of_plane" in captured.err
    path.write_text(TAILING.format(capacity="capacity = 500.0\ncapacity_out_of_plane = 300.0"))
    assert main(["sequence", str(path)]) == 0


def test_bad_input_exits_2_with_one_line(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(TAILING.format(capacity="").replace("plumb = true", "plumb = false"))
    assert main(["sequence", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "plumb" in err


def test_figure_and_report_are_written(tmp_path, capsys):
    figure, report = tmp_path / "f.png", tmp_path / "rep"
    code = main(
        ["sequence", str(EXAMPLES / "mast_upend.toml"), "--figure", str(figure), "--report", str(report)]
    )
    assert code == 0
    assert figure.stat().st_size > 10_000
    assert "Continuous maxima" in (report / "report.html").read_text()
    data = json.loads((report / "sequence.json").read_text())
    assert {s["name"] for s in data["stages"]} == {"tailing", "on the pivot"}


def test_a_file_that_plans_its_lugs_prints_the_choice_and_reports_it(tmp_path, capsys):
    report = tmp_path / "rep"
    code = main(["sequence", str(EXAMPLES / "block_turnover_plan.toml"), "--json", "--report", str(report)])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["lug_plan"]["lugs"] == {"B1": "TP3", "B2": "TS3", "C1": "BP3", "C2": "BS3"}
    assert out["lug_plan"]["all_checks_met"] is True
    assert "Lugs planned" in (report / "report.html").read_text()


def test_the_3d_view_has_one_state_per_reported_angle(tmp_path):
    import re

    view = tmp_path / "v.html"
    assert main(["sequence", str(EXAMPLES / "mast_upend.toml"), "--view", str(view)]) == 0
    found = re.search(
        r'<script type="application/json" id="liftplan-scene">(.*?)</script>', view.read_text(), re.S
    )
    states = json.loads(found.group(1))["states"]
    assert [s["name"] for s in states[:2]] == ["tailing: 0 deg", "tailing: 5 deg"]
    assert len(states) == 10 + 10  # 0..45 by 5; 45..85 by 5, and 86
    # the tailing lug's rope carries the Tail crane's hook load at 0 deg
    assert states[0]["tensions"]["Tail"] == pytest.approx(32.0, abs=1e-9)
