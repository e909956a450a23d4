"""Wind on the lifted body and on the floating cranes' booms (``[wind]``).

The wind blows at ``speed`` towards ``direction`` (in plan); on an exposed area A with drag
coefficient Cd it pushes with F = 1/2 rho_air Cd A V^2 (t, after g), horizontally, at the
area's centre of pressure (GL Noble Denton 0027/ND counts wind among a lift's special loads).

* On the body (``body = { area, cd, height }``, height in the body frame): vertical ropes
  carry no horizontal force; the body swings until the ropes' small inclinations carry F at
  the lugs, and the couple F (h - h_lugs) (h_lugs the lugs' mean height) is carried by the
  vertical tensions. That is the weight W acting F (h - h_lugs) / W further downwind in plan:
  the scene is solved with its CG so moved (exact for lugs at one height, in the small-swing
  limit of the vertical-rope models).
* On a floating crane's boom (``booms = [{ crane, area, cd, height }]``, height above the
  vessel's waterline): the moment F h heels and trims the vessel (F h d_stb / (disp GM_T),
  F h d_fwd / (disp GM_L), d the wind's direction in the vessel's axes), which moves each of
  its tips by y_t heel + x_t trim: the scene is solved with those tips so lowered and the
  vessel's heel and trim include the wind's. A crane on land keeps its tip (the wind on its
  boom is a matter of its rating, not of the load sharing).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from liftplan.model.errors import InvalidScene

#: Air density  [t/m3] (15 deg C at sea level).
AIR_DENSITY = 1.225e-3
#: Standard gravity  [m/s2]: a force in kN over it is in t.
GRAVITY = 9.80665


def _positive(path, value, zero=False):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidScene(f"{path} = {value!r}: expected a number") from None
    if not math.isfinite(number) or number < 0.0 or (number == 0.0 and not zero):
        raise InvalidScene(f"{path} = {value!r}: expected a finite number {'>=' if zero else '>'} 0")
    return number


@dataclass(frozen=True)
class WindArea:
    """An area exposed to the wind.

    Parameters
    ----------
    area : float  [m2]
    cd : float  [-]
        Drag coefficient.
    height : float  [m]
        Its centre of pressure: for the body, in the body frame (``z-up``); for a boom, above
        the vessel's waterline.
    crane : str or None
        The crane whose boom this is (None for the body).
    """

    area: float
    cd: float
    height: float
    crane: str | None = None

    def __post_init__(self):
        where = "wind.body" if self.crane is None else f"wind.booms[{self.crane}]"
        object.__setattr__(self, "area", _positive(f"{where}.area", self.area))
        object.__setattr__(self, "cd", _positive(f"{where}.cd", self.cd))
        height = float(self.height)
        if not math.isfinite(height):
            raise InvalidScene(f"{where}.height = {self.height!r}: expected a finite number")
        object.__setattr__(self, "height", height)


@dataclass(frozen=True)
class Wind:
    """The wind over the lift, ``z-up``.

    Parameters
    ----------
    speed : float  [m/s]
    direction : float  [deg]
        Where it blows towards, in world plan from +x, > 0 towards +y.
    body : WindArea or None
    booms : tuple of WindArea
        Each with its ``crane``.
    density : float  [t/m3]
        Air density.
    """

    speed: float
    direction: float = 0.0
    body: WindArea | None = None
    booms: tuple[WindArea, ...] = ()
    density: float = AIR_DENSITY

    def __post_init__(self):
        object.__setattr__(self, "speed", _positive("wind.speed", self.speed, zero=True))
        object.__setattr__(self, "density", _positive("wind.density", self.density))
        direction = float(self.direction)
        if not math.isfinite(direction):
            raise InvalidScene(f"wind.direction = {self.direction!r}: expected a finite number")
        object.__setattr__(self, "direction", direction)
        object.__setattr__(self, "booms", tuple(self.booms))

    def force(self, area):
        """The wind's force on an area  [t]."""
        return 0.5 * self.density * area.cd * area.area * self.speed**2 / GRAVITY

    @property
    def unit(self):
        """The direction as a world plan unit vector."""
        h = math.radians(self.direction)
        return (math.cos(h), math.sin(h))


