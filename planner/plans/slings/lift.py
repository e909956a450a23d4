"""What every sling-lift plan has in common: labels, the rules' chain, checks and outputs.

A sling plan (two cranes: :class:`~.two_crane.SlingPlan`; three or more with body-fixed apexes:
:class:`~.apex.ApexSlingPlan`) gives per crane the candidates its sling takes, its hook (level,
body frame), radius and chart SWL, hook loads and leg tensions. From those this base class
builds the labels, the rules' design-load chain per crane and per lug (the leg's sling angle
in the lug's design load; a spreader bar's weight as rigging on its hook), the checks, the
rigging scene that ``liftplan solve`` re-checks, and the contract's JSON keys.

With a weight curve and ``[strength]`` the hull girder is checked too: the rigging scene is
solved at every state the plan holds (:attr:`SlingLift.hung`, the states each subclass names in
``held_poses``), where the legs pull the lugs along their lines, and the largest |M| and |Q|
against the allowables over those states become the plan's ``bending_moment`` and
``shear_force`` checks (:mod:`liftplan.planner.plans.girder`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.rules import CraneLoads, DesignLoadChain, LugLoads
from liftplan.model.scene.objects import Analysis, Attitude, Crane, Lug, Scene
from liftplan.model.scene.rigging_gear import Leg, RiggingLimits, Sling, Spreader
from liftplan.model.statics.rigging import solve_rigging
from liftplan.planner.plans.breakout import hooks_breakout_json
from liftplan.planner.plans.common import InFileFrame, contract_json, weight_json
from liftplan.planner.plans.girder import applies as girder_applies
from liftplan.planner.plans.girder import girder_json, moved_body, solved_worst, worst_of
from liftplan.planner.search.scenarios import Scenario


def bar_weight(crane):
    """Weight of the spreader bar on ``crane``'s hook  [t] (0 without one)."""
    sling = crane.sling
    return 0.0 if sling is None or sling.spreader is None else sling.spreader.weight


def hook_tolerances(problem):
    """Each crane's hook-height tolerance, fleet order  [m]: its own, else ``plan.hook_tolerance``."""
    return np.array(
        [problem.hook_tolerance if c.hook_tolerance is None else c.hook_tolerance for c in problem.fleet]
    )


def rules_with_bars(problem):
    """The problem's rules with each spreader bar's weight added to its crane's rigging weight."""
    rules = problem.rules
    if not any(bar_weight(c) for c in problem.fleet):
        return rules
    weights = {c.name: rules.rigging_for(c.name) + bar_weight(c) for c in problem.fleet}
    return dataclasses.replace(rules, rigging_weight=weights)


@dataclass(frozen=True)
class HungState(Scenario):
    """A state a sling plan holds, as the rigging model hung the body there.

    Parameters
    ----------
    heel, trim : float  [deg]
        The solved pose's (where the body hung, not a target).
    cog_offset : tuple of 3 float  [m]
        From the nominal CG, body frame (z up).
    boom_shifts : tuple of float  [m]
        Each crane's boom tip (and so its hook) raised from the plan's, fleet order.
    """

    boom_shifts: tuple[float, ...] = ()


@dataclass(frozen=True)
class Hung:
    """One state of a sling plan solved on the rigging model.

    Parameters
    ----------
    state : HungState
        Its heel and trim the solved pose's (NaN when the solve failed).
    scene : Scene
        The plan's rigging scene posed so (:meth:`SlingLift.posed_scene`).
    eq : Equilibrium or None
        None when the rigging model did not solve it.
    error : EquilibriumNotFound or None
        Why it did not.
    """

    state: HungState
    scene: object
    eq: object = None
    error: EquilibriumNotFound | None = None

    @property
    def solved(self):
        """The Equilibrium; raises the solve's :class:`EquilibriumNotFound` when it failed."""
        if self.error is not None:
            raise self.error
        return self.eq


