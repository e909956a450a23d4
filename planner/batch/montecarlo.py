"""Monte-Carlo check of a plan against hook-height errors, on the forward elastic model.

Each draw moves every hook off its planned height by an independent error (uniform within
the tolerance, or normal with the tolerance as its standard deviation) and solves the full
elastic model (the body finds its own pose; slack ropes carry nothing): Newton mapped over
blocks of 4096 draws in one casadi call, each answer accepted by the same test as every
elastic answer (:mod:`liftplan.model.statics.acceptance`). The planner's worst case holds every
error within the tolerance box exactly, so no uniform draw may exceed the plan's worst
spread or any rope's largest load (``tests/planner/test_montecarlo.py``); the draws show how likely
the crew is to see what, and what happens when they are worse than assumed. The same
draws run as a ``batch`` study (``kind = "montecarlo"``, one CSV row per draw).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.statics.model import BLOCK, FastCall, Layout, rope_model
from liftplan.model.statics.vertical import elastic_verdict, pack_params

DISTRIBUTIONS = ("uniform", "normal")


@dataclass(frozen=True)
class HookMonteCarlo:
    """Draws of hook-height errors on a plan and what the elastic model gives for each.

    Parameters
    ----------
    labels : tuple of str
        The plan's lug labels.
    tolerance : numpy.ndarray, shape (n,)  [m]
        Each hook's error scale: the half-width (uniform) or standard deviation (normal).
    distribution : {"uniform", "normal"}
    seed : int
    errors : numpy.ndarray, shape (draws, n)  [m]
    tensions : numpy.ndarray, shape (draws, n)  [t]
        NaN where no stable upright equilibrium was found (counted in ``failed``).
    heel, trim : numpy.ndarray, shape (draws,)  [deg]
    plan_worst_spread : float  [t]
        The plan's worst spread over everything it declared uncertain.
    plan_rope_max : numpy.ndarray, shape (n,)  [t]
        The plan's largest load of each rope.
    design_load, swl : numpy.ndarray, shape (n,)  [t]
        Each crane's design hook load and chart SWL.
    design_tension : numpy.ndarray, shape (n,) or None  [t]
        Each rope's largest static tension the design hook load covers
        (:attr:`~liftplan.planner.plans.design_loads.CraneDesign.design_tension`): what a drawn
        static tension is compared with (NaN where no design load was computed).
    """

    labels: tuple
    tolerance: np.ndarray
    distribution: str
    seed: int
    errors: np.ndarray
    tensions: np.ndarray
    heel: np.ndarray
    trim: np.ndarray
    plan_worst_spread: float
    plan_rope_max: np.ndarray
    design_load: np.ndarray
    swl: np.ndarray
    design_tension: np.ndarray | None = None

    @property
    def draws(self):
        return len(self.errors)

    @property
    def solved(self):
        """Draws with an accepted equilibrium (bool, (draws,))."""
        return np.all(np.isfinite(self.tensions), axis=1)

    @property
    def failed(self):
        return int(np.sum(~self.solved))

    @property
    def spread(self):
        """max - min tension of each solved draw  [t]."""
        return np.ptp(self.tensions[self.solved], axis=1)

    @property
    def inside(self):
        """Draws with every error within its hook's tolerance (bool, (draws,))."""
        return np.all(np.abs(self.errors) <= self.tolerance * (1 + 1e-12), axis=1)

    def probability(self, event):
        """Share of solved draws where ``event`` (bool per solved draw) holds  [-]."""
        event = np.asarray(event)
        return float(np.mean(event)) if event.size else float("nan")

    def above(self, limit):
        """Share of solved draws with a rope above its ``limit`` (n,)  [-]; NaN when a limit
        is not known (a design load that could not be computed is no pass)."""
        limit = np.asarray(limit, dtype=float)
        if limit.shape != (len(self.labels),) or not np.all(np.isfinite(limit)):
            return float("nan")
        return self.probability(np.any(self.tensions[self.solved] > limit, axis=1))

    def summary(self):
        """The figures a crew and a checker read: spread percentiles, per-rope maxima, and
        the chance of exceeding the plan's worst spread, a design load or an SWL.

        ``p_above_design_tension``: a drawn static tension above the static tension its
        crane's design load covers (like for like: both static, nominal weight).
        ``p_above_design_load``: a drawn static tension above the design hook load itself,
        which carries the contingency, the DAF and the rigging on top (lenient; kept for
        scripts that read it).
        """
        solved = self.tensions[self.solved]
        spread = self.spread
        slack = np.any(solved <= 0.0, axis=1)
        return {
            "draws": self.draws,
            "failed": self.failed,
            "distribution": self.distribution,
            "seed": self.seed,
            "tolerance": dict(zip(self.labels, self.tolerance.tolist())),
            "heel_max": float(np.nanmax(np.abs(self.heel))) if self.draws else 0.0,
            "trim_max": float(np.nanmax(np.abs(self.trim))) if self.draws else 0.0,
            "spread_p50": float(np.percentile(spread, 50)),
            "spread_p95": float(np.percentile(spread, 95)),
            "spread_max": float(spread.max()),
            "rope_max": dict(zip(self.labels, solved.max(axis=0).tolist())),
            "p_spread_above_plan_worst": self.probability(spread > self.plan_worst_spread + 1e-6),
            "p_above_design_load": self.above(self.design_load),
            "p_above_design_tension": (
                self.above(self.design_tension) if self.design_tension is not None else float("nan")
            ),
            "design_tension": (
                dict(zip(self.labels, self.design_tension.tolist()))
                if self.design_tension is not None
                else None
            ),
            "p_above_swl": self.above(self.swl),
            "p_slack": self.probability(slack),
            "plan_worst_spread": self.plan_worst_spread,
        }


