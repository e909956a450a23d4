"""Two-crane sling lifts: each crane's hook carries a 2-leg sling to a pair of lugs.

The shipyard's common block lift (README "Two-crane sling lifts"). The planner chooses, for
each crane, the pair of candidates its sling takes, and which crane takes which pair.

Physics (statically determinate; checked afterwards on the one casadi rigging model)
------------------------------------------------------------------------------------
* Each sling is two equal legs of length L from the hook to lugs a, b: with the sling
  hanging in the vertical plane through a and b, the hook is the apex P above the pair's
  midpoint at h = sqrt(L^2 - (|ab| / 2)^2), and each leg's angle from the horizontal follows.
  The crane tip is placed above P, so the hook load is vertical.
* With two hooks the body hangs from the hook line P1 P2. The operators set the tilt along
  that line by the hoist (the design tilt is the tolerance of the body axis nearest to it);
  about the hook line itself the body settles by gravity: the roll that brings the CG under
  the line, which the plan reports and checks against the other tolerance.
* Hook loads by the lever rule along the hook line at each tilt, for every vertex of the CG
  envelope (0027/ND Appendix B's two-crane tilt model); leg tensions from the statics of
  each sling's triangle.

The candidate pairs are every two candidates whose legs meet the sling-angle limit; the
search is exhaustive over pairs x pairs x the two assignments, vectorised, so it is exact.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from itertools import combinations

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import PlanInfeasible
from liftplan.model.frames import rotation_matrix

#: Crane-code margin over each crane's share for two cranes lifting together.
TWO_CRANE_MARGIN = 0.20


@dataclass(frozen=True)
class SlingOption:
    """One way to rig the lift: a pair of lugs for each crane.

    Parameters
    ----------
    pairs : ((int, int), (int, int))
        Candidate indices of each crane's pair, in fleet order.
    apex : numpy.ndarray, shape (2, 3)  [m]
        Each hook at the level attitude, body frame.
    radius, swl : numpy.ndarray, shape (2,)  [m, t]
        Each crane's radius to its hook and its chart SWL there.
    hook_nominal : numpy.ndarray, shape (2,)  [t]
        Hook loads, level, nominal CG.
    hook_worst : numpy.ndarray, shape (2,)  [t]
        Largest hook load over the tilt tolerance and the CG envelope.
    sling_angles : numpy.ndarray, shape (2, 2)  [deg]
        Each leg's angle from the horizontal at level.
    legs_nominal, legs_worst : numpy.ndarray, shape (2, 2)  [t]
        Leg tensions, level / the largest over the tolerance and the CG envelope.
    roll : float  [deg]
        Largest roll about the hook line to bring the CG under it (over the CG envelope).
    worst_value : float  [t or -]
        The objective's worst value: max - min of hook load (spread) or of hook load / SWL.
    worst_tilt : float  [deg]
        The tilt along the hook line where it occurs.
    worst_cog_offset : tuple of 3 float  [m]
        The CG offset (body frame, z-up) where it occurs.
    """

    pairs: tuple
    apex: np.ndarray
    radius: np.ndarray
    swl: np.ndarray
    hook_nominal: np.ndarray
    hook_worst: np.ndarray
    sling_angles: np.ndarray
    legs_nominal: np.ndarray
    legs_worst: np.ndarray
    roll: float
    worst_value: float
    worst_tilt: float
    worst_cog_offset: tuple


def apex(a, b, length):
    """Hook of an equal-legged 2-leg sling on lugs a, b: in the vertical plane through a and
    b, above them, at ``length`` from both (the sling hinges freely about the line ab, so it
    hangs in that plane whatever the body's attitude)  [m].

    Parameters
    ----------
    a, b : (..., 3)  [m]
    length : float  [m]
    """
    half = 0.5 * np.linalg.norm(b - a, axis=-1)
    along = (b - a) / (2 * half)[..., None]
    up = np.array([0.0, 0.0, 1.0]) - along[..., 2:3] * along  # vertical, square to ab
    up = up / np.linalg.norm(up, axis=-1, keepdims=True)
    return 0.5 * (a + b) + np.sqrt(length**2 - half**2)[..., None] * up


def sling_pairs(problem, crane):
    """Candidate pairs a crane's 2-leg sling can take, with the hook apex and leg angles.

    Returns
    -------
    pairs : (P, 2) int
    apex : (P, 3)  [m]   body frame, level
    angles : (P, 2)  [deg]   legs from the horizontal
    """
    sling = crane.sling
    points = problem.points
    pairs = np.array(list(combinations(range(len(points)), 2)), dtype=np.int64).reshape(-1, 2)
    a, b = points[pairs[:, 0]], points[pairs[:, 1]]
    ok = 0.5 * np.linalg.norm(b - a, axis=1) < sling.length
    pairs, a, b = pairs[ok], a[ok], b[ok]
    top = apex(a, b, sling.length)
    angles = np.degrees(np.arcsin(np.clip(np.stack([top[:, 2] - a[:, 2], top[:, 2] - b[:, 2]],
                                                   axis=1) / sling.length, -1.0, 1.0)))
    return pairs, top, angles


def _turn(axis, angle, points):
    """Points turned by ``angle`` about a horizontal ``axis`` through the origin (Rodrigues).

    axis : (N, 3) unit; angle : (N,) [rad]; points : (N, 3) -> (N, 3)
    """
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    return points * c + np.cross(axis, points) * s + axis * (axis * points).sum(1, keepdims=True) * (1 - c)


def _leg_split(apex, a, b, load):
    """Leg tensions of a 2-leg sling: a vertical load at the apex, legs to a and b  [t].

    Least squares of [u_a u_b] T = (0, 0, load) (exact when the sling's plane is vertical).
    """
    ua, ub = apex - a, apex - b
    ua /= np.linalg.norm(ua, axis=-1, keepdims=True)
    ub /= np.linalg.norm(ub, axis=-1, keepdims=True)
    mat = np.stack([ua, ub], axis=-1)  # (..., 3, 2)
    rhs = np.zeros(mat.shape[:-1])
    rhs[..., 2] = load
    gram = np.einsum("...ki,...kj->...ij", mat, mat)
    return np.linalg.solve(gram, np.einsum("...ki,...k->...i", mat, rhs)[..., None])[..., 0]


def uses_slings(problem):
    """Whether ``problem`` is planned by the sling-lift planner (two cranes)."""
    return problem.cranes == 2


def plan_slings(problem, top=None):
    """Plan a lift whose cranes carry sling sets (see :func:`plan_two_slings`)."""
    return plan_two_slings(problem, top)


def plan_two_slings(problem, top=None):
    """Choose each crane's lug pair for a two-crane lift on 2-leg slings.

    Parameters
    ----------
    problem : PlanProblem
        Two cranes, each with a 2-leg :class:`~liftplan.planner.problem.fleet.SlingSpec`.
    top : int, optional

    Returns
    -------
    SlingPlan

    Raises
    ------
    PlanInfeasible
        No pair of pairs meets the sling angle, reach, SWL, code margin and roll limits; the
        message counts what ruled them out.
    """
    top = top or problem.top
    fleet = problem.fleet
    weight = problem.body.weight
    cog = np.array(problem.body.cog)
    offsets = problem.cog_envelope.offsets()
    yaw = rotation_matrix(0.0, 0.0, problem.yaw)
    limit = problem.min_sling_angle
    options = [sling_pairs(problem, crane) for crane in fleet]
    counts = {"legs shorter than half the pair's spacing": 0, "sling angle below the limit": 0,
              "beyond the crane's reach": 0, "lugs shared by both slings": 0,
              "hook load over SWL / 1.2 (code margin)": 0,
              "a hook load over the SWL within the tolerance": 0,
              "roll about the hook line beyond the tolerance": 0,
              "the two hooks (nearly) coincide": 0, "a hook unloaded (the CG beyond a hook)": 0}
    per_crane = []
    every = len(problem.candidates) * (len(problem.candidates) - 1) // 2
    for crane, (pairs, tops, angles) in zip(fleet, options):
        counts["legs shorter than half the pair's spacing"] += every - len(pairs)
        steep = np.all(angles >= limit - 1e-9, axis=1)
        counts["sling angle below the limit"] += int(np.sum(~steep))
        plan_xy = (tops @ yaw.T)[:, :2]
        radius = crane.radius(plan_xy)
        swl = crane.swl_at(radius)
        reach = ~np.isnan(swl)
        counts["beyond the crane's reach"] += int(np.sum(steep & ~reach))
        keep = steep & reach
        per_crane.append((pairs[keep], tops[keep], angles[keep], radius[keep], swl[keep]))
    (p1, x1, g1, r1, s1), (p2, x2, g2, r2, s2) = per_crane
    if len(p1) == 0 or len(p2) == 0:
        raise PlanInfeasible(_no_plan(problem, counts))
    i1, i2 = np.meshgrid(np.arange(len(p1)), np.arange(len(p2)), indexing="ij")
    i1, i2 = i1.ravel(), i2.ravel()
    shared = (p1[i1][:, :, None] == p2[i2][:, None, :]).any(axis=(1, 2))
    counts["lugs shared by both slings"] += int(np.sum(shared))
    i1, i2 = i1[~shared], i2[~shared]
    hook1, hook2 = x1[i1], x2[i2]
    swl = np.stack([s1[i1], s2[i2]], axis=1)
    axis = hook2 - hook1
    axis_h = axis.copy()
    axis_h[:, 2] = 0.0
    length = np.linalg.norm(axis_h, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = axis_h / length[:, None]
    span = np.ptp(problem.points, axis=0).max()
    longitudinal = np.abs(e[:, 0]) >= np.abs(e[:, 1])
    tilt_tol = np.where(longitudinal, problem.trim_tolerance, problem.heel_tolerance)
    roll_tol = np.where(longitudinal, problem.heel_tolerance, problem.trim_tolerance)
    tilts = np.stack([-tilt_tol, 0 * tilt_tol, tilt_tol], axis=1)  # (N, 3) deg
    # The operators tilt the body about the horizontal axis square to the hook line; each
    # sling then hangs in the vertical plane through its (turned) lugs, so its hook is the
    # apex of the turned pair, and the hook loads follow by the lever rule along the line.
    turn_axis = np.cross(np.array([0.0, 0.0, 1.0]), e)  # + tilt lowers hook 2's side
    lugs = [problem.points[p1[i1]], problem.points[p2[i2]]]  # (N, 2, 3) each
    lengths = [fleet[0].sling.length, fleet[1].sling.length]
    loads = np.empty((len(i1), len(offsets), 3, 2))
    for k in range(3):
        angle = np.radians(tilts[:, k])
        hooks = []
        for lug, length in zip(lugs, lengths):
            a, b = (_turn(turn_axis, angle, lug[:, j]) for j in (0, 1))
            hooks.append((apex(a, b, length) * e).sum(1))  # along the hook line
        for m, offset in enumerate(offsets):
            g = (_turn(turn_axis, angle, np.broadcast_to(cog + offset, (len(i1), 3))) * e).sum(1)
            share2 = weight * (g - hooks[0]) / (hooks[1] - hooks[0])
            loads[:, m, k] = np.stack([weight - share2, share2], axis=-1)
    nominal = loads[:, 0, 1]  # nominal CG, level
    # roll to bring the CG under the hook line: its offset square to the line, over its depth
    rolls = []
    for offset in offsets:
        g = cog + offset - hook1
        side = g - (g * e).sum(1)[:, None] * e
        lateral = np.linalg.norm(side[:, :2], axis=1)
        rolls.append(np.degrees(np.arctan2(lateral, -side[:, 2])))
    roll = np.max(rolls, axis=0)
    scale = np.ones_like(swl) if problem.objective == "spread" else 1.0 / swl
    scaled = loads * scale[:, None, None, :]
    # reserve: the larger hook load / SWL; otherwise the difference of the two
    values = scaled.max(axis=-1) if problem.objective == "reserve" else \
        np.abs(scaled[..., 0] - scaled[..., 1])
    worst_value = values.reshape(len(values), -1).max(axis=1)
    worst_load = loads.max(axis=(1, 2))
    bad = np.zeros(len(values), dtype=np.int64)
    checks = [
        ((length <= 1e-6 * span) | ~np.all(np.isfinite(loads), axis=(1, 2, 3)),
         "the two hooks (nearly) coincide"),
        (np.any(loads <= 0, axis=(1, 2, 3)), "a hook unloaded (the CG beyond a hook)"),
        (np.any(nominal > swl / (1 + TWO_CRANE_MARGIN), axis=1), "hook load over SWL / 1.2 (code margin)"),
        (np.any(worst_load > swl, axis=1), "a hook load over the SWL within the tolerance"),
        (roll > roll_tol + 1e-9, "roll about the hook line beyond the tolerance"),
    ]
    for k, (failed, text) in enumerate(checks, start=1):
        fresh = failed & (bad == 0)
        counts[text] += int(np.sum(fresh))
        bad = np.where(fresh, k, bad)
    good = np.flatnonzero(bad == 0)
    if len(good) == 0:
        raise PlanInfeasible(_no_plan(problem, counts))
    order = good[np.lexsort((np.ptp(nominal[good] * scale[good], axis=1), worst_value[good]))][:top]
    ranking = []
    for k in order:
        a1, a2 = int(i1[k]), int(i2[k])
        flat = int(np.argmax(values[k]))
        cg_k, tilt_k = np.unravel_index(flat, values[k].shape)
        pair_points = [problem.points[list(p1[a1])], problem.points[list(p2[a2])]]
        hooks = np.stack([x1[a1], x2[a2]])
        legs_nominal = np.stack([_leg_split(hooks[c], *pair_points[c], nominal[k, c]) for c in range(2)])
        legs_worst = np.stack([_leg_split(hooks[c], *pair_points[c], worst_load[k, c]) for c in range(2)])
        ranking.append(SlingOption(
            pairs=(tuple(int(v) for v in p1[a1]), tuple(int(v) for v in p2[a2])),
            apex=hooks,
            radius=np.array([r1[a1], r2[a2]]),
            swl=swl[k],
            hook_nominal=nominal[k],
            hook_worst=worst_load[k],
            sling_angles=np.stack([g1[a1], g2[a2]]),
            legs_nominal=legs_nominal,
            legs_worst=legs_worst,
            roll=float(roll[k]),
            worst_value=float(worst_value[k]),
            worst_tilt=float(tilts[k, tilt_k]),
            worst_cog_offset=tuple(float(v) for v in offsets[cg_k]),
        ))
    return SlingPlan(problem=problem, ranking=ranking, options=int(len(i1)),
                     ruled_out={t: n for t, n in counts.items() if n})


def _no_plan(problem, counts):
    causes = "; ".join(f"{n} options: {text}" for text, n in counts.items() if n)
    return (f"no pair of lug pairs among {len(problem.candidates)} candidates can take the two "
            f"slings ({causes})")


@dataclass(frozen=True)
class SlingPlan:
    """A two-crane sling lift plan: each crane's lug pair, hook and boom height.

    Parameters
    ----------
    problem : PlanProblem
    ranking : list of SlingOption
        Best first.
    options : int
        Pairs of pairs (with both assignments) considered.
    ruled_out : dict of str to int
        Why the others were ruled out.
    """

    problem: object
    ranking: list
    options: int
    ruled_out: dict

    @property
    def chosen(self):
        return self.ranking[0]

    @property
    def objective(self):
        return self.problem.objective

    @property
    def tolerances(self):
        """(tilt along the hook line, roll about it)  [deg]: trim and heel for a hook line
        nearer the body's x axis, heel and trim for one nearer its y axis."""
        line = self.chosen.apex[1] - self.chosen.apex[0]
        problem = self.problem
        if abs(line[0]) >= abs(line[1]):
            return problem.trim_tolerance, problem.heel_tolerance
        return problem.heel_tolerance, problem.trim_tolerance

    @cached_property
    def labels(self):
        """Planned lug labels L1..L4: crane 1's pair, then crane 2's."""
        return ("L1", "L2", "L3", "L4")

    def _per_lug(self, values):
        return dict(zip(self.labels, [float(v) for v in np.ravel(values)]))

    @property
    def lugs(self):
        names = self.problem.names
        return dict(zip(self.labels, [names[i] for pair in self.chosen.pairs for i in pair]))

    @property
    def cranes(self):
        """Planned label -> the crane whose sling takes that lug."""
        names = [c.name for c in self.problem.fleet]
        return dict(zip(self.labels, [names[0], names[0], names[1], names[1]]))

    @cached_property
    def hook_heights(self):
        """Hook height above the datum at level, per crane  [m]."""
        return self.problem.lift_height + self.chosen.apex[:, 2]

    @cached_property
    def crane_boom_heights(self):
        """Boom-tip height H per crane: hook height + hoist rope l0 + its stretch  [m]."""
        fleet = self.problem.fleet
        return np.array([self.hook_heights[c] + fleet[c].rope_length
                         + self.chosen.hook_nominal[c] / fleet[c].stiffness for c in range(2)])

    @property
    def boom_heights(self):
        return self._per_lug(np.repeat(self.crane_boom_heights, 2))

    @property
    def tensions(self):
        """Planned label -> leg tension at level, nominal CG  [t]."""
        return self._per_lug(self.chosen.legs_nominal)

    @property
    def spread(self):
        return float(np.ptp(self.chosen.legs_nominal))

    @property
    def worst_spread(self):
        """Largest max - min leg tension found over the tilt tolerance and CG envelope  [t]."""
        return float(np.ptp(self.chosen.legs_worst))

    @property
    def radius(self):
        return self._per_lug(np.repeat(self.chosen.radius, 2))

    @property
    def swl(self):
        return self._per_lug(np.repeat(self.chosen.swl, 2))

    @property
    def utilisation(self):
        """Planned label -> the crane's nominal hook load over its SWL  [-]."""
        return self._per_lug(np.repeat(self.chosen.hook_nominal / self.chosen.swl, 2))

    @property
    def worst_utilisation_spread(self):
        worst = self.chosen.hook_worst / self.chosen.swl
        return self.chosen.worst_value if self.objective == "utilisation" else \
            float(abs(worst[0] - worst[1]))

    @cached_property
    def scene(self):
        """The plan as a rigging scene (hooks free, legs inclined) for ``liftplan solve``."""
        from liftplan.model.rigging_gear import Leg, RiggingLimits, Sling
        from liftplan.model.scene import Analysis, Attitude, Body, Crane, Lug, Scene

        problem, chosen = self.problem, self.chosen
        yaw = rotation_matrix(0.0, 0.0, problem.yaw)
        lugs, cranes = [], []
        for c, (crane, pair) in enumerate(zip(problem.fleet, chosen.pairs)):
            names = [problem.names[i] for i in pair]
            lugs += [Lug(name=n, at=tuple(problem.points[i])) for n, i in zip(names, pair)]
            tip_xy = (yaw @ chosen.apex[c])[:2]
            cranes.append(Crane(
                name=crane.name, EA=crane.EA, rope_length=crane.rope_length,
                boom_height=float(self.crane_boom_heights[c]), swl=float(chosen.swl[c]),
                tip=(float(tip_xy[0]), float(tip_xy[1]), float(self.crane_boom_heights[c])),
                sling=Sling(legs=tuple(Leg(lug=n, length=crane.sling.length, EA=crane.sling.EA)
                                       for n in names)),
            ))
        return Scene(body=Body(problem.body.weight, problem.body.cog), lugs=tuple(lugs),
                     cranes=tuple(cranes),
                     attitude=Attitude(lift_height=problem.lift_height, yaw=problem.yaw),
                     analysis=Analysis(model="rigging"),
                     rigging=RiggingLimits(min_sling_angle=problem.min_sling_angle),
                     name=f"{problem.name or 'plan'}: chosen slings")

    @cached_property
    def verified(self):
        """The plan solved on the rigging model (free hooks, elastic legs): Equilibrium."""
        from liftplan.model.rigging import solve_rigging

        return solve_rigging(self.scene)

    @cached_property
    def checks(self):
        """Per crane: worst hook load against the chart SWL, the 20 % two-crane code margin;
        per leg: the sling angle; the roll about the hook line; the rigging model's hook
        loads against the plan's (1 % of W: the plan's lever rule takes the hooks above the
        pairs' midpoints, the model finds them)."""
        problem, chosen = self.problem, self.chosen
        out = []
        names = [c.name for c in problem.fleet]
        for c, name in enumerate(names):
            out.append(Check.upper("design_load", name, chosen.hook_worst[c], chosen.swl[c], "t",
                                   note=f"worst hook load in the tolerance, SWL at {chosen.radius[c]:.1f} m"))
            margin = chosen.swl[c] / chosen.hook_nominal[c] - 1.0
            out.append(Check.lower("code_margin", name, 100 * margin, 100 * TWO_CRANE_MARGIN, "%",
                                   note="SWL over the nominal share, minus one"))
        for label, angle in zip(self.labels, np.ravel(chosen.sling_angles)):
            out.append(Check.lower("sling_angle", f"{label} ({self.lugs[label]})", angle,
                                   problem.min_sling_angle, "deg", note="from the horizontal"))
        out.append(Check.upper("roll", "hook line", chosen.roll, self.tolerances[1], "deg",
                               note="the CG settles under the hook line"))
        solved = self.verified.tensions
        for c, name in enumerate(names):
            out.append(Check.upper("model_agreement", name, abs(solved[name] - chosen.hook_nominal[c]),
                                   0.01 * problem.body.weight, "t",
                                   note="rigging model hook load vs the plan's lever rule"))
        return out

    def to_json(self):
        """The plan JSON (the contract's keys; labels L1..L4 are the four lugs)."""
        chosen = self.chosen
        return {
            "lugs": self.lugs,
            "boom_heights": self.boom_heights,
            "tensions": self.tensions,
            "spread": self.spread,
            "worst_spread": self.worst_spread,
            "objective": self.objective,
            "cranes": self.cranes,
            "radius": self.radius,
            "swl": self.swl,
            "utilisation": self.utilisation,
            "worst_utilisation_spread": self.worst_utilisation_spread,
            "lift": "two-crane slings",
            "hook_loads": dict(zip([c.name for c in self.problem.fleet], chosen.hook_nominal.tolist())),
            "worst_hook_loads": dict(zip([c.name for c in self.problem.fleet], chosen.hook_worst.tolist())),
            "sling_angles": self._per_lug(chosen.sling_angles),
            "roll": chosen.roll,
            "worst_attitude": {"tilt_along_hook_line": chosen.worst_tilt,
                               "cog_offset": list(chosen.worst_cog_offset)},
            "ranking": [{"lugs": [self.problem.names[i] for p in r.pairs for i in p],
                         "worst": r.worst_value, "hook_loads": r.hook_nominal.tolist()}
                        for r in self.ranking],
            "options": self.options,
            "ruled_out": self.ruled_out,
            "checks": [c.to_json() for c in self.checks],
        }
