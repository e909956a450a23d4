"""Water draining from a hull's compartments as it rises: orifice flow in time.

A compartment that holds water (``contents = "water"``) may have openings
(:class:`~liftplan.model.scene.objects.Opening`: area A, body point, discharge coefficient C_d).
The compartment is taken as vented (air enters above its water at atmospheric pressure),
so its water has a free surface at the inside level h_in, a horizontal plane cutting the
compartment's box at the hull's attitude; the water is the part of the box below it. Each
opening j at world height z_j passes the volume flow (out of the compartment)

    Q_j = C_d A sign(d) sqrt(2 g |d|),   d = max(h_in, z_j) - max(h_out, z_j)

with h_out the outside water level: Torricelli's free discharge (d = h_in - z_j) while the
opening is above the outside water, a submerged orifice (d = h_in - h_out, either way)
while it is below it. A full compartment takes no more water in; an empty one gives none.

* Area 0: the water never drains (a trapped compartment, today's ``contents = "water"``).
* Area ``inf``: it drains at once, h_in = max(h_out, lowest sill): the compartment's water
  and its own displacement cancel below the outside level (free-flooding), and water below
  the sill stays.
* Otherwise the volumes V_k(t) follow dV_k/dt = -sum_j Q_j at the hoist v t, the hull's
  pose found at every instant from the equilibrium with the water it holds then
  (quasi-static: the hoist is slow against the hull's own motions). The integration is
  scipy's RK45 (``solve_ivp``) at relative tolerance :data:`RTOL`, never stepping over a
  hoist step; the water drained is integrated alongside, so V + drained = V_0 checks the
  bookkeeping.

A compartment's *drain time* is when its water has fallen to the sill of an opening above
the outside water. Near the sill the head falls as (t_drain - t)^2 (Torricelli), which an
integrator approaches only slowly, so the drain is located where the head is
:data:`SILL_HEAD` and the last sliver's time is added in closed form, the free surface's
area taken as constant over it: dt = (A_s / sum C_d A) sqrt(2 h / g).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import EquilibriumNotFound
from liftplan.model.water.equilibrium import BodyLoads, settle
from liftplan.model.water.hydrostatics import MeshHydrostatics

G = 9.80665  # m/s2
RTOL = 1e-10  # the integrator's relative tolerance on the volumes
SILL_HEAD = 1e-6  # m: the head at which a drain is located (the rest in closed form)
# The free surface and the pose are solved together by fixed-point iteration: the water's
# centre moves with the attitude. Stop when the loads change by less than these (relative
# to the weight and to the hull length), or fail after FIXED_POINT_MAX rounds.
FIXED_POINT_TOL = 1e-12
FIXED_POINT_MAX = 30


class Tank:
    """A compartment with openings: its water at a pose, and the flow through them.

    Parameters
    ----------
    compartment : liftplan.model.scene.hull.Compartment
    openings : sequence of Opening
        Its openings.
    """

    def __init__(self, compartment, openings):
        self.name = compartment.name
        self.full = float(compartment.volume)
        self.centroid = np.asarray(compartment.centroid, dtype=float)
        self.vertices = np.unique(compartment.triangles.reshape(-1, 3), axis=0)
        self.hydro = MeshHydrostatics(compartment.triangles)
        self.points = np.array([o.at for o in openings], dtype=float).reshape(-1, 3)
        self.coefficient = np.array([o.discharge * o.area for o in openings], dtype=float)
        self.instant = bool(np.any(np.isinf(self.coefficient)))
        self.never = not self.instant and not np.any(self.coefficient > 0.0)

    def _below(self, rot, zo, level):
        """Volume [m3] and body-frame centre [m] of the box below the world plane ``level``
        (height over the outside water)."""
        hs = self.hydro.at(rot, zo - level)
        if hs.volume <= 0.0:
            return 0.0, self.centroid, hs
        world = np.asarray(hs.centre) + [0.0, 0.0, level - zo]  # from the body origin
        return hs.volume, np.asarray(rot).T @ world, hs

    def heights(self, rot, zo):
        """Lowest and highest point of the box above the outside water  [m]."""
        z = (np.asarray(rot) @ self.vertices.T)[2] + zo
        return float(z.min()), float(z.max())

    def level(self, rot, zo, volume):
        """The inside level over the outside water  [m] that holds ``volume`` [m3]."""
        from scipy.optimize import brentq

        low, high = self.heights(rot, zo)
        if volume <= 0.0:
            return low
        if volume >= self.full:
            return high

        def excess(h):
            return self._below(rot, zo, h)[0] - volume

        if excess(high) <= 0.0:  # within round-off of full
            return high
        if excess(low) >= 0.0:
            return low
        return brentq(excess, low, high, xtol=1e-13 * max(1.0, high - low), rtol=4 * np.finfo(float).eps)

    def water(self, rot, zo, volume):
        """Body-frame centre [m] of ``volume`` [m3] of water in the tank at a pose."""
        if volume >= self.full or volume <= 0.0:
            return self.centroid
        return self._below(rot, zo, self.level(rot, zo, volume))[1]

    def instant_volume(self, rot, zo):
        """The water [m3] an instantly draining tank holds at a pose: up to the outside
        level or its lowest opening's sill, whichever is higher."""
        sills = (np.asarray(rot) @ self.points[np.isinf(self.coefficient)].T)[2] + zo
        return min(self.full, self._below(rot, zo, max(0.0, float(sills.min())))[0])

    def flow(self, rot, zo, volume):
        """Volume flow out of the tank  [m3/s] (< 0: in), and the head over the lowest
        sill above the outside water [m] (None when every opening is under it)."""
        if self.never:
            return 0.0, None
        inside = self.level(rot, zo, volume)
        z = (np.asarray(rot) @ self.points.T)[2] + zo
        head = np.maximum(inside, z) - np.maximum(0.0, z)
        q = float(np.sum(self.coefficient * np.sign(head) * np.sqrt(2.0 * G * np.abs(head))))
        if (q < 0.0 and volume >= self.full) or (q > 0.0 and volume <= 0.0):
            q = 0.0
        dry = z >= 0.0
        return q, (float(inside - np.min(z[dry])) if np.any(dry) else None)

    def surface_area(self, rot, zo, volume):
        """Area of the water's free surface in the tank  [m2]."""
        return self._below(rot, zo, self.level(rot, zo, volume))[2].waterplane_area


