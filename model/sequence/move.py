"""A ``kind = "move"`` stage: boom tips moved, the body solved on its elastic ropes at each state.

Each crane named in the stage's ``moves`` has its boom tip moved in a straight line from where
it starts to its end position (``to``, else where it starts, raised by ``hoist``), over a stage
parameter s from 0 to 1; the other cranes' tips stay. A move that opens the sequence starts
from the file (each crane's ``tip``, else above its lug, or its sling's lugs, at its
``boom_height``); a later one where the stage before left the body and the tips
(:class:`ChainStart`), its scene written in that frame. At every s the body's equilibrium is
that of :func:`liftplan.model.solve.solve` on the scene of the stage's cranes with their tips
there:

* tips that only rise and fall (no ``to``, no ``tip`` in the file, no sling): the ``elastic``
  model, vertical ropes from the boom heights H_i + s hoist_i;
* a tip moved in plan (``to``) or placed in the world (``tip``): the ``inclined`` model, every
  rope from its tip to its lug (the body swings until the rope directions balance); a crane on
  a 2-leg sling: the ``rigging`` model (hoist rope to a free hook, elastic legs);
* on a ``pivot`` (vertical ropes only), :mod:`liftplan.model.sequence.pivoted` while the ground
  pushes, the ``elastic`` model once the body lifts off.

All are elastic (T = EA max(0, stretch) / l0): four or more ropes share the load as their
stretches decide, and a rope whose stretch falls to zero is slack and carries nothing. A state
the solver cannot hold (fewer than three taut ropes, no convergence) raises
:class:`~liftplan.model.errors.EquilibriumNotFound` naming the parameter: no number is made up.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from liftplan.model.errors import EquilibriumNotFound
from liftplan.model.frames import rotation_matrix
from liftplan.model.scene.objects import Scene
from liftplan.model.sequence.objects import crane_key
from liftplan.model.sequence.pivoted import OnPivot
from liftplan.model.sequence.states import LugLoad, SequenceState
from liftplan.model.sequence.statics import Support, sling_apex
from liftplan.model.solve import solve


def start_tip(sequence, crane):
    """Where a crane's boom tip is at the start of a move stage that opens the sequence
    (world, ``z-up``)  [m]."""
    if crane.tip is not None:
        return np.array(crane.tip, dtype=float)
    # one rope: above its lug; a sling: above the centroid of its lugs (as liftplan solve puts it)
    at = np.mean([sequence.lug(name).at for name in crane.lugs], axis=0)
    return np.array([at[0], at[1], crane.boom_height], dtype=float)


def load_keys(stage, lugs, legs):
    """Every load's key of a stage's states: each crane's hook (``hook:NAME``), the ground
    where a pivot is, each lug's load and its in-plane and out-of-plane parts, each sling leg."""
    out = [f"hook:{k}" for k in stage.cranes]
    if stage.pivot is not None:
        out.append("ground")
    for lug in lugs:
        out += [f"lug:{lug}", f"lug_in:{lug}", f"lug_out:{lug}"]
    return out + [f"leg:{leg}" for leg in legs]


@dataclass(frozen=True)
class ChainStart:
    """Where the stage before a move stage left the body and the boom tips.

    Parameters
    ----------
    rotation : ndarray (3, 3)
        Body -> world at the previous stage's last state.
    offset : ndarray (3,)  [m]
        World position of the body-frame origin there (world = offset + rotation @ body).
    tips : dict of str to ndarray (3,)  [m]
        The boom tip of each crane of the previous stage: above its hook at its rope's
        stretched length, l0 + T / k (a turning stage), or where the move left it.
    stage : str
        The previous stage.
    """

    rotation: np.ndarray
    offset: np.ndarray
    tips: dict
    stage: str

    def world(self, body_point):
        """A body point where the previous stage left it  [m]."""
        return self.offset + self.rotation @ np.asarray(body_point, dtype=float)


