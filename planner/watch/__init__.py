"""Watching a lift: from the load cells to the next hook move (``liftplan watch``).

A plan's :class:`~liftplan.planner.plans.watch_basis.WatchBasis` (from a plan, or the plan
JSON's ``"watch"`` object) sets up the plan's elastic forward model (:mod:`.forward`). Each
reading (:mod:`.readings`: CSV or JSON, checked row by row) is fitted by weighted least squares
(:mod:`.estimate`: the weight, the CG and the hooks' height errors, their covariance and what
the readings cannot tell apart), and the fit gives the least hook move back into the plan's
band, or the stop signal (:mod:`.advice`). :class:`~.update.Watcher` runs both per reading;
:mod:`.simulate` writes a synthetic lift with a known truth; :mod:`.command` and
:mod:`.handlers` are the command line.
"""

from liftplan.model.lazy import lazy_package

# loaded on first use: the command line imports .command at start-up, not cvxpy
_EXPORTS = {"Update": "update", "Watcher": "update", "advise": "update", "estimate": "estimate"}
__all__ = sorted(_EXPORTS)
__getattr__, __dir__ = lazy_package(__name__, _EXPORTS)
