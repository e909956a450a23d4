"""Crane fleets: unequal cranes with load charts round the tanker's seven deck points, and the
brute force over every lug set and every assignment of the cranes to it (scipy LPs)."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
from scipy.optimize import linprog

from liftplan.model.frames import choi_to_zup
from liftplan.model.scene.objects import Body
from liftplan.planner.problem.clearance import clear, segment_distance
from liftplan.planner.problem.definition import Candidate, CogEnvelope, PlanProblem
from liftplan.planner.problem.fleet import FleetCrane
from liftplan.planner.search.scenarios import LugSet, Scenario, box_attitudes
from support.planning import POINTS


def fleet(count):
    """Unequal cranes round the hull (z-up plan), charts short enough that reach matters."""
    specs = [
        ("Big aft", (10.0, -30.0), ((20.0, 700.0), (35.0, 450.0), (45.0, 300.0)), 80000.0, 40.0),
        ("Big fwd", (65.0, -30.0), ((20.0, 700.0), (35.0, 450.0), (45.0, 300.0)), 80000.0, 40.0),
        ("Small aft", (20.0, 22.0), ((15.0, 420.0), (30.0, 260.0), (40.0, 180.0)), 40000.0, 30.0),
        ("Small fwd", (60.0, 22.0), ((15.0, 420.0), (30.0, 260.0), (40.0, 180.0)), 40000.0, 30.0),
        ("Mid", (38.0, 30.0), ((20.0, 500.0), (40.0, 300.0), (48.0, 240.0)), 60000.0, 35.0),
    ]
    # each chart from 5 m at its first SWL: every candidate lies more than 5 m from every
    # crane, so the charts' least radii rule none out (reach is the last radius)
    return tuple(
        FleetCrane(
            name=n,
            position=p,
            load_chart=((5.0, c[0][1]),) + c,
            EA=ea,
            rope_length=l0,
            boom_min=30.0,
            boom_max=70.0,
        )
        for n, p, c, ea, l0 in specs[:count]
    )


def fleet_problem(count, objective="utilisation", **changes):
    problem = PlanProblem(
        body=Body(904.0, choi_to_zup((35.86, 2.5, 6.0))),
        candidates=tuple(Candidate(f"C{i}", choi_to_zup(p)) for i, p in enumerate(POINTS)),
        cranes=count,
        crane=None,
        fleet=fleet(count),
        objective=objective,
        heel_tolerance=2.0,
        trim_tolerance=2.0,
        min_tension=5.0,
        lift_height=1.0,
        cog_envelope=CogEnvelope((0.3, 0.2, 0.0)),
        top=3,
    )
    return dataclasses.replace(problem, **changes)


def buildable(problem, indices, cranes):
    """Every two booms of a row (slew centre to the lug in plan) apart by the clearance, by
    the closed-form segment distance (tested against sampling in test_crane_clearance.py)."""
    tips = problem.plan_points[list(indices)]
    ends = [(np.asarray(problem.fleet[j].position, dtype=float), tips[k]) for k, j in enumerate(cranes)]
    for (a0, a1), (b0, b1) in itertools.combinations(ends, 2):
        if not clear(segment_distance(a0, a1, b0, b1), problem.crane_clearance):
            return False
    return True


def linprog_minimax(lugset, scenarios):
    """The preload minimax of one set and assignment as a scipy LP (HiGHS): T* (n), high_k,
    low_k, worst; per-rope SWL at the crane's radius; the spread of s_i T_i."""
    problem = lugset.problem
    gains, offsets = lugset.affine(scenarios)
    if not (np.all(np.isfinite(gains)) and np.all(np.isfinite(offsets))):
        return None  # collinear lugs
    n, m = lugset.n, len(scenarios)
    size = n + 2 * m + 1
    rows, rhs = [], []
    reserve = problem.objective == "reserve"
    for k in range(m):
        for i in range(n):
            g = np.zeros(size)
            g[:n] = gains[k, i]
            s = lugset.scale[i]
            if reserve:  # the largest s_i T_i itself: s_i T_i - worst <= 0
                up = s * g
                up[-1] = -1.0
                rows.append(up), rhs.append(-s * offsets[k, i])
            else:
                up = s * g
                up[n + k] = -1.0
                rows.append(up), rhs.append(-s * offsets[k, i])
                down = -s * g
                down[n + m + k] = 1.0
                rows.append(down), rhs.append(s * offsets[k, i])
            rows.append(g), rhs.append(lugset.limit[i] - offsets[k, i])
            rows.append(-g), rhs.append(offsets[k, i] - problem.min_tension)
        if not reserve:
            spread = np.zeros(size)
            spread[n + k], spread[n + m + k], spread[-1] = 1.0, -1.0, -1.0
            rows.append(spread), rhs.append(0.0)
    a_level, b_level = lugset.level_statics
    a_eq = np.hstack([a_level, np.zeros((3, size - n))])
    low, high = lugset.preload_range()
    bounds = list(zip(low, high)) + [(None, None)] * (2 * m + 1)
    cost = np.zeros(size)
    cost[-1] = 1.0
    result = linprog(
        cost, A_ub=np.array(rows), b_ub=rhs, A_eq=a_eq, b_eq=b_level, bounds=bounds, method="highs"
    )
    return result.fun if result.status == 0 else None


def brute_force(problem, grid=7):
    """Every set and EVERY permutation of the cranes on it (no reach pruning, no symmetry)."""
    scenarios = [
        Scenario(h, t, tuple(o))
        for o in problem.cog_envelope.offsets()
        for h, t in box_attitudes(problem, grid, grid)
    ]
    swl = problem.reach[1]
    best = {}
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        for perm in itertools.permutations(range(problem.cranes)):
            if np.any(np.isnan(swl[list(indices), list(perm)])):
                continue  # a crane beyond its chart's reach
            if not buildable(problem, indices, perm):
                continue  # two booms crossing or within plan.crane_clearance
            best[(indices, perm)] = linprog_minimax(LugSet(problem, indices, perm), scenarios)
    return best