def turned_end(sequence, stage, held, anchor):
    """The :class:`ChainStart` a turning stage leaves at its last state.

    Parameters
    ----------
    sequence : Sequence
    stage : Stage
        The turning stage.
    held : HeldState
        Its state at its last angle.
    anchor : array (3,)  [m]
        The body point that stays where it is (the pivot, else the centre of gravity).
    """
    if not held.held:
        raise EquilibriumNotFound(
            f"{stage.where} ends at {held.angle:g} deg, an angle it cannot hold; a move stage after it "
            "has no state to start from"
        )
    anchor = np.asarray(anchor, dtype=float)
    tips = {}
    for key, hook in held.hooks.items():
        crane = sequence.crane(key)
        if crane.rope_length is None or crane.EA is None:
            continue  # not in the move (a crane of the move gives both: checked on reading)
        stretched = crane.rope_length * (1.0 + held.forces[key] / crane.EA)
        tips[key] = np.asarray(hook, dtype=float) + np.array([0.0, 0.0, stretched])
    return ChainStart(held.rotation, anchor - held.rotation @ anchor, tips, stage.where)


#: A reaction above -this x W is the body resting on its pivot (rounding), not lifting off.
REACTION_TOL = 1e-12
#: A free-hanging pivot point this far below the ground is rounding, not a contradiction  [m].
LIFT_TOL = 1e-9


@dataclass(frozen=True)
class BodyPose:
    """What a move stage's equilibrium gives at one parameter.

    Parameters
    ----------
    rotation : ndarray (3, 3)
        Base frame -> world.
    position : ndarray (3,)  [m]
        World position of the base frame's origin.
    heel, trim : float  [deg]
    tensions : dict of str to float  [t]
        Each crane's hook load.
    pulls : dict of str to ndarray (3,)  [t]
        Each one-rope crane's pull on its lug, world.
    legs : dict of str to float  [t]
        Sling legs, ``"CRANE/LUG"``.
    slings : dict of str to ndarray (3,)  [m]
        Each sling crane's hook, world.
    reaction : float  [t]
        The ground's push at the pivot (0: none, or lifted off).
    slack : tuple of str
        ``("pivot",)`` when the body has lifted off its pivot.
    model : str
    """

    rotation: np.ndarray
    position: np.ndarray
    heel: float
    trim: float
    tensions: dict
    pulls: dict
    legs: dict = field(default_factory=dict)
    slings: dict = field(default_factory=dict)
    reaction: float = 0.0
    slack: tuple = ()
    model: str = ""