@dataclass(frozen=True)
class WindState:
    """What the wind did to a solved scene.

    Parameters
    ----------
    body_force : float  [t]
        On the body.
    cog_shift : tuple of 2 float  [m]
        How far downwind (world plan) the body's weight acts for the couple.
    booms : dict of str to (float, float, float)
        Per boom (by crane): its force [t], the vessel's heel and trim from it [deg].
    tip_drops : dict of str to float  [m]
        Each floating crane's tip drop from the wind on its vessel's booms (by lug).
    load_changes : dict of str to float or None  [t]
        Each rope's tension less its tension in still air (the same scene and model solved
        without the wind), keyed as the tensions: the wind's share of each crane's static
        load. None when the scene has no equilibrium in still air.
    """

    body_force: float
    cog_shift: tuple[float, float]
    booms: dict
    tip_drops: dict
    load_changes: dict | None = None

    def to_json(self):
        return {
            "body_force": self.body_force,
            "cog_shift": list(self.cog_shift),
            "booms": {k: {"force": f, "heel": h, "trim": t} for k, (f, h, t) in self.booms.items()},
            "tip_drops": dict(self.tip_drops),
            "load_changes": None if self.load_changes is None else dict(self.load_changes),
        }


def apply_wind(scene, tips):
    """The scene with the wind's effects on the vertical-rope models, and what they were.

    Parameters
    ----------
    scene : Scene
        With ``wind``.
    tips : numpy.ndarray, shape (n, 2)  [m]
        The boom tips' world plan positions (above the lugs at the level pose).

    Returns
    -------
    (Scene, WindState)
        The scene without its wind: the CG moved downwind by the body's couple over W, each
        floating crane's boom height lowered by its tip's drop from the booms' wind, and each
        vessel's ballast moment taking the wind's moment (so its reported heel and trim
        include it).
    """
    wind = scene.wind
    ux, uy = wind.unit
    body = scene.body
    force = wind.force(wind.body) if wind.body is not None else 0.0
    shift = (0.0, 0.0)
    if force > 0.0 and body.weight_curve is not None:
        raise InvalidScene(
            "wind.body: wind on a body with a weight_curve is not modelled (its couple moves the "
            "weight's line, not its curve); expected no wind.body, or no weight curve"
        )
    if force > 0.0:
        lugs = scene.lug_points()
        lever = wind.body.height - float(lugs[:, 2].mean())
        s = force * lever / body.weight
        yaw = math.radians(scene.attitude.yaw)  # the shift is in world plan; the CG in the body frame
        shift = (s * ux, s * uy)
        dx = math.cos(yaw) * shift[0] + math.sin(yaw) * shift[1]
        dy = -math.sin(yaw) * shift[0] + math.cos(yaw) * shift[1]
        body = dataclasses.replace(body, cog=(body.cog[0] + dx, body.cog[1] + dy, body.cog[2]))
    moments = {}
    booms = {}
    for boom in wind.booms:
        crane = scene.crane(boom.crane)
        if crane.vessel is None:
            raise InvalidScene(
                f"wind.booms[{boom.crane}]: the crane stands on land; expected a floating crane "
                "(cranes[].vessel): the wind on a boom moves only a floating crane's tip"
            )
        name = crane.vessel_name
        vessel = scene.vessels[name][0]
        h = math.radians(vessel.heading)
        forward, starboard = ux * math.cos(h) + uy * math.sin(h), ux * math.sin(h) - uy * math.cos(h)
        f = wind.force(boom)
        heeling, trimming = f * boom.height * starboard, f * boom.height * forward
        old = moments.get(name, (0.0, 0.0))
        moments[name] = (old[0] + heeling, old[1] + trimming)
        booms[boom.crane] = (
            f,
            math.degrees(heeling / vessel.heel_stiffness),
            math.degrees(trimming / vessel.trim_stiffness),
        )
    drops = {}
    cranes = list(scene.cranes)
    for k, crane in enumerate(cranes):
        name = crane.vessel_name
        if name not in moments:
            continue
        vessel = scene.vessels[name][0]
        forward, starboard = vessel.axes(tips[k])
        heeling, trimming = moments[name]
        drop = starboard * heeling / vessel.heel_stiffness + forward * trimming / vessel.trim_stiffness
        drops[crane.label] = float(drop)
        changes = {"boom_height": crane.boom_height - drop} if crane.boom_height is not None else {}
        if isinstance(crane.vessel, type(vessel)):
            ballast = (vessel.ballast[0] + heeling, vessel.ballast[1] + trimming)
            changes["vessel"] = dataclasses.replace(vessel, ballast=ballast)
        cranes[k] = dataclasses.replace(crane, **changes)
    state = WindState(body_force=force, cog_shift=shift, booms=booms, tip_drops=drops)
    return dataclasses.replace(scene, body=body, cranes=tuple(cranes), wind=None), state
