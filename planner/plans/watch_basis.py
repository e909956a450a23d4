"""What ``liftplan watch`` needs of a plan, in one object that a plan JSON carries too.

A watched lift is the plan's chosen set as it hangs: its lugs, ropes (EA, unstretched
length) and boom heights, the body's planned weight and CG, and what the plan allowed: each
rope's tension band (its lowest and highest over the heel/trim box, the CG envelope and the
hook tolerance, on the design loads' dense grid), the minimum tension, each crane's chart SWL,
the CG envelope and the rules' chain (its settings and, per crane, the plan's share at the
rules' tilt over its static input, and its computed skew factor). :func:`watch_basis` reads
them off a held (or rope-length) plan; the plan JSON carries them as its ``"watch"`` object
(:meth:`WatchBasis.to_json`), so a plan JSON alone can be watched.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.rules import CraneLoads, DesignLoadChain, Rules
from liftplan.planner.problem.readings_accuracy import ReadingsAccuracy

#: Plan kinds a watch follows: single vertical ropes, one per crane.
WATCHED_KINDS = ("held", "lengths")


@dataclass(frozen=True)
class WatchBasis:
    """A planned lift as the watch sees it (``z-up`` body frame, plan labels L1..Ln).

    Parameters
    ----------
    name : str
    frame : str
        The planning file's frame, for what a person reads.
    labels, cranes, candidates : tuple of str
        Planned lug label, the crane's name and the candidate's name, per rope.
    points : numpy.ndarray, shape (n, 3)  [m]
        Lugs, body frame.
    EA : numpy.ndarray  [t]
    rope_length : numpy.ndarray  [m]
        Unstretched length l0.
    boom_height : numpy.ndarray  [m]
        Planned boom-tip height H.
    weight : float  [t]
    cog : numpy.ndarray, shape (3,)  [m]
    lift_height : float  [m]
    yaw : float  [deg]
    swl : numpy.ndarray  [t]
        Chart SWL at each crane's radius.
    radius : tuple of (float or None)  [m]
    min_tension : float  [t]
    heel_tolerance, trim_tolerance : float  [deg]
    cog_tolerance : numpy.ndarray, shape (3,)  [m]
        The CG envelope's half-widths (body frame).
    cog_shape : str
        ``"box"`` or ``"cross"``.
    hook_tolerance : numpy.ndarray  [m]
    band_low, band_high : numpy.ndarray  [t]
        Each rope's lowest and highest planned tension.
    rules : Rules
    cog_searched : bool
    tilt_ratio : tuple of (float or None)  [-]
        The plan's share at the rules' tilt over its static input, per crane (None: none).
    skew : tuple of (float or None)  [-]
        The plan's computed skew factor per crane.
    accuracy : ReadingsAccuracy
    """

    name: str
    frame: str
    labels: tuple
    cranes: tuple
    candidates: tuple
    points: np.ndarray
    EA: np.ndarray
    rope_length: np.ndarray
    boom_height: np.ndarray
    weight: float
    cog: np.ndarray
    lift_height: float
    yaw: float
    swl: np.ndarray
    radius: tuple
    min_tension: float
    heel_tolerance: float
    trim_tolerance: float
    cog_tolerance: np.ndarray
    cog_shape: str
    hook_tolerance: np.ndarray
    band_low: np.ndarray
    band_high: np.ndarray
    rules: Rules
    cog_searched: bool
    tilt_ratio: tuple
    skew: tuple
    accuracy: ReadingsAccuracy

    @property
    def n(self):
        return len(self.labels)

    @property
    def plan_diameter(self):
        """Largest plan distance between two lugs  [m] (a length scale)."""
        plan = self.points[:, :2]
        return float(np.max(np.linalg.norm(plan[:, None, :] - plan[None, :, :], axis=2)))

    def names(self):
        """Every name a readings column may use for a rope -> its label (label, crane, candidate)."""
        out = {}
        for label, crane, candidate in zip(self.labels, self.cranes, self.candidates):
            for name in (label, crane, candidate):
                out.setdefault(name, set()).add(label)
        return out

    def design_chain(self, tensions, weight):
        """The rules' chain with each crane's static input at ``tensions`` and the lift at
        ``weight``: the design hook loads the lift has now.

        Each crane's nominal and worst share are its tension now, its share at the rules'
        tilt that tension times the plan's ratio (:attr:`tilt_ratio`), its skew the plan's.

        Parameters
        ----------
        tensions : array_like (n,)  [t]
        weight : float  [t]

        Returns
        -------
        DesignLoadChain or str
            The chain, or why it cannot be built (one line).
        """
        loads = []
        for k in range(self.n):
            t = max(float(tensions[k]), 0.0)
            ratio = self.tilt_ratio[k]
            loads.append(
                CraneLoads(
                    name=self.cranes[k],
                    nominal=t,
                    worst=t,
                    tilt=None if ratio is None else t * ratio,
                    swl=float(self.swl[k]),
                    radius=self.radius[k],
                    skew=self.skew[k],
                )
            )
        try:
            chain = DesignLoadChain(tuple(loads), weight, self.rules, cog_searched=self.cog_searched)
            chain.results  # noqa: B018 - built now, so that a refusal is said here
        except InvalidScene as err:
            return str(err)
        return chain

    def to_json(self):
        """The plan JSON's ``"watch"`` object (coordinates ``z-up``, body frame)."""
        return {
            "coordinates": "z-up",
            "name": self.name,
            "frame": self.frame,
            "labels": list(self.labels),
            "cranes": list(self.cranes),
            "candidates": list(self.candidates),
            "points": self.points.tolist(),
            "EA": self.EA.tolist(),
            "rope_length": self.rope_length.tolist(),
            "boom_height": self.boom_height.tolist(),
            "weight": self.weight,
            "cog": self.cog.tolist(),
            "lift_height": self.lift_height,
            "yaw": self.yaw,
            "swl": self.swl.tolist(),
            "radius": list(self.radius),
            "min_tension": self.min_tension,
            "heel_tolerance": self.heel_tolerance,
            "trim_tolerance": self.trim_tolerance,
            "cog_tolerance": self.cog_tolerance.tolist(),
            "cog_shape": self.cog_shape,
            "hook_tolerance": self.hook_tolerance.tolist(),
            "band_low": self.band_low.tolist(),
            "band_high": self.band_high.tolist(),
            "rules": asdict(self.rules),
            "cog_searched": self.cog_searched,
            "tilt_ratio": list(self.tilt_ratio),
            "skew": list(self.skew),
            "readings": self.accuracy.to_json(),
        }

    @classmethod
    def from_json(cls, data, where="plan JSON"):
        """The basis from :meth:`to_json`'s object; a one-line :class:`InvalidScene` naming the
        missing or bad key otherwise."""
        if not isinstance(data, dict):
            raise InvalidScene(
                f'{where}: no "watch" object; expected a plan JSON written by `liftplan plan --json`'
            )
        try:
            arrays = {
                key: np.asarray(data[key], dtype=float)
                for key in ("points", "EA", "rope_length", "boom_height", "swl", "cog", "cog_tolerance")
                + ("hook_tolerance", "band_low", "band_high")
            }
            readings = data["readings"]
            rules = dict(data["rules"])
            basis = cls(
                name=str(data["name"]),
                frame=str(data["frame"]),
                labels=tuple(data["labels"]),
                cranes=tuple(data["cranes"]),
                candidates=tuple(data["candidates"]),
                weight=float(data["weight"]),
                lift_height=float(data["lift_height"]),
                yaw=float(data["yaw"]),
                radius=tuple(None if r is None else float(r) for r in data["radius"]),
                min_tension=float(data["min_tension"]),
                heel_tolerance=float(data["heel_tolerance"]),
                trim_tolerance=float(data["trim_tolerance"]),
                cog_shape=str(data["cog_shape"]),
                rules=Rules(**rules),
                cog_searched=bool(data["cog_searched"]),
                tilt_ratio=tuple(None if r is None else float(r) for r in data["tilt_ratio"]),
                skew=tuple(None if s is None else float(s) for s in data["skew"]),
                accuracy=ReadingsAccuracy(
                    load_cell=readings["load_cell_accuracy"],
                    inclinometer=readings["inclinometer_accuracy"],
                    hook=readings["hook_accuracy"],
                ),
                **arrays,
            )
        except KeyError as err:
            raise InvalidScene(
                f'{where}: watch.{err.args[0]} missing; expected the plan JSON\'s whole "watch" object'
            ) from None
        except (TypeError, ValueError) as err:
            raise InvalidScene(
                f'{where}: watch: {err}; expected the plan JSON\'s "watch" object as written'
            ) from None
        n = basis.n
        if basis.points.shape != (n, 3) or any(
            getattr(basis, key).shape != (n,)
            for key in ("EA", "rope_length", "boom_height", "swl", "hook_tolerance", "band_low", "band_high")
        ):
            raise InvalidScene(f"{where}: watch: arrays of {n} ropes expected (one per label)")
        return basis


