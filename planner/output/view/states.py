"""The 3D view's geometry (:class:`~.geometry.LiftView`) of a solved scene, a plan, a lift.

Each builder reads the result it is given (the solved pose, the plan's tensions, the load
curve's equilibria) and never solves again, but for the states a plan names and does not hold
as an equilibrium: a sling plan's level rigging solve (the plan's ``verified`` one) and a
strength plan's level solve of its scene.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from liftplan.model.frames import rotation_matrix
from liftplan.model.scene.hull import box_triangles
from liftplan.model.solve import solve
from liftplan.planner.output.view.geometry import CraneMark, LiftView, Rope, ViewState

#: Rope drawn above a lug whose crane gives no boom height or tip (rigid model), as a
#: fraction of the body's size: the rope's direction is shown, not its length.
STUB = 0.3


# -- the body -------------------------------------------------------------------------------
def body_box(points, cog):
    """Triangles of a box around ``points`` (k, 3) and the CG, body frame  [m]: as deep below
    the CG as the lugs are above it when every lug is above it (deck lugs)."""
    pts = np.vstack([np.asarray(points, dtype=float).reshape(-1, 3), np.asarray(cog, dtype=float)])
    lower, upper = pts.min(axis=0), pts.max(axis=0)
    lower[2] = min(lower[2], 2.0 * cog[2] - upper[2])
    size = float(np.max(upper - lower)) or 1.0
    flat = upper - lower < 1e-3 * size  # a flat side (one row of lugs) gets some thickness
    lower, upper = np.where(flat, lower - 0.05 * size, lower), np.where(flat, upper + 0.05 * size, upper)
    return box_triangles(lower, upper)


def prism(outline, low, high):
    """Triangles of a prism on a plan ``outline`` ((x, y) pairs, body frame) from ``low`` to
    ``high`` [m]: a fan for the top and bottom (the outline is the hull's plan, convex or
    nearly), a quad per side."""
    xy = np.asarray(outline, dtype=float)
    if np.allclose(xy[0], xy[-1]):
        xy = xy[:-1]
    n = len(xy)
    bottom = np.column_stack([xy, np.full(n, low)])
    top = np.column_stack([xy, np.full(n, high)])
    tris = []
    for k in range(1, n - 1):
        tris.append([top[0], top[k], top[k + 1]])
        tris.append([bottom[0], bottom[k + 1], bottom[k]])
    for k in range(n):
        j = (k + 1) % n
        tris.append([bottom[k], bottom[j], top[j]])
        tris.append([bottom[k], top[j], top[k]])
    return np.array(tris)


def _scene_body(scene):
    if scene.hull is not None:
        return np.asarray(scene.hull.triangles), f"hull ({scene.hull.source})"
    return body_box(scene.lug_points(), scene.body.cog), "a box around the lugs and the CG (no hull given)"


def _problem_body(problem):
    points, cog = problem.points, np.asarray(problem.body.cog, dtype=float)
    if problem.outline:
        box = body_box(points, cog).reshape(-1, 3)
        low, high = float(box[:, 2].min()), float(box[:, 2].max())
        return prism(problem.outline, low, high), "the plan outline, from the CG's depth to the lugs"
    return body_box(points, cog), "a box around the candidates and the CG (no outline given)"


def _seabed(scene):
    if scene.ground is None:
        return None
    a = scene.attitude
    return float(
        (rotation_matrix(a.heel, a.trim, a.yaw) @ np.asarray(scene.ground.contact))[2] + a.lift_height
    )


def _t(v):
    return tuple(float(x) for x in v)


# -- a solved scene ---------------------------------------------------------------------------
def solved_state(scene, eq, name):
    """The :class:`ViewState` of ``eq``, an equilibrium of ``scene``.

    The body's place: the inclined and rigging models' solved ``position``; in water, where its
    CG is (``afloat.centre_of_gravity``); else the pose's lift height above the origin in plan.
    A rope's upper end: the crane's tip where given; above the lug where the scene started it
    (inclined and rigging models, whose tips stay put) or where it hangs (vertical ropes) at the
    boom height.
    """
    pose = eq.pose
    rot = rotation_matrix(pose.heel, pose.trim, pose.yaw)
    cog = np.asarray(scene.body.cog, dtype=float)
    if eq.position is not None:
        origin = np.asarray(eq.position, dtype=float)
    elif eq.afloat is not None:
        origin = np.asarray(eq.afloat.centre_of_gravity, dtype=float) - rot @ cog
    else:
        origin = np.array([0.0, 0.0, pose.lift_height])
    names = scene.lug_names
    now = dict(zip(names, scene.lug_points() @ rot.T + origin))
    a = scene.attitude
    start = dict(
        zip(names, scene.lug_points() @ rotation_matrix(a.heel, a.trim, a.yaw).T + [0.0, 0.0, a.lift_height])
    )
    moved_tips = eq.model in ("rigging", "inclined")
    utilisation = eq.utilisation
    ropes, spreaders, tips = [], [], {}
    size = float(np.ptp(scene.lug_points(), axis=0).max()) or 1.0
    for crane in scene.cranes:
        label = crane.label
        if crane.sling is None:
            lower = now[crane.lug]
            below = start[crane.lug] if moved_tips else lower
            upper = _tip(crane, below, lower, size)
            ropes.append(
                Rope(
                    label,
                    "rope",
                    _t(lower),
                    _t(upper),
                    float(eq.tensions[label]),
                    utilisation[label],
                    crane.lug,
                )
            )
            tips[crane.name or label] = _t(upper)
            continue
        rig = eq.rigging
        centre = np.mean([start[n] for n in crane.sling.lugs], axis=0)
        tip = _tip(crane, centre, centre, size)
        hook = np.asarray(rig.hook_positions[label])
        tips[label] = _t(tip)
        ropes.append(Rope(label, "hoist", _t(hook), _t(tip), float(eq.tensions[label]), utilisation[label]))
        spreader = crane.sling.spreader
        ends = rig.spreader_ends.get(label)
        for leg in crane.sling.legs:
            key = f"{label}/{leg.lug}"
            upper = hook if spreader is None else ends[leg.end - 1]
            ropes.append(Rope(key, "leg", _t(now[leg.lug]), _t(upper), float(rig.legs[key]), None, leg.lug))
        if spreader is not None:
            spreaders.append((label, _t(ends[0]), _t(ends[1])))
            for k in (1, 2):
                key = f"{label}/top{k}"
                ropes.append(Rope(key, "top", _t(ends[k - 1]), _t(hook), float(rig.legs[key]), None))
    return ViewState(name, _t3(rot), _t(origin), _t(cog), tuple(ropes), tuple(spreaders), tips)


def _tip(crane, below, lower, size):
    """A crane's boom tip: given, or above ``below`` at the boom height; without either, a
    stub above the lug (:data:`STUB`)."""
    if crane.tip is not None:
        return np.asarray(crane.tip, dtype=float)
    if crane.boom_height is not None:
        return np.array([below[0], below[1], crane.boom_height])
    return np.asarray(lower, dtype=float) + [0.0, 0.0, STUB * size]


def _t3(rot):
    return tuple(tuple(float(v) for v in row) for row in np.asarray(rot))


def _colour(states):
    every = [r.utilisation for s in states for r in s.ropes]
    return "utilisation" if every and all(u is not None for u in every) else "tension"


def _scene_cranes(scene):
    return tuple(CraneMark(c.name or c.label) for c in scene.cranes)


def scene_view(scene, eq, title=None):
    """The view of one solved scene: one state, ``"solved"``."""
    states = (solved_state(scene, eq, f"solved ({eq.model} model)"),)
    return _scene_view(scene, states, title)


def _scene_view(scene, states, title):
    body, source = _scene_body(scene)
    return LiftView(
        title=title or scene.name or "liftplan scene",
        frame=scene.frame,
        body=body,
        body_source=source,
        lugs={lug.name: _t(lug.at) for lug in scene.lugs},
        labels={name: name for name in scene.lug_names},
        cranes=_scene_cranes(scene),
        cog_box=None,
        water_level=scene.water.level if scene.water is not None else None,
        seabed=_seabed(scene),
        states=states,
        colour=_colour(states),
    )


# -- a lift's load curve ------------------------------------------------------------------------
def lift_view(scene, curve, title=None):
    """The view of a load curve: the first hoist, each event (lift-off, breakout, surface,
    clear, ...), the largest crane load and the last hoist, in hoist order, each drawn at the
    curve's equilibrium nearest its hoist (an event's bracket end, within its tolerance)."""
    if not curve.equilibria:
        raise ValueError("lift_view: the load curve carries no equilibria (made without them)")
    hoists = np.asarray(curve.hoist)
    picks = [(0, f"start: hoist {hoists[0]:.2f} m")]
    for event in curve.events:
        k = int(np.argmin(np.abs(hoists - event.hoist)))
        what = event.name if event.subject is None else f"{event.name} ({event.subject})"
        picks.append((k, f"{what}: hoist {hoists[k]:.2f} m"))
    peak = int(np.argmax(curve.tensions.max(axis=1)))
    picks.append((peak, f"largest rope load {curve.tensions[peak].max():.1f} t: hoist {hoists[peak]:.2f} m"))
    picks.append((len(hoists) - 1, f"end: hoist {hoists[-1]:.2f} m"))
    seen, states = set(), []
    for k, name in sorted(picks, key=lambda p: p[0]):
        if k in seen:
            continue
        seen.add(k)
        state = solved_state(scene, curve.equilibria[k], name)
        states.append(dataclasses.replace(state, hoist=float(hoists[k])))
    return _scene_view(scene, tuple(states), title or f"{scene.name or 'lift'}: load curve")


# -- a plan ------------------------------------------------------------------------------------------
def plan_view(plan):
    """The view of any plan: the level plan first, then the worst case it names.

    Held preload (``held``, ``lengths``): the plan's level tensions, then its worst case over
    the tolerance box and CG envelope (``chosen.worst``) with the tensions the held preload
    gives there (:meth:`tensions_at`), the body turned about its origin. Slings: the plan's
    rigging scene solved level (the plan's ``verified``), then the held state of the largest
    leg tension (:attr:`hung`). Other kinds: the level solve of the plan's scene.
    """
    problem = plan.problem
    if plan.kind in ("held", "lengths"):
        states = _held_states(plan)
    elif plan.kind == "slings":
        states = _sling_states(plan)
    else:
        states = (solved_state(plan.scene, solve(plan.scene), "level"),)
    body, source = _problem_body(problem)
    half = np.asarray(problem.cog_envelope.half_widths, dtype=float)
    cog = np.asarray(problem.body.cog, dtype=float)
    chosen = {name: label for label, name in plan.lugs.items()}
    if plan.kind not in ("held", "lengths"):  # scenes by candidate name: keyed as the plan's JSON
        states = tuple(_legs_by_label(s, chosen) for s in states)
    return LiftView(
        title=f"{problem.name or 'plan'}: chosen lugs",
        frame=plan.frame,
        body=body,
        body_source=source,
        lugs=dict(zip(problem.names, (_t(p) for p in problem.points))),
        labels=chosen,
        cranes=tuple(
            CraneMark(c.name, None if c.position is None else _t(c.position)) for c in problem.fleet
        ),
        cog_box=(_t(cog - half), _t(cog + half)) if half.any() else None,
        water_level=None,
        seabed=None,
        states=states,
        colour=_colour(states),
    )


def _legs_by_label(state, labels):
    ropes = tuple(
        dataclasses.replace(r, key=labels[r.lug]) if r.role in ("rope", "leg") and r.lug in labels else r
        for r in state.ropes
    )
    return dataclasses.replace(state, ropes=ropes)


def _held_states(plan):
    problem = plan.problem
    names, labels = plan.lugs, plan.labels
    points = dict(zip(problem.names, problem.points))
    body = np.array([points[names[label]] for label in labels])
    heights, swl, cranes = plan.boom_heights, plan.swl, plan.cranes
    worst = plan.chosen.worst
    cases = [
        ("level", 0.0, 0.0, (0.0, 0.0, 0.0), [plan.tensions[label] for label in labels]),
        (
            f"worst case: heel {worst.heel:+.2f} deg, trim {worst.trim:+.2f} deg, CG offset "
            f"({', '.join(f'{v:+.2f}' for v in plan.in_file_frame(worst.cog_offset))}) m",
            worst.heel,
            worst.trim,
            tuple(worst.cog_offset),
            plan.tensions_at(worst.heel, worst.trim, worst.cog_offset)[0].tolist(),
        ),
    ]
    states = []
    origin = np.array([0.0, 0.0, problem.lift_height])
    for name, heel, trim, offset, tensions in cases:
        rot = rotation_matrix(heel, trim, problem.yaw)
        lugs = body @ rot.T + origin
        ropes, tips = [], {}
        for label, lug, t in zip(labels, lugs, tensions):
            upper = (float(lug[0]), float(lug[1]), float(heights[label]))
            ropes.append(Rope(label, "rope", _t(lug), upper, float(t), float(t) / swl[label], names[label]))
            tips[cranes[label]] = upper
        cog = np.asarray(problem.body.cog, dtype=float) + np.asarray(offset, dtype=float)
        states.append(ViewState(name, _t3(rot), _t(origin), _t(cog), tuple(ropes), (), tips))
    return tuple(states)


def _sling_states(plan):
    level = solved_state(plan.scene, plan.verified, "level")
    solved = [h for h in plan.hung if h.error is None]
    if not solved:
        return (level,)
    worst = max(solved, key=lambda h: max(h.eq.rigging.legs.values()))
    s = worst.state
    offset = ", ".join(f"{v:+.2f}" for v in plan.in_file_frame(s.cog_offset))
    return (level, solved_state(worst.scene, worst.eq, sling_worst_caption(plan, worst.eq, s, offset)))


def sling_worst_caption(plan, eq, state, offset):
    """The caption of a sling plan's worst state on the rigging model: the largest leg tension in
    that state, and the leg table's worst (over every state the plan holds, by the plan's own
    statics, hook errors included) when it differs, so the two numbers are never read as one."""
    here = max(eq.rigging.legs.values())
    table = float(max(np.max(legs) for legs in plan.legs_worst))
    of_table = (
        "the leg table's worst"
        if round(here, 2) == round(table, 2)
        else f"leg table: {table:.2f} t, the plan's own statics over every state it holds"
    )
    return (
        f"worst state on the rigging model: largest leg tension {here:.2f} t in this state ({of_table}); "
        f"heel {state.heel:+.2f} deg, trim {state.trim:+.2f} deg, CG offset ({offset}) m"
    )
