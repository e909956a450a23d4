"""Lifting a hull off the seabed and through the waterline: the load curve.

Every hook rises by the hoist s (boom raised or rope hauled in: the same for the rope's
stretch). At each s the equilibrium is solved on the clipped-hull model of
:mod:`liftplan.model.water`, started from the previous step's pose (continuation):
grounded while the contact carries load, hanging once the ground reaction would go
negative (lift-off), then through the surface as the buoyancy is lost. A step that finds
no equilibrium is kept in the curve as a failed step with its reason; it never gets
numbers.

Events are located between the steps by bisection on the hoist, each solve started from
the pose on the near side, until the bracket is at most ``EVENT_TOL`` wide:

* ``lift-off``: the ground reaction reaches 0 (the grounded solve no longer holds);
* ``surface``: the hull's highest point first reaches the surface from below;
* ``clear``: its lowest point leaves the water.

The two solved ends of each final bracket join the curve's rows, so a kink (lift-off, say)
is drawn where it is, not smeared over a step.

The maximum crane load is reported with its plateau: the hoist ranges where the largest
rope load is within ``PLATEAU_REL`` of the peak, their ends bisected the same way. Clear
of the water (or hanging submerged) the loads are constant, so the peak has no single
hoist; a point of such a plateau would be an artefact of the step.

With a breakout model (``[ground] breakout``, :mod:`liftplan.model.water.breakout`) two
more events: ``breakout`` (the soil lets go: the ropes carry W + water - B + F_b, the peak)
and ``released`` (the contact ``clear`` m off its bed: F_b gone). With a hoist ``speed``
(m/min) the curve carries time (s, hoist / speed) and the water in compartments with
openings drains by orifice flow (:mod:`liftplan.model.water.draining`), integrated in time
first; each hoist of the curve is then solved with the water its compartments hold then.
Each compartment's drain is an event ``drained``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.statics.floating import (
    check_floating,
    scene_fleet,
    series_scene,
    vessel_states,
    with_vessels,
)
from liftplan.model.water import WaterSetup, hull_heights, settle
from liftplan.model.water.draining import RTOL, Drainage, TankSummary, integrate
from liftplan.model.water.vessels import CoupledWater

# Bracket width [m] at which an event's bisection stops (the event is reported at the
# bracket's middle, to +-half of it). Hooks are set to centimetres; 0.1 mm costs about a
# dozen solves per event at a 0.25 m step.
EVENT_TOL = 1e-4
# The plateau: rope loads within 0.1 % of the peak. Relative, so it reads the same on a
# 50 t block and a 20 000 t wreck; 0.1 % is well below what a crane's load cell or a
# weight estimate resolves, and still only millimetres of hoist where the load is rising
# (about 40 t/m per rope as the sunken block pierces the surface).
PLATEAU_REL = 1e-3

EVENTS = {
    "lift-off": "ground reaction reaches 0",
    "breakout": "the soil lets go: the ropes carry the submerged weight + the breakout force",
    "released": "contact risen clear of its bed: the breakout force is gone",
    "surface": "hull first touches the surface from below",
    "clear": "hull fully clear of the water",
    "drained": "a compartment's water down to the sill of an opening above the water",
}


#: Hoist steps a load curve may take (each an equilibrium solve).
MAX_STEPS = 100_000


@dataclass(frozen=True)
class Event:
    """A change of state on the load curve, located by bisection between steps.

    Parameters
    ----------
    name : str
        One of :data:`EVENTS`.
    hoist : float  [m]
        Middle of the final bracket.
    tolerance : float  [m]
        Half the bracket's width: the event lies within ``hoist +- tolerance``.
        At most ``EVENT_TOL / 2`` unless a solve inside the bracket failed. A ``drained``
        event is located in time by the integrator (to its relative tolerance, reported
        here as ``RTOL`` x the hoist).
    time : float or None  [s]
        hoist / speed, with a hoist speed.
    subject : str or None
        The compartment, for ``drained``.
    """

    name: str
    hoist: float
    tolerance: float
    time: float | None = None
    subject: str | None = None

    @property
    def description(self):
        return EVENTS[self.name] + (f" ({self.subject})" if self.subject else "")

    def to_json(self):
        out = {
            "event": self.name,
            "hoist": self.hoist,
            "tolerance": self.tolerance,
            "description": self.description,
        }
        if self.time is not None:
            out["time"] = self.time
        if self.subject is not None:
            out["subject"] = self.subject
        return out


@dataclass(frozen=True)
class MaxLoad:
    """The largest rope load on the curve and where it holds.

    Parameters
    ----------
    tension : float  [t]
        The peak.
    lug : str
        The rope that carries it.
    plateau : tuple of (float, float)  [m]
        Hoist ranges (from, to) where the largest rope load is within ``tolerance`` of
        the peak; ends bisected between steps to ``EVENT_TOL``. A range may end at the
        curve's last hoist (``to_end``): it goes on beyond.
    tolerance : float  [t]
        ``PLATEAU_REL`` x the peak.
    to_end : bool
        The last range reaches the last hoist computed.
    """

    tension: float
    lug: str
    plateau: tuple[tuple[float, float], ...]
    tolerance: float
    to_end: bool

    def to_json(self):
        return {
            "tension": self.tension,
            "lug": self.lug,
            "plateau": [{"from": a, "to": b} for a, b in self.plateau],
            "tolerance": self.tolerance,
            "tolerance_rule": f"within {100 * PLATEAU_REL:g} % of the peak",
            "to_end": self.to_end,
        }


#: A crane vessel's limits followed over the curve: (check name, VesselState attribute, the
#: Vessel's limit attribute, unit, what the sign means).
VESSEL_LIMITS = (
    ("vessel_heel", "heel", "max_heel", "deg", "+ starboard down"),
    ("vessel_trim", "trim", "max_trim", "deg", "+ bow down"),
    ("vessel_freeboard", "freeboard", "min_freeboard", "m", "the lowest deck corner"),
)


@dataclass(frozen=True)
class VesselLimit:
    """One crane vessel's limit followed over the load curve.

    Parameters
    ----------
    vessel : str
    check : str
        ``vessel_heel``, ``vessel_trim`` (|angle| <= limit) or ``vessel_freeboard``
        (freeboard >= limit), as :func:`liftplan.model.solve_checks.vessel_checks` names them.
    limit : float  [deg or m]
        ``max_heel``, ``max_trim`` or ``min_freeboard``.
    unit : str
    worst : float  [deg or m]
        The largest |heel| or |trim|, or the lowest freeboard, over the curve's hoists.
    worst_signed : float  [deg or m]
        The heel or trim there with its sign (ballast included).
    worst_hoist : float  [m]
    first_broken : float or None  [m]
        The first hoist where the limit is broken: bisected between the last hoist within it
        and the first beyond it to ``EVENT_TOL`` (the middle of the final bracket), or the
        first hoist if it is broken from the start; None when it holds all along.
    tolerance : float or None  [m]
        Half the final bracket's width (0 broken from the start).
    sense : str
        What the sign means.
    """

    vessel: str
    check: str
    limit: float
    unit: str
    worst: float
    worst_signed: float
    worst_hoist: float
    first_broken: float | None
    tolerance: float | None
    sense: str = ""

    @property
    def ok(self):
        return self.first_broken is None

    def as_check(self):
        """The flagged :class:`~liftplan.model.checks.Check` of the whole curve (its worst value)."""
        where = f"worst {self.worst_signed:+.3f} {self.unit} ({self.sense}) at hoist {self.worst_hoist:.4f} m"
        if self.first_broken is not None:
            where += f"; first broken at hoist {self.first_broken:.4f} m +- {1e3 * self.tolerance:.2f} mm"
        make = Check.lower if self.check == "vessel_freeboard" else Check.upper
        check = make(self.check, self.vessel, self.worst, self.limit, self.unit, note=where)
        return replace(check, ok=self.ok and check.ok)

    def to_json(self):
        return {
            "vessel": self.vessel,
            "check": self.check,
            "limit": self.limit,
            "unit": self.unit,
            "worst": self.worst,
            "worst_signed": self.worst_signed,
            "worst_hoist": self.worst_hoist,
            "first_broken_hoist": self.first_broken,
            "first_broken_tolerance": self.tolerance,
            "ok": self.ok,
        }


@dataclass(frozen=True)
class LoadCurve:
    """Crane loads, attitude and water forces against hoist (and time, with a speed).

    Parameters
    ----------
    lugs : tuple of str
    hoist : numpy.ndarray, shape (k,)  [m]
        Hoists that solved: the steps, and the two ends of each event's and plateau
        end's final bracket (so the curve shows each kink where it is).
    tensions : numpy.ndarray, shape (k, n)  [t]
    heel, trim : numpy.ndarray, shape (k,)  [deg]
    buoyancy : numpy.ndarray, shape (k,)  [t]
        Weight of the displaced water (>= 0).
    displaced_volume : numpy.ndarray, shape (k,)  [m3]
    ground_reaction : numpy.ndarray, shape (k,)  [t]
        What the ground pushes up (>= 0); 0 once lifted off (and without a ground contact).
    bottom, top : numpy.ndarray, shape (k,)  [m]
        Lowest and highest point of the hull envelope above the water level.
    state : tuple of str
        Per step, one of :attr:`~liftplan.model.results.Afloat.STATES`.
    failed : tuple of (float, str)
        Hoists [m] with no equilibrium found, and why.
    weight : float  [t]
        The body's weight in air.
    trapped_water : float  [t]
        Water in compartments at the start (all of them full).
    density : float  [t/m3]
    events : tuple of Event
        In hoist order.
    max_load : MaxLoad
    name : str
        The scene's name (the figure's title).
    soil_force : numpy.ndarray, shape (k,) or None  [t]
        The soil's downward pull on the hull: its suction while grounded, the breakout
        force while breaking out (None: the same as zeros).
    water : numpy.ndarray, shape (k,) or None  [t]
        Water in compartments at each hoist (None: ``trapped_water`` throughout).
    compartments : dict of str to numpy.ndarray, optional  [t]
        Water in each compartment with openings.
    speed : float or None  [m/min]
    time : numpy.ndarray, shape (k,) or None  [s]
        hoist / speed.
    breakout : BreakoutForce or None
    drainage : tuple of TankSummary
    drainage_note : str
        How the compartments with openings were taken (said on the console and in JSON).
    equilibria : tuple of Equilibrium
        The solved equilibrium at each hoist of ``hoist`` (pose, tensions, water): what the
        3D view draws at each state. Empty for a curve made without them.
    vessels : dict of str to dict of str to numpy.ndarray, optional
        Floating cranes: per crane vessel, its ``heave`` [m], ``heel``, ``trim`` [deg],
        ``tip_drop`` [m] and, where it gives one, ``freeboard`` [m] (the lowest deck
        corner's) at each hoist (:class:`~liftplan.model.results.VesselState`).
    vessel_limits : tuple of VesselLimit
        Each vessel's ``max_heel``, ``max_trim`` and ``min_freeboard`` (where it gives them)
        over the curve, with the first hoist where each is broken; :attr:`checks` flags them.
    """

    lugs: tuple[str, ...]
    hoist: np.ndarray
    tensions: np.ndarray
    heel: np.ndarray
    trim: np.ndarray
    buoyancy: np.ndarray
    displaced_volume: np.ndarray
    ground_reaction: np.ndarray
    bottom: np.ndarray
    top: np.ndarray
    state: tuple[str, ...]
    failed: tuple[tuple[float, str], ...]
    weight: float
    trapped_water: float
    density: float
    events: tuple[Event, ...]
    max_load: MaxLoad
    name: str = ""
    soil_force: np.ndarray | None = None
    water: np.ndarray | None = None
    compartments: dict = field(default_factory=dict)
    speed: float | None = None
    time: np.ndarray | None = None
    breakout: object | None = None
    drainage: tuple = ()
    drainage_note: str = ""
    equilibria: tuple = field(default=(), repr=False, compare=False)
    vessels: dict = field(default_factory=dict)
    vessel_limits: tuple = ()

    @property
    def checks(self):
        """The curve's checks (list of Check): each vessel limit, flagged when broken at any hoist."""
        return [limit.as_check() for limit in self.vessel_limits]

    @property
    def crane_load(self):
        """Sum of the rope tensions per step  [t] (= W + water - B - F_R + soil)."""
        return self.tensions.sum(axis=1)

    @property
    def water_carried(self):
        """Water in compartments per step  [t]."""
        return self.water if self.water is not None else np.full(len(self.hoist), self.trapped_water)

    @property
    def soil(self):
        """The soil's pull per step  [t]."""
        return self.soil_force if self.soil_force is not None else np.zeros(len(self.hoist))

    @property
    def peak_crane_load(self):
        """(load [t], hoist [m]) of the largest sum of rope tensions on the curve: with a
        breakout model, the breakout peak."""
        k = int(np.argmax(self.crane_load))
        return float(self.crane_load[k]), float(self.hoist[k])

    def event(self, name):
        """The first :class:`Event` called ``name``, or None if it did not happen in the range."""
        return next((e for e in self.events if e.name == name), None)

    @property
    def lift_off(self):
        """Hoist [m] at which the ground reaction reaches 0 (None if the hull never rested
        on the ground, or did not leave it within the range)."""
        event = self.event("lift-off")
        return event.hoist if event is not None else None

    def rows(self):
        """One dict per solved hoist (for CSV / JSON)."""
        out = []
        for k, h in enumerate(self.hoist):
            row = {"hoist": float(h)}
            if self.time is not None:
                row["time"] = float(self.time[k])
            row.update({f"T_{name}": float(t) for name, t in zip(self.lugs, self.tensions[k])})
            row.update(
                crane_load=float(self.crane_load[k]),
                heel=float(self.heel[k]),
                trim=float(self.trim[k]),
                buoyancy=float(self.buoyancy[k]),
                displaced_volume=float(self.displaced_volume[k]),
                ground_reaction=float(self.ground_reaction[k]),
                bottom=float(self.bottom[k]),
                top=float(self.top[k]),
                state=self.state[k],
            )
            if self.soil_force is not None:
                row["soil_force"] = float(self.soil_force[k])
            if self.water is not None:
                row["water_in_compartments"] = float(self.water[k])
            for name, series in self.vessels.items():
                row.update({f"vessel_{key}_{name}": float(v[k]) for key, v in series.items()})
                if any(limit.vessel == name for limit in self.vessel_limits):
                    row[f"vessel_within_limits_{name}"] = self.within_limits(name, k)
            out.append(row)
        return out

    def within_limits(self, vessel, k):
        """Whether crane vessel ``vessel`` is within its limits at hoist step ``k`` (bool)."""
        series = self.vessels[vessel]
        for limit in self.vessel_limits:
            if limit.vessel == vessel:
                key = next(attr for name, attr, *_ in VESSEL_LIMITS if name == limit.check)
                value = float(series[key][k])
                if not (
                    value >= limit.limit if limit.check == "vessel_freeboard" else abs(value) <= limit.limit
                ):
                    return False
        return True

    def to_json(self):
        load, at = self.peak_crane_load
        out = {
            "name": self.name,
            "lugs": list(self.lugs),
            "weight": self.weight,
            "trapped_water": self.trapped_water,
            "water_density": self.density,
            "max_load": self.max_load.to_json(),
            "lift_off": self.lift_off,
            "events": [e.to_json() for e in self.events],
            "curve": self.rows(),
            "failed": [{"hoist": h, "reason": r} for h, r in self.failed],
        }
        if self.vessel_limits:
            out["vessel_limits"] = [limit.to_json() for limit in self.vessel_limits]
            out["checks"] = [check.to_json() for check in self.checks]
        if self.breakout is not None or self.speed is not None or self.drainage:
            out["max_crane_load"] = {"load": load, "hoist": at, "time": self.hoist_time(at)}
            out["breakout"] = self.breakout.to_json() if self.breakout is not None else None
            out["speed"] = self.speed
            out["drainage"] = {
                "note": self.drainage_note,
                "compartments": [t.to_json() for t in self.drainage],
            }
        return out

    def hoist_time(self, hoist):
        """The time [s] at ``hoist`` [m] with a speed, else None."""
        return None if self.speed is None else float(hoist) * 60.0 / self.speed


def default_stop(scene):
    """A hoist that takes the whole hull 1 m clear of the water, from the scene's pose  [m]."""
    rot = rotation_matrix(scene.attitude.heel, scene.attitude.trim, scene.attitude.yaw)
    heights = (rot @ scene.hull.vertices.T)[2] + scene.attitude.lift_height
    return float(scene.water.level - heights.min() + 1.0)


@dataclass(frozen=True)
class _Point:
    """One solved hoist: the equilibrium, the pose to start the next solve from, the hull's
    lowest and highest point above the water, what the soil did and the water held."""

    hoist: float
    eq: object
    start: object
    bottom: float
    top: float
    soil: float
    phase: str
    reaction: float  # what the ground pushes up less the soil's pull [t] (0 off the ground)
    water: float
    tanks: tuple

    @property
    def peak(self):
        return max(self.eq.tensions.values())


class _Lift:
    """Solves at any hoist from a given pose (one built model)."""

    def __init__(self, scene, speed=None, coupled=None):

        self.scene = scene
        self.coupled = coupled  # a CoupledWater: crane vessels under several cranes
        self.setup = WaterSetup(scene) if coupled is None else coupled.setup
        self.drainage = Drainage(self.setup, speed) if scene.openings else None
        self.history = None  # the timed tanks' volumes in time, once integrated
        self.speed = speed
        self.brackets = []  # the solved ends of every final bracket, added to the curve

    def timed(self, hoist):
        if self.history is None:
            return self.drainage.initial()
        return self.history.timed(hoist * 60.0 / self.speed)

    def at(self, hoist, start=None):
        """The solved :class:`_Point` at ``hoist`` [m]; raises EquilibriumNotFound."""
        scene, drainage = self.scene, self.drainage
        timed = None if drainage is None else self.timed(hoist)

        def solve():
            if drainage is None:
                return settle(self.setup, hoist, start)
            return drainage.settle(hoist, timed, start)

        state = solve() if self.coupled is None else self.coupled.hold(solve, hoist)
        eq, pose = state.eq, state.start
        bottom, top = hull_heights(scene.hull, pose.rotation, pose.zo)
        water = state.loads.trapped
        reaction = 0.0
        if eq.afloat.state == "grounded":
            reaction = scene.body.weight + water - eq.afloat.buoyancy - sum(eq.tensions.values())
        tanks = ()
        if drainage is not None:
            tanks = tuple(
                float(v) * drainage.density for v in drainage.volumes(pose.rotation, pose.zo, timed)
            )
        return _Point(float(hoist), eq, pose, bottom, top, state.soil, state.phase, reaction, water, tanks)

    def bisect(self, lo, hi, test):
        """Narrow [lo, hi] (``test`` false at ``lo``, true at ``hi``) to ``EVENT_TOL``.

        Returns (middle, half-width) [m] of the last bracket: a solve that fails inside it
        stops the bisection there, and the wider bracket is what is reported."""
        while hi.hoist - lo.hoist > EVENT_TOL:
            mid = 0.5 * (lo.hoist + hi.hoist)
            try:
                point = self.at(mid, lo.start)
            except EquilibriumNotFound:
                break
            if test(point):
                hi = point
            else:
                lo = point
        self.brackets += [lo, hi]
        return 0.5 * (lo.hoist + hi.hoist), 0.5 * (hi.hoist - lo.hoist)


def _adjacent(points, failed):
    """Pairs of neighbouring solved points (k, k + 1) with no failed hoist between them."""
    bad = [h for h, _ in failed]
    return [
        k for k in range(len(points) - 1) if not any(points[k].hoist < h < points[k + 1].hoist for h in bad)
    ]


def _events(lift, points, failed):
    tests = {
        "lift-off": lambda p: not (p.eq.afloat.state == "grounded" and p.reaction > 0.0),
        "surface": lambda p: p.top >= 0.0,
        "clear": lambda p: p.bottom >= 0.0,
    }
    if lift.setup.breakout is not None and lift.setup.breakout.force > 0.0:
        tests["breakout"] = lambda p: p.phase != "grounded"
        tests["released"] = lambda p: p.phase == "free"
    pairs = _adjacent(points, failed)
    out = []
    for name, test in tests.items():
        if test(points[0]):  # already past it at the first hoist: it is not in the range
            continue
        first = next((k for k in range(len(points) - 1) if test(points[k + 1])), None)
        if first is None:
            continue
        if first in pairs:
            hoist, tol = lift.bisect(points[first], points[first + 1], test)
        else:  # a failed step lies between: the bracket is the two solved neighbours
            a, b = points[first].hoist, points[first + 1].hoist
            hoist, tol = 0.5 * (a + b), 0.5 * (b - a)
        out.append(Event(name, hoist, tol))
    if lift.history is not None:
        for tank, t in lift.history.drain_times.items():
            hoist = t * lift.speed / 60.0
            out.append(Event("drained", hoist, RTOL * hoist, subject=tank))
    if lift.speed is not None:
        out = [replace(e, time=e.hoist * 60.0 / lift.speed) for e in out]
    return tuple(sorted(out, key=lambda e: e.hoist))


def _max_load(lift, points, failed, lugs, tensions):
    k, i = np.unravel_index(int(np.argmax(tensions)), tensions.shape)
    peak = float(tensions[k, i])
    tolerance = PLATEAU_REL * abs(peak)
    threshold = peak - tolerance
    inside = tensions.max(axis=1) >= threshold
    pairs = set(_adjacent(points, failed))
    ranges, j, last = [], 0, len(points) - 1
    while j <= last:
        if not inside[j]:
            j += 1
            continue
        end = j
        while end < last and inside[end + 1] and end in pairs:
            end += 1
        start_at = points[j].hoist
        if j > 0 and (j - 1) in pairs:
            start_at = lift.bisect(points[j - 1], points[j], lambda p: p.peak >= threshold)[0]
        end_at = points[end].hoist
        if end < last and end in pairs:
            end_at = lift.bisect(points[end], points[end + 1], lambda p: p.peak < threshold)[0]
        ranges.append((float(start_at), float(end_at)))
        j = end + 1
    to_end = bool(inside[last])
    return MaxLoad(peak, lugs[i], tuple(ranges), tolerance, to_end)


def _with_brackets(lift, points):
    """The solved points and every bracket end solved so far, by hoist (one per hoist)."""
    by_hoist = {p.hoist: p for p in lift.brackets}
    by_hoist.update({p.hoist: p for p in points})
    return [by_hoist[h] for h in sorted(by_hoist)]


def _check_stop(scene, stop):
    """A last hoist (``--to``) in (0, the shortest rope]: hauled in by its whole length, a rope's
    hook is at its boom tip, and no crane hoists further (``--to 1e308`` ended in an
    OverflowError)."""
    crane = min(scene.cranes, key=lambda c: c.rope_length or np.inf)
    reach = crane.rope_length
    if reach is None:  # the model refuses the scene itself, naming the crane
        return
    if not (np.isfinite(stop) and 0.0 < stop <= reach):
        raise InvalidScene(
            f"lift: --to {stop:g} m: expected a hoist in (0, {reach:g}] m (hoisted {reach:g} m, "
            f"crane {crane.label}'s hook reaches its boom tip: its rope_length)"
        )


def _bar(progress, total, desc, unit):
    """A tqdm bar on stderr from the first second (None without ``progress``); its
    remaining time is tqdm's, from the rate so far."""
    if not progress:
        return None
    import sys

    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, leave=False, dynamic_ncols=True)


