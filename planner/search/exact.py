"""The exact search: branch and bound over lug sets and crane assignments.

1. :func:`~liftplan.planner.search.screen.screen` gives every (set, assignment) row a lower
   bound on its worst value (and rules out the rows it can prove infeasible).
2. Rows are evaluated best bound first by
   :class:`~liftplan.planner.search.evaluator.SetEvaluator` (the preload minimax LP with
   cutting planes over the dense box).
3. The search stops when the next row's bound is no better than the k-th best worst value
   found: no row left can enter the top k (every bound is a valid lower bound).
"""

from __future__ import annotations

import heapq
import math
import time
from collections import Counter

import numpy as np

from liftplan.model.errors import PlanInfeasible
from liftplan.planner.search.evaluator import (
    Interrupted,
    SearchStats,
    SetEvaluator,
    SetInfeasible,
    tick,
)
from liftplan.planner.search.lines import line_bound
from liftplan.planner.search.progress import phase, progress_bar
from liftplan.planner.search.screen import (
    FEASIBLE,
    FULL_COLUMNS,
    REASONS,
    row_ceiling,
    screen,
    screening_scenarios,
    set_rows,
)

#: Rows whose coarse screening bound is replaced by the full one at a time (256: fewer, larger
#: calls; 4 of 100 candidates 21.9 -> 18.3 s, 8 of 16 5.4 -> 4.6 s against 64).
REFINE = 256
#: Rows in the first refinement batch under a time limit (its time sets the next batches').
FIRST_REFINE = 8
#: n >= 5: refine the preload-free pair bound to the LP's dual bound before a row is
#: evaluated (False: the pair bound alone, as before; studies/planner_scale.py compares).
DUAL_BOUND = True
#: A row whose dual bound over its first few scenarios falls short of the k-th best found
#: goes back to the queue with that bound instead of being bounded over every scenario at
#: once; when it comes up again the k-th best is usually lower and the first stage reaches
#: it (:func:`~liftplan.planner.search.dual.staged_lp_bound`). A row is deferred again only
#: against a lower k-th best than the last time (so it cannot come back for ever).
DEFER = True


