"""The 3D view of a sequence: every reported angle of every stage a state of the view's slider."""

from __future__ import annotations

import numpy as np

from liftplan.model.sequence import pose_matrix
from liftplan.planner.output.view.geometry import CraneMark, LiftView, Rope, ViewState
from liftplan.planner.output.view.states import STUB, body_box


def _t(v):
    return tuple(float(x) for x in v)


def sequence_view(result):
    """A :class:`~liftplan.planner.output.view.geometry.LiftView` of a swept sequence.

    Each state is one grid angle of one stage, named ``"STAGE: ANGLE deg"``: the body at its
    turn and tilt, the anchor (pivot, else centre of gravity) where it is at angle 0, each
    crane's rope (or sling legs and hoist rope) to its hook, the hoist drawn as a short stub
    straight up (the hooks follow; no boom tip is fixed). Ropes are coloured by utilisation
    where every crane has an SWL, else by tension.

    Parameters
    ----------
    result : liftplan.model.sequence.SequenceResult
    """
    seq = result.sequence
    points = np.array([lug.at for lug in seq.lugs], dtype=float)
    cog = np.asarray(seq.body.cog, dtype=float)
    size = float(np.ptp(np.vstack([points, cog]), axis=0).max()) or 1.0
    states, ground = [], None
    for stage_result in result.stages:
        stage = stage_result.stage
        anchor = np.asarray(stage.pivot if stage.pivot is not None else cog, dtype=float)
        if stage.pivot is not None:
            ground = float(anchor[2]) if ground is None else min(ground, float(anchor[2]))
        move = stage.kind == "move"
        for state in stage_result.states:
            if move:  # the body where its elastic ropes hold it, each rope up to its boom tip
                rot = np.asarray(state.rotation, dtype=float)
                origin = np.asarray(state.origin, dtype=float)
            else:
                rot = pose_matrix(stage.axis, state.angle, state.tilt)
                origin = anchor - rot @ anchor
            ropes = []
            for key in stage.cranes:
                crane = seq.crane(key)
                load = state.hook_loads[key]
                use = load / crane.swl if crane.swl is not None else None
                hook = np.asarray(state.hooks[key])
                top = hook + [0.0, 0.0, STUB * size]
                if move and crane.sling is None:
                    at = rot @ np.asarray(seq.lug(crane.lug).at) + origin
                    ropes.append(Rope(key, "rope", _t(at), _t(hook), load, use, crane.lug))
                    continue
                if move:  # the hoist rope from the sling's hook up to the boom tip
                    hook, top = np.asarray(state.sling_hooks[key]), hook
                if crane.sling is None:
                    ropes.append(Rope(key, "rope", _t(hook), _t(top), load, use, crane.lug))
                    continue
                ropes.append(Rope(key, "hoist", _t(hook), _t(top), load, use))
                for name in crane.lugs:
                    at = rot @ np.asarray(seq.lug(name).at) + origin
                    tension = state.sling_tensions[f"{key}/{name}"]
                    ropes.append(Rope(f"{key}/{name}", "leg", _t(at), _t(hook), tension, None, name))
            states.append(
                ViewState(
                    f"{stage.where}: s = {state.angle:g}" if move else f"{stage.where}: {state.angle:g} deg",
                    tuple(tuple(float(v) for v in row) for row in rot),
                    _t(origin),
                    _t(cog),
                    tuple(ropes),
                )
            )
    every = [r.utilisation for s in states for r in s.ropes if r.role != "leg"]
    return LiftView(
        title=seq.name or "lift sequence",
        frame=seq.frame,
        body=body_box(points, cog),
        body_source="a box around the lugs and the centre of gravity",
        lugs={lug.name: _t(lug.at) for lug in seq.lugs},
        labels={lug.name: lug.name for lug in seq.lugs},
        cranes=tuple(CraneMark(key) for key in seq.crane_keys),
        cog_box=None,
        water_level=None,
        seabed=ground,
        states=tuple(states),
        colour="utilisation" if every and all(u is not None for u in every) else "tension",
    )