def load_curve(scene, stop=None, step=0.25, speed=None, progress=False):
    """The load curve of a lift from the scene's pose.

    Parameters
    ----------
    scene : Scene
        Hull, water, vertical ropes (boom heights, rope lengths, EA at hoist 0), and
        usually a ground contact.
    stop : float, optional  [m]
        Last hoist; default :func:`default_stop`.
    step : float  [m]
    speed : float, optional  [m/min]
        Hoist speed: the curve carries time, and compartments with openings drain in it.
        Without it they are carried full (never drain; the conservative bound), except
        those with an opening of infinite area (drain at once).
    progress : bool
        Progress bars on stderr: the draining's lift time integrated (its work grows as
        the speed falls: 17 s at 2 m/min, over 250 s at 0.02 m/min), then the hoist steps.

    Returns
    -------
    LoadCurve
    """
    if scene.hull is None or not scene.n:
        raise InvalidScene("lift: expected a scene with [hull], [water] and three or more cranes")
    for key in ("tide", "wind"):
        if getattr(scene, key) is not None:
            raise InvalidScene(
                f"lift: [{key}] is not followed through a load curve; expected liftplan solve for it "
                f"(at each hoist: boom_height raised by the hoist), or the scene without [{key}]"
            )
    floating = scene  # with its crane vessels, for their states at each hoist
    fleet = coupled = None
    if scene.vessels:  # each rope in series with its vessel, as solve's hydrostatic
        check_floating(scene, "hydrostatic")
        fleet = scene_fleet(scene)
        if np.all(fleet.membership.sum(axis=1) == 1.0):  # one crane each: the series stiffness
            scene = series_scene(scene, fleet)
        else:  # a vessel under several cranes: the ropes' coupled stiffness
            coupled = CoupledWater(scene, fleet)
            scene = coupled.scene
    if stop is not None:
        _check_stop(scene, stop)
    stop = default_stop(scene) if stop is None else float(stop)
    if not (step > 0 and np.isfinite(step)) or not stop > 0:
        raise InvalidScene(f"lift: hoist to {stop:g} m in steps of {step:g} m; expected both > 0")
    if speed is not None and not (np.isfinite(speed) and speed > 0):
        raise InvalidScene(f"lift: speed = {speed!r} m/min; expected a finite number > 0")
    steps = stop / step  # may overflow to inf (--to 1e308): refused below, never int(inf)
    if not steps <= MAX_STEPS:
        raise InvalidScene(
            f"lift: hoist to {stop:g} m in steps of {step:g} m is {steps:.3g} steps; expected at most "
            f"{MAX_STEPS} (--step at least {stop / MAX_STEPS:.3g} m, or a lower --to)"
        )
    count = int(np.floor(steps + 1e-9)) + 1
    lift = _Lift(scene, speed, coupled)
    hoists = np.linspace(0.0, step * (count - 1), count)
    points, failed = [], []
    note = ""
    drainage = lift.drainage
    if drainage is not None:
        if speed is None:
            note = (
                "no hoist speed: compartments with finite openings carried full (never drain, "
                "the conservative bound)"
            )
        elif drainage.timed:
            seconds = hoists[-1] * 60.0 / speed
            if seconds > 0:
                bar = _bar(progress, seconds, "draining", "s of lift")
                try:
                    lift.history = integrate(drainage, seconds, step * 60.0 / speed, bar)
                finally:
                    if bar is not None:
                        bar.close()
            note = f"drained by orifice flow at {speed:g} m/min"
            if lift.history is not None and lift.history.failure:
                note += f"; {lift.history.failure}"
        if any(t.instant for t in drainage.tanks):
            note += ("; " if note else "") + "openings of infinite area drain at once"
    end = lift.history.end * speed / 60.0 if lift.history is not None else np.inf
    start = None
    bar = _bar(progress, len(hoists), "hoist steps", "step")
    try:
        for hoist in hoists:
            if bar is not None:
                bar.update(1)
            if hoist > end * (1 + 1e-12):
                failed.append(
                    (float(hoist), f"no water state beyond hoist {end:.4g} m ({lift.history.failure})")
                )
                continue
            try:
                point = lift.at(hoist, start)
            except EquilibriumNotFound as err:
                failed.append((float(hoist), str(err)))
                continue
            points.append(point)
            start = point.start
    finally:
        if bar is not None:
            bar.close()
    if not points:
        raise EquilibriumNotFound(f"lift: no hoist step solved; first failure: {failed[0][1]}")
    events = _events(lift, points, failed)
    # the bracket ends are equilibria too: on the curve, they show each kink where it is, and
    # the largest load is looked for among them (a breakout peak falls between two steps)
    points = _with_brackets(lift, points)
    tensions = np.array([list(p.eq.tensions.values()) for p in points])
    max_load = _max_load(lift, points, failed, scene.lug_names, tensions)
    breaks = {}
    if fleet is not None:
        breaks = _breaks(lift, _with_brackets(lift, points), failed, floating, fleet)
    points = _with_brackets(lift, points)  # and the plateau's and limits' own bracket ends
    if fleet is not None:
        points = [
            replace(p, eq=with_vessels(p.eq, vessel_states(floating, fleet, list(p.eq.tensions.values()))))
            for p in points
        ]
    afloat = [p.eq.afloat for p in points]
    tensions = np.array([list(p.eq.tensions.values()) for p in points])
    hoist = np.array([p.hoist for p in points])
    breakout = lift.setup.breakout
    summaries, compartments = (), {}
    if drainage is not None:
        compartments = {t.name: np.array([p.tanks[k] for p in points]) for k, t in enumerate(drainage.tanks)}
        summaries = _summaries(lift, compartments, hoist)
    return LoadCurve(
        lugs=scene.lug_names,
        hoist=hoist,
        tensions=tensions,
        heel=np.array([p.eq.pose.heel for p in points]),
        trim=np.array([p.eq.pose.trim for p in points]),
        buoyancy=np.array([a.buoyancy for a in afloat]),
        displaced_volume=np.array([a.displaced_volume for a in afloat]),
        ground_reaction=np.array([a.ground_reaction or 0.0 for a in afloat]),
        bottom=np.array([p.bottom for p in points]),
        top=np.array([p.top for p in points]),
        state=tuple(a.state for a in afloat),
        failed=tuple(failed),
        weight=scene.body.weight,
        trapped_water=lift.setup.trapped,
        density=scene.water.density,
        events=events,
        max_load=max_load,
        name=scene.name or "",
        soil_force=np.array([p.soil for p in points]) if breakout is not None else None,
        water=np.array([p.water for p in points]) if drainage is not None else None,
        compartments=compartments,
        speed=speed,
        time=hoist * 60.0 / speed if speed is not None else None,
        breakout=breakout,
        drainage=summaries,
        drainage_note=note,
        equilibria=tuple(p.eq for p in points),
        vessels=_vessel_series(points),
        vessel_limits=_vessel_limits(points, floating, breaks) if fleet is not None else (),
    )