class SlingLift(InFileFrame):
    """Shared outputs of a sling plan; subclasses set ``problem`` and the per-crane arrays.

    Subclasses provide ``groups`` (candidate indices per crane), ``hooks`` (n, 3) [m],
    ``hook_radius``, ``hook_swl``, ``hook_nominal``, ``hook_worst`` (n,) [m, t, t, t],
    ``leg_angles``, ``legs_nominal``, ``legs_worst`` (tuples of (k,) arrays [deg, t, t]),
    ``top_legs``/``top_angles`` (per crane, None without a spreader), ``tilt_shares`` and
    ``tilt_note`` (each crane's body share at the rules' tilt), ``lift_text``, ``held_poses``
    (the states the plan holds, to solve on the rigging model) and ``girder_over`` (those
    states in words).
    """

    kind = "slings"

    #: Agreement of the plan's hook loads with the rigging model, as a fraction of W.
    AGREEMENT = 0.01

    # -- the breakout case and the rope lengths ------------------------------------------------
    @property
    def breakout(self):
        """Each crane's hook at breakout (``[plan] breakout_scene``), fleet order: a
        :class:`~liftplan.planner.plans.breakout.BreakoutCase` whose tensions are the body's
        shares on the hooks (a spreader bar's weight in its ``rigging``); None without one."""
        return None

    @property
    def ranked_breakouts(self):
        """(lug names, :class:`BreakoutCase`) of each ranked option (empty without a case)."""
        return []

    @cached_property
    def box_shares(self):
        """Each crane's largest share of the body in the box (its hook's worst less a bar, at
        least the level share)  [t]."""
        bars = self.bar_weights
        return np.maximum(np.asarray(self.hook_worst) - bars, np.asarray(self.hook_nominal) - bars)

    @cached_property
    def breakout_legs(self):
        """Each crane's lug legs at breakout  [t] (per crane, (k,)): its worst hook load there
        (hook errors at worst, with a bar's weight) split by the sling's statics at level; None
        without a breakout case."""
        case = self.breakout
        if case is None:
            return None
        return tuple(
            np.asarray(self.level_legs(c, float(case.worst[c] + self.bar_weights[c])), dtype=float)
            for c in range(len(self.crane_names))
        )

    @property
    def rope_lengths(self):
        """Planned label -> the hoist rope's unstretched length (tip to hook) of the crane whose
        sling takes that lug  [m] (the plan JSON's ``rope_lengths``, keyed as a single-rope plan's)."""
        length = {c.name: c.rope_length for c in self.problem.fleet}
        return {label: length[crane] for label, crane in self.cranes.items()}

    def with_lengths(self, search, stats=None):
        """This plan with the rope-length search that chose its lengths
        (:mod:`liftplan.planner.plans.lengths`); ``stats`` over every trial where the plan
        has a search's stats."""
        return dataclasses.replace(self, lengths=search)

    @property
    def hook_tilt_text(self):
        """What the crew's hook errors do to the plan, one sentence (None: said elsewhere)."""
        return None

    def hook_tilt_json(self):
        """The hook errors' tilt for the plan JSON's ``hooks`` (empty: none computed)."""
        return {}

    @property
    def hook_skews(self):
        """Computed skew factor per crane (None: the rules' default where it applies)."""
        return [None] * len(self.problem.fleet)

    @property
    def crane_names(self):
        return [c.name for c in self.problem.fleet]

    @cached_property
    def labels(self):
        """Planned lug labels L1, L2, ...: crane 1's lugs, then crane 2's, ..."""
        count = sum(len(g) for g in self.groups)
        return tuple(f"L{i + 1}" for i in range(count))

    def _per_lug(self, per_crane_arrays):
        values = [float(v) for arr in per_crane_arrays for v in np.ravel(arr)]
        return dict(zip(self.labels, values))

    def _repeat(self, per_crane):
        return self._per_lug([np.full(len(g), v) for g, v in zip(self.groups, per_crane)])

    @property
    def lugs(self):
        names = self.problem.names
        return dict(zip(self.labels, [names[i] for g in self.groups for i in g]))

    @property
    def cranes(self):
        """Planned label -> the crane whose sling takes that lug."""
        names = self.crane_names
        return dict(zip(self.labels, [names[c] for c, g in enumerate(self.groups) for _ in g]))

    @cached_property
    def bar_weights(self):

        return np.array([bar_weight(c) for c in self.problem.fleet])

    @cached_property
    def hook_heights(self):
        """Hook height above the datum at level, per crane  [m]."""
        return self.problem.lift_height + np.asarray(self.hooks)[:, 2]

    @cached_property
    def crane_boom_heights(self):
        """Boom-tip height H per crane: hook height + hoist rope l0 + its stretch  [m]."""
        fleet = self.problem.fleet
        return np.array(
            [
                self.hook_heights[c] + fleet[c].rope_length + self.hook_nominal[c] / fleet[c].stiffness
                for c in range(len(fleet))
            ]
        )

    @property
    def boom_heights(self):
        return self._repeat(self.crane_boom_heights)

    @property
    def tensions(self):
        """Planned label -> leg tension at level, nominal CG  [t]."""
        return self._per_lug(self.legs_nominal)

    @property
    def spread(self):
        return float(np.ptp(np.concatenate(self.legs_nominal)))

    @property
    def worst_spread(self):
        """Largest max - min leg tension found over the tolerance and CG envelope  [t]."""
        return float(np.ptp(np.concatenate(self.legs_worst)))

    @property
    def radius(self):
        return self._repeat(self.hook_radius)

    @property
    def swl(self):
        return self._repeat(self.hook_swl)

    @property
    def utilisation(self):
        """Planned label -> the crane's nominal hook load over its SWL  [-]."""
        return self._repeat(np.asarray(self.hook_nominal) / np.asarray(self.hook_swl))

    # -- the rules' chain ----------------------------------------------------------------------
    @cached_property
    def design(self):
        """The rules' design-load chain per crane and per lug (``DesignLoadChain``), or the
        reason it could not be built (str)."""

        problem = self.problem
        if len(self.crane_names) > 1 and any(t is None for t in self.tilt_shares):
            # the chain would only say "tilt: missing"; the reason is the tilt case's
            return self.tilt_note or "rules' tilt not evaluated"
        cranes = []
        for c, name in enumerate(self.crane_names):
            group = self.groups[c]
            angles = np.asarray(self.leg_angles[c])
            worst_legs = np.asarray(self.legs_worst[c])
            nominal = float(self.hook_nominal[c] - self.bar_weights[c])
            worst = float(self.box_shares[c])
            if self.breakout is not None:  # the static input: the larger of box and breakout
                worst = max(worst, float(self.breakout.worst[c]))
                worst_legs = np.maximum(worst_legs, self.breakout_legs[c])
            lugs = tuple(
                LugLoads(
                    name=problem.names[i],
                    share=float(t * math.sin(math.radians(a))),
                    sling_angle=float(min(a, 90.0)),
                    capacity=problem.candidates[i].capacity,
                )
                for i, a, t in zip(group, angles, worst_legs)
            )
            cranes.append(
                CraneLoads(
                    name=name,
                    nominal=nominal,
                    worst=worst,
                    tilt=self.tilt_shares[c],
                    swl=float(self.hook_swl[c]),
                    radius=float(self.hook_radius[c]),
                    skew=self.hook_skews[c],
                    lugs=lugs,
                )
            )
        try:
            chain = DesignLoadChain(
                cranes=tuple(cranes),
                weight=problem.body.weight,
                rules=rules_with_bars(problem),
                cog_searched=any(w > 0 for w in problem.cog_envelope.half_widths),
                tilt_note=self.tilt_note,
            )
            chain.results  # noqa: B018 - builds (and validates) every factor now
        except InvalidScene as err:
            return str(err)
        return chain

    @property
    def design_hook_loads(self):
        """Per crane the rules' design hook load  [t] (NaN when the chain could not be built)."""
        if isinstance(self.design, str):
            return np.full(len(self.crane_names), np.nan)
        return np.array([r.design_hook_load for r in self.design.results])

    @property
    def design_utilisation(self):
        return self.design_hook_loads / np.asarray(self.hook_swl)

    def _lift_checks(self):
        """Checks common to every sling plan: the chain's, the sling angles, taut legs and
        agreement with the rigging model."""
        problem = self.problem
        out = []
        if isinstance(self.design, str):
            out.append(
                Check(
                    name="design_chain",
                    subject="plan",
                    value=float("nan"),
                    limit=0.0,
                    unit="-",
                    ok=False,
                    note=self.design,
                )
            )
        else:
            out += self.design.checks
        angles = [a for arr in self.leg_angles for a in np.ravel(arr)]
        for label, angle in zip(self.labels, angles):
            out.append(
                Check.lower(
                    "sling_angle",
                    f"{label} ({self.lugs[label]})",
                    angle,
                    problem.min_sling_angle,
                    "deg",
                    note="from the horizontal",
                )
            )
        for c, top in enumerate(self.top_angles):
            if top is not None:
                for j, angle in enumerate(np.ravel(top)):
                    out.append(
                        Check.lower(
                            "sling_angle",
                            f"{self.crane_names[c]} top leg {j + 1}",
                            angle,
                            problem.min_sling_angle,
                            "deg",
                            note="spreader top leg, from the horizontal",
                        )
                    )
        solved = self.verified.tensions
        for c, name in enumerate(self.crane_names):
            out.append(
                Check.upper(
                    "model_agreement",
                    name,
                    abs(solved[name] - self.hook_nominal[c]),
                    self.AGREEMENT * problem.body.weight,
                    "t",
                    note="rigging model hook load vs the plan's",
                )
            )
        if self.breakout is not None:
            out += self.breakout.checks
        return out + self._girder_checks()

    # -- the hull girder -------------------------------------------------------------------------
    @cached_property
    def hung(self):
        """Every state of ``held_poses`` solved on the rigging model (list of :class:`Hung`): a
        failed solve is kept with its error, never with a number."""
        return [self.hang(offset, shifts) for offset, shifts in self.held_poses]

    def hang(self, cog_offset, boom_shifts):
        """The plan's rigging scene posed (:meth:`posed_scene`) and solved.

        Parameters
        ----------
        cog_offset : (3,)  [m]
            From the nominal CG, body frame (z up).
        boom_shifts : (n,)  [m]
            Each crane's boom tip raised, fleet order.

        Returns
        -------
        Hung
            The solved pose's heel and trim in its state; the error when it did not solve.
        """
        offset = tuple(float(v) for v in cog_offset)
        shifts = tuple(float(v) for v in boom_shifts)
        scene = self.posed_scene(offset, shifts)
        try:
            eq = solve_rigging(scene)
        except EquilibriumNotFound as err:
            return Hung(HungState(float("nan"), float("nan"), offset, shifts), scene, error=err)
        state = HungState(float(eq.pose.heel), float(eq.pose.trim), offset, shifts)
        return Hung(state, scene, eq)

    def posed_scene(self, cog_offset, boom_shifts):
        """The rigging scene with the CG moved by ``cog_offset`` [m] and each crane's boom tip
        raised by ``boom_shifts`` [m]; its weight curve moved with the CG
        (:func:`~..girder.moved_body`) when the girder is checked, else left out with
        ``[strength]`` (the rigging solve does not use them)."""
        scene = self.scene
        if not girder_applies(self.problem):
            scene = dataclasses.replace(
                scene, body=dataclasses.replace(scene.body, weight_curve=None), strength=None
            )
        cranes = tuple(
            dataclasses.replace(
                crane, boom_height=crane.boom_height + shift, tip=(*crane.tip[:2], crane.tip[2] + shift)
            )
            for crane, shift in zip(scene.cranes, boom_shifts)
        )
        return dataclasses.replace(scene, body=moved_body(scene.body, cog_offset), cranes=cranes)

    @cached_property
    def girder(self):
        """The hull girder's largest |M| and |Q| against the allowables over the solved states
        (:class:`~..girder.GirderWorst`, bending first; empty when not checked)."""
        if not girder_applies(self.problem):
            return ()
        return worst_of(solved_worst(h.scene, h.eq, h.state) for h in self.hung if h.error is None)

    def _girder_checks(self):
        """The girder's checks, and a failed one when states did not solve (their girder unknown)."""
        if not girder_applies(self.problem):
            return []
        out = [w.check(self.girder_over) for w in self.girder]
        failed = [h for h in self.hung if h.error is not None]
        if failed:
            first = failed[0].state
            out.append(
                Check.upper(
                    "girder_states",
                    "rigging model",
                    len(failed),
                    0,
                    "-",
                    note=(
                        f"{len(failed)} of {len(self.hung)} states not solved, their hull girder "
                        f"unknown; first: CG offset {tuple(round(v, 3) for v in first.cog_offset)} m, "
                        f"boom shifts {tuple(round(v, 4) for v in first.boom_shifts)} m: {failed[0].error}"
                    ),
                )
            )
        return out

    def scenario_json(self, scenario):
        """A hung state as JSON: heel, trim [deg], CG offset and position [m] in the file's frame,
        and each crane's boom shift [m]."""
        return super().scenario_json(scenario) | {
            "boom_shifts": dict(zip(self.crane_names, scenario.boom_shifts))
        }

    # -- the rigging scene ---------------------------------------------------------------------
    @cached_property
    def scene(self):
        """The plan as a rigging scene (hooks free, legs inclined) for ``liftplan solve``, in the
        planning file's frame (``scene.frame``; its coordinates z-up, as in every Scene)."""

        problem = self.problem
        yaw = rotation_matrix(0.0, 0.0, problem.yaw)
        lugs, cranes = [], []
        for c, (crane, group) in enumerate(zip(problem.fleet, self.groups)):
            names = [problem.names[i] for i in group]
            lugs += [Lug(name=n, at=tuple(problem.points[i])) for n, i in zip(names, group)]
            tip_xy = (yaw @ self.hooks[c])[:2]
            sling = crane.sling
            spreader = None
            legs = tuple(Leg(lug=n, length=sling.length, EA=sling.EA) for n in names)
            if sling.spreader is not None:
                bar = sling.spreader
                spreader = Spreader(
                    length=bar.length,
                    weight=bar.weight,
                    top=tuple(Leg(lug=None, length=bar.top_length, EA=sling.EA) for _ in range(2)),
                )
                legs = tuple(
                    Leg(lug=n, length=sling.length, EA=sling.EA, end=j + 1) for j, n in enumerate(names)
                )
            cranes.append(
                Crane(
                    name=crane.name,
                    EA=crane.EA,
                    rope_length=crane.rope_length,
                    boom_height=float(self.crane_boom_heights[c]),
                    swl=float(self.hook_swl[c]),
                    tip=(float(tip_xy[0]), float(tip_xy[1]), float(self.crane_boom_heights[c])),
                    sling=Sling(legs=legs, spreader=spreader),
                )
            )
        return Scene(
            body=problem.body,
            lugs=tuple(lugs),
            cranes=tuple(cranes),
            attitude=Attitude(lift_height=problem.lift_height, yaw=problem.yaw),
            analysis=Analysis(model="rigging"),
            rigging=RiggingLimits(min_sling_angle=problem.min_sling_angle),
            name=f"{problem.name or 'plan'}: chosen slings",
            frame=problem.frame,
            strength=problem.strength,
        )

    @cached_property
    def verified(self):
        """The plan solved on the rigging model (free hooks, elastic legs): Equilibrium."""

        return solve_rigging(self.scene)

    def _lift_json(self):
        names, problem = self.crane_names, self.problem
        design = None if isinstance(self.design, str) else self.design.to_json()

        return contract_json(self) | {
            "weight": weight_json(self.problem),
            "lift": self.lift_text,
            "hook_loads": dict(zip(names, np.asarray(self.hook_nominal, dtype=float).tolist())),
            "worst_hook_loads": dict(zip(names, np.asarray(self.hook_worst, dtype=float).tolist())),
            "design_hook_loads": dict(zip(names, self.design_hook_loads.tolist())),
            "sling_angles": self._per_lug(self.leg_angles),
            "worst_leg_tensions": self._per_lug(self.legs_worst),
            "spreader_top_legs": {
                names[c]: np.asarray(t, dtype=float).tolist()
                for c, t in enumerate(self.top_legs)
                if t is not None
            },
            "design_loads": design,
            "girder": girder_json(self.girder, self.scenario_json),
            # the inputs that shape the plan, echoed so a reader sees them honoured
            "hooks": {
                "tolerance": dict(zip(names, hook_tolerances(problem).tolist())),
                **self.hook_tilt_json(),
            },
            "limits": {
                "search": problem.search,
                "gap": problem.gap,
                "time_limit": problem.time_limit,
                "work_limit": problem.work_limit,
            },
            **hooks_breakout_json(self),
            **(
                {}
                if self.lengths is None
                else {"rope_lengths": self.rope_lengths, "rope_length_search": self.lengths.to_json()}
            ),
        }
