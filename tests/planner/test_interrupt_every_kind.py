"""Ctrl-C keeps the plan in every kind of plan (issue 29 item 11).

Each test raises KeyboardInterrupt at a chosen point deep in one planner (a monkeypatched
function, counted calls: deterministic) and checks that ``plan()`` raises
:class:`Interrupted` carrying the best plan found so far, of the expected kind, marked
``stopped = "interrupted"`` where the search did not finish, and that ``liftplan plan`` (its
``main`` in-process, on the same problem) prints that plan marked INTERRUPTED and exits 130.
The last test sends a real SIGINT to a MIP that HiGHS cannot finish and checks it stops within
seconds (the strength planner's 30 s partner MIP took its whole time limit to notice).
"""

from __future__ import annotations

import dataclasses
import json
import os
import signal
import threading
import time

import cvxpy as cp
import numpy as np
import pytest
from helpers import EXAMPLES
from support.planning import small_problem as held_problem
from support.strength import small_problem as strength_problem

import liftplan.planner.problem.file as problem_file
from liftplan.planner.cli import main
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem
from liftplan.planner.search.evaluator import Interrupted, SetEvaluator


def interrupt_on(monkeypatch, owner, name, call):
    """``owner.name`` raises KeyboardInterrupt on its ``call``-th call (1-based), else runs."""
    original = getattr(owner, name)
    calls = []

    def wrapped(*args, **kwargs):
        calls.append(1)
        if len(calls) == call:
            raise KeyboardInterrupt
        return original(*args, **kwargs)

    monkeypatch.setattr(owner, name, wrapped)
    return calls


def cli(monkeypatch, capsys, problem, *options):
    """``liftplan plan`` in-process on ``problem``: (exit code, stdout, stderr)."""
    monkeypatch.setattr(problem_file, "load_problem", lambda path: problem)
    code = main(["plan", "problem.toml", *options])
    out, err = capsys.readouterr()
    return code, out, err


def test_local_search_swap_phase_keeps_the_best_set(monkeypatch, capsys):
    """The tanker's seven deck points, local search: its second start takes one swap, to
    (C0, C1, C5, C6), the best set so far; Ctrl-C while it screens the next swaps."""
    import liftplan.planner.search.local as local

    problem = held_problem(4, search="local")
    # screen calls: start 1 (one row), its swaps; start 2, its swaps, swaps after one move
    interrupt_on(monkeypatch, local, "screen", 5)
    with pytest.raises(Interrupted) as caught:
        plan(problem)
    stop = caught.value
    result = stop.plan
    assert result is not None and result.kind == "held" and not stop.finished
    assert stop.phase == "local search: swaps"
    assert result.chosen.indices == (0, 1, 5, 6)
    assert result.stats.stopped == "interrupted" and result.stats.method == "local"
    assert result.stats.refined == 1  # the one swap taken
    # checked over the box as any plan: its value is the exact evaluation's
    exact = SetEvaluator(problem).evaluate((0, 1, 5, 6))
    assert result.chosen.worst_value == pytest.approx(exact.worst_value, rel=1e-9)
    assert 0.0 <= result.stats.lower_bound <= result.chosen.worst_value

    interrupt_on(monkeypatch, local, "screen", 5)  # the count starts again
    code, out, err = cli(monkeypatch, capsys, problem)
    assert code == 130
    assert out.startswith("INTERRUPTED: best plan found so far")
    assert "C0 C1 C5 C6" in out
    assert err.strip().splitlines()[-1].startswith("liftplan: interrupted; the plan above is the best")


