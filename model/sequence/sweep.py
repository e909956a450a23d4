"""A whole sequence: every stage swept over its angles, its maxima, ranges, design loads, checks.

:func:`run_sequence` solves each stage's held-angle equilibrium
(:mod:`liftplan.model.sequence.statics`) on the user's grid and between its points
(:mod:`liftplan.model.sequence.maxima`), reports each lug's load in the lug's own frame
(magnitude, and its components in and across the lug plate, whose normal is the lug's
``normal`` or the stage's turning axis), the angle ranges where a rope is slack or the angle
is not held, and per stage the rules' design-load chain on the stage's maxima
(:class:`~liftplan.model.rules.DesignLoadChain`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.rules import CraneLoads, DesignLoadChain, LugLoads
from liftplan.model.sequence.maxima import Peak, Sampler, adaptive_samples, continuous_maxima
from liftplan.model.sequence.move import MoveModel, load_keys, turned_end
from liftplan.model.sequence.states import LugLoad, SequenceState
from liftplan.model.sequence.statics import HeldAngle, Support

#: Chord tolerance of the adaptive sampling, x W.
SAMPLE_TOL = 1e-5
#: Narrowest interval the sampling halves  [deg].
MIN_WIDTH = 1e-4
#: Brent's tolerance on the angle of a maximum  [deg].
XTOL = 1e-7
#: Bisections that place the ends of a slack or not-held range  [-] (2^-40 of a step).
EDGE_BISECTIONS = 40
#: Largest out-of-plane angle the rules' chain takes  [deg] (it refuses 90: a load wholly
#: across the plate is then its out-of-plane part, checked on its own).
CHAIN_MAX_OFF = 89.99


@dataclass(frozen=True)
class AngleRange:
    """Angles of a stage over which something holds  [deg] (``start`` <= ``stop``)."""

    what: str
    stage: str
    start: float
    stop: float

    def to_json(self):
        return {"what": self.what, "stage": self.stage, "from": self.start, "to": self.stop}


@dataclass(frozen=True)
class StageResult:
    """One stage swept.

    Parameters
    ----------
    stage : Stage
    states : tuple of SequenceState
        On the user's grid.
    maxima : dict of str to Peak
        Each load's continuous maximum, keyed ``"hook:CRANE"``, ``"ground"``, ``"lug:LUG"``,
        ``"lug_in:LUG"``, ``"lug_out:LUG"``, ``"leg:CRANE/LUG"``.
    curves : dict of str to ndarray
        Every load at the adaptive samples (``"angle"`` holds the angles), for figures.
    slack : tuple of AngleRange
    not_held : tuple of AngleRange
    design : DesignLoadChain
        The rules' chain on this stage's maxima.
    checks : tuple of Check
    evaluations : int
        Equilibria solved.
    """

    stage: object
    states: tuple
    maxima: dict
    curves: dict = field(repr=False)
    slack: tuple
    not_held: tuple
    design: DesignLoadChain
    checks: tuple
    evaluations: int

    @property
    def hook_travel(self):
        """Each crane's hook motion over the stage  [m]: ``{crane: {"rise": ..., "lowest": ...,
        "highest": ..., "plan": ...}}``, from its first grid state (rise: the last height less
        the first; plan: the largest horizontal distance from where it started)."""
        out = {}
        first = self.states[0].hooks
        for key in first:
            pts = np.array([s.hooks[key] for s in self.states])
            start = pts[0]
            out[key] = {
                "rise": float(pts[-1, 2] - start[2]),
                "lowest": float(pts[:, 2].min()),
                "highest": float(pts[:, 2].max()),
                "plan": float(np.max(np.hypot(pts[:, 0] - start[0], pts[:, 1] - start[1]))),
            }
        return out


@dataclass(frozen=True)
class SequenceResult:
    """A whole sequence: its stages, overall maxima and checks; ``seconds`` of solving."""

    sequence: object
    stages: tuple
    seconds: float

    @property
    def checks(self):
        return tuple(c for s in self.stages for c in s.checks)

    @property
    def states(self):
        return tuple(st for s in self.stages for st in s.states)

    def maxima(self, prefix):
        """The largest of each load over all stages: ``{name: (Peak, stage)}``."""
        out = {}
        for s in self.stages:
            for key, peak in s.maxima.items():
                kind, _, name = key.partition(":")
                if kind != prefix:
                    continue
                name = name or kind
                if name not in out or peak.value > out[name][0].value:
                    out[name] = (peak, s.stage.where)
        return out

    def to_json(self):
        moves = {s.stage.where for s in self.stages if s.stage.kind == "move"}

        def where(peak, stage):
            if stage in moves:  # a move stage's maximum is at a parameter, not an angle
                return {
                    "value": peak.value,
                    "angle": None,
                    "param": peak.angle,
                    "stage": stage,
                    "bound": peak.bound,
                }
            return {"value": peak.value, "angle": peak.angle, "stage": stage, "bound": peak.bound}

        def table(prefix):
            return {k: where(p, stage) for k, (p, stage) in self.maxima(prefix).items()}

        ground = self.maxima("ground").get("ground")
        return {
            "name": self.sequence.name,
            "states": [st.to_json() for st in self.states],
            "maxima": {
                "hook_loads": table("hook"),
                "lug_loads": table("lug"),
                "lug_in_plane": table("lug_in"),
                "lug_out_of_plane": table("lug_out"),
                "sling_tensions": table("leg"),
                "ground_reaction": (where(ground[0], ground[1]) if ground else None),
            },
            "slack": [_range_json(r, s.stage) for s in self.stages for r in s.slack],
            "not_held": [r.to_json() for s in self.stages for r in s.not_held],
            "stages": [
                {
                    "name": s.stage.where,
                    "kind": s.stage.kind,
                    "axis": s.stage.axis,
                    "from": s.stage.start,
                    "to": s.stage.stop,
                    "step": s.stage.step,
                    "cranes": list(s.stage.cranes),
                    "pivot": list(s.stage.pivot) if s.stage.pivot is not None else None,
                    "evaluations": s.evaluations,
                    "hook_travel": s.hook_travel,
                    "moves": [
                        {"crane": m.crane, "hoist": m.hoist, "to": list(m.to) if m.to is not None else None}
                        for m in s.stage.moves
                    ],
                    "steps": s.stage.steps,
                    "design_loads": s.design.to_json(),
                }
                for s in self.stages
            ],
            "checks": [c.to_json() for c in self.checks],
            "converged": True,
        }


def _range_json(span, stage):
    """An :class:`AngleRange` as JSON; in a move stage its ends are parameters (``from_param``)."""
    if stage.kind != "move":
        return span.to_json()
    return {
        "what": span.what,
        "stage": span.stage,
        "from": None,
        "to": None,
        "from_param": span.start,
        "to_param": span.stop,
    }


def supports_of(sequence, stage):
    """The :class:`Support` list of a stage: its cranes in order, then the pivot."""
    out = []
    for key in stage.cranes:
        crane = sequence.crane(key)
        pts = np.array([sequence.lug(n).at for n in crane.lugs], dtype=float)
        legs = tuple(leg.length for leg in crane.sling.legs) if crane.sling is not None else ()
        out.append(Support(key=key, lugs=tuple(crane.lugs), points=pts, legs=legs))
    if stage.pivot is not None:
        out.append(Support(key="pivot", lugs=(), points=np.array([stage.pivot], dtype=float)))
    return out


class StageModel:
    """The loads of one stage as functions of the angle.

    Parameters
    ----------
    sequence : Sequence
    stage : Stage
    """

    def __init__(self, sequence, stage):
        self.sequence, self.stage = sequence, stage
        cog = np.array(sequence.body.cog, dtype=float)
        anchor = np.array(stage.pivot, dtype=float) if stage.pivot is not None else cog
        stiffness = {
            key: crane.EA / crane.rope_length
            for key in stage.cranes
            if (crane := sequence.crane(key)).EA is not None and crane.rope_length is not None
        }
        self.statics = HeldAngle(
            supports_of(sequence, stage), sequence.body.weight, cog, stage.axis, anchor, stiffness
        )
        self.lugs = [lug for key in stage.cranes for lug in sequence.crane(key).lugs]
        self.normals = {
            name: np.array(sequence.lug(name).normal or stage.axis_vector, dtype=float) for name in self.lugs
        }
        self.legs = [
            f"{key}/{lug}"
            for key in stage.cranes
            if sequence.crane(key).sling is not None
            for lug in sequence.crane(key).lugs
        ]

    def names(self):
        """Every load's key."""
        return load_keys(self.stage, self.lugs, self.legs)

    def __call__(self, angle):
        """``(SequenceState, {load key: value})`` at ``angle``  [deg]."""
        held = self.statics.state(angle)
        loads = {}
        zero = np.zeros(3)
        for lug in self.lugs:
            force = held.lug_forces.get(lug, zero)
            n = self.normals[lug]
            across = abs(float(force @ n))
            magnitude = float(np.linalg.norm(force))
            inside = float(np.linalg.norm(force - (force @ n) * n))
            loads[lug] = LugLoad(magnitude, inside, across)
        state = SequenceState(
            stage=self.stage.where,
            angle=float(angle),
            tilt=held.tilt,
            held=held.held,
            hook_loads={k: held.forces[k] for k in self.stage.cranes},
            ground_reaction=held.forces.get("pivot", 0.0),
            lug_loads=loads,
            sling_tensions={k: held.legs.get(k, 0.0) for k in self.legs},
            hooks={k: tuple(float(v) for v in held.hooks[k]) for k in self.stage.cranes},
            slack=held.slack,
            note=held.note,
        )
        values = {f"hook:{k}": v for k, v in state.hook_loads.items()}
        if self.stage.pivot is not None:
            values["ground"] = state.ground_reaction
        for lug, ld in loads.items():
            values[f"lug:{lug}"], values[f"lug_in:{lug}"], values[f"lug_out:{lug}"] = (
                ld.load,
                ld.in_plane,
                ld.out_of_plane,
            )
        for leg in self.legs:
            values[f"leg:{leg}"] = state.sling_tensions[leg]
        values["_held"] = 1.0 if state.held else 0.0
        return state, values


