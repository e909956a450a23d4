"""The held-preload plan: single ropes, a level preload the crews dial in (``plan_held``).

A :class:`Plan` holds the chosen lug set (labelled L1..Ln), the boom heights that dial in
its level preload, the ranking of the best sets, and what an engineer hands over with it:
each crane's design load by the rules' chain (:mod:`.design_loads`, ``docs/design-loads.md``)
against its chart SWL, skew load factors from the hook-height tolerance, and the operators'
guidance table (tension change per step of heel and of trim). Coordinates a person reads
(JSON, console, report) are in the frame of the planning file (:meth:`Plan.in_file_frame`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.errors import PlanInfeasible
from liftplan.model.scene.objects import Analysis, Attitude, Crane, Lug, Scene
from liftplan.planner.plans.breakout import breakout_json
from liftplan.planner.plans.common import InFileFrame, contract_json, weight_json
from liftplan.planner.plans.design_loads import CraneDesign, DesignBuilder, rope_skew
from liftplan.planner.plans.flexible import flexible_hull_json
from liftplan.planner.plans.girder import applies as girder_applies
from liftplan.planner.plans.girder import girder_json, set_girder
from liftplan.planner.plans.in_water import in_water_json
from liftplan.planner.plans.vessel_loads import vessel_plans, wind_json
from liftplan.planner.plans.watch_basis import watch_basis
from liftplan.planner.problem.definition import DEFAULT_SKEW_FACTOR, PlanProblem
from liftplan.planner.problem.vessels import series_problem, uses_vessels
from liftplan.planner.search.bounds import AdmissibleTensions
from liftplan.planner.search.evaluator import Interrupted, SearchStats, SetResult, robust
from liftplan.planner.search.methods import search
from liftplan.planner.search.progress import phase
from liftplan.planner.search.scenarios import Scenario, set_lugset

#: Heel and trim steps of the guidance table  [deg] (Choi & Shin 2003, Table 3).
GUIDANCE_STEP = 5.0
GUIDANCE_STEPS = 2

#: One crane's loads against its chart (the README's ``p.capacity[0].utilisation``).
CraneCapacity = CraneDesign


@dataclass(frozen=True)
class SkewLoad:
    """Skew load factor of a rope or a diagonal pair from the hook-height tolerance.

    Parameters
    ----------
    lugs : tuple of str
        One label (a rope) or two (a diagonal pair).
    nominal : float  [t]
    skewed : float  [t]   largest load with every hook within +-its own hook tolerance
    """

    lugs: tuple[str, ...]
    nominal: float
    skewed: float

    @property
    def factor(self):
        """Skewed over nominal load  [-] (Noble Denton's default is 1.25)."""
        return self.skewed / self.nominal


@dataclass(frozen=True)
class GuidanceStep:
    """Tension change for one step of heel or trim (the 2003 paper's Table 3).

    Parameters
    ----------
    angle : str  ``"heel"`` or ``"trim"``
    start, end : float  [deg]
    change : dict of str to float  [t]   by lug label
    within_model : bool
        False where a rope would go slack inside the step (the numbers then no longer hold).
    """

    angle: str
    start: float
    end: float
    change: dict[str, float]
    within_model: bool


@dataclass(frozen=True)
class CrewMargin:
    """The plan held (lugs, boom heights) with the hooks worse than assumed.

    Parameters
    ----------
    factor : float  [-]   the hook tolerance multiplied by this
    tolerance : numpy.ndarray  [m]   each hook's tolerance at that factor
    worst_spread : float  [t]   over the box, the CG envelope and the hook errors
    rope_max : numpy.ndarray  [t]   each rope's largest tension (in the box, and at breakout
        with a breakout case)
    lowest : float  [t]   the lowest tension, the same places (below 0: a rope would go slack, the affine
        form no longer holds, and the figures are only an estimate)
    limit : numpy.ndarray  [t]   the search's limit of each rope (chart SWL / DAF, less
        rigging, over contingency)
    swl : numpy.ndarray  [t]
    """

    factor: float
    tolerance: np.ndarray
    worst_spread: float
    rope_max: np.ndarray
    lowest: float
    limit: np.ndarray
    swl: np.ndarray

    @property
    def within_limits(self):
        """Every rope within its limit and above zero."""
        return bool(np.all(self.rope_max <= self.limit + 1e-9) and self.lowest > 0.0)

    def verdict(self, labels):
        """``"within the limits"``, or ``"EXCEEDS"`` with what: the rope furthest over its
        limit (``L2 387.9 t > 317.5 t``) and a rope going slack."""
        if self.within_limits:
            return "within the limits"
        what = []
        k = int(np.argmax(self.rope_max - self.limit))
        if self.rope_max[k] > self.limit[k] + 1e-9:
            what.append(f"{labels[k]} {self.rope_max[k]:.1f} t > {self.limit[k]:.1f} t")
        if self.lowest <= 0.0:
            what.append(f"a rope slack (lowest {self.lowest:.1f} t)")
        return "EXCEEDS: " + ", ".join(what)


@dataclass(frozen=True)
class Plan(InFileFrame):
    """A lift plan: chosen lugs, boom heights and the checks that go with them.

    Parameters
    ----------
    problem : PlanProblem
    ranking : list of SetResult
        Best first; ``ranking[0]`` is the plan.
    stats : SearchStats
    lengths : LengthSearch or None
        How the rope lengths were chosen (:mod:`liftplan.planner.plans.lengths`); None when every
        crane's length was given. With it, ``problem`` is the problem at the chosen lengths.
    girders : list of tuple of GirderWorst, optional
        The hull girder's worst of each ranked set when already computed (by
        :func:`girder_first`); else computed when first asked for.
    hull_models : list of HullModel, optional
        With ``[hull] EI``: each ranked set on the rigid and the flexible hull at its worst
        states, and which governs (:mod:`.flexible`); None without.
    hull_search : HullSearch, optional
        With ``[hull] EI`` or ``[water]``: how the ranking was redone (:mod:`.hull_water`).
    designs : list of DesignLoads, optional
        The rules' design loads of each ranked set when already computed (by
        :func:`design_first`); else computed when first asked for.
    passed_over : int
        How many sets the ranking had before the plan that fail a design-load check or
        overload the hull girder (:func:`design_first` ranked them after it).
    """

    problem: PlanProblem
    ranking: list[SetResult]
    stats: SearchStats
    lengths: object = None
    girders: list | None = None
    hull_models: list | None = None
    hull_search: object = None
    designs: list | None = None
    passed_over: int = 0

    # -- the chosen set ------------------------------------------------------------------
    @property
    def kind(self):
        """``"lengths"`` when the rope lengths were chosen too, else ``"held"``."""
        return "lengths" if self.lengths is not None else "held"

    @property
    def chosen(self):
        return self.ranking[0]

    @cached_property
    def labels(self):
        """Planned lug labels L1..Ln, in candidate order."""
        return tuple(f"L{i + 1}" for i in range(len(self.chosen.lugs)))

    @property
    def lugs(self):
        """Planned label -> candidate name."""
        return dict(zip(self.labels, self.chosen.lugs))

    @property
    def boom_heights(self):
        """Planned label -> boom-tip height H  [m]."""
        return dict(zip(self.labels, self.chosen.boom_heights.tolist()))

    @property
    def tensions(self):
        """Planned label -> level tension with the nominal CG  [t]."""
        return dict(zip(self.labels, self.chosen.preload.tolist()))

    @property
    def rope_lengths(self):
        """Planned label -> unstretched rope length l0 of the crane on that lug  [m]."""
        return {label: self.problem.fleet[j].rope_length for label, j in zip(self.labels, self.chosen.cranes)}

    @property
    def spread(self):
        """Max - min of the level tensions  [t]."""
        return float(np.ptp(self.chosen.preload))

    @property
    def worst_spread(self):
        """Largest max - min tension over the tolerance box and CG envelope  [t]: with the
        spread objective and ``[hull] EI`` or ``[water]``, the governing value the set is ranked
        on (the flexible hull's where it governs, the start in water's where it is larger)."""
        if self.hull_search is not None and self.problem.objective == "spread":
            return float(self.hull_search.values[0])
        return self.chosen.worst_spread

    @property
    def objective(self):
        """``"spread"`` or ``"utilisation"``: what the plan keeps small."""
        return self.problem.objective

    @property
    def cranes(self):
        """Planned label -> name of the crane on that lug."""
        return dict(zip(self.labels, self.chosen.crane_names))

    @property
    def radius(self):
        """Planned label -> the crane's radius to its lug  [m]."""
        return dict(zip(self.labels, self.chosen.radius.tolist()))

    @property
    def swl(self):
        """Planned label -> the crane's SWL at that radius  [t]."""
        return dict(zip(self.labels, self.chosen.swl.tolist()))

    @property
    def utilisation(self):
        """Planned label -> nominal (level) tension over the crane's SWL there  [-]."""
        return dict(zip(self.labels, (self.chosen.preload / self.chosen.swl).tolist()))

    @property
    def worst_utilisation_spread(self):
        """Largest max - min of T_i / SWL_i over the tolerance box and CG envelope  [-]."""
        return self.chosen.worst_utilisation_spread

    @cached_property
    def lugset(self):
        return set_lugset(self.problem, self.chosen.indices, self.chosen.cranes)

    def tensions_at(self, heel, trim, cog_offset=(0.0, 0.0, 0.0)):
        """Tensions with the plan's preload held, at many attitudes.

        Parameters
        ----------
        heel, trim : array_like  [deg]
        cog_offset : tuple of 3 float  [m]

        Returns
        -------
        numpy.ndarray, shape (m, n)  [t]
            Negative values mean the rope went slack (the linear model no longer holds).
        """
        heel, trim = np.broadcast_arrays(np.atleast_1d(heel), np.atleast_1d(trim))
        scenarios = [Scenario(float(h), float(t), tuple(cog_offset)) for h, t in zip(heel, trim)]
        return self.lugset.tensions(self.chosen.preload, scenarios)

    @cached_property
    def scene(self):
        """The chosen plan as a :class:`~liftplan.model.scene.objects.Scene` for ``solve``.

        Its ``elastic`` solve gives the plan's level tensions at the plan's lift height.
        """
        problem, chosen = self.problem, self.chosen
        lugs = tuple(
            Lug(name=label, at=tuple(problem.points[i])) for label, i in zip(self.labels, chosen.indices)
        )
        cranes = tuple(
            Crane(
                lug=label,
                # a floating crane: the rope's own EA and its vessel (in series, the plan's EA)
                EA=problem.fleet[j].rope_EA or problem.fleet[j].EA,
                boom_height=float(h),
                rope_length=problem.fleet[j].rope_length,
                swl=float(swl),
                vessel=problem.fleet[j].vessel,
            )
            for label, j, h, swl in zip(self.labels, chosen.cranes, chosen.boom_heights, chosen.swl)
        )
        return Scene(
            body=problem.body,
            lugs=lugs,
            cranes=cranes,
            attitude=Attitude(lift_height=problem.lift_height, yaw=problem.yaw),
            # in water the written scene carries [hull] and [water]: solve picks its model
            analysis=Analysis(model=None if problem.in_water is not None else "elastic"),
            name=f"{problem.name or 'plan'}: chosen lugs",
            strength=problem.strength,
            girder=problem.hull_stiffness,  # solve keeps the flexible hull where it changes T > 1 %
        )

    @cached_property
    def named_scene(self):
        """:attr:`scene` under the names a person uses, as ``plan_scene.toml`` holds it: each lug
        by its candidate name, each crane by its name (and its lug), in the planning file's
        frame (``scene.frame``; the coordinates stay z-up, as in every Scene). Same numbers, so
        its solve gives the same tensions, keyed by candidate name."""
        scene, names = self.scene, self.lugs
        return dataclasses.replace(
            scene,
            lugs=tuple(dataclasses.replace(lug, name=names[lug.name]) for lug in scene.lugs),
            cranes=tuple(
                dataclasses.replace(crane, lug=names[crane.lug], name=self.cranes[crane.lug])
                for crane in scene.cranes
            ),
            frame=self.frame,
        )

    # -- checks to hand over ------------------------------------------------------------
    @cached_property
    def _twist_gain(self):
        return self.lugset.twist_gain(self.chosen.preload)

    @cached_property
    def _design_builder(self):
        return DesignBuilder(self.problem)

    @cached_property
    def design_loads(self):
        """The rules' design loads of the chosen set (:class:`~.design_loads.DesignLoads`)."""
        if self.designs is not None:
            return self.designs[0]
        return self._design_builder.build(self.chosen, self.labels, self._governing(0))

    def _governing(self, k):
        """(nominal, worst) of ranked set k on the flexible hull where it governs, else None."""
        if not self.hull_models or self.hull_models[k].used != "flexible":
            return None
        return self.hull_models[k].nominal, self.hull_models[k].worst

    @cached_property
    def ranked_design(self):
        """The same design loads for every ranked set, best first (``ranked_design[0]`` is
        :attr:`design_loads`)."""
        if self.designs is not None:
            return self.designs
        return [self.design_loads] + [
            self._design_builder.build(r, self.labels, self._governing(k))
            for k, r in enumerate(self.ranking[1:], start=1)
        ]

    @cached_property
    def ranked_girder(self):
        """The hull girder's worst |M| and |Q| of every ranked set, best first (each a tuple
        of :class:`~.girder.GirderWorst`; empty without a weight curve and ``[strength]``)."""
        if self.girders is not None:
            return self.girders
        return [set_girder(self.problem, r, self._design_builder.dense) for r in self.ranking]

    @property
    def girder(self):
        """The chosen set's worst |M| and |Q| over the box, the CG envelope and the hook errors
        (:class:`~.girder.GirderWorst`, bending first; empty when not checked)."""
        return self.ranked_girder[0]

    @property
    def design_note(self):
        """What ranking the sets by the design-load checks (:func:`design_first`) did, in one
        line; "" when the search's best meets them."""
        what = "every design-load check" + (" and keeps the hull girder" if self.girder else "")
        if not meets_checks(self.design_loads, self.girder):
            return (
                f"none of the {len(self.ranking)} ranked sets meets {what}: the plan is the best "
                "ranked set, its failing checks flagged (a larger top ranks more sets)"
            )
        if self.passed_over:
            return (
                f"the plan is the best ranked set that meets {what}: the {self.passed_over} "
                f"set{'s' if self.passed_over > 1 else ''} ranked better by the objective "
                f"fail{'' if self.passed_over > 1 else 's'} one and "
                f"{'are' if self.passed_over > 1 else 'is'} ranked after it"
            )
        return ""

    @cached_property
    def clearances(self):
        """Per planned lug label: (crane, least plan distance [m] from its boom and hoist line to
        another crane's, that crane's name); empty without crane positions
        (:mod:`~liftplan.planner.problem.clearance`)."""
        d = self.problem.boom_distances
        if d is None:
            return {}
        idx, cranes, names = self.chosen.indices, self.chosen.cranes, self.chosen.crane_names
        out = {}
        for k, label in enumerate(self.labels):
            others = [d[idx[k], cranes[k], idx[m], cranes[m]] for m in range(len(idx))]
            m = int(np.argmin(others))
            if np.isfinite(others[m]):
                out[label] = (names[k], float(others[m]), names[m])
        return out

    @property
    def capacity(self):
        """Per crane (L1..Ln): static loads, where they occur, and the design hook load against
        the chart SWL (:class:`~.design_loads.CraneDesign`; ``utilisation`` = design / SWL)."""
        return list(self.design_loads.cranes)

    @cached_property
    def checks(self):
        """Every check of the plan that can fail, as :class:`~liftplan.model.checks.Check`.

        The rules' chain: per crane the design hook load against the chart SWL at its radius
        and the crane code's margin over the calculated share, per lug with a ``capacity`` its
        design load, with a breakout case each crane's breakout hook load, with crane positions
        each crane's least plan clearance to the others' booms and hoist lines; per plan: the lowest
        tension in the box against min_tension and, with a weight curve and ``[strength]``, the
        hull girder's worst |M| and |Q| against the allowables (:mod:`.girder`).
        """
        out = list(self.design_loads.checks) + [w.check() for w in self.girder]
        out += [check for vessel in self.vessels for check in vessel.checks()]
        out += clearance_checks(self.clearances, self.problem.crane_clearance)
        out.append(
            Check.lower(
                "min_tension",
                "all ropes",
                self.chosen.tension_range[0],
                self.problem.min_tension,
                "t",
                note="lowest tension in the box",
            )
        )
        if self.hull_models and self.hull_models[0].used == "flexible":
            out.append(
                Check.lower(
                    "flexible_min_tension",
                    "all ropes",
                    self.hull_models[0].lowest,
                    self.problem.min_tension,
                    "t",
                    note="lowest tension on the flexible hull at the plan's worst states, hook errors "
                    "at worst",
                )
            )
        return out

    @cached_property
    def vessels(self):
        """Each floating crane's heel, trim, tip drop and levelling ballast, at the level tension
        and over the worst case (:mod:`.vessel_loads`); empty when every crane is on land."""
        return vessel_plans(self)

    @cached_property
    def skew(self):
        """Skew loads: each rope, and for four lugs each diagonal pair (plan order), every hook
        within its own tolerance (``lugset.hook_tolerance``)."""
        delta = self.lugset.hook_tolerance
        gain, preload = self._twist_gain, self.chosen.preload
        skewed = rope_skew(self.lugset, preload)
        out = [SkewLoad((label,), float(t), float(ts)) for label, t, ts in zip(self.labels, preload, skewed)]
        for i, j in self.diagonals:
            out.append(
                SkewLoad(
                    (self.labels[i], self.labels[j]),
                    float(preload[i] + preload[j]),
                    float(preload[i] + preload[j] + np.abs(gain[i] + gain[j]) @ delta),
                )
            )
        return out

    @property
    def hook_tolerances(self):
        """Planned label -> the hook's own height tolerance  [m]: its crane's ``hook_tolerance``
        or the plan's, a floating crane's widened by its boom's wind tip error at its lug."""
        return dict(zip(self.labels, self.lugset.hook_tolerance.tolist()))

    def tolerance_text(self, factor=1.0, unit=" m", short=False):
        """Each hook's tolerance (times ``factor``) in words: ``+-0.02 m on every hook``, or
        per hook with its crane, ``L1 (Crane C) +-0.1 m, L2 (Sheerleg A) +-0 m, ...``
        (``unit`` after each value: ``""`` in a table whose column names it); ``short``: the
        hooks off the most common value by name, then ``the others +-0 m``."""
        values = np.round(factor * self.lugset.hook_tolerance, 9)
        if np.ptp(values) < 5e-7:
            return f"+-{values[0]:.3g}{unit} on every hook"
        names = [f"{label} ({crane})" for label, crane in zip(self.labels, self.chosen.crane_names)]
        common, count = max(((v, int(np.sum(values == v))) for v in values), key=lambda vc: vc[1])
        if not short or count < 2:
            return ", ".join(f"{name} +-{v:.3g}{unit}" for name, v in zip(names, values))
        return ", ".join(
            [f"{name} +-{v:.3g}{unit}" for name, v in zip(names, values) if v != common]
            + [f"the others +-{common:.3g}{unit}"]
        )

    @cached_property
    def hook_sensitivity(self):
        """dT_i / dH_j at level, nominal CG, the pose held  [t per cm]: what a load-cell
        watcher sees for each centimetre of one hook off its height, (n, n), row = rope."""
        return self._twist_gain / 100.0

    @cached_property
    def twist_stiffness(self):
        """Largest tension change of any rope per centimetre of every hook off its height in
        the worst combination (the hooks' errors all 1 cm, signs the worst)  [t/cm]."""
        return float(np.abs(self.hook_sensitivity).sum(axis=1).max())

    @cached_property
    def _dense_held(self):
        """Tensions and dT/dH with the preload held on the search's dense grid of the box for
        every CG vertex (the design loads' grid): (m, n) [t], (m, n, n) [t/m]."""
        return self.lugset.tensions_and_gain(self.chosen.preload, self._design_builder.dense)

    @property
    def dense_held(self):
        """Tensions (m, n) [t] and dT/dH (m, n, n) [t/m], preload held, on the design loads'
        dense grid of the box for every CG vertex (computed once per plan)."""
        return self._dense_held

    def crew_margin(self, factors=(1.0, 2.0, 5.0)):
        """The plan as it stands (lugs, boom heights, preload) with the hook tolerance
        multiplied by each factor: what a crew worse than assumed would see.

        Returns
        -------
        list of CrewMargin
        """
        tensions, gain = self._dense_held
        breakout = self.design_loads.breakout
        out = []
        for factor in factors:
            delta = self.lugset.hook_tolerance * factor
            _, low, high, spread, _ = robust(tensions, gain, self.lugset, delta)
            rope_max, lowest = high.max(axis=0), float(low.min())
            if breakout is not None:  # the breakout state with the same hook errors
                widening = np.abs(breakout.gain) @ delta
                rope_max = np.maximum(rope_max, breakout.tensions + widening)
                lowest = min(lowest, float((breakout.tensions - widening).min()))
            out.append(
                CrewMargin(
                    factor=float(factor),
                    tolerance=delta,
                    worst_spread=float(spread.max()),
                    rope_max=rope_max,
                    lowest=lowest,
                    limit=self.lugset.limit,
                    swl=self.lugset.swl,
                )
            )
        return out

    @cached_property
    def hook_accuracy_needed(self):
        """The largest hook-height error (the same on every hook) the plan holds with every
        rope within its limits and above zero, its preload held, over the box and, with a
        breakout case, at breakout, with ``[water]`` at the start in water  [m]; inf when no
        hook error can break it (to 10 m)."""
        problem = self.problem
        tensions, gain = self._dense_held
        limit = self.lugset.limit
        value = _largest_error(tensions, np.abs(gain).sum(axis=2), limit, max(problem.min_tension, 0.0))
        breakout = self.design_loads.breakout
        if breakout is not None:  # the breakout state too: its tensions and dT/dH there
            reach = np.abs(breakout.gain).sum(axis=1)
            value = min(value, _largest_error(breakout.tensions, reach, limit, breakout.min_tension))
        water = self.design_loads.in_water
        if water is not None:  # the start in water too, at each CG vertex, >= min_tension
            reach = np.abs(water.gain).sum(axis=2)
            value = min(value, _largest_error(water.tensions, reach, limit, water.min_tension))
        # 0 where a state breaks a limit with the hooks exact (a failed check says which)
        return max(value, 0.0) if value < 10.0 else float("inf")

    @cached_property
    def diagonals(self):
        """Index pairs of the diagonals of a four-lug plan (lugs ordered round the CG)."""
        if len(self.labels) != 4:
            return []
        plan = self.lugset.points[:, :2] - np.array(self.problem.body.cog[:2])
        order = np.argsort(np.arctan2(plan[:, 1], plan[:, 0]))
        return [tuple(sorted((int(order[0]), int(order[2])))), tuple(sorted((int(order[1]), int(order[3]))))]

    @cached_property
    def admissible(self):
        """Convex sub-study at level and at the box corners (nominal CG): for each, the
        bounds of every tension over all statically admissible sets within
        [min_tension, SWL], and the least spread any of them achieves.

        Returns
        -------
        list of (Scenario, TensionBounds or None)
            None where no admissible set exists at that attitude.
        """
        problem = self.problem
        lp = AdmissibleTensions(len(self.labels))
        lower = np.full(len(self.labels), problem.min_tension)
        upper = np.asarray(self.chosen.swl, dtype=float)
        out = []
        for heel, trim in [(0.0, 0.0)] + [(h, t) for h in (-1, 1) for t in (-1, 1)]:
            scenario = Scenario(heel * problem.heel_tolerance + 0.0, trim * problem.trim_tolerance + 0.0)
            a_mat, b_vec = self.lugset.statics_at(scenario)
            try:
                out.append((scenario, lp.bounds(a_mat, b_vec, lower, upper)))
            except PlanInfeasible:
                out.append((scenario, None))
        return out

    @property
    def default_skew_factor(self):
        return DEFAULT_SKEW_FACTOR

    @cached_property
    def guidance(self):
        """Tension change per :data:`GUIDANCE_STEP` of heel (trim 0) and of trim (heel 0)."""
        edges = GUIDANCE_STEP * np.arange(-GUIDANCE_STEPS, GUIDANCE_STEPS + 1)
        fine = np.linspace(edges[0], edges[-1], 8 * len(edges) + 1)
        rows = []
        for angle in ("heel", "trim"):
            heel, trim = (edges, 0 * edges) if angle == "heel" else (0 * edges, edges)
            tensions = self.tensions_at(heel, trim)
            heel_f, trim_f = (fine, 0 * fine) if angle == "heel" else (0 * fine, fine)
            slack_at = fine[np.any(self.tensions_at(heel_f, trim_f) < 0.0, axis=1)]
            for k in range(len(edges) - 1):
                lo, hi = edges[k], edges[k + 1]
                rows.append(
                    GuidanceStep(
                        angle=angle,
                        start=float(lo),
                        end=float(hi),
                        change=dict(zip(self.labels, (tensions[k + 1] - tensions[k]).tolist())),
                        within_model=not np.any((slack_at >= lo) & (slack_at <= hi)),
                    )
                )
        return rows

    def spread_map(self, count=41):
        """The plan's objective over a heel x trim grid, at each attitude the worst over the
        CG envelope and the hook-height errors within their tolerance (as the plan's worst
        case: the map's largest value is at most :attr:`chosen.worst_value`, reached at its
        worst attitude when that lies on the grid).

        Parameters
        ----------
        count : int
            Points per axis.

        Returns
        -------
        heel : (count,)  [deg]
        trim : (count,)  [deg]
        value : (count, count)  [the objective's unit], indexed [heel, trim]
        """
        heel = np.linspace(-self.problem.heel_tolerance, self.problem.heel_tolerance, count)
        trim = np.linspace(-self.problem.trim_tolerance, self.problem.trim_tolerance, count)
        hh, tt = np.meshgrid(heel, trim, indexing="ij")
        value = np.full(hh.size, -np.inf)
        for offset in self.problem.cog_envelope.offsets():
            scenarios = [Scenario(float(h), float(t), tuple(offset)) for h, t in zip(hh.ravel(), tt.ravel())]
            tensions, gain = self.lugset.tensions_and_gain(self.chosen.preload, scenarios)
            value = np.maximum(value, robust(tensions, gain, self.lugset)[0])
        return heel, trim, value.reshape(hh.shape)

    # -- output -------------------------------------------------------------------------
    def to_json(self):
        """The JSON object of ``liftplan plan --json`` (keys fixed by CONTRACT.md first).

        ``utilisation`` is the contract's nominal T / SWL; the plan's design utilisation
        (design hook load / chart SWL) is ``capacity[].utilisation`` and
        ``design_loads.cranes[].utilisation``. Coordinates are in the file's ``frame``.
        """
        design = self.design_loads
        return (
            contract_json(self)
            | {
                "weight": weight_json(self.problem),
                "ranking": [
                    self._ranking_entry(r, d, g) | self._hull_entry(k)
                    for k, (r, d, g) in enumerate(zip(self.ranking, self.ranked_design, self.ranked_girder))
                ],
                "frame": self.frame,
                "worst_attitude": self.scenario_json(self.chosen.worst),
                "bound": self.chosen.bound,
                "capacity": [self._capacity_entry(c) for c in self.capacity],
                "design_loads": design.to_json(),
                "skew": [
                    {"lugs": list(s.lugs), "nominal": s.nominal, "skewed": s.skewed, "factor": s.factor}
                    for s in self.skew
                ],
                "guidance": [
                    {
                        "angle": g.angle,
                        "from": g.start,
                        "to": g.end,
                        "change": g.change,
                        "within_model": g.within_model,
                    }
                    for g in self.guidance
                ],
                "hooks": {
                    "tolerance": dict(zip(self.labels, self.lugset.hook_tolerance.tolist())),
                    "accuracy_needed": (
                        self.hook_accuracy_needed if np.isfinite(self.hook_accuracy_needed) else None
                    ),
                    "twist_stiffness": self.twist_stiffness,
                    "per_cm": {
                        a: dict(zip(self.labels, row.tolist()))
                        for a, row in zip(self.labels, self.hook_sensitivity)
                    },
                },
                "design_first": {
                    "met": meets_checks(self.design_loads, self.girder),
                    "passed_over": self.passed_over,
                    "note": self.design_note,
                },
                "lower_bound": self.stats.lower_bound,
                "gap": self.stats.gap,
                "relative_gap": self.stats.relative_gap,
                "search": {
                    "sets": self.stats.sets,
                    "rows": self.stats.rows,
                    "stopped": self.stats.stopped,
                    "method": self.stats.method,
                    "out_of_reach": self.stats.out_of_reach,
                    "clashing": self.stats.clashing,
                    "screened_out": self.stats.screened_out,
                    "evaluated": self.stats.evaluated,
                    "pruned": self.stats.pruned,
                    "infeasible": self.stats.infeasible,
                    "seconds": self.stats.seconds,
                    # what the search was allowed: with a work limit alone (no time limit) the
                    # same file gives the same plan on any machine
                    "limits": {
                        "search": self.problem.search,
                        "gap": self.problem.gap,
                        "time_limit": self.problem.time_limit,
                        "work_limit": self.problem.work_limit,
                    },
                },
                "checks": [c.to_json() for c in self.checks],
                "girder": girder_json(self.girder, self.scenario_json),
                "watch": watch_basis(self).to_json(),  # what `liftplan watch PLAN.json` reads
            }
            | (
                {}
                if self.lengths is None
                else {"rope_lengths": self.rope_lengths, "rope_length_search": self.lengths.to_json()}
            )
            | breakout_json(self)
            | flexible_hull_json(self)
            | in_water_json(self)
            | ({"vessels": {v.crane: v.to_json() for v in self.vessels}} if self.vessels else {})
            | wind_json(self)
        )

    def _capacity_entry(self, c):
        tilt = None
        if c.tilt is not None:
            tilt = {
                "load": c.tilt.load,
                "tilt": c.tilt.tilt,
                "axis": list(self.in_file_frame(c.tilt.axis)),
                "cog_offset": list(self.in_file_frame(c.tilt.cog_offset)),
                "cog": list(self.cog_at(Scenario(0.0, 0.0, c.tilt.cog_offset))),
                "frame": self.frame,
            }
        ok = (
            c.design is not None
            and c.design.check.ok
            and (c.design.code_margin is None or c.design.code_margin.ok)
        )
        return {
            "lug": c.label,
            "candidate": c.lug,
            "crane": c.crane,
            "radius": c.radius,
            "swl": c.swl,
            "nominal": c.nominal,
            "worst": c.worst,
            "worst_at": self.scenario_json(c.worst_at),
            "tilt_share": c.tilt.load if c.tilt is not None else None,
            "tilt_at": tilt,
            "skewed": c.skewed,
            "skew": c.skew,
            "design_hook_load": c.design_hook_load if c.design is not None else None,
            "utilisation": c.utilisation if c.design is not None else None,
            "ok": ok,
        }

    def _hull_entry(self, k):
        """A ranked set's hull keys: ``hull_model`` (which hull governs), its
        ``max_tension_change`` and ``governing_value`` (the value it is ranked on), with
        ``[water]`` its ``value_in_water``; empty without ``[hull] EI`` or ``[water]``."""
        if self.hull_search is None:
            return {}
        out = {"governing_value": self.hull_search.values[k]}
        if self.hull_models:
            model = self.hull_models[k]
            out |= {
                "hull_model": model.used,
                "max_tension_change": model.max_change if np.isfinite(model.max_change) else None,
            }
        if self.problem.in_water is not None:
            out["value_in_water"] = self.ranked_design[k].in_water.value
        return out

    def _ranking_entry(self, result, design, girder):
        return {
            "lugs": list(result.lugs),
            "cranes": list(result.crane_names),
            "nominal_spread": result.nominal_spread,
            "worst_spread": result.worst_spread,
            "worst_utilisation_spread": result.worst_utilisation_spread,
            "worst_attitude": self.scenario_json(result.worst),
            "bound": result.bound,
            "highest_in_box_load_over_swl": result.max_utilisation,
            "design_utilisation": design.max_utilisation if design.chain is not None else None,
            "design_ok": design.ok,
            "girder_ok": all(w.ratio <= 1.0 for w in girder),
            "girder_ratio": max((w.ratio for w in girder), default=None),
            "boom_heights": result.boom_heights.tolist(),
            "preload": result.preload.tolist(),
            "twist_stiffness": _twist_stiffness(self.problem, result),
            "converged": result.converged,
        }


def _largest_error(tensions, reach, limit, low):
    """The largest hook error e [m] with every T + reach e <= limit and T - reach e >= low
    (``reach``: each tension's change per 1 m on every hook, the worst signs; each constraint
    is linear in e); inf where nothing reaches."""
    with np.errstate(divide="ignore", invalid="ignore"):
        up = np.where(reach > 0, (limit - tensions) / reach, np.inf)
        down = np.where(reach > 0, (tensions - low) / reach, np.inf)
    return float(min(up.min(), down.min()))


def girder_first(problem, ranking):
    """The ranking with the sets whose hull girder holds first (the order kept within each
    group), and each set's girder worst in that order: the plan is the best set that does not
    overload the girder, when one was ranked.

    Returns
    -------
    ranking : list of SetResult
    girders : list of tuple of GirderWorst, or None when the girder is not checked
    """
    if not girder_applies(problem):
        return ranking, None
    dense = DesignBuilder(problem).dense
    worst = [set_girder(problem, r, dense) for r in ranking]
    order = sorted(range(len(ranking)), key=lambda k: any(w.ratio > 1.0 for w in worst[k]))
    return [ranking[k] for k in order], [worst[k] for k in order]


def _twist_stiffness(problem, result):
    """A ranked set's largest tension change per cm of every hook off (worst signs)  [t/cm]."""
    gain = set_lugset(problem, result.indices, result.cranes).twist_gain(result.preload)
    return float(np.abs(gain).sum(axis=1).max() / 100.0)


def plan_held(problem, top=None, girder_order=True):
    """Plan a lift on single ropes with a held level preload: lugs among the candidates (and
    the crane on each, for a fleet) and boom heights, by the search ``problem.search`` names.

    Parameters
    ----------
    problem : PlanProblem
    top : int, optional
        How many lug sets to rank (default ``problem.top``).
    girder_order : bool
        With a weight curve and ``[strength]``: rank the sets that overload the hull girder
        last (:func:`girder_first`). The rope-length search leaves it to its chosen plan.

    Returns
    -------
    Plan

    Raises
    ------
    PlanInfeasible
        No lug set can hold the body within the tolerances and limits; the message names
        the causes and how many sets each ruled out.
    Interrupted
        Ctrl-C: ``plan`` holds the best plan found so far (None when none was).
    """
    try:
        ranking, stats = search(problem, top)
    except Interrupted as stop:
        if stop.ranking:
            ranked, girders = girder_first(problem, stop.ranking) if girder_order else (stop.ranking, None)
            stop.plan = Plan(problem=problem, ranking=ranked, stats=stop.stats, girders=girders)
        raise
    try:
        with phase("hull girder of the ranked sets", None):
            ranked, girders = girder_first(problem, ranking) if girder_order else (ranking, None)
    except KeyboardInterrupt:  # the search had finished: its plan (the girder checked when shown)
        raise Interrupted(
            ranking,
            stats,
            plan=Plan(problem=problem, ranking=ranking, stats=stats),
            phase="hull girder of the ranked sets",
            finished=True,
        ) from None
    return Plan(problem=problem, ranking=ranked, stats=girder_stats(stats, ranking, ranked), girders=girders)


def girder_stats(stats, ranking, ranked):
    """The search's stats for the plan the girder chose: when the sets that overload the hull
    girder moved the search's best down the ranking, the plan is another set, and the best
    value and the gap are its own (the lower bound of every set still holds under it). With
    the top sets proved, every set better than the plan is in the ranking and overloads the
    girder, so the plan is the proved best that keeps it: its value is then the bound."""
    if ranked[0] is ranking[0]:
        return stats
    best = float(ranked[0].worst_value)
    lower = best if stats.stopped == "proved" else min(stats.lower_bound, best)
    return dataclasses.replace(stats, best=best, lower_bound=lower)


def meets_checks(design, girder):
    """A ranked set meets every design-load check of the rules' chain (each crane's design hook
    load within its chart SWL, its code margin, each lug's design load within its ``capacity``,
    the breakout and in-water checks) and keeps the hull girder within its allowables."""
    return design.ok and all(w.ratio <= 1.0 for w in girder)


def design_first(plan):
    """The plan with the ranked sets that meet every design-load check (and keep the hull
    girder) first, the order kept within each group: the plan is the best ranked set that meets
    them when one was ranked; else the order stands and the plan's checks fail
    (:attr:`Plan.design_note`).

    The design chain runs once per ranked set (the outputs show every ranked set's design
    utilisation anyway; :attr:`Plan.designs` carries them), never per searched set: a set the
    search did not rank is not looked at.

    Parameters
    ----------
    plan : Plan

    Returns
    -------
    Plan
        With ``designs``; when the order changed, ``passed_over`` counts the sets the plan's
        ranking had before it, its ``stats`` give the new plan's value (:func:`girder_stats`),
        and with floating cranes its ``problem`` is the new plan's series problem.
    """
    try:
        with phase("design loads of the ranked sets", None):
            designs, girders = plan.ranked_design, plan.ranked_girder
    except KeyboardInterrupt:  # the search had finished: its plan (the design loads computed when shown)
        raise Interrupted(
            plan.ranking,
            plan.stats,
            plan=plan,
            phase="design loads, report and output",
            finished=True,
        ) from None
    order = sorted(range(len(plan.ranking)), key=lambda k: not meets_checks(designs[k], girders[k]))

    def pick(items):
        return None if items is None else [items[k] for k in order]

    if order == sorted(order):
        return dataclasses.replace(plan, designs=list(designs), girders=list(girders))
    # every per-set list in the same new order (a set that fails moves below one that meets
    # them, even where the plan itself stays: the designs must stay beside their sets)
    ranking = pick(plan.ranking)
    changes = {
        "designs": pick(designs),
        "girders": pick(list(girders)),
        "ranking": ranking,
        "hull_models": pick(plan.hull_models),
    }
    values = None if plan.hull_search is None else pick(plan.hull_search.values)
    if values is not None:
        changes["hull_search"] = dataclasses.replace(plan.hull_search, values=values)
    if order[0] != 0:  # the search's best fails a check: the best that meets them is the plan
        changes |= {
            "passed_over": plan.passed_over + order[0],
            "stats": girder_stats(plan.stats, plan.ranking, ranking),
        }
        if plan.hull_search is not None or plan.lengths is not None:  # ranked on other values
            best = float(ranking[0].worst_value) if values is None else values[0]
            changes["stats"] = dataclasses.replace(
                plan.stats, best=best, lower_bound=min(plan.stats.lower_bound, best)
            )
        if uses_vessels(plan.problem):  # each floating crane in series at the new plan's lugs
            given = tuple(c.given if c.given is not None else c for c in plan.problem.fleet)
            base = dataclasses.replace(plan.problem, fleet=given)
            changes["problem"] = series_problem(base, ranking[0].indices, ranking[0].cranes)
    return dataclasses.replace(plan, **changes)


def clearance_checks(clearances, limit):
    """``crane_clearance`` checks of a plan's :attr:`Plan.clearances` against
    ``plan.crane_clearance`` ``limit`` [m]."""
    return [
        Check.lower(
            "crane_clearance",
            crane,
            distance,
            limit,
            "m",
            note=f"boom and hoist line to {nearest}'s, in plan",
        )
        for crane, distance, nearest in clearances.values()
    ]
