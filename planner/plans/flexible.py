"""The flexible hull in a plan: the ranked sets evaluated again, and ranked on the model that governs.

With ``[hull] EI`` (and ``GJ``) in a planning file the search runs on the rigid hull, as
always; then every ranked set is solved on the flexible hull at its worst states
(:func:`evaluate_flexible`): the level state at the nominal CG, the state where its objective
is worst, and each rope's own worst state (the design loads' grid). Each state is the plan's
scene posed there - boom heights that dial in the preload plus the hook motions that bring the
body to the state's heel and trim, the CG and its weight curve moved - solved by
:func:`liftplan.model.solve.solve` on the ``elastic`` model with the hull's beam
(:class:`~liftplan.model.strength.flexible_model.FlexibleRopeModel`), which also gives the
rigid hull's tensions of the same hooks. ``solve``'s own rule decides: where flexibility
changes a tension by more than :data:`~liftplan.model.strength.flexible.TENSION_CHANGE` of the
rigid one at any of the states, the set's tensions, design loads and objective are the
flexible ones (the objective: its largest value over the states, the hook errors at their worst
with the rigid hull's dT/dH there); else the rigid ones stand. The sets are ranked again on
the governing value.

Why no better set is missed (:func:`change_bound`): for a linear beam on linear ropes the
flexible correction dT of a state satisfies (I + Q M Q) y = -Q K^1/2 u (y = K^-1/2 dT, K the
ropes' stiffnesses, Q the projector that removes rigid motions, M = K^1/2 F K^1/2 >= 0 with F
the beam's flexibility at the lugs, u the lugs' deflection under the rigid tensions), so
|y| <= |K^1/2 u| and |dT_i| <= sqrt(k_i) |K^1/2 u|. The deflection u is bounded for every set
alike: with every rope pulling up, the bending moment at x lies between minus the weight's
moment on the left of x and the weight's moment on the right of x, whatever the lugs; its
curvature integrated with the simply supported Green's function bounds the deflection from the
chord, and the torque W max|dy| bounds the twist. Every objective's change is then at most
2 max s_i |dT_i| (a spread) or max s_i |dT_i| (the reserve's peak): ``bound``. A set the
search did not rank is at least as bad as the last ranked set on the rigid hull, so no better
than (last - bound) on the flexible one; when that is no better than the best governing value
the re-ranked plan is the best over every set (``certified``); otherwise the ranking is asked
longer (:func:`liftplan.planner.plans.hull_water.plan_hull_water`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.scene.objects import Analysis, Attitude, Crane, Lug, Scene
from liftplan.model.solve import solve
from liftplan.model.strength.flexible import TENSION_CHANGE, tension_change
from liftplan.planner.plans.girder import moved_body
from liftplan.planner.search.evaluator import robust
from liftplan.planner.search.scenarios import LugSet, Scenario

#: Points along the body for the deflection bound's integrals.
BOUND_POINTS = 2001


@dataclass(frozen=True)
class HullModel:
    """One ranked set on the rigid and the flexible hull at its worst states.

    Parameters
    ----------
    used : {"flexible", "rigid"}
        The hull whose numbers govern the set (``solve``'s 1 % rule over its states).
    states : tuple of Scenario
        Where it was solved: level (nominal CG), the objective's worst, each rope's worst.
    rigid, flexible : numpy.ndarray, shape (m, n)  [t]
        Each state's tensions, the same hooks, rigid and flexible hull.
    gain : numpy.ndarray, shape (m, n, n)  [t/m]
        dT/dH of the rigid hull at each state (the hook errors' widening of both).
    max_change : float  [-]
        Largest |T_flexible - T_rigid| / T_rigid over the states and ropes.
    max_change_rope : int
        Its rope (index in the set's order).
    max_change_at : Scenario
    rigid_value : float  [t or -]
        The search's worst of the objective over the box (rigid hull).
    flexible_value : float  [t or -]
        The objective's largest over the states on the flexible hull, the hook errors at worst.
    nominal : numpy.ndarray, shape (n,)  [t]
        Level tensions at the nominal CG of the governing hull.
    worst : numpy.ndarray, shape (n,)  [t]
        Each rope's tension at its worst state, hook errors at worst, of the governing hull
        (for the rigid hull: the search's).
    lowest : float  [t]
        The lowest tension over the states, hook errors at worst, of the flexible hull.
    bound : float  [t or -]
        This set's bound on |flexible - rigid| of its objective (module docstring).
    """

    used: str
    states: tuple
    rigid: np.ndarray
    flexible: np.ndarray
    gain: np.ndarray
    max_change: float
    max_change_rope: int
    max_change_at: Scenario
    rigid_value: float
    flexible_value: float
    nominal: np.ndarray
    worst: np.ndarray
    lowest: float
    bound: float

    @property
    def value(self):
        """The governing objective value  [t or -]: flexible where flexibility changes a tension
        by more than 1 %, else the search's."""
        return self.flexible_value if self.used == "flexible" else self.rigid_value

    def reason(self, labels):
        """One clause: which hull, and the measured change (as ``solve`` says it)."""
        rope = labels[self.max_change_rope]
        change = f"{100 * self.max_change:.3g} %" if math.isfinite(self.max_change) else "from 0 t"
        if self.used == "flexible":
            return (
                f"flexibility changes {rope} by {change}, more than {100 * TENSION_CHANGE:g} %: "
                "the flexible hull governs"
            )
        return (
            f"flexibility changes no tension by more than {100 * TENSION_CHANGE:g} % (at most "
            f"{change}, {rope}): the rigid hull governs"
        )

    def to_json(self, labels, scenario_json):
        """The ``hull_model`` of a ranked set in ``plan --json``."""
        return {
            "used": self.used,
            "reason": self.reason(labels),
            "threshold": TENSION_CHANGE,
            "max_tension_change": self.max_change if math.isfinite(self.max_change) else None,
            "max_tension_change_rope": labels[self.max_change_rope],
            "max_tension_change_at": scenario_json(self.max_change_at),
            "rigid_value": self.rigid_value,
            "flexible_value": self.flexible_value,
            "value": self.value,
            "bound": self.bound,
            "level_tensions": {
                "rigid": dict(zip(labels, self.rigid[0].tolist())),
                "flexible": dict(zip(labels, self.flexible[0].tolist())),
            },
        }


def state_scene(problem, result, scenario, labels=None):
    """The plan's scene of one ranked set posed at a state, with the hull's stiffness.

    The boom heights dial in the set's preload; the hooks move by the rigid motion that brings
    the body to the state's heel and trim (the held preload); the CG and its weight curve are
    moved by the state's offset. ``solve`` of it gives, on the rigid hull, the planner's
    tensions there, and on the flexible hull what the beam makes of them.
    """
    lugset = LugSet(problem, result.indices, result.cranes)
    preload = np.asarray(result.preload, dtype=float)
    shift = lugset.hook_shifts(preload, [scenario])[0]
    boom = lugset.boom_heights(preload) + shift
    labels = labels or tuple(f"L{k + 1}" for k in range(lugset.n))
    return Scene(
        body=moved_body(problem.body, scenario.cog_offset),
        lugs=tuple(Lug(name=label, at=tuple(map(float, p))) for label, p in zip(labels, lugset.points)),
        cranes=tuple(
            Crane(lug=label, EA=float(ea), boom_height=float(h), rope_length=float(l0), swl=float(swl))
            for label, ea, h, l0, swl in zip(labels, lugset.EA, boom, lugset.rope_length, lugset.swl)
        ),
        attitude=Attitude(
            lift_height=problem.lift_height, heel=scenario.heel, trim=scenario.trim, yaw=problem.yaw
        ),
        analysis=Analysis(model="elastic", hull="flexible"),
        girder=problem.hull_stiffness,
        strength=problem.strength,
        name=f"{problem.name or 'plan'}: flexible hull",
    )


def worst_states(problem, result, dense):
    """The states a set is solved at on the flexible hull: level at the nominal CG, its
    objective's worst, each rope's worst on the dense grid (hook errors at worst); no repeats."""
    lugset = LugSet(problem, result.indices, result.cranes)
    tensions, gain = lugset.tensions_and_gain(np.asarray(result.preload, dtype=float), dense)
    where = np.argmax(tensions + np.abs(gain) @ lugset.hook_tolerance, axis=0)
    out = []
    for s in [Scenario(0.0, 0.0), result.worst, *(dense[k] for k in where)]:
        if s not in out:
            out.append(s)
    return tuple(out)


def evaluate_flexible(problem, result, dense, bounds=None):
    """One ranked set on the rigid and the flexible hull at its worst states (:class:`HullModel`).

    Parameters
    ----------
    problem : PlanProblem
        With ``hull_stiffness``.
    result : SetResult
    dense : list of Scenario
        The design loads' grid (:attr:`~.design_loads.DesignBuilder.dense`).
    bounds : numpy.ndarray, optional  [m]
        Each candidate's deflection bound (:func:`deflection_bounds`); computed when None.

    Raises
    ------
    EquilibriumNotFound
        ``solve`` found no accepted flexible equilibrium at a state (with its reason and the state).
    """
    lugset = LugSet(problem, result.indices, result.cranes)
    states = worst_states(problem, result, dense)
    rigid, flexible = [], []
    for s in states:
        try:
            eq = solve(state_scene(problem, result, s))
        except (EquilibriumNotFound, InvalidScene) as err:
            raise EquilibriumNotFound(
                f"flexible hull, lugs {' '.join(result.lugs)} at heel {s.heel:g} deg, trim "
                f"{s.trim:g} deg, CG offset {list(s.cog_offset)}: {err}"
            ) from None
        report = eq.flexible_hull
        rigid.append(list(report.rigid_tensions.values()))
        flexible.append(list(report.flexible_tensions.values()))
    rigid, flexible = np.array(rigid), np.array(flexible)
    gain = lugset.tensions_and_gain(np.asarray(result.preload, dtype=float), list(states))[1]
    change = tension_change(rigid, flexible, problem.body.weight)
    at = np.unravel_index(int(np.argmax(change)), change.shape)
    max_change = float(change[at])
    used = "flexible" if max_change > TENSION_CHANGE else "rigid"
    value, low, high, _, _ = robust(flexible, gain, lugset)
    widened = flexible + np.abs(gain) @ lugset.hook_tolerance
    if bounds is None:
        bounds = deflection_bounds(problem)
    if used == "flexible":
        nominal, worst = flexible[0], np.array([widened[:, k].max() for k in range(lugset.n)])
    else:
        nominal = np.asarray(result.preload, dtype=float)
        worst = np.asarray(result.rope_max, dtype=float)
    return HullModel(
        used=used,
        states=states,
        rigid=rigid,
        flexible=flexible,
        gain=gain,
        max_change=max_change,
        max_change_rope=int(at[1]),
        max_change_at=states[at[0]],
        rigid_value=float(result.worst_value),
        flexible_value=float(value.max()),
        nominal=nominal,
        worst=worst,
        lowest=float(low.min()),
        bound=set_bound(problem, lugset, bounds),
    )


# -- the bound -------------------------------------------------------------------------------
def _pairs(pairs, x):
    """A [[x, value], ...] table at x: linear between points, its end values held beyond."""
    table = np.asarray(pairs, dtype=float)
    return np.interp(x, table[:, 0], table[:, 1])


def _cumulative(values, x):
    """Cumulative trapezoid integral of values over x, 0 at x[0]."""
    out = np.zeros_like(values)
    out[1:] = np.cumsum(0.5 * (values[1:] + values[:-1]) * np.diff(x))
    return out


def deflection_bounds(problem):
    """Each candidate's bound on its lug's deflection from the rigid motion, any set, any state  [m].

    Bending: |M(x)| <= max(left weight moment, right weight moment) (every rope pulls up) plus
    the axial forces' couple sin(trim tolerance) W max|dz|, over every CG-envelope vertex's
    moved weight curve; the curvature M / EI integrated with the simply supported Green's
    function bounds the deflection w and slope w' from the chord through the ends. Twist (with
    ``GJ``): the torque is at most W (max|dy| + sin(heel tolerance) max|dz|) anywhere, so the
    twist from one end is at most its integral over GJ. The lug moves by
    w + |dz| sin(trim) |w'| + (|dy| + |dz| sin(heel)) theta (the model's up-vector terms).
    """
    body, stiff = problem.body, problem.hull_stiffness
    curve = np.asarray(body.weight_curve, dtype=float)
    x = np.linspace(curve[0, 0], curve[-1, 0], BOUND_POINTS)
    x0, x1 = x[0], x[-1]
    length = x1 - x0
    weight = body.weight
    offsets = np.array(problem.cog_envelope.offsets(), dtype=float)
    cog = np.asarray(body.cog, dtype=float)
    dy = np.abs(problem.points[:, 1] - cog[1]) + np.abs(offsets[:, 1]).max()
    dz = np.abs(problem.points[:, 2] - cog[2]) + np.abs(offsets[:, 2]).max()
    sin_heel = math.sin(math.radians(problem.heel_tolerance))
    sin_trim = math.sin(math.radians(problem.trim_tolerance))
    moment = np.zeros_like(x)
    for offset in offsets:
        q = _pairs(moved_body(body, offset).weight_curve, x)
        total, first = _cumulative(q, x), _cumulative(q * x, x)
        left = x * total - first
        right = (first[-1] - first) - x * (total[-1] - total)
        moment = np.maximum(moment, np.maximum(left, right))
    moment = moment + sin_trim * weight * dz.max()
    curvature = moment / _pairs(stiff.EI, x)
    a = _cumulative((x - x0) * curvature, x)  # int_x0^x (s - x0) k ds
    b = _cumulative((x1 - x) * curvature, x)
    b = b[-1] - b  # int_x^x1 (x1 - s) k ds
    w = ((x1 - x) * a + (x - x0) * b) / length
    slope = (a + b) / length
    theta = 0.0
    if stiff.GJ is not None:
        torque = weight * (dy.max() + sin_heel * dz.max())
        theta = float(_cumulative(torque / _pairs(stiff.GJ, x), x)[-1])
    at = problem.points[:, 0]
    return np.interp(at, x, w) + sin_trim * dz * np.interp(at, x, slope) + (dy + sin_heel * dz) * theta


def set_bound(problem, lugset, bounds):
    """A set's bound on |flexible - rigid| of its objective at any state  [t or -]:
    |dT_i| <= sqrt(k_i) sqrt(sum_j k_j u_j^2) (module docstring), times s_i, times 2 for a
    spread (max - min), 1 for the reserve's peak."""
    k = lugset.stiffness
    norm = math.sqrt(float(np.sum(k * bounds[list(lugset.indices)] ** 2)))
    scale = lugset.scale
    factor = 1.0 if lugset.problem.goal.peak else 2.0
    return factor * float(np.max(scale * np.sqrt(k))) * norm


def change_bound(problem, bounds):
    """The bound of :func:`set_bound` over every set and assignment  [t or -]: the n largest
    deflection bounds, the stiffest crane, the largest s_i."""
    fleet = problem.fleet
    k = max(c.EA / c.rope_length for c in fleet)
    largest = np.sort(bounds)[::-1][: problem.cranes]
    norm = math.sqrt(k * float(np.sum(largest**2)))
    goal = problem.goal
    if goal.per_swl:
        swl = problem.reach[1]
        scale = 1.0 / float(np.nanmin(np.where(swl > 0, swl, np.nan)))
    else:
        scale = 1.0
    return (1.0 if goal.peak else 2.0) * scale * math.sqrt(k) * norm


def flexible_hull_json(plan):
    """``{"flexible_hull": {...}}`` of ``plan --json`` (``{}`` without ``[hull] EI``)."""
    models = plan.hull_models
    if not models:
        return {}
    chosen = models[0]
    out = chosen.to_json(plan.labels, plan.scenario_json)
    out["certified"] = plan.hull_search.certified
    out["margin"] = plan.hull_search.margin
    out["evaluated"] = plan.hull_search.evaluated
    out["note"] = plan.hull_search.note
    return {"flexible_hull": out}


def replace_design(design, model):
    """Design-load inputs of a set with its governing hull's nominal and worst tensions."""
    return [
        dataclasses.replace(c, nominal=float(n), worst=float(w))
        for c, n, w in zip(design.cranes, model.nominal, model.worst)
    ]