def stage_model(sequence, stage):
    """The loads of a stage as functions of its sweep variable: the angle of a turn
    (:class:`StageModel`), the parameter of a move (:class:`~liftplan.model.sequence.move.MoveModel`,
    started where the stage before left the body and the tips: :func:`chain_start`)."""
    if stage.kind == "move":
        return MoveModel(sequence, stage, chain_start(sequence, stage))
    return StageModel(sequence, stage)


def chain_start(sequence, stage):
    """Where the stage before ``stage`` left the body and the boom tips
    (:class:`~liftplan.model.sequence.move.ChainStart`), or None for a stage that opens the
    sequence or turns (a turning stage starts from the body as the file gives it)."""
    index = next(k for k, s in enumerate(sequence.stages) if s is stage)
    if stage.kind != "move" or index == 0:
        return None
    previous = sequence.stages[index - 1]
    model = stage_model(sequence, previous)
    if previous.kind == "move":
        return model.end()
    return turned_end(sequence, previous, model.statics.state(previous.angles[-1]), model.statics.anchor)


def run_stage(sequence, stage):
    """Sweep one stage: :class:`StageResult`."""
    model = stage_model(sequence, stage)
    sampler = Sampler(model)
    grid = stage.angles
    ordered = np.sort(grid)
    weight = sequence.body.weight
    angles = adaptive_samples(sampler, ordered, SAMPLE_TOL * weight, MIN_WIDTH)
    names = model.names()
    maxima = continuous_maxima(sampler, angles, names, XTOL, noise=1e-10 * weight)
    states = tuple(sampler(a)[0] for a in grid)
    curves = {"angle": angles}
    for name in names:
        curves[name] = np.array([sampler.values(a)[name] for a in angles])
    slack = _ranges(
        sampler, angles, stage, lambda st, what: what in st.slack, _slack_names(model, angles, sampler)
    )
    not_held = _ranges(sampler, angles, stage, lambda st, what: not st.held, ["angle not held"])
    design = design_chain(sequence, stage, model, maxima, sampler)
    checks = _checks(sequence, stage, model, maxima, design, not_held, sampler, angles)
    return StageResult(
        stage=stage,
        states=states,
        maxima=maxima,
        curves=curves,
        slack=slack,
        not_held=not_held,
        design=design,
        checks=checks,
        evaluations=sampler.evaluations,
    )


