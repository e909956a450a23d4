"""Shear force and bending moment of the body as a beam along its x axis, in a solved state.

Loads (each in the body frame, at the solved attitude R; g = R^T e_z is the world's up
direction in the body frame):

* the weight curve w(x) [t/m], vertical, taken at the CG's height z_G;
* buoyancy per length b(x) [t/m] of the clipped hull (:mod:`.sections`), vertical, at the
  immersed section's centroid;
* water trapped in compartments, a weight per length over each compartment's length, at
  its centre;
* each rope or sling leg's force at its lug (vertical ropes: T up; inclined ropes and sling
  legs: along the line), and the ground reaction at the contact, as point loads.

Each force f (body components) loads the beam with its component normal to the beam axis
in the body's vertical plane, f_z, at its x, and, through its axial component f_x acting at
height z off the reference height z_G, with a couple (z - z_G) f_x. With the body level
(g = e_z) the couples vanish and this is the textbook beam; inclined, the couples are what
makes the moment close (sum of f_z x alone balances only at zero trim). Components across
the body (f_y) bend it sideways and twist it, which is not reported.

Signs (CONTRACT.md): shear and moment of the part aft of the section. Q(x) is the net upward
(body +z) load on the part aft of x; M(x) the moment about the body's y axis, at the section's
point at height z_G, of the loads on that part: sum of f_z (x - x_i) + (z_i - z_G) f_x.
M > 0 sags the hull (held near its ends), M < 0 hogs it (held near its middle, ends
overhanging).

The curves are exact piecewise polynomials (:mod:`.piecewise`): the weight linear, buoyancy
quadratic, so Q is cubic and M quartic at most between breakpoints, integrated without a grid.
Past the fore end Q and M are the state's residual force and moment: in equilibrium they
close to its residual (1e-13 W for the given-attitude models, at most 1e-9 W for the solved
ones, tested).

A weight curve agrees with ``body.weight`` and the CG's x only to the tolerance the scene
accepts (:data:`~liftplan.model.scene.objects.WEIGHT_CURVE_REL`, ``WEIGHT_CURVE_CENTROID``), while
the equilibrium holds W at G exactly. The difference is spread over the curve's length as
the linear load c0 + c1 (x - x_mid) that restores the integral and the first moment exactly
(reported as ``correction``), so the curves close whatever the rounding of the curve.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.scene.objects import curve_totals
from liftplan.model.strength.piecewise import Extreme, Piecewise, on_breaks
from liftplan.model.strength.sections import sectional_buoyancy
from liftplan.model.water.afloat import buoyancy_weights

#: Output stations: the breakpoints and this many equal steps over the loaded length.
GRID = 200


@dataclass(frozen=True)
class PointLoad:
    """A concentrated load on the girder.

    Parameters
    ----------
    name : str
        ``"rope T1"``, ``"leg FWD/F-P"``, ``"ground"``.
    x : float  [m]
        Body x of the point.
    normal : float  [t]
        Component normal to the beam axis in the body's vertical plane (> 0 up).
    couple : float  [t m]
        (z - z_G) x axial component.
    """

    name: str
    x: float
    normal: float
    couple: float


@dataclass(frozen=True)
class GirderForces:
    """Shear force and bending moment along the body in one solved state.

    Parameters
    ----------
    stations : numpy.ndarray  [m]
        Body x of the output points: breakpoints (listed twice where Q or M jumps: the
        value just aft, then just forward), :data:`GRID` equal steps and the maxima.
    shear : numpy.ndarray  [t]
        Q at ``stations``.
    moment : numpy.ndarray  [t m]
        M at ``stations``.
    max_shear : Extreme  [t]
    max_moment : Extreme  [t m]
    shear_curve, moment_curve : Piecewise
        The exact curves (evaluate anywhere: ``moment_curve(x)``).
    weight : Piecewise  [t/m]
        Weight per length (downward, vertical), the correction included.
    buoyancy : Piecewise or None  [t/m]
        Buoyancy per length (upward, vertical); None out of the water.
    trapped_water : Piecewise or None  [t/m]
        Trapped water per length (downward); None without.
    point_loads : tuple of PointLoad
    correction : tuple of (float, float)
        (weight added [t], centroid moved [m]) to make the curve carry W at G's x exactly.
    closure : tuple of (float, float)
        (Q [t], M [t m]) just past the fore end: the state's residual.
    normal_factor : float
        g_z, the cosine between the world vertical and the body's z (1 when level).
    """

    stations: np.ndarray
    shear: np.ndarray
    moment: np.ndarray
    max_shear: Extreme
    max_moment: Extreme
    shear_curve: Piecewise
    moment_curve: Piecewise
    weight: Piecewise
    buoyancy: Piecewise | None
    trapped_water: Piecewise | None
    point_loads: tuple[PointLoad, ...]
    correction: tuple[float, float]
    closure: tuple[float, float]
    normal_factor: float

    def to_json(self):
        """The ``"strength"`` block of ``solve --json`` (keys fixed by CONTRACT.md, t and t m)."""
        return {
            "x": self.stations.tolist(),
            "shear_force": self.shear.tolist(),
            "bending_moment": self.moment.tolist(),
            "max_bending_moment": self.max_moment.to_json(),
            "max_shear_force": self.max_shear.to_json(),
            "point_loads": [
                {"name": p.name, "x": p.x, "normal": p.normal, "couple": p.couple} for p in self.point_loads
            ],
            "weight_correction": {"weight": self.correction[0], "centroid_shift": self.correction[1]},
            "closure": {"shear_force": self.closure[0], "bending_moment": self.closure[1]},
        }


def hull_girder(scene, eq, grid=GRID):
    """Shear force and bending moment of the body in a solved state.

    Parameters
    ----------
    scene : Scene
        With ``body.weight_curve``.
    eq : Equilibrium
        The solved state of that scene (any model).
    grid : int
        Equal steps over the loaded length in the output stations.

    Returns
    -------
    GirderForces

    Raises
    ------
    InvalidScene
        The body has no weight curve.
    """
    body = scene.body
    if body.weight_curve is None:
        raise InvalidScene(
            "body.weight_curve: missing; expected [[x m, t/m], ...] for the shear force and bending moment"
        )
    pose = eq.pose
    rot = attitude_matrix(pose.heel, pose.trim, pose.yaw)
    up = rot[2]
    z_ref = body.cog[2]
    weight, correction = _weight(body)
    parts = [(weight, -up[2], None)]  # (t/m piecewise, normal factor, couple density)
    buoyancy = trapped = None
    if eq.afloat is not None:
        flexible = getattr(eq.flexible_hull, "buoyancy", None)  # the deflected hull's, when used
        use = flexible is not None and eq.flexible_hull.used == "flexible"
        buoyancy, moment = flexible if use else _buoyancy(scene, pose, up)
        # axial part b g_x at the section's centroid: couple (z_B - z_G) b g_x per length
        couple = Piecewise(buoyancy.breaks, up[0] * (moment.coef - z_ref * buoyancy.coef))
        parts.append((buoyancy, up[2], couple))
        trapped, trapped_couple = _trapped(scene, up, z_ref)
        if trapped is not None:
            parts.append((trapped, -up[2], trapped_couple))
    points = tuple(_point_loads(scene, eq, rot, z_ref))
    breaks = np.unique(np.concatenate([p[0].breaks for p in parts] + [[p.x for p in points]]))
    q = sum(factor * on_breaks(breaks, pw.breaks, _quadratic(pw.coef)) for pw, factor, _ in parts)
    m = np.zeros((len(breaks) - 1, 4))
    for _, _, couple in parts:
        if couple is not None:
            shifted = on_breaks(breaks, couple.breaks, couple.coef)
            m[:, : shifted.shape[1]] += shifted
    index = np.searchsorted(breaks, [p.x for p in points])
    forces, couples = np.zeros(len(breaks)), np.zeros(len(breaks))
    np.add.at(forces, index, [p.normal for p in points])
    np.add.at(couples, index, [p.couple for p in points])
    shear = Piecewise(breaks, q).integral(jumps=forces)
    moment_curve = shear.integral(jumps=couples, density=Piecewise(breaks, m))
    max_shear, max_moment = shear.extreme(), moment_curve.extreme()
    stations, q_out, m_out = _sample(
        shear, moment_curve, grid, (max_shear.x, max_moment.x), tol=1e-12 * body.weight
    )
    return GirderForces(
        stations=stations,
        shear=q_out,
        moment=m_out,
        max_shear=max_shear,
        max_moment=max_moment,
        shear_curve=shear,
        moment_curve=moment_curve,
        weight=weight,
        buoyancy=buoyancy,
        trapped_water=trapped,
        point_loads=points,
        correction=correction,
        closure=(shear.end(), moment_curve.end()),
        normal_factor=float(up[2]),
    )


def attitude_matrix(heel, trim, yaw):
    """R = Rx(heel) Rz(yaw) Ry(trim) from degrees, in numpy: the definition of
    :func:`liftplan.model.frames.rotation` (which builds casadi matrices, ~0.2 ms a call),
    pinned to it by tests/model/test_strength.py."""
    h, t, y = np.radians([heel, trim, yaw])
    ch, sh, ct, st, cy, sy = np.cos(h), np.sin(h), np.cos(t), np.sin(t), np.cos(y), np.sin(y)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, ch, -sh], [0.0, sh, ch]])
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    return rx @ rz @ ry


def _quadratic(coef):
    """Coefficients padded or cut to a quadratic (the buoyancy's cubic term is round-off)."""
    out = np.zeros((len(coef), 3))
    width = min(3, coef.shape[1])
    out[:, :width] = coef[:, :width]
    return out


def _weight(body):
    """The weight curve as a piecewise-linear load, corrected to W at G's x exactly."""
    x, w = body.weight_curve_arrays
    h = np.diff(x)
    area, first = curve_totals(x, w)
    length, middle = x[-1] - x[0], 0.5 * (x[0] + x[-1])
    # c0 + c1 (x - middle) over the curve: integral c0 L, first moment c0 L middle + c1 L^3 / 12
    c0 = (body.weight - area) / length
    c1 = 12.0 * (body.weight * body.cog[0] - first - c0 * length * middle) / length**3
    coef = np.stack([w[:-1] + c0 + c1 * (x[:-1] - middle), (w[1:] - w[:-1]) / h + c1], axis=1)
    shift = body.cog[0] - first / area
    return Piecewise(x, coef), (float(body.weight - area), float(shift))


def _buoyancy(scene, pose, up):
    """Buoyancy per length and its moment about body z = 0, at the solved pose."""

    tris, kappa, _ = buoyancy_weights(scene.hull, scene.body.weight, scene.water.density)
    zo = pose.lift_height - scene.water.level
    breaks, per_length, moment = sectional_buoyancy(tris, kappa, up, zo)
    return Piecewise(breaks, per_length), Piecewise(breaks, moment)


def _trapped(scene, up, z_ref):
    """Water trapped in compartments: weight per length (uniform over each box's length) and
    the couple density of its axial part."""
    density = scene.water.density
    tanks = [c for c in scene.hull.compartments if c.contents == "water"]
    if not tanks:
        return None, None
    lows = [c.box["min"][0] for c in tanks]
    highs = [c.box["max"][0] for c in tanks]
    breaks = np.unique(np.concatenate([lows, highs]))
    load, couple = np.zeros((len(breaks) - 1, 1)), np.zeros((len(breaks) - 1, 1))
    middle = 0.5 * (breaks[:-1] + breaks[1:])
    for c in tanks:
        lo, hi = np.asarray(c.box["min"], dtype=float), np.asarray(c.box["max"], dtype=float)
        inside = (middle > lo[0]) & (middle < hi[0])
        per_length = density * (hi[1] - lo[1]) * (hi[2] - lo[2])
        load[inside, 0] += per_length
        couple[inside, 0] += -up[0] * per_length * (0.5 * (lo[2] + hi[2]) - z_ref)
    return Piecewise(breaks, load), Piecewise(breaks, couple)


def _point_loads(scene, eq, rot, z_ref):
    """Rope, sling-leg and ground forces on the body, as :class:`PointLoad`."""
    lugs = dict(zip(scene.lug_names, scene.lug_points()))

    def load(name, at, world_force):
        f = np.asarray(world_force, dtype=float) @ rot  # body components, R^T F
        return PointLoad(name, float(at[0]), float(f[2]), float((at[2] - z_ref) * f[0]))

    if eq.rigging is not None:
        r, origin = eq.rigging, np.asarray(eq.position, dtype=float)
        for crane in scene.cranes:
            if crane.sling is None:
                yield load(f"rope {crane.lug}", lugs[crane.lug], eq.rope_forces[crane.label].force)
                continue
            for leg in crane.sling.legs:
                key = f"{crane.label}/{leg.lug}"
                upper = (
                    r.hook_positions[crane.label]
                    if crane.sling.spreader is None
                    else r.spreader_ends[crane.label][leg.end - 1]
                )
                span = np.asarray(upper) - (origin + rot @ lugs[leg.lug])
                yield load(f"leg {key}", lugs[leg.lug], r.legs[key] * span / np.linalg.norm(span))
    elif eq.rope_forces is not None:
        for name, force in eq.rope_forces.items():
            yield load(f"rope {name}", lugs[name], force.force)
    else:
        for name, tension in eq.tensions.items():
            yield load(f"rope {name}", lugs[name], (0.0, 0.0, tension))
    if eq.afloat is not None and eq.afloat.ground_reaction and scene.ground is not None:
        yield load("ground", np.asarray(scene.ground.contact), (0.0, 0.0, eq.afloat.ground_reaction))


def _sample(shear, moment, grid, extra, tol):
    """Output stations and values: both sides of every jump, the grid and the maxima."""
    lo, hi = shear.span
    xs = np.unique(np.concatenate([shear.breaks, np.linspace(lo, hi, grid + 1), extra]))
    q_left, q_right = shear(xs, "left"), shear(xs, "right")
    m_left, m_right = moment(xs, "left"), moment(xs, "right")
    scale = max(hi - lo, 1.0)
    jump = (np.abs(q_left - q_right) > tol) | (np.abs(m_left - m_right) > tol * scale)
    stations = np.concatenate([xs[jump], xs])
    order = np.argsort(
        np.concatenate([np.zeros(jump.sum()), np.ones(len(xs))])
        + 2 * np.concatenate([np.nonzero(jump)[0], np.arange(len(xs))]),
        kind="stable",
    )
    q = np.concatenate([q_left[jump], q_right])[order]
    m = np.concatenate([m_left[jump], m_right])[order]
    return stations[order], q, m
