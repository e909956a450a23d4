"""Small sling-lift planning problems: cranes on 2-leg slings and spreader bars."""

from __future__ import annotations

from liftplan.model.scene.objects import Body
from liftplan.planner.problem.definition import Candidate, CogEnvelope, PlanProblem
from liftplan.planner.problem.fleet import FleetCrane, SlingSpec, SpreaderSpec


def crane(name, swl, sling):
    return FleetCrane(name=name, EA=40000.0, rope_length=24.0, swl=swl, sling=sling)


def spreader_problem(bar_length=4.0):
    bar = SpreaderSpec(length=bar_length, top_length=5.0, weight=2.0)
    sling = SlingSpec(length=1.5, legs=2, EA=20000.0, spreader=bar)
    candidates = tuple(
        Candidate(f"S{x:+.0f}{y:+.0f}", (x, y, 3.0), bulkhead=f"x{x:+.0f}")
        for x in (-7.0, -3.0, 1.0, 3.0, 7.0)
        for y in (-4.0, 4.0)
    )
    fleet = tuple(crane(n, 300.0, sling) for n in ("FP", "FS", "AP", "AS"))
    return PlanProblem(
        body=Body(180.0, (0.0, 0.0, 1.3)),
        candidates=candidates,
        cranes=4,
        crane=None,
        fleet=fleet,
        heel_tolerance=2.0,
        trim_tolerance=2.0,
        lift_height=8.0,
        top=3,
        cog_envelope=CogEnvelope((0.2, 0.2, 0.1)),
    )