def watch_basis(plan):
    """The :class:`WatchBasis` of a held or rope-length plan.

    Raises
    ------
    InvalidScene
        For a plan of another kind (slings, strength-optimal forces): what is refused and why.
    """
    if plan.kind not in WATCHED_KINDS:
        raise InvalidScene(
            f"a {plan.kind!r} plan: liftplan watch follows plans of single vertical ropes "
            f"({', '.join(WATCHED_KINDS)}), one load cell per rope; expected such a plan"
        )
    problem, chosen = plan.problem, plan.chosen
    lugset = plan.lugset
    tensions, gain = plan.dense_held  # the design loads' dense grid, every CG vertex
    reach = np.abs(gain) @ lugset.hook_tolerance
    design = plan.design_loads
    tilt_ratio, skew = [], []
    for crane in design.cranes:
        base = crane.static_input
        load = None if crane.tilt is None else crane.tilt.load
        tilt_ratio.append(None if load is None or not base > 0 else float(load / base))
        value = crane.skew
        skew.append(None if value is None or not math.isfinite(value) else float(value))
    return WatchBasis(
        name=problem.name or "plan",
        frame=problem.frame,
        labels=tuple(plan.labels),
        cranes=tuple(lugset.crane_names),
        candidates=tuple(lugset.names),
        points=np.array(lugset.points, dtype=float),
        EA=np.array(lugset.EA, dtype=float),
        rope_length=np.array(lugset.rope_length, dtype=float),
        boom_height=np.array(chosen.boom_heights, dtype=float),
        weight=float(problem.body.weight),
        cog=np.array(problem.body.cog, dtype=float),
        lift_height=float(problem.lift_height),
        yaw=float(problem.yaw),
        swl=np.array(lugset.swl, dtype=float),
        radius=tuple(None if c.radius is None else float(c.radius) for c in design.cranes),
        min_tension=float(problem.min_tension),
        heel_tolerance=float(problem.heel_tolerance),
        trim_tolerance=float(problem.trim_tolerance),
        cog_tolerance=np.array(problem.cog_envelope.half_widths, dtype=float),
        cog_shape=problem.cog_envelope.shape,
        hook_tolerance=np.array(lugset.hook_tolerance, dtype=float),
        band_low=(tensions - reach).min(axis=0),
        band_high=(tensions + reach).max(axis=0),
        rules=problem.rules,
        cog_searched=bool(design.chain.cog_searched) if design.chain is not None else False,
        tilt_ratio=tuple(tilt_ratio),
        skew=tuple(skew),
        accuracy=problem.readings,
    )
