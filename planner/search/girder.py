"""The hull girder of one lug set at its worst states: max |M| and |Q| against ``[strength]``.

The search's side of :mod:`liftplan.planner.plans.girder`: :func:`girder_worst` finds the
largest |M| / allowable and |Q| / allowable of lug forces over many states (section screening,
then the exact piecewise curves of the worst states,
:func:`~liftplan.planner.search.strength.exact_peaks`), and :func:`set_girder` does it for an
evaluated set (:class:`~liftplan.planner.search.evaluator.SetResult`) at its preload, its hook
errors at their worst. Every plan kind checks its girder with these, and the local search
(:mod:`~liftplan.planner.search.local_girder`) ranks its swaps with the same numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.checks import Check
from liftplan.model.strength.checks import QUANTITIES as CURVES
from liftplan.model.strength.girder import attitude_matrix
from liftplan.planner.search.scenarios import Scenario, set_lugset
from liftplan.planner.search.strength import (
    GirderLoads,
    Sections,
    State,
    allowable,
    exact_peaks,
    section_ratios,
)

#: The states whose exact curves are taken, per quantity: the worst ones at the sections.
EXACT_STATES = 3

#: (check name, what the value is, unit) of the two quantities, bending first.
QUANTITIES = tuple(q[:3] for q in CURVES)


@dataclass(frozen=True)
class GirderWorst:
    """The largest bending moment or shear force of a plan over the states it must hold.

    Parameters
    ----------
    name : {"bending_moment", "shear_force"}
    value : float  [t m or t]
        |M| or |Q| there, the hook errors' worst effect included.
    allowable : float  [t m or t]
        The envelope's value at ``x``.
    x : float  [m]
        The section, body frame (the file's x: the same axis in both frames).
    scenario : Scenario
        The state: heel, trim [deg] and CG offset [m] (body frame, z up); a sling plan's
        :class:`~.slings.lift.HungState` also says how its hooks were set.
    """

    name: str
    value: float
    allowable: float
    x: float
    scenario: Scenario

    @property
    def ratio(self):
        """value / allowable  [-]."""
        return self.value / self.allowable

    def check(self, what="over the plan's states"):
        """The plan's check of this quantity (:class:`~liftplan.model.checks.Check`)."""
        symbol, unit = next((s, u) for n, s, u in QUANTITIES if n == self.name)
        s = self.scenario
        return Check.upper(
            self.name,
            f"x = {self.x:.1f} m",
            self.value,
            self.allowable,
            unit,
            note=(
                f"{symbol} / allowable = {self.ratio:.0%}, the worst {what}, at heel {s.heel:+.2f} "
                f"deg, trim {s.trim:+.2f} deg"
            ),
        )


def applies(problem):
    """True when a plan's hull girder is checked: a weight curve and an allowable envelope."""
    strength = problem.strength
    return (
        problem.body.weight_curve is not None
        and strength is not None
        and (strength.bending_moment is not None or strength.shear_force is not None)
    )


def girder_worst(problem, points, scenarios, tensions, hook=None):
    """The worst bending moment and shear force of lug forces over many states.

    Parameters
    ----------
    problem : PlanProblem
        Its body (weight, CG, weight curve), yaw and ``strength`` envelopes.
    points : (n, 3)  [m]
        The lugs, body frame (z up).
    scenarios : list of Scenario
        The states: attitude and CG offset.
    tensions : (k, n)  [t]
        Vertical lug force of each lug in each state.
    hook : (gain (k, n, n) [t/m], tolerance (n,) [m]), optional
        dT/dH at each state and each hook's height tolerance: its worst effect is added.

    Returns
    -------
    tuple of GirderWorst
        One per envelope given: bending first, then shear.
    """
    if not applies(problem):
        return ()
    loads = GirderLoads(problem.body)
    envelopes = (problem.strength.bending_moment, problem.strength.shear_force)
    points = np.asarray(points, dtype=float)
    tensions = np.asarray(tensions, dtype=float)
    states = [
        State(tuple(attitude_matrix(s.heel, s.trim, problem.yaw)[2]), tuple(s.cog_offset)) for s in scenarios
    ]
    sections = Sections.initial(loads, points[:, 0], envelopes)
    ratios = section_ratios(loads, envelopes, points, sections, states, tensions, hook)
    out = []
    for which, (name, _, _) in enumerate(QUANTITIES):
        if envelopes[which] is None:
            continue
        top = np.argsort(-ratios[which])[:EXACT_STATES]
        sub_hook = None if hook is None else (hook[0][top], hook[1])
        peaks, _ = exact_peaks(loads, envelopes, points, tensions[top], [states[k] for k in top], sub_hook)
        peak = peaks[which]
        out.append(
            GirderWorst(
                name=name,
                value=float(peak.value),
                allowable=float(allowable(envelopes[which], [peak.x])[0]),
                x=float(peak.x),
                scenario=scenarios[int(top[peak.state])],
            )
        )
    return tuple(out)


def set_girder(problem, result, scenarios):
    """A ranked set's hull girder worst over the scenarios, its hook errors at their worst.

    Parameters
    ----------
    problem : PlanProblem
    result : SetResult
        The set, its cranes and its preload T*  [t].
    scenarios : list of Scenario
        The states (the dense grid of the box at every CG vertex).

    Returns
    -------
    tuple of GirderWorst
        As :func:`girder_worst`. The last :data:`MEMO` results are kept: the local search
        checks its set's girder before the plan does (:mod:`.local_girder`), on the same
        :class:`SetResult`, and the dense grid's girder costs as much as the set's evaluation.
    """
    key = id(result)
    known = _MEMO.get(key)
    if known is not None and known[0] is result and known[1] is problem and known[2] == scenarios:
        return known[3]
    lugset = set_lugset(problem, result.indices, result.cranes)
    tensions, gain = lugset.tensions_and_gain(np.asarray(result.preload, dtype=float), scenarios)
    hook = (gain, lugset.hook_tolerance) if lugset.hook_uncertain else None
    worst = girder_worst(problem, lugset.points, scenarios, tensions, hook)
    _MEMO[key] = (result, problem, list(scenarios), worst)
    while len(_MEMO) > MEMO:
        del _MEMO[next(iter(_MEMO))]
    return worst


#: Sets whose girder :func:`set_girder` keeps (with the result, the problem and the states).
MEMO = 16
_MEMO = {}
