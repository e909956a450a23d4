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

c depends on the lug the crane takes: :func:`series_fleet` / :func:`series_problem` set it
for one assignment (exact for that lug set, from the crane as given however the problem's
fleet stands), :func:`reference_problem` for the search's bounds, at each crane's stiffest
lug within its reach (the one nearest its vessel's axes: the largest twist a hook error puts
in, the safe side for the hook tolerance).

Limits (:func:`vessel_worst`, :func:`vessel_breach`): with the levelling ballast set for the
rope's level tension T0, a state where it holds T heels the vessel by (T - T0) y_t /
(disp GM_T) and trims it by (T - T0) x_t / (disp GM_L); over a plan's worst states the largest
|heel| is max(|T_max - T0|, |T_min - T0|) |y_t| / (disp GM_T), and the search rules out a set
that breaks ``max_heel``, ``max_trim`` or ``min_freeboard`` there.

Wind (``[wind]`` of a planning file, from any direction; :mod:`liftplan.model.scene.wind`):
the body's couple F (h - h_lugs) moves its weight's line by F (h - h_lugs) / W downwind, so
the CG envelope's plan half-widths grow by that much (:func:`wind_problem`; h_lugs the
candidates' mean height); a floating crane's boom wind heels and trims its vessel and moves
its tip by up to F h sqrt((y_t / (disp GM_T))^2 + (x_t / (disp GM_L))^2) (the worst direction):
a hook-height error, added to the crane's hook tolerance at the lug it takes (the most over
its reach in the reference problem).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import InvalidScene


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


@dataclass(frozen=True)
class VesselWorst:
    """A crane vessel over a plan's worst states, its levelling ballast set.

    The ballast levels the vessel at the rope's level tension T0 (:func:`vessel_worst`), so at
    a state where the rope holds T the vessel heels by (T - T0) y_t / (disp GM_T) and trims by
    (T - T0) x_t / (disp GM_L) (small angles), and heaves by T / (rho A_wp).

    Parameters
    ----------
    heel, trim : float  [deg]
        The largest |heel| and |trim| over the states.
    freeboard : float or None  [m]
        The lowest deck corner's freeboard over the states; None where the vessel gives none.
    """

    heel: float
    trim: float
    freeboard: float | None

    def breach(self, vessel):
        """The first of the vessel's limits these states break: ``"heel"`` (beyond
        ``max_heel``), ``"trim"`` (beyond ``max_trim``), ``"freeboard"`` (below
        ``min_freeboard``), or None within every one (a limit met exactly is kept, as its
        check passes)."""
        if vessel.max_heel is not None and not self.heel <= vessel.max_heel:
            return "heel"
        if vessel.max_trim is not None and not self.trim <= vessel.max_trim:
            return "trim"
        if self.freeboard is not None and not self.freeboard >= vessel.min_freeboard:
            return "freeboard"
        return None


def limit_checks(prefix, crane, worst, limits, where):
    """The checks of a vessel's worst heel, trim and freeboard against its limits.

    Parameters
    ----------
    prefix : str
        Before each check's name: ``""`` (``vessel_heel``, ``vessel_trim``,
        ``vessel_freeboard``) or ``"breakout_"``.
    crane : str
        The crane's name (the checks' subject).
    worst : VesselWorst
    limits : tuple
        (max_heel [deg] or None, max_trim [deg] or None, min_freeboard [m] or None); a check
        only where its limit is given (the freeboard where ``worst`` has one).
    where : str
        The states, for the notes ("over the box and hook errors", "at breakout ...").

    Returns
    -------
    list of Check
    """
    max_heel, max_trim, min_freeboard = limits
    out = []
    for name, value, limit, what in (
        ("vessel_heel", worst.heel, max_heel, "heel"),
        ("vessel_trim", worst.trim, max_trim, "trim"),
    ):
        if limit is not None:
            note = f"largest |{what}| {where}, the levelling ballast set"
            out.append(Check.upper(prefix + name, crane, value, limit, "deg", note=note))
    if worst.freeboard is not None:
        note = f"lowest deck corner {where}, the levelling ballast set"
        out.append(
            Check.lower(prefix + "vessel_freeboard", crane, worst.freeboard, min_freeboard, "m", note=note)
        )
    return out


