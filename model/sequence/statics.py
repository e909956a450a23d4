"""The body at a held turning angle: a full equilibrium on vertical ropes and a pivot.

Every hook is plumb (it follows so its rope stays vertical), so every crane pulls straight up
and the ground reaction at a pivot is vertical: no force is horizontal, and the body's
equilibrium is three equations, the vertical force and the moments about the two horizontal
axes, each written with the plan positions of the forces' lines of action::

    sum f_k = W,      sum f_k q_k = W g          (q_k, g: plan points, m)

A crane on one lug acts through the lug. A crane on a 2-leg sling acts through the sling's
apex (the hook), which hangs in the vertical plane through its two lugs where the legs
(fixed lengths, tension only) meet; the legs share the hook load by the hook's own balance,
and a leg whose share would be negative is slack (the hook then hangs plumb over the other
lug). The pose is the turn about the stage's body axis (held) and a tilt ``psi`` about the
horizontal world axis across it:

* two supports (two cranes, or a crane and the pivot): the body is free to roll about the line
  between them, so ``psi`` is found (Newton from the last state's tilt) such that the centre
  of gravity is in the vertical plane of the two lines of action; the two forces then follow
  from the lever rule;
* three supports: the three equations give the three forces at ``psi = 0`` (the hooks hold
  the turning axis level);
* four or more: the ropes' stiffness shares the load (:func:`level_share`): each rope's
  stretch is one plane over the plan positions (the hooks set level and moved only as one
  rigid pattern, no twist dialled in), the least elastic energy that balances the body at
  ``psi = 0``; a pivot in contact is rigid (the plane is zero there).

A support whose force would be negative carries nothing: a crane's rope goes slack, or the
body lifts off its pivot; the state is solved again without it. With one support left the
angle cannot be held (the body swings until its centre of gravity is under that support),
unless the centre of gravity is already there: the state says ``held = False``.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import nnls

from liftplan.model.errors import InvalidScene

#: A force above -this x W is taken as zero, not as a slack rope (rounding of the solves).
SLACK_TOL = 1e-9
#: Largest tilt across the turning axis accepted as holding the angle  [deg].
MAX_TILT = 60.0
#: Plan distance below which two lines of action are one (x the body's size)  [-].
COINCIDENT = 1e-9
#: Newton steps of the level share (each piece of its energy is a quadratic: a few suffice).
NEWTON_STEPS = 50
#: Supports from which a stage is statically indeterminate and shared by the ropes' stiffness.
ELASTIC_FROM = 4


def _rot(axis, angle):
    """Rotation matrix about world axis 0, 1 or 2 by ``angle`` rad (right hand)."""
    c, s = math.cos(angle), math.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return r


def pose_matrix(axis, angle, tilt=0.0):
    """Rotation body -> world of a stage at turning ``angle`` and ``tilt``  [deg].

    For axis ``"y"`` the body's +x end rises by ``angle`` (a rotation of -angle about y) and
    the tilt is about world x; for ``"x"`` its +y side rises (+angle about x) and the tilt is
    about world y.
    """
    if axis == "y":
        return _rot(0, math.radians(tilt)) @ _rot(1, -math.radians(angle))
    return _rot(1, math.radians(tilt)) @ _rot(0, math.radians(angle))


@dataclass(frozen=True)
class Support:
    """One support of a stage as the statics sees it.

    Parameters
    ----------
    key : str
        The crane's key, or ``"pivot"``.
    lugs : tuple of str
        The lugs it holds (none for the pivot).
    points : ndarray (k, 3)  [m]
        Body points: the lug (one rope), the two lugs (a sling) or the pivot.
    legs : tuple of float  [m]
        Sling leg lengths (empty for a rope or the pivot).
    """

    key: str
    lugs: tuple
    points: np.ndarray
    legs: tuple = ()

    @property
    def is_pivot(self):
        return self.key == "pivot"


@dataclass(frozen=True)
class Hook:
    """Where a support acts at one pose, and how its force reaches the lugs.

    Parameters
    ----------
    at : ndarray (3,)  [m]
        World point of the line of action: the lug, the sling's apex, or the pivot.
    pulls : ndarray (k, 3)  [-]
        Force on each of the support's lugs per unit of the support's force, world frame.
    slack : tuple of str
        Sling legs (lug names) that carry nothing at this pose.
    """

    at: np.ndarray
    pulls: np.ndarray
    slack: tuple = ()


@dataclass(frozen=True)
class HeldState:
    """The body's equilibrium at one held angle.

    Parameters
    ----------
    angle : float  [deg]
    tilt : float  [deg]
        Rotation across the turning axis found by the equilibrium (0 with three supports).
    held : bool
        The angle is held by the supports that carry load (False: the body would swing).
    forces : dict of str to float  [t]
        Vertical force of each support (crane key, ``"pivot"``), 0 when slack.
    lug_forces : dict of str to ndarray (3,)  [t]
        Force on each loaded lug, body frame.
    legs : dict of str to float  [t]
        Sling leg tensions, keyed ``"CRANE/LUG"``.
    hooks : dict of str to ndarray (3,)  [m]
        World position of each crane's hook (its rope's lower end: the lug, or the sling apex).
    slack : tuple of str
        Cranes whose rope is slack, ``"pivot"`` when the body lifts off, and slack sling legs
        (``"CRANE/LUG"``).
    rotation : ndarray (3, 3)
        Body -> world.
    note : str
        Why the angle is not held, when it is not.
    """

    angle: float
    tilt: float
    held: bool
    forces: dict
    lug_forces: dict
    legs: dict
    hooks: dict
    slack: tuple
    rotation: np.ndarray = field(repr=False)
    note: str = ""


class HeldAngle:
    """The statics of one stage: :meth:`state` solves the body at a held angle.

    Parameters
    ----------
    supports : sequence of Support
    weight : float  [t]
    cog : array (3,)  [m]
        Body frame.
    axis : {"x", "y"}
    anchor : array (3,)  [m]
        Body point that stays where it is at angle 0 (the pivot, else the centre of gravity).
    """

    def __init__(self, supports, weight, cog, axis, anchor, stiffness=None):
        self.supports = tuple(supports)
        self.stiffness = dict(stiffness or {})
        self.weight = float(weight)
        self.cog = np.asarray(cog, dtype=float)
        self.axis = axis
        self.anchor = np.asarray(anchor, dtype=float)
        pts = np.vstack([s.points for s in self.supports] + [self.cog])
        self.size = max(float(np.ptp(pts, axis=0).max()), 1.0)
        self._tilt = 0.0  # continuation: the last state's tilt starts the next Newton

    def world(self, rot, body_points):
        """Body points to world points at rotation ``rot`` (the anchor kept in place)."""
        return self.anchor + (np.atleast_2d(body_points) - self.anchor) @ rot.T

    def hook(self, support, rot):
        """Where ``support`` acts at rotation ``rot``: a :class:`Hook`."""
        pts = self.world(rot, support.points)
        up = np.array([0.0, 0.0, 1.0])
        if not support.legs:
            return Hook(pts[0], up[None, :] if not support.is_pivot else np.zeros((0, 3)))
        return sling_apex(support, pts)

    def state(self, angle, tilt=None):
        """Solve the body at turning ``angle``  [deg]; ``tilt`` starts the tilt's Newton.

        The largest set of supports that holds the body with no negative force carries it
        (among sets of one size, the one with the least tilt); the rest are slack. When no
        two supports can, the body hangs from the support nearest its centre of gravity in
        plan and the angle is not held.
        """
        start = self._tilt if tilt is None else tilt
        supports = list(self.supports)
        sizes = range(len(supports), 1, -1)
        if len(supports) >= ELASTIC_FROM:
            shared = self._elastic(angle)
            if shared is not None:
                return shared
            sizes = (2,)  # the CG is off every taut set at psi = 0: two supports, tilted, or none
        for size in sizes:
            found = []
            for subset in itertools.combinations(supports, size):
                if size == 2 and self._apart(subset, angle):
                    continue
                solved = self._solve(list(subset), angle, start)
                if solved is not None and min(solved[0]) >= -SLACK_TOL * self.weight:
                    found.append((abs(solved[1]), subset, solved))
            if found:
                _, subset, (forces, psi, rot, hooks) = min(found, key=lambda item: item[0])
                chosen = {s.key for s in subset}
                slack = [s.key for s in supports if s.key not in chosen]
                if size == 2:
                    self._tilt = psi
                return self._result(angle, psi, rot, list(subset), forces, hooks, slack, True, "")
        rot = pose_matrix(self.axis, angle, 0.0)
        g = self.world(rot, self.cog)[0][:2]
        only = min(supports, key=lambda s: float(np.linalg.norm(self.hook(s, rot).at[:2] - g)))
        slack = [s.key for s in supports if s.key != only.key]
        return self._single(only, angle, slack)

    def _apart(self, pair, angle):
        """True when two supports on points (no sling) cannot carry the body at any tilt.

        The tilt turns the body about the world's horizontal axis across the turning axis,
        which moves no point along the other horizontal axis: along it the centre of gravity
        must lie between the two lines of action for both forces to be >= 0 (the lever rule).
        """
        if any(s.legs for s in pair):
            return False  # a sling's apex moves along that axis as the lugs tilt
        rot = pose_matrix(self.axis, angle, 0.0)
        along = 0 if self.axis == "y" else 1
        ends = [float(self.world(rot, s.points)[0][along]) for s in pair]
        g = float(self.world(rot, self.cog)[0][along])
        slack = COINCIDENT * self.size
        return not min(ends) - slack <= g <= max(ends) + slack

    # -- four or more supports: the level share of the elastic ropes -----------------------------
    def _elastic(self, angle):
        """The body at ``angle`` and no tilt on four or more supports, or None.

        Each rope's stretch is one plane over the plan positions of the lines of action,
        s_k = c0 + c1 x_k + c2 y_k (the hooks set as if every rope came taut together and were
        then hoisted as one rigid pattern: no twist dialled in), its tension k_k max(0, s_k);
        a pivot in contact is rigid (the plane passes through zero there) and pushes only.
        None when the centre of gravity is outside the plan hull of the supports that could
        carry it (no state at this tilt).
        """
        rot = pose_matrix(self.axis, angle, 0.0)
        hooks = [self.hook(s, rot) for s in self.supports]
        g = self.world(rot, self.cog)[0][:2]
        plan = np.array([h.at[:2] for h in hooks])
        ropes = [i for i, s in enumerate(self.supports) if not s.is_pivot]
        k = np.array([self.stiffness[self.supports[i].key] for i in ropes])
        forces = np.zeros(len(self.supports))
        pivot = [i for i, s in enumerate(self.supports) if s.is_pivot]
        shared = None
        if pivot:  # in contact: the ropes' stretch plane is zero at the pivot, moments about it
            q = plan[pivot[0]]
            shared = level_share((plan[ropes] - q) / self.size, k, self.weight * (g - q) / self.size)
            if shared is not None:
                reaction = self.weight - float(shared.sum())
                if reaction < -SLACK_TOL * self.weight:
                    shared = None  # the pivot would have to pull: the body lifts off it
                else:
                    forces[pivot[0]] = max(reaction, 0.0)
        if shared is None:
            forces[:] = 0.0
            rows = np.hstack([np.ones((len(ropes), 1)), plan[ropes] / self.size])
            shared = level_share(rows, k, self.weight * np.concatenate([[1.0], g / self.size]))
        if shared is None:
            return None
        forces[ropes] = shared
        slack = [s.key for s, f in zip(self.supports, forces) if f <= 0.0]
        return self._result(angle, 0.0, rot, list(self.supports), forces, hooks, slack, True, "")

    # -- the equilibrium with a set of supports ------------------------------------------------
    def _solve(self, active, angle, start):
        if len(active) == 1:
            return None
        if len(active) == 3:
            rot = pose_matrix(self.axis, angle, 0.0)
            hooks = [self.hook(s, rot) for s in active]
            g = self.world(rot, self.cog)[0]
            a = np.vstack([np.ones(3), [h.at[0] for h in hooks], [h.at[1] for h in hooks]])
            rhs = self.weight * np.array([1.0, g[0], g[1]])
            scale = self.size**2
            if abs(np.linalg.det(a)) < COINCIDENT * scale:  # in one vertical plane at this angle
                return None
            return np.linalg.solve(a, rhs), 0.0, rot, hooks
        psi = self._tilt_root(active, angle, start)
        if psi is None:  # the CG cannot be brought into the pair's plane: this pair cannot hold it
            return None
        rot = pose_matrix(self.axis, angle, psi)
        hooks = [self.hook(s, rot) for s in active]
        return self._lever(hooks, rot), psi, rot, hooks

    def _lever(self, hooks, rot):
        g = self.world(rot, self.cog)[0][:2]
        q1, q2 = hooks[0].at[:2], hooks[1].at[:2]
        d = q2 - q1
        f2 = self.weight * float(np.dot(g - q1, d) / np.dot(d, d))
        return np.array([self.weight - f2, f2])

    def _offset(self, active, angle, psi):
        """Signed plan distance of the CG from the line of the two supports  [m]."""
        rot = pose_matrix(self.axis, angle, psi)
        q1, q2 = (self.hook(s, rot).at[:2] for s in active)
        g = self.world(rot, self.cog)[0][:2]
        d = q2 - q1
        length = math.hypot(*d)
        if length < COINCIDENT * self.size:
            return math.nan
        return float(d[0] * (g - q1)[1] - d[1] * (g - q1)[0]) / length

    def _tilt_root(self, active, angle, start):
        """The tilt (deg) that puts the CG in the supports' vertical plane, or None."""
        psi = start
        h = 1e-6
        for _ in range(60):
            f = self._offset(active, angle, psi)
            if not math.isfinite(f):
                return None
            if abs(f) < 1e-12 * self.size:
                return psi if abs(psi) <= MAX_TILT else None
            slope = (self._offset(active, angle, psi + h) - self._offset(active, angle, psi - h)) / (2 * h)
            if not math.isfinite(slope) or abs(slope) < 1e-12 * self.size:
                break
            step = -f / slope
            psi += max(-10.0, min(10.0, step))
            if abs(psi) > 2 * MAX_TILT:
                break
        return self._tilt_scan(active, angle)

    def _offsets(self, pair, angle, tilts):
        """:meth:`_offset` of two supports on points (no sling) at many ``tilts`` (deg)."""
        turned = (np.vstack([s.points[0] for s in pair] + [self.cog]) - self.anchor) @ pose_matrix(
            self.axis, angle, 0.0
        ).T
        axis = 0 if self.axis == "y" else 1  # the world axis the tilt turns about
        other = 1 - axis
        c, sn = np.cos(np.radians(tilts))[:, None], np.sin(np.radians(tilts))[:, None]
        # the plan coordinate the tilt moves: y for a tilt about x (y c - z s), x for one about y
        sign = -1.0 if axis == 0 else 1.0
        moved = turned[None, :, other] * c + sign * turned[None, :, 2] * sn
        fixed = np.broadcast_to(turned[None, :, axis], moved.shape)
        plan = np.stack([fixed, moved], axis=-1) if axis == 0 else np.stack([moved, fixed], axis=-1)
        q1, q2, g = plan[:, 0], plan[:, 1], plan[:, 2]
        d = q2 - q1
        length = np.hypot(d[:, 0], d[:, 1])
        cross = d[:, 0] * (g - q1)[:, 1] - d[:, 1] * (g - q1)[:, 0]
        with np.errstate(invalid="ignore", divide="ignore"):
            out = cross / length
        out[length < COINCIDENT * self.size] = np.nan
        return out

    def _tilt_scan(self, active, angle):
        """Bracket and bisect the tilt when Newton did not converge."""
        grid = np.linspace(-MAX_TILT, MAX_TILT, 241)
        if any(s.legs for s in active):
            vals = [self._offset(active, angle, p) for p in grid]
        else:  # two points: every tilt of the grid at once
            vals = self._offsets(active, angle, grid).tolist()
        roots = []
        for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]):
            if math.isfinite(fa) and math.isfinite(fb) and fa * fb <= 0.0:
                for _ in range(80):
                    m = 0.5 * (a + b)
                    fm = self._offset(active, angle, m)
                    if fa * fm <= 0.0:
                        b = m
                    else:
                        a, fa = m, fm
                roots.append(0.5 * (a + b))
        if not roots:
            return None
        return min(roots, key=abs)

    def _single(self, only, angle, slack):
        """The body on one support: held only if its centre of gravity is on that line."""
        rot = pose_matrix(self.axis, angle, 0.0)
        hooks = [self.hook(only, rot)]
        g = self.world(rot, self.cog)[0][:2]
        off = float(np.linalg.norm(hooks[0].at[:2] - g))
        held = off < 1e-9 * self.size
        note = (
            ""
            if held
            else f"only {only.key} can carry the body, {off:.3g} m in plan from its centre of "
            "gravity: the body swings (the angle is not held)"
        )
        return self._result(angle, 0.0, rot, [only], np.array([self.weight]), hooks, slack, held, note)

    def _result(self, angle, psi, rot, active, forces, hooks, slack, held, note):
        out_forces = {s.key: 0.0 for s in self.supports}
        lug_forces, legs, hook_at, slack_legs = {}, {}, {}, []
        for s in self.supports:
            if not s.is_pivot:
                hook_at[s.key] = self.hook(s, rot).at  # a slack crane's hook still follows
        for s, f, hk in zip(active, forces, hooks):
            f = max(float(f), 0.0)
            out_forces[s.key] = f
            for lug, pull in zip(s.lugs, hk.pulls):
                lug_forces[lug] = rot.T @ (f * pull)
                if s.legs:
                    legs[f"{s.key}/{lug}"] = float(np.linalg.norm(f * pull))
            slack_legs += [f"{s.key}/{lug}" for lug in hk.slack]
        for s in self.supports:
            if s.key not in [a.key for a in active] and s.legs:
                for lug in s.lugs:
                    legs[f"{s.key}/{lug}"] = 0.0
        return HeldState(
            angle=float(angle),
            tilt=float(psi),
            held=bool(held),
            forces=out_forces,
            lug_forces=lug_forces,
            legs=legs,
            hooks=hook_at,
            slack=tuple(slack) + tuple(slack_legs),
            rotation=rot,
            note=note,
        )


