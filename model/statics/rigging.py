"""Sling sets and spreader bars: the ``rigging`` model.

A crane with a sling (:mod:`liftplan.model.scene.rigging_gear`) becomes part of the network of
:mod:`liftplan.model.statics.inclined` (the one casadi model of inclined lines):

* its hoist rope is a line from the tip to the **hook**, a free point (3 unknowns);
* each leg is a line from the hook to its lug (tension only: a slack leg carries nothing);
* with a spreader bar, the hook's two top legs run to the bar's **ends**, two more free
  points, and the legs hang from the ends. The bar is a stiff *strut* between its ends
  (tension and compression, EA of the bar) with half its weight at each end.

Why a strut and not a rigid 5-DOF bar: every free point stays a plain point with three
unknowns, so hooks, bar ends and the body's lugs are joined by one kind of member, and the
strut's axial force is its own output (the bar compression to check); a real bar does
shorten elastically, and with the default EA (1e6 t, a stiff steel pipe) the shortening
is millimetres, so the answer differs from a rigid bar's by a few parts in 1e5 of the leg
loads, less than the legs' own stretch. Loads are applied at the ends only, so the bar is
a two-force member either way and the strut loses nothing a rigid bar would carry.

A crane's tip defaults to straight above the centroid of its sling's lugs (at their start
positions: the scene's attitude and lift height) at its boom height; a one-rope crane
keeps the ``inclined`` rule (above its lug). The solve starts from the scene's attitude
with each hook where its legs just reach their lugs, the whole lift raised or lowered so
the hoist ropes carry the weight, then runs Newton, and IPOPT on the energy if Newton's
answer is not a stable upright equilibrium (:mod:`liftplan.model.statics.acceptance`).

An **equalised** 2-leg sling (``equalised = true``: one rope over a sheave at the hook, or an
equaliser) is one continuous rope: both legs carry the same tension and their unstretched
lengths add up to the rope's. The casadi network carries each leg as its own line, whose
unstretched length is a parameter; the split of the rope between the legs is the one more
unknown per sheave, found by Newton on the tension difference around the network solve
(secant slope, each step a full network solve from the last state) until the legs' tensions
agree to :data:`~liftplan.model.statics.acceptance.RESIDUAL_TOL` W. Equal tension means equal strain
T / EA on both sides, so the two legs then are exactly one rope of the total length. It
removes the hook's share of the twist: the pair can no longer load one lug against the other.

Results: ``tensions`` are the cranes' hook loads (hoist-rope tensions), keyed by crane name
(a one-rope crane by its lug); ``rigging`` holds leg tensions (``"CRANE/LUG"``,
``"CRANE/top1"``, ``"CRANE/top2"``), sling angles from the horizontal, hook positions and
spreader compressions. :func:`rigging_checks` flags legs flatter than
``[rigging] min_sling_angle``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.results import Equilibrium, Pose, RiggingState, SolverInfo
from liftplan.model.statics.acceptance import RESIDUAL_TOL
from liftplan.model.statics.inclined import (
    Member,
    RopeForce,
    Topology,
    network_model,
    refuse_water,
    start_pose,
)


@dataclass(frozen=True)
class _Part:
    """One member of the network as the results name it."""

    key: str  # crane label, "CRANE/LUG", "CRANE/top1|2" or "CRANE/spreader"
    role: str  # "hoist", "leg", "top" or "bar"
    crane: str  # crane label
    lug: str | None = None


class _Builder:
    """Collects points, members and start positions for one scene."""

    def __init__(self, scene):
        self.scene = scene
        self.lug_index = {name: k for k, name in enumerate(scene.lug_names)}
        a = scene.attitude
        rot = rotation_matrix(a.heel, a.trim, a.yaw)
        self.lug_start = scene.lug_points() @ rot.T + [0.0, 0.0, a.lift_height]
        self.tips, self.free, self.weights = [], [], []
        self.members, self.parts, self.lengths, self.stiffness = [], [], [], []
        self.hooks = {}  # crane label -> free index
        self.bars = {}  # crane label -> (free index of end 1, end 2)
        self.hoists = []  # (tip index, upper end of the hoist rope, l0, EA)
        self.sheaves = []  # (member index of leg 1, of leg 2, the rope's unstretched length)

    def add_free(self, position, weight=0.0):
        self.free.append(np.asarray(position, dtype=float))
        self.weights.append(weight)
        return ("free", len(self.free) - 1)

    def add(self, kind, a, b, length, stiffness, part):
        self.members.append(Member(kind, a, b))
        self.lengths.append(length)
        self.stiffness.append(stiffness)
        self.parts.append(part)

    def lug(self, name):
        return ("lug", self.lug_index[name])

    def tip(self, crane, below):
        """The crane's tip: given, or above ``below`` (plan) at the boom height."""
        if crane.tip is not None:
            self.tips.append(np.asarray(crane.tip, dtype=float))
        elif crane.boom_height is not None:
            self.tips.append(np.array([below[0], below[1], crane.boom_height]))
        else:
            raise InvalidScene(f"cranes[{crane.label}]: expected tip = [x, y, z] or boom_height")
        return ("tip", len(self.tips) - 1)

    def crane(self, crane):
        length = _need(crane, "rope_length")
        stiffness = _need(crane, "EA")
        label = crane.label
        if crane.sling is None:
            start = self.lug_start[self.lug_index[crane.lug]]
            tip = self.tip(crane, start)
            self.add(
                "line", self.lug(crane.lug), tip, length, stiffness, _Part(label, "hoist", label, crane.lug)
            )
            self.hoists.append((tip[1], ("lug", self.lug_index[crane.lug]), length, stiffness))
            return
        sling = crane.sling
        lugs = np.array([self.lug_start[self.lug_index[name]] for name in sling.lugs])
        centre = lugs.mean(axis=0)
        tip = self.tip(crane, centre)
        if sling.spreader is None:
            height = _hang_height([(leg, lugs[k], centre) for k, leg in enumerate(sling.legs)])
            hook = self.add_free((centre[0], centre[1], height))
            first = len(self.members)
            for leg in sling.legs:
                self.add(
                    "line",
                    self.lug(leg.lug),
                    hook,
                    leg.length,
                    leg.stiffness,
                    _Part(f"{label}/{leg.lug}", "leg", label, leg.lug),
                )
            if sling.equalised:
                self.sheaves.append((first, first + 1, sling.rope_length))
        else:
            bar = sling.spreader
            ends_plan = [lugs[[leg.end == e for leg in sling.legs]].mean(axis=0)[:2] for e in (1, 2)]
            axis = ends_plan[1] - ends_plan[0]
            axis = axis / np.linalg.norm(axis) if np.linalg.norm(axis) > 1e-9 else np.array([1.0, 0.0])
            middle = 0.5 * (ends_plan[0] + ends_plan[1])
            ends = [middle - 0.5 * bar.length * axis, middle + 0.5 * bar.length * axis]
            height = _hang_height([(leg, lugs[k], ends[leg.end - 1]) for k, leg in enumerate(sling.legs)])
            points = [self.add_free((e[0], e[1], height), 0.5 * bar.weight) for e in ends]
            top = max(
                math.sqrt(max(leg.length**2 - (0.5 * bar.length) ** 2, (0.05 * leg.length) ** 2))
                for leg in bar.top
            )
            hook = self.add_free((middle[0], middle[1], height + top))
            self.bars[label] = (points[0][1], points[1][1])
            for k, leg in enumerate(bar.top):
                self.add(
                    "line",
                    points[k],
                    hook,
                    leg.length,
                    leg.stiffness,
                    _Part(f"{label}/top{k + 1}", "top", label),
                )
            self.add(
                "strut", points[0], points[1], bar.length, bar.EA, _Part(f"{label}/spreader", "bar", label)
            )
            for leg in sling.legs:
                self.add(
                    "line",
                    self.lug(leg.lug),
                    points[leg.end - 1],
                    leg.length,
                    leg.stiffness,
                    _Part(f"{label}/{leg.lug}", "leg", label, leg.lug),
                )
        self.add("line", hook, tip, length, stiffness, _Part(label, "hoist", label))
        self.hooks[label] = hook[1]
        self.hoists.append((tip[1], hook, length, stiffness))

    def start(self):
        """The body at the scene's attitude and the free points where the legs just reach,
        all raised by the heave s at which the hoist ropes (stiffness EA / l0 each) carry the
        weight: sum k_c (e_c - s) = W + bars, e_c the rope's stretch before the shift. Each
        level below a hook is then lowered by its legs' estimated stretch under an equal
        share of the weight, so that no leg starts exactly at its unstretched length (where
        a tension-only line has no stiffness and Newton's first step would be singular)."""
        total = self.scene.body.weight + sum(self.weights)
        stiff, stretched = [], []
        for tip, upper, length, stiffness in self.hoists:
            at = self.free[upper[1]] if upper[0] == "free" else self.lug_start[upper[1]]
            stiff.append(stiffness / length)
            stretched.append(np.linalg.norm(self.tips[tip] - at) - length)
        stiff = np.array(stiff)
        heave = (stiff @ np.array(stretched) - total) / stiff.sum()
        share = total / len(self.hoists)
        free = [f + [0.0, 0.0, heave] for f in self.free]
        sags = [0.0]
        for label, hook in self.hooks.items():
            below = self.sag(hook, share)
            if label in self.bars:
                ends = self.bars[label]
                for k in ends:
                    free[k][2] -= below
                below += max(self.sag(k, share / 2) for k in ends)
            sags.append(below)
        x0 = start_pose(self.scene)
        x0[2] += heave - float(np.mean(sags))
        return np.concatenate([x0, np.ravel(free)]) if free else x0

    def sag(self, upper, load):
        """Vertical stretch of the lines hanging from free point ``upper`` under ``load``
        shared equally among them  [m] (a start estimate)."""
        drops = []
        hanging = [
            (m, length, ea)
            for m, length, ea in zip(self.members, self.lengths, self.stiffness)
            if m.kind == "line" and m.b == ("free", upper)
        ]
        for member, length, stiffness in hanging:
            lower = self.free[member.a[1]] if member.a[0] == "free" else self.lug_start[member.a[1]]
            sine = max(0.2, min(1.0, (self.free[upper][2] - lower[2]) / length))
            drops.append(load / len(hanging) * length / (stiffness * sine**2))
        return float(np.mean(drops)) if drops else 0.0


