"""Breakout: the pull beyond the submerged weight that frees a hull bedded in the seabed.

A wreck lying in soft soil does not come up at its submerged weight: the soil holds it
down (suction under the base, adhesion and the shear of the soil around it) until it breaks
out. Three models (``[ground] breakout``, :class:`~liftplan.model.scene.objects.Breakout`):

* **factor** on the submerged weight at rest, F_b = k (W + trapped water - B). A measured
  salvage lift of a small vessel (Ocean Engineering, 2016) peaked at twice its initial
  lifting force, 1.38 MN against 0.69 MN: k = 1.0 there.
* **ncel**, the immediate breakout force of an object partly embedded in a cohesive
  seabed, the method of the US Navy's Naval Civil Engineering Laboratory (Port Hueneme):

      F_b = A s_u N_c (1 + 0.2 D/B) (1 + 0.2 B/L)

  Lee (1973), "Unaided breakout of partially embedded objects from cohesive seafloor
  soils", NCEL R-755, carried into the NCEL Handbook for Marine Geotechnical Engineering
  (Rocker, ed., 1985): from field and laboratory pulls in cohesive soils, a force that
  frees the object at once (a crane pull of minutes) is the reverse bearing capacity of its
  base with full suction under it; lesser forces free it only after a time, which R-755
  estimates separately (to about +-100 %; not modelled here, a crane lift does not hold a
  lesser pull for hours). R-755 puts the force prediction at about +-50 %. N_c is
  ``bearing_factor`` (5.14, Prandtl's strip), D the ``embedment`` of the base below the
  seabed, B and L the contact's shorter and longer plan sides; the shape and depth terms are
  Skempton's (1951), whose depth term stops growing at D/B = 2.5 (:data:`DEPTH_LIMIT`).
  This is the model for a pull that lifts the hull within minutes of taking the weight.
* **soil**, the model of before, kept with its meaning: F_b = 1.5 (T / T_e)^-0.07 x F_r,
  Liu's (1969, "Ocean sediment holding strength against breakout of embedded objects",
  NCEL R-635) correlation of the mean holding strength over the static soil resistance
  F_r with the pull time T and the time embedded T_e, fitted for 1e-3 <= T / T_e <= 10
  (outside it the scene is refused, ``LIU_RANGE``). Here F_r = N_c s_u A: but that is
  already the full-suction immediate force of the NCEL method above, and Liu's factor is
  2.4 at T / T_e = 1e-3, so suction is likely counted twice (F_b some 2.3 x the NCEL
  force); :func:`bed_warnings` says so whenever it is used. Use ``ncel``.

The contact area A defaults to the plan area of the hull's underside at rest, as Muga
(1968, NCEL R-591, "Ocean bottom breakout forces") used the horizontal projection of the
largest contact area; B and L default to the underside's extents across and along the
hull's heading. :func:`bed_warnings` also checks that the bed carries the hull at rest: a
bearing pressure (submerged weight / A) above N_c s_u (1 + 0.2 D/B)(1 + 0.2 B/L) means the
soil the scene describes would have let the hull sink further.

The breakout force acts down at the ground contact; :func:`~.equilibrium.settle` applies it
in the load curve until the contact has risen ``clear`` m above its bed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.water.held import held_loads

#: kPa in one t/m2 (a tonne-force per square metre, g = 9.80665 m/s2).
KPA_PER_T_M2 = 9.80665
#: Liu (1969, R-635): F_m / F_r = LIU_COEFFICIENT (T / T_e)^LIU_EXPONENT.
LIU_COEFFICIENT = 1.5
LIU_EXPONENT = -0.07
#: Skempton (1951), as the NCEL method uses them: N_c (1 + 0.2 D/B)(1 + 0.2 B/L).
SHAPE_DEPTH_COEFFICIENT = 0.2
#: Skempton's depth term grows no further beyond D/B = 2.5 (deep failure).
DEPTH_LIMIT = 2.5


@dataclass(frozen=True)
class BreakoutForce:
    """The breakout force of a scene and how it was found.

    Parameters
    ----------
    force : float  [t]
        F_b: the soil's hold beyond the submerged weight.
    model : str
        ``"factor"``, ``"ncel"`` or ``"soil"`` (``"none"`` without a model).
    submerged_weight : float  [t]
        W + trapped water - B at rest (the scene's attitude and lift height).
    clear : float  [m]
        The hold lasts until the contact has risen this far off its bed.
    area : float or None  [m2]
        Soil models: the contact area used.
    static_resistance : float or None  [t]
        Soil models: N_c s_u A.
    time_factor : float or None  [-]
        ``soil``: 1.5 (T / T_e)^-0.07.
    embedment, width, length : float or None  [m]
        ``ncel``: D, B and L.
    depth_factor, shape_factor : float or None  [-]
        ``ncel``: 1 + 0.2 min(D/B, 2.5) and 1 + 0.2 B/L.
    """

    force: float
    model: str
    submerged_weight: float
    clear: float
    area: float | None = None
    static_resistance: float | None = None
    time_factor: float | None = None
    embedment: float | None = None
    width: float | None = None
    length: float | None = None
    depth_factor: float | None = None
    shape_factor: float | None = None

    def describe(self):
        """How F_b was found, in one line (no leading F_b)."""
        if self.model == "ncel":
            return (
                f"NCEL immediate breakout: N_c s_u A = {self.static_resistance:.1f} t over "
                f"{self.area:.1f} m2 x depth {self.depth_factor:.3f} (D {self.embedment:g} m, "
                f"B {self.width:.2f} m) x shape {self.shape_factor:.3f} (L {self.length:.2f} m)"
            )
        if self.model == "soil":
            return (
                f"soil model: 1.5 (T/T_e)^-0.07 = {self.time_factor:.3f} x N_c s_u A = "
                f"{self.static_resistance:.1f} t over {self.area:.1f} m2 (Liu 1969; may count "
                "suction twice)"
            )
        if self.model == "factor":
            if self.submerged_weight > 0.0:
                return f"a factor {self.force / self.submerged_weight:.3g} on the submerged weight"
            return "a factor on the submerged weight"
        return "no breakout model in the scene"

    def to_json(self):
        return {
            "force": self.force,
            "model": self.model,
            "submerged_weight": self.submerged_weight,
            "clear": self.clear,
            "area": self.area,
            "static_resistance": self.static_resistance,
            "time_factor": self.time_factor,
            "embedment": self.embedment,
            "width": self.width,
            "length": self.length,
            "depth_factor": self.depth_factor,
            "shape_factor": self.shape_factor,
        }


def _underside(hull, rotation):
    """The hull's downward-facing triangles at an attitude and their plan areas."""
    tris = np.asarray(hull.triangles) @ np.asarray(rotation).T
    up = 0.5 * np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])[:, 2]
    return tris[up < 0.0], -up[up < 0.0]


