"""Floating cranes in the planning problem: each vessel in series with its crane's rope.

A fleet crane with a ``vessel`` has its boom tip above the lug it takes, at the level pose;
under the hook load T the tip drops by c T, c = 1 / (rho A_wp) + y_t^2 / (disp GM_T) +
x_t^2 / (disp GM_L) with (x_t, y_t) the lug's plan offset from the vessel's flotation centre
in the vessel's axes (:mod:`liftplan.model.scene.vessel`). With vertical ropes and one crane
per vessel the rope and the vessel are springs in series, exactly: the problem's rope of
stiffness EA / l0 becomes one of 1 / (l0 / EA + c), i.e. ``EA`` becomes l0 / (l0 / EA + c)
(the rope's own EA kept in ``rope_EA``). Every part of the planner that reads a crane's
``EA`` (the held preload, the robust worst case over the box, the hook-height tolerance's
twist, the boom heights) then works with the coupled stiffness, unchanged.

c depends on the lug the crane takes: :func:`series_problem` sets it for one assignment
(exact for that lug set), :func:`reference_problem` for the search, at each crane's stiffest
lug within its reach (the one nearest its vessel's axes: the largest twist a hook error puts
in, the safe side for the hook tolerance).
"""

from __future__ import annotations

import dataclasses

import numpy as np


def tip_compliance(vessel, plan_points):
    """Drop of a boom tip per tonne of its hook load at world plan points  [m/t].

    Parameters
    ----------
    vessel : Vessel
    plan_points : array_like, shape (k, 2)  [m]
        World plan (x, y), ``z-up``.

    Returns
    -------
    numpy.ndarray, shape (k,)  [m/t]
    """
    points = np.asarray(plan_points, dtype=float).reshape(-1, 2)
    offsets = np.array([vessel.axes(p) for p in points]).reshape(-1, 2)
    forward, starboard = offsets[:, 0], offsets[:, 1]
    return (
        1.0 / vessel.heave_stiffness
        + starboard**2 / vessel.heel_stiffness
        + forward**2 / vessel.trim_stiffness
    )


def tip_offsets(vessel, plan_point):
    """(x_t forward, y_t to starboard) of a world plan point from the vessel's flotation centre  [m]."""
    return vessel.axes(plan_point)


def uses_vessels(problem):
    """True when a crane of the fleet stands on a vessel."""
    return any(c.vessel is not None for c in problem.fleet)


def _series(crane, compliance):
    """``crane`` with its vessel in series at a tip compliance  [m/t]."""
    rope = crane.rope_EA if crane.rope_EA is not None else crane.EA
    ea = crane.rope_length / (crane.rope_length / rope + compliance)
    return dataclasses.replace(crane, EA=float(ea), rope_EA=rope)


def series_problem(problem, indices, cranes):
    """The problem with each vessel's crane in series with its rope at the lug it takes.

    Parameters
    ----------
    problem : PlanProblem
    indices : sequence of int
        Candidate indices of a lug set.
    cranes : sequence of int
        The fleet index of the crane on each.

    Returns
    -------
    PlanProblem
        Cranes not in the set, and cranes on land, unchanged.
    """
    fleet = list(problem.fleet)
    points = problem.plan_points
    for i, j in zip(indices, cranes):
        crane = fleet[j]
        if crane.vessel is not None:
            fleet[j] = _series(crane, float(tip_compliance(crane.vessel, points[i])[0]))
    return dataclasses.replace(problem, fleet=tuple(fleet))


def reference_problem(problem):
    """The problem the search uses: each vessel's crane in series at its stiffest lug in reach.

    Returns
    -------
    PlanProblem
        With each floating crane's ``EA`` the series stiffness at the candidate within its
        chart's reach of least tip compliance (every candidate without a chart).
    """
    _, swl = problem.reach
    fleet = list(problem.fleet)
    for j, crane in enumerate(fleet):
        if crane.vessel is None:
            continue
        inside = np.isfinite(swl[:, j])
        points = problem.plan_points[inside] if inside.any() else problem.plan_points
        fleet[j] = _series(crane, float(tip_compliance(crane.vessel, points).min()))
    return dataclasses.replace(problem, fleet=tuple(fleet))
