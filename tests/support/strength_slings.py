"""The 60 m pontoon of support/strength.py on cranes with 2-leg slings: its planning file's text
(the strength objectives with slings, tests/planner/test_strength_slings.py)."""

from liftplan.planner.problem.file import loads_problem
from support.strength import SMALL, cog_x

#: the pontoon's body and allowables, as support/strength.py writes them
BODY = SMALL[SMALL.index("[body]") : SMALL.index("[plan]")]

TEXT = """
name = "60 m pontoon on slings"
{body}
[plan]
cranes = {cranes}
objective = "{objective}"
tolerance = {{ heel = {tilt}, trim = {tilt} }}
cog_tolerance = [0.1, 0.0, 0.0]
min_tension = 20.0
hook_tolerance = {hook}
[rigging]
min_sling_angle = 45.0
{cranes_tables}
{candidates}
[report]
project = "Pontoon salvage"
document = "PS-02-LP"
revision = "A"
date = "2026-05-01"
"""

CRANE = """[[cranes]]
name = "C{k}"
swl = 1500.0
EA = {rope_ea}
rope_length = {rope}
sling = {{ legs = 2, length = 10.0, EA = {leg_ea} }}
"""


def sling_text(
    objective="strength",
    cranes=4,
    tilt=1.0,
    hook=0.0,
    leg_ea=20000.0,
    rope=25.0,
    stations=(4, 16, 28, 40, 52),
):
    """The pontoon's planning file: ``cranes`` equal cranes on 2-leg slings of 10 m (legs' EA
    ``leg_ea`` t), hoist ropes of ``rope`` m at 2400 t/m, candidates 5 m either side of the
    centreline at ``stations`` (x, m), 6 m above the keel."""
    rows = []
    for k, x in enumerate(stations):
        for side, y in (("P", 5.0), ("S", -5.0)):
            rows.append(f'[[candidates]]\nname = "S{k}{side}"\nat = [{x}, {y}, 6.0]\n')
    return TEXT.format(
        body=BODY.format(cog_x=f"{cog_x():.6f}"),
        cranes=cranes,
        objective=objective,
        tilt=tilt,
        hook=hook,
        cranes_tables="\n".join(
            CRANE.format(k=k + 1, leg_ea=leg_ea, rope=rope, rope_ea=2400.0 * rope) for k in range(cranes)
        ),
        candidates="\n".join(rows),
    )


def sling_problem(**options):
    """:func:`sling_text` as a PlanProblem."""
    return loads_problem(sling_text(**options))