def _need(crane, field):
    value = getattr(crane, field)
    if value is None:
        raise InvalidScene(
            f"cranes[{crane.label}].{field}: missing, the rigging model needs it for every crane"
        )
    return value


def _hang_height(legs):
    """Height at which every leg (leg, lug start, plan point above) just reaches its lug; a
    leg shorter than its plan distance is taken as nearly flat (the solve sorts it out)."""
    heights = []
    for leg, lug, above in legs:
        reach = math.hypot(lug[0] - above[0], lug[1] - above[1])
        heights.append(lug[2] + math.sqrt(max(leg.length**2 - reach**2, (0.05 * leg.length) ** 2)))
    return max(heights)


def solve_rigging(scene):
    """Equilibrium of the body, the hooks and the spreader bars on inclined lines.

    Parameters
    ----------
    scene : Scene
        Every crane with ``rope_length``, ``EA`` (of the hoist rope, or of the one rope to
        its lug) and ``boom_height`` or ``tip``; two or more cranes; no hull.

    Returns
    -------
    Equilibrium
        ``model = "rigging"``; ``tensions`` the hook loads by crane, ``rigging`` the legs,
        sling angles, hooks and bars, ``rope_forces`` the hoist ropes' pulls (side loads),
        ``position`` the body origin's world position.

    Raises
    ------
    InvalidScene
        Missing crane data, a hull, or a single crane (the body could turn freely about its
        hoist rope: its yaw is undetermined).
    EquilibriumNotFound
        No stable upright equilibrium found.
    """
    refuse_water(scene, "cranes.sling: slings")
    if len(scene.cranes) < 2:
        raise InvalidScene(
            f"cranes[{scene.cranes[0].label}]: one crane holds the body, which could then turn "
            "freely about its hoist rope (its yaw is undetermined); expected two or more cranes"
        )
    build = _Builder(scene)
    for crane in scene.cranes:
        build.crane(crane)
    x0 = build.start()
    topology = Topology(scene.n, len(build.tips), len(build.free), tuple(build.members))
    body = scene.body
    p = topology.pack(
        scene.lug_points(),
        np.array(build.tips),
        build.lengths,
        build.stiffness,
        build.weights,
        body.weight,
        body.cog,
        max(scene.plan_diameter, 1.0),
    )
    model = network_model(topology)
    x, info = model.solve(x0, p, "rigging")
    if build.sheaves:
        x, p, info = _equalise(scene, build, topology, model, x, p, info)
    residual, tensions, pulls, spans = (np.asarray(v) for v in model.evaluate(x, p))
    return _result(scene, build, x, residual.ravel(), tensions.ravel(), pulls, spans.ravel(), info)


