"""Monte-Carlo hook-height errors on the forward elastic model: the plan's worst case holds."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model.errors import InvalidScene
from liftplan.planner.batch.montecarlo import hook_monte_carlo
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem


@pytest.fixture(scope="module")
def tanker_plan():
    return plan(load_problem(EXAMPLES / "tanker_plan.toml"))  # hook_tolerance = 0.02 m


def test_no_draw_inside_the_tolerance_exceeds_the_plan(tanker_plan):
    mc = hook_monte_carlo(tanker_plan, draws=3000, seed=7)
    assert mc.failed == 0 and np.all(mc.inside)
    solved = mc.tensions[mc.solved]
    # the plan's worst case covers every error in the box, every attitude of the tolerance box
    # and the CG envelope; 1e-6 t: both are solved to 1e-9 W
    assert mc.spread.max() <= tanker_plan.worst_spread + 1e-6
    assert np.all(solved.max(axis=0) <= np.asarray(tanker_plan.chosen.rope_max) + 1e-6)
    assert np.all(solved.max(axis=0) <= mc.design_load)
    summary = mc.summary()
    assert summary["p_spread_above_plan_worst"] == 0.0 and summary["p_above_swl"] == 0.0
    # the draws are not trivial: they spread the ropes well beyond the level spread
    assert summary["spread_p95"] > 2 * tanker_plan.spread


def test_draws_are_reproducible_and_larger_errors_exceed_the_plan(tanker_plan):
    first = hook_monte_carlo(tanker_plan, draws=200, seed=3)
    again = hook_monte_carlo(tanker_plan, draws=200, seed=3)
    np.testing.assert_array_equal(first.tensions, again.tensions)
    worse = hook_monte_carlo(tanker_plan, draws=2000, tolerance=0.1, seed=3).summary()
    # five times the planned tolerance: the crew's errors now exceed the plan's worst spread
    assert worse["p_spread_above_plan_worst"] > 0.2
    normal = hook_monte_carlo(tanker_plan, draws=500, distribution="normal", seed=3)
    assert not np.all(normal.inside)  # a normal draw leaves the box now and then


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"draws": 0}, "draws = 0: expected an integer >= 1"),
        ({"distribution": "gauss"}, "expected uniform or normal"),
        ({"tolerance": -0.1}, "expected finite hook tolerances >= 0 m"),
    ],
)
def test_bad_input(tanker_plan, kwargs, message):
    with pytest.raises(InvalidScene, match=message):
        hook_monte_carlo(tanker_plan, **kwargs)


# -- the batch study kind (liftplan batch, kind = "montecarlo") ---------------------------------
MC_STUDY = """
[study]
problem = "tanker_plan.toml"
kind = "montecarlo"
output = "mc.csv"
chunk = 700

[montecarlo]
draws = 2000
seed = 5
"""


def _study(tmp_path, text):
    import shutil

    from liftplan.planner.batch.study import load_study

    shutil.copy(EXAMPLES / "tanker_plan.toml", tmp_path / "tanker_plan.toml")
    path = tmp_path / "mc.toml"
    path.write_text(text, encoding="utf-8")
    return load_study(path)


@pytest.fixture(scope="module")
def client():
    """A local Dask cluster of two single-threaded worker processes."""
    import logging

    from dask.distributed import Client, LocalCluster

    with (
        LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as dask_client,
    ):
        yield dask_client


def _table(path):
    import csv

    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_montecarlo_study_is_seeded_reproducible_and_within_the_plan(tmp_path, client, tanker_plan):
    from liftplan.planner.batch.run import run_study

    study = _study(tmp_path, MC_STUDY)
    assert study.size == 2000
    summary = run_study(study, client=client, progress=False)
    assert summary.counts == {"ok": 2000}
    first = (tmp_path / "mc.csv").read_bytes()
    rows = _table(tmp_path / "mc.csv")
    # the same numbers again, chunked differently (the draws are made from the seed alone)
    again = _study(tmp_path, MC_STUDY.replace("chunk = 700", "chunk = 333"))
    run_study(again, client=client, progress=False, output=tmp_path / "again.csv")
    assert (tmp_path / "again.csv").read_bytes() == first
    # the rows are the API's draws (same seed, same solve)
    api = hook_monte_carlo(tanker_plan, draws=2000, seed=5)
    errors = np.array([[float(r[f"error.L{i}"]) for i in range(1, 5)] for r in rows])
    tensions = np.array([[float(r[f"tension.L{i}"]) for i in range(1, 5)] for r in rows])
    np.testing.assert_array_equal(errors, api.errors)
    np.testing.assert_allclose(tensions, api.tensions, rtol=0, atol=1e-9)
    # uniform draws inside the plan's +-0.02 m: none exceeds the plan's worst case (the
    # planner's bound is exact over the box; 1e-6 t: both solved to 1e-9 W)
    assert np.all(np.abs(errors) <= 0.02)
    spread = np.array([float(r["spread"]) for r in rows])
    assert spread.max() <= tanker_plan.worst_spread + 1e-6
    assert all(r["above_plan_worst"] == "0" and r["above_swl"] == "0" for r in rows)
    np.testing.assert_allclose(spread, np.ptp(tensions, axis=1), atol=1e-9)


def test_montecarlo_study_per_crane_tolerance_and_normal(tmp_path, client, tanker_plan):
    from liftplan.planner.batch.run import run_study

    text = MC_STUDY.replace(
        "seed = 5", 'seed = 5\ndistribution = "normal"\ntolerance = 0.1\ntolerances = { "crane 2" = 0.0 }'
    )
    study = _study(tmp_path, text)
    run_study(study, client=client, progress=False)
    rows = _table(tmp_path / "mc.csv")
    crane = dict(zip(tanker_plan.labels, tanker_plan.chosen.crane_names))
    still = [label for label, name in crane.items() if name == "crane 2"]
    assert len(still) == 1
    assert all(float(r[f"error.{still[0]}"]) == 0.0 for r in rows)
    # five times the plan's tolerance as a standard deviation: the plan's worst is exceeded,
    # and rows over an SWL or with a slack rope are unsafe with their reason
    assert any(r["above_plan_worst"] == "1" for r in rows)
    unsafe = [r for r in rows if r["status"] == "unsafe"]
    assert unsafe and all("over the plan's limit" in r["reason"] or "slack" in r["reason"] for r in unsafe)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (MC_STUDY.replace("draws = 2000", "draws = 0"), "montecarlo.draws"),
        (MC_STUDY.replace("seed = 5", 'seed = 5\ndistribution = "gauss"'), "montecarlo.distribution"),
        (MC_STUDY.replace("seed = 5", "seed = 5\ntolerance = -0.1"), "montecarlo.tolerance = -0.1"),
        (
            MC_STUDY.replace("seed = 5", 'seed = 5\ntolerances = { "crane 9" = 0.1 }'),
            "montecarlo.tolerances.crane 9: no such crane",
        ),
        (MC_STUDY.replace("seed = 5", "seed = 5\ntolerance = 0.0"), "every hook's tolerance is 0"),
        (MC_STUDY + '\n[sweep]\n"body.weight" = [900.0]\n', "sweep: given with study.kind = 'montecarlo'"),
        (MC_STUDY.replace('kind = "montecarlo"', 'kind = "check"'), "montecarlo: given with study.kind"),
    ],
)
def test_bad_montecarlo_studies_are_one_line_errors(tmp_path, text, match):
    with pytest.raises(InvalidScene, match=match) as err:
        _study(tmp_path, text)
    assert "\n" not in str(err.value)
