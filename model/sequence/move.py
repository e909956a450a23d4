"""A ``kind = "move"`` stage: boom tips moved, the body solved on its elastic ropes at each state.

Each crane named in the stage's ``moves`` has its boom tip moved in a straight line from where
the file puts it (its ``tip``, else above its lug at its ``boom_height``) to its end position
(``to``, else where it starts, raised by ``hoist``), over a stage parameter s from 0 to 1; the
other cranes' tips stay. At every s the body's equilibrium is that of
:func:`liftplan.model.solve.solve` on the scene of the stage's cranes with their tips there:

* tips that only rise and fall (no ``to``, no ``tip`` in the file): the ``elastic`` model,
  vertical ropes from the boom heights H_i + s hoist_i;
* a tip moved in plan (``to``) or placed in the world (``tip``): the ``inclined`` model, every
  rope from its tip to its lug (the body swings until the rope directions balance).

Both are elastic (T = EA max(0, stretch) / l0): four or more ropes share the load as their
stretches decide, and a rope whose stretch falls to zero is slack and carries nothing. A state
the solver cannot hold (fewer than three taut ropes, no convergence) raises
:class:`~liftplan.model.errors.EquilibriumNotFound` naming the parameter: no number is made up.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from liftplan.model.errors import EquilibriumNotFound
from liftplan.model.frames import rotation_matrix
from liftplan.model.scene.objects import Scene
from liftplan.model.sequence.states import LugLoad, SequenceState
from liftplan.model.solve import solve


def start_tip(sequence, crane):
    """Where a crane's boom tip is at a move stage's start (world, ``z-up``)  [m]."""
    if crane.tip is not None:
        return np.array(crane.tip, dtype=float)
    at = sequence.lug(crane.lug).at
    return np.array([at[0], at[1], crane.boom_height], dtype=float)


class MoveModel:
    """The loads of one move stage as functions of its parameter s in [0, 1].

    Parameters
    ----------
    sequence : Sequence
    stage : Stage
        ``kind = "move"``.
    """

    def __init__(self, sequence, stage):
        self.sequence, self.stage = sequence, stage
        self.cranes = [sequence.crane(key) for key in stage.cranes]
        self.lugs = [crane.lug for crane in self.cranes]
        moves = {m.crane: m for m in stage.moves}
        self.starts = {key: start_tip(sequence, c) for key, c in zip(stage.cranes, self.cranes)}
        self.ends = {
            key: moves[key].end(start) if key in moves else start for key, start in self.starts.items()
        }
        self.inclined = any(m.to is not None for m in stage.moves) or any(
            c.tip is not None for c in self.cranes
        )
        self.scene = Scene(
            body=sequence.body,
            lugs=tuple(sequence.lug(name) for name in self.lugs),
            cranes=tuple(dataclasses.replace(c, name=None, swl=None) for c in self.cranes),
            name=stage.where,
        )
        self.normals = {
            name: np.array(sequence.lug(name).normal or stage.axis_vector, dtype=float) for name in self.lugs
        }

    @property
    def legs(self):
        """Sling legs: none (a move stage hangs one rope per lug)."""
        return []

    def names(self):
        """Every load's key."""
        out = [f"hook:{k}" for k in self.stage.cranes]
        for lug in self.lugs:
            out += [f"lug:{lug}", f"lug_in:{lug}", f"lug_out:{lug}"]
        return out

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
        try:
            eq = solve(self.scene_at(s))
        except EquilibriumNotFound as err:
            raise EquilibriumNotFound(f"{self.stage.where} at s = {s:.6g}: {err}") from None
        rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
        loads, hook_loads, slack = {}, {}, []
        for key, lug in zip(self.stage.cranes, self.lugs):
            tension = max(float(eq.tensions[lug]), 0.0)
            if eq.rope_forces is not None:
                pull = np.array(eq.rope_forces[lug].force, dtype=float)
            else:
                pull = np.array([0.0, 0.0, tension])
            force = rot.T @ pull  # into the body frame, where the lug's normal is given
            n = self.normals[lug]
            along = float(force @ n)
            loads[lug] = LugLoad(
                float(np.linalg.norm(force)), float(np.linalg.norm(force - along * n)), abs(along)
            )
            hook_loads[key] = tension
            if lug in eq.slack:
                slack.append(key)
        tips = self.tips(s)
        state = SequenceState(
            stage=self.stage.where,
            angle=float(s),
            tilt=0.0,
            held=True,
            hook_loads=hook_loads,
            ground_reaction=0.0,
            lug_loads=loads,
            sling_tensions={},
            hooks={k: tuple(float(v) for v in tips[k]) for k in self.stage.cranes},
            slack=tuple(slack),
            note=f"{eq.model} model",
            heel=eq.pose.heel,
            trim=eq.pose.trim,
            # the elastic model keeps the body origin at plan (0, 0); the inclined one moves it
            origin=tuple(eq.position) if eq.position is not None else (0.0, 0.0, eq.pose.lift_height),
        )
        values = {f"hook:{k}": v for k, v in hook_loads.items()}
        for lug, ld in loads.items():
            values[f"lug:{lug}"], values[f"lug_in:{lug}"], values[f"lug_out:{lug}"] = (
                ld.load,
                ld.in_plane,
                ld.out_of_plane,
            )
        values["_held"] = 1.0
        return state, values


__all__ = ["MoveModel", "start_tip"]
