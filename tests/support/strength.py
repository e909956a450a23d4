"""A 60 m pontoon lifted at points chosen among stations on both sides: the hull girder's
planning problem (small enough for a brute force), as a planning file's text."""

from liftplan.planner.problem.file import loads_problem

SMALL = """
name = "60 m pontoon"
[body]
weight = 1265.0
cog = [{cog_x}, 0.0, 3.0]
weight_curve = [[0.0, 10.0], [15.0, 30.0], [40.0, 20.0], [60.0, 14.0]]
[strength]
bending_moment = [[0.0, 1500.0], [30.0, 4000.0], [60.0, 1500.0]]
shear_force = [[0.0, 400.0], [60.0, 400.0]]
[plan]
cranes = {cranes}
objective = "{objective}"
tolerance = {{ heel = 2.0, trim = 3.0 }}
cog_tolerance = [0.1, 0.05, 0.1]
min_tension = 20.0
[crane]
control = "{control}"
swl = 900.0
EA = 60000.0
rope_length = 25.0
{candidates}
"""


def cog_x():
    from liftplan.model.scene.objects import curve_totals

    area, first = curve_totals([0, 15, 40, 60], [10, 30, 20, 14])
    return first / area


REPORT = """
[report]
project = "Pontoon salvage"
document = "PS-01-LP"
revision = "A"
date = "2026-05-01"
"""


def small_text(control="force", cranes=5, bending="[[0.0, 1500.0], [30.0, 4000.0], [60.0, 1500.0]]"):
    rows = []
    for k, x in enumerate((4, 16, 28, 40, 52)):
        for side, y in (("P", 5.0), ("S", -5.0)):
            rows.append(f'[[candidates]]\nname = "S{k}{side}"\nat = [{x}, {y}, 6.0]\nbulkhead = "B{k}"\n')
    text = SMALL.format(
        cog_x=f"{cog_x():.6f}",
        cranes=cranes,
        objective="bending",
        control=control,
        candidates="\n".join(rows),
    )
    return text.replace("[[0.0, 1500.0], [30.0, 4000.0], [60.0, 1500.0]]", bending) + REPORT


def small_problem(  # the pontoon's planning problem
    control="force",
    objective="bending",
    cranes=5,
    stations=(4, 16, 28, 40, 52),
    plan_extra="",
    drop_curve=False,
    drop_shear=False,
):
    rows = []
    for k, x in enumerate(stations):
        for side, y in (("P", 5.0), ("S", -5.0)):
            rows.append(f'[[candidates]]\nname = "S{k}{side}"\nat = [{x}, {y}, 6.0]\n')
    text = SMALL.format(
        cog_x=f"{cog_x():.6f}",
        cranes=cranes,
        objective=objective,
        control=control,
        candidates="\n".join(rows),
    )
    text = text.replace("min_tension = 20.0", "min_tension = 20.0\n" + plan_extra)
    if drop_curve:
        text = text.replace("weight_curve = [[0.0, 10.0], [15.0, 30.0], [40.0, 20.0], [60.0, 14.0]]", "")
        text = (
            text.replace("[strength]", "[plan_strength_unused]").split("[plan_strength_unused]")[0]
            + text.split("shear_force = [[0.0, 400.0], [60.0, 400.0]]")[1]
        )
    if drop_shear:
        text = text.replace("shear_force = [[0.0, 400.0], [60.0, 400.0]]", "")
    return loads_problem(text)