def search_exact(problem, started, top, progress=None):
    """The exact search: every (set, assignment) row screened, then evaluated best bound first.

    It stops when no row left can enter the top ``top`` (the optimum is proved), when the
    best plan is within ``problem.gap`` of the certified lower bound, or at
    ``problem.time_limit`` counted from ``started`` (:func:`time.perf_counter`).

    Returns, raises: as :func:`liftplan.planner.search.methods.search`.
    """
    top = top or problem.top
    sets, cranes, out_of_reach, clashing = set_rows(problem)
    if len(sets) == 0:
        if clashing:
            raise PlanInfeasible(
                f"every assignment of the cranes in reach ({clashing}) has two booms crossing in "
                f"plan or nearer than plan.crane_clearance = {problem.crane_clearance:g} m; "
                "expected cranes placed apart, or more candidates"
            )
        raise PlanInfeasible(_unreachable(problem))
    with phase(f"exact search: screening {len(sets)} rows", progress):
        screening = screen(problem, sets, cranes)
    evaluator = SetEvaluator(problem)
    reasons = Counter(
        dict(
            zip(
                *(
                    v.tolist()
                    for v in np.unique(screening.reason[screening.reason != FEASIBLE], return_counts=True)
                )
            )
        )
    )
    bound = screening.bound.copy()
    # rows whose bound is refined before they are evaluated: from the coarse screening, or
    # (n >= 5) from the preload-free pair bound to the LP's dual bound
    dual = problem.cranes >= 5 and DUAL_BOUND
    lazy = _coarse(screening, problem) or dual
    # the target at which each row's dual bound last stopped at its first stage, short of it
    # (inf: never): bounded again when it comes up, deferred again only against a lower
    # target (DEFER)
    deferred = np.full(len(bound), np.inf)
    finite = np.flatnonzero(np.isfinite(bound))
    feasible_rows = len(finite)
    # the heap: rows with a refined bound (False) and rows deferred (True), least bound first
    heap = [] if lazy else [(float(bound[k]), False, int(k)) for k in finite]
    heapq.heapify(heap)
    # the rows still to refine, in the order they are refined (Screening.priority: where the
    # bound orders the rows poorly, the order that finds good plans early), and the least
    # bound of each tail of that order: what no row still to refine can beat
    pending = finite[np.argsort(screening.priority[finite], kind="stable")] if lazy else finite[:0]
    tail = np.append(np.minimum.accumulate(bound[pending][::-1])[::-1], np.inf)
    # rows refined out of their bound order are evaluated in another order than the bound's:
    # ties to rounding (mirror-image sets) are then ranked by their lugs, not by that order
    reordered = lazy and bool(np.any(screening.priority[finite] != bound[finite]))
    rank = rank_key if reordered else (lambda r: (r.worst_value, r.nominal_value))
    cursor = 0  # pending[cursor:] are still to refine
    ranking, evaluated, refine_count = [], 0, 0
    evaluated_bound = math.inf  # least LP bound of the rows evaluated feasible
    stopped = "proved"
    bar = progress_bar(feasible_rows, progress, desc="exact search", unit="rows", ticker=True)

    def least():
        """The least bound of every row not evaluated (the heap's and those to refine)."""
        return min(heap[0][0] if heap else math.inf, float(tail[cursor]))

    def lower_bound():
        return min(evaluated_bound, least())

    def stats_now():
        best = ranking[0].worst_value if ranking else math.inf
        return SearchStats(
            sets=problem.set_count,
            screened_out=int(np.sum(screening.reason != FEASIBLE)),
            evaluated=evaluated,
            pruned=feasible_rows - evaluated,
            infeasible={REASONS[c]: n for c, n in reasons.most_common()},
            seconds=time.perf_counter() - started,
            rows=len(sets),
            out_of_reach=out_of_reach,
            clashing=clashing,
            refined=refine_count,
            # stopped early: the two-line bound may be the better of two valid bounds
            lower_bound=min(
                lower_bound()
                if stopped == "proved"
                else max(lower_bound(), line_bound(problem, evaluator.dense)),
                best,
            ),
            best=best,
            stopped=stopped,
        )

    done = np.zeros(len(bound), dtype=bool)  # evaluated out of turn

    def evaluate(k, value):
        nonlocal evaluated, evaluated_bound
        evaluated += 1
        tick(bar, ranking, lower_bound)
        try:
            result = evaluator.evaluate(sets[k], cranes[k], value)
        except SetInfeasible as err:
            reasons[err.code] += 1
            return
        evaluated_bound = min(evaluated_bound, result.bound)
        ranking.append(result)
        ranking.sort(key=rank)
        del ranking[top:]

    per_row = None  # seconds to refine one row's bound, once measured

    def batch_size():
        """Rows to refine at once: :data:`REFINE`, fewer where the time limit would not hold
        them (the first batch under a time limit is small, to measure the rate)."""
        if problem.time_limit is None:
            return REFINE
        if per_row is None:
            return min(REFINE, FIRST_REFINE)
        left = problem.time_limit - (time.perf_counter() - started)
        return max(1, min(REFINE, int(left / per_row)))

    try:
        while heap or cursor < len(pending):
            if len(ranking) >= top and least() >= ranking[top - 1].worst_value:
                break
            if ranking:
                best, low = ranking[0].worst_value, min(lower_bound(), ranking[0].worst_value)
                if problem.gap > 0 and best - low <= problem.gap * best:
                    stopped = "gap"
                    break
                if problem.work_limit is not None and evaluated >= problem.work_limit:
                    stopped = "work_limit"  # rows evaluated: the same on any machine
                    break
            if problem.time_limit is not None and time.perf_counter() - started > problem.time_limit:
                stopped = "time_limit"  # with no plan yet: none found in time (said so below)
                break
            if heap and not heap[0][1] and heap[0][0] <= tail[cursor]:
                value, _, k = heapq.heappop(heap)  # the least bound, refined: evaluated
                if not done[k]:
                    evaluate(k, value)
                continue
            # a bound past the k-th best found need not be tightened further
            target = ranking[top - 1].worst_value if len(ranking) >= top else np.inf
            # refine a batch: the deferred rows with the least bounds, then the next rows
            # still to refine (those whose bound already passes the k-th best are done with)
            size = batch_size()
            batch = []
            while heap and heap[0][1] and len(batch) < size:
                batch.append(heapq.heappop(heap)[2])
            while cursor < len(pending) and len(batch) < size:
                cursor += 1
                if bound[pending[cursor - 1]] < target:
                    batch.append(int(pending[cursor - 1]))
            if batch:
                clock = time.perf_counter()
                full = screen(
                    problem,
                    sets[batch],
                    cranes[batch],
                    coarse=False,
                    dual=dual,
                    target=target,
                    defer=target < deferred[batch] if dual and DEFER else None,
                )
                per_row = (time.perf_counter() - clock) / len(batch)
                refine_count += int(np.sum(np.isinf(deferred[batch])))  # each row counted once
                partial = np.zeros(len(batch), dtype=bool) if full.partial is None else full.partial
                pushed = []
                for j, new_bound, reason, again in zip(batch, full.bound, full.reason, partial):
                    if reason != FEASIBLE:
                        reasons[int(reason)] += 1
                        continue
                    if again:  # a valid bound, refined further when it comes up
                        deferred[j] = target
                        bound[j] = max(float(new_bound), float(bound[j]))
                        heapq.heappush(heap, (float(bound[j]), True, int(j)))
                        continue
                    entry = (max(float(new_bound), float(bound[j])), False, int(j))
                    heapq.heappush(heap, entry)
                    pushed.append(entry)
                # evaluate the batch's best now when it can enter the top k (and its bound does
                # not prove it infeasible), so that its value lets the next batches' bounds stop
                # early: a k-th best found late leaves every bound refined to the end. Until
                # there are k plans, the batch's best k - (plans) rows (a row is not evaluated
                # twice: it stays in the heap, marked done)
                dives = max(1, top - len(ranking))
                for entry in sorted(pushed)[:dives]:
                    j = entry[2]
                    if entry[0] > row_ceiling(problem, sets[j][None], cranes[j][None])[0]:
                        continue  # its bound proves it infeasible (screen.value_ceiling)
                    if len(ranking) >= top and entry[0] >= ranking[top - 1].worst_value:
                        break
                    if ranking and problem.work_limit is not None and evaluated >= problem.work_limit:
                        break  # the loop's own checks stop the search next
                    if problem.time_limit is not None and time.perf_counter() - started > problem.time_limit:
                        break
                    done[j] = True
                    evaluate(j, entry[0])
    except KeyboardInterrupt:
        stopped = "interrupted"
        raise Interrupted(ranking, stats_now()) from None
    finally:
        if bar is not None:
            bar.close()
    stats = stats_now()
    if not ranking:
        causes = "; ".join(f"{n} sets: {text}" for text, n in stats.infeasible.items())
        what = f"{problem.cranes} lugs among {len(problem.candidates)} candidates"
        if not problem.equal_cranes:
            what += (
                f" with any assignment of the cranes in reach ({out_of_reach} out of reach, "
                f"{clashing} with booms crossing or within the clearance)"
            )
        if stopped == "time_limit":
            what += f" found within the time limit {problem.time_limit:g} s"
        raise PlanInfeasible(
            f"no set of {what} can hold the body within heel +-{problem.heel_tolerance:g} deg, "
            f"trim +-{problem.trim_tolerance:g} deg, tensions {problem.min_tension:g} t to "
            f"each crane's SWL ({causes})"
        )
    return ranking, stats


