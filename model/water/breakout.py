"""Breakout: the pull beyond the submerged weight that frees a hull bedded in the seabed.

A wreck lying in soft soil does not come up at its submerged weight: the soil holds it
down (suction under the base, adhesion and the shear of the soil around it) until it breaks
out. Two models (``[ground] breakout``, :class:`~liftplan.model.scene.objects.Breakout`):

* **factor** on the submerged weight at rest, F_b = k (W + trapped water - B). A measured
  salvage lift of a small vessel (Ocean Engineering, 2016) peaked at twice its initial
  lifting force, 1.38 MN against 0.69 MN: k = 1.0 there.
* **soil model** from the contact area and the time, after the US Navy's laboratory and
  field reports (Naval Civil Engineering Laboratory, Port Hueneme):

      F_b = 1.5 (T / T_e)^-0.07 x F_r,      1e-3 <= T / T_e <= 10

  Liu (1969), "Ocean sediment holding strength against breakout of embedded objects",
  NCEL R-635: the mean holding strength over the static soil resistance F_r, with T the
  time allowed for the pull and T_e the time the object has lain embedded, fitted to the
  Gulf of Mexico field tests and a model study over that range of T / T_e (outside it the
  scene is refused, ``liftplan.model.scene.objects.LIU_RANGE``). R-635 builds F_r from the
  soil's cohesion and the object's geometry; its own formula is not in the copy we could
  read, so here F_r is the reverse undrained bearing capacity with full suction under the
  base, F_r = N_c s_u A (N_c = 5.14, Prandtl, for a long footing; about 6.2 for a square or
  a circle, Skempton), which is our assumption. A is the contact area: by default the plan
  area of the hull's underside at rest, as Muga (1968, NCEL R-591, "Ocean bottom breakout
  forces") used the horizontal projection of the largest contact area. Lee (1973, NCEL
  R-755) puts such force predictions at +-50 %.

The breakout force acts down at the ground contact; :func:`~.equilibrium.settle` applies it
in the load curve until the contact has risen ``clear`` m above its bed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.water.held import held_loads

#: kPa in one t/m2 (a tonne-force per square metre, g = 9.80665 m/s2).
KPA_PER_T_M2 = 9.80665
#: Liu (1969, R-635): F_m / F_r = LIU_COEFFICIENT (T / T_e)^LIU_EXPONENT.
LIU_COEFFICIENT = 1.5
LIU_EXPONENT = -0.07


@dataclass(frozen=True)
class BreakoutForce:
    """The breakout force of a scene and how it was found.

    Parameters
    ----------
    force : float  [t]
        F_b: the soil's hold beyond the submerged weight.
    model : str
        ``"factor"`` or ``"soil"``.
    submerged_weight : float  [t]
        W + trapped water - B at rest (the scene's attitude and lift height).
    clear : float  [m]
        The hold lasts until the contact has risen this far off its bed.
    area : float or None  [m2]
        Soil model: the contact area used.
    static_resistance : float or None  [t]
        Soil model: F_r = N_c s_u A.
    time_factor : float or None  [-]
        Soil model: 1.5 (T / T_e)^-0.07.
    """

    force: float
    model: str
    submerged_weight: float
    clear: float
    area: float | None = None
    static_resistance: float | None = None
    time_factor: float | None = None

    def to_json(self):
        return {
            "force": self.force,
            "model": self.model,
            "submerged_weight": self.submerged_weight,
            "clear": self.clear,
            "area": self.area,
            "static_resistance": self.static_resistance,
            "time_factor": self.time_factor,
        }


def underside_area(hull, rotation):
    """Plan area of the hull's downward-facing surface at an attitude  [m2].

    Parameters
    ----------
    hull : Hull
    rotation : numpy.ndarray, shape (3, 3)
    """
    tris = np.asarray(hull.triangles) @ np.asarray(rotation).T
    up = 0.5 * np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])[:, 2]
    return float(-up[up < 0.0].sum())


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


def breakout_force(scene):
    """The breakout force of a scene with ``[ground] breakout`` (:class:`BreakoutForce`).

    Raises
    ------
    EquilibriumNotFound
        The hull would float up at rest (nothing to break out).
    """

    spec = scene.ground.breakout
    net = held_loads(scene).net_weight
    if spec.factor is not None:
        return BreakoutForce(spec.factor * net, "factor", net, spec.clear)
    a = scene.attitude
    area = (
        spec.area
        if spec.area is not None
        else underside_area(scene.hull, rotation_matrix(a.heel, a.trim, a.yaw))
    )
    resistance = soil_resistance(spec.shear_strength, area, spec.bearing_factor)
    factor = liu_time_factor(spec.pull_time, spec.embedded_time)  # the scene checked the ratio
    return BreakoutForce(factor * resistance, "soil", net, spec.clear, area, resistance, factor)


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