def run_sequence(sequence):
    """Sweep every stage of ``sequence``: :class:`SequenceResult`."""
    started = time.perf_counter()
    stages = tuple(run_stage(sequence, s) for s in sequence.stages)
    return SequenceResult(sequence=sequence, stages=stages, seconds=time.perf_counter() - started)


def _slack_names(model, angles, sampler):
    seen = []
    for a in angles:
        for what in sampler(a)[0].slack:
            if what not in seen:
                seen.append(what)
    return seen


def _ranges(sampler, angles, stage, test, names):
    """Angle ranges where ``test(state, name)`` holds, their ends placed by bisection."""
    out = []
    for what in names:
        flags = [test(sampler(a)[0], what) for a in angles]
        k = 0
        while k < len(angles):
            if not flags[k]:
                k += 1
                continue
            j = k
            while j + 1 < len(angles) and flags[j + 1]:
                j += 1
            start = angles[k] if k == 0 else _edge(sampler, angles[k - 1], angles[k], test, what)
            stop = angles[j] if j == len(angles) - 1 else _edge(sampler, angles[j + 1], angles[j], test, what)
            out.append(AngleRange(what, stage.where, float(min(start, stop)), float(max(start, stop))))
            k = j + 1
    return tuple(out)


def _edge(sampler, outside, inside, test, what):
    """The angle between ``outside`` (test false) and ``inside`` (true) where it changes."""
    model = sampler.evaluate
    for _ in range(EDGE_BISECTIONS):
        mid = 0.5 * (outside + inside)
        if test(model(mid)[0], what):
            inside = mid
        else:
            outside = mid
    return inside