#: Newton steps on the sheaves' rope splits before the solve gives up.
SHEAVE_STEPS = 30


def _equalise(scene, build, topology, model, x, p, info):
    """Split each sheave's rope between its two legs so that both carry one tension.

    Unknowns: s_k, leg 1's unstretched share of sheave k's rope (leg 2 has L_k - s_k).
    Residual: T_1k - T_2k. Newton with a finite-difference Jacobian (one network solve per
    sheave and step, each from the last accepted state), the step kept inside (0, L_k).

    Returns
    -------
    x, p, info : the equalised state, its parameters, the last solve's SolverInfo
    """
    import time

    begin = time.perf_counter()
    offset = 3 * topology.lugs + 3 * topology.tips  # the unstretched lengths in p
    legs = np.array([[a, b] for a, b, _ in build.sheaves])
    totals = np.array([total for _, _, total in build.sheaves])
    weight = scene.body.weight
    iterations = info.iterations

    def state(split, start):
        q = p.copy()
        q[offset + legs[:, 0]] = split
        q[offset + legs[:, 1]] = totals - split
        y, inner = model.solve(start, q, "rigging")
        tension = np.asarray(model.evaluate(y, q)[1]).ravel()
        return y, q, tension[legs[:, 0]] - tension[legs[:, 1]], inner

    split = p[offset + legs[:, 0]].copy()
    x, p, gap, inner = state(split, x)
    for _ in range(SHEAVE_STEPS):
        iterations += inner.iterations
        if np.max(np.abs(gap)) <= RESIDUAL_TOL * weight:
            return x, p, SolverInfo(info.method, True, iterations, info.seconds + time.perf_counter() - begin)
        step = 1e-6 * totals
        jacobian = np.empty((len(totals), len(totals)))
        for k in range(len(totals)):
            trial = split.copy()
            trial[k] += step[k]
            jacobian[:, k] = (state(trial, x)[2] - gap) / step[k]
        move = np.linalg.solve(jacobian, -gap)
        # stay strictly inside the rope: a leg of zero length has no direction
        limit = np.where(move > 0, (totals - split) * 0.9, split * 0.9)
        move = np.sign(move) * np.minimum(np.abs(move), limit)
        split = split + move
        x, p, gap, inner = state(split, x)
    raise EquilibriumNotFound(
        f"rigging: the equalised slings' legs did not reach one tension within {SHEAVE_STEPS} steps "
        f"(difference {np.max(np.abs(gap)):.3g} t); check the legs can reach their lugs"
    )


