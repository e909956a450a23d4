"""``[plan] breakout_scene`` with the strength objectives (issue 24 item 3: it was refused).

The sunken block of examples/sunken_block_plan.toml with a weight curve and allowable |M|, |Q|,
planned for the least bending on six candidates by two pairs of unequal cranes (hoist
control: the breakout case is the held model's). The breakout loads enter the strength plan as
they enter the spread plans: each crane's held tension at breakout (hook errors at worst) is
the chain's static input where it exceeds the box worst, with its breakout checks; the lug
choice is the strength optimum of the same states and limits, equal to the brute force over
every lug set and assignment.
"""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model.errors import InvalidScene, PlanInfeasible
from liftplan.planner.plans.breakout import breakout_case
from liftplan.planner.plans.strength import (
    StrengthContext,
    StrengthEvaluator,
    StrengthPlan,
    objective_weights,
    search_strength,
)
from liftplan.planner.problem.file import loads_problem
from liftplan.planner.search.scenarios import LugSet

PLAN = EXAMPLES / "sunken_block_plan.toml"
KEEP = ("F10", "F20", "F50")  # six candidates of the twelve
CRANES = """
[[cranes]]
name = "Aft P"
swl = 420.0
EA = 50000.0
rope_length = 44.0
[[cranes]]
name = "Aft S"
swl = 420.0
EA = 50000.0
rope_length = 44.0
[[cranes]]
name = "Fwd P"
swl = 360.0
EA = 30000.0
rope_length = 40.0
[[cranes]]
name = "Fwd S"
swl = 360.0
EA = 30000.0
rope_length = 40.0
"""


def block_text(objective="bending", control="hoist", fleet=False):
    """The example's plan for a strength objective: weight curve (uniform: W at the CG's x),
    allowables, six candidates, the two crane pairs, the CG envelope along x."""
    text = PLAN.read_text()
    blocks = text.split("[[candidates]]")
    head, tail = blocks[0], blocks[-1].split("[plan]", 1)[1]
    kept = [b for b in blocks[1:] if any(f'"{k}-' in b for k in KEEP)]
    kept[-1] = kept[-1].split("[plan]")[0]
    curve = "weight_curve = [[0.0, 10.0], [60.0, 10.0]]"
    head = head.replace('weight_basis = "air"', f'weight_basis = "air"\n{curve}')
    head += (
        "[strength]\nbending_moment = [[0.0, 2500.0], [60.0, 2500.0]]\n"
        "shear_force = [[0.0, 300.0], [60.0, 300.0]]\n\n"
    )
    tail = tail.replace("cog_tolerance = [0.5, 0.2, 0.3]", "cog_tolerance = [0.5, 0.0, 0.0]")
    tail = tail.replace("cranes = 4", f'cranes = 4\nobjective = "{objective}"')
    tail = tail.replace("[crane]", f'{CRANES if fleet else ""}\n[crane]\ncontrol = "{control}"')
    return head + "".join("[[candidates]]" + b for b in kept) + "[plan]" + tail


def block_problem(**kw):
    return loads_problem(block_text(**kw), base=EXAMPLES)


def brute_force(problem):
    """The best (value, indices, cranes) over every lug set and every assignment (two pairs of
    equal cranes: the distinct patterns; equal cranes: one)."""
    weights = objective_weights(problem)
    evaluator = StrengthEvaluator(StrengthContext(problem))
    best = None
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        kinds = (0, 0, 2, 2) if not problem.equal_cranes else (0, 0, 0, 0)
        for pattern in sorted(set(itertools.permutations(kinds))):
            try:
                found = evaluator.evaluate(indices, weights, _members(pattern))
            except PlanInfeasible:
                continue
            if best is None or found.value < best[0]:
                best = (found.value, found.indices, found.cranes)
    return best


def _members(kinds):
    """Fleet indices for a pattern of crane classes (0: the aft pair or every crane, 2: the
    forward pair)."""
    taken = {0: [0, 1, 2, 3], 2: [2, 3]} if kinds.count(0) == 4 else {0: [0, 1], 2: [2, 3]}
    return [taken[k].pop(0) for k in kinds]


@pytest.fixture(
    scope="module",
    params=[False, pytest.param(True, marks=pytest.mark.slow)],  # the 2 + 2 fleet: 90 rows, 20 s
    ids=["equal cranes", "two crane pairs"],
)
def block(request):
    """The strength plan of the block (its own search; the spread-optimal partner, which takes
    its 30 s, is not part of what is shown here)."""
    problem = block_problem(fleet=request.param)
    chosen, stats = search_strength(problem, objective_weights(problem))
    return problem, StrengthPlan(problem, chosen, stats, spread_plan=None, spread_stats=None)


def test_plan_is_the_brute_force_optimum(block):
    problem, result = block
    value, _, _ = brute_force(problem)
    assert result.chosen.value == pytest.approx(value, rel=1e-6)
    assert result.stats.stopped == "proved"


def test_breakout_enters_the_design_loads(block):
    """Each crane's breakout tension is the held model's on the chosen set and preload; the
    chain's static input is the larger of it and the box worst; the breakout checks are the
    plan's checks and its JSON's."""
    problem, result = block
    chosen = result.chosen
    case = breakout_case(problem, LugSet(problem, chosen.indices, chosen.cranes), chosen.preload)
    design = result.design_loads
    np.testing.assert_allclose(design.breakout.worst, case.worst, rtol=1e-12)
    for k, crane in enumerate(design.cranes):
        assert crane.breakout == pytest.approx(case.worst[k], rel=1e-12)
        assert crane.static_input == max(crane.worst, crane.nominal, case.worst[k])
        assert crane.crane == problem.fleet[chosen.cranes[k]].name
    assert any(c.governs == "breakout" for c in design.cranes)  # the case matters here
    names = [c.name for c in result.checks]
    assert names.count("breakout_hook_load") == 4 and "breakout_min_tension" in names
    out = result.to_json()
    assert out["breakout"]["tensions_with_hook_errors"] == dict(zip(result.labels, case.worst.tolist()))


def test_a_breakout_too_heavy_fails_its_check(tmp_path):
    """A soil that holds harder: the breakout hook loads pass the SWL and the plan's breakout
    checks fail (``liftplan plan`` exits 4 on a failed check of ``result.checks``); the design
    hook loads fail only where breakout governs."""
    scene = (EXAMPLES / "sunken_block_breakout.toml").read_text()
    (tmp_path / "seabed.toml").write_text(scene.replace("shear_strength = 1.2", "shear_strength = 4.0"))
    text = block_text().replace("sunken_block_breakout.toml", "seabed.toml")
    problem = loads_problem(text, base=tmp_path)
    chosen, stats = search_strength(problem, objective_weights(problem))
    result = StrengthPlan(problem, chosen, stats, spread_plan=None, spread_stats=None)
    failed = [c for c in result.checks if not c.ok]
    assert "breakout_hook_load" in {c.name for c in failed}
    # the design hook loads fail too where breakout governs the chain's static input
    governed = {c.crane for c in result.design_loads.cranes if c.governs == "breakout"}
    assert {c.subject for c in failed if c.name == "design_hook_load"} <= governed
    assert not result.to_json()["breakout"]["ok"]


def test_force_control_refused_one_line():
    with pytest.raises(InvalidScene) as err:
        dataclasses.replace(block_problem(), controls=("force",) * 4, hook_tolerance=0.0)
    assert 'breakout_scene: given with control = "force"' in str(err.value)
    assert "\n" not in str(err.value)
