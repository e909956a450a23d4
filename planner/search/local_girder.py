"""The hull girder inside the local search's moves: feasibility first, then the objective.

With a weight curve and ``[strength]`` allowables every plan checks the hull girder of its set
at its worst states (:func:`~liftplan.planner.search.girder.set_girder`: the set evaluated
exactly over the box, :class:`~liftplan.planner.search.evaluator.SetEvaluator`, its preload
held at every state of the dense grid, each hook error at its worst sign). The local search
ranks (set, cranes) rows as the exact search's ranking does: a row that overloads the girder
after every row that keeps it, then by the objective. Its exact verdict costs a set's whole
evaluation (the LP with its cutting planes, the dense grid, the girder's curves), some ten
times a swap's screening, so the search takes it in two steps:

* :meth:`LocalGirder.screen`, a necessary screen of every swap at once: the girder at level
  with the nominal CG, where the tensions are the preload T* itself and T* satisfies the level
  statics A T* = b (rows 1, x, y). A section whose moment or shear row g lies in the row space
  of A (g = lambda A: every section aft of a group of lugs whose share of the weight and of its
  moment the statics fix) has the value lambda b + offset whatever the preload; the largest
  such |value| / allowable is a lower bound on the girder's worst over the plan's states (the
  level state at the nominal CG is one of them, and the hook errors only add to it). A swap
  whose bound exceeds 1 overloads the girder whatever the preload: the descent never takes it
  while a row it does not rule out improves the objective.
* :meth:`LocalGirder.verdict`, the exact check, with the numbers the plan's own check gives
  (the same :class:`SetEvaluator` and :func:`set_girder`, cached per row): taken for the set a
  descent ends on, best value first, and for the swaps out of a set that overloads (best value
  first, until one keeps the girder).

The search (:func:`~liftplan.planner.search.local.local_search`) moves on the objective among
the swaps the screen leaves, then checks its end sets exactly, best first; one that overloads
the girder is left for its best neighbour that keeps it (any value: feasibility first; else
for the neighbour that overloads it least), from which the descent goes on among the swaps not
found to overload it. The plan is the best row found that
keeps the girder, or, when no row reached keeps it, the best row found (its girder check then
fails, exit 4, and the plan says the local search reached no set that keeps the girder).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.planner.search.evaluator import SetInfeasible
from liftplan.planner.search.girder import applies, set_girder
from liftplan.planner.search.strength import GirderLoads, Sections, State, allowable, section_rows

#: A row's girder bound must exceed 1 by this much before the screen rules it out (the
#: statics' projection is exact to rounding; this keeps a set at its limit in play).
SCREEN_MARGIN = 1e-6
#: Relative residual below which a section's row counts as fixed by the level statics.
FIXED = 1e-9
#: Sets per block of the screen (each block holds (block, sections, n) floats).
BLOCK = 512


@dataclass(frozen=True)
class Verdict:
    """A row's exact girder check.

    Parameters
    ----------
    result : SetResult or None
        The set evaluated over the box; None when it cannot hold the body over the box.
    worst : tuple of GirderWorst
        Its girder's worst |M| and |Q| (empty when ``result`` is None).
    """

    result: object
    worst: tuple

    @property
    def feasible(self):
        """The set holds the body over the box."""
        return self.result is not None

    @property
    def keeps(self):
        """Feasible, and every girder ratio is at most 1 (the plan's own checks pass)."""
        return self.feasible and all(w.ratio <= 1.0 for w in self.worst)

    @property
    def ratio(self):
        """The largest |M| or |Q| / allowable  [-] (inf when infeasible)."""
        return max((w.ratio for w in self.worst), default=0.0) if self.feasible else np.inf


class LocalGirder:
    """The girder's screen and exact verdict for one problem (module docstring).

    Parameters
    ----------
    problem : PlanProblem
        With a weight curve and ``[strength]`` (:func:`~.girder.applies`).
    evaluator : SetEvaluator
        The one whose results the plan reports: a verdict's result is the plan's.
    """

    def __init__(self, problem, evaluator):
        self.problem, self.evaluator = problem, evaluator
        self.verdicts = {}  # (indices, cranes) -> Verdict
        self.exact = 0  # exact verdicts taken (each a set's evaluation)
        self.ruled_out = 0  # swaps the screen ruled out
        loads = GirderLoads(problem.body)
        envelopes = (problem.strength.bending_moment, problem.strength.shear_force)
        points = np.asarray(problem.points, dtype=float)
        sections = Sections.initial(loads, points[:, 0], envelopes)
        gain_m, offset_m, gain_q, offset_q = section_rows(loads, points, sections, State((0.0, 0.0, 1.0)))
        # a section at a candidate's station counts for the sets with a lug there (the plan's
        # check takes the sections at its own lugs); the others for every set
        self.rows = [
            (gain, offset, allowable(envelope, sections.x))
            for gain, offset, envelope in ((gain_m, offset_m, envelopes[0]), (gain_q, offset_q, envelopes[1]))
            if envelope is not None
        ]
        stations = len(np.unique(points[:, 0]))  # Sections.initial: the plain ones, then each station twice
        self.station = np.arange(len(sections)) >= len(sections) - 2 * stations
        self.section_x = sections.x
        self.points = points
        self.weight = problem.body.weight * np.array([1.0, problem.body.cog[0], problem.body.cog[1]])
        self.hinged = problem.hinge_rows is not None  # hinged slings: no body-fixed level forces

    @staticmethod
    def of(problem, evaluator):
        """A :class:`LocalGirder` when the problem's girder is checked, else None."""
        return LocalGirder(problem, evaluator) if applies(problem) else None

    # -- the necessary screen -------------------------------------------------------------------
    def screen(self, sets):
        """A lower bound on each set's girder ratio over the plan's states, whatever its preload.

        Parameters
        ----------
        sets : (N, n) int
            Candidate indices of each row.

        Returns
        -------
        (N,) float  [-]
            The largest |M| or |Q| / allowable at level with the nominal CG over the sections
            whose value the level statics fix (0 where none is fixed).
        """
        sets = np.asarray(sets, dtype=np.int64)
        out = np.zeros(len(sets))
        if self.hinged or not len(sets):
            return out
        for start in range(0, len(sets), BLOCK):
            block = sets[start : start + BLOCK]
            xyz = self.points[block]  # (B, n, 3)
            statics = np.stack([np.ones(xyz.shape[:2]), xyz[..., 0], xyz[..., 1]], axis=1)  # (B, 3, n)
            # (A A^T)^+: collinear lugs (singular statics, ruled out by the search's screening)
            # get a projection onto what their statics span
            normal = np.linalg.pinv(statics @ statics.transpose(0, 2, 1), hermitian=True)  # (B, 3, 3)
            # the sections of this set: every one but the stations of candidates not in it
            here = ~self.station[None, :] | np.any(
                self.section_x[None, :, None] == xyz[:, None, :, 0], axis=2
            )  # (B, S)
            for gain, offset, allow in self.rows:
                g = gain.T[block]  # (B, n, S)
                lam = normal @ (statics @ g)  # (B, 3, S)
                residual = np.linalg.norm(g - statics.transpose(0, 2, 1) @ lam, axis=1)
                fixed = (residual <= FIXED * (1.0 + np.linalg.norm(g, axis=1))) & here
                value = np.abs(np.einsum("bks,k->bs", lam, self.weight) + offset[None, :]) / allow
                out[start : start + len(block)] = np.maximum(
                    out[start : start + len(block)], np.where(fixed, value, 0.0).max(axis=1)
                )
        return out

    def passes(self, sets):
        """(N,) True where the screen does not rule the set out (counted in ``ruled_out``)."""
        keep = self.screen(sets) <= 1.0 + SCREEN_MARGIN
        self.ruled_out += int(np.sum(~keep))
        return keep

    def allowed(self, sets, cranes):
        """(N,) True where a swap may be taken: the screen does not rule it out and no exact
        check found it to overload the girder."""
        keep = self.passes(sets)
        for k in np.flatnonzero(keep):
            keep[k] = not self.overloads((sets[k], cranes[k]))
        return keep

    # -- the exact verdict ----------------------------------------------------------------------
    def verdict(self, row):
        """The exact girder check of a row (set, cranes), as the plan checks it (cached).

        Returns
        -------
        Verdict
        """
        key = _key(row)
        if key not in self.verdicts:
            self.exact += 1
            try:
                result = self.evaluator.evaluate(*key)
            except SetInfeasible:
                self.verdicts[key] = Verdict(None, ())
            else:
                self.verdicts[key] = Verdict(result, set_girder(self.problem, result, self.evaluator.dense))
        return self.verdicts[key]

    def overloads(self, row):
        """True when the row's exact verdict is known and it does not keep the girder."""
        key = _key(row)
        return key in self.verdicts and not self.verdicts[key].keeps

    def result(self, row):
        """The row's evaluated set when its verdict was taken and it is feasible, else None."""
        verdict = self.verdicts.get(_key(row))
        return None if verdict is None else verdict.result


def _key(row):
    """A row (set, cranes) as a key: two tuples of int."""
    return tuple(int(i) for i in row[0]), tuple(int(j) for j in row[1])