def _result(scene, build, x, residual, tensions, pulls, spans, info):
    rot = rotation_matrix(*np.degrees(x[3:6]))
    world = {
        "lug": scene.lug_points() @ rot.T + x[:3],
        "tip": np.array(build.tips),
        "free": x[6:].reshape(-1, 3),
    }

    def at(end):
        return world[end[0]][end[1]]

    hook_loads, swl, forces, slack = {}, {}, {}, []
    legs, angles, leg_lugs, compression = {}, {}, {}, {}
    for member, part, tension, pull in zip(build.members, build.parts, tensions, pulls.T):
        if part.role == "bar":
            compression[part.crane] = -float(tension)
            continue
        if tension <= 0.0:
            slack.append(part.key)
        if part.role == "hoist":
            hook_loads[part.key] = float(tension)
            forces[part.key] = RopeForce.of(pull)
            continue
        d = at(member.b) - at(member.a)
        legs[part.key] = float(tension)
        angles[part.key] = math.degrees(math.asin(min(1.0, abs(d[2]) / np.linalg.norm(d))))
        leg_lugs[part.key] = part.lug
    for crane in scene.cranes:
        swl[crane.label] = crane.swl
    state = RiggingState(
        legs=legs,
        sling_angles=angles,
        leg_lugs=leg_lugs,
        hook_positions={label: tuple(float(v) for v in world["free"][k]) for label, k in build.hooks.items()},
        spreader_compression=compression,
        spreader_ends={
            label: tuple(tuple(float(v) for v in world["free"][k]) for k in ends)
            for label, ends in build.bars.items()
        },
        min_sling_angle=scene.rigging.min_sling_angle,
    )
    return Equilibrium(
        model="rigging",
        pose=Pose(
            heel=math.degrees(x[3]), trim=math.degrees(x[4]), yaw=math.degrees(x[5]), lift_height=float(x[2])
        ),
        tensions=hook_loads,
        weight=scene.body.weight,
        swl=swl,
        slack=tuple(slack),
        residual=float(np.max(np.abs(residual))) * scene.body.weight,
        solver=info,
        rope_forces=forces,
        position=(float(x[0]), float(x[1]), float(x[2])),
        rigging=state,
        frame=scene.frame,
    )


def rigging_checks(scene, eq):
    """Sling-angle checks of a solved scene: one per leg, failed below the limit.

    Parameters
    ----------
    scene : Scene
        Its ``rigging.min_sling_angle`` [deg from the horizontal] is the limit.
    eq : Equilibrium
        From :func:`liftplan.model.solve`; no checks unless it has ``rigging``.

    Returns
    -------
    list of Check
        ``Check.lower("sling_angle", "CRANE/LUG", angle, limit, "deg")`` per leg, spreader top
        legs included, in crane and leg order.
    """
    if eq.rigging is None:
        return []
    limit = scene.rigging.min_sling_angle
    return [
        Check.lower("sling_angle", key, angle, limit, "deg", note="leg angle from the horizontal")
        for key, angle in eq.rigging.sling_angles.items()
    ]