def underside_area(hull, rotation):
    """Plan area of the hull's downward-facing surface at an attitude  [m2].

    Parameters
    ----------
    hull : Hull
    rotation : numpy.ndarray, shape (3, 3)
    """
    return float(_underside(hull, rotation)[1].sum())


def underside_sides(hull, rotation):
    """B and L  [m]: the plan extents of the hull's underside across and along its heading
    (the body x axis projected on the plan), shorter first.

    Parameters
    ----------
    hull : Hull
    rotation : numpy.ndarray, shape (3, 3)
    """
    tris, _ = _underside(hull, rotation)
    points = tris.reshape(-1, 3)[:, :2]
    heading = np.asarray(rotation)[:2, 0]
    norm = float(np.hypot(*heading))
    heading = heading / norm if norm > 1e-9 else np.array([1.0, 0.0])
    across = np.array([-heading[1], heading[0]])
    along = float(np.ptp(points @ heading))
    wide = float(np.ptp(points @ across))
    return min(along, wide), max(along, wide)


def liu_time_factor(pull_time, embedded_time):
    """Liu's (1969) 1.5 (T / T_e)^-0.07  [-] (the ratio is checked by the scene)."""
    return LIU_COEFFICIENT * (pull_time / embedded_time) ** LIU_EXPONENT


