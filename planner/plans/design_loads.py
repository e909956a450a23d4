"""Each crane's design load for a planned lug set: the rules' chain fed by the planner.

The plan's one defined design load per crane is the design hook load of
:class:`liftplan.model.rules.DesignLoadChain` (``docs/design-loads.md``), built from what the
planner found for the lug set:

* ``nominal``: the level tension T* the plan dials in (nominal CG);
* ``worst``: the rope's largest tension over the heel/trim box, the CG envelope and the
  hook-height tolerance, on the search's dense grid (the same grid and values as the search's
  ``rope_max``: T + sum_j |dT/dH_j| delta_j at each attitude), with the scenario where it occurs;
* ``tilt``: the hook's largest load at the rules' tilt (0027/ND 5.4: the worse of the tilt
  and the hook elevation difference over the hooks' spacing along each tilt direction), the
  hoists holding T*,
  over every tilt axis and the CG envelope's vertices;
* ``skew``: 1, because the searched worst (and the breakout tension) already holds every
  hook error within the tolerance (the skew the rules' 1.25 stands for; the plan's skew
  table shows the computed factors beside it);
* ``swl`` and ``radius``: the crane's chart SWL at its radius to the lug;
* ``breakout`` (with ``[plan] breakout_scene``): the crane's held tension when the bedded hull
  breaks out of the seabed, at its worst over the hook errors
  (:mod:`liftplan.planner.plans.breakout`); the chain's static input is
  then the larger of it and the worst in the box, and the plan says which governs.
* ``in_water`` (with ``[water]`` and ``plan.start_lift_height``): the crane's held tension at the
  start of the lift with the hull partly submerged, at its worst over the hook errors and the
  CG envelope (:mod:`liftplan.planner.plans.in_water`); the static input takes the larger too.
* with ``[hull] EI`` a set on which the flexible hull governs (:mod:`liftplan.planner.plans.flexible`)
  has its ``nominal`` and ``worst`` from the flexible hull at its worst states.

Then the chain's factors (weight contingency, DAF, rigging weight; yaw only with slings) turn
it into the design hook load, checked against the chart SWL, with the crane-code margin and,
where a candidate has a ``capacity``, the lug's design load. Utilisation is design hook load
/ chart SWL; every output uses this one figure.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.rules import CraneLoads, DesignLoadChain, LugLoads, TiltGeometry, governing_tilt
from liftplan.planner.plans.breakout import BreakoutCase, breakout_case
from liftplan.planner.plans.in_water import InWaterCase, in_water_case
from liftplan.planner.search.evaluator import DENSE
from liftplan.planner.search.scenarios import Scenario, box_attitudes, set_lugset


@dataclass(frozen=True)
class PlanChain(DesignLoadChain):
    """The rules' chain with the notes naming the planner's static input.

    :class:`~liftplan.model.rules.DesignLoadChain` calls its ``worst`` input the crane's worst
    tension over the tolerance box and the CG envelope. With a breakout case that input is the
    breakout tension where it is larger (:attr:`CraneDesign.static_input`), so the tilt and CoG
    notes here (:meth:`factor_notes`) say which load is the input and what it governs over;
    the numbers are the chain's own.

    Parameters
    ----------
    inputs : tuple of (str, CraneDesign)
        Per crane name, the planner's loads of that crane (for the notes).
    """

    inputs: tuple = ()

    def factor_notes(self, crane):
        """The chain's notes, the tilt and CoG ones from the planner's loads where it has them
        (:meth:`CraneDesign.tilt_note_for`, :meth:`CraneDesign.cog_note`; an empty one keeps
        the chain's own)."""
        notes = super().factor_notes(crane)
        design = dict(self.inputs).get(crane.name)
        if design is None:
            return notes
        mine = {
            "tilt": design.tilt_note_for(crane.tilt, self.tilt_note),
            "cog": design.cog_note(self.cog_searched),
        }
        notes.update({name: note for name, note in mine.items() if note})
        return notes


def rope_skew(lugset, preload, delta=None):
    """Each rope's load with every hook within +-its tolerance of its planned height, pose held.

    Parameters
    ----------
    lugset : LugSet
    preload : (n,)  [t]
    delta : float or (n,) array_like, optional  [m]
        Each hook's tolerance (one value: the same on every hook); default the lug set's own,
        hook by hook (``lugset.hook_tolerance``: a crane's ``hook_tolerance`` or the plan's,
        a floating crane's widened by its boom's wind tip error).

    Returns
    -------
    numpy.ndarray, shape (n,)  [t]
        T*_i + sum_j |dT_i / dH_j| delta_j.
    """
    gain = lugset.twist_gain(preload)
    delta = (
        lugset.hook_tolerance
        if delta is None
        else np.broadcast_to(np.asarray(delta, dtype=float), (lugset.n,))
    )
    return np.asarray(preload, dtype=float) + np.abs(gain) @ delta


@dataclass(frozen=True)
class TiltCase:
    """Where a hook's load at the rules' tilt is largest.

    Parameters
    ----------
    load : float  [t]
    tilt : float  [deg]
    axis : tuple of 3 float  [-]
        Unit vector of the tilt axis, z-up body frame (the body turns right-handed about it).
    cog_offset : tuple of 3 float  [m]
        CG-envelope vertex, z-up body frame.
    """

    load: float
    tilt: float
    axis: tuple
    cog_offset: tuple


@dataclass(frozen=True)
class CraneDesign:
    """One crane of a planned lug set: its static loads, where they occur, its design load.

    Parameters
    ----------
    label : str
        Planned lug label (L1..Ln).
    crane : str
    lug : str
        Candidate name.
    radius : float or None  [m]
        None: a crane with no position (no chart).
    swl : float  [t]
        Chart SWL at the radius.
    nominal : float  [t]
        Level tension, nominal CG.
    worst : float  [t]
        Largest tension over the box and the CG envelope.
    worst_at : Scenario
        Where ``worst`` occurs (z-up CG offset).
    tilt : TiltCase
    skewed : float  [t]
        Level tension with the hooks within the hook tolerance.
    design : CraneDesignLoad or None
        The chain's result; None when the chain could not be built (see
        :attr:`DesignLoads.missing`).
    breakout : float or None  [t]
        Held tension when the hull breaks out of the seabed (``[plan] breakout_scene``), at
        its worst over the hook errors; None without a breakout case.
    in_water : float or None  [t]
        Held tension at the start in water (``[water]``), at its worst over the hook errors
        and the CG envelope; None without ``[water]``.
    """

    label: str
    crane: str
    lug: str
    radius: float | None
    swl: float
    nominal: float
    worst: float
    worst_at: Scenario
    tilt: TiltCase
    skewed: float
    design: object = None
    breakout: float | None = None
    in_water: float | None = None

    @property
    def static_input(self):
        """The chain's static input  [t]: the worst in the box (at least the level tension),
        or the breakout or in-water tension where that is larger."""
        box = max(self.worst, self.nominal)
        return max(v for v in (box, self.breakout, self.in_water) if v is not None)

    @property
    def governs(self):
        """``"in_water"`` or ``"breakout"`` when that tension is the static input, else ``"box"``."""
        box = max(self.worst, self.nominal)
        if self.in_water is not None and self.in_water > max(box, self.breakout or 0.0):
            return "in_water"
        return "breakout" if self.breakout is not None and self.breakout > box else "box"

    @property
    def static_note(self):
        """Which load is the chain's static input, in words."""
        box = max(self.worst, self.nominal)
        if self.in_water is not None:
            water = f"in water at the start {self.in_water:.4g} t (hook errors at worst)"
            if self.governs == "in_water":
                return f"{water} governs over the worst in the box {box:.4g} t"
            if self.governs == "box":
                return f"worst in the box {box:.4g} t governs over {water}"
        if self.breakout is None:
            return f"worst in the box {box:.4g} t (no breakout case)"
        if self.governs == "breakout":
            return (
                f"breakout {self.breakout:.4g} t (hook errors at worst) governs over the worst "
                f"in the box {box:.4g} t"
            )
        return (
            f"worst in the box {box:.4g} t governs over breakout {self.breakout:.4g} t (hook errors at worst)"
        )

    def tilt_note_for(self, tilt_share, how=""):
        """The chain's tilt note: the share at the rules' tilt against the static input
        that governs (the worst in the box, or the breakout tension), then ``how`` the tilt
        was found."""
        if tilt_share is None:
            return ""
        box = max(self.worst, self.nominal)
        against = f"the worst in the box {box:.4g} t"  # a lower breakout: said by static_note
        if self.governs == "in_water":
            against = f"the tension in water {self.in_water:.4g} t (over the worst in the box {box:.4g} t)"
        if self.governs == "breakout":
            against = (
                f"the breakout tension {self.breakout:.4g} t (breakout governs over the worst "
                f"in the box {box:.4g} t)"
            )
        note = f"share at the rules' tilt {tilt_share:.4g} t against {against}"
        if tilt_share > self.static_input:
            note += ": the tilt governs"
        return note + (f"; {how}" if how else "")

    def cog_note(self, searched):
        """The chain's CoG note where breakout governs (the chain's ``worst`` is then the
        breakout tension, not a CoG extreme): the box worst over the nominal share; ""
        elsewhere (the chain's own note)."""
        if not searched or self.nominal <= 0.0 or self.governs != "breakout":
            return ""
        box = max(self.worst, self.nominal)
        return (
            f"CoG envelope searched by the planner: in the worst in the box (worst / nominal = "
            f"{box / self.nominal:.4f}); the breakout tension that governs is at the breakout "
            "scene's load point, no CoG envelope on it"
        )

    @property
    def skew(self):
        """Computed skew factor, skewed / nominal  [-] (None at a zero nominal load)."""
        return self.skewed / self.nominal if self.nominal > 0.0 else None

    @property
    def design_hook_load(self):
        """The design hook load  [t] (NaN when not computed)."""
        return self.design.design_hook_load if self.design is not None else float("nan")

    @property
    def design_tension(self):
        """The largest static rope tension the design hook load covers  [t] (NaN when not
        computed).

        The static hook load less the rigging weight, over the weight contingency and the CoG
        factor: the static share the chain was built from (the larger of the static input and
        the share at the rules' tilt) times the hook skew factor. A static tension at the
        nominal weight and CG (a Monte-Carlo draw of hook errors) is like for like with it;
        the design hook load adds the contingency, the DAF and the rigging on top.
        """
        if self.design is None:
            return float("nan")
        factor = {f.name: f.value for f in self.design.factors}
        return (self.design.static_hook_load - self.design.rigging_weight) / (
            factor["weight_contingency"] * factor["cog"]
        )

    @property
    def utilisation(self):
        """Design hook load / chart SWL at the radius  [-]: the plan's one utilisation."""
        return self.design_hook_load / self.swl


@dataclass(frozen=True)
class DesignLoads:
    """The rules' design loads of one planned lug set.

    Parameters
    ----------
    cranes : tuple of CraneDesign
        In the lug set's order (L1..Ln).
    tilt : float  [deg]
        The governing tilt used.
    tilt_note : str
    chain : DesignLoadChain or None
    missing : str or None
        Why no design load could be computed (a one-line reason), else None.
    breakout : BreakoutCase or None
        Each crane's load at breakout (``[plan] breakout_scene``), else None.
    """

    cranes: tuple
    tilt: float
    tilt_note: str
    chain: DesignLoadChain | None
    missing: str | None = None
    breakout: BreakoutCase | None = None
    in_water: InWaterCase | None = None

    @property
    def ok(self):
        """True when every design check is met (False when none could be computed)."""
        return self.missing is None and all(c.ok for c in self.checks)

    @property
    def max_utilisation(self):
        """Largest design hook load / chart SWL over the cranes  [-] (NaN when not computed)."""
        return max(c.utilisation for c in self.cranes)

    @property
    def checks(self):
        """Design hook load per crane, code margin per crane, lug design loads (with a capacity),
        and with a breakout case its hook load per crane and lowest tension."""
        if self.chain is None:
            out = [
                Check(
                    "design_loads",
                    "all cranes",
                    float("nan"),
                    float("nan"),
                    "-",
                    False,
                    note=f"not computed: {self.missing}",
                )
            ]
        else:
            out = list(self.chain.checks)
        out += [] if self.breakout is None else self.breakout.checks
        return out + ([] if self.in_water is None else self.in_water.checks)

    def crane(self, label):
        """The :class:`CraneDesign` of a planned lug label."""
        return next(c for c in self.cranes if c.label == label)

    def to_json(self):
        """The chain's JSON (``docs/design-loads.md``) with the tilt used; None parts when missing."""
        out = {"tilt": self.tilt, "tilt_note": self.tilt_note, "missing": self.missing}
        if self.chain is not None:
            out.update(self.chain.to_json())
        return out


class DesignBuilder:
    """Builds :class:`DesignLoads` for lug sets of one problem (shares the dense grid)."""

    def __init__(self, problem):
        self.problem = problem
        offsets = [tuple(map(float, o)) for o in problem.cog_envelope.offsets()]
        grid = box_attitudes(problem, DENSE, DENSE)
        self.dense = [Scenario(float(h), float(t), o) for o in offsets for h, t in grid]
        # at a fixed pose a hook's load is affine in the CG offset and the nominal CG is the
        # vertices' mean, so the vertices alone hold the worst
        self.vertices = offsets[1:] if len(offsets) > 1 else offsets
        self.searched = any(w > 0.0 for w in problem.cog_envelope.half_widths)

    def build(self, result, labels, governing=None):
        """The :class:`DesignLoads` of a ranked set; ``governing``: (nominal, worst) tensions [t]
        per rope of the hull that governs it when not the search's (the flexible hull,
        :mod:`~liftplan.planner.plans.flexible`), else None."""
        problem = self.problem
        lugset = set_lugset(problem, result.indices, result.cranes)
        preload = np.asarray(result.preload, dtype=float)
        tensions, gain = lugset.tensions_and_gain(preload, self.dense)
        tensions = tensions + np.abs(gain) @ lugset.hook_tolerance  # the hook errors' worst
        where = np.argmax(tensions, axis=0)
        skewed = preload  # the hook tolerance is in the worst: no skew factor on top
        names = lugset.crane_names
        tilt, tilt_note, at_tilt, missing = self._tilt(lugset, preload)
        fleet = [problem.fleet[j] for j in lugset.cranes]
        breakout = None if problem.breakout is None else breakout_case(problem, lugset, preload)
        water = None if problem.in_water is None else in_water_case(problem, lugset, preload)
        nominal, worst = preload, tensions[where, range(lugset.n)]
        if governing is not None:  # the hook errors are in its worst too: skew 1 on its level load
            nominal, worst = governing
            skewed = nominal
        cranes = []
        for k, label in enumerate(labels):
            case = at_tilt.get(names[k])
            cranes.append(
                CraneDesign(
                    label=label,
                    crane=names[k],
                    lug=lugset.names[k],
                    radius=None if fleet[k].position is None else float(lugset.radius[k]),
                    swl=float(lugset.swl[k]),
                    nominal=float(nominal[k]),
                    worst=float(worst[k]),
                    worst_at=self.dense[where[k]],
                    tilt=case,
                    skewed=float(skewed[k]),
                    breakout=None if breakout is None else float(breakout.worst[k]),
                    in_water=None if water is None else float(water.worst[k]),
                )
            )
        chain = None
        if missing is None:
            cranes, chain, missing = self.chained(cranes, tilt_note)
        return DesignLoads(
            cranes=tuple(cranes),
            tilt=tilt,
            tilt_note=tilt_note,
            chain=chain,
            missing=missing,
            breakout=breakout,
            in_water=water,
        )

    def chained(self, cranes, tilt_note):
        """The rules' chain over ``cranes`` (each a :class:`CraneDesign`): (the cranes with
        their design results, the :class:`PlanChain`, None), or (the cranes as given, None, why
        the chain could not be built)."""
        problem = self.problem
        try:
            chain = PlanChain(
                cranes=tuple(self._loads(c) for c in cranes),
                weight=problem.body.weight,
                rules=problem.rules,
                cog_searched=self.searched,
                tilt_note=tilt_note,
                inputs=tuple((c.crane, c) for c in cranes),
            )
            results = chain.results
        except InvalidScene as err:
            return list(cranes), None, str(err)
        return [replace(c, design=r) for c, r in zip(cranes, results)], chain, None

    def _tilt(self, lugset, preload):
        """(tilt [deg], note, {crane: TiltCase}, missing reason or None)."""
        problem = self.problem
        names = lugset.crane_names
        geometry = TiltGeometry(
            {n: tuple(p) for n, p in zip(names, lugset.points)},
            problem.body.cog,
            problem.body.weight,
            preload=dict(zip(names, preload.tolist())),
            stiffness=dict(zip(names, lugset.stiffness.tolist())),
        )
        design_tilt, elevation = problem.rules.design_tilt()
        try:
            if lugset.n > 2:  # per direction: the elevation difference over the spacing along it
                tilts = [geometry.tilt_along(d, design_tilt, elevation) for d in range(0, 180, 5)]
                tilt = max(tilts)
                note = (
                    f"{min(tilts):.2f} to {tilt:.2f} deg by direction: the worse of "
                    f"{design_tilt:g} deg and a {elevation:g} m hook elevation difference over "
                    "the hooks' spacing along each tilt"
                )
            else:
                spacing = geometry.least_spacing()
                tilt = governing_tilt(design_tilt, elevation, spacing)
                from_elevation = float(np.degrees(np.arcsin(elevation / spacing)))
                note = (
                    f"{tilt:.2f} deg: the worse of {design_tilt:g} deg and a {elevation:g} m "
                    f"hook elevation difference over the hook spacing {spacing:.2f} m "
                    f"({from_elevation:.2f} deg)"
                )
        except InvalidScene as err:
            return float("nan"), "", {}, str(err)
        try:
            worst = geometry.worst_per_direction(design_tilt, elevation, self.vertices)
        except EquilibriumNotFound as err:
            return tilt, note, {}, f"at the rules' tilt {tilt:.2f} deg: {err}"
        cases = {}
        for name, load in worst.items():
            psi = np.radians(load.direction)
            cases[name] = TiltCase(
                load=float(load.load),
                tilt=float(load.tilt),
                axis=(float(np.cos(psi)), float(np.sin(psi)), 0.0),
                cog_offset=tuple(load.cog_offset),
            )
        return tilt, note, cases, None

    def _loads(self, crane):
        candidate = self.problem.candidates[self.problem.names.index(crane.lug)]
        static = crane.static_input  # the box worst, or the breakout tension where larger
        return CraneLoads(
            name=crane.crane,
            nominal=crane.nominal,
            worst=static,
            tilt=crane.tilt.load,
            swl=crane.swl,
            radius=crane.radius,
            skew=crane.skew,
            lugs=(LugLoads(name=crane.lug, share=static, capacity=candidate.capacity),),
        )


def design_loads(problem, results, labels):
    """The rules' design loads of lug sets of one problem.

    Parameters
    ----------
    problem : PlanProblem
    results : sequence of SetResult
    labels : sequence of str
        Planned lug labels, in each set's lug order.

    Returns
    -------
    list of DesignLoads
    """
    builder = DesignBuilder(problem)
    return [builder.build(r, labels) for r in results]