def vessel_worst(vessel, offset, load, extremes):
    """A vessel's largest heel and trim and least freeboard over a rope's tensions.

    Parameters
    ----------
    vessel : Vessel
    offset : tuple of 2 float  [m]
        The tip's (x_t forward, y_t to starboard) from the flotation centre.
    load : float  [t]
        The rope's level tension T0, at which the levelling ballast (-T0 y_t, -T0 x_t) leaves
        the vessel level.
    extremes : tuple of 2 float  [t]
        The rope's lowest and highest tension over the states (the tolerance box, the CG
        envelope and the hook errors; or one state twice).

    Returns
    -------
    VesselWorst
        heel = max |T - T0| |y_t| / (disp GM_T) and trim = max |T - T0| |x_t| / (disp GM_L) over
        T in ``extremes`` (linear in T, so at an end); the freeboard, freeboard - T / (rho A_wp)
        - (beam / 2) |T - T0| |y_t| / (disp GM_T) - (length / 2) |T - T0| |x_t| / (disp GM_L),
        concave in T, so least at an end too.
    """
    forward, starboard = offset
    swing = max(abs(t - load) for t in extremes)
    freeboard = None
    if vessel.freeboard is not None:
        freeboard = min(
            vessel.lowest_freeboard(
                t / vessel.heave_stiffness,
                (t - load) * starboard / vessel.heel_stiffness,
                (t - load) * forward / vessel.trim_stiffness,
            )
            for t in extremes
        )
    return VesselWorst(
        heel=math.degrees(swing * abs(starboard) / vessel.heel_stiffness),
        trim=math.degrees(swing * abs(forward) / vessel.trim_stiffness),
        freeboard=freeboard,
    )


def vessel_breach(problem, indices, cranes, preload, low, high):
    """The first vessel limit a lug set breaks over its states, or None.

    Parameters
    ----------
    problem : PlanProblem
    indices, cranes : sequence of int
        The set's candidates and the fleet index of the crane on each.
    preload : array_like, shape (n,)  [t]
        The level tensions T0 (the levelling ballast is set for them).
    low, high : array_like, shape (n,)  [t]
        Each rope's lowest and highest tension over the states.

    Returns
    -------
    str or None
        ``"heel"``, ``"trim"`` or ``"freeboard"`` (:meth:`VesselWorst.breach`) for the first
        floating crane, in the set's order, that breaks one.
    """
    for k, (i, j) in enumerate(zip(indices, cranes)):
        vessel = problem.fleet[j].vessel
        if vessel is None:
            continue
        offset = tip_offsets(vessel, problem.plan_points[i])
        worst = vessel_worst(vessel, offset, float(preload[k]), (float(low[k]), float(high[k])))
        cause = worst.breach(vessel)
        if cause is not None:
            return cause
    return None


def has_limits(problem):
    """True when a crane's vessel gives a limit the plan checks (heel, trim or freeboard)."""
    return any(
        c.vessel is not None
        and (c.vessel.max_heel is not None or c.vessel.max_trim is not None or c.vessel.freeboard is not None)
        for c in problem.fleet
    )


def uses_vessels(problem):
    """True when a crane of the fleet stands on a vessel."""
    return any(c.vessel is not None for c in problem.fleet)


def _series(problem, crane, compliance, wind_error):
    """``crane`` (as given: its ``given`` when it already stands in series) with its vessel in
    series at a tip compliance [m/t], its hook tolerance widened by its boom's wind error [m]."""
    source = crane.given if crane.given is not None else crane
    rope = source.EA
    ea = source.rope_length / (source.rope_length / rope + compliance)
    changes = {"EA": float(ea), "rope_EA": rope, "given": source}
    if wind_error > 0.0:
        base = source.hook_tolerance if source.hook_tolerance is not None else problem.hook_tolerance
        changes["hook_tolerance"] = base + wind_error
    return dataclasses.replace(source, **changes)


