"""Where methods fail, the library says so (studies/failure_modes.py is the table).

Every case of the study runs here: each answer is checked independently of the solver
(balance to 1e-6 W, no compression, upright, elastic tensions equal to EA x stretch / l0),
and each failure must be a one-line LiftPlanError, never a wrong number or a crash. The
expected outcome of the cases that matter most is pinned one by one.
"""

import numpy as np
import pytest
from failure_modes import cases, outcome, stiff_limit

CASES = cases()
EXPECTED = {
    ("collinear lugs (4 on a line)", "elastic"): ("refused", "collinear"),
    ("nearly collinear (1 mm off the line)", "elastic"): ("ok", ""),
    ("CG on the support edge (y = 6 m)", "rigid"): ("refused", "compression"),
    ("CG 1 m beyond the edge", "elastic"): ("refused", "outside the lugs' support polygon"),
    ("stiff ropes, EA/l = 1e+07 t/m", "elastic"): ("ok", ""),
    ("stiff ropes, EA/l = 1e+10 t/m", "elastic"): ("refused", "too stiff"),
    ("stiff ropes, EA/l = 1e+10 t/m", "paper-elastic"): ("ok", ""),
    ("heel 60 deg", "paper-elastic"): ("refused", "compression"),
    ("heel 90 deg", "rigid"): ("refused", "singular"),
    ("heel 90 deg", "paper-elastic"): ("refused", "no equilibrium"),
    ("heel 20, trim 20 deg", "elastic"): ("ok", ""),
    ("capsized tanker, heel 2 deg", "elastic"): ("ok", ""),
    ("capsized tanker, heel 10 deg", "paper-elastic"): ("refused", "compression"),
    ("stranded barge, start 10 deg off", "newton"): ("ok", ""),
    ("stranded barge, start 20 deg off", "newton"): ("refused", "turned over"),
    ("stranded barge, start 45 deg off", "paper-newton"): ("refused", "unstable"),
    ("flooded block hanging fully submerged (hoist +0 m)", "hydrostatic"): ("ok", "submerged"),
    ("flooded block leaving the water (hoist +17 m)", "hydrostatic"): ("ok", "state piercing the surface"),
    ("flooded block clear of the water (hoist +30 m)", "hydrostatic"): ("ok", "state clear"),
}
RUNS = [(name, method, run, scene) for name, runs in CASES.items() for method, run, scene in runs]


@pytest.mark.parametrize("name, method, run, scene", RUNS, ids=[f"{r[0]} / {r[1]}" for r in RUNS])
def test_never_a_wrong_number(name, method, run, scene):
    result = outcome(run, scene)
    assert result["outcome"] in ("ok", "refused"), result
    if result["outcome"] == "refused":
        assert result["one_line"], result
    if (name, method) in EXPECTED:
        expected, words = EXPECTED[(name, method)]
        assert result["outcome"] == expected and words in result["detail"], result


def test_every_pinned_case_exists():
    runs = {(name, method) for name, method, _, _ in RUNS}
    assert set(EXPECTED) <= runs


def test_stiff_ropes_tend_to_the_rigid_limit_then_are_refused():
    data = stiff_limit()
    ok = [r for r in data["rows"] if r["outcome"] == "ok"]
    refused = [r for r in data["rows"] if r["outcome"] == "refused"]
    # first order in 1/k: ten times stiffer, ten times closer (6 decades measured)
    k = np.array([r["stiffness"] for r in ok])
    distance = np.array([r["distance"] for r in ok])
    slope = np.polyfit(np.log10(k), np.log10(distance), 1)[0]
    assert slope == pytest.approx(-1.0, abs=0.02)
    assert distance[-1] < 1e-5
    # refused only where float64 heights cannot meet the tolerance (the floor is an upper
    # estimate: it can still succeed a little beyond), and solved wherever they clearly can
    assert refused and all(r["rounding_floor"] > r["tolerance"] for r in refused)
    assert all(r["outcome"] == "ok" for r in data["rows"] if r["rounding_floor"] < r["tolerance"])
    assert all("too stiff" in r["detail"] for r in refused)