def soil_resistance(shear_strength, area, bearing_factor):
    """Static soil resistance F_r = N_c s_u A  [t].

    Parameters
    ----------
    shear_strength : float  [kPa]
    area : float  [m2]
    bearing_factor : float  [-]
    """
    return bearing_factor * shear_strength / KPA_PER_T_M2 * area


def ncel_factors(embedment, width, length):
    """The NCEL method's depth and shape terms (1 + 0.2 min(D/B, 2.5), 1 + 0.2 B/L)  [-].

    Parameters
    ----------
    embedment, width, length : float  [m]
        D, B and L (B <= L; a larger B is taken as L and the other as B).
    """
    short, long_ = min(width, length), max(width, length)
    depth = 1.0 + SHAPE_DEPTH_COEFFICIENT * min(embedment / short, DEPTH_LIMIT)
    return depth, 1.0 + SHAPE_DEPTH_COEFFICIENT * short / long_


def ncel_breakout(shear_strength, area, bearing_factor, embedment, width, length):
    """The NCEL immediate breakout force A s_u N_c (1 + 0.2 D/B)(1 + 0.2 B/L)  [t].

    Parameters
    ----------
    shear_strength : float  [kPa]
    area : float  [m2]
    bearing_factor : float  [-]
    embedment, width, length : float  [m]
    """
    depth, shape = ncel_factors(embedment, width, length)
    return soil_resistance(shear_strength, area, bearing_factor) * depth * shape


def _contact(scene):
    """The soil models' contact: area A, sides B <= L  [m2, m, m] (given or from the hull)."""
    spec = scene.ground.breakout
    a = scene.attitude
    rotation = rotation_matrix(a.heel, a.trim, a.yaw)
    area = spec.area if spec.area is not None else underside_area(scene.hull, rotation)
    width, length = spec.width, spec.length
    if width is None or length is None:
        b, l_ = underside_sides(scene.hull, rotation)
        width = b if width is None else width
        length = l_ if length is None else length
    return area, min(width, length), max(width, length)


def breakout_force(scene):
    """The breakout force of a scene with ``[ground] breakout`` (:class:`BreakoutForce`).

    Raises
    ------
    EquilibriumNotFound
        The hull would float up at rest (nothing to break out).
    """

    spec = scene.ground.breakout
    net = held_loads(scene).net_weight
    if spec.model == "factor":
        return BreakoutForce(spec.factor * net, "factor", net, spec.clear)
    area, width, length = _contact(scene)
    resistance = soil_resistance(spec.shear_strength, area, spec.bearing_factor)
    if spec.model == "ncel":
        depth, shape = ncel_factors(spec.embedment, width, length)
        return BreakoutForce(
            resistance * depth * shape,
            "ncel",
            net,
            spec.clear,
            area,
            resistance,
            embedment=spec.embedment,
            width=width,
            length=length,
            depth_factor=depth,
            shape_factor=shape,
        )
    factor = liu_time_factor(spec.pull_time, spec.embedded_time)  # the scene checked the ratio
    return BreakoutForce(factor * resistance, "soil", net, spec.clear, area, resistance, factor)


