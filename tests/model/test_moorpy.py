"""The forward elastic model against MoorPy on four-rope cases, one with a slack rope.

Tolerance 1e-6 relative (1e-6 W for a slack rope's zero): MoorPy's lines weigh 1e-9 t/m
(it needs a weight) and it stops at 1e-10 m; both leave ~1e-9 relative."""

import numpy as np
import pytest
from numpy.testing import assert_allclose
from support.moorpy_peer import moorpy_solve

from liftplan.model import rotation_matrix, solve

CASES = {  # name: (change to the symmetric block, lugs expected slack)
    "level, even": (lambda s: s, ()),
    "twist on one diagonal": (lambda s: s.with_crane("FP", boom_height=40.2), ()),
    "off-centre CG, uneven hoist": (
        lambda s: (
            s.with_body(cog=(1.5, -0.8, 2.5))
            .with_crane("FS", boom_height=40.1)
            .with_crane("AS", boom_height=39.93)
        ),
        (),
    ),
    "soft rope": (lambda s: s.with_crane("AP", EA=20000.0).with_crane("FS", boom_height=39.9), ()),
    "one rope slack": (lambda s: s.with_crane("FP", boom_height=39.0), ("FP",)),
}


@pytest.mark.parametrize(("change", "slack"), CASES.values(), ids=CASES.keys())
def test_elastic_matches_moorpy(block, change, slack):
    scene = change(block)
    eq = solve(scene, "elastic")
    ours = np.array(list(eq.tensions.values()))
    theirs, heights = moorpy_solve(scene, eq.pose.heel, eq.pose.trim, eq.pose.lift_height)
    assert_allclose(ours, theirs, rtol=1e-6, atol=1e-6 * scene.body.weight)
    assert eq.slack == slack
    # same pose, compared through the lugs' heights (free of angle conventions)
    ours_h = (scene.lug_points() @ rotation_matrix(eq.pose.heel, eq.pose.trim).T)[:, 2]
    assert_allclose(ours_h + eq.pose.lift_height, heights, atol=1e-7)
