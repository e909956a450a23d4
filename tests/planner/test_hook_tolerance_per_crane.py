"""Review finding 4: each hook's own tolerance enters the skew factors, console and report.

Four lugs on a square, CG central, equal ropes (k = EA / l0): the held preload's twist gain is
dT_i / dH_j = (k / 4) t_i t_j with t = (1, -1, 1, -1) (``test_skew_factor_of_a_square_block``),
so with hook j within +-delta_j a rope's skewed load is W / 4 + (k / 4) sum_j delta_j and a
diagonal pair's W / 2 + (k / 2) sum_j delta_j: both factors 1 + k sum_j delta_j / W, whatever
hook has which tolerance. Before, the skew took the plan-wide ``hook_tolerance`` for every hook
(1.000 with a plan-wide 0 and one crane's own 0.03 m).
"""

from __future__ import annotations

import pytest

from liftplan.model.scene.objects import Body
from liftplan.planner import plan
from liftplan.planner.output.console.held import plan_table
from liftplan.planner.output.report.held import _basis, _checks
from liftplan.planner.problem.definition import Candidate, CraneSpec, PlanProblem
from liftplan.planner.problem.fleet import FleetCrane

WEIGHT, EA, LENGTH, HALF = 400.0, 20000.0, 40.0, 10.0


def _square(own, plan_wide):
    """The square block on four cranes, crane k with hook tolerance ``own[k]`` (None: the
    plan's ``plan_wide``)."""
    return PlanProblem(
        body=Body(WEIGHT, (0.0, 0.0, 0.0)),
        candidates=tuple(
            Candidate(f"C{i}", (sx * HALF, sy * HALF, 2.0))
            for i, (sx, sy) in enumerate([(1, 1), (-1, 1), (-1, -1), (1, -1)])
        ),
        cranes=4,
        crane=CraneSpec(EA=EA, rope_length=LENGTH, swl=300.0),
        fleet=tuple(
            FleetCrane(f"crane {k + 1}", EA=EA, rope_length=LENGTH, swl=300.0, hook_tolerance=t)
            for k, t in enumerate(own)
        ),
        heel_tolerance=0.0,
        trim_tolerance=0.0,
        hook_tolerance=plan_wide,
        lift_height=2.0,
        top=1,
    )


@pytest.mark.parametrize(
    "own, plan_wide",
    [
        ((None, None, 0.03, None), 0.0),  # one crane's own tolerance, the plan's 0
        ((0.10, None, 0.10, None), 0.02),  # two cranes override the plan's 0.02
    ],
)
def test_skew_takes_each_hooks_own_tolerance(own, plan_wide):
    result = plan(_square(own, plan_wide))
    by_crane = {f"crane {k + 1}": plan_wide if t is None else t for k, t in enumerate(own)}
    deltas = [by_crane[name] for name in result.chosen.crane_names]
    assert list(result.hook_tolerances.values()) == pytest.approx(deltas, abs=1e-12)
    k = EA / LENGTH
    factor = 1.0 + k * sum(deltas) / WEIGHT  # by hand
    assert len(result.skew) == 6
    for s in result.skew:
        share = WEIGHT / 4 * len(s.lugs)
        assert s.nominal == pytest.approx(share, rel=1e-9)
        assert s.skewed == pytest.approx(share * factor, rel=1e-9)
        assert s.factor == pytest.approx(factor, rel=1e-9)
    assert factor > 1.0 + 1e-3  # the case is not trivial


def test_console_and_report_name_each_hooks_tolerance():
    result = plan(_square((None, None, 0.03, None), 0.0))
    label = next(lab for lab, t in result.hook_tolerances.items() if t > 0)
    crane = result.cranes[label]
    console = plan_table(result)
    assert f"{label} ({crane}) +-0.03 m" in console
    assert "the same hook error on every hook" in console  # the accuracy needed is for one error on all
    assert f"each its own tolerance x 2: {label} ({crane}) +-0.06 m, the others +-0 m" in console
    basis = "".join(_basis(result))
    assert "hook-height tolerance (each hook&#x27;s own)" in basis or "each hook's own" in basis
    assert f"{label} ({crane}) +-0.03" in basis
    assert "+-0 m" not in basis.split("hook-height tolerance")[1][:60]  # not the plan-wide 0
    checks = "".join(_checks(result))
    caption = checks.split("Skew loads for hook heights each within its own tolerance (")[1].split(")</")[0]
    assert f"{label} ({crane}) +-0.03 m" in caption and caption.count("+-0 m") == 3
