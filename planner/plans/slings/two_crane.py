"""Two-crane sling lifts: each crane's hook carries a sling set (2-4 legs, or a spreader bar).

The shipyard's common block lift (README "Sling lifts"). The planner chooses, for each crane,
the candidates its sling takes (:mod:`.rigs`), and which crane takes which.

Physics (statically determinate; checked afterwards on the one casadi rigging model)
------------------------------------------------------------------------------------
* A 2-leg sling of equal legs L on lugs a, b hangs in the vertical plane through a and b:
  the hook is the apex P above the pair's midpoint at h = sqrt(L^2 - (|ab| / 2)^2). A spreader
  rig hangs in the same plane, its sway found from its potential (:func:`.geometry.spreader_hook`).
  A 3- or 4-leg sling fixes its hook to the body (:func:`.geometry.tripod_apex`). The crane
  tip is placed above P, so the hook load is vertical.
* With two hooks the body hangs from the hook line P1 P2. The operators set the tilt along
  that line by the hoist (the design tilt is the tolerance of the body axis nearest to it);
  about the hook line itself the body settles by gravity: the roll that brings the CG under
  the line, which the plan reports and checks against the other tolerance.
* Hook loads by the lever rule along the hook line at each tilt, for every vertex of the CG
  envelope (0027/ND Appendix B's two-crane tilt model); leg tensions from the statics of
  each sling (:func:`.geometry.leg_split`). A spreader bar's weight hangs on its hook: it is
  added to the hook load (and is the hook's rigging weight in the rules' chain).

The search is exhaustive over rigs x rigs x the two assignments, vectorised, so it is exact.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import EquilibriumNotFound, InvalidScene, PlanInfeasible
from liftplan.model.frames import rotation_matrix
from liftplan.model.rules import TiltGeometry, governing_tilt
from liftplan.planner.plans.breakout import BreakoutCase
from liftplan.planner.plans.slings.geometry import leg_split, spreader_hook
from liftplan.planner.plans.slings.lift import SlingLift, bar_weight, hook_tolerances, rules_with_bars
from liftplan.planner.plans.slings.rigs import Rigs, crane_rigs, turned_hooks
from liftplan.planner.problem.clearance import clear, segment_distance
from liftplan.planner.problem.fleet import rule_limits
from liftplan.planner.search.budget import Budget


@dataclass(frozen=True)
class SlingOption:
    """One way to rig the lift: the lugs of each crane's sling.

    Parameters
    ----------
    pairs : tuple of tuple of int
        Candidate indices of each crane's sling (2, 3 or 4), in fleet order.
    apex : numpy.ndarray, shape (2, 3)  [m]
        Each hook at the level attitude, body frame.
    radius, swl : numpy.ndarray, shape (2,)  [m, t]
        Each crane's radius to its hook and its chart SWL there.
    hook_nominal : numpy.ndarray, shape (2,)  [t]
        Hook loads, level, nominal CG (with a spreader bar's weight).
    hook_worst : numpy.ndarray, shape (2,)  [t]
        Largest hook load over the tilt tolerance and the CG envelope.
    sling_angles : tuple of numpy.ndarray  [deg]
        Each crane's lug legs' angles from the horizontal at level.
    legs_nominal, legs_worst : tuple of numpy.ndarray  [t]
        Each crane's lug-leg tensions, level / the largest over the tolerance and CG envelope.
    roll : float  [deg]
        Largest roll about the hook line to bring the CG under it (over the CG envelope).
    worst_value : float  [t or -]
        The objective's worst value: max - min of hook load (spread) or of hook load / SWL.
    worst_tilt : float  [deg]
        The tilt along the hook line where it occurs.
    worst_cog_offset : tuple of 3 float  [m]
        The CG offset (body frame, z-up) where it occurs.
    hook_worst_at : tuple of 2 (float, tuple of 3 float)
        Each crane's largest hook load: the tilt along the hook line [deg] and the CG offset
        (body frame, z-up) [m] where it occurs (not where the objective is worst: the CG at
        one end loads one crane and unloads the other).
    top_legs : tuple of (numpy.ndarray or None)  [t]
        A spreader's two top legs at level (None without a bar).
    top_angles : tuple of (numpy.ndarray or None)  [deg]
    hook_tilt : float  [deg]
        The largest tilt along the hook line the crew's hook errors add on top of the tolerance
        (:func:`hook_error_tilt`); the tilts above are taken within the tolerance plus it.
    """

    pairs: tuple
    apex: np.ndarray
    radius: np.ndarray
    swl: np.ndarray
    hook_nominal: np.ndarray
    hook_worst: np.ndarray
    sling_angles: tuple
    legs_nominal: tuple
    legs_worst: tuple
    roll: float
    worst_value: float
    worst_tilt: float
    worst_cog_offset: tuple
    hook_worst_at: tuple = ()
    top_legs: tuple = (None, None)
    top_angles: tuple = (None, None)
    hook_tilt: float = 0.0


#: The cause of a pair of rigs dropped before the pairs are considered (a lug in both slings).
SHARED = "lugs shared by both slings"
#: The cause of a pair whose boom tips would sit outside a crane's ``boom_height`` range.
BOOM_RANGE = "a boom tip outside its boom_height range"


def _where(loads, tilts, offsets):
    """(tilt [deg], CG offset [m]) of the largest of ``loads`` (CG vertex, tilt)."""
    cg, tilt = np.unravel_index(int(np.argmax(loads)), loads.shape)
    return float(tilts[tilt]), tuple(float(v) for v in offsets[cg])


def _turn(axis, angle, points):
    """Points turned by ``angle`` about a horizontal ``axis`` through the origin (Rodrigues).

    axis : (N, 3) unit; angle : (N,) [rad]; points : (N, 3) -> (N, 3)
    """
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    return points * c + np.cross(axis, points) * s + axis * (axis * points).sum(1, keepdims=True) * (1 - c)


def rig_legs(crane, hook, lugs, load):
    """Lug-leg tensions (and a spreader's top legs) of one rig under a vertical hook load  [t].

    Returns
    -------
    legs : (k,)  [t]
    top : (2,)  [t] or None
    """
    if crane.sling.spreader is None:
        stiff = np.full(len(lugs), crane.sling.EA / crane.sling.length)
        return leg_split(hook, lugs, (0.0, 0.0, load), stiff), None

    bar = crane.sling.spreader
    _, e1, e2 = spreader_hook(
        lugs[:1], lugs[1:], crane.sling.length, bar.length, bar.top_length, load, bar.weight
    )
    ends = np.vstack([e1, e2])
    top = leg_split(hook, ends, (0.0, 0.0, load))
    legs = []
    for j in range(2):  # each end: top leg + bar + bottom leg + half the bar's weight = 0
        up = hook - ends[j]
        force = top[j] * up / np.linalg.norm(up) - np.array([0.0, 0.0, 0.5 * bar.weight])
        along = ends[1 - j] - ends[j]
        down = lugs[j] - ends[j]
        mat = np.column_stack([along / np.linalg.norm(along), down / np.linalg.norm(down)])
        legs.append(np.linalg.lstsq(mat, -force, rcond=None)[0][1])
    return np.array(legs), top


def hook_error_tilt(tolerance, span):
    """The largest tilt along the hook line the crew's hook errors give  [rad].

    One hook high by its tolerance and the other low by its own: atan((delta_1 + delta_2) / span).

    Parameters
    ----------
    tolerance : (2,)  [m]
        Each hook's height tolerance.
    span : float or numpy.ndarray  [m]
        Horizontal distance between the two hooks.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.arctan((tolerance[0] + tolerance[1]) / np.asarray(span, dtype=float))


def uses_slings(problem):
    """Whether ``problem`` is planned by the sling-lift planner (its cranes carry slings)."""
    return any(c.sling is not None for c in problem.fleet)


def plan_two_slings(problem, top=None):
    """Choose each crane's lugs for a two-crane lift on slings or spreader bars.

    Parameters
    ----------
    problem : PlanProblem
        Two cranes, each with a :class:`~liftplan.planner.problem.fleet.SlingSpec`.
    top : int, optional

    Returns
    -------
    SlingPlan

    Raises
    ------
    InvalidScene
        ``plan.search`` asks for a search this plan has not (``mip``, ``local``).
    PlanInfeasible
        No pair of rigs meets the sling angle, reach, the rules' limits and the roll (the
        message counts what ruled them out); or ``plan.time_limit`` ran out before the
        enumeration ended (it stops only whole).
    """

    if problem.search in ("mip", "local"):
        raise InvalidScene(
            f'plan.search = "{problem.search}": a two-crane sling plan enumerates every pair of rigs '
            'and proves its best, with no MIP or local search; expected search = "auto" or "exact"'
        )
    started = time.perf_counter()
    budget = Budget.of(problem.time_limit, started=started)
    top = top or problem.top
    fleet = problem.fleet
    weight = problem.body.weight
    cog = np.array(problem.body.cog)
    offsets = problem.cog_envelope.offsets()
    yaw = rotation_matrix(0.0, 0.0, problem.yaw)
    bars = np.array([bar_weight(c) for c in fleet])
    limits_problem = dataclasses.replace(problem, rules=rules_with_bars(problem))
    counts = {
        "beyond the crane's reach": 0,
        SHARED: 0,
        "hook load over the rules' level limit (code margin)": 0,
        "hook load over the rules' limit within the tolerance": 0,
        "roll about the hook line beyond the tolerance": 0,
        "the two hooks (nearly) coincide": 0,
        "a hook unloaded (the CG beyond a hook)": 0,
        "booms crossing or within plan.crane_clearance in plan": 0,
        BOOM_RANGE: 0,
    }
    per_crane = []
    rig_causes = {"beyond the crane's reach"}  # counts of one crane's rigs, not of pairs
    for crane in fleet:
        rigs = crane_rigs(problem, crane, 0.5 * weight)
        for text, n in rigs.ruled_out.items():
            counts[text] = counts.get(text, 0) + n
            rig_causes.add(text)
        plan_xy = (rigs.hook @ yaw.T)[:, :2]
        radius = crane.radius(plan_xy)
        swl = crane.swl_at(radius)
        reach = ~np.isnan(swl)
        counts["beyond the crane's reach"] += int(np.sum(~reach))
        per_crane.append((rigs.take(reach), radius[reach], swl[reach]))
        _on_time(problem, budget, started)
    (g1, r1, s1), (g2, r2, s2) = per_crane
    if len(g1) == 0 or len(g2) == 0:
        raise PlanInfeasible(_no_plan(problem, counts))
    i1, i2 = np.meshgrid(np.arange(len(g1)), np.arange(len(g2)), indexing="ij")
    i1, i2 = i1.ravel(), i2.ravel()
    shared = (g1.lugs[i1][:, :, None] == g2.lugs[i2][:, None, :]).any(axis=(1, 2))
    counts[SHARED] += int(np.sum(shared))
    i1, i2 = i1[~shared], i2[~shared]
    r1g, r2g = g1.take(i1), g2.take(i2)
    hook1, hook2 = r1g.hook, r2g.hook
    swl = np.stack([s1[i1], s2[i2]], axis=1)
    axis = hook2 - hook1
    axis_h = axis.copy()
    axis_h[:, 2] = 0.0
    length = np.linalg.norm(axis_h, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = axis_h / length[:, None]
    span = np.ptp(problem.points, axis=0).max()
    longitudinal = np.abs(e[:, 0]) >= np.abs(e[:, 1])
    roll_tol = np.where(longitudinal, problem.heel_tolerance, problem.trim_tolerance)
    # the crew's hook errors tilt the body along the hook line on top of the tolerance
    hook_tilt = np.nan_to_num(np.degrees(hook_error_tilt(hook_tolerances(problem), length)))
    tilt_tol = np.where(longitudinal, problem.trim_tolerance, problem.heel_tolerance) + hook_tilt
    tilts = np.stack([-tilt_tol, 0 * tilt_tol, tilt_tol], axis=1)  # (N, 3) deg
    # The operators tilt the body about the horizontal axis square to the hook line; each
    # hook then sits where its rig puts it over the turned lugs (a 2-leg sling or a spreader
    # in the vertical plane of its pair, a 3/4-leg apex turned with the body), and the hook
    # loads follow by the lever rule along the line.
    turn_axis = np.cross(np.array([0.0, 0.0, 1.0]), e)  # + tilt lowers hook 2's side
    loads = np.empty((len(i1), len(offsets), 3, 2))
    for k in range(3):
        angle = np.radians(tilts[:, k])
        hooks = [
            (
                turned_hooks(
                    rigs,
                    crane,
                    problem.points,
                    lambda p, angle=angle: _turn(turn_axis, angle, p),
                    0.5 * weight,
                )
                * e
            ).sum(1)
            for rigs, crane in zip((r1g, r2g), fleet)
        ]
        for m, offset in enumerate(offsets):
            g = (_turn(turn_axis, angle, np.broadcast_to(cog + offset, (len(i1), 3))) * e).sum(1)
            with np.errstate(divide="ignore", invalid="ignore"):
                share2 = weight * (g - hooks[0]) / (hooks[1] - hooks[0])
            loads[:, m, k] = np.stack([weight - share2, share2], axis=-1)  # the body's shares
        _on_time(problem, budget, started)
    nominal = loads[:, 0, 1]  # nominal CG, level
    # roll to bring the CG under the hook line: its offset square to the line, over its depth
    rolls = []
    for offset in offsets:
        g = cog + offset - hook1
        side = g - (g * e).sum(1)[:, None] * e
        lateral = np.linalg.norm(side[:, :2], axis=1)
        rolls.append(np.degrees(np.arctan2(lateral, -side[:, 2])))
    roll = np.max(rolls, axis=0)
    hook_loads = loads + bars  # what each crane carries: the body's share and its bar
    scale = problem.goal.scale(swl)
    scaled = hook_loads * scale[:, None, None, :]
    # reserve: the larger hook load / SWL; otherwise the difference of the two
    values = scaled.max(axis=-1) if problem.goal.peak else np.abs(scaled[..., 0] - scaled[..., 1])
    worst_value = values.reshape(len(values), -1).max(axis=1)
    worst_share = loads.max(axis=(1, 2))
    in_box, level = rule_limits(limits_problem, swl, np.broadcast_to([0, 1], swl.shape))
    bad = np.zeros(len(values), dtype=np.int64)
    checks = [
        (
            (length <= 1e-6 * span) | ~np.all(np.isfinite(loads), axis=(1, 2, 3)),
            "the two hooks (nearly) coincide",
        ),
        (np.any(loads <= 0, axis=(1, 2, 3)), "a hook unloaded (the CG beyond a hook)"),
        (np.any(nominal > level, axis=1), "hook load over the rules' level limit (code margin)"),
        (np.any(worst_share > in_box, axis=1), "hook load over the rules' limit within the tolerance"),
        (roll > roll_tol + 1e-9, "roll about the hook line beyond the tolerance"),
        (~_booms_clear(problem, hook1, hook2, yaw), "booms crossing or within plan.crane_clearance in plan"),
        (~_booms_in_range(problem, np.stack([hook1[:, 2], hook2[:, 2]], axis=1), nominal + bars), BOOM_RANGE),
    ]
    for k, (failed, text) in enumerate(checks, start=1):
        fresh = failed & (bad == 0)
        counts[text] += int(np.sum(fresh))
        bad = np.where(fresh, k, bad)
    good = np.flatnonzero(bad == 0)
    if len(good) == 0:
        raise PlanInfeasible(_no_plan(problem, counts))
    nominal_hooks = nominal + bars
    order = good[np.lexsort((np.ptp(nominal_hooks[good] * scale[good], axis=1), worst_value[good]))][:top]
    ranking = []
    for k in order:
        rigs = (r1g.take([k]), r2g.take([k]))
        flat = int(np.argmax(values[k]))
        cg_k, tilt_k = np.unravel_index(flat, values[k].shape)
        hooks = np.stack([rigs[0].hook[0], rigs[1].hook[0]])
        worst_hook = hook_loads[k].max(axis=(0, 1))
        split = [
            [
                rig_legs(crane, hooks[c], problem.points[rig.lugs[0]], load)
                for load in (nominal_hooks[k, c], worst_hook[c])
            ]
            for c, (crane, rig) in enumerate(zip(fleet, rigs))
        ]
        ranking.append(
            SlingOption(
                pairs=tuple(tuple(int(v) for v in rig.lugs[0]) for rig in rigs),
                apex=hooks,
                radius=np.array([r1[i1[k]], r2[i2[k]]]),
                swl=swl[k],
                hook_nominal=nominal_hooks[k],
                hook_worst=worst_hook,
                sling_angles=tuple(rig.angles[0] for rig in rigs),
                legs_nominal=tuple(s[0][0] for s in split),
                legs_worst=tuple(s[1][0] for s in split),
                roll=float(roll[k]),
                worst_value=float(worst_value[k]),
                worst_tilt=float(tilts[k, tilt_k]),
                worst_cog_offset=tuple(float(v) for v in offsets[cg_k]),
                hook_worst_at=tuple(_where(hook_loads[k][..., c], tilts[k], offsets) for c in range(2)),
                top_legs=tuple(s[0][1] for s in split),
                top_angles=tuple(None if rig.top_angles is None else rig.top_angles[0] for rig in rigs),
                hook_tilt=float(hook_tilt[k]),
            )
        )
    _on_time(problem, budget, started)
    return SlingPlan(
        problem=problem,
        ranking=ranking,
        options=int(len(i1)),
        ruled_out={t: n for t, n in counts.items() if n},
        rig_causes=tuple(t for t in counts if counts[t] and t in rig_causes),
        seconds=time.perf_counter() - started,
    )


def _on_time(problem, budget, started):
    """Raise PlanInfeasible when ``plan.time_limit`` has run out: the enumeration proves its best
    only once every pair of rigs is in, so a part of it is no plan."""
    if budget.out() == "time_limit":
        spent = time.perf_counter() - started
        raise PlanInfeasible(
            f"plan.time_limit = {problem.time_limit:g} s ran out after {spent:.3g} s, "
            "before the enumeration of every pair of rigs ended (it gives a plan only whole); "
            "expected a longer time_limit or none"
        )


def _booms_clear(problem, hook1, hook2, yaw):
    """Per option: the two booms (slew centre to the hook above the rig, in plan) apart by
    ``plan.crane_clearance`` and never crossing (:mod:`liftplan.planner.problem.clearance`);
    all True when a crane has no position."""
    positions = [c.position for c in problem.fleet]
    if any(p is None for p in positions):
        return np.ones(len(hook1), dtype=bool)
    tips = [(h @ yaw.T)[:, :2] for h in (hook1, hook2)]
    starts = [np.broadcast_to(np.asarray(p, dtype=float), t.shape) for p, t in zip(positions, tips)]
    return clear(segment_distance(starts[0], tips[0], starts[1], tips[1]), problem.crane_clearance)


def _booms_in_range(problem, hook_z, hook_loads):
    """Per option: each crane's boom tip at level (hook height + hoist rope l0 + its stretch
    under the level hook load) within its ``boom_height`` range.

    hook_z : (N, 2) [m] the hooks' heights at level, body frame; hook_loads : (N, 2) [t]
    """
    fleet = problem.fleet
    length = np.array([c.rope_length for c in fleet])
    stiffness = np.array([c.stiffness for c in fleet])
    boom = problem.lift_height + hook_z + length + hook_loads / stiffness
    low = np.array([c.boom_min for c in fleet]) - 1e-9
    high = np.array([c.boom_max for c in fleet]) + 1e-9
    with np.errstate(invalid="ignore"):
        return np.all((boom >= low) & (boom <= high), axis=1)


def _option_rigs(problem, option):
    """The chosen option's two rigs as :class:`~.rigs.Rigs` of one rig each (fleet order)."""
    out = []
    for c, crane in enumerate(problem.fleet):
        sling = crane.sling
        kind = "spreader" if sling.spreader is not None else ("fixed" if sling.body_fixed else "pair")
        lugs = np.array([option.pairs[c]], dtype=np.int64)
        out.append(Rigs(kind, lugs, option.apex[c][None, :], np.atleast_2d(option.sling_angles[c])))
    return out


def hooks_breakout(problem, option):
    """The breakout case held by the two hooks of one option (fleet order).

    The body's shares of the breakout load (``total`` at the breakout point) by the lever rule
    along the hook line at level, as the plan takes its hook loads; the crew's hook errors
    (each hook within its tolerance) tilt the body along the hook line by up to
    atan((delta_1 + delta_2) / span) either way, and the shares are taken there too: ``extremes``
    are the least and largest of the three (exact: the lever rule moves one way over so small
    a tilt), ``gain`` the shares' slope per metre of each hook at level. ``hook_shift``: the boom
    rise that takes up each hoist rope's extra stretch (the hook at its planned height).

    Parameters
    ----------
    problem : PlanProblem   with ``breakout_scene``
    option : SlingOption

    Returns
    -------
    BreakoutCase
    """
    load, fleet = problem.breakout, problem.fleet
    total, point = float(load.total), np.asarray(load.point, dtype=float)
    hooks = np.asarray(option.apex, dtype=float)
    line = hooks[1] - hooks[0]
    line[2] = 0.0
    span = float(np.linalg.norm(line))
    e = line / span
    axis = np.cross([0.0, 0.0, 1.0], e)[None, :]
    rigs = _option_rigs(problem, option)

    def shares(angle):
        """The body's shares of the breakout load at a tilt along the hook line [rad]  [t]."""
        a = np.array([angle])

        def turn(p):
            return _turn(axis, a, p)

        along = [
            float((turned_hooks(rig, crane, problem.points, turn, 0.5 * total) * e).sum())
            for rig, crane in zip(rigs, fleet)
        ]
        g = float((_turn(axis, a, point[None, :]) * e).sum())
        second = total * (g - along[0]) / (along[1] - along[0])
        return np.array([total - second, second])

    tolerance = hook_tolerances(problem)
    tilt = float(hook_error_tilt(tolerance, span))
    level = shares(0.0)
    every = np.stack([level, shares(-tilt), shares(tilt)])
    step = 1e-6  # rad: the slope at level by central difference
    slope = (shares(step) - shares(-step)) / (2.0 * step)
    gain = np.outer(slope, [1.0 / span, -1.0 / span])  # + tilt: hook 1 up, hook 2 down
    bars = np.array([bar_weight(c) for c in fleet])
    stiffness = np.array([c.stiffness for c in fleet])
    rules = rules_with_bars(problem)
    return BreakoutCase(
        load=load,
        cranes=tuple(c.name for c in fleet),
        lugs=tuple("+".join(problem.names[i] for i in pair) for pair in option.pairs),
        tensions=level,
        gain=gain,
        hook_tolerance=tolerance,
        hook_shift=(level + bars - np.asarray(option.hook_nominal, dtype=float)) / stiffness,
        swl=np.asarray(option.swl, dtype=float),
        rigging=np.array([rules.rigging_for(c.name) for c in fleet], dtype=float),
        extremes=(every.min(axis=0), every.max(axis=0)),
        min_tension=max(float(problem.min_tension), 0.0),
    )


def _no_plan(problem, counts):
    causes = "; ".join(f"{n} options: {text}" for text, n in counts.items() if n)
    return f"no two rigs among {len(problem.candidates)} candidates can take the two slings ({causes})"


@dataclass(frozen=True)
class SlingPlan(SlingLift):
    """A two-crane sling lift plan: each crane's lugs, hook and boom height.

    Parameters
    ----------
    problem : PlanProblem
    ranking : list of SlingOption
        Best first.
    options : int
        Pairs of rigs (with both assignments) considered: each crane's rigs that pass its own
        checks, paired.
    ruled_out : dict of str to int
        Why the others were ruled out: rigs of one crane for the causes in ``rig_causes``
        (before pairing), pairs for the rest (each pair counted under its first cause).
    rig_causes : tuple of str
        The keys of ``ruled_out`` that count one crane's rigs.
    """

    problem: object
    ranking: list
    options: int
    ruled_out: dict
    rig_causes: tuple = ()
    lengths: object = None
    seconds: float = 0.0

    lift_text = "two-crane slings"

    @property
    def time_text(self):
        """How long the enumeration took, against ``plan.time_limit`` when given."""
        limit = self.problem.time_limit
        within = "" if limit is None else f", within plan.time_limit = {limit:g} s"
        return f"enumeration of every pair of rigs ended in {self.seconds:.2f} s{within}"

    # -- the breakout case and the rope lengths ------------------------------------------------
    @cached_property
    def breakout(self):
        """Each crane's hook at breakout (:func:`hooks_breakout`), None without a breakout case."""
        return None if self.problem.breakout is None else hooks_breakout(self.problem, self.chosen)

    @cached_property
    def ranked_breakouts(self):
        if self.problem.breakout is None:
            return []
        names = self.problem.names
        return [
            ([names[i] for p in r.pairs for i in p], hooks_breakout(self.problem, r)) for r in self.ranking
        ]

    def level_legs(self, c, load):
        """Crane c's lug legs under a vertical hook load ``load`` [t] at level  [t]."""
        lugs = self.problem.points[list(self.groups[c])]
        return rig_legs(self.problem.fleet[c], self.hooks[c], lugs, load)[0]

    @property
    def length_summary(self):
        """(worst value, lower bound, lug names, options considered) for the rope-length
        search's trials: the search over every pair of rigs is exhaustive, so its bound is
        its value."""
        names = self.problem.names
        lugs = tuple(names[i] for g in self.groups for i in g)
        value = float(self.chosen.worst_value)
        return value, value, lugs, int(self.options)

    @property
    def chosen(self):
        return self.ranking[0]

    @property
    def objective(self):
        return self.problem.objective

    # -- the per-crane arrays of SlingLift ------------------------------------------------------
    @property
    def groups(self):
        return self.chosen.pairs

    @property
    def hooks(self):
        return self.chosen.apex

    @property
    def hook_radius(self):
        return self.chosen.radius

    @property
    def hook_swl(self):
        return self.chosen.swl

    @property
    def hook_nominal(self):
        return self.chosen.hook_nominal

    @property
    def hook_worst(self):
        return self.chosen.hook_worst

    @property
    def leg_angles(self):
        return self.chosen.sling_angles

    @property
    def legs_nominal(self):
        return self.chosen.legs_nominal

    @property
    def legs_worst(self):
        """Each lug leg's largest tension  [t]: the larger of the lever rule's worst hook load
        split at the level sling geometry and the rigging model's solve at every vertex of
        the CG envelope and the tilt box (:attr:`posed_legs`, the roll included)."""
        return tuple(np.maximum(a, b) for a, b in zip(self.chosen.legs_worst, self.posed_legs))

    @cached_property
    def posed_legs(self):
        """Each lug leg's largest tension solved on the rigging model  [t] (per crane, (k,)).

        The plan's rigging scene at each of :attr:`held_poses` (:attr:`hung`): the body then
        rolls about the hook line by gravity, as it hangs, and loads the low-side leg more
        (issue 29: an equal split of the worst hook load at the level geometry was 4.4 % low).
        A pose the rigging model does not solve raises its :class:`EquilibriumNotFound`: no
        number is given for it.
        """
        problem = self.problem
        out = [np.zeros(len(g)) for g in self.groups]
        keys = [[f"{name}/{problem.names[i]}" for i in g] for name, g in zip(self.crane_names, self.groups)]
        for hung in self.hung:
            legs = hung.solved.rigging.legs
            for c, names in enumerate(keys):
                out[c] = np.maximum(out[c], [legs[k] for k in names])
        return tuple(out)

    @property
    def held_poses(self):
        """(CG offset [m], boom shifts [m]) of every state the plan holds: the CG at each vertex
        of the CG envelope, the hooks set for the tilt along the hook line at -tol, 0 and +tol,
        tol the tolerance and the hook errors' tilt (:attr:`SlingOption.hook_tilt`; hook 1 raised
        and hook 2 lowered by half the span x tan(tilt))."""
        tilt = self.tolerances[0] + self.chosen.hook_tilt
        for offset in self.problem.cog_envelope.offsets():
            for angle in (-tilt, 0.0, tilt):
                drop = 0.5 * self._span * np.tan(np.radians(angle))
                yield offset, (drop, -drop)

    @property
    def _span(self):
        """Horizontal distance between the two hooks  [m]."""
        return float(np.linalg.norm(self.chosen.apex[1, :2] - self.chosen.apex[0, :2]))

    girder_over = "over the CG envelope and the tilt along the hook line (rigging model)"

    @property
    def hook_tilt_text(self):
        """What the crew's hook errors do to the plan, one sentence (console and report)."""
        tolerance = hook_tolerances(self.problem)
        tilt, total = self.chosen.hook_tilt, self.tolerances[0] + self.chosen.hook_tilt
        if not np.any(tolerance > 0):
            return "hook errors: none (hook tolerance 0 m), no tilt added to the tolerance"
        each = ", ".join(f"{n} +-{d:g} m" for n, d in zip(self.crane_names, tolerance))
        return (
            f"hook errors ({each}) over the {self._span:.2f} m hook line tilt the body up to "
            f"{tilt:.2f} deg more along it: every state is taken within +-{total:.2f} deg"
        )

    def hook_tilt_json(self):
        """The hook errors' tilt along the hook line, for the plan JSON's ``hooks``  [deg, m]."""
        return {
            "tilt_along_hook_line": self.chosen.hook_tilt,
            "span": self._span,
            "tilt_taken": self.tolerances[0] + self.chosen.hook_tilt,
        }

    @property
    def top_legs(self):
        return self.chosen.top_legs

    @property
    def top_angles(self):
        return self.chosen.top_angles

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
    def _rules_tilt(self):
        """(shares at the rules' tilt per crane [t], note): 0027/ND B.1.2's two-crane model,
        the hooks' lift points their level hooks, the worse of the rules' tilt and the hook
        elevation difference over the hook spacing."""

        problem = self.problem
        names = self.crane_names
        offsets = [tuple(map(float, o)) for o in problem.cog_envelope.offsets()]
        vertices = offsets[1:] if len(offsets) > 1 else offsets
        geometry = TiltGeometry(
            {n: tuple(p) for n, p in zip(names, self.chosen.apex)}, problem.body.cog, problem.body.weight
        )
        design_tilt, elevation = problem.rules.design_tilt()
        spacing = geometry.least_spacing()
        try:
            tilt = governing_tilt(design_tilt, elevation, spacing)
            worst = geometry.worst(tilt, vertices)
        except (InvalidScene, EquilibriumNotFound) as err:
            return [None, None], f"rules' tilt not evaluated: {err}"
        note = (
            f"{tilt:.2f} deg: the worse of {design_tilt:g} deg and a {elevation:g} m hook "
            f"elevation difference over the hook spacing {spacing:.2f} m"
        )
        return [float(worst[n].load) for n in names], note

    @property
    def tilt_shares(self):
        return self._rules_tilt[0]

    @property
    def tilt_note(self):
        return self._rules_tilt[1]

    @property
    def worst_utilisation_spread(self):
        worst = self.chosen.hook_worst / self.chosen.swl
        per_swl = self.problem.goal.per_swl and not self.problem.goal.peak
        return self.chosen.worst_value if per_swl else float(abs(worst[0] - worst[1]))

    @cached_property
    def checks(self):
        """The rules' chain per crane and lug, the sling angles, the roll about the hook line,
        and the rigging model's hook loads against the plan's (1 % of W: the plan's lever rule
        takes the hooks where the rig's geometry puts them, the model finds them)."""
        out = self._lift_checks()
        out.append(
            Check.upper(
                "roll",
                "hook line",
                self.chosen.roll,
                self.tolerances[1],
                "deg",
                note="the CG settles under the hook line",
            )
        )
        return out

    def to_json(self):
        """The plan JSON (the contract's keys; labels L1, L2, ... are the lugs)."""
        chosen = self.chosen
        return {
            **self._lift_json(),
            "roll": chosen.roll,
            "worst_attitude": {  # where the objective is worst; CG offset in the file's frame
                "tilt_along_hook_line": chosen.worst_tilt,
                "cog_offset": list(self.in_file_frame(chosen.worst_cog_offset)),
            },
            "worst_hook_load_at": {  # where each crane's hook load is largest
                name: {"tilt_along_hook_line": tilt, "cog_offset": list(self.in_file_frame(offset))}
                for name, (tilt, offset) in zip(self.crane_names, chosen.hook_worst_at)
            },
            "ranking": [
                {
                    "lugs": [self.problem.names[i] for p in r.pairs for i in p],
                    "worst": r.worst_value,
                    "hook_loads": r.hook_nominal.tolist(),
                }
                for r in self.ranking
            ],
            "options": self.options,
            "seconds": self.seconds,
            "ruled_out": self.ruled_out,
            "checks": [c.to_json() for c in self.checks],
        }
