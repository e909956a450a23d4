"""A plan whose breakout scene holds water in its compartments says that its in-air case
takes that water as drained (issue 29 item 9: 147.6 t left out without a word)."""

from __future__ import annotations

from helpers import EXAMPLES

from liftplan.planner import load_problem, loads_problem
from liftplan.planner.cli import main
from liftplan.planner.problem.plausibility import problem_warnings


def test_the_in_air_case_says_what_water_it_leaves_out():
    problem = load_problem(EXAMPLES / "sunken_block_plan.toml")
    (line,) = [w for w in problem_warnings(problem) if w.startswith("plan.breakout_scene")]
    assert "147.6 t of water" in line and "up to 747.6 t" in line


def test_no_breakout_scene_no_such_warning():
    text = (EXAMPLES / "tanker_plan.toml").read_text(encoding="utf-8")
    assert not any("breakout_scene" in w for w in problem_warnings(loads_problem(text)))


def test_the_command_line_prints_it_on_stderr(capsys):
    main(["plan", str(EXAMPLES / "sunken_block_plan.toml"), "--json"])
    err = capsys.readouterr().err
    assert "liftplan: warning: plan.breakout_scene: its compartments hold 147.6 t" in err
