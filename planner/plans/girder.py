"""The hull girder of any plan at its worst states: max |M| and |Q| against ``[strength]``.

A planning file that gives the body's weight curve (``body.weight_curve``) and the allowable
envelopes (``[strength]``) has its hull girder checked whatever the plan's objective: every
plan kind hands the lug forces of the states it must hold (each attitude of the tolerance box
on the dense grid, at every vertex of the CG envelope, with each hook's height error at its
worst sign) to :func:`~liftplan.planner.search.girder.girder_worst`, which finds the largest
|M| / allowable and |Q| / allowable over those states (section screening, then the exact
piecewise curves of the worst states, :func:`~liftplan.planner.search.strength.exact_peaks`).
The two results become the ``bending_moment`` and ``shear_force`` checks of the plan (exit
code 4 when one fails, like every check). Those two live in the search layer
(:mod:`liftplan.planner.search.girder`), because the local search ranks its swaps with them;
this module re-exports them for the plan kinds.

The loads are those of :mod:`liftplan.model.strength.girder`, which ``liftplan solve`` uses:
the same numbers come from solving the plan's written scene at the worst state.

Sling plans, whose legs pull the lugs along their lines, solve their rigging scene at each
state they hold instead (:attr:`~.slings.lift.SlingLift.hung`); each solved state gives
its :class:`~liftplan.planner.search.girder.GirderWorst` by :func:`solved_worst`
(:func:`~liftplan.model.strength.hull_girder` and the exact worst ratio along the body),
:func:`worst_of` keeps the largest. A state with the CG moved carries its weight curve moved
with it (:func:`moved_body`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.strength import hull_girder
from liftplan.model.strength.checks import worst_ratios

# girder_worst and its result are the search's (the local search ranks its swaps with them);
# every plan kind takes them from here
from liftplan.planner.search.girder import (  # noqa: F401 (re-exported)
    EXACT_STATES,
    QUANTITIES,
    GirderWorst,
    applies,
    girder_worst,
    set_girder,
)


def girder_json(worst, scenario_json):
    """The JSON of a plan's girder results: one object per quantity, its state in the file's
    frame (``scenario_json`` of the plan)."""
    return [
        {
            "check": w.name,
            "value": w.value,
            "allowable": w.allowable,
            "ratio": w.ratio,
            "x": w.x,
            "at": scenario_json(w.scenario),
        }
        for w in worst
    ]


def moved_body(body, offset):
    """The body with its CG moved by ``offset`` and its weight curve moved with it.

    The curve gains the linear term 12 W dx (x - x_mid) / L^3, which keeps its integral and
    moves its centroid by dx: the correction :func:`~liftplan.model.strength.hull_girder` and
    the planner's girder both apply to a curve whose centroid is off the CG, made explicit so
    that the body's check (centroid within 0.05 m of the CG) accepts it.

    Parameters
    ----------
    body : Body
        Weight W [t], CG [m] (body frame, z up) and weight curve (over x_0..x_1, L = x_1 - x_0)
        or None.
    offset : (3,)  [m]
        The CG offset, body frame (z up); dx is its x.

    Returns
    -------
    Body

    Raises
    ------
    InvalidScene
        The moved curve would go below 0 t/m at one of its points (a curve near 0 t/m at an end
        and a CG offset large for the body's length): it is not a weight curve any more.
    """
    cog = tuple(float(c + d) for c, d in zip(body.cog, offset))
    if body.weight_curve is None:
        return dataclasses.replace(body, cog=cog)
    x, w = body.weight_curve_arrays
    length, middle = x[-1] - x[0], 0.5 * (x[0] + x[-1])
    moved = w + 12.0 * body.weight * float(offset[0]) * (x - middle) / length**3
    if moved.min() < 0.0:
        at = int(np.argmin(moved))
        raise InvalidScene(
            f"body.weight_curve: moved with the CG by {offset[0]:+g} m in x (plan.cog_tolerance) it "
            f"is {moved[at]:.3g} t/m at x = {x[at]:g} m; expected >= 0 (the linear term "
            "12 W dx (x - x_mid) / L^3 that moves its centroid); a smaller x tolerance or a "
            "curve with weight at its ends"
        )
    return dataclasses.replace(body, cog=cog, weight_curve=tuple(zip(x.tolist(), moved.tolist())))


def solved_worst(scene, eq, scenario):
    """The largest |M| / allowable and |Q| / allowable of one solved state.

    Parameters
    ----------
    scene : Scene
        With ``body.weight_curve`` and ``strength``, posed as solved.
    eq : Equilibrium
        Its solve.
    scenario : Scenario
        What the state is, kept in the result.

    Returns
    -------
    tuple of GirderWorst
        One per envelope given, bending first, each at its exact worst ratio along the body.
    """
    girder = hull_girder(scene, eq)
    return tuple(
        GirderWorst(name=name, value=value, allowable=limit, x=x, scenario=scenario)
        for name, x, value, limit in worst_ratios(scene.strength, girder)
    )


def worst_of(per_state):
    """The largest ratio of each quantity over many states' :class:`GirderWorst` tuples.

    Parameters
    ----------
    per_state : iterable of tuple of GirderWorst

    Returns
    -------
    tuple of GirderWorst
        Bending first; the first state kept on a tie.
    """
    best = {}
    for worst in per_state:
        for w in worst:
            if w.name not in best or w.ratio > best[w.name].ratio:
                best[w.name] = w
    return tuple(best[name] for name, _, _ in QUANTITIES if name in best)
