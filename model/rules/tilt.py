"""Hook loads of a tilted body: rigid-body statics with vertical hoist lines.

The rules' multi-hook tilt (0027/ND Rev 11 5.4, Appendix B.1) asks for each hook's load with
the lifted body tilted by the rules' angle (or by the hook elevation difference). Here the body
is rigid, the hoist lines vertical, and each hook acts at one lift point: a lug, or the point
a hook's sling set acts through (for a pair of lift points, their mid-point).

* Two hooks: determinate. The body hangs with its CG in the vertical plane of the two lift
  points, and each hook carries the lever-rule share of the horizontal distances in that
  plane, as 0027/ND Appendix B.1.2 draws it (the CG's offset out of that plane does not enter).
* Three hooks: determinate, the three equilibrium equations at the tilted pose.
* Four or more: indeterminate; the hoists hold the level preload (the redundant tensions the
  operators set), and the tilt comes from moving the hook pattern as a rigid body, exactly the
  planner's ``held`` model: T = T* + k (dH - dz) with dH = c0 + c1 x + c2 y over the level plan
  positions, dz the lift points' height change from the rotation, and c from the statics at the
  tilted pose. With the lift points at one height and equal stiffness the answer does not
  depend on the stiffness.

Angles in degrees, lengths in m, loads in t. The tilt is a right-handed rotation by ``tilt``
about the horizontal axis at ``direction`` degrees from +x (z-up frame).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.rules.factors import governing_tilt
from liftplan.model.scene.objects import finite, point, positive

_DIRECTIONS = 72  # first sweep of tilt directions (5 deg steps), then golden-section refined
_GOLDEN_STEPS = 48  # bracket of 10 deg shrunk to ~1e-9 deg


def rotation_about(direction, tilt):
    """Rotation by ``tilt`` about the horizontal axis at ``direction`` from +x  (deg -> 3x3)."""
    psi, alpha = math.radians(direction), math.radians(tilt)
    ux, uy = math.cos(psi), math.sin(psi)
    c, s = math.cos(alpha), math.sin(alpha)
    k = np.array([[0.0, 0.0, uy], [0.0, 0.0, -ux], [-uy, ux, 0.0]])
    return np.eye(3) + s * k + (1.0 - c) * (k @ k)


@dataclass(frozen=True)
class TiltGeometry:
    """A body on n vertical hoist lines, for the rules' tilt.

    Parameters
    ----------
    points : dict of str -> tuple of 3 float  [m]
        Each hook's lift point in the body frame (z-up), keyed by the hook's (crane's) name.
    cog : tuple of 3 float  [m]
        Nominal centre of gravity, body frame.
    weight : float  [t]
    preload : dict of str -> float or None  [t]
        Level tensions the hoists hold (nominal CG); needed for four or more hooks.
    stiffness : dict of str -> float or None  [t/m]
        Hoist line stiffness EA / l; needed for four or more hooks whose lift points are not at
        one height (equal stiffness otherwise).
    """

    points: dict
    cog: tuple
    weight: float
    preload: dict | None = None
    stiffness: dict | None = None

    def __post_init__(self):
        if not isinstance(self.points, dict) or len(self.points) < 2:
            raise InvalidScene(f"tilt points = {self.points!r}: expected two or more named lift points")
        object.__setattr__(
            self, "points", {str(k): point(f"tilt points[{k}]", v) for k, v in self.points.items()}
        )
        object.__setattr__(self, "cog", point("tilt cog", self.cog))
        object.__setattr__(self, "weight", positive("tilt weight", self.weight))
        names = list(self.points)
        for key in ("preload", "stiffness"):
            values = getattr(self, key)
            if values is None:
                continue
            if set(values) != set(names):
                raise InvalidScene(
                    f"tilt {key} = {values!r}: expected one value for each of {', '.join(names)}"
                )
            check = positive if key == "stiffness" else finite
            object.__setattr__(self, key, {k: check(f"tilt {key}[{k}]", values[k]) for k in names})
        if self.n >= 4:
            if self.preload is None:
                raise InvalidScene(
                    f"tilt preload: missing; {self.n} hooks are statically indeterminate: expected the level "
                    "tensions the hoists hold"
                )
            heights = self._body[:, 2]
            if self.stiffness is None and np.ptp(heights) > 1e-9 * (1.0 + np.abs(heights).max()):
                raise InvalidScene(
                    "tilt stiffness: missing; the lift points are not at one height, so the held tensions "
                    "depend on the hoist lines' stiffness: expected EA / l per hook [t/m]"
                )

    @property
    def names(self):
        return tuple(self.points)

    @property
    def n(self):
        return len(self.points)

    @property
    def _body(self):
        return np.array([self.points[k] for k in self.points])

    def least_spacing(self):
        """The least plan distance between two lift points  [m]."""
        plan = self._body[:, :2]
        gaps = [np.hypot(*(plan[i] - plan[j])) for i in range(self.n) for j in range(i)]
        return float(min(gaps))

    def spacing_along(self, direction):
        """Extent of the lift points along the direction the body tilts about the axis at
        ``direction`` deg from +x (square to it, in plan)  [m]: the largest plan distance
        between two hooks measured along the tilt, over which a hook elevation difference
        turns into a tilt."""
        psi = math.radians(direction)
        along = self._body[:, :2] @ np.array([-math.sin(psi), math.cos(psi)])
        return float(np.ptp(along))

    def tilt_along(self, direction, tilt, hook_elevation):
        """The rules' tilt about the axis at ``direction``  [deg]: the worse of ``tilt`` and the
        hook elevation difference over the hooks' spacing along the tilt,
        max(tilt, asin(e / s(direction))) (0027/ND Rev 11 5.4, Appendix B.1.2 per direction).

        Raises
        ------
        InvalidScene
            The elevation difference is not less than the spacing along that direction.
        """

        return governing_tilt(tilt, hook_elevation, self.spacing_along(direction))

    def loads(self, tilt=0.0, direction=0.0, cog_offset=(0.0, 0.0, 0.0)):
        """Each hook's load with the body tilted  [t].

        Parameters
        ----------
        tilt : float  [deg]
            For two hooks: the tilt in their vertical plane, > 0 raising the first hook's side.
        direction : float  [deg]
            Axis of the tilt (three or more hooks), from +x.
        cog_offset : tuple of 3 float  [m]
            CG offset from the nominal CG (a CoG-envelope vertex).

        Returns
        -------
        dict of str -> float  [t]

        Raises
        ------
        EquilibriumNotFound
            A hoist line would go slack (negative load): the vertical-line statics no longer hold.
        """
        body = self._body
        cog = np.asarray(self.cog) + np.asarray(point("tilt cog_offset", cog_offset))
        if self.n == 2:
            loads = self._two_hooks(body, cog, finite("tilt", tilt))
        else:
            loads = self._many_hooks(body, cog, rotation_about(direction, tilt))
        if loads.min() < 0.0:
            low = int(np.argmin(loads))
            raise EquilibriumNotFound(
                f"hook {self.names[low]} would carry {loads[low]:.4g} t at tilt {tilt:g} deg (direction "
                f"{direction:g} deg): its line goes slack, the vertical-line statics do not hold"
            )
        return dict(zip(self.names, loads.tolist()))

    def _two_hooks(self, body, cog, tilt):
        along = body[1, :2] - body[0, :2]
        span = float(np.hypot(*along))
        if span <= 0.0:
            raise InvalidScene(
                "tilt points: the two lift points are above one another, expected a plan distance > 0"
            )
        unit = along / span
        s = np.array([0.0, span, float((cog[:2] - body[0, :2]) @ unit)])
        z = np.array([body[0, 2], body[1, 2], cog[2]])
        # rotation in the vertical plane, > 0 raising the first hook's side (its lift point up)
        alpha = math.radians(tilt)
        s_rot = s * math.cos(alpha) + z * math.sin(alpha)
        first = self.weight * (s_rot[1] - s_rot[2]) / (s_rot[1] - s_rot[0])
        return np.array([first, self.weight - first])

    def _many_hooks(self, body, cog, rot):
        world = body @ rot.T
        cog_w = rot @ cog
        a_mat = np.vstack([np.ones(self.n), world[:, 0], world[:, 1]])
        b_vec = self.weight * np.array([1.0, cog_w[0], cog_w[1]])
        if self.n == 3:
            return _solve(a_mat, b_vec)
        preload = np.array([self.preload[k] for k in self.names])
        stiff = (
            np.ones(self.n) if self.stiffness is None else np.array([self.stiffness[k] for k in self.names])
        )
        dz = world[:, 2] - body[:, 2]
        phi0 = np.column_stack([np.ones(self.n), body[:, 0], body[:, 1]])
        base = preload - stiff * dz
        c = _solve(a_mat @ (stiff[:, None] * phi0), b_vec - a_mat @ base)
        return base + stiff * (phi0 @ c)

    def worst(self, tilt, cog_offsets=((0.0, 0.0, 0.0),)):
        """Each hook's largest load over tilt directions (both senses) and CG offsets  [t].

        Two hooks: the tilt in their plane, both senses. Three or more: every horizontal axis,
        a 5 deg sweep refined by golden-section search around each hook's best direction (the
        load is smooth and single-peaked in the direction at a fixed tilt).

        Returns
        -------
        dict of str -> TiltLoad
        """
        out = {}
        for offset in cog_offsets:
            for name, (load, direction) in self._worst_at(tilt, offset).items():
                if name not in out or load > out[name].load:
                    out[name] = TiltLoad(name, load, float(tilt), direction, tuple(map(float, offset)))
        return out

    def worst_per_direction(self, tilt, hook_elevation, cog_offsets=((0.0, 0.0, 0.0),)):
        """Each hook's largest load with the rules' tilt taken per direction  [t].

        About each horizontal axis the body tilts by :meth:`tilt_along`: the worse of ``tilt``
        and the hook elevation difference over the hooks' spacing along that tilt, rather than
        over the least hook spacing about every axis (which :meth:`worst` with
        :func:`~liftplan.model.rules.factors.governing_tilt` does). Two hooks: the same as
        :meth:`worst` (their spacing is along their line).

        Parameters
        ----------
        tilt : float  [deg]
            The rules' tilt (3 deg one vessel, 5 deg separate vessels).
        hook_elevation : float  [m]
            The rules' hook elevation difference (1.0 m).
        cog_offsets : sequence of 3-tuples  [m]

        Returns
        -------
        dict of str -> TiltLoad   (``tilt`` of each: the tilt about its worst direction)
        """
        out = {}

        if self.n > 2:

            def along(direction):
                return self.tilt_along(direction, tilt, hook_elevation)
        else:
            along = governing_tilt(tilt, hook_elevation, self.least_spacing())
        for offset in cog_offsets:
            for name, (load, direction) in self._worst_at(along, offset).items():
                angle = along(direction) if callable(along) else along
                if name not in out or load > out[name].load:
                    out[name] = TiltLoad(name, load, float(angle), direction, tuple(map(float, offset)))
        return out

    def _worst_at(self, tilt, offset):
        """Worst load of each hook over tilt directions; ``tilt`` a number or a function of the
        direction [deg -> deg]."""
        if self.n == 2:
            up, down = self.loads(tilt, 0.0, offset), self.loads(-tilt, 0.0, offset)
            return {k: (up[k], 0.0) if up[k] >= down[k] else (down[k], 180.0) for k in self.names}
        angle = tilt if callable(tilt) else (lambda _d, t=tilt: t)
        step = 360.0 / _DIRECTIONS
        sweep = [self.loads(angle(j * step), j * step, offset) for j in range(_DIRECTIONS)]
        out = {}
        for name in self.names:
            best = max(range(_DIRECTIONS), key=lambda j, name=name: sweep[j][name])
            lo, hi = (best - 1) * step, (best + 1) * step
            ratio = (math.sqrt(5.0) - 1.0) / 2.0
            for _ in range(_GOLDEN_STEPS):
                a, b = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
                if self.loads(angle(a), a, offset)[name] >= self.loads(angle(b), b, offset)[name]:
                    hi = b
                else:
                    lo = a
            direction = 0.5 * (lo + hi)
            load = self.loads(angle(direction), direction, offset)[name]
            if sweep[best][name] > load:
                load, direction = sweep[best][name], best * step
            out[name] = (load, direction % 360.0)
        return out


@dataclass(frozen=True)
class TiltLoad:
    """A hook's worst load at the rules' tilt.

    Parameters
    ----------
    hook : str
    load : float  [t]
    tilt : float  [deg]
    direction : float  [deg]
        Tilt axis from +x (two hooks: 0 = the first hook's side up, 180 = down).
    cog_offset : tuple of 3 float  [m]
        The CoG-envelope vertex where it occurs.
    """

    hook: str
    load: float
    tilt: float
    direction: float
    cog_offset: tuple


def _solve(matrix, rhs):
    try:
        cond = np.linalg.cond(matrix)
    except np.linalg.LinAlgError:
        cond = math.inf
    if not cond < 1e12:
        raise InvalidScene("tilt points: the lift points are collinear in plan, the statics are singular")
    return np.linalg.solve(matrix, rhs)