@dataclass(frozen=True)
class TankSummary:
    """What one compartment's water did over a lift.

    Parameters
    ----------
    name : str
    initial, final : float  [t]
        Water in it at the first and last hoist.
    drain_time : float or None  [s]
        When its water fell to the sill of an opening above the outside water (None: it
        did not within the lift).
    mass_error : float  [-]
        |V + drained - V_0| / V_0 at the end (0 when nothing was integrated).
    """

    name: str
    initial: float
    final: float
    drain_time: float | None
    mass_error: float

    def to_json(self):
        return {
            "compartment": self.name,
            "initial": self.initial,
            "final": self.final,
            "drain_time": self.drain_time,
            "mass_error": self.mass_error,
        }


class Drainage:
    """The water in a scene's compartments, and its equilibrium with the hull.

    Parameters
    ----------
    setup : WaterSetup
    speed : float or None  [m/min]
        Hoist speed; None: tanks with finite openings are carried full (never drain: the
        conservative bound), instantly draining ones still follow the pose.
    """

    def __init__(self, setup, speed=None):
        scene = setup.scene
        self.setup, self.speed = setup, speed
        self.density = scene.water.density
        by_tank = {}
        for opening in scene.openings:
            by_tank.setdefault(opening.compartment, []).append(opening)
        comps = {c.name: c for c in scene.hull.compartments}
        self.tanks = [Tank(comps[name], openings) for name, openings in by_tank.items()]
        # water compartments without openings: full for ever
        fixed = [c for c in scene.hull.compartments if c.contents == "water" and c.name not in by_tank]
        self.fixed = self.density * sum(c.volume for c in fixed)
        self.fixed_moment = self.density * sum(
            (c.volume * np.asarray(c.centroid) for c in fixed), np.zeros(3)
        )
        self.timed = [k for k, t in enumerate(self.tanks) if not t.instant and speed is not None]
        self.size = scene.hull.size

    @property
    def active(self):
        """True when some water can change (a tank that is not simply held full)."""
        return any(t.instant for t in self.tanks) or any(not self.tanks[k].never for k in self.timed)

    def initial(self):
        """Volumes [m3] of the timed tanks at the start: full."""
        return np.array([self.tanks[k].full for k in self.timed])

    def volumes(self, rot, zo, timed):
        """Every tank's water [m3] at a pose, with the timed tanks' volumes ``timed``
        (an integrator's step may overshoot an empty or full tank by its tolerance: the
        water carried is held within [0, full])."""
        out = np.array([t.full for t in self.tanks])
        for k, tank in enumerate(self.tanks):
            if tank.instant:
                out[k] = tank.instant_volume(rot, zo)
        out[self.timed] = timed
        return np.clip(out, 0.0, [t.full for t in self.tanks])

    def loads(self, rot, zo, timed):
        """:class:`BodyLoads` at a pose with the timed tanks' volumes ``timed`` [m3]."""
        volumes = self.volumes(rot, zo, timed)
        weight, moment = self.fixed, self.fixed_moment.copy()
        for tank, volume in zip(self.tanks, volumes):
            weight += self.density * volume
            moment = moment + self.density * volume * tank.water(rot, zo, volume)
        centre = tuple(float(v) for v in moment / weight) if weight > 0.0 else None
        return BodyLoads(float(weight), centre)

    def settle(self, hoist, timed, start=None):
        """The equilibrium at ``hoist`` [m] with the timed tanks holding ``timed`` [m3]:
        the pose and the water's free surfaces found together.

        Returns
        -------
        Settled

        Raises
        ------
        EquilibriumNotFound
            No equilibrium, or the free surfaces and the pose did not settle together.
        """
        setup = self.setup
        pose = start or setup.start
        loads = self.loads(pose.rotation, pose.zo, timed)
        weight = setup.scene.body.weight
        for _ in range(FIXED_POINT_MAX):
            state = settle(setup, hoist, start, loads)
            pose = state.start
            again = self.loads(pose.rotation, pose.zo, timed)
            shift = 0.0
            if again.trapped_centre is not None and loads.trapped_centre is not None:
                shift = float(np.max(np.abs(np.subtract(again.trapped_centre, loads.trapped_centre))))
            if (
                abs(again.trapped - loads.trapped) <= FIXED_POINT_TOL * weight
                and shift * again.trapped <= FIXED_POINT_TOL * weight * self.size
            ):
                return state
            loads, start = again, pose
        raise EquilibriumNotFound(
            f"at hoist {hoist:.4g} m the water's free surfaces and the hull's pose did not settle "
            f"together in {FIXED_POINT_MAX} rounds (free-surface effect too large for this pose)"
        )


