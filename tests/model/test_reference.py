"""The linear models against a 50-digit mpmath reference (tests/reference/, regenerate with
``python tests/reference/make_linear_reference.py``). Tolerance 1e-11 relative: these
systems have condition numbers below 1e4, so double precision leaves ~1e-12."""

import json

import pytest
from helpers import ROOT
from numpy.testing import assert_allclose

from liftplan.model import Analysis, Attitude, Body, Crane, Lug, Redundant, Scene, solve

CASES = json.loads((ROOT / "tests" / "reference" / "linear_reference.json").read_text())


def scene_of(case, model):
    names = [f"L{i}" for i in range(len(case["lugs"]))]
    held = tuple(Redundant(names[int(i)], t) for i, t in case["held"].items())
    return Scene(
        body=Body(case["weight"], tuple(case["cog"])),
        lugs=tuple(Lug(name, tuple(p)) for name, p in zip(names, case["lugs"])),
        cranes=tuple(Crane(name, EA=ea, boom_height=h) for name, ea, h in zip(names, case["EA"], case["H"])),
        attitude=Attitude(case["heel"], case["trim"], case["yaw"], case["lift"]),
        analysis=Analysis(model, held if model == "rigid" else ()),
    )


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
@pytest.mark.parametrize("model", ["rigid", "paper-elastic"])
def test_linear_models_match_high_precision(case, model):
    eq = solve(scene_of(case, model))
    expected = [float(v) for v in case["rigid" if model == "rigid" else "paper_elastic"]]
    assert_allclose(list(eq.tensions.values()), expected, rtol=1e-11)
