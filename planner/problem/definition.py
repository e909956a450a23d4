"""The planning problem: a body, candidate lug points, cranes and tolerances.

Frozen dataclasses in the ``z-up`` frame (see :mod:`liftplan.model.frames`). Each checks its
own values where it is made, with the same one-line :class:`InvalidScene` messages as the
scene, so a problem built in Python obeys the same rules as one read from a file.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import rotation_matrix, zup_to_choi
from liftplan.model.rules import CODE_MARGIN, CODE_MARGIN_MANY, DEFAULT_SKEW_FACTOR, Rules, code_margin
from liftplan.model.scene.objects import Body, GirderStiffness, Scene, Strength, finite, point, positive
from liftplan.model.scene.wind import Wind
from liftplan.model.statics.model import check_hinges
from liftplan.model.water.breakout import breakout_load
from liftplan.planner.problem.clearance import DEFAULT_CLEARANCE, boom_distances, check_positions
from liftplan.planner.problem.fleet import (
    FleetCrane,
    crane_classes,
    equal_fleet,
    length_range,
    reach_table,
)
from liftplan.planner.problem.hull_water import InWater, check_hull_water
from liftplan.planner.problem.objectives import OBJECTIVES, STRENGTH_OBJECTIVES
from liftplan.planner.problem.readings_accuracy import ReadingsAccuracy
from liftplan.planner.problem.report_info import ReportInfo

# the rules' constants, imported here too by the planner's modules
__all__ = [
    "CODE_MARGIN",
    "CODE_MARGIN_MANY",
    "DEFAULT_SKEW_FACTOR",
    "Candidate",
    "CogEnvelope",
    "CraneSpec",
    "PlanProblem",
    "code_margin",
]

MAX_CRANES = 64
#: How a lifting point is controlled: by its hoist (boom height, rope length) or by its force
#: (a strand jack holds its force whatever the attitude).
CONTROLS = ("hoist", "force")
#: Lug sets the exact search will enumerate; beyond this ``search = "auto"`` takes the local
#: search (planner/search/local.py) and ``"exact"`` is refused.
MAX_SETS = 5_000_000
#: Lug sets ranked unless ``[plan] top`` says otherwise.
DEFAULT_TOP = 5
SEARCHES = ("auto", "exact", "local", "mip")
#: ``body.weight_basis``: the weight in air, in water, or not stated (None).
WEIGHT_BASES = ("air", "water", None)


def _set(obj, name, value):
    object.__setattr__(obj, name, value)


@dataclass(frozen=True)
class Candidate:
    """A strong point the planner may put a lug on.

    Parameters
    ----------
    name : str
    at : tuple of 3 float  [m]
        Body frame.
    bulkhead : str
        Grouping label (e.g. ``"BH2"``), may be empty.
    capacity : float or None  [t]
        The lug's allowed design load (its own strength check against the rules' lug design
        load); None: no lug check.
    """

    name: str
    at: tuple[float, float, float]
    bulkhead: str = ""
    capacity: float | None = None

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.strip():
            raise InvalidScene(f"candidates.name = {self.name!r}: expected a non-empty string")
        _set(self, "at", point(f"candidates[{self.name}].at", self.at))
        if self.capacity is not None:
            _set(self, "capacity", positive(f"candidates[{self.name}].capacity", self.capacity))


@dataclass(frozen=True)
class CraneSpec:
    """What every planned crane has (the papers' four equal cranes).

    Parameters
    ----------
    EA : float  [t]
        Rope axial stiffness.
    rope_length : float  [m]
        Unstretched rope length l0 between boom tip and lug.
    swl : float  [t]
        Safe working load at the working radius.
    boom_min, boom_max : float  [m]
        Range of the boom-tip height H above the datum.
    rope_length_range : tuple of 2 float or None  [m]
        (min, max) payout the planner may choose from; ``rope_length`` is then its max.
    """

    EA: float
    rope_length: float
    swl: float
    boom_min: float = -math.inf
    boom_max: float = math.inf
    rope_length_range: tuple[float, float] | None = None

    def __post_init__(self):
        _set(self, "EA", positive("crane.EA", self.EA))
        _set(self, "rope_length", positive("crane.rope_length", self.rope_length))
        if self.rope_length_range is not None:
            _set(self, "rope_length_range", length_range("crane.rope_length", self.rope_length_range))
        _set(self, "swl", positive("crane.swl", self.swl))
        for name in ("boom_min", "boom_max"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isinf(value)):
                _set(self, name, finite(f"crane.boom_height.{name[5:]}", value))
        if self.boom_min > self.boom_max:
            raise InvalidScene(
                f"crane.boom_height = {{min = {self.boom_min:g}, max = {self.boom_max:g}}}: "
                "expected min <= max"
            )

    @property
    def stiffness(self):
        """Rope spring rate EA / l0  [t/m]."""
        return self.EA / self.rope_length


@dataclass(frozen=True)
class CogEnvelope:
    """Where the CG may really be, around its nominal position.

    Parameters
    ----------
    half_widths : tuple of 3 float  [m]
        Uncertainty along x, y, z (body frame).
    shape : {"box", "cross"}
        ``"box"``: anywhere in the box; ``"cross"``: along one axis at a time.

    Notes
    -----
    At a given attitude the tensions are affine in the CG position and the spread (max -
    min) is convex in it, so its worst case over either envelope lies at a vertex: the
    envelope is represented exactly by its vertices.
    """

    half_widths: tuple[float, float, float] = (0.0, 0.0, 0.0)
    shape: str = "box"

    def __post_init__(self):
        widths = point("plan.cog_tolerance", self.half_widths)
        if min(widths) < 0.0:
            raise InvalidScene(f"plan.cog_tolerance = {list(widths)}: expected half-widths >= 0 m")
        _set(self, "half_widths", widths)
        if self.shape not in ("box", "cross"):
            raise InvalidScene(f"plan.cog_tolerance.shape = {self.shape!r}: expected box or cross")

    def offsets(self):
        """CG offsets to check, nominal first, shape (m, 3)  [m]."""
        widths = np.array(self.half_widths)
        if self.shape == "box":
            corners = [widths * np.array(s) for s in itertools.product((-1.0, 1.0), repeat=3)]
        else:
            corners = [sign * widths[axis] * np.eye(3)[axis] for axis in range(3) for sign in (-1, 1)]
        out = {(0.0, 0.0, 0.0): None}  # insertion-ordered, without repeats (zero widths)
        out.update(dict.fromkeys(tuple(float(v) for v in c) for c in corners))
        return np.array(list(out))


@dataclass(frozen=True)
class PlanProblem:
    """Choose lugs among candidates and boom heights for the smallest worst spread.

    Parameters
    ----------
    body : Body
    candidates : tuple of Candidate
    cranes : int
        How many cranes (lugs) to use, 3 to 64 (2 with slings).
    crane : CraneSpec or None
        The ``[crane]`` defaults: a fleet of ``cranes`` equal cranes when ``fleet`` is empty.
    heel_tolerance, trim_tolerance : float  [deg]
        Half-widths of the attitude box around level.
    min_tension : float  [t]
        No rope may fall below this anywhere in the box.
    lift_height : float  [m]
        Height of the body-frame origin above the datum at which the plan holds the body
        level.
    yaw : float  [deg]
    hook_tolerance : float  [m]
        Hook-height tolerance of the operators (twist), for the skew load factors; 0 (the
        default) assumes no hook error, and the plan says so.
    cog_envelope : CogEnvelope
    top : int
        How many lug sets to rank.
    outline : tuple of (x, y) points  [m]
        Hull outline in plan, body frame (empty: none): drawn in the figures, and each crane's
        slew centre must stand outside it by ``crane_clearance``.
    crane_clearance : float  [m]
        Least plan distance between two cranes' booms and hoist lines, and from a crane to the
        hull's outline (:mod:`~liftplan.planner.problem.clearance`; default 3 m, GL Noble
        Denton 0027/ND 16.2). Sets and assignments that break it are ruled out.
    name : str
    frame : str
        Frame of the file the problem came from (``"z-up"`` or ``"choi"``), to echo the
        inputs as the engineer wrote them.
    fleet : tuple of FleetCrane
        The cranes, one per lug (default: ``cranes`` equal cranes from ``crane``).
    objective : {"spread", "utilisation", "reserve"} or None
        What the plan keeps small over the box: max - min tension [t], max - min of
        T_i / SWL_i [-], or the largest T_i / SWL_i (``reserve``: the most load left before
        the first crane reaches its SWL) [-]. None: ``spread`` for equal cranes,
        ``utilisation`` when they differ.
    gap : float  [-]
        Relative optimality gap at which the search may stop (0: prove the optimum).
    time_limit : float or None  [s]
        Stop the search after this long with the best plan and its honest gap.
    work_limit : int or None  [-]
        Stop the search after this much work, counted, not timed, so the same file gives the
        same plan on any machine: (set, assignment) rows evaluated by the exact search; swaps
        tried by the local search (half) and cells searched for its bound (half); the MIP's
        cutting-plane rounds. Held-preload plans only.
    search : {"auto", "exact", "local", "mip"}
        ``exact``: every lug set, bounded and pruned (proves the optimum or states the gap);
        ``local``: swaps from an even spread (a local optimum, no gap proved); ``mip``: one
        mixed-integer program over candidates, cranes and scenarios, no set enumerated
        (:mod:`~liftplan.planner.search.mip`; proves the optimum or states the gap); ``auto``:
        exact up to :data:`MAX_SETS` sets, local beyond.
    rules : Rules
        The lifting rules' settings for the design-load chain (``[rules]``; default: the
        rules' defaults, see ``docs/design-loads.md``).
    min_sling_angle : float  [deg]
        Lowest sling-leg angle from the horizontal (``[rigging]``; slings only).
    report : ReportInfo
        The report's title block (``[report]``: project, client, revision, signatures);
        default all empty.
    strength : Strength or None
        Allowable |M| and |Q| envelopes (``[strength]``) for the strength objectives.
    strength_weights : tuple of (float, float) or None
        (bending, shear) weights of ``objective = "strength"`` (default (1, 1)); only with it.
    controls : tuple of str
        ``"hoist"`` or ``"force"`` per crane in fleet order (empty: all ``"hoist"``); one
        control for every crane.
    breakout_scene : Scene or None
        The hull resting on the seabed (``[plan] breakout_scene``: ``[hull]``, ``[water]``,
        ``[ground]``, the same body as ``body``): its breakout case (:attr:`breakout`) is
        carried into each crane's capacity check. None: no breakout case.
    hinges : tuple of tuple of 8 float
        Empty (every candidate a body-fixed lift point), or per candidate how its lift point
        hangs from the body: the lugs A, B [m], drop c [m] and bar weight w [t] of
        :class:`~liftplan.model.statics.model.HingedLayout` (a 2-leg sling or spreader bar hinged
        about its pair; ``at`` is then its hook at level). Set by the sling planner on its
        derived problem (``planner/plans/slings/apex.py``), not read from files.
    weight_basis : str or None
        ``"air"`` or ``"water"``: what ``body.weight`` is (the plan says it beside W); None,
        not stated.
    wind : Wind or None
        Wind on the body and the floating cranes' booms, from any direction
        (:mod:`liftplan.planner.problem.vessels`); single-rope held plans only.
    readings : ReadingsAccuracy
        The live readings' accuracies (``[readings]``) that ``liftplan watch`` weighs them by.
    hull_stiffness : GirderStiffness or None
        ``[hull] EI`` (and ``GJ``): the ranked sets are evaluated again on the flexible hull
        (:mod:`liftplan.planner.plans.flexible`). None: the hull is rigid.
    in_water : InWater or None
        ``[water]``, ``[hull]``'s geometry and ``[plan] start_lift_height``: the state where the
        lift starts in water is one more worst state (:mod:`liftplan.planner.plans.in_water`).
    """

    body: Body
    candidates: tuple[Candidate, ...]
    cranes: int
    crane: CraneSpec | None
    heel_tolerance: float = 2.0
    trim_tolerance: float = 2.0
    min_tension: float = 0.0
    lift_height: float = 0.0
    yaw: float = 0.0
    hook_tolerance: float = 0.0
    cog_envelope: CogEnvelope = field(default_factory=CogEnvelope)
    top: int = DEFAULT_TOP
    outline: tuple[tuple[float, float], ...] = ()
    crane_clearance: float = DEFAULT_CLEARANCE
    name: str = ""
    frame: str = "z-up"
    fleet: tuple[FleetCrane, ...] = ()
    objective: str | None = None
    gap: float = 0.0
    time_limit: float | None = None
    work_limit: int | None = None
    search: str = "auto"
    rules: Rules = field(default_factory=Rules)
    min_sling_angle: float = 60.0
    report: ReportInfo = field(default_factory=ReportInfo)
    strength: Strength | None = None
    strength_weights: tuple[float, float] | None = None
    controls: tuple[str, ...] = ()
    breakout_scene: Scene | None = None
    hinges: tuple[tuple[float, ...], ...] = ()
    weight_basis: str | None = None
    wind: Wind | None = None
    readings: ReadingsAccuracy = field(default_factory=ReadingsAccuracy)
    hull_stiffness: GirderStiffness | None = None
    in_water: InWater | None = None

    def __post_init__(self):
        if self.weight_basis not in WEIGHT_BASES:
            raise InvalidScene(f'body.weight_basis = {self.weight_basis!r}: expected "air" or "water"')
        candidates = tuple(self.candidates)
        names = [c.name for c in candidates]
        for name in names:
            if names.count(name) > 1:
                raise InvalidScene(f"candidates.name = {name!r}: duplicate, expected unique names")
        _set(self, "candidates", candidates)
        if not isinstance(self.cranes, int) or isinstance(self.cranes, bool):
            raise InvalidScene(f"plan.cranes = {self.cranes!r}: expected an integer 3 to {MAX_CRANES}")
        if not 2 <= self.cranes <= MAX_CRANES:
            raise InvalidScene(
                f"plan.cranes = {self.cranes}: expected 3 to {MAX_CRANES} (or 2 cranes with slings)"
            )
        if len(candidates) < self.cranes:
            raise InvalidScene(
                f"candidates: {len(candidates)} given for plan.cranes = {self.cranes}: "
                "expected at least as many candidates as cranes"
            )
        if self.search not in SEARCHES:
            raise InvalidScene(f"plan.search = {self.search!r}: expected one of {', '.join(SEARCHES)}")
        sets = math.comb(len(candidates), self.cranes)
        if sets > MAX_SETS and self.search == "exact":
            raise InvalidScene(
                f"candidates: {len(candidates)} choose {self.cranes} = {sets} lug sets, more than "
                f'{MAX_SETS} for search = "exact"; expected fewer candidates (group them by '
                'bulkhead) or cranes, or search = "local"'
            )
        for name in ("heel_tolerance", "trim_tolerance"):
            value = finite(f"plan.tolerance.{name[:4]}", getattr(self, name))
            if not 0.0 <= value < 90.0:
                raise InvalidScene(f"plan.tolerance.{name[:4]} = {value!r}: expected 0 to 90 deg")
            _set(self, name, value)
        value = finite("plan.min_tension", self.min_tension)
        if value < 0.0:
            raise InvalidScene(f"plan.min_tension = {value!r}: expected >= 0 t")
        _set(self, "min_tension", value)
        _set(self, "lift_height", finite("attitude.lift_height", self.lift_height))
        _set(self, "yaw", finite("attitude.yaw", self.yaw))
        value = finite("plan.hook_tolerance", self.hook_tolerance)
        if value < 0.0:
            raise InvalidScene(f"plan.hook_tolerance = {value!r}: expected >= 0 m")
        _set(self, "hook_tolerance", value)
        if not isinstance(self.top, int) or self.top < 1:
            raise InvalidScene(f"plan.top = {self.top!r}: expected an integer >= 1")
        if self.min_tension * self.cranes > self.body.weight:
            raise InvalidScene(
                f"plan.min_tension = {self.min_tension:g} t: {self.cranes} ropes at that tension "
                f"carry more than the weight {self.body.weight:g} t; expected a smaller value"
            )
        _set(
            self,
            "outline",
            tuple((finite("plan.outline", x), finite("plan.outline", y)) for x, y, *_ in self.outline),
        )
        value = finite("plan.crane_clearance", self.crane_clearance)
        if value < 0.0:
            raise InvalidScene(f"plan.crane_clearance = {value!r}: expected >= 0 m")
        _set(self, "crane_clearance", value)
        value = finite("plan.gap", self.gap)
        if not 0.0 <= value < 1.0:
            raise InvalidScene(f"plan.gap = {value!r}: expected a relative gap 0 <= gap < 1 (0.01 = 1 %)")
        _set(self, "gap", value)
        if self.time_limit is not None:
            value = finite("plan.time_limit", self.time_limit)
            if value <= 0.0:
                raise InvalidScene(f"plan.time_limit = {value!r}: expected > 0 s")
            _set(self, "time_limit", value)
        if self.work_limit is not None and (
            isinstance(self.work_limit, bool) or not isinstance(self.work_limit, int) or self.work_limit < 1
        ):
            raise InvalidScene(f"plan.work_limit = {self.work_limit!r}: expected a whole number >= 1")
        if not isinstance(self.report, ReportInfo):
            raise InvalidScene(f"report = {self.report!r}: expected a ReportInfo (the [report] table)")
        self._check_fleet()
        if len(self.hinges):
            rows = np.asarray(self.hinges, dtype=float)
            if rows.shape != (len(candidates), 8) or not np.all(np.isfinite(rows)):
                raise InvalidScene(
                    f"hinges: shape {rows.shape}: expected one row of 8 finite values "
                    f"(A, B, c, w) per candidate, ({len(candidates)}, 8)"
                )

            # the sling planner's rule for its own pairs, for rows given from Python too
            check_hinges(
                rows,
                self.heel_tolerance,
                self.trim_tolerance,
                self.yaw,
                names,
                zup_to_choi if self.frame == "choi" else tuple,
            )
            _set(self, "hinges", tuple(tuple(float(v) for v in r) for r in rows))

    def _check_fleet(self):
        fleet = tuple(self.fleet)
        if all(c.from_defaults for c in fleet):  # none given, or made from [crane] before
            if self.crane is None:
                raise InvalidScene(
                    "crane: missing, expected [crane] defaults or one [[cranes]] table per crane"
                )
            fleet = equal_fleet(self.crane, self.cranes)
        _set(self, "fleet", fleet)
        if len(fleet) != self.cranes:
            raise InvalidScene(
                f"plan.cranes = {self.cranes}: {len(fleet)} [[cranes]] tables "
                "given; expected one table per crane"
            )
        slings = [c.sling is not None for c in fleet]
        if self.cranes == 2 and not all(slings):
            raise InvalidScene(
                "plan.cranes = 2: expected a sling on both cranes (two cranes on "
                "single ropes cannot hold a body level; give each [[cranes]] a "
                "sling = { legs, length, diameter or EA }) or 3 cranes or more"
            )
        if any(slings) and not all(slings):
            bare = next(c.name for c in fleet if c.sling is None)
            raise InvalidScene(
                f"cranes[{bare}].sling: missing; expected a sling on every crane or "
                "on none (the planner places any crane on any lift point)"
            )
        value = finite("rigging.min_sling_angle", self.min_sling_angle)
        if not 0.0 < value <= 90.0:
            raise InvalidScene(
                f"rigging.min_sling_angle = {value!r}: expected 0 to 90 deg from the horizontal"
            )
        _set(self, "min_sling_angle", value)
        names = [c.name for c in fleet]
        for name in names:
            if names.count(name) > 1:
                raise InvalidScene(f"cranes.name = {name!r}: duplicate, expected unique names")
        if self.objective is None:
            equal = len(crane_classes(fleet)) == 1
            _set(self, "objective", "spread" if equal else "utilisation")
        if self.objective not in OBJECTIVES:
            raise InvalidScene(
                f"plan.objective = {self.objective!r}: expected one of {', '.join(OBJECTIVES)}"
            )
        self._check_strength(fleet)
        self._check_breakout(fleet)
        check_hull_water(self)
        if self.wind is not None and (
            any(c.sling is not None or c.rope_length_range is not None for c in fleet)
            or self.objective in STRENGTH_OBJECTIVES
        ):
            raise InvalidScene(
                "wind: planned for single ropes of fixed length with a held preload; expected no "
                "slings, rope-length ranges or strength objective with [wind]"
            )
        if self.work_limit is not None:
            kind = (
                "cranes on slings (the sling search is exhaustive)"
                if any(c.sling is not None for c in fleet)
                else f"plan.objective = {self.objective!r} (its search takes a time limit only)"
                if self.goal.girder
                else "rope-length ranges (the outer search takes a time limit only)"
                if any(c.rope_length_range is not None for c in fleet)
                else None
            )
            if kind is not None:
                raise InvalidScene(
                    f"plan.work_limit: given with {kind}; expected it for single ropes with a held "
                    "preload, or plan.time_limit"
                )
        if not isinstance(self.rules, Rules):
            raise InvalidScene(f"rules = {self.rules!r}: expected a Rules")
        if isinstance(self.rules.rigging_weight, dict):
            unknown = sorted(set(self.rules.rigging_weight) - set(names))
            if unknown:
                raise InvalidScene(
                    f"rules.rigging_weight.{unknown[0]}: no such crane, expected one of {', '.join(names)}"
                )
        radius, swl = self.reach
        for j, crane in enumerate(fleet):
            if np.all(np.isnan(swl[:, j])):
                i = int(np.argmin(radius[:, j]))
                least = crane.load_chart[0][0] if crane.load_chart else 0.0
                raise InvalidScene(
                    f"cranes[{crane.name}]: reaches no candidate (chart radii {least:g} to "
                    f"{crane.reach:g} m; nearest candidate {self.names[i]} at radius {radius[i, j]:.2f} m)"
                )
        outline = [tuple(p) for p in self.world_plan(np.array(self.outline))] if self.outline else []
        shown = zup_to_choi if self.frame == "choi" else tuple
        check_positions(
            fleet,
            outline,
            self.crane_clearance,
            lambda xy: "(" + ", ".join(f"{v:g}" for v in shown((xy[0], xy[1], 0.0))) + ")",
        )

    def _check_strength(self, fleet):
        controls = tuple(self.controls) or ("hoist",) * len(fleet)
        for name, value in zip([c.name for c in fleet], controls):
            if value not in CONTROLS:
                raise InvalidScene(f"cranes[{name}].control = {value!r}: expected hoist or force")
        if len(set(controls)) > 1:
            raise InvalidScene(
                "cranes.control: hoist and force mixed; expected the same control on "
                "every crane (a mixed lift is not planned)"
            )
        if len(controls) != len(fleet) and len(set(controls)) == 1:
            controls = controls[:1] * len(fleet)  # one control for all: a re-made fleet keeps it
        if len(controls) != len(fleet):
            raise InvalidScene(f"controls: {len(controls)} given for {len(fleet)} cranes; expected one each")
        _set(self, "controls", controls)
        if self.strength is not None and not isinstance(self.strength, Strength):
            raise InvalidScene(f"strength = {self.strength!r}: expected a Strength ([strength])")
        weights = self.strength_weights
        if weights is not None and self.objective != "strength":
            raise InvalidScene(
                f"plan.strength_weights: given with plan.objective = {self.objective!r}; "
                'expected objective = "strength"'
            )
        if self.objective not in STRENGTH_OBJECTIVES:
            if self.strength is not None and self.body.weight_curve is None:
                raise InvalidScene(
                    "[strength]: given without body.weight_curve; the hull girder's |M| and |Q| need "
                    "the weight along the body; expected body.weight_curve = [[x m, t/m], ...], or "
                    "no [strength]"
                )
            if controls[0] == "force":
                raise InvalidScene(
                    f'cranes.control = "force" with plan.objective = {self.objective!r}; '
                    "expected bending, shear or strength (force control is planned for "
                    "the hull girder)"
                )
            return
        if self.objective == "strength":
            weights = (1.0, 1.0) if weights is None else tuple(weights)
            if len(weights) != 2:
                raise InvalidScene(f"plan.strength_weights = {weights!r}: expected {{ bending, shear }}")
            weights = tuple(
                finite(f"plan.strength_weights.{k}", w) for k, w in zip(("bending", "shear"), weights)
            )
            if min(weights) < 0.0 or max(weights) <= 0.0:
                raise InvalidScene(
                    f"plan.strength_weights = {{ bending = {weights[0]:g}, shear = "
                    f"{weights[1]:g} }}: expected weights >= 0, not both 0"
                )
            _set(self, "strength_weights", weights)
        need = {"bending": ("bending_moment",), "shear": ("shear_force",)}.get(self.objective)
        if need is None:
            need = tuple(k for k, w in zip(("bending_moment", "shear_force"), self.strength_weights) if w > 0)
        if self.body.weight_curve is None:
            raise InvalidScene(
                f"body.weight_curve: missing for plan.objective = {self.objective!r}; "
                "expected [[x m, t/m], ...]"
            )
        for key in need:
            if self.strength is None or getattr(self.strength, key) is None:
                raise InvalidScene(
                    f"strength.{key}: missing for plan.objective = {self.objective!r}; "
                    "expected the allowable envelope [[x m, value], ...]"
                )
        self._check_strength_slings(fleet, controls)
        if any(c.vessel is not None for c in fleet):
            raise InvalidScene(
                f"plan.objective = {self.objective!r}: planned for cranes on land (the strength "
                "search does not put a vessel in series with the rope); expected no cranes.vessel"
            )
        # keys the strength planner would not use: refused, not ignored
        if self.search != "auto":
            raise InvalidScene(
                f'plan.search = "{self.search}": the strength objectives have their own search (a MIP '
                "over the candidates with each set's exact LP); expected no plan.search (auto)"
            )
        if any(c.rope_length_range is not None for c in fleet):
            raise InvalidScene(
                f"crane.rope_length = {{ min, max }}: a range with plan.objective = {self.objective!r}, "
                "whose planner takes one rope length; expected a fixed rope_length"
            )
        own = next((c for c in fleet if c.hook_tolerance), None)
        if controls[0] == "force" and own is not None:
            raise InvalidScene(
                f'cranes[{own.name}].hook_tolerance = {own.hook_tolerance:g} m with control = "force": '
                "jacks hold their forces, so hook heights do not change them; expected no hook_tolerance"
            )
        if controls[0] == "force" and self.hook_tolerance > 0.0:
            raise InvalidScene(
                f'plan.hook_tolerance = {self.hook_tolerance:g} m with control = "force": jacks hold '
                "their forces, so hook heights do not change them; expected hook_tolerance = 0, or "
                'control = "hoist"'
            )

    def _check_strength_slings(self, fleet, controls):
        """A strength objective with slings: hoist control on 3 cranes or more, no spreader bars."""
        slung = next((c for c in fleet if c.sling is not None), None)
        if slung is None:
            return
        goal = f"plan.objective = {self.objective!r} with cranes on slings"
        if controls[0] == "force":
            raise InvalidScene(
                f'cranes.control = "force": {goal} is planned for hoists; a strand jack holds its '
                "force on a sling hook whose place in the body moves with the legs, which the force "
                'plan (forces at body-fixed lugs) does not pose; expected control = "hoist"'
            )
        if self.cranes < 3:
            raise InvalidScene(
                f"plan.cranes = {self.cranes}: {goal} is planned for 3 cranes or more; two hooks' "
                "loads follow from the lever rule alone, with no tensions to choose for the girder; "
                "expected 3 cranes or more"
            )
        if slung.sling.spreader is not None:
            raise InvalidScene(
                f"cranes[{slung.name}].sling.spreader: {goal} is planned for 2- to 4-leg slings; a "
                "bar's weight adds a load on its lugs that is not in proportion to the hook's "
                "tension, which the strength search's girder rows do not carry; expected no spreader"
            )

    def _check_breakout(self, fleet):
        """The breakout scene: a seabed scene of this body, for a held plan (single ropes or slings)."""
        scene, key = self.breakout_scene, "plan.breakout_scene"
        if scene is None:
            return
        if not isinstance(scene, Scene):
            raise InvalidScene(
                f"{key} = {scene!r}: expected a Scene (a scene file with [hull], [water] and [ground])"
            )
        missing = [t for t in ("hull", "water", "ground") if getattr(scene, t) is None]
        if missing:
            raise InvalidScene(
                f"{key}: the scene {scene.name!r} has no [{'], ['.join(missing)}]; "
                "expected the hull resting on the seabed with [hull], [water] and "
                "[ground]"
            )
        if self.control == "force":
            raise InvalidScene(
                f'{key}: given with control = "force"; expected cranes held by their hoists '
                "(the breakout case is the held model's, on hoists or slings)"
            )
        body, mine = scene.body, self.body
        if not math.isclose(body.weight, mine.weight, rel_tol=1e-9) or not np.allclose(
            body.cog, mine.cog, rtol=0.0, atol=1e-9
        ):
            shown = zup_to_choi if self.frame == "choi" else tuple

            def xyz(cog):
                return "(" + ", ".join(f"{v:g}" for v in shown(tuple(cog))) + ")"

            raise InvalidScene(
                f"{key}: the scene's body (weight {body.weight:g} t, cog {xyz(body.cog)} m) is not "
                f"the plan's (weight {mine.weight:g} t, cog {xyz(mine.cog)} m); expected the same "
                "body in the same body frame (the breakout point is applied to the candidates)"
            )
        try:
            _ = self.breakout  # computed now: a scene with nothing to break out is bad input
        except EquilibriumNotFound as err:
            raise InvalidScene(f"{key}: {err}") from None

    @cached_property
    def breakout(self):
        """The breakout case of ``breakout_scene`` (:class:`~liftplan.model.water.breakout.
        BreakoutLoad`: peak total hook load [t] and a z-up body point on its line), or None."""
        if self.breakout_scene is None:
            return None

        return breakout_load(self.breakout_scene)

    @property
    def weight_basis_text(self):
        """``"in air"``, ``"in water"`` or ``"not stated"``: what ``body.weight`` is."""
        return "not stated" if self.weight_basis is None else f"in {self.weight_basis}"

    @property
    def weight_text(self):
        """W and its basis in words, as the console and the report print it."""
        basis = self.weight_basis_text
        basis = "in air or in water: not stated" if self.weight_basis is None else basis
        return f"weight W {self.body.weight:.2f} t ({basis})"

    @property
    def goal(self):
        """The objective (:class:`~liftplan.planner.problem.objectives.Objective`) the plan keeps
        small: its shape and scaling, for the search."""
        return OBJECTIVES[self.objective]

    @property
    def control(self):
        """``"hoist"`` or ``"force"``: how every lifting point is controlled."""
        return self.controls[0] if self.controls else "hoist"

    @cached_property
    def points(self):
        """Candidate positions, body frame, shape (m, 3)  [m]."""
        return np.array([c.at for c in self.candidates], dtype=float)

    @property
    def names(self):
        return tuple(c.name for c in self.candidates)

    @cached_property
    def hinge_rows(self):
        """:attr:`hinges` as an array (C, 8), or None when every candidate is body-fixed."""
        return np.array(self.hinges, dtype=float) if self.hinges else None

    @cached_property
    def plan_points(self):
        """Candidates at the level attitude in world plan coordinates (yaw applied), (C, 2)  [m]."""
        return (self.points @ rotation_matrix(0.0, 0.0, self.yaw).T)[:, :2]

    def world_plan(self, xy):
        """Body-frame plan points (k, 2) at the level attitude in world plan (yaw)  [m]."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        rot = rotation_matrix(0.0, 0.0, self.yaw)[:2, :2]
        return xy @ rot.T

    @cached_property
    def boom_distances(self):
        """Least plan distance between every two cranes' booms, each on each candidate,
        (C, m, C, m) [m] (:func:`~liftplan.planner.problem.clearance.boom_distances`); None
        when no two cranes have positions."""
        positions = [c.position for c in self.fleet]
        if sum(p is not None for p in positions) < 2:
            return None
        xy = np.array([(np.nan, np.nan) if p is None else p for p in positions], dtype=float)
        return boom_distances(xy, self.plan_points)

    @cached_property
    def reach(self):
        """(radius, swl), each (C, m): every crane at every candidate; SWL NaN out of reach."""
        return reach_table(self.fleet, self.plan_points)

    @cached_property
    def crane_classes(self):
        """Interchangeable cranes grouped: tuple of tuples of fleet indices."""
        return crane_classes(self.fleet)

    @property
    def equal_cranes(self):
        """True when every crane is the same (one class)."""
        return len(self.crane_classes) == 1

    @property
    def chooses_rope_lengths(self):
        """True when a crane gives a rope-length range for the planner to choose in."""
        return any(c.rope_length_range is not None for c in self.fleet)

    @property
    def set_count(self):
        """Number of lug sets: candidates choose cranes."""
        return math.comb(len(self.candidates), self.cranes)

    @property
    def row_count(self):
        """Number of (lug set, crane assignment) rows a ranking can hold: the sets times the
        distinct ways to put the fleet's crane classes on a set's lugs."""
        sizes = [len(group) for group in self.crane_classes]
        if sum(sizes) != self.cranes:  # a fleet to choose from: the ordered choices, a bound
            return self.set_count * max(math.perm(sum(sizes), self.cranes), 1)
        ways = math.factorial(self.cranes)
        for size in sizes:
            ways //= math.factorial(size)
        return self.set_count * ways

    def check_top(self, top, key="plan.top"):
        """Refuse a ranking longer than there are rows to rank (and than the default 5).

        Ranking K rows proves the K best, so a K beyond the rows makes the search evaluate
        every row, and allocate for K: ``--top 1000000000`` ran 214 s for the 1 820 rows of
        the tanker's plan. ``key`` names the value in the message. Cranes on slings are
        not checked: their search ranks pairings of lugs, counted otherwise, and is
        exhaustive whatever the ranking's length (a large K costs it nothing)."""
        if any(c.sling is not None for c in self.fleet):
            return
        rows = self.row_count
        if top > max(rows, DEFAULT_TOP):
            what = "lug sets" if rows == self.set_count else "(lug set, crane assignment) rows"
            given = f"{key} {top}" if key.startswith("-") else f"{key} = {top}"
            raise InvalidScene(
                f"{given}: more than the {rows} {what} there are to rank "
                f"({len(self.candidates)} candidates choose {self.cranes}); expected at most "
                f"{max(rows, DEFAULT_TOP)}"
            )
