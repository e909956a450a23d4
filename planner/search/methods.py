"""The search methods as a table, and :func:`search`, which picks one.

Each method takes ``(problem, started, top, progress)`` and returns ``(ranking, stats)``: the
best (set, assignment) rows found, best first, and their :class:`~.evaluator.SearchStats`
with a certified lower bound. A new method is one module and one row of :data:`METHODS`
(and its name among the ``[plan] search`` choices of the planning file).
"""

from __future__ import annotations

import time

from liftplan.planner.problem.definition import MAX_SETS
from liftplan.planner.search.exact import search_exact
from liftplan.planner.search.local import search_local
from liftplan.planner.search.mip import search_mip

#: ``[plan] search`` -> the method.
METHODS = {
    "exact": search_exact,
    "local": search_local,
    "mip": search_mip,
}


def search(problem, top=None, progress=None):
    """Rank the best lug sets with their crane assignments.

    Best bound first over every (set, assignment) row: the search stops when no row left
    can enter the top k (the optimum is proved), when the best plan is within
    ``problem.gap`` of the certified lower bound, or at ``problem.time_limit``.

    Parameters
    ----------
    problem : PlanProblem
    top : int, optional
        How many to rank (default ``problem.top``).
    progress : bool, optional
        A progress bar on stderr (rows done, best, bound, gap). Default: when stderr is a
        terminal, shown once the search has run a second.

    Returns
    -------
    ranking : list of SetResult
        Best first (smallest worst value of the objective).
    stats : SearchStats
        With the certified lower bound and the gap.

    Raises
    ------
    PlanInfeasible
        No lug set is feasible; the message counts the causes.
    Interrupted
        Ctrl-C: carries the best ranking found so far.
    """
    started = time.perf_counter()
    method = problem.search
    if method == "auto":
        method = "exact" if problem.set_count <= auto_exact_limit(problem.cranes) else "local"
    return METHODS[method](problem, started, top or problem.top, progress)


#: ``search = "auto"``: the exact search for five or more lugs up to this many sets
#: (studies/planner_scale.py on an idle machine: 5 of 24 candidates, 42 504 sets, proved in
#: 5.7 s; 5 of 40, 658 008 sets, proved in 151 s, where the local search is 0.9 % above in
#: 0.9 s; about a quarter of a millisecond a set, so some 50 s at this limit).
AUTO_EXACT_MANY = 200_000


def auto_exact_limit(cranes):
    """Lug sets up to which ``search = "auto"`` runs the exact search (n <= 4: its screening
    is the exact LP over the screening scenarios, and 5e6 sets screen in seconds)."""
    return MAX_SETS if cranes <= 4 else AUTO_EXACT_MANY