def level_share(rows, stiffness, load):
    """Tensions k_k max(0, rows_k . c) that balance ``load``: sum_k T_k rows_k = load, or None.

    The convex potential E(c) = 1/2 sum_k k_k max(0, rows_k . c)^2 - load . c is least at the
    balance; it is bounded below only when ``load`` is in the cone of the rows (the centre of
    gravity inside the plan hull of the supports), which is tested first (non-negative least
    squares). Newton with a backtracking line search, the taut set re-read at every step, then
    one exact solve on the final taut set.

    Parameters
    ----------
    rows : ndarray (n, d)
        Each support's row (1 and its plan lever, scaled), d = 2 or 3.
    stiffness : ndarray (n,)  [t/m]
    load : ndarray (d,)

    Returns
    -------
    ndarray (n,) or None  [t]
    """
    rows, k, b = np.asarray(rows, float), np.asarray(stiffness, float), np.asarray(load, float)
    scale = max(float(np.linalg.norm(b)), 1e-300)
    _, misfit = nnls(rows.T, b)
    if misfit > 1e-12 * scale:
        return None

    def grad(c):
        s = rows @ c
        return (k * np.maximum(s, 0.0)) @ rows - b, s

    def energy(c):
        s = np.maximum(rows @ c, 0.0)
        return 0.5 * float(k @ (s * s)) - float(b @ c)

    c = np.linalg.lstsq((rows.T * k) @ rows, b, rcond=None)[0]
    for _ in range(NEWTON_STEPS):
        f, s = grad(c)
        taut = s > 0.0
        if np.linalg.norm(f) < 1e-14 * scale:
            break
        jac = (rows[taut].T * k[taut]) @ rows[taut]
        step = np.linalg.lstsq(jac, -f, rcond=None)[0] if taut.any() else -f
        if taut.sum() >= rows.shape[1] and np.array_equal(rows @ (c + step) > 0.0, taut):
            c = c + step  # the least of this piece's quadratic, on the same taut set: the balance
            break
        e0, t = energy(c), 1.0
        while t > 1e-12 and energy(c + t * step) > e0 + 1e-4 * t * float(f @ step):
            t *= 0.5
        c = c + t * step
    s = rows @ c
    taut = s > 0.0
    if taut.sum() >= rows.shape[1]:  # polish: the balance on the taut set, exactly
        exact = np.linalg.lstsq((rows[taut].T * k[taut]) @ rows[taut], b, rcond=None)[0]
        if np.all((rows @ exact > 0.0) == taut):
            c = exact
    f, s = grad(c)
    if np.linalg.norm(f) > 1e-10 * scale:
        return None
    return k * np.maximum(s, 0.0)


