"""The held-preload search's small problem (seven deck points of the tanker, equal cranes) and
its brute force: every lug set's preload minimax as a scipy LP on a dense grid of scenarios;
the tanker fleet with her hull girder's allowables."""

import dataclasses
import itertools
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import linprog

from liftplan.model import solve
from liftplan.model.frames import choi_to_zup
from liftplan.model.scene.objects import Body
from liftplan.model.strength import strength_checks
from liftplan.planner.plans.girder import moved_body
from liftplan.planner.problem.definition import Candidate, CogEnvelope, CraneSpec, PlanProblem
from liftplan.planner.search.scenarios import LugSet, Scenario, box_attitudes

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

#: Seven deck points of the tanker (papers' frame).
POINTS = [
    (4.2, 6, 0),
    (16.2, 6, 12),
    (28.55, 6, 0),
    (40.9, 6, 12),
    (53.25, 6, 6),
    (65.6, 6, 0),
    (73.6, 6, 12),
]


def small_problem(cranes, **changes):
    """Seven deck points of the tanker (papers' frame), a CG box: 35 sets of 4."""
    problem = PlanProblem(
        body=Body(904.0, choi_to_zup((35.86, 2.5, 6.0))),
        candidates=tuple(Candidate(f"C{i}", choi_to_zup(p)) for i, p in enumerate(POINTS)),
        cranes=cranes,
        crane=CraneSpec(EA=50000.0, rope_length=30.0, swl=600.0, boom_min=30.0, boom_max=60.0),
        heel_tolerance=2.0,
        trim_tolerance=3.0,
        min_tension=5.0,
        lift_height=1.0,
        cog_envelope=CogEnvelope((0.3, 0.2, 0.1)),
        top=3,
    )
    return dataclasses.replace(problem, **changes)


def brute_force(problem, grid=9):
    """Every set, the preload LP on a dense grid of scenarios, solved by scipy's HiGHS."""
    scenarios = [
        Scenario(h, t, tuple(o))
        for o in problem.cog_envelope.offsets()
        for h, t in box_attitudes(problem, grid, grid)
    ]
    best = {}
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        value = linprog_minimax(LugSet(problem, indices), scenarios)
        if value is not None:
            best[indices] = value
    return best


def linprog_minimax(lugset, scenarios):
    """The preload minimax as scipy LP: variables T* (n), high_k, low_k, worst."""
    problem = lugset.problem
    gains, offsets = lugset.affine(scenarios)
    if not (np.all(np.isfinite(gains)) and np.all(np.isfinite(offsets))):
        return None  # lugs collinear in plan: singular statics
    n, m = lugset.n, len(scenarios)
    size = n + 2 * m + 1
    rows, rhs = [], []
    for k in range(m):
        for i in range(n):
            g = np.zeros(size)
            g[:n] = gains[k, i]
            up = g.copy()
            up[n + k] = -1.0  # T_ki - high_k <= -q
            rows.append(up), rhs.append(-offsets[k, i])
            down = -g
            down[n + m + k] = 1.0  # low_k - T_ki <= q
            rows.append(down), rhs.append(offsets[k, i])
            rows.append(g), rhs.append(lugset.limit[i] - offsets[k, i])
            rows.append(-g), rhs.append(offsets[k, i] - problem.min_tension)
        spread = np.zeros(size)
        spread[n + k], spread[n + m + k], spread[-1] = 1.0, -1.0, -1.0
        rows.append(spread), rhs.append(0.0)
    a_level, b_level = lugset.level_statics
    a_eq = np.hstack([a_level, np.zeros((3, size - n))])
    low, high = lugset.preload_range()
    bounds = [(lo, hi) for lo, hi in zip(low, high)] + [(None, None)] * (2 * m + 1)
    cost = np.zeros(size)
    cost[-1] = 1.0
    result = linprog(
        cost, A_ub=np.array(rows), b_ub=rhs, A_eq=a_eq, b_eq=b_level, bounds=bounds, method="highs"
    )
    return result.fun if result.status == 0 else None


def fleet_with_girder(bending=None):
    """examples/tanker_fleet.toml with the weight curve and allowables of
    examples/tanker_strength.toml (the bending allowable replaced when given): a fleet plan
    whose hull girder is checked."""
    fleet = (EXAMPLES / "tanker_fleet.toml").read_text(encoding="utf-8")
    strength = (EXAMPLES / "tanker_strength.toml").read_text(encoding="utf-8")
    curve = strength[strength.index("weight_curve") : strength.index("[strength]")]
    allowables = strength[strength.index("[strength]") : strength.index("[[lugs]]")]
    if bending is not None:
        start = allowables.index("bending_moment = ")
        allowables = (
            allowables[:start] + f"bending_moment = {bending}" + allowables[allowables.index("   # t m") :]
        )
    text = fleet.replace("cog = [35.86, 2.5, 6.0]\n", "cog = [35.86, 2.5, 6.0]\n" + curve, 1)
    return text.replace("[attitude]", allowables + "\n[attitude]", 1)


#: Cranes added to the tanker fleet for the six- and eight-crane cases (papers' frame, like the
#: example's [[cranes]]): a 600 t crane off each side amidships, a 400 t crane off the stern and
#: off the bow. ASSUMED data, like the example's.
EXTRA_CRANES = """
[[cranes]]
name = "Crane E"
position = [40.0, 0.0, -25.0]
load_chart = [[15.0, 600.0], [25.0, 450.0], [32.0, 330.0]]
EA = 40000.0
rope_length = 30.0

[[cranes]]
name = "Crane F"
position = [40.0, 0.0, 37.0]
load_chart = [[15.0, 600.0], [25.0, 450.0], [32.0, 330.0]]
EA = 40000.0
rope_length = 30.0

[[cranes]]
name = "Crane G"
position = [-22.0, 0.0, 6.0]
load_chart = [[15.0, 400.0], [30.0, 250.0], [40.0, 180.0]]
EA = 30000.0
rope_length = 30.0

[[cranes]]
name = "Crane H"
position = [104.0, 0.0, 6.0]
load_chart = [[15.0, 400.0], [30.0, 250.0], [40.0, 180.0]]
EA = 30000.0
rope_length = 30.0
"""


def larger_fleet(count, text=None):
    """examples/tanker_fleet.toml (or ``text``, a variant of it) with ``count`` - 4 of
    :data:`EXTRA_CRANES` added (count 4 to 8)."""
    text = (EXAMPLES / "tanker_fleet.toml").read_text(encoding="utf-8") if text is None else text
    blocks = EXTRA_CRANES.split("\n[[cranes]]")[1:]
    added = "".join("\n[[cranes]]" + b for b in blocks[: count - 4])
    return text.replace("\n[attitude]", added + "\n[attitude]", 1)


def solved_checks(result, worst):
    """solve's girder checks of the plan's scene at a GirderWorst's state: the CG moved and
    each hook moved by the plan's hook shift that brings the body to that attitude (the held
    preload: the crews hold the level tensions' pattern as the body heels and trims)."""
    scene, s = result.scene, worst.scenario
    shift = result.lugset.hook_shifts(result.chosen.preload, [s])[0]
    scene = dataclasses.replace(
        scene,
        body=moved_body(scene.body, s.cog_offset),
        cranes=tuple(
            dataclasses.replace(c, boom_height=c.boom_height + float(d)) for c, d in zip(scene.cranes, shift)
        ),
    )
    eq = solve(scene)
    assert eq.pose.heel == pytest.approx(s.heel, abs=1e-9) and eq.pose.trim == pytest.approx(s.trim, abs=1e-9)
    return {c.name: c for c in strength_checks(scene, eq)}