#: Significant digits of the values that rank two plans when the rows were refined out of
#: their bound order: rows equal to these (mirror-image sets, whose values differ by solver
#: rounding, ~1e-10 relative) are ranked by their lugs and cranes.
RANK_DIGITS = 7


def rank_key(result):
    """Sort key of an evaluated row: worst value, then level value, each to
    :data:`RANK_DIGITS` significant digits, then the candidate indices and cranes (so the
    plan does not depend on the order the rows were evaluated in)."""

    def rounded(value):
        return float(f"{value:.{RANK_DIGITS}g}")

    return (
        rounded(result.worst_value),
        rounded(result.nominal_value),
        tuple(int(i) for i in result.indices),
        tuple(int(c) for c in result.cranes),
    )


def _coarse(screening, problem):
    return len(screening.sets) * len(screening_scenarios(problem)[0]) > FULL_COLUMNS


def _unreachable(problem):
    """Why no assignment puts every crane within reach of a distinct lug."""
    swl = problem.reach[1]
    counts = np.sum(~np.isnan(swl), axis=0)
    worst = int(np.argmin(counts))
    crane = problem.fleet[worst]
    return (
        f"no assignment puts every crane within reach of its own lug: crane "
        f"{crane.name} reaches {int(counts[worst])} of {len(problem.candidates)} candidates "
        f"(chart reach {crane.reach:g} m); expected cranes closer to the candidates or "
        "longer charts"
    )
