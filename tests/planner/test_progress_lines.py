"""Progress on stderr for every long phase of ``liftplan plan`` (issue 29 item 10).

The lines are shown when stderr is a terminal (tests run without one, so the rule is forced
here by monkeypatching :func:`~liftplan.planner.search.progress.shown`, and the 1 s delay set
to 0 so the small problems' short phases draw too). Each planner's phases must name
themselves; stdout (``--json``) never carries a line; a terminal of unknown width gets a bar.
"""

from __future__ import annotations

import dataclasses
import json
import os
import re
import time

import pytest
from helpers import EXAMPLES
from support.planning import small_problem as held_problem
from support.strength import small_problem as strength_problem

import liftplan.planner.problem.file as problem_file
import liftplan.planner.search.progress as progress
from liftplan.planner.cli import main
from liftplan.planner.problem.file import load_problem


@pytest.fixture
def terminal(monkeypatch):
    """stderr taken for a terminal; lines drawn at once, and at every update (however fast
    the machine: a line that only had to be redrawn once per 0.1 s was not, under xdist)."""
    monkeypatch.setattr(progress, "shown", lambda wanted, file=None: wanted is not False)
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "MININTERVAL", 0.0)
    # a wide terminal, whatever the environment says (xdist's workers have COLUMNS = 80,
    # which cuts the best / bound off the longer lines)
    monkeypatch.setenv("COLUMNS", "200")


def run_plan(monkeypatch, capsys, problem):
    monkeypatch.setattr(problem_file, "load_problem", lambda path: problem)
    code = main(["plan", "problem.toml", "--json"])
    out, err = capsys.readouterr()
    return code, out, err


def test_unknown_width_still_gets_a_bar(monkeypatch, capsys):
    """No size from the terminal and no COLUMNS: drawn FALLBACK_WIDTH wide, the bar (20
    cells) before the numbers; a long postfix is cut, not the bar."""

    def no_size(fd=None):
        raise OSError("no size")

    monkeypatch.setattr(os, "get_terminal_size", no_size)
    monkeypatch.delenv("COLUMNS", raising=False)
    assert progress.width(None) == progress.FALLBACK_WIDTH
    monkeypatch.setattr(progress, "DELAY", 0.0)
    bar = progress.progress_bar(10, True, desc="exact search", unit="rows")
    bar.update(5)
    bar.set_postfix_str(progress.best_bound(91.74, 80.0, "x" * 300))
    bar.refresh()
    bar.close()
    drawn = [line for line in re.split(r"[\r\n]", capsys.readouterr().err) if "50%" in line]
    assert drawn, "no line at 50 %"
    line = drawn[-1]
    assert re.search(r"exact search:  50% \|.{20}\| 5/10 rows", line)
    assert len(line) <= progress.FALLBACK_WIDTH
    assert "best 91.74, bound 80" in line


def test_a_terminal_of_no_size_still_gets_its_line(monkeypatch, capsys):
    """A pty with no size set reports 0 x 0: tqdm alone drew nothing there (it took 0 lines
    for no room), which is how hull154's first minute showed nothing."""
    monkeypatch.setattr(os, "get_terminal_size", lambda fd=None: os.terminal_size((0, 0)))
    monkeypatch.setenv("COLUMNS", "57")
    assert progress.width(None) == 57
    monkeypatch.delenv("COLUMNS")
    monkeypatch.delenv("LINES", raising=False)
    assert progress.width(None) == progress.FALLBACK_WIDTH
    assert progress.height(None) == progress.FALLBACK_HEIGHT
    monkeypatch.setattr(progress, "DELAY", 0.0)
    bar = progress.progress_bar(4, True, desc="local search: swaps", unit="starts")
    bar.update(1)
    bar.refresh()
    bar.close()
    assert re.search(r"local search: swaps:  25% \|.{20}\| 1/4 starts", capsys.readouterr().err)


def test_not_shown_without_a_terminal(capsys):
    """The rule kept: progress=None shows nothing when stderr is not a terminal (here)."""
    assert progress.progress_bar(10, None) is None
    with progress.phase("design loads", None) as bar:
        assert bar is None
    assert capsys.readouterr().err == ""


def test_a_phase_without_steps_is_redrawn(monkeypatch, capsys):
    """A phase with no steps (one long MIP, the design loads) moves: its ticker redraws it."""
    monkeypatch.setattr(progress, "DELAY", 0.0)
    monkeypatch.setattr(progress, "TICK", 0.01)
    drawn = 0
    with progress.phase("design loads and checks", True, "best 1") as bar:
        deadline = time.monotonic() + 10.0
        while drawn < 3 and time.monotonic() < deadline:
            drawn = capsys.readouterr().err.count("design loads and checks:") + drawn
            time.sleep(0.01)
        assert bar is not None
    assert drawn >= 3


def test_local_search_shows_its_swaps_and_the_output_phase(terminal, monkeypatch, capsys):
    """hull154's first ~50 s were silent: the local search's swaps and the check of its set
    now show, and the design loads after it; stdout is the JSON alone."""
    code, out, err = run_plan(monkeypatch, capsys, held_problem(4, search="local"))
    assert code == 0
    json.loads(out)  # no progress on stdout
    assert "local search: swaps" in err and "starts" in err
    assert "local search: checking its set over the box" in err
    assert "design loads and checks" in err


def test_exact_search_shows_screening_and_rows(terminal, monkeypatch, capsys):
    code, out, err = run_plan(monkeypatch, capsys, held_problem(4))
    assert code == 0
    json.loads(out)
    assert "exact search: screening 35 rows" in err
    assert re.search(r"exact search: +\d+% \|", err)
    # an estimate of the time left from the first line (tqdm's "?" before a rate is known)
    assert re.search(r"exact search: +\d+% \|.*, (\?|[0-9:]+) left", err)


def test_rope_lengths_show_their_trials(terminal, monkeypatch, capsys):
    base = held_problem(4)
    problem = dataclasses.replace(base, crane=dataclasses.replace(base.crane, rope_length_range=(25.0, 35.0)))
    code, out, err = run_plan(monkeypatch, capsys, problem)
    assert code == 0
    json.loads(out)
    assert re.search(r"rope lengths: trials: +\d+% \|.{20}\| \d+/\d+ trials.*best [0-9.]+, bound", err)


def test_strength_plan_shows_both_searches(terminal, monkeypatch, capsys):
    code, out, err = run_plan(monkeypatch, capsys, strength_problem())
    assert code == 0
    json.loads(out)
    assert re.search(r"strength search: MIP rounds: .*best [0-9.e-]+, bound", err)
    assert "spread-optimal partner: MIP rounds" in err


def test_sling_plans_show_their_phase(terminal, monkeypatch, capsys):
    code, out, err = run_plan(monkeypatch, capsys, load_problem(EXAMPLES / "block_sling_plan.toml"))
    assert code == 0
    json.loads(out)
    assert "sling plan: every pair of rigs" in err