def test_after_the_search_finished_the_plan_is_printed(monkeypatch, capsys):
    """Ctrl-C in the design loads, after the search finished: the complete plan is printed,
    marked INTERRUPTED as the search's answer (stopped as the search ended), exit 130."""
    from liftplan.planner.plans.design_loads import DesignBuilder

    problem = held_problem(4)
    interrupt_on(monkeypatch, DesignBuilder, "build", 1)
    code, out, err = cli(monkeypatch, capsys, problem, "--json")
    assert code == 130
    printed = json.loads(out)
    assert printed["interrupted"] is True and printed["search_finished"] is True
    assert printed["interrupted_in"] == "design loads, report and output"
    assert printed["search"]["stopped"] in ("proved", "gap")  # as the search ended
    assert printed["design_loads"] is not None  # computed for the printing, as in any plan
    assert (
        err.strip()
        .splitlines()[-1]
        .startswith(
            "liftplan: interrupted; the plan above is the search's answer (the search had finished; "
            "Ctrl-C in the design loads, report and output)"
        )
    )


def test_sling_plan_keeps_the_best_disjoint_sets(monkeypatch, capsys):
    """Three cranes on 2-leg slings (the apex planner): Ctrl-C at the search's third set
    evaluated; the plan holds the best set with disjoint slings ranked so far."""
    problem = load_problem(EXAMPLES / "block_three_slings_plan.toml")
    interrupt_on(monkeypatch, SetEvaluator, "evaluate", 3)
    with pytest.raises(Interrupted) as caught:
        plan(problem)
    result = caught.value.plan
    assert result is not None and result.kind == "slings"
    assert result.inner.stats.stopped == "interrupted"
    assert caught.value.phase.startswith("sling plan")
    assert len(result.inner.ranking) >= 1

    interrupt_on(monkeypatch, SetEvaluator, "evaluate", 3)
    code, out, err = cli(monkeypatch, capsys, problem)
    assert code == 130 and out.startswith("INTERRUPTED: best plan found so far")
    assert "liftplan: interrupted; the plan above" in err


@pytest.mark.parametrize("disguised", [False, True])
def test_two_crane_sling_plan_after_its_search(monkeypatch, capsys, disguised):
    """The two-crane sling planner is one vectorised pass; a Ctrl-C in what follows it (the
    legs posed on the rigging model, for the output) still prints its plan, also when casadi
    hands the Ctrl-C back as a RuntimeError naming it."""
    from liftplan.planner.plans.slings import lift

    problem = load_problem(EXAMPLES / "block_sling_plan.toml")
    lugs = json.loads(json.dumps(plan(problem).lugs))
    if disguised:
        original = lift.solve_rigging

        def casadi_style(*args, **kwargs):
            monkeypatch.setattr(lift, "solve_rigging", original)
            raise RuntimeError(".../casadi/core/function.cpp: Error in Function::call: KeyboardInterrupt")

        monkeypatch.setattr(lift, "solve_rigging", casadi_style)
    else:
        interrupt_on(monkeypatch, lift, "solve_rigging", 1)
    code, out, err = cli(monkeypatch, capsys, problem, "--json")
    assert code == 130, err
    printed = json.loads(out)
    assert printed["interrupted"] is True and printed["search_finished"] is True
    assert printed["lugs"] == lugs


def test_rope_lengths_keep_the_best_length_so_far(monkeypatch, capsys):
    """A range of payout: two lengths tried, Ctrl-C in the third trial after its first set
    evaluated; the plan is the best of the three (the third's best so far), stopped
    "interrupted"."""
    from liftplan.planner.plans import lengths

    base = held_problem(4)
    problem = dataclasses.replace(base, crane=dataclasses.replace(base.crane, rope_length_range=(25.0, 35.0)))
    real = lengths.plan_held
    trials = []

    def third_interrupted(inner, top=None, girder_order=True):
        trials.append(inner.crane.rope_length)
        if len(trials) == 3:  # its second set evaluated is where Ctrl-C lands
            with pytest.MonkeyPatch.context() as patch:
                interrupt_on(patch, SetEvaluator, "evaluate", 2)
                return real(inner, top, girder_order)
        return real(inner, top, girder_order)

    monkeypatch.setattr(lengths, "plan_held", third_interrupted)
    with pytest.raises(Interrupted) as caught:
        plan(problem)
    result = caught.value.plan
    assert result is not None and result.kind == "lengths"
    assert len(result.lengths.trials) == 3
    assert result.stats.stopped == "interrupted"
    values = [t.value for t in result.lengths.trials]
    assert result.chosen.worst_value == min(values)
    assert result.lengths.chosen in [t.lengths for t in result.lengths.trials]
    assert result.lengths.trials[-1].reason.startswith("interrupted")

    trials.clear()
    code, out, err = cli(monkeypatch, capsys, problem)
    assert code == 130 and out.startswith("INTERRUPTED: best plan found so far")
    assert "rope lengths" in err