def _limits(scene):
    """(vessel, check, attribute, limit, unit, sense, lower) of every limit the crane vessels give."""
    out = []
    for name, (vessel, _) in scene.vessels.items():
        for check, attr, key, unit, sense in VESSEL_LIMITS:
            limit = getattr(vessel, key)
            if limit is not None and (check != "vessel_freeboard" or vessel.freeboard is not None):
                out.append((name, check, attr, limit, unit, sense, check == "vessel_freeboard"))
    return out


def _measure(state, attr, lower):
    """The value a limit is checked on: the freeboard, or |heel| or |trim|."""
    value = getattr(state, attr)
    return value if lower else abs(value)


def _breaks(lift, points, failed, scene, fleet):
    """The first hoist (middle, half-width) [m] where each vessel limit is broken, keyed by
    (vessel, check); bisected between steps as the events are (the brackets join the curve)."""
    pairs = set(_adjacent(points, failed))
    out = {}
    for name, check, attr, limit, _, _, lower in _limits(scene):

        def broken(point, name=name, attr=attr, limit=limit, lower=lower):
            state = vessel_states(scene, fleet, list(point.eq.tensions.values()))[name]
            value = _measure(state, attr, lower)
            return not (value >= limit if lower else value <= limit)

        first = next((j for j, p in enumerate(points) if broken(p)), None)
        if first == 0:
            out[name, check] = (points[0].hoist, 0.0)
        elif first is not None and first - 1 in pairs:
            out[name, check] = lift.bisect(points[first - 1], points[first], broken)
        elif first is not None:  # a failed step lies between: the two solved neighbours
            a, b = points[first - 1].hoist, points[first].hoist
            out[name, check] = (0.5 * (a + b), 0.5 * (b - a))
    return out