def bed_warnings(scene, key="ground.breakout"):
    """Warnings on a soil breakout model: the bed cannot carry the hull at rest, or the
    ``soil`` model (Liu's time factor) likely counts suction twice.

    Parameters
    ----------
    scene : Scene
    key : str
        What the lines name (a plan names its breakout scene).

    Returns
    -------
    list of str
    """
    ground = scene.ground
    if ground is None or ground.breakout is None or scene.hull is None or scene.water is None:
        return []
    spec = ground.breakout
    if spec.model == "factor":
        return []
    try:
        force = breakout_force(scene)
    except EquilibriumNotFound:
        return []  # floats up at rest: the solve says so
    area, width, length = _contact(scene)
    embedment = spec.embedment if spec.model == "ncel" else 0.0
    depth, shape = ncel_factors(embedment, width, length)
    capacity = spec.bearing_factor * spec.shear_strength * depth * shape  # kPa
    pressure = force.submerged_weight / area * KPA_PER_T_M2  # kPa
    out = []
    if pressure > capacity:
        out.append(
            f"{key}: the bed cannot carry the hull at rest: bearing pressure {pressure:.2f} kPa "
            f"(submerged weight {force.submerged_weight:.1f} t on {area:.1f} m2) above the soil's "
            f"capacity N_c s_u (1 + 0.2 D/B)(1 + 0.2 B/L) = {capacity:.2f} kPa (s_u "
            f"{spec.shear_strength:g} kPa); the hull would have sunk further: expected the "
            "shear strength at the depth it rests at"
        )
    if spec.model == "soil":
        ncel = ncel_breakout(spec.shear_strength, area, spec.bearing_factor, 0.0, width, length)
        out.append(
            f"{key}: pull_time and embedded_time select Liu's time factor "
            f"({force.time_factor:.2f}) on N_c s_u A, which is already the full-suction "
            f"immediate breakout force (NCEL R-755): F_b {force.force:.1f} t likely counts suction "
            f"twice; the NCEL immediate breakout (no times, with embedment) gives {ncel:.1f} t at "
            "zero embedment"
        )
    return out


@dataclass(frozen=True)
class BreakoutLoad:
    """The peak total hook load of breaking a bedded hull out: one load case for a plan.

    Parameters
    ----------
    total : float  [t]
        W + trapped water - B + F_b: what the cranes carry together at breakout.
    breakout : BreakoutForce
    weight : float  [t]
        The body's weight in air.
    point : tuple of 3 float  [m]
        A body-frame (z-up) point on the line of action of ``total``: the weight, the
        trapped water and the buoyancy at rest, and F_b at the ground contact.
    """

    total: float
    breakout: BreakoutForce
    weight: float
    point: tuple[float, float, float]

    @property
    def weight_factor(self):
        """``total`` over the weight in air  [-]: the factor a planner puts on W."""
        return self.total / self.weight

    def to_json(self):
        return {
            "total": self.total,
            "weight": self.weight,
            "weight_factor": self.weight_factor,
            "point": list(self.point),
            "breakout": self.breakout.to_json(),
        }


def breakout_load(scene):
    """The peak total hook load at breakout, with its line of action.

    The hull rests at the scene's attitude and lift height, compartments full. At the
    breakout instant the ropes carry the submerged weight W + trapped water - B at its
    point P (:func:`~liftplan.model.water.held.held_loads`) and F_b at the contact c, so
    ``total`` = (W + T_w - B) + F_b on the line through (net P + F_b c) / total. A plan's
    capacity check takes it as a load case with weight ``total`` at ``point``.

    Parameters
    ----------
    scene : Scene
        With ``[hull]``, ``[water]`` and ``[ground]``; no breakout model means F_b = 0 (the
        case is then the submerged weight).

    Returns
    -------
    BreakoutLoad
    """

    if scene.ground is None or scene.hull is None:
        raise InvalidScene("breakout: expected a scene with [hull], [water] and [ground]")
    held = held_loads(scene)
    net = held.net_weight
    if scene.ground.breakout is None:
        force = BreakoutForce(0.0, "none", net, 0.0)
    else:
        force = breakout_force(scene)
    total = net + force.force
    point = (net * np.asarray(held.net_point) + force.force * np.asarray(scene.ground.contact)) / total
    return BreakoutLoad(total, force, scene.body.weight, tuple(float(v) for v in point))