def draw_units(draws, n, distribution="uniform", seed=0):
    """Standard hook-error draws: uniform on [-1, 1] or standard normal, shape (draws, n).

    Multiplied by each hook's tolerance they are the errors [m]; drawn from ``seed`` alone
    (one generator, row by row), so a study chunked for Dask draws the same numbers.
    """
    if not isinstance(draws, int) or isinstance(draws, bool) or draws < 1:
        raise InvalidScene(f"draws = {draws!r}: expected an integer >= 1")
    if distribution not in DISTRIBUTIONS:
        raise InvalidScene(f"distribution = {distribution!r}: expected uniform or normal")
    rng = np.random.default_rng(seed)
    if distribution == "uniform":
        return rng.uniform(-1.0, 1.0, (draws, n))
    return rng.normal(0.0, 1.0, (draws, n))


@cache
def block_solver(n):
    """The elastic Newton solve mapped over :data:`BLOCK` parameter columns (one call)."""
    return FastCall(
        rope_model(n).elastic_solver.function.map(f"elastic_solve_{n}_block", "serial", BLOCK, [], [])
    )


def solve_draws(scene, errors):
    """Solve a scene's elastic model with its boom heights moved by each row of ``errors``.

    Parameters
    ----------
    scene : Scene
        Vertical ropes (the plan's scene), cranes in lug order.
    errors : numpy.ndarray, shape (draws, n)  [m]

    Returns
    -------
    tensions : numpy.ndarray, shape (draws, n)  [t]
        NaN where the draw has no accepted equilibrium (solve's own acceptance,
        :func:`~liftplan.model.statics.vertical.elastic_verdict`: residual, stability, upright).
    heel, trim : numpy.ndarray, shape (draws,)  [deg]
    """
    errors = np.atleast_2d(np.asarray(errors, dtype=float))
    draws, n = errors.shape
    p0 = pack_params(scene, "elastic")
    boom = Layout(n).boom
    solver = block_solver(n)
    tensions = np.full((draws, n), np.nan)
    heel = np.full(draws, np.nan)
    trim = np.full(draws, np.nan)
    params = np.tile(p0, (BLOCK, 1))
    for start in range(0, draws, BLOCK):
        size = min(BLOCK, draws - start)
        params[:, boom] = p0[boom]  # padding columns: the plan itself
        params[:size, boom] += errors[start : start + size]
        x, t, _, residual, minors = (a.reshape(BLOCK, -1) for a in solver(params.ravel()))
        for k in range(size):
            if elastic_verdict(scene, x[k], residual[k], minors[k]).ok:
                tensions[start + k] = t[k]
                heel[start + k], trim[start + k] = np.degrees(x[k, 1]), np.degrees(x[k, 2])
    return tensions, heel, trim


def hook_monte_carlo(plan, draws=10_000, tolerance=None, distribution="uniform", seed=0):
    """Solve the plan's elastic model under random hook-height errors.

    Parameters
    ----------
    plan : Plan
    draws : int
    tolerance : float or array_like of n floats, optional  [m]
        Error scale per hook (default: the plan's hook tolerances).
    distribution : {"uniform", "normal"}
        ``uniform``: within +-tolerance; ``normal``: standard deviation = tolerance.
    seed : int
        The draws are reproducible from it.

    Returns
    -------
    HookMonteCarlo
    """
    n = len(plan.labels)
    scale = (
        plan.lugset.hook_tolerance
        if tolerance is None
        else np.broadcast_to(np.asarray(tolerance, dtype=float), (n,))
    )
    if not np.all(np.isfinite(scale)) or np.any(scale < 0):
        raise InvalidScene(f"tolerance = {tolerance!r}: expected finite hook tolerances >= 0 m")
    errors = draw_units(draws, n, distribution, seed) * scale
    # the plan's scene lists its cranes in label order, as the errors are drawn
    tensions, heel, trim = solve_draws(plan.scene, errors)
    return HookMonteCarlo(
        labels=plan.labels,
        tolerance=np.asarray(scale, dtype=float),
        distribution=distribution,
        seed=seed,
        errors=errors,
        tensions=tensions,
        heel=heel,
        trim=trim,
        plan_worst_spread=plan.worst_spread,
        plan_rope_max=np.asarray(plan.chosen.rope_max),
        design_load=np.array([c.design_hook_load for c in plan.capacity]),
        swl=np.asarray(plan.chosen.swl, dtype=float),
        design_tension=np.array([c.design_tension for c in plan.capacity]),
    )