def test_strength_plan_interrupted_in_its_partner_search(monkeypatch, capsys):
    """The pontoon, force control: the strength search ends (proved); Ctrl-C in the
    spread-optimal partner's first MIP. The plan is the strength search's answer, without a
    partner; printed with '-' in the partner's column."""
    from liftplan.planner.search.strength import CandidateMIP

    problem = strength_problem()
    expected = plan(problem)
    interrupt_on(monkeypatch, CandidateMIP, "solve", 2)
    with pytest.raises(Interrupted) as caught:
        plan(problem)
    result = caught.value.plan
    assert result is not None and result.kind == "strength"
    assert caught.value.phase == "spread-optimal partner search" and caught.value.finished
    assert result.spread_plan is None and result.spread_stats is None
    assert result.chosen.indices == expected.chosen.indices
    assert result.stats.stopped == expected.stats.stopped
    assert result.to_json()["spread_optimal"] is None

    interrupt_on(monkeypatch, CandidateMIP, "solve", 2)
    code, out, err = cli(monkeypatch, capsys, problem)
    assert code == 130 and out.startswith("INTERRUPTED: the search's plan (the search had finished")
    assert "spread-optimal plan: none" in out


def test_strength_plan_interrupted_before_any_set(monkeypatch, capsys):
    """Ctrl-C in the strength search's first set: nothing to keep; the CLI says so, exit 130."""
    from liftplan.planner.plans.strength import StrengthEvaluator

    problem = strength_problem()
    interrupt_on(monkeypatch, StrengthEvaluator, "evaluate", 1)
    with pytest.raises(Interrupted) as caught:
        plan(problem)
    assert caught.value.plan is None and caught.value.phase == "strength search"

    interrupt_on(monkeypatch, StrengthEvaluator, "evaluate", 1)
    code, out, err = cli(monkeypatch, capsys, problem)
    assert code == 130 and out == ""
    assert err.strip().splitlines()[-1] == "liftplan: interrupted (strength search) before any plan was found"


def market_split(rows=4, columns=40, seed=3):
    """A market-split MIP (Cornuejols & Dawande 1998): sum_j a_ij x_j + s_i - t_i = b_i,
    x binary, minimise sum (s + t). Branch and bound needs hours for these sizes."""
    rng = np.random.default_rng(seed)
    a = rng.integers(0, 100, size=(rows, columns))
    b = a.sum(axis=1) // 2
    x = cp.Variable(columns, boolean=True)
    slack = cp.Variable((2, rows), nonneg=True)
    problem = cp.Problem(cp.Minimize(cp.sum(slack)), [a @ x + slack[0] - slack[1] == b])
    return problem


def test_highs_stops_promptly_on_sigint():
    """A real SIGINT 1 s into a MIP HiGHS cannot finish (time limit 60 s): KeyboardInterrupt
    well before the time limit."""
    from liftplan.planner.search.bounds import run_highs

    problem = market_split()
    sent = {}

    def send():
        sent["at"] = time.perf_counter()
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(1.0, send)
    started = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            run_highs(problem, "market split", time_limit=60.0)
    finally:
        timer.cancel()
    stopped = time.perf_counter()
    assert "at" in sent, "the MIP ended before the signal: not a test of stopping"
    # without the stop HiGHS runs to its 60 s limit; the margins are wide so that a loaded
    # machine cannot fail it by chance (it stops within 1 s when idle)
    assert stopped - sent["at"] < 20.0, f"stopped {stopped - sent['at']:.1f} s after SIGINT"
    assert stopped - started < 30.0
