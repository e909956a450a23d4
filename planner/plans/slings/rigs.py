"""Every way one crane's sling set can be rigged on the candidates: its lugs, hook and legs.

The candidate rule (README "Sling lifts"):

* a 2-leg sling or a spreader bar takes any **pair** of candidates (the legs must reach and
  meet the sling-angle limit);
* a 3- or 4-leg sling takes k candidates on **one group or two adjacent groups**: a group is
  the candidates sharing a ``bulkhead`` label (without a label, those at the same x), groups
  ordered by their mean x (then y), adjacent = next in that order. The legs of one length must
  meet at a common apex above the lugs (three non-collinear lugs within the legs' reach; a
  fourth lug concyclic with them to :data:`~.geometry.FIT`), every leg at or above
  ``[rigging] min_sling_angle`` and every leg taut at level.

Each rule out is counted by its cause, so an infeasible plan can say why.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import combinations

import numpy as np

from liftplan.model.errors import InvalidScene

# the rule a hinged pair must meet (the model's, which a Python-built PlanProblem meets too)
from liftplan.model.statics.model import PLUMB_MARGIN
from liftplan.model.statics.model import near_plumb as plumb_in_box
from liftplan.planner.plans.slings.geometry import (
    FIT,
    leg_angles,
    leg_split,
    pair_apex,
    spreader_hook,
    tripod_apex,
)

#: The most k-tuples one crane's sling may have before the rule is refused as too loose.
MAX_TUPLES = 200_000


@dataclass(frozen=True)
class Rigs:
    """One crane's candidate rigs.

    Parameters
    ----------
    kind : {"pair", "fixed", "spreader"}
        How the hook moves with the body: hinged about a pair, body-fixed (3/4 legs), or a
        spreader rig in the pair's vertical plane.
    lugs : (R, k) int
        Candidate indices of each rig.
    hook : (R, 3)  [m]
        The hook at level, body frame.
    angles : (R, k)  [deg]
        Each lug leg's angle from the horizontal at level.
    top_angles : (R, 2)  [deg] or None
        A spreader's top legs.
    ruled_out : dict of str to int
    """

    kind: str
    lugs: np.ndarray
    hook: np.ndarray
    angles: np.ndarray
    top_angles: np.ndarray | None = None
    ruled_out: dict = field(default_factory=dict)

    def __len__(self):
        return len(self.lugs)

    def take(self, keep):
        return Rigs(
            self.kind,
            self.lugs[keep],
            self.hook[keep],
            self.angles[keep],
            None if self.top_angles is None else self.top_angles[keep],
            self.ruled_out,
        )


def groups(problem):
    """Candidate groups in order: tuple of index arrays (see the module docstring)."""
    labels = [c.bulkhead or f"x = {c.at[0]:.3f}" for c in problem.candidates]
    points = problem.points
    names = list(dict.fromkeys(labels))
    members = [np.array([i for i, lab in enumerate(labels) if lab == name]) for name in names]
    order = sorted(
        range(len(names)), key=lambda g: (points[members[g], 0].mean(), points[members[g], 1].mean())
    )
    return tuple(members[g] for g in order)


def sling_tuples(problem, legs):
    """Every k-tuple of candidates on one group or two adjacent groups, (T, k) int, sorted."""
    parts = groups(problem)
    pools = list(parts) + [np.concatenate([a, b]) for a, b in zip(parts, parts[1:])]
    seen = set()
    for pool in pools:
        for combo in combinations(sorted(int(i) for i in pool), legs):
            seen.add(combo)
            if len(seen) > MAX_TUPLES:
                raise InvalidScene(
                    f"candidates: more than {MAX_TUPLES} {legs}-lug tuples on adjacent "
                    "groups; expected bulkhead labels that group the candidates"
                )
    return np.array(sorted(seen), dtype=np.int64).reshape(-1, legs)


def crane_rigs(problem, crane, load, parallel=False):
    """The rigs ``crane``'s sling can take, and how many were ruled out by each cause.

    Parameters
    ----------
    problem : PlanProblem
    crane : FleetCrane   with a sling
    load : float  [t]   hook load a spreader rig is pulled up by (for its sway; W / n)
    parallel : bool
        A spreader takes only pairs it spans (lug spacing = bar length to
        :data:`~.geometry.FIT`): its bottom legs then hang parallel and vertical, and the rig
        swings about the pair like a 2-leg sling (what the held search plans with three cranes
        or more). A bar of another length is a trapezoid linkage that sways with the tilt.

    Returns
    -------
    Rigs
    """
    sling, points, limit = crane.sling, problem.points, problem.min_sling_angle - 1e-9
    counts = {}

    def drop(keep, text, rigs):
        counts[text] = counts.get(text, 0) + int(np.sum(~keep))
        return rigs.take(keep)

    if sling.legs == 2:
        pairs = np.array(list(combinations(range(len(points)), 2)), dtype=np.int64).reshape(-1, 2)
        a, b = points[pairs[:, 0]], points[pairs[:, 1]]
        if parallel:  # the hinge needs a pair that stays off plumb (its vertical plane)
            ok = ~plumb_in_box(a, b, problem.heel_tolerance, problem.trim_tolerance)
            counts[
                f"the pair turns within {PLUMB_MARGIN:g} deg of plumb in the heel/trim box (no hinge plane)"
            ] = int(np.sum(~ok))
            pairs, a, b = pairs[ok], a[ok], b[ok]
        if sling.spreader is None:
            ok = 0.5 * np.linalg.norm(b - a, axis=1) < sling.length
            counts["legs shorter than half the pair's spacing"] = int(np.sum(~ok))
            pairs, a, b = pairs[ok], a[ok], b[ok]
            hook = pair_apex(a, b, sling.length)
            rigs = Rigs("pair", pairs, hook, leg_angles(hook, points[pairs]))
        elif parallel:
            bar = sling.spreader
            ok = np.abs(np.linalg.norm(b - a, axis=1) - bar.length) <= FIT
            counts[
                f"the pair's spacing is not the spreader bar's length (to {1000 * FIT:g} mm): "
                "a trapezoid rig sways with the tilt, planned for two cranes only"
            ] = int(np.sum(~ok))
            pairs, a, b = pairs[ok], a[ok], b[ok]
            e1, e2 = a + [0.0, 0.0, sling.length], b + [0.0, 0.0, sling.length]
            hook = pair_apex(e1, e2, bar.top_length)
            ends = np.stack([e1, e2], axis=1)
            rigs = Rigs(
                "spreader", pairs, hook, np.full((len(pairs), 2), 90.0), top_angles=leg_angles(hook, ends)
            )
        else:
            bar = sling.spreader
            hook, e1, e2 = spreader_hook(a, b, sling.length, bar.length, bar.top_length, load, bar.weight)
            ok = np.all(np.isfinite(hook), axis=1)
            counts["the spreader rig cannot close on the pair"] = int(np.sum(~ok))
            pairs, hook, e1, e2 = pairs[ok], hook[ok], e1[ok], e2[ok]
            ends = np.stack([e1, e2], axis=1)
            bottom = np.stack(
                [leg_angles(e1, points[pairs[:, :1]])[:, 0], leg_angles(e2, points[pairs[:, 1:]])[:, 0]],
                axis=1,
            )
            rigs = Rigs("spreader", pairs, hook, bottom, top_angles=leg_angles(hook, ends))
        steep = np.all(rigs.angles >= limit, axis=1)
        if rigs.top_angles is not None:
            steep &= np.all(rigs.top_angles >= limit, axis=1)
        rigs = drop(steep, "sling angle below the limit", rigs)
    else:
        tuples = sling_tuples(problem, sling.legs)
        hook, reach = tripod_apex(points[tuples], sling.length)
        fits = np.all(np.isfinite(hook), axis=1)
        counts["legs cannot meet above the lugs (collinear, or out of reach)"] = int(np.sum(~fits))
        tuples, hook, reach = tuples[fits], hook[fits], reach[fits]
        fit = np.all(np.abs(reach - sling.length) <= FIT, axis=1)
        counts[f"a leg misses its lug by over {1000 * FIT:g} mm (lugs not concyclic)"] = int(np.sum(~fit))
        rigs = Rigs("fixed", tuples[fit], hook[fit], leg_angles(hook[fit], points[tuples[fit]]))
        rigs = drop(np.all(rigs.angles >= limit, axis=1), "sling angle below the limit", rigs)
        taut = np.array(
            [leg_split(h, points[t], (0.0, 0.0, 1.0)).min() > 1e-9 for h, t in zip(rigs.hook, rigs.lugs)],
            dtype=bool,
        ).reshape(-1)
        rigs = drop(taut, "a leg slack at level (the apex outside the lugs' polygon)", rigs)
    return Rigs(
        rigs.kind, rigs.lugs, rigs.hook, rigs.angles, rigs.top_angles, {k: v for k, v in counts.items() if v}
    )


def turned_hooks(rigs, crane, points, turn, load):
    """Each rig's hook with the body turned by ``turn`` (a function of (N, 3) points)  [m].

    Parameters
    ----------
    rigs : Rigs   (N rigs, one per option)
    crane : FleetCrane
    points : (C, 3)  [m]   candidates, body frame
    turn : callable   (N, 3) -> (N, 3), the body's rotation per option
    load : float or (N,)  [t]   the hook load (a spreader's sway)
    """
    if rigs.kind == "fixed":
        return turn(rigs.hook)
    a, b = turn(points[rigs.lugs[:, 0]]), turn(points[rigs.lugs[:, 1]])
    if rigs.kind == "pair":
        return pair_apex(a, b, crane.sling.length)
    bar = crane.sling.spreader
    return spreader_hook(a, b, crane.sling.length, bar.length, bar.top_length, load, bar.weight)[0]
