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
swl = {swl}
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
    specs=None,
):
    """The pontoon's planning file: ``cranes`` equal cranes on 2-leg slings of 10 m (legs' EA
    ``leg_ea`` t), hoist ropes of ``rope`` m at 2400 t/m, candidates 5 m either side of the
    centreline at ``stations`` (x, m), 6 m above the keel. ``specs``: each crane's (SWL t,
    rope stiffness t/m) instead of 1500 t and 2400 t/m (a fleet of unequal cranes)."""
    specs = specs or [(1500.0, 2400.0)] * cranes
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
            CRANE.format(k=k + 1, leg_ea=leg_ea, rope=rope, rope_ea=stiff * rope, swl=swl)
            for k, (swl, stiff) in enumerate(specs)
        ),
        candidates="\n".join(rows),
    )


def sling_problem(**options):
    """:func:`sling_text` as a PlanProblem."""
    return loads_problem(sling_text(**options))


#: Nine lugs for 3-leg slings: pairs off the centreline at x = 4, 24, 44 m and single lugs at
#: x = 14, 34, 54 m (groups by x, so a sling takes a pair and the next single lug)
TRIPOD_LUGS = (
    ("A0", 4, 6),
    ("B0", 4, -4),
    ("C1", 14, -2),
    ("A2", 24, 4),
    ("B2", 24, -6),
    ("C3", 34, 2),
    ("A4", 44, 6),
    ("B4", 44, -4),
    ("C5", 54, -2),
)


def tripod_text(objective="bending"):
    """The pontoon on three cranes with 3-leg slings of 10 m (legs of EA 1e6 t) over
    :data:`TRIPOD_LUGS`, 6 m above the keel, sling angles down to 30 deg."""
    text = sling_text(objective=objective, cranes=3, leg_ea=1e6, stations=())
    text = text.replace("legs = 2", "legs = 3").replace("min_sling_angle = 45.0", "min_sling_angle = 30.0")
    return text + "\n".join(
        f'[[candidates]]\nname = "{n}"\nat = [{x}, {y}, 6.0]\n' for n, x, y in TRIPOD_LUGS
    )