def boom_wind(problem, crane):
    """The wind's area on a crane's boom (None without), refused on a crane on land."""
    wind = problem.wind
    if wind is None:
        return None
    boom = next((b for b in wind.booms if b.crane == crane.name), None)
    if boom is not None and crane.vessel is None:
        raise InvalidScene(
            f"wind.booms[{crane.name}]: the crane stands on land; expected a floating crane "
            "(cranes[].vessel): the wind on a boom moves only a floating crane's tip"
        )
    return boom


def wind_tip_error(problem, crane, plan_points):
    """How far the wind on a floating crane's boom can move its tip, the worst direction, at
    world plan points  [m] (zeros without)."""
    points = np.asarray(plan_points, dtype=float).reshape(-1, 2)
    boom = boom_wind(problem, crane)
    if boom is None:
        return np.zeros(len(points))
    vessel = crane.vessel
    offsets = np.array([vessel.axes(p) for p in points]).reshape(-1, 2)
    moment = problem.wind.force(boom) * boom.height
    return moment * np.hypot(offsets[:, 1] / vessel.heel_stiffness, offsets[:, 0] / vessel.trim_stiffness)


def wind_problem(problem):
    """The problem with the body's wind couple in its CG envelope (module docstring)."""
    wind = problem.wind
    for crane in problem.fleet:
        boom_wind(problem, crane)  # a boom on land is refused
    if wind is None or wind.body is None:
        return problem
    shift = wind_shift(problem)
    x, y, z = problem.cog_envelope.half_widths
    envelope = dataclasses.replace(problem.cog_envelope, half_widths=(x + shift, y + shift, z))
    return dataclasses.replace(problem, cog_envelope=envelope)


def wind_shift(problem):
    """How far the body's wind couple moves its weight's line in plan  [m] (0 without)."""
    wind = problem.wind
    if wind is None or wind.body is None:
        return 0.0
    lever = wind.body.height - float(np.mean(problem.points[:, 2]))
    return abs(wind.force(wind.body) * lever / problem.body.weight)


def series_fleet(problem, indices, cranes):
    """The fleet with each vessel's crane in series with its rope at the lug it takes.

    Parameters
    ----------
    problem : PlanProblem
        Its cranes as given, or already in series elsewhere (:func:`reference_problem`): each
        is put in series from the crane as given.
    indices : sequence of int
        Candidate indices of a lug set.
    cranes : sequence of int
        The fleet index of the crane on each.

    Returns
    -------
    tuple of FleetCrane
        In fleet order; cranes not in the set, and cranes on land, unchanged.
    """
    fleet = list(problem.fleet)
    points = problem.plan_points
    for i, j in zip(indices, cranes):
        crane = fleet[j]
        if crane.vessel is not None:
            compliance = float(tip_compliance(crane.vessel, points[i])[0])
            fleet[j] = _series(
                problem, crane, compliance, float(wind_tip_error(problem, crane, points[i])[0])
            )
    return tuple(fleet)


def series_problem(problem, indices, cranes):
    """The problem with each vessel's crane in series with its rope at the lug it takes
    (:func:`series_fleet`).

    Returns
    -------
    PlanProblem
        Cranes not in the set, and cranes on land, unchanged.
    """
    return dataclasses.replace(problem, fleet=series_fleet(problem, indices, cranes))


def reference_problem(problem):
    """The problem the search uses: each vessel's crane in series at its stiffest lug in reach,
    its boom wind's tip error the largest over its reach.

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
        compliance = float(tip_compliance(crane.vessel, points).min())
        fleet[j] = _series(problem, crane, compliance, float(wind_tip_error(problem, crane, points).max()))
    return dataclasses.replace(problem, fleet=tuple(fleet))