@dataclass(frozen=True)
class DrainHistory:
    """The timed tanks' volumes over the lift (scipy's dense solution).

    Parameters
    ----------
    end : float  [s]
        The last time integrated (short of the lift's end if an equilibrium failed).
    failure : str or None
        Why the integration stopped early.
    drain_times : dict of str to float  [s]
    """

    solution: object
    tanks: tuple
    end: float
    failure: str | None
    drain_times: dict
    initial: np.ndarray

    def timed(self, time):
        """Volumes [m3] of the timed tanks at ``time`` [s]."""
        return np.asarray(self.solution(time))[: len(self.tanks)]

    def drained(self, time):
        """Water that has left each timed tank by ``time``  [m3]."""
        return np.asarray(self.solution(time))[len(self.tanks) :]

    def mass_error(self, time):
        """|V + drained - V_0| / V_0 of each timed tank at ``time``  [-]."""
        return np.abs(self.timed(time) + self.drained(time) - self.initial) / self.initial


def integrate(drainage, duration, max_step, bar=None):
    """Integrate the timed tanks' volumes over ``duration`` [s] at the drainage's speed.

    Parameters
    ----------
    drainage : Drainage
    duration : float  [s]
    max_step : float  [s]
        The integrator never steps further (a hoist step's time).
    bar : tqdm, optional
        A progress bar whose total is ``duration``: moved on to each time the integrator
        reaches (its work per second of lift grows as the hoist speed falls).

    Returns
    -------
    DrainHistory
    """
    from scipy.integrate import solve_ivp

    speed = drainage.speed / 60.0  # m/s
    tanks = [drainage.tanks[k] for k in drainage.timed]
    count = len(tanks)
    poses = {}  # time [s] -> a solved pose: each solve starts from the nearest in time
    cache = {}

    def state(t, y):
        key = (float(t), tuple(np.asarray(y, dtype=float)))
        if key not in cache:
            near = min(poses, key=lambda s: abs(s - t)) if poses else None
            settled = drainage.settle(speed * t, np.asarray(y[:count]), poses.get(near))
            poses[float(t)] = settled.start
            cache.clear()  # only the latest matters; the integrator moves on
            cache[key] = settled
        return cache[key]

    def rhs(t, y):
        if bar is not None and t > bar.n:
            bar.update(float(t) - bar.n)
        pose = state(t, y).start
        flows = np.array([tank.flow(pose.rotation, pose.zo, v)[0] for tank, v in zip(tanks, y[:count])])
        return np.concatenate([-flows, flows])  # the volumes, and the water each has lost

    def sill(k):
        def event(t, y):
            pose = state(t, y).start
            head = tanks[k].flow(pose.rotation, pose.zo, y[k])[1]
            return SILL_HEAD if head is None else head - SILL_HEAD

        event.direction = -1.0
        return event

    events = [sill(k) for k in range(len(tanks))]
    y0 = np.concatenate([drainage.initial(), np.zeros(count)])
    failure = None
    try:
        sol = solve_ivp(
            rhs,
            (0.0, duration),
            y0,
            method="RK45",
            rtol=RTOL,
            atol=RTOL * max(1.0, float(y0.max())),
            max_step=max_step,
            events=events or None,
            dense_output=True,
        )
    except EquilibriumNotFound as err:
        raise EquilibriumNotFound(f"draining: {err}") from None
    if sol.status < 0:
        failure = f"draining: the integrator stopped at {sol.t[-1]:.4g} s ({sol.message})"
    drain_times = {}
    for k, tank in enumerate(tanks):
        times = sol.t_events[k] if events else []
        if len(times):
            t, y = float(times[0]), sol.y_events[k][0]
            pose = state(t, y).start
            area = tank.surface_area(pose.rotation, pose.zo, y[k])
            z = (np.asarray(pose.rotation) @ tank.points.T)[2] + pose.zo
            # the openings still flowing: above the outside water, at the lowest sill
            coefficient = float(np.sum(tank.coefficient[(z >= 0.0) & (z <= z[z >= 0.0].min() + SILL_HEAD)]))
            drain_times[tank.name] = float(t + area / coefficient * np.sqrt(2.0 * SILL_HEAD / G))
    return DrainHistory(
        sol.sol, tuple(t.name for t in tanks), float(sol.t[-1]), failure, drain_times, y0[:count]
    )
