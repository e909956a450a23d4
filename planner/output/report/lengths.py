"""The report's section on rope lengths the planner chose (``crane.rope_length = { min, max }``,
:mod:`liftplan.planner.plans.lengths`): the range, the chosen length and every length tried
with its best value, for single ropes and for the hoist ropes of cranes on slings alike."""

from __future__ import annotations

import html
import math

from liftplan.planner.output.report import page as report_page

#: What the range is of, per kind of plan: (heading, the chosen length's column).
ROPES = {
    "hoist": ("Hoist rope lengths", "chosen hoist rope length, tip to hook [m]"),
    "single": ("Rope lengths", "chosen rope length l0 (payout), tip to lug [m]"),
}


def lengths_section(plan, ropes="single"):
    """The rope lengths the planner chose in each crane's range, and every length tried.

    Parameters
    ----------
    plan : Plan or sling plan
        With ``lengths`` (a :class:`~liftplan.planner.plans.lengths.LengthSearch`, or None:
        no section) and ``objective``.
    ropes : {"single", "hoist"}
        Single ropes to the lugs, or the hoist ropes of cranes on slings.

    Returns
    -------
    list of str
        HTML.
    """
    search = plan.lengths
    if search is None:
        return []
    heading, column = ROPES[ropes]
    chosen = report_page.table(
        ["cranes", "range [m]", column],
        [
            (", ".join(names), f"{lo:g} to {hi:g}", f"{length:.3f}")
            for names, (lo, hi), length in zip(search.classes, search.ranges, search.chosen)
        ],
        f"{heading} chosen by the planner",
        full=False,
        text_columns=(0,),
    )
    unit, scale = ("t", 1.0) if plan.objective == "spread" else ("%", 100.0)

    def bound(t):
        if t.cut_short and t.value is None:
            return "none claimed"
        return "-" if not math.isfinite(t.lower_bound) else f"{scale * t.lower_bound:.2f}"

    trials = report_page.table(
        ["lengths [m]", f"worst [{unit}]", f"lower bound [{unit}]", "search ended", "lugs, or why no plan"],
        [
            (
                ", ".join(f"{v:.3f}" for v in t.lengths),
                "-" if t.value is None else f"{scale * t.value:.2f}",
                bound(t),
                _ended(t),
                " ".join(t.lugs) if t.value is not None else t.reason,
            )
            for t in search.trials
        ],
        "Every length tried (each an exact plan at those lengths), in the order tried; "
        "'share': what was left of the time limit when the trial began",
        text_columns=(3, 4),
    )
    untried = (
        f" The time limit ran out with {search.not_tried} length(s) the search meant to try left "
        "untried: no lower bound is claimed over the range."
        if search.not_tried
        else ""
    )
    timed = (
        "; a trial cut short by the time limit that found no plan claims no bound"
        if any(t.time_share is not None for t in search.trials)
        else ""
    )
    text = (
        f"<p>The planner chose the rope length within each range: {len(search.trials)} lengths "
        "tried, the first pass evenly spaced over the range, then halved steps about the best. "
        f"The lower bound and a 'proved' optimum hold over the lengths tried, not between them"
        f"{timed}.{untried} "
        f"The appendix's search counts are the chosen length's; {search.evaluated} sets were "
        "evaluated over every length tried.</p>"
    )
    return [f"<h3>{html.escape(heading)}</h3>", text, chosen, trials]


def _ended(trial):
    """Why a trial's search ended, with its share of the time limit."""
    ended = "infeasible (proved)" if trial.value is None and not trial.cut_short else trial.stopped
    return ended if trial.time_share is None else f"{ended} (share {trial.time_share:.3g} s)"