def sling_apex(support, pts):
    """The hook of a 2-leg sling on lugs ``pts`` (world): apex and the legs' pulls per unit."""
    (l1, l2), (a1, a2) = support.legs, pts
    up = np.array([0.0, 0.0, 1.0])
    d = a2 - a1
    plan = math.hypot(d[0], d[1])
    dist = float(np.linalg.norm(d))
    if dist >= l1 + l2:
        raise InvalidScene(
            f"cranes[{support.key}].sling: legs {l1:g} + {l2:g} m cannot reach lugs {dist:.3g} m apart"
        )
    u = d.copy()
    u[2] = 0.0
    u = u / plan if plan > 1e-12 else np.array([1.0, 0.0, 0.0])
    # in the vertical plane through the lugs: s along u, z up; apex = upper circle intersection
    s2, z2 = plan, d[2]
    a = (l1 * l1 - l2 * l2 + dist * dist) / (2 * dist)
    h2 = l1 * l1 - a * a
    if h2 < 0.0:  # one leg longer than the other plus the spacing: it is slack for good
        h2 = 0.0
    h = math.sqrt(h2)
    es, ez = s2 / dist, z2 / dist
    cands = [(a * es - h * ez, a * ez + h * es), (a * es + h * ez, a * ez - h * es)]
    s_h, z_h = max(cands, key=lambda c: c[1])
    apex = a1 + s_h * u + z_h * up
    v1, v2 = (apex - a1) / l1, (apex - a2) / l2  # unit vectors lug -> apex (legs pull lugs this way)
    m = np.array([[v1 @ u, v2 @ u], [v1[2], v2[2]]])
    try:
        t1, t2 = np.linalg.solve(m, [0.0, 1.0])
    except np.linalg.LinAlgError:
        t1, t2 = -1.0, -1.0
    lugs = support.lugs
    if t1 >= -SLACK_TOL and t2 >= -SLACK_TOL:
        return Hook(apex, np.vstack([max(t1, 0.0) * v1, max(t2, 0.0) * v2]))
    # one leg slack: the hook hangs plumb over the other lug
    keep = 0 if t1 > t2 else 1
    apex = pts[keep] + support.legs[keep] * up
    pulls = np.zeros((2, 3))
    pulls[keep] = up
    return Hook(apex, pulls, slack=(lugs[1 - keep],))