class MoveModel:
    """The loads of one move stage as functions of its parameter s in [0, 1].

    Parameters
    ----------
    sequence : Sequence
    stage : Stage
        ``kind = "move"``.
    """

    def __init__(self, sequence, stage, chain=None):
        self.sequence, self.stage, self.chain = sequence, stage, chain
        self.cranes = [sequence.crane(key) for key in stage.cranes]
        self.lugs = [lug for crane in self.cranes for lug in crane.lugs]
        moves = {m.crane: m for m in stage.moves}
        # the base frame the stage's scene is written in: the body where the stage starts
        self.base = np.eye(3) if chain is None else chain.rotation
        self.offset = np.zeros(3) if chain is None else chain.offset
        if chain is None:
            self.starts = {key: start_tip(sequence, c) for key, c in zip(stage.cranes, self.cranes)}
        else:
            self.starts = {
                key: chain.tips[key] if key in chain.tips else self._joining_tip(c)
                for key, c in zip(stage.cranes, self.cranes)
            }
        self.ends = {
            key: moves[key].end(start) if key in moves else start for key, start in self.starts.items()
        }
        slung = any(c.sling is not None for c in self.cranes)
        self.inclined = (
            slung
            or any(m.to is not None for m in stage.moves)
            or (chain is None and any(c.tip is not None for c in self.cranes))
        )
        self.scene = Scene(
            body=dataclasses.replace(sequence.body, cog=self._based(sequence.body.cog)),
            lugs=tuple(self._based_lug(sequence.lug(name)) for name in self.lugs),
            cranes=tuple(
                dataclasses.replace(
                    c,
                    name=c.name if c.sling is not None else None,  # a sling's results go by its crane
                    swl=None,
                    tip=c.tip if chain is None else None,
                )
                for c in self.cranes
            ),
            name=stage.where,
        )
        self.normals = {
            name: np.array(sequence.lug(name).normal or stage.axis_vector, dtype=float) for name in self.lugs
        }
        self.based_at = {lug.name: lug.at for lug in self.scene.lugs}
        self.on_pivot = None
        if stage.pivot is not None:  # vertical ropes only (checked on reading)
            self.on_pivot = OnPivot(
                sequence.body.weight,
                self.scene.body.cog,
                [self.based_at[c.lug] for c in self.cranes],
                self._based(stage.pivot),
                [c.EA / c.rope_length for c in self.cranes],
                [c.rope_length for c in self.cranes],
            )
        self.legs = [f"{key}/{lug}" for key, c in zip(stage.cranes, self.cranes) if c.sling for lug in c.lugs]

    def _joining_tip(self, crane):
        """A crane that joins at a chained move: its tip l0 above its hook where the hook just
        reaches (its lug, or its sling's apex with the legs straight), carrying nothing yet."""
        pts = np.array([self.chain.world(self.sequence.lug(name).at) for name in crane.lugs])
        if crane.sling is None:
            hook = pts[0]
        else:
            legs = tuple(leg.length for leg in crane.sling.legs)
            hook = sling_apex(Support(crane_key(crane), tuple(crane.lugs), pts, legs), pts).at
        return hook + np.array([0.0, 0.0, crane.rope_length])

    def _based(self, point):
        """A body point in the stage's base frame (the world where the stage starts)  [m]."""
        return tuple(float(v) for v in self.offset + self.base @ np.asarray(point, dtype=float))

    def _based_lug(self, lug):
        normal = None if lug.normal is None else tuple(float(v) for v in self.base @ np.asarray(lug.normal))
        return dataclasses.replace(lug, at=self._based(lug.at), normal=normal)

    def names(self):
        """Every load's key."""
        return load_keys(self.stage, self.lugs, self.legs)

    def tips(self, s):
        """Each crane's boom tip at parameter ``s``  [m]."""
        return {k: (1.0 - s) * self.starts[k] + s * self.ends[k] for k in self.stage.cranes}

    def scene_at(self, s):
        """The :class:`~liftplan.model.scene.objects.Scene` the stage solves at ``s``."""
        tips = self.tips(s)
        cranes = []
        for key, crane in zip(self.stage.cranes, self.scene.cranes):
            tip = tips[key]
            if self.inclined:
                cranes.append(dataclasses.replace(crane, tip=tuple(float(v) for v in tip)))
            else:
                cranes.append(dataclasses.replace(crane, boom_height=float(tip[2])))
        return dataclasses.replace(self.scene, cranes=tuple(cranes))

    def __call__(self, s):
        """``(SequenceState, {load key: value})`` at parameter ``s``."""
        pose = self.pose(s)
        rot = pose.rotation
        pulls, hook_loads, legs, slack = {}, {}, {}, list(pose.slack)
        for key, crane in zip(self.stage.cranes, self.cranes):
            hook_loads[key] = pose.tensions[key]
            if hook_loads[key] <= 0.0:
                slack.append(key)
            if crane.sling is None:
                pulls[crane.lug] = pose.pulls[key]
                continue
            hook = pose.slings[key]
            for lug in crane.lugs:
                leg = f"{key}/{lug}"
                legs[leg] = pose.legs[leg]
                if legs[leg] <= 0.0:
                    slack.append(leg)
                at = pose.position + rot @ np.array(self.based_at[lug], dtype=float)
                pulls[lug] = legs[leg] * (hook - at) / np.linalg.norm(hook - at)
        loads = {}
        for lug, pull in pulls.items():
            force = self.base.T @ rot.T @ pull  # into the body frame, where the lug's normal is given
            n = self.normals[lug]
            along = float(force @ n)
            loads[lug] = LugLoad(
                float(np.linalg.norm(force)), float(np.linalg.norm(force - along * n)), abs(along)
            )
        tips = self.tips(s)
        state = SequenceState(
            stage=self.stage.where,
            angle=float(s),
            tilt=0.0,
            held=True,
            hook_loads=hook_loads,
            ground_reaction=pose.reaction,
            lug_loads=loads,
            sling_tensions=legs,
            hooks={k: tuple(float(v) for v in tips[k]) for k in self.stage.cranes},
            slack=tuple(slack),
            note=pose.model,
            heel=pose.heel,
            trim=pose.trim,
            origin=tuple(float(v) for v in pose.position + rot @ self.offset),
            rotation=tuple(tuple(float(v) for v in row) for row in rot @ self.base),
            sling_hooks={k: tuple(float(v) for v in hook) for k, hook in pose.slings.items()},
        )
        values = {f"hook:{k}": v for k, v in hook_loads.items()}
        if self.stage.pivot is not None:
            values["ground"] = pose.reaction
        for lug, ld in loads.items():
            values[f"lug:{lug}"], values[f"lug_in:{lug}"], values[f"lug_out:{lug}"] = (
                ld.load,
                ld.in_plane,
                ld.out_of_plane,
            )
        for leg, tension in legs.items():
            values[f"leg:{leg}"] = tension
        values["_held"] = 1.0
        return state, values

    def pose(self, s):
        """The body's :class:`BodyPose` at parameter ``s``: on its pivot while the ground pushes,
        else on its ropes alone (``liftplan solve`` of the stage's scene)."""
        where = f"{self.stage.where} at s = {s:.6g}"
        if self.on_pivot is not None:
            heights = [self.tips(s)[key][2] for key in self.stage.cranes]
            rest = self.on_pivot.solve(heights, where)
            if rest.reaction >= -REACTION_TOL * self.sequence.body.weight:
                return BodyPose(
                    rotation=rest.rotation,
                    position=self.on_pivot.pivot - rest.rotation @ self.on_pivot.pivot,
                    heel=rest.heel,
                    trim=rest.trim,
                    tensions={k: float(t) for k, t in zip(self.stage.cranes, rest.tensions)},
                    pulls={
                        k: np.array([0.0, 0.0, float(t)]) for k, t in zip(self.stage.cranes, rest.tensions)
                    },
                    reaction=max(rest.reaction, 0.0),
                    model="elastic model, on the pivot",
                )
        try:
            eq = solve(self.scene_at(s))
        except EquilibriumNotFound as err:
            raise EquilibriumNotFound(f"{where}: {err}") from None
        rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
        # the elastic model keeps the base frame's origin at plan (0, 0); the inclined one moves it
        position = np.array(eq.position if eq.position is not None else (0.0, 0.0, eq.pose.lift_height))
        slack = ()
        if self.on_pivot is not None:
            lifted = self.on_pivot.height(rot, position) - self.on_pivot.pivot[2]
            if lifted < -LIFT_TOL:
                raise EquilibriumNotFound(
                    f"{where}: the ropes alone would put the pivot {-lifted:.3g} m below the ground, and "
                    "on the ground it would have to pull; no state"
                )
            slack = ("pivot",)
        tensions, pulls, legs, slings = {}, {}, {}, {}
        for key, crane in zip(self.stage.cranes, self.cranes):
            name = crane.name if crane.sling is not None else crane.lug  # the solve's key
            tensions[key] = 0.0 if name in eq.slack else max(float(eq.tensions[name]), 0.0)
            if crane.sling is None:
                pulls[key] = (
                    np.array(eq.rope_forces[name].force, dtype=float)
                    if eq.rope_forces is not None
                    else np.array([0.0, 0.0, tensions[key]])
                )
                continue
            slings[key] = np.array(eq.rigging.hook_positions[name], dtype=float)
            for lug in crane.lugs:
                legs[f"{key}/{lug}"] = max(float(eq.rigging.legs[f"{name}/{lug}"]), 0.0)
        return BodyPose(
            rotation=rot,
            position=position,
            heel=eq.pose.heel,
            trim=eq.pose.trim,
            tensions=tensions,
            pulls=pulls,
            legs=legs,
            slings=slings,
            slack=slack,
            model=f"{eq.model} model",
        )

    def end(self):
        """The :class:`ChainStart` this stage leaves at its end (s = 1)."""
        state, _ = self(1.0)
        rot = self.pose(1.0).rotation
        tips = {k: np.asarray(v, dtype=float) for k, v in state.hooks.items()}
        return ChainStart(rot @ self.base, np.asarray(state.origin, dtype=float), tips, self.stage.where)


__all__ = ["ChainStart", "MoveModel", "start_tip", "turned_end"]