def _vessel_limits(points, scene, breaks):
    """Each vessel limit over the curve's points (with their vessels' states): its worst value
    and where, and the first hoist where it is broken (``breaks``)."""
    out = []
    for name, check, attr, limit, unit, sense, lower in _limits(scene):
        values = np.array([_measure(p.eq.vessels[name], attr, lower) for p in points])
        k = int(np.argmin(values) if lower else np.argmax(values))
        hoist, tolerance = breaks.get((name, check), (None, None))
        signed = float(getattr(points[k].eq.vessels[name], attr))
        out.append(
            VesselLimit(
                name, check, limit, unit, float(values[k]), signed, points[k].hoist, hoist, tolerance, sense
            )
        )
    return tuple(out)


def _vessel_series(points):
    """Each crane vessel's heave, heel, trim, tip drop and (where it gives one) freeboard per
    point (``{}`` without vessels)."""
    first = points[0].eq.vessels or {}
    out = {}
    for name, state in first.items():
        keys = ("heave", "heel", "trim", "tip_drop") + (() if state.freeboard is None else ("freeboard",))
        out[name] = {key: np.array([getattr(p.eq.vessels[name], key) for p in points]) for key in keys}
    return out


def _summaries(lift, compartments, hoist):

    history = lift.history
    out = []
    for tank in lift.drainage.tanks:
        error, drain = 0.0, None
        if history is not None and tank.name in history.tanks:
            error = float(history.mass_error(history.end)[history.tanks.index(tank.name)])
            drain = history.drain_times.get(tank.name)
        water = compartments[tank.name]
        out.append(TankSummary(tank.name, float(water[0]), float(water[-1]), drain, error))
    return tuple(out)