def design_chain(sequence, stage, model, maxima, sampler):
    """The rules' chain on the stage's maxima: each crane's largest hook load, each lug's
    largest load (taken along itself, at its angle to the plate there)."""
    cranes = []
    many = len(stage.cranes) >= 2
    for key in stage.cranes:
        crane = sequence.crane(key)
        worst = maxima[f"hook:{key}"].value
        if not worst > 0.0 and len(stage.cranes) > 1:
            continue  # slack all through the stage: nothing to factor (the DAF table needs a load)
        lugs = []
        for name in crane.lugs:
            peak = maxima[f"lug:{name}"]
            load = sampler(peak.angle)[0].lug_loads[name]
            lugs.append(
                LugLoads(
                    name=name,
                    share=peak.value,
                    sling_angle=90.0,  # the share is the load itself, along its own line
                    out_of_plane=min(load.off_plane_angle, CHAIN_MAX_OFF),
                    capacity=sequence.lug(name).capacity,
                )
            )
        cranes.append(
            CraneLoads(
                name=key,
                nominal=worst,
                worst=worst,
                # the turn itself is the tilt: every angle of it is swept, so no further share
                tilt=worst if many else None,
                # a crane without an SWL gets no hook check; the chain needs a number, and its
                # hook check and utilisation are dropped below (never reported)
                swl=crane.swl if crane.swl is not None else max(worst, 1.0),
                lugs=tuple(lugs),
            )
        )
    return DesignLoadChain(cranes=tuple(cranes), weight=sequence.body.weight, rules=sequence.rules)


def _checks(sequence, stage, model, maxima, design, not_held, sampler, angles):
    where = stage.where
    rules = sequence.rules
    out = []
    unheld = sum(r.stop - r.start for r in not_held)
    off = [a for a in angles if not sampler(a)[0].held]
    # every state of a move is an equilibrium of the solver, or the stage raised: no angle check
    if stage.kind != "move":
        out.append(
            Check(
                "angle_held",
                where,
                float(unheld),
                0.0,
                "deg",
                not off,
                note=f"degrees of the stage where the supports cannot hold the angle ({len(off)} samples)",
            )
        )
    for result in design.results:
        crane = sequence.crane(result.crane)
        if crane.swl is not None:
            out.append(_named(result.check, f"{result.crane} ({where})"))
        for lug in result.lugs:
            spec = sequence.lug(lug.lug)
            peak = maxima[f"lug_out:{lug.lug}"]
            factor = lug.product * rules.consequence_factor
            if spec.capacity is not None:
                out.append(
                    Check.upper(
                        "lug_design_load",
                        f"{lug.lug} ({where})",
                        lug.design_load,
                        spec.capacity,
                        "t",
                        note=(
                            f"largest load {lug.share:.4g} t {_at(stage, maxima[f'lug:{lug.lug}'].angle)} x "
                            f"factors {lug.product:.4g} x consequence {rules.consequence_factor:g}"
                        ),
                    )
                )
            if spec.capacity_out_of_plane is not None:
                across = peak.value * factor + rules.lateral_fraction * lug.design_load
                out.append(
                    Check.upper(
                        "lug_out_of_plane",
                        f"{lug.lug} ({where})",
                        across,
                        spec.capacity_out_of_plane,
                        "t",
                        note=(
                            f"largest out-of-plane load {peak.value:.4g} t {_at(stage, peak.angle)} x "
                            f"{factor:.4g} + lateral {rules.lateral_fraction:g} x design load"
                        ),
                    )
                )
    if stage.friction is not None:
        reactions = [sampler(a)[0].ground_reaction for a in angles if sampler(a)[0].held]
        out.append(
            Check.upper(
                "pivot_friction",
                where,
                0.0,
                stage.friction * min(reactions, default=0.0),
                "t",
                note="plumb hooks: no horizontal force at the pivot; limit friction x least reaction",
            )
        )
    return tuple(out)


def _at(stage, where):
    """Where on a stage a maximum is, in words: an angle, or a move stage's parameter."""
    return f"at s = {where:.3f}" if stage.kind == "move" else f"at {where:.3f} deg"


def _named(check, subject):
    return Check(check.name, subject, check.value, check.limit, check.unit, check.ok, check.kind, check.note)


__all__ = ["Peak", "run_sequence", "run_stage", "stage_model", "StageModel"]
