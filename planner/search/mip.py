"""Which lugs, which crane on each and which preload: one mixed-integer linear program.

No lug set is enumerated. With the boom heights set at level and the hooks then moved as a
rigid plane (:mod:`~liftplan.planner.search.scenarios`), the tension of a rope on candidate i
with crane c at scenario k (attitude, CG position) is, exactly while it is taut,

    T_k,ic = P_ic + kappa_c (h_k(p_i) - r_k,i),      h_k(p) = c_k0 + c_k1 x0 + c_k2 y0,

P the level preload, kappa_c = EA / l0 the crane's rope stiffness, r_k,i the lug's rise from
level to the scenario's pose (known), and h_k the hook plane's shift at the candidate's level
plan position: three unknowns per scenario shared by every rope, whatever the set. Every
quantity but the set is linear. One binary y_ic per (candidate, crane class) chooses; the
product y_ic h_k(p_i) is written exactly (McCormick) with bounds on the hook plane
(:func:`hook_bounds`), the statics at each scenario sum over all candidates, and every
unchosen candidate's tensions are zero:

    minimise z   subject to   sum_i y_ic = n_c,  sum_c y_ic <= 1,
        level statics A0 P = b0,  preload, boom-height and code-margin bounds on P,
        for each scenario k:  A_k T_k = b_k,  min_tension y <= T_k <= limit y,
                              hi_k >= s T_k,  lo_k <= s T_k + (1 - y) W / n,  z >= hi_k - lo_k

(s = 1 for ``spread``, 1 / SWL for ``utilisation``; ``reserve``: z >= T_k / SWL). It is solved
by HiGHS through cvxpy over a scenario list that grows by cutting planes: the chosen set is
evaluated exactly over the dense box (:class:`~liftplan.planner.search.evaluator.SetEvaluator`)
and its worst scenario is added until the MIP's value reaches the dense worst. HiGHS's dual
bound over a scenario list is a certified lower bound for every set over the whole box (the
list is part of the box).

Hook-height tolerances fit the same formulation: a hook raised by e_i adds kappa e_i to the
rope (the hook plane takes up the errors' plane through the statics), so a scenario may carry
a hook error for every candidate (:class:`Cut`: the worst errors the dense check finds for the
chosen set, each other candidate with its nearest chosen lug's) and stays linear. The list
starts with none (a part of the errors' box, so still a lower bound) and grows by the chosen
set's worst errors. When the candidates lie on one plane of the body (a deck) the errors'
worst over their whole box is instead written exactly for every set at once
(:mod:`~liftplan.planner.search.mip_hooks`): each rope's own worst change in its band and
limit rows at every scenario, and the spread's pair widening at the scenarios marked ``box``
(the first plans' worst, then each round's), so a round adds one scenario, never one error
pattern. With one crane class and at most :data:`SET_CAP` sets these rows are set-wise: one
weight x_S per lug set carries each set's closed-form widenings and its own lower bound over
the list's and the dense check's scenarios, which keeps the hook errors in the relaxation
with the lugs fractional (the proof is then combinatorial, every set bounded by its own
closed form inside the MIP; :mod:`~liftplan.planner.search.mip_hooks` proves each row).

Sling hooks hinged about their lug pairs (``PlanProblem.hinges``, 2-leg slings) fit too: where
a hook hangs at a pose depends on its own sling only, so each candidate's statics row, rise and
spreader-bar moment per scenario come from the hinged model of that hook alone
(:func:`poses`), and the held model is the same expression. A bar's moment enters the statics
as a constant per chosen hook; with a bar weight the MIP refuses (the least-width bound below
does not hold the bar's moment).

Tightening (the big-M relaxation alone closes little gap): the incumbent's worst value z_bar
(a local search first) cuts off every set that cannot beat it, which bounds each chosen rope's
tension and its change |T_k,i - P_i| (:func:`tension_band`) and from it the hook plane, rigorously
(:func:`hook_bounds`); a problem symmetric about its centre plane searches one of each mirror
pair. Even so the relaxation is weak: with the y fractional the spread's lower side averages
out; README "Many lifting points" charts what that costs against the enumeration.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy import sparse

from liftplan.model.errors import PlanInfeasible, SolverFailed
from liftplan.model.frames import rotation_matrix
from liftplan.model.statics.model import hinged_model
from liftplan.planner.problem.clearance import clear
from liftplan.planner.problem.fleet import rule_limits
from liftplan.planner.search.bounds import run_highs
from liftplan.planner.search.evaluator import (
    Interrupted,
    SearchStats,
    SetEvaluator,
    SetInfeasible,
    tolerance,
)
from liftplan.planner.search.exact import search_exact
from liftplan.planner.search.lines import count_bounds, two_lines
from liftplan.planner.search.local import search_local
from liftplan.planner.search.mip_hooks import (
    Columns,
    SetTables,
    hull_points,
    lug_coefficients,
    on_one_plane,
    residuals,
    scenario_vectors,
    set_bounds,
    set_tables,
    widening,
)
from liftplan.planner.search.progress import best_bound, progress_bar
from liftplan.planner.search.scenarios import LugSet, Scenario, first_scenarios, pack
from liftplan.planner.search.screen import REASONS

#: Angles at which the sets' least width is bounded (:func:`least_width`).
ANGLES = 720
#: Cutting-plane rounds at most.
MAX_ROUNDS = 20
#: With the hook errors' box rows: the first plans whose worst scenarios start the pair rows.
BOX_FIRST = 3
#: The box rows' size at most (candidate pairs x columns, each an absolute value and two rows;
#: the tanker's 16 candidates: 1 920 for equal cranes, 7 680 for four classes); past it the
#: hook errors come in as cuts (the MIP's many-point cases would otherwise grow as C^3 K).
BOX_SIZE = 20_000
#: One crane class with at most this many lug sets: the hook widenings set-wise
#: (:meth:`LugMip._set_rows`). Measured: the tanker's 8 of 16 (12 870 sets) built and solved
#: one round in 276 s against a 30 s limit; 5 of 16 (4 368) kept its limit.
SET_CAP = 5_000


@dataclass(frozen=True)
class Poses:
    """Set-independent data of a scenario list, for every candidate.

    Parameters
    ----------
    scenarios : list
    a_mat : numpy.ndarray, shape (m, 3, C)
        Statics rows (1, X, Y) of each candidate at each scenario's pose (world plan)  [-, m].
    b_vec : numpy.ndarray, shape (m, 3)  [t, t m]
        W (1, X_G, Y_G) at each pose.
    rise : numpy.ndarray, shape (m, C)  [m]
        Each lift point's height at the pose minus its height at level.
    level_plan : numpy.ndarray, shape (C, 2)  [m]
        Level world plan positions (the hook plane's coordinates).
    moment : numpy.ndarray, shape (m, 3, C)  [t m]
        What a chosen lift point's spreader bar takes off the statics' right-hand side
        (:func:`~liftplan.model.statics.model.hinged_points`; zero without bars).
    """

    scenarios: list
    a_mat: np.ndarray
    b_vec: np.ndarray
    rise: np.ndarray
    level_plan: np.ndarray
    moment: np.ndarray


def poses(problem, scenarios):
    """:class:`Poses` of ``scenarios``: body-fixed candidates turn with the body; lift points
    hinged on slings (``problem.hinge_rows``) are posed by the hinged rope model, each alone
    (where a lift point hangs at a pose depends on its own sling only)."""
    points = problem.points
    cog = np.array(problem.body.cog, dtype=float)
    level = points @ rotation_matrix(0.0, 0.0, problem.yaw).T
    if problem.hinge_rows is not None:
        return _hinged_poses(problem, list(scenarios), level)
    a_mat, b_vec, rise = [], [], []
    for s in scenarios:
        rot = rotation_matrix(s.heel, s.trim, problem.yaw)
        world = points @ rot.T
        g = rot @ (cog + np.asarray(s.cog_offset, dtype=float))
        a_mat.append(np.vstack([np.ones(len(points)), world[:, 0], world[:, 1]]))
        b_vec.append(problem.body.weight * np.array([1.0, g[0], g[1]]))
        rise.append(world[:, 2] - level[:, 2])
    a_mat = np.array(a_mat)
    return Poses(
        list(scenarios), a_mat, np.array(b_vec), np.array(rise), level[:, :2].copy(), np.zeros_like(a_mat)
    )


def _hinged_poses(problem, scenarios, level):
    """:class:`Poses` of lift points hinged on slings, from the hinged model's statics of
    each lift point alone (its row of A, its hook's height and its bar's moment)."""
    count = len(problem.points)
    model = hinged_model(1)
    crane = problem.fleet[0]
    cog = np.array(problem.body.cog, dtype=float)
    weight = problem.body.weight
    m = len(scenarios)
    a_mat, b_vec = np.zeros((m, 3, count)), np.zeros((m, 3))
    height, moment = np.zeros((m + 1, count)), np.zeros((m, 3, count))
    for k, s in enumerate([Scenario(0.0, 0.0)] + scenarios):
        x = np.array([problem.lift_height, math.radians(s.heel), math.radians(s.trim)])
        for i in range(count):
            p = pack(
                problem,
                problem.points[i : i + 1],
                cog + np.asarray(s.cog_offset, dtype=float),
                problem.lift_height + problem.points[i, 2] + crane.rope_length,  # one rope: scalars
                rope_length=crane.rope_length,
                EA=crane.EA,
                hinges=problem.hinge_rows[i : i + 1],
            )
            a_flat, b, hooks, cog_w = model.statics_fast(x, p)
            height[k, i] = hooks[2]
            if k:
                full = weight * np.array([1.0, cog_w[0], cog_w[1]])
                a_mat[k - 1, :, i], b_vec[k - 1] = a_flat, full
                moment[k - 1, :, i] = full - b
    return Poses(scenarios, a_mat, b_vec, height[1:] - height[0], level[:, :2].copy(), moment)


@dataclass(frozen=True)
class Cut:
    """A scenario with hook-height errors: ``errors`` ((column, metres), ...) over the MIP's
    (candidate, crane class) columns, candidate-major; a column not named has none. ``box``:
    the spread's pair rows with the hook errors' worst over their whole box at this scenario
    (:meth:`LugMip._box_rows`; then ``errors`` is empty)."""

    scenario: Scenario
    errors: tuple = ()
    box: bool = False


def worst_errors(lugset, preload, scenario, kind):
    """The hook-height errors [m] of each rope, within its tolerance, at which the chosen set
    meets its worst at ``scenario`` (the held model is affine in them there): ``"value"`` the
    objective's worst (the pair of ropes or, for ``reserve``, the rope :func:`robust` finds),
    ``"low"`` the lowest tension, ``"over"`` the largest excess over the limit."""
    tensions, gain = lugset.tensions_and_gain(preload, [scenario])
    tensions, gain, delta = tensions[0], gain[0], lugset.hook_tolerance
    if kind == "low":
        rope = int(np.argmin(tensions - np.abs(gain) @ delta))
        return -delta * np.sign(gain[rope])
    if kind == "over":
        rope = int(np.argmax(tensions + np.abs(gain) @ delta - lugset.limit))
        return delta * np.sign(gain[rope])
    if lugset.problem.goal.peak:
        rope = int(np.argmax((tensions + np.abs(gain) @ delta) / lugset.swl))
        return delta * np.sign(gain[rope])
    scale = lugset.scale
    values, scaled = tensions * scale, gain * scale[:, None]
    n = len(tensions)
    pairs = [(a, b) for a in range(n) for b in range(n) if a != b]
    a, b = max(pairs, key=lambda p: values[p[0]] - values[p[1]] + np.abs(scaled[p[0]] - scaled[p[1]]) @ delta)
    return delta * np.sign(scaled[a] - scaled[b])


@dataclass(frozen=True)
class Classes:
    """The fleet in classes of interchangeable cranes.

    Parameters
    ----------
    members : list of tuple of int
        Fleet indices of each class.
    stiffness : numpy.ndarray, shape (K,)  [t/m]
    """

    members: list
    stiffness: np.ndarray

    @property
    def counts(self):
        return np.array([len(m) for m in self.members])


def crane_classes(problem):
    """One class for an equal fleet; otherwise one class per crane."""
    fleet = problem.fleet[: problem.cranes]
    members = (
        [tuple(range(problem.cranes))] if problem.equal_cranes else [(j,) for j in range(problem.cranes)]
    )
    stiffness = np.array([fleet[m[0]].EA / fleet[m[0]].rope_length for m in members])
    return Classes(members, stiffness)


def tension_band(problem, swl, cutoff):
    """Bounds [t] on every tension of a chosen rope of chart SWL ``swl`` (any array), at any
    scenario, in any set whose worst value is below ``cutoff`` (the objective's unit).

    ``spread``: every tension lies within the spread of the mean W / n. ``utilisation``: every
    T_i / SWL_i within ``cutoff`` of W / sum SWL, the sum between n times the least and the
    largest SWL. ``reserve``: at most ``cutoff`` SWL. Each within min_tension and above.

    Returns
    -------
    low, high : numpy.ndarray, the shape of ``swl`` (NaN where ``swl`` is: out of reach)
    """
    swl = np.asarray(swl, dtype=float)
    weight, n = problem.body.weight, problem.cranes
    goal = problem.goal
    if not goal.peak and not goal.per_swl:  # the width of the tensions
        low, high = weight / n - cutoff, weight / n + cutoff
    elif not goal.peak:  # the width of T / SWL
        low = swl * (weight / (n * np.nanmax(swl)) - cutoff)
        high = swl * (weight / (n * np.nanmin(swl)) + cutoff)
    else:
        low, high = -np.inf, cutoff * swl
    low = np.maximum(np.broadcast_to(low, swl.shape), problem.min_tension)
    return low, np.maximum(np.broadcast_to(high, swl.shape), low)


def least_width(problem, data, change):
    """A lower bound on the least plan width [m] of any lug set whose chosen ropes change by
    at most ``change`` [t] between scenarios.

    Between scenarios k and m the moment about a plan direction w changes by
    sum_i (T_k,i - T_m,i) (w . P_i) = W (w . (G_k - G_m)) - sum_i T_k,i (w . (P_k,i - P_m,i))
    (P the lugs' world plan positions); the changes sum to zero, so the left side is at most
    n x change x (the set's width along w) / 2, and the last sum is within
    W ptp_i(w . dP_i) / 2 of W times its mid value. Hence a width along every direction, at
    level (m a level scenario of the list; :func:`first_scenarios` has one per CG vertex).
    """
    n = problem.cranes
    angles = np.linspace(0.0, math.pi, ANGLES, endpoint=False)
    w = np.column_stack([np.cos(angles), np.sin(angles)])
    cog = data.b_vec[:, 1:] / data.b_vec[:, :1]  # (m, 2) world plan CG
    plan = data.a_mat[:, 1:, :]  # (m, 2, C)
    # the width is taken at a level pose m (where the plan positions are the level ones)
    level = [j for j, s in enumerate(data.scenarios) if s.heel == 0.0 and s.trim == 0.0]
    best = np.zeros(len(angles))
    lipschitz = 0.0
    for k in range(len(cog)):
        d_cog = (cog[k] - cog[level]) @ w.T  # (levels, A)
        d_lug = np.einsum("mdc,ad->mac", plan[k][None] - plan[level], w)  # (levels, A, C)
        mid = 0.5 * (d_lug.max(axis=2) + d_lug.min(axis=2))
        half = 0.5 * (d_lug.max(axis=2) - d_lug.min(axis=2))
        best = np.maximum(best, (np.abs(d_cog - mid) - half).max(axis=0))
        lipschitz = max(
            lipschitz,
            float(np.linalg.norm(cog[k] - cog[level], axis=1).max())
            + 2.0 * float(np.linalg.norm(plan[k][None] - plan[level], axis=1).max()),
        )
    # between two sampled angles each term moves by at most its Lipschitz constant x half a step
    least = float(best.min()) - lipschitz * (math.pi / ANGLES) / 2.0
    return max(problem.body.weight * least / (0.5 * n * change), 0.0)


def hook_bounds(problem, data, change, stiffness, errors=0.0):
    """Bounds [m] on the hook plane's shift h_k at every candidate, valid for every set whose
    chosen ropes change by at most ``change`` [t] (a chosen lug's own bound is tighter: h_k
    is within change / kappa of its rise there).

    Let rho_k be the rises' affine fit over the candidates (misfit eps_k) and a = h_k - rho_k:
    affine, within B = change / kappa + eps_k on the chosen lugs, so its slope is at most
    2 B / (the set's least width, :func:`least_width`) and at a candidate q it is within
    B + slope x (q's largest distance to any candidate). Hook errors of at most ``errors`` [m]
    in the scenarios widen B by as much (h_k is then within change / kappa of r_k - e there).

    Returns
    -------
    centre, half : numpy.ndarray, shape (m, C)  [m]
    """
    width = least_width(problem, data, change)
    if width <= 0.0:
        raise PlanInfeasible(
            'search = "mip" needs the CG envelope or the tilt tolerance to move the CG '
            "against the lugs in every plan direction (it bounds the hook plane from that); "
            'expected cog_tolerance or heel/trim tolerances, or search = "exact"'
        )
    plan = data.level_plan
    basis = np.column_stack([np.ones(len(plan)), plan])
    coef, *_ = np.linalg.lstsq(basis, data.rise.T, rcond=None)
    centre = (basis @ coef).T  # (m, C)
    bound = change / float(np.min(stiffness)) + errors + np.abs(data.rise - centre).max(axis=1, keepdims=True)
    reach = np.sqrt(((plan[:, None, :] - plan[None, :, :]) ** 2).sum(axis=2)).max(axis=1)
    return centre, bound + 2.0 * bound / width * reach[None, :]


def mirror_map(problem):
    """Candidate index of each candidate's mirror image about the fore-and-aft plane through
    the CG, or None when the problem (candidates, CG envelope, equal fleet) is not symmetric
    about it."""
    if not problem.equal_cranes:
        return None
    rot = rotation_matrix(0.0, 0.0, problem.yaw)
    level = problem.points @ rot.T
    centre = (rot @ np.array(problem.body.cog, dtype=float))[1]
    scale = 1e-9 * max(1.0, float(np.abs(level).max()))
    offsets = problem.cog_envelope.offsets() @ rot.T
    flipped = offsets * [1.0, -1.0, 1.0]
    if not all(np.any(np.all(np.abs(offsets - f) < scale, axis=1)) for f in flipped):
        return None
    image = level.copy()
    image[:, 1] = 2.0 * centre - level[:, 1]
    match = np.all(np.abs(level[None, :, :] - image[:, None, :]) < scale, axis=2)
    if not np.all(match.sum(axis=1) == 1):
        return None
    return np.argmax(match, axis=1)


def mirror_side(problem):
    """+1 / -1 / 0: each candidate's side of the fore-and-aft plane through the CG (level)."""
    rot = rotation_matrix(0.0, 0.0, problem.yaw)
    lateral = (problem.points @ rot.T)[:, 1] - (rot @ np.array(problem.body.cog, dtype=float))[1]
    return np.where(np.abs(lateral) < 1e-9 * max(1.0, float(np.abs(lateral).max())), 0.0, np.sign(lateral))


@dataclass(frozen=True)
class MipSolution:
    """One solve of the lug-choice MIP over a scenario list.

    Parameters
    ----------
    indices : tuple of int or None
        Chosen candidates (candidate order); None when no set beats the cutoff.
    cranes : tuple of int or None
        Fleet index of the crane on each chosen lug.
    preload : numpy.ndarray or None  [t]
        The MIP's level preload of each chosen lug.
    value : float
        The MIP's objective for that choice over the list (inf when none).
    bound : float
        HiGHS's dual bound: no set does better over the list (the cutoff when none beats it).
    status : {"optimal", "gap", "time_limit", "cutoff"}
    seconds : float  [s]
    """

    indices: tuple | None
    cranes: tuple | None
    preload: np.ndarray | None
    value: float
    bound: float
    status: str
    seconds: float


class LugMip:
    """The lug-choice MIP of a problem (module docstring), rebuilt per scenario list.

    Parameters
    ----------
    problem : PlanProblem
        Body-fixed candidates, or sling hooks hinged about their lug pairs (``hinge_rows``)
        without a spreader bar's weight.
    cutoff : float
        An incumbent's worst value (the objective's unit): sets that cannot beat it are cut off.
    dense : list of Scenario, optional
        The dense check's scenarios, for the two-line cut (default: a new evaluator's).
    """

    def __init__(self, problem, cutoff, dense=None):
        hinged = problem.hinge_rows is not None
        if hinged and np.any(problem.hinge_rows[:, 7] != 0.0):
            raise PlanInfeasible(
                'search = "mip" takes lift points hinged on slings without a spreader bar\'s weight '
                "(a bar's moment moves with the set, and the MIP's bound on the sets' plan width "
                'does not hold it); expected search = "exact" or "local"'
            )
        self.problem = problem
        self.cutoff = float(cutoff)
        self.classes = crane_classes(problem)
        fleet = problem.fleet
        count = len(problem.candidates)
        radius, swl = problem.reach  # (C, fleet)
        first = [m[0] for m in self.classes.members]
        self.swl = swl[:, first]  # (C, K); NaN: out of reach
        reach_swl = np.where(np.isnan(self.swl), 1.0, self.swl)
        cranes = np.broadcast_to(np.array(first), self.swl.shape)
        self.limit, self.share = rule_limits(problem, reach_swl, cranes)
        boom_zero = (
            problem.lift_height
            + problem.points[:, 2][:, None]
            + np.array([fleet[j].rope_length for j in first])[None, :]
        )
        kappa = self.classes.stiffness[None, :]
        low = kappa * (np.array([fleet[j].boom_min for j in first])[None, :] - boom_zero)
        high = kappa * (np.array([fleet[j].boom_max for j in first])[None, :] - boom_zero)
        self.preload_low = np.maximum(low, problem.min_tension)
        self.preload_high = np.minimum(high, self.share)
        self.usable = ~np.isnan(self.swl) & (self.preload_low <= self.preload_high)
        self.scale = problem.goal.scale(reach_swl)
        self.reach_swl = reach_swl
        #: each class's hook-height tolerance [m]
        self.hook = np.array(
            [
                problem.hook_tolerance if fleet[j].hook_tolerance is None else fleet[j].hook_tolerance
                for j in first
            ]
        )
        #: the hook errors' worst case as rows over the whole box (:mod:`mip_hooks`), else cuts
        # (hinged lift points do not turn with the body: their rows are no linear map of the
        # level ones, and their hook errors come in as cuts)
        pairs = count * (count - 1) // 2 * count * len(first)  # pair rows' absolute values
        self.box = (
            bool(np.any(self.hook > 0.0)) and not hinged and pairs <= BOX_SIZE and on_one_plane(problem)
        )
        self.mirror = None if hinged else mirror_map(problem)
        self.count = count
        self._tables = None
        self._dense_beta = None
        self.dense = dense
        # candidates on two lines: each count of lugs per line has a bound of its own
        self.lines = two_lines(problem)
        if self.lines is not None and (
            not problem.goal.peak and (not problem.goal.per_swl or np.nanmax(swl) == np.nanmin(swl))
        ):
            if dense is None:
                dense = SetEvaluator(problem).dense
            self.line_counts = count_bounds(problem, self.lines, dense)
        else:
            self.line_counts = None

    def clashing_pairs(self):
        """Column pairs (candidate-major, as ``y``) whose cranes' booms cross in plan or come
        nearer than ``plan.crane_clearance``, shape (P, 2) (none without crane positions)."""
        d, kinds = self.problem.boom_distances, len(self.classes.members)
        if d is None:
            return np.empty((0, 2), dtype=np.int64)
        first = [m[0] for m in self.classes.members]
        sub = d[:, first][:, :, :, first]  # (C, K, C, K)
        i, c, i2, c2 = np.nonzero(~clear(sub, self.problem.crane_clearance))
        keep = (i * kinds + c) < (i2 * kinds + c2)
        return np.column_stack([i[keep] * kinds + c[keep], i2[keep] * kinds + c2[keep]])

    def _box_rows(self, cp, chosen, values, bands, layout):
        """The limits' and the objective's rows with the hook errors' exact worst over their
        box (:mod:`~liftplan.planner.search.mip_hooks`).

        Each rope's own worst change enters its band and limit rows (and, for ``reserve``, the
        objective) at every scenario of the list; the spread's pair rows, whose widening is of
        a pair, at the scenarios marked ``box`` only (:class:`Cut`).

        ``chosen`` (y, Y per candidate, z); ``values`` (tensions, scaled tensions) per scenario
        and candidate; ``bands`` (band low, band high, floor, ceiling); ``layout`` (each
        column's candidate, its stiffness, the sets' least width, the column-to-candidate sum,
        the indices of the box scenarios).
        """
        problem = self.problem
        y, per_set, z = chosen
        load, scaled = values
        band_low, band_high, floor, ceiling = bands
        col_cand, kappa, width, per_candidate, boxed, data = layout
        count = self.count
        columns = Columns(
            col_cand,
            kappa,
            self.hook[np.tile(np.arange(len(self.classes.members)), count)],
            (problem.points @ rotation_matrix(0.0, 0.0, problem.yaw).T)[:, :2],
            problem.cranes,
        )
        off = 1 - per_set
        across = np.ones((load.shape[0], 1))

        def spread_out(v):  # a per-candidate row to every scenario
            return across @ cp.reshape(v, (1, v.shape[0]), order="C")

        tables = self._set_tables(columns, width, data, (band_low, band_high))
        if tables is not None:
            return self._set_rows(cp, tables, (y, per_set, z), values, bands, boxed, spread_out)

        # each rope's own change: its low side above the band's low (and min_tension), its high
        # side below the limit and the band's high
        ones = np.ones(len(col_cand))
        own, cons = residuals(cp, y, columns, lug_coefficients(ones, col_cand, count), width)
        rise, more = widening(cp, own, columns)
        # the residuals' diagonal is the trace of I - H over the chosen lugs: n - 3 at every set
        diagonal = np.zeros((count, len(col_cand)))
        diagonal[col_cand, np.arange(len(col_cand))] = 1.0
        more.append(cp.sum(cp.multiply(diagonal, own)) == problem.cranes - 3)
        low = per_candidate.T @ cp.multiply(band_low.ravel(), y)
        high = per_candidate.T @ cp.multiply(np.minimum(self.limit, band_high).ravel(), y)
        cons += more + [
            load - spread_out(rise) >= spread_out(low),
            load + spread_out(rise) <= spread_out(high),
        ]
        scale = self.scale.ravel()
        if np.all(scale == 1.0):
            scaled_own = own
        else:
            scaled_own, more = residuals(cp, y, columns, lug_coefficients(scale, col_cand, count), width)
            cons += more
        if problem.goal.peak:  # reserve: each rope's largest scaled tension
            rise, more = widening(cp, scaled_own, columns)
            return cons + more + [scaled + spread_out(floor * off + rise) <= z]
        if not boxed:
            return cons
        # the pair (a, b)'s residual is a's less b's (the fit is linear in c)
        a, b = np.triu_indices(count, k=1)
        wide, more = widening(cp, scaled_own[a, :] - scaled_own[b, :], columns)
        return cons + more + [_pair_rows(cp, (a, b), wide, (scaled, off, z), (floor, ceiling), boxed)]

    def _set_tables(self, columns, width, data, bands):
        """The set-wise widening tables (:func:`~liftplan.planner.search.mip_hooks.set_tables`)
        and each set's bound (:func:`~liftplan.planner.search.mip_hooks.set_bounds`) over the
        list's scenarios and the dense check's, for one crane class with at most
        :data:`SET_CAP` sets; else None (the fit's rows)."""
        problem = self.problem
        if len(self.classes.members) != 1 or math.comb(self.count, problem.cranes) > SET_CAP:
            return None
        key = (float(width), self.cutoff)
        if self._tables is None or self._tables[0] != key:
            tables = set_tables(
                columns.level_plan,
                columns.stiffness,
                columns.tolerance,
                self.scale[:, 0],
                problem.cranes,
                self.usable[:, 0],
                width,
            )
            self._tables = (key, tables)
        tables = self._tables[1]
        level = poses(problem, [Scenario(0.0, 0.0)])
        if self._dense_beta is None:
            dense = poses(problem, self.dense) if self.dense else None
            self._dense_beta = (
                np.empty((0, 3))
                if dense is None
                else hull_points(scenario_vectors(dense.a_mat, dense.b_vec, dense.level_plan))
            )
        beta = np.vstack([scenario_vectors(data.a_mat, data.b_vec, data.level_plan), self._dense_beta])
        band_low, band_high = bands
        bound = set_bounds(
            tables,
            columns.stiffness,
            self.scale[:, 0],
            (level.a_mat[0], level.b_vec[0], hull_points(beta)),
            (np.maximum(self.preload_low, band_low)[:, 0], np.minimum(self.preload_high, band_high)[:, 0]),
            (band_low[:, 0], np.minimum(self.limit, band_high)[:, 0]),
            problem.goal.peak,
        )
        keep = np.isfinite(bound) | (bound < 0)
        return SetTables(
            tables.sets[keep], tables.own[keep], tables.scaled_own[keep], tables.pair[keep]
        ), bound[keep]

    def set_bounds(self, scenarios):
        """The sets the set-wise rows keep and each one's bound (the objective's unit) over
        ``scenarios`` and the dense check's, at the present cutoff: (sets (S, n), bound (S,)),
        or None where the fit's rows are used (:meth:`_set_tables`)."""
        problem = self.problem
        data = poses(problem, list(scenarios))
        band_low, band_high = tension_band(problem, self.swl, self.cutoff)
        band_low, band_high = (np.nan_to_num(v, nan=0.0) for v in (band_low, band_high))
        count, kinds = self.count, len(self.classes.members)
        columns = Columns(
            np.repeat(np.arange(count), kinds),
            self.classes.stiffness[np.tile(np.arange(kinds), count)],
            self.hook[np.tile(np.arange(kinds), count)],
            data.level_plan,
            problem.cranes,
        )
        width = least_width(problem, data, float((band_high - band_low).max()))
        found = self._set_tables(columns, width, data, (band_low, band_high))
        return None if found is None else (found[0].sets, found[1])

    def _set_rows(self, cp, found, chosen, values, bands, boxed, spread_out):
        """The box rows with each widening a weighted sum over the sets (module docstring):
        x_S >= 0 with sum_{S ni i} x_S = Y_i, so at an integer Y the weight is on the chosen
        set alone, and with Y fractional each widening is a mixture of whole sets' own."""
        problem, count = self.problem, self.count
        tables, bound = found
        y, per_set, z = chosen
        load, scaled = values
        band_low, band_high, floor, ceiling = bands
        sets = tables.sets
        n_sets, n = sets.shape
        x = cp.Variable(n_sets, nonneg=True)
        cols = np.repeat(np.arange(n_sets), n)
        members = sets.ravel()

        def over_sets(table, rows, count_rows, where=None):  # sum_S x_S table[S, m] into row rows[S, m]
            if where is None:
                where = np.repeat(np.arange(n_sets), table.shape[1])
            matrix = sparse.csr_matrix((table.ravel(), (rows.ravel(), where)), shape=(count_rows, n_sets))
            total = cp.Variable(count_rows)  # one variable per row: the rows below stay sparse
            cons.append(total == matrix @ x)
            return total

        incidence = sparse.csr_matrix((np.ones(len(members)), (members, cols)), shape=(count, n_sets))
        cons = [incidence @ x == per_set]
        if np.all(np.isfinite(bound)):  # each set's own bound (set_bounds)
            cons.append(z >= bound @ x)
        rise = over_sets(tables.own, sets, count)
        low = cp.multiply(band_low[:, 0], y)
        high = cp.multiply(np.minimum(self.limit, band_high)[:, 0], y)
        cons += [load - spread_out(rise) >= spread_out(low), load + spread_out(rise) <= spread_out(high)]
        off = 1 - per_set
        if problem.goal.peak:  # reserve: each rope's largest scaled tension
            lift = over_sets(tables.scaled_own, sets, count)
            return cons + [scaled + spread_out(floor * off + lift) <= z]
        if not boxed:
            return cons
        a, b = np.triu_indices(count, k=1)
        index = np.full((count, count), -1)
        index[a, b] = np.arange(len(a))
        index[b, a] = np.arange(len(a))
        # a pair of two members: its own widening; one member and one other lug: the member's
        # own (the other's residual is zero); neither: none
        rows, vals, where = [], [], []
        for m in range(n):
            for m2 in range(m + 1, n):
                rows.append(index[sets[:, m], sets[:, m2]])
                vals.append(tables.pair[:, m, m2])
                where.append(np.arange(n_sets))
        inside = np.zeros((n_sets, count), dtype=bool)
        inside[np.arange(n_sets)[:, None], sets] = True
        for m in range(n):
            other = np.nonzero(~inside)  # (set, candidate) not in the set
            rows.append(index[sets[other[0], m], other[1]])
            vals.append(tables.scaled_own[other[0], m])
            where.append(other[0])
        wide = over_sets(np.concatenate(vals), np.concatenate(rows), len(a), np.concatenate(where))
        return cons + [_pair_rows(cp, (a, b), wide, (scaled, off, z), (floor, ceiling), boxed)]

    def solve(self, scenarios, gap=0.0, time_limit=None, forbidden=()):
        """Solve over ``scenarios``; a :class:`MipSolution`.

        Parameters
        ----------
        scenarios : list of Scenario or Cut
        gap : float  [-]   HiGHS's relative gap target
        time_limit : float, optional  [s]
        forbidden : iterable of tuple of int
            Lug sets not to choose again (found infeasible over the dense box).
        """
        import cvxpy as cp

        problem, classes = self.problem, self.classes
        cuts = [c if isinstance(c, Cut) else Cut(c) for c in scenarios]
        data = poses(problem, [c.scenario for c in cuts])
        m, count, kinds = len(cuts), self.count, len(classes.members)
        errors = np.zeros((m, count * kinds))  # each column's hook error at each scenario [m]
        for k, cut in enumerate(cuts):
            for column, value in cut.errors:
                errors[k, column] = value
        band_low, band_high = tension_band(problem, self.swl, self.cutoff)  # (C, K)
        band_low, band_high = (np.nan_to_num(v, nan=0.0) for v in (band_low, band_high))
        change = band_high - band_low
        centre, off = hook_bounds(
            problem, data, float(change.max()), classes.stiffness, float(np.abs(errors).max(initial=0.0))
        )
        width = least_width(problem, data, float(change.max())) if self.box else None
        col_cand = np.repeat(np.arange(count), kinds)  # columns (i, c), candidate-major
        col_class = np.tile(np.arange(kinds), count)
        usable = self.usable.ravel()
        kappa = classes.stiffness[col_class]
        y = cp.Variable(count * kinds, boolean=True)
        preload = cp.Variable(count * kinds)
        plane = cp.Variable((m, 3))
        hooks = plane @ np.vstack([np.ones(count), data.level_plan.T])  # (m, C)
        hooks = hooks[:, col_cand]
        product = cp.Variable((m, count * kinds))  # y h_k(p_i)
        ones = np.ones((m, 1))
        chosen = ones @ cp.reshape(y, (1, count * kinds), order="C")
        rise = data.rise[:, col_cand] - errors  # a hook raised by e: as if the lug sank by e
        on_lo = rise - (change.ravel() / kappa)[None, :]
        on_hi = rise + (change.ravel() / kappa)[None, :]
        off_lo = centre[:, col_cand] - off[:, col_cand]
        off_hi = centre[:, col_cand] + off[:, col_cand]
        tension = ones @ cp.reshape(preload, (1, count * kinds), order="C") + cp.multiply(
            kappa[None, :], product - cp.multiply(rise, chosen)
        )
        weight = problem.body.weight
        scale = self.scale.ravel()[None, :]
        limit = self.limit.ravel()[None, :]
        cons = [
            y <= usable.astype(float),
            cp.sum(cp.reshape(y, (count, kinds), order="C"), axis=0) == classes.counts,
            cp.sum(cp.reshape(y, (count, kinds), order="C"), axis=1) <= 1,  # a lug, one crane
            preload >= cp.multiply(np.where(usable, np.maximum(self.preload_low, band_low).ravel(), 0.0), y),
            preload
            <= cp.multiply(np.where(usable, np.minimum(self.preload_high, band_high).ravel(), 0.0), y),
            product <= cp.multiply(on_hi, chosen),
            product >= cp.multiply(on_lo, chosen),
            product <= hooks - cp.multiply(off_lo, 1 - chosen),
            product >= hooks - cp.multiply(off_hi, 1 - chosen),
            tension >= cp.multiply(band_low.ravel()[None, :], chosen),
            tension <= cp.multiply(np.minimum(limit, band_high.ravel()[None, :]), chosen),
        ]
        per_candidate = np.zeros((count * kinds, count))
        per_candidate[np.arange(count * kinds), col_cand] = 1.0
        level_a = poses(problem, [Scenario(0.0, 0.0)])
        per_set = cp.sum(cp.reshape(y, (count, kinds), order="C"), axis=1)
        cons.append(
            level_a.a_mat[0] @ (per_candidate.T @ preload) + level_a.moment[0] @ per_set == level_a.b_vec[0]
        )
        load = tension @ per_candidate  # (m, C)
        for row in range(3):
            cons.append(
                cp.sum(cp.multiply(data.a_mat[:, row, :], load), axis=1) + data.moment[:, row, :] @ per_set
                == data.b_vec[:, row]
            )
        z = cp.Variable()
        scaled = cp.multiply(scale, tension)
        # the largest scaled tension is at least the mean W / n (spread) or W / (n max SWL),
        # the least at most W / n or W / (n min SWL): an unchosen candidate stands at those
        # (the perspective of max / min over the chosen; tighter than a plain big M)
        floor = weight / problem.cranes * float(np.min(scale[:, usable]))
        ceiling = weight / problem.cranes * float(np.max(scale[:, usable]))
        if self.box:  # the hook errors' worst over the whole box, for every set at once
            cons += self._box_rows(
                cp,
                (y, per_set, z),
                (tension @ per_candidate, scaled @ per_candidate),
                (band_low, band_high, floor, ceiling),
                (col_cand, kappa, width, per_candidate, [k for k, c in enumerate(cuts) if c.box], data),
            )
        if problem.goal.peak:
            cons.append(scaled + floor * (1 - chosen) <= z)
        else:
            high, low = cp.Variable(m), cp.Variable(m)
            across = np.ones((1, count * kinds))
            cons += [
                scaled + floor * (1 - chosen) <= high[:, None] @ across,
                low[:, None] @ across <= scaled + ceiling * (1 - chosen),
                z >= high - low,
            ]
        if self.line_counts is not None:  # z >= B(n1): n1 lugs on line 0 (planner/search/lines)
            allowed = np.flatnonzero(np.isfinite(self.line_counts))
            pick = cp.Variable(len(allowed), boolean=True)
            cons += [
                cp.sum(pick) == 1,
                allowed @ pick == cp.sum(per_set[np.flatnonzero(self.lines.line == 0)]),
                z >= self.line_counts[allowed] @ pick,
            ]
        for lugs in forbidden:
            cons.append(cp.sum(per_set[list(lugs)]) <= problem.cranes - 1)
        clash = self.clashing_pairs()
        if len(clash):  # two booms crossing or within the clearance: not both
            rows = np.repeat(np.arange(len(clash)), 2)
            pairs = sparse.csr_matrix(
                (np.ones(2 * len(clash)), (rows, clash.ravel())), shape=(len(clash), count * kinds)
            )
            cons.append(pairs @ y <= 1)
        if self.mirror is not None:  # one of each mirror pair of sets
            cons.append(mirror_side(problem)[col_cand] @ y >= 0)
        mip = cp.Problem(cp.Minimize(z), cons)
        options = dict(mip_rel_gap=gap, objective_bound=self.cutoff, random_seed=0)
        if time_limit is not None:
            options["time_limit"] = max(float(time_limit), 0.1)
        started = time.perf_counter()
        run_highs(mip, "lug-choice MIP", **options)
        seconds = time.perf_counter() - started
        info = mip.solver_stats.extra_stats if mip.solver_stats is not None else None
        dual = float(getattr(info, "mip_dual_bound", -math.inf)) if info is not None else -math.inf
        infeasible = (cp.INFEASIBLE, cp.settings.INFEASIBLE_OR_UNBOUNDED)
        # at a time limit HiGHS may hand back a vector that is no solution (status 2: feasible)
        found = y.value is not None and (
            mip.status == cp.OPTIMAL or getattr(info, "primal_solution_status", 0) == 2
        )
        if mip.status in infeasible or not found:
            if mip.status in infeasible or (mip.status == cp.USER_LIMIT and dual >= self.cutoff):
                # every set is cut off: none beats the cutoff over these scenarios
                return MipSolution(None, None, None, math.inf, self.cutoff, "cutoff", seconds)
            if mip.status == cp.USER_LIMIT:  # time limit before any set below the cutoff
                return MipSolution(
                    None, None, None, math.inf, min(max(dual, 0.0), self.cutoff), "time_limit", seconds
                )
            raise SolverFailed(f"lug-choice MIP: HiGHS ended with status {mip.status!r}")
        picked = np.flatnonzero(y.value > 0.5)
        value = float(z.value)
        bound = min(max(dual, 0.0), value)
        if mip.status == cp.OPTIMAL:
            status = "optimal" if value - bound <= 1e-6 * max(abs(value), 1.0) + gap * value else "gap"
        else:
            status = "time_limit"
        indices = col_cand[picked]
        order = np.argsort(indices)
        members = [list(classes.members[c]) for c in range(kinds)]
        cranes = [members[c].pop(0) for c in col_class[picked][order]]
        return MipSolution(
            tuple(int(i) for i in indices[order]),
            tuple(cranes),
            np.asarray(preload.value)[picked][order],
            value,
            bound,
            status,
            seconds,
        )


def _pair_rows(cp, pairs, wide, values, bands, boxed):
    """The spread's pair rows with the hook errors at the ``boxed`` scenarios: for each pair
    (a, b) of candidates, in both orders, s_a T_a - s_b T_b + W_ab <= z, an unchosen
    candidate standing at the floor (its high side) or the ceiling (its low side).

    ``pairs`` (a, b) the candidate pairs a < b; ``wide`` each pair's widening; ``values``
    (scaled tensions per scenario and candidate, 1 - Y per candidate, z); ``bands`` (floor,
    ceiling)."""
    a, b = pairs
    scaled, off, z = values
    floor, ceiling = bands
    first = np.concatenate([a, b])
    second = np.concatenate([b, a])
    twice = np.concatenate([np.arange(len(a))] * 2)
    row = floor * off[first] - ceiling * off[second] + wide[twice]
    pick = scaled[boxed, :]
    rows = np.ones((len(boxed), 1)) @ cp.reshape(row, (1, len(first)), order="C")
    return pick[:, first] - pick[:, second] + rows <= z


def search_mip(problem, started, top=1, progress=None):
    """Plan by the lug-choice MIP with cutting planes (module docstring).

    A first plan gives the cutoff: the local search's (equal cranes) or the exact search's
    first evaluated set (a fleet). Each round
    solves the MIP over the scenario list within what is left of ``problem.time_limit`` and
    to ``problem.gap``, checks its set and preload over the dense box and adds the worst
    scenario found, until the MIP's value holds over the box (the optimum proved, or within
    the gap), or the time runs out. The certified lower bound is the larger of the first
    plan's (the two-line bound, :mod:`~liftplan.planner.search.lines`) and the least of the
    last MIP's dual bound and the best value found.

    Returns
    -------
    ranking : list of SetResult
        Every set evaluated, best first (the first is the plan).
    stats : SearchStats
    """
    from collections import Counter

    ranking, first = _incumbent(problem, started)
    evaluator = SetEvaluator(problem)
    mip = LugMip(problem, ranking[0].worst_value, dense=evaluator.dense)
    scenarios = [Cut(s) for s in first_scenarios(problem)]
    if mip.box:  # the pair rows over the whole hook box, first at the first plans' worst
        scenarios += list(dict.fromkeys(Cut(r.worst, box=True) for r in ranking[:BOX_FIRST]))
    forbidden, reasons = [], Counter()
    lower, rounds, stopped = first.lower_bound, 0, "proved"
    deadline = math.inf if problem.time_limit is None else started + problem.time_limit
    bar = progress_bar(MAX_ROUNDS, progress, desc="MIP search", unit="rounds", ticker=True)

    def stats_now():
        best = ranking[0].worst_value
        return SearchStats(
            sets=problem.set_count,
            screened_out=0,
            evaluated=len(ranking) + len(forbidden),
            pruned=0,
            infeasible={REASONS[c]: k for c, k in reasons.most_common()},
            seconds=time.perf_counter() - started,
            rows=problem.set_count,
            refined=rounds,
            lower_bound=min(lower, best),
            best=best,
            stopped=stopped,
            method="mip",
        )

    try:
        while True:
            best = ranking[0].worst_value
            # the first plan's bound already suffices (to rounding: 1e-12 of the value)
            if best - lower <= max(problem.gap * best, 1e-12 * abs(best)):
                stopped = "gap" if best > lower else "proved"
                break
            if problem.work_limit is not None and rounds >= problem.work_limit:
                stopped = "work_limit"  # rounds counted: the same on any machine
                break
            if rounds >= MAX_ROUNDS or time.perf_counter() >= deadline:
                stopped = "rounds" if rounds >= MAX_ROUNDS else "time_limit"
                break
            rounds += 1
            left = None if deadline == math.inf else deadline - time.perf_counter()
            solution = mip.solve(scenarios, gap=problem.gap, time_limit=left, forbidden=forbidden)
            best = ranking[0].worst_value
            if solution.indices is None:  # nothing beats the incumbent over the list
                lower = max(min(solution.bound, best), first.lower_bound)
                stopped = "proved" if solution.status == "cutoff" else "time_limit"
                break
            try:
                result = evaluator.evaluate(solution.indices, solution.cranes)
            except SetInfeasible as err:
                reasons[err.code] += 1
                forbidden.append(solution.indices)
                continue
            lugset = LugSet(problem, solution.indices, solution.cranes)
            found = evaluator.dense_search(lugset, solution.preload)
            if all(r.indices != result.indices or r.cranes != result.cranes for r in ranking):
                ranking.append(result)
                ranking.sort(key=lambda r: (r.worst_value, r.nominal_value))
            best = ranking[0].worst_value
            mip.cutoff = best
            lower = max(min(solution.bound, best), first.lower_bound)
            if bar is not None:
                bar.update(1)
                bar.set_postfix_str(best_bound(best, lower))
            if solution.status == "time_limit":
                stopped = "time_limit"
                break
            tol = tolerance(problem) * (1.0 if not problem.goal.per_swl else 1.0 / float(np.max(result.swl)))
            cuts = (
                [_cut(mip, solution, lugset, found.worst[1], "value")]
                if found.worst[0] > solution.value + tol
                else []
            )
            if found.low[0] < problem.min_tension - tolerance(problem):
                cuts.append(_cut(mip, solution, lugset, found.low[1], "low"))
            if found.over[0] > tolerance(problem):
                cuts.append(_cut(mip, solution, lugset, found.over[1], "over"))
            cuts = [c for c in dict.fromkeys(cuts) if c not in scenarios]
            if not cuts:  # the MIP's choice and preload hold over the dense box
                stopped = "proved" if best - lower <= tol else "gap"
                break
            scenarios += cuts
    except KeyboardInterrupt:
        stopped = "interrupted"
        raise Interrupted(ranking, stats_now()) from None
    finally:
        if bar is not None:
            bar.close()
    return ranking, stats_now()


def _cut(mip, solution, lugset, scenario, kind):
    """The scenario as a :class:`Cut`, with the chosen set's worst hook errors there
    (:func:`worst_errors`) when its cranes have a hook tolerance.

    Every other candidate gets the error of the chosen lug nearest to it in plan (any errors
    within the tolerance are a scenario of the box, so the MIP stays a relaxation): a set that
    moves a lug to a neighbour meets nearly the same twist, where errors on the chosen lugs
    alone would leave it none, and the next round would only pick that neighbour."""
    if mip.box:  # the box rows hold every hook error
        return Cut(scenario, box=True)
    if not lugset.hook_uncertain:
        return Cut(scenario)
    errors = worst_errors(lugset, solution.preload, scenario, kind)
    problem = mip.problem
    plan = (problem.points @ rotation_matrix(0.0, 0.0, problem.yaw).T)[:, :2]
    chosen = np.array(solution.indices)
    distance = np.linalg.norm(plan[:, None, :] - plan[None, chosen, :], axis=2)  # (C, n)
    nearest = np.argmin(distance, axis=1)
    nearest[chosen] = np.arange(len(chosen))  # a chosen lug keeps its own error
    kinds = len(mip.classes.members)
    return Cut(
        scenario,
        tuple(
            (int(i) * kinds + c, float(errors[nearest[i]]))
            for i in range(mip.count)
            for c in range(kinds)
            if errors[nearest[i]] != 0.0
        ),
    )


def _incumbent(problem, started):
    """A first plan to cut off with, (ranking, stats): the local search's for equal cranes,
    the exact search's first evaluated (set, assignment) for a fleet."""
    import dataclasses

    if problem.equal_cranes:
        return search_local(problem, started)
    # the work limit stops the exact search at its first plan (a time limit would stop it
    # before any plan is found)
    first = dataclasses.replace(problem, gap=0.0, time_limit=None, work_limit=1)
    return search_exact(first, time.perf_counter(), 1)
