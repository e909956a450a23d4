"""What a held plan asks of its crane vessels: heel, trim, tip drop and the ballast to set.

For each crane on a vessel (one rope, the vessel in series with it,
:mod:`liftplan.planner.problem.vessels`), at the plan's level tension T0 (nominal CG) and
over its worst case (the tolerance box, the CG envelope and the hook-height errors, the
preload held, :func:`~liftplan.planner.search.evaluator.robust`):

* heave T0 / (rho A_wp), heel T0 y_t / (disp GM_T), trim T0 x_t / (disp GM_L) and the tip
  drop c T0: the extra hoist the crane needs as the load comes on;
* the levelling ballast (-T0 y_t, -T0 x_t) [t m]: the moment that, set before the lift,
  leaves the vessel level at the planned load;
* with that ballast set, the largest heel and trim over the worst case, (T - T0) y_t /
  (disp GM_T), checked against ``max_heel`` / ``max_trim`` (``vessel_heel``,
  ``vessel_trim``);
* with that ballast set, the lowest deck corner's freeboard over the worst case (where the
  vessel gives ``freeboard``, ``beam`` and ``length``), freeboard - T / (rho A_wp) - (beam / 2)
  |T - T0| |y_t| / (disp GM_T) - (length / 2) |T - T0| |x_t| / (disp GM_L): concave in T, so
  least at the rope's lowest or highest tension; checked against ``min_freeboard``
  (``vessel_freeboard``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from liftplan.planner.problem.vessels import (
    VesselWorst,
    limit_checks,
    tip_compliance,
    tip_offsets,
    vessel_worst,
    wind_shift,
    wind_tip_error,
)
from liftplan.planner.search.evaluator import robust


@dataclass(frozen=True)
class VesselPlan:
    """One floating crane of a plan.

    Parameters
    ----------
    crane : str
        The crane's name (its vessel's).
    label : str
        The planned lug (L1..Ln) it takes.
    offset : tuple of 2 float  [m]
        The tip's plan offset from the flotation centre (x_t forward, y_t to starboard).
    compliance : float  [m/t]
        The tip's drop per tonne of hook load.
    load : float  [t]
        The level tension (nominal CG), T0.
    heave : float  [m]
        At T0, + down.
    heel, trim : float  [deg]
        At T0 without ballast (+ starboard down, + bow down).
    tip_drop : float  [m]
        c T0: the extra hoist as the load comes on.
    ballast : tuple of 2 float  [t m]
        The levelling ballast (heeling, trimming) to set before the lift.
    worst_heel, worst_trim : float  [deg]
        The largest |heel| and |trim| over the worst case with that ballast set.
    worst_load : tuple of 2 float  [t]
        The rope's lowest and highest tension over the worst case.
    max_heel, max_trim : float or None  [deg]
        The vessel's limits, when given.
    freeboard : float or None  [m]
        The lowest deck corner's freeboard over the worst case with that ballast set, when the
        vessel gives ``freeboard``, ``beam`` and ``length``.
    min_freeboard : float or None  [m]
        Its least allowed freeboard, when ``freeboard`` is given.
    """

    crane: str
    label: str
    offset: tuple[float, float]
    compliance: float
    load: float
    heave: float
    heel: float
    trim: float
    tip_drop: float
    ballast: tuple[float, float]
    worst_heel: float
    worst_trim: float
    worst_load: tuple[float, float]
    max_heel: float | None = None
    max_trim: float | None = None
    freeboard: float | None = None
    min_freeboard: float | None = None

    def checks(self):
        """``vessel_heel`` and ``vessel_trim`` where the vessel gives its limit, and
        ``vessel_freeboard`` where it gives its freeboard."""
        worst = VesselWorst(self.worst_heel, self.worst_trim, self.freeboard)
        limits = (self.max_heel, self.max_trim, self.min_freeboard)
        return limit_checks("", self.crane, worst, limits, "over the box and hook errors")

    def to_json(self):
        return {
            "lug": self.label,
            "offset": list(self.offset),
            "compliance": self.compliance,
            "load": self.load,
            "heave": self.heave,
            "heel": self.heel,
            "trim": self.trim,
            "tip_drop": self.tip_drop,
            "extra_hoist": self.tip_drop,
            "ballast": {"heel": self.ballast[0], "trim": self.ballast[1]},
            "worst_heel": self.worst_heel,
            "worst_trim": self.worst_trim,
            "worst_load": list(self.worst_load),
            "freeboard": self.freeboard,
        }


def vessel_plans(plan):
    """Every floating crane of a held plan, in label order.

    Parameters
    ----------
    plan : Plan
        Its problem's floating cranes in series at the chosen lugs.

    Returns
    -------
    tuple of VesselPlan
        Empty when every crane stands on land.
    """
    problem, chosen = plan.problem, plan.chosen
    tensions, gain = plan.dense_held
    _, low, high, _, _ = robust(tensions, gain, plan.lugset)
    low, high = low.min(axis=0), high.max(axis=0)
    out = []
    for k, (label, i, j) in enumerate(zip(plan.labels, chosen.indices, chosen.cranes)):
        crane = problem.fleet[j]
        vessel = crane.vessel
        if vessel is None:
            continue
        point = problem.plan_points[i]
        forward, starboard = tip_offsets(vessel, point)
        load = float(chosen.preload[k])
        heel = load * starboard / vessel.heel_stiffness
        trim = load * forward / vessel.trim_stiffness
        extremes = (float(low[k]), float(high[k]))
        worst = vessel_worst(vessel, (forward, starboard), load, extremes)
        out.append(
            VesselPlan(
                crane=crane.name,
                label=label,
                offset=(float(forward), float(starboard)),
                compliance=float(tip_compliance(vessel, point)[0]),
                load=load,
                heave=load / vessel.heave_stiffness,
                heel=math.degrees(heel),
                trim=math.degrees(trim),
                tip_drop=float(tip_compliance(vessel, point)[0]) * load,
                ballast=(0.0 - load * starboard, 0.0 - load * forward),
                worst_heel=worst.heel,
                worst_trim=worst.trim,
                worst_load=extremes,
                max_heel=vessel.max_heel,
                max_trim=vessel.max_trim,
                freeboard=worst.freeboard,
                min_freeboard=vessel.min_freeboard,
            )
        )
    return tuple(out)


def vessel_lines(vessels, infeasible=None):
    """The console's lines for a plan's floating cranes (none without), and how many sets the
    vessels' limits ruled out of the search (``infeasible``: the search's reasons and counts)."""
    if not vessels:
        return []
    ruled = {text: n for text, n in (infeasible or {}).items() if text.startswith("a crane vessel")}
    lines = [
        "",
        *(
            f"ruled out by a vessel's limit: {n} set{'' if n == 1 else 's'}, {text}"
            for text, n in ruled.items()
        ),
        "crane vessels at the level tension (heave + down, heel + starboard down, trim + bow down; tip "
        "drop: the extra hoist as the load comes on; ballast: heeling, trimming moment to set before "
        "the lift, levels the vessel at this load; worst: largest |heel|, |trim| over the box and the "
        "hook errors with that ballast set; freeboard: lowest deck corner over them / its minimum):",
        f"{'crane':<13}{'lug':<5}{'T [t]':>7}{'heave':>7}{'heel':>7}{'trim':>7}{'drop':>7}"
        f"{'ballast [t m]':>18}{'worst [deg]':>14}{'freeboard [m]':>15}",
        f"{'':<25}{'[m]':>7}{'[deg]':>7}{'[deg]':>7}{'[m]':>7}",
    ]
    for v in vessels:
        ballast = f"{round(v.ballast[0]) + 0:+d}, {round(v.ballast[1]) + 0:+d}"
        worst = f"{v.worst_heel:.2f}, {v.worst_trim:.2f}"
        freeboard = "-" if v.freeboard is None else f"{v.freeboard:.2f} / {v.min_freeboard:g}"
        lines.append(
            f"{v.crane[:12]:<13}{v.label:<5}{v.load:7.1f}{v.heave:7.3f}{round(v.heel, 2) + 0.0:+7.2f}"
            f"{round(v.trim, 2) + 0.0:+7.2f}{v.tip_drop:7.3f}{ballast:>18}{worst:>14}{freeboard:>15}"
        )
    return lines


def wind_json(plan):
    """The wind a held plan took, for its JSON (``{}`` without a wind): the body's force and how
    far its couple widened the CG envelope, each boom's force and the tip error it added."""
    problem = plan.problem
    wind = problem.wind
    if wind is None:
        return {}
    booms = {}
    for i, j in zip(plan.chosen.indices, plan.chosen.cranes):
        crane = problem.fleet[j]
        boom = next((b for b in wind.booms if b.crane == crane.name), None)
        if boom is not None:
            error = float(wind_tip_error(problem, crane, problem.plan_points[i])[0])
            booms[crane.name] = {"force": wind.force(boom), "hook_error": error}
    body = wind.force(wind.body) if wind.body is not None else 0.0
    return {
        "wind": {"speed": wind.speed, "body_force": body, "cog_widening": wind_shift(problem), "booms": booms}
    }


def wind_lines(plan):
    """The console's line for a plan's wind (none without)."""
    data = wind_json(plan).get("wind")
    if data is None:
        return []
    booms = ", ".join(
        f"{k} {v['force']:.2f} t (tip +-{v['hook_error']:.3f} m)" for k, v in data["booms"].items()
    )
    return [
        f"wind {data['speed']:g} m/s from any direction: {data['body_force']:.2f} t on the body, its couple "
        f"widening the CG envelope by {data['cog_widening']:.3f} m in plan"
        + (f"; on the booms {booms}, added to their hook tolerances" if booms else "")
    ]
