"""The one line that says a search limit ended an exact search (``liftplan plan``'s console:
held, sling and strength plans), and the lines of a rope-length search (:func:`length_lines`).

A plan whose search ran out of time (``[plan] time_limit``) or work (``[plan] work_limit``)
is the best found, not proved the best: the console says so next to the search counts, with
the certified lower bound and the gap, and, for a rope-length search, how many lengths were
cut short or not tried.
"""

from __future__ import annotations

#: What ended the search -> (what it is, the key a larger value of which searches further).
LIMITS = {
    "time_limit": ("the time limit", "[plan] time_limit"),
    "work_limit": ("the work limit", "[plan] work_limit"),
}

#: Length sets the console lists by value (more: the count only; the report lists them all).
MAX_LISTED = 9


def limit_lines(stats, problem, lengths=None):
    """One line when a time or work limit ended the search, else none.

    Parameters
    ----------
    stats : SearchStats or None
        The plan's search (``stopped``, ``best``, ``lower_bound``, ``gap``).
    problem : PlanProblem
        The user's limits (``time_limit`` [s], ``work_limit`` [sets]) and the objective's unit.
    lengths : LengthSearch, optional
        The rope-length search, when the planner chose the lengths.

    Returns
    -------
    list of str
    """
    if stats is None or stats.stopped not in LIMITS:
        return []
    what, key = LIMITS[stats.stopped]
    given = (
        f" of {problem.time_limit:g} s"
        if stats.stopped == "time_limit"
        else f" of {problem.work_limit} sets evaluated"
    )
    unit = problem.goal.unit
    fmt = (lambda v: f"{v:.4f}") if unit == "-" else (lambda v: f"{v:.2f} t")
    trials = ""
    if lengths is not None:
        cut, untried = len(lengths.cut_short), lengths.not_tried
        trials = (
            f" ({cut} of {len(lengths.trials)} rope-length trials cut short, {untried} "
            f"length{'s' if untried != 1 else ''} not tried)"
        )
    if stats.gap > 0.0:
        bound = (
            f"lower bound {fmt(stats.lower_bound)}"
            if stats.lower_bound > 0.0
            else "no lower bound claimed (the limit left part of the search undone)"
        )
        what_of = (
            f"the plan is the best found, not proved the best; {bound}, gap {fmt(stats.gap)} "
            f"({100 * stats.relative_gap:.1f} %)"
        )
    else:  # the first plan's bound met before the limit: the ranking below it is what was cut
        what_of = (
            f"the plan is proved the best (lower bound {fmt(stats.lower_bound)}, gap 0), the "
            "alternatives ranked below it are not"
        )
    return [f"SEARCH STOPPED AT {what.upper()}{given}{trials}: {what_of}; a larger {key} searches further"]


def length_lines(search, rope="rope length", where=""):
    """The rope lengths the planner chose, and what the search counts above cover.

    Parameters
    ----------
    search : LengthSearch
    rope : str
        What the length is of ("rope length", "hoist rope length").
    where : str
        Between what, e.g. " (tip to hook)".

    Returns
    -------
    list of str
    """
    lines = [
        f"{rope} {length:.3f} m{where} chosen within {lo:g} to {hi:g} m for {', '.join(names)}"
        for names, (lo, hi), length in zip(search.classes, search.ranges, search.chosen)
    ]
    tried = (
        ", ".join("/".join(f"{v:g}" for v in t.lengths) for t in search.trials) + " m; "
        if len(search.trials) <= MAX_LISTED
        else ""
    )
    lines.append(
        f"{len(search.trials)} lengths tried ({tried}each an exact plan, {search.evaluated} sets "
        "evaluated over them); the search counts are the chosen length's, and its bound "
        "holds over the lengths tried"
    )
    return lines
