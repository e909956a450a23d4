"""Read planning scene files (TOML, CONTRACT.md "Planning") into :class:`PlanProblem`.

The file's shape is checked by pydantic, its values by the dataclasses, with the scene
reader's one-line messages; ``[rules]`` (the design-load chain's settings) is read by
:mod:`liftplan.model.rules.table`. Coordinates (candidates, CG, outline, CG tolerance) are read in
the file's frame and converted to ``z-up``. Each key is declared with its documentation
(``Key``: the convention is in :mod:`liftplan.model.scene.file`), from which the file
reference's tables are generated.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Annotated, Literal

from pydantic import Field, Strict, ValidationError

from liftplan.model.errors import InvalidScene
from liftplan.model.frames import choi_to_zup
from liftplan.model.rules import RulesTable, rules_from_table
from liftplan.model.scene.file import (
    HullTable,
    Key,
    Num,
    Pair,
    Point,
    Table,
    Text,
    VesselTable,
    WaterTable,
    WindTable,
    load_scene,
    load_with,
    one_line,
    parse_toml,
    refuse_sequence,
    to_girder,
    to_hull,
    to_vessel,
    to_wind,
)
from liftplan.model.scene.objects import Body, Strength, Water
from liftplan.planner.problem.definition import Candidate, CogEnvelope, CraneSpec, PlanProblem
from liftplan.planner.problem.fleet import FleetCrane, SlingSpec, SpreaderSpec
from liftplan.planner.problem.hull_water import InWater
from liftplan.planner.problem.readings_accuracy import (
    DEFAULT_HOOK,
    DEFAULT_INCLINOMETER,
    DEFAULT_LOAD_CELL,
    ReadingsAccuracy,
)
from liftplan.planner.problem.report_info import ReportInfo

Count = Annotated[int, Strict(), Field(ge=1)]


class _Body(Table):
    weight: Num = Key(doc="total weight W", unit="t", values="number > 0", example="weight = 904.0")
    weight_basis: Literal["air", "water"] | None = Key(
        None,
        doc=(
            "what `weight` is: `air`, the body's weight in air, or `water`, its weight in water "
            "(less its buoyancy, flooded compartments included); the plan says it beside W in the "
            "console, the report's basis table and the JSON (`weight.basis`). The planner uses W as "
            "given either way; with `water` and the DAF taken from 0027/ND Table 5-1 (the table for "
            "lifts in air; no `[rules] daf`) the plan warns, on the console and page 1"
        ),
        absent='not stated: the plan says "not stated"',
        example='weight_basis = "water"',
    )
    cog: Point = Key(
        doc="nominal centre of gravity", unit="m", frame="body, file frame", example="cog = [35.86, 2.5, 6.0]"
    )
    weight_curve: list[Pair] | None = Key(
        None,
        doc=(
            "weight per unit length along the body's x, as in a scene file; needed by the strength "
            'objectives (`plan.objective = "bending"`, `"shear"`, `"strength"`)'
        ),
        unit="[m, t/m]",
        values="array of [x, w] pairs, x increasing, w >= 0",
        frame="body x (the same axis in both frames)",
        absent="none",
        example="weight_curve = [[0.0, 30.0], [146.0, 30.0]]",
    )


class _Strength(Table):
    bending_moment: list[Pair] | None = Key(
        None,
        doc="allowable absolute bending moment; needed by `bending` (and `strength` with a bending weight)",
        unit="[m, t m]",
        values="array of [x, M] pairs, x increasing, M > 0",
        frame="body x",
        example="bending_moment = [[0.0, 20000.0], [146.0, 20000.0]]",
    )
    shear_force: list[Pair] | None = Key(
        None,
        doc="allowable absolute shear force; needed by `shear` (and `strength` with a shear weight)",
        unit="[m, t]",
        values="array of [x, Q] pairs, x increasing, Q > 0",
        frame="body x",
        example="shear_force = [[0.0, 1500.0], [146.0, 1500.0]]",
    )


class _StrengthWeights(Table):
    bending: Num = Key(
        1.0,
        doc="weight of the worst |M| / allowable",
        unit="-",
        values="number >= 0",
        example="bending = 1.0",
    )
    shear: Num = Key(
        1.0, doc="weight of the worst |Q| / allowable", unit="-", values="number >= 0", example="shear = 0.5"
    )


class _Candidate(Table):
    name: Text = Key(
        doc="the candidate's name, unique; the plan's `lugs` name them", example='name = "BH3-S"'
    )
    at: Point = Key(
        doc="where the lug would be", unit="m", frame="body, file frame", example="at = [16.2, 6.0, 12.0]"
    )
    bulkhead: Text = Key(
        "", doc="a grouping label (the bulkhead or frame it sits on)", example='bulkhead = "BH3"'
    )
    capacity: Num | None = Key(
        None,
        doc=(
            "the lug's allowed design load; the plan checks the rules' lug design load (leg load x "
            "consequence factor, `docs/design-loads.md`) against it"
        ),
        unit="t",
        values="number > 0",
        absent="no lug check",
        example="capacity = 700.0",
    )


class _Tolerance(Table):
    heel: Num = Key(
        2.0, doc="heel from -heel to +heel", unit="deg", values="number >= 0", example="heel = 2.0"
    )
    trim: Num = Key(
        2.0, doc="trim from -trim to +trim", unit="deg", values="number >= 0", example="trim = 2.0"
    )


class _Plan(Table):
    cranes: Count | None = Key(
        None,
        doc="how many lugs and cranes to choose",
        unit="-",
        values="integer 3 to 64",
        absent="the number of `[[cranes]]` tables",
        example="cranes = 4",
    )
    # the choices of OBJECTIVES (tests/project/test_registries.py checks they agree; a type checker
    # needs them written out)
    objective: Literal["spread", "utilisation", "reserve", "bending", "shear", "strength"] | None = Key(
        None,
        doc=(
            "what the plan minimises over the box: `spread`, max - min tension (the papers'); "
            "`utilisation`, max - min of T_i / SWL_i; `reserve`, the largest T_i / SWL_i (the most "
            "load left before the first crane reaches its SWL); `bending`, the worst |M| / allowable "
            "of the hull girder (`strength.bending_moment`) over the states and along the body; "
            '`shear`, the same of |Q|; `strength`, `strength_weights` x both (README "Lift forces for '
            "the hull's strength\"; equal cranes or a fleet with charts, no slings; needs "
            "`body.weight_curve`)"
        ),
        absent="`spread` for equal cranes, `utilisation` when they differ",
        example='objective = "bending"',
    )
    strength_weights: _StrengthWeights | None = Key(
        None,
        doc=(
            "weights of the worst bending and shear ratios in the `strength` objective (w_M "
            'max|M|/M_allow + w_Q max|Q|/Q_allow); only with `objective = "strength"`'
        ),
        values="table { bending, shear }",
        absent='`{ bending = 1.0, shear = 1.0 }` with `objective = "strength"`',
        example="strength_weights = { bending = 1.0, shear = 0.5 }",
    )
    gap: Num = Key(
        0.0,
        doc=(
            "stop the search once the best plan is proved within this relative gap of the optimum "
            "(0.01 = 1 %); 0 proves the optimum (a local plan: its bound is worked towards the plan's "
            "value less this gap)"
        ),
        unit="-",
        values="number, 0 <= gap < 1",
        example="gap = 0.01",
    )
    time_limit: Num | None = Key(
        None,
        doc=(
            "stop the search after this long with the best plan found and its certified gap (a local "
            "plan: half for the swaps, half for its lower bound)"
        ),
        unit="s",
        values="number > 0",
        absent="none",
        example="time_limit = 60",
    )
    work_limit: Count | None = Key(
        None,
        doc=(
            "stop the search after this much work, counted not timed, so the same file gives the same "
            "plan on any machine: rows evaluated (exact search), swaps tried and cells searched "
            "(local search, half each), cutting-plane rounds (MIP); held-preload plans only (refused "
            "with slings, strength objectives and rope-length ranges); the plan says which limit "
            "stopped it"
        ),
        unit="-",
        values="whole number >= 1",
        absent="none",
        example="work_limit = 2000",
    )
    search: Literal["auto", "exact", "local", "mip"] = Key(
        "auto",
        doc=(
            "`exact`: every lug set bounded and pruned (the optimum proved, or the gap stated); "
            "`local`: one swap at a time from an even spread of the candidates and, with lugs on two "
            "lines in one plane, from lugs at both ends of each line (a local optimum, the plan says "
            "so; its lower bound is what holds for every set: the two-line bound, refined cell by "
            'cell for lugs at stations of one spacing, README "Along the lines, cell by cell"; with '
            "`time_limit` half the time goes to the search, half to the bound); `mip`: one "
            "mixed-integer program over candidates, cranes and scenarios solved by HiGHS, no lug set "
            "enumerated (the optimum proved, or the gap stated; body-fixed lugs, hook tolerances as "
            'cuts; slower than `exact` wherever both run, README "Many lifting points"); `auto`: '
            "exact up to 5 000 000 lug sets for at most 4 lugs and up to 200 000 for 5 or more, local "
            "beyond"
        ),
        example='search = "mip"',
    )
    tolerance: _Tolerance = Key(
        _Tolerance(),
        doc="the heel/trim box around the level attitude",
        example="tolerance = { heel = 2.0, trim = 2.0 }",
    )
    min_tension: Num = Key(
        0.0,
        doc="no rope may go below this anywhere in the box",
        unit="t",
        values="number >= 0",
        example="min_tension = 20.0",
    )
    hook_tolerance: Num = Key(
        0.0,
        doc=(
            "each hook may be off its planned height by up to this, independently: part of the worst "
            "case the plan is robust against (`worst_spread`, every limit, the design loads); 0: no "
            "hook error assumed, and the plan says so"
        ),
        unit="m",
        values="number >= 0",
        example="hook_tolerance = 0.02",
    )
    cog_tolerance: Point = Key(
        (0.0, 0.0, 0.0),
        doc="where the CG may really be around `body.cog`",
        unit="m",
        values="[dx, dy, dz] >= 0",
        frame="half-widths, file frame axes",
        example="cog_tolerance = [0.5, 0.2, 0.3]",
    )
    cog_envelope: Literal["box", "cross"] = Key(
        "box",
        doc="`box`: anywhere in the box of `cog_tolerance`; `cross`: along one axis at a time",
        example='cog_envelope = "cross"',
    )
    top: Count = Key(
        5, doc="how many lug sets the ranking lists", unit="-", values="integer >= 1", example="top = 10"
    )
    outline: list[Point] = Key(
        [],
        doc=(
            "the body's plan outline, drawn in the plan view (only x and y in plan count); each "
            "crane's slew centre must stand outside it by `crane_clearance`"
        ),
        unit="m",
        frame="body, file frame",
        example="outline = [[0, 6, 0], [74, 6, 0], [74, 6, 12]]",
    )
    crane_clearance: Num = Key(
        3.0,
        doc=(
            "least plan distance between two cranes' booms and hoist lines (a boom in plan runs from "
            "the crane's slew centre to its tip above the lug; the hoist line is the tip); sets and "
            "assignments whose booms cross or come nearer are ruled out of every search, each crane's "
            "slew centre must stand outside `outline` by it, and the plan carries a `crane_clearance` "
            "check per crane. The default is GL Noble Denton 0027/ND Rev 11, 16.2 (3 m, offshore; "
            "smaller may be accepted inshore). Crossing booms are ruled out whatever the value"
        ),
        unit="m",
        values="number >= 0",
        example="crane_clearance = 5.0",
    )
    breakout_scene: Text | None = Key(
        None,
        doc=(
            "a scene file (read as by `liftplan solve`; relative to this file) of the same body "
            "resting on the seabed, with `[hull]`, `[water]` and `[ground]` (its `breakout` model, "
            "its attitude and lift height at rest; its lugs and cranes are not used). Its breakout "
            "case (peak total hook load = submerged weight + breakout force, on a line through a body "
            "point; `liftplan lift` shows the same case in the load curve) is held by each crane of "
            "every ranked lug set at the level attitude with the plan's preload held; each crane's "
            "static input to the design-load chain becomes the larger of its worst in the box and its "
            "breakout tension (the plan says which governs), a check `breakout_hook_load` per crane "
            "(tension + rigging <= chart SWL) and `breakout_min_tension` are added, and the plan JSON "
            "gains `breakout`. With slings each crane's hook holds it (two cranes: the lever rule "
            "along the hook line; three or more: the held model on the hooks) and its legs carry "
            "it into the lug design loads. With the strength objectives (hoist control) it enters "
            "the strength plan's design loads and checks the same way. The scene's body weight and "
            'CG must equal `[body]`\'s. Not with `control = "force"`'
        ),
        values="string (a path)",
        absent="no breakout case",
        example='breakout_scene = "sunken_block_breakout.toml"',
    )
    start_lift_height: Num | None = Key(
        None,
        doc=(
            "with `[water]` and `[hull]`'s `box` or `mesh`: the lift height (world height of the body "
            "origin, `[water] level` the surface) where the lift starts, the body level and the hull "
            "partly submerged. There W + trapped water - B and its line of action (buoyancy from the "
            "hull cut by the water plane) set each rope's share with the plan's preload held; that "
            "state is one more of the plan's worst states: in its objective (the ranking is redone "
            "on it), its lowest tension, the design loads (the larger) and the checks "
            '(docs/planning.md "A lift that starts in water")'
        ),
        unit="m",
        frame="world height",
        absent="needed with [water]",
        example="start_lift_height = -2.0",
    )


class _Payout(Table):
    # rope_length = { min, max }; not one class with _Range: each is documented for its key
    min: Num = Key(
        doc="shortest payout the planner may choose", unit="m", values="number > 0", example="min = 25.0"
    )
    max: Num = Key(
        doc="longest payout the planner may choose", unit="m", values="number >= min", example="max = 55.0"
    )


class _Range(Table):
    # boom_height = { min, max }; its name is in pydantic's messages ("instance of _Range")
    min: Num = Key(doc="lowest H above the datum", unit="m", frame="world height", example="min = 30.0")
    max: Num = Key(doc="highest H above the datum", unit="m", frame="world height", example="max = 60.0")


class _Crane(Table):
    EA: Num | None = Key(
        None,
        doc="hoist rope axial stiffness",
        unit="t",
        values="number > 0",
        absent="`ropes.EA`",
        example="EA = 50000.0",
    )
    rope_length: Num | _Payout | None = Key(
        None,
        doc=(
            "unstretched rope length, boom tip to lug; needed unless every `[[cranes]]` gives one. A "
            "number is that length, fixed; a table is the payout range the planner chooses a length "
            "in (a longer rope is softer against twist, but needs a higher boom tip): the cranes of "
            "one class share one length, tried at 5 evenly spaced lengths then refined by two "
            'halvings (README "Rope lengths"); the plan\'s JSON adds `rope_lengths`'
        ),
        unit="m",
        values="number > 0, or table { min, max }",
        example="rope_length = { min = 25.0, max = 55.0 }",
    )
    swl: Num | None = Key(
        None,
        doc="safe working load; needed unless every `[[cranes]]` gives a `swl` or `load_chart`",
        unit="t",
        values="number > 0",
        example="swl = 400.0",
    )
    boom_height: _Range | None = Key(
        None,
        doc="range of the boom-tip height H the planner may choose",
        absent="no limit",
        example="boom_height = { min = 30.0, max = 60.0 }",
    )
    control: Literal["hoist", "force"] | None = Key(
        None,
        doc=(
            "how every lifting point is controlled: `hoist`, by its boom height (the held-preload "
            "model: a tilt comes from the hooks moving as a plane, the preload held); `force`, as a "
            "strand jack: it holds its force at every attitude and the body takes the attitude where "
            'the forces balance its weight (README "Lift forces for the hull\'s strength"); `force` '
            "only with the strength objectives, and every crane the same (in a fleet each jack's "
            "capacity is its table's `swl` or `load_chart`, through the rules' chain)"
        ),
        absent='`"hoist"`',
        example='control = "force"',
    )


class _Spreader(Table):
    length: Num = Key(
        doc="distance between the bar's end pins", unit="m", values="number > 0", example="length = 10.0"
    )
    top_length: Num = Key(
        doc="each top leg's length, hook to bar end (the sling's wire); more than half the bar length",
        unit="m",
        values="number > 0",
        example="top_length = 8.0",
    )
    weight: Num = Key(
        0.0,
        doc=(
            "the bar with its shackles: added to the hook load and to the crane's rigging weight in "
            "the rules' chain"
        ),
        unit="t",
        values="number >= 0",
        example="weight = 4.0",
    )


class _Sling(Table):
    legs: Count = Key(
        2,
        doc=(
            "number of legs: 2 (a pair: the sling hinges about it; with three cranes or more its hook "
            "is planned as a lift point hinged about the pair, and a spreader must span its pair, lug "
            "spacing = bar length to 1 mm), 3 or 4 (on one group or two adjacent groups of "
            "candidates, all legs meeting at one apex; with 4, the lugs concyclic to 1 mm)"
        ),
        unit="-",
        values="integer 2 to 4",
        example="legs = 4",
    )
    length: Num = Key(
        doc="each leg's length, pin to pin (with a spreader: each bottom leg, bar end to lug)",
        unit="m",
        values="number > 0",
        example="length = 9.0",
    )
    EA: Num | None = Key(
        None,
        doc="each leg's axial stiffness",
        unit="t",
        values="number > 0",
        absent="give `EA` or `diameter`",
        example="EA = 20000.0",
    )
    diameter: Num | None = Key(
        None,
        doc="wire-rope diameter: EA = 80 000 N/mm2 x 0.785 d^2 (Noble Denton 0027/ND 5.6.13)",
        unit="mm",
        values="number > 0",
        absent="give `EA` or `diameter`",
        example="diameter = 56.0",
    )
    spreader: _Spreader | None = Key(
        None,
        doc=(
            "a spreader bar under the hook (`legs = 2`, one bottom leg from each bar end down to a "
            "lug; with three cranes or more only on pairs it spans, lug spacing = `length` to 1 mm): "
            "two top legs from the hook to the bar's ends"
        ),
        absent="no bar",
        example="spreader = { length = 10.0, top_length = 8.0, weight = 4.0 }",
    )


class _Rigging(Table):
    min_sling_angle: Num = Key(
        60.0,
        doc=(
            "lowest sling-leg angle from the horizontal a planned sling may have (riggers' practice; "
            'README "Rigging")'
        ),
        unit="deg",
        values="number, 0 to 90",
        example="min_sling_angle = 60.0",
    )


class _FleetCrane(Table):
    name: Text = Key(
        doc="the crane's name; the plan's `cranes` name which crane takes each lug", example='name = "Big-P"'
    )
    position: Point | None = Key(
        None,
        doc="the crane's slew centre; only its plan coordinates count",
        unit="m",
        frame="world, file frame",
        absent="anywhere: no reach limit",
        example="position = [12.0, 30.0, 0.0]",
    )
    load_chart: list[tuple[Num, Num]] | None = Key(
        None,
        doc=(
            "radii increasing; SWL linear between points, the first point's SWL inside its radius, no "
            "reach past the last point; exactly one of `load_chart` and `swl` (here or `crane.swl`)"
        ),
        unit="m, t",
        values="array of [radius, SWL]",
        example="load_chart = [[15.0, 900.0], [25.0, 700.0], [35.0, 520.0]]",
    )
    swl: Num | None = Key(
        None,
        doc="a fixed SWL and no reach limit, instead of a chart",
        unit="t",
        values="number > 0",
        absent="`crane.swl`",
        example="swl = 800.0",
    )
    EA: Num | None = Key(
        None,
        doc="hoist rope axial stiffness",
        unit="t",
        values="number > 0",
        absent="`crane.EA`, then `ropes.EA`",
        example="EA = 70000.0",
    )
    rope_length: Num | _Payout | None = Key(
        None,
        doc=(
            "unstretched rope length, boom tip to lug; a table: the payout range the planner chooses "
            "in, as `crane.rope_length` (with a sling: the hoist rope's, tip to hook)"
        ),
        unit="m",
        values="number > 0, or table { min, max }",
        absent="`crane.rope_length`",
        example="rope_length = 40.0",
    )
    boom_height: _Range | None = Key(
        None,
        doc="this crane's range of H",
        absent="`crane.boom_height`",
        example="boom_height = { min = 30.0, max = 70.0 }",
    )
    sling: _Sling | None = Key(
        None,
        doc=(
            "a sling set on this crane's hook: the planner takes `legs` candidates for it (README "
            '"Sling lifts"): two cranes with 2-, 3- or 4-leg slings or spreader bars, or three cranes '
            "or more with one sling spec on every crane (`legs`, `length`, `spreader`): 3- or 4-leg "
            "hooks are body-fixed apexes, 2-leg and spreader hooks lift points hinged about their lug "
            "pair; every crane or none has a sling; `rope_length` and `EA` are then the hoist rope's, "
            "tip to hook"
        ),
        absent="a single rope to one lug",
        example="sling = { legs = 4, length = 9.0, diameter = 56.0 }",
    )
    vessel: VesselTable | None = Key(
        None,
        doc=(
            "a floating crane: its vessel's particulars, the keys of a scene file's `cranes[].vessel` "
            "(the boom tip above the crane's lug moves with the vessel under the hook load: the planner "
            "puts the vessel in series with the rope); one rope of fixed length, no sling"
        ),
        absent="a crane on land or a jack-up: the tip stays where it is",
        example=(
            "vessel = { displacement = 9000.0, waterplane_area = 2800.0, gm_t = 6.0, gm_l = 180.0, "
            "flotation = [20.0, -45.0], heading = 90.0 }"
        ),
    )
    hook_tolerance: Num | None = Key(
        None,
        doc="this hook's height tolerance, overriding the plan's",
        unit="m",
        values="number >= 0",
        absent="`plan.hook_tolerance`",
        example="hook_tolerance = 0.05",
    )
    control: Literal["hoist", "force"] | None = Key(
        None,
        doc="this lifting point's control, as `crane.control` (every crane the same)",
        absent="`crane.control`",
        example='control = "force"',
    )


class _Ropes(Table):
    EA: Num | None = Key(
        None,
        doc="rope stiffness when neither `[crane]` nor a `[[cranes]]` table gives one",
        unit="t",
        values="number > 0",
        example="EA = 50000.0",
    )


class _Report(Table):
    project: Text = Key(
        "",
        doc="project name; also in every page's running header",
        example='project = "Salvage of MT Example"',
    )
    client: Text = Key("", doc="who the plan is for", example='client = "Harbour Authority"')
    document: Text = Key("", doc="document number", example='document = "LP-0042"')
    revision: Text = Key("", doc="revision of the document", example='revision = "B"')
    prepared_by: Text = Key("", doc="who prepared the plan", example='prepared_by = "A. Engineer"')
    checked_by: Text = Key("", doc="who checked it", example='checked_by = "B. Checker"')
    approved_by: Text = Key("", doc="who approved it", example='approved_by = "C. Approver"')
    date: Text = Key(
        "",
        doc="issue date, printed as given",
        absent="the day the report is written",
        example='date = "2026-03-01"',
    )


class _Attitude(Table):
    lift_height: Num = Key(
        0.0,
        doc="height of the body-frame origin above the datum at the level attitude",
        unit="m",
        frame="world height",
        example="lift_height = 1.0",
    )
    yaw: Num = Key(0.0, doc="the body's heading, > 0 bow to port", unit="deg", example="yaw = 0.0")


class _Readings(Table):
    load_cell_accuracy: Num = Key(
        DEFAULT_LOAD_CELL,
        doc=(
            "one standard deviation of each crane's load-cell tension (`liftplan watch` weighs "
            "the readings by it)"
        ),
        unit="t",
        values="number > 0",
        example="load_cell_accuracy = 1.0",
    )
    inclinometer_accuracy: Num = Key(
        DEFAULT_INCLINOMETER,
        doc="one standard deviation of the inclinometer's heel and trim",
        unit="deg",
        values="number > 0",
        example="inclinometer_accuracy = 0.05",
    )
    hook_accuracy: Num = Key(
        DEFAULT_HOOK,
        doc="one standard deviation of a measured hook (boom-tip) height, `hook:NAME` columns",
        unit="m",
        values="number > 0",
        example="hook_accuracy = 0.01",
    )


class _PlanFile(Table):
    name: Text = Key(
        "", doc="a label for the plan, shown in outputs and the report", example='name = "1500 GT tanker"'
    )
    frame: Literal["z-up", "choi"] = Key(
        "z-up",
        doc="the axes every coordinate of the file is read in; reports use it too",
        example='frame = "choi"',
    )
    body: _Body = Key(doc="the lifted body", example="[body]")
    candidates: list[_Candidate] = Key(
        doc="strong points the planner may put a lug on (at least as many as cranes)",
        example="[[candidates]]",
    )
    plan: _Plan = Key(doc="what to plan and the tolerances", example="[plan]")
    crane: _Crane = Key(
        _Crane(),
        doc="defaults for every planned crane (the whole crane when there are no `[[cranes]]`)",
        example="[crane]",
    )
    cranes: list[_FleetCrane] = Key(
        [], doc="the fleet: one table per crane, each placed on one lug by the planner", example="[[cranes]]"
    )
    ropes: _Ropes = Key(_Ropes(), doc="rope defaults", example="[ropes]")
    attitude: _Attitude = Key(_Attitude(), doc="where the level body sits", example="[attitude]")
    rules: RulesTable | None = Key(
        None, doc="the rules' settings for this lift", absent="every default below", example="[rules]"
    )
    rigging: _Rigging = Key(_Rigging(), doc="sling limits (sling lifts)", example="[rigging]")
    wind: WindTable | None = Key(
        None,
        doc=(
            "wind on the body and on floating cranes' booms, the keys of a scene file's `[wind]` "
            "without `direction`: the plan takes it from any direction (the body's couple widens the "
            "CG envelope in plan, a boom's moves its vessel's tip like a hook-height error)"
        ),
        absent="no wind",
        example="[wind]",
    )
    report: _Report = Key(_Report(), doc="the report's title block", example="[report]")
    readings: _Readings = Key(
        _Readings(), doc="the live readings' accuracies (`liftplan watch`)", example="[readings]"
    )
    strength: _Strength | None = Key(
        None,
        doc=(
            "allowable envelopes of the hull girder, as in a scene file; the strength objectives "
            "divide by them"
        ),
        absent="none",
        example="[strength]",
    )
    hull: HullTable | None = Key(
        None,
        doc=(
            "the scene file's `[hull]`: `EI` (and `GJ`) make the plan evaluate its ranked sets again "
            "on the flexible hull at their worst states, the flexible numbers governing a set where "
            'they change a tension by more than 1 % (docs/planning.md "The flexible hull in a '
            'plan"); `box` or `mesh` (with its flooding and compartments) is the hull in `[water]`'
        ),
        absent="a rigid hull, clear of the water",
        example="[hull]",
    )
    water: WaterTable | None = Key(
        None,
        doc=(
            "the scene file's `[water]`: with `[hull]`'s geometry and `plan.start_lift_height`, the "
            "lift starts in water (one more worst state)"
        ),
        absent="no state in water",
        example="[water]",
    )


def load_problem(path: str | os.PathLike[str]) -> PlanProblem:
    """Read and validate a planning scene file.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    PlanProblem
        In the ``z-up`` frame.

    Raises
    ------
    InvalidScene
        One line naming the file, the key, the value and what is expected.
    """
    return load_with(path, lambda text: loads_problem(text, base=Path(path).parent))


def loads_problem(text: str, base: str | os.PathLike[str] | None = None) -> PlanProblem:
    """Validate a planning scene given as TOML text; see :func:`load_problem`.

    ``base`` is the folder a relative ``plan.breakout_scene`` is read from (default: the
    working directory).
    """
    return problem_from_dict(parse_toml(text), base=base)


#: Scene tables a planning file refuses, each with why and what to do instead (docs/planning.md
#: "What the planner does not plan").
NOT_PLANNED = {
    "ground": (
        "the planner plans the lift clear of the seabed; expected [ground] in the scene that "
        "plan.breakout_scene names (its breakout case is the lift off the seabed)"
    ),
}


def problem_from_dict(raw, base=None):
    """Validate a planning scene given as the dict its TOML file parses to (``base``: see
    :func:`loads_problem`)."""
    refuse_sequence(raw, "a planning file")
    if "candidates" not in raw and "lugs" in raw:
        raise InvalidScene(
            "[[lugs]]: a scene with fixed lugs; expected [[candidates]] and [plan] for "
            "planning (use `liftplan solve` for a fixed scene)"
        )
    for table, reason in NOT_PLANNED.items():
        if table in raw:
            raise InvalidScene(f"[{table}]: not in a planning file; {reason}")
    try:
        data = _PlanFile.model_validate(raw)
    except ValidationError as err:
        raise InvalidScene(one_line(err, _PlanFile)) from None
    return _to_problem(data, Path(base) if base is not None else Path.cwd())


def _breakout_scene(path, base):
    """The scene file ``plan.breakout_scene`` names (read by the scene reader), or None."""
    if path is None:
        return None
    try:
        return load_scene(base / path)
    except InvalidScene as err:
        raise InvalidScene(f"plan.breakout_scene = {path!r}: {err}") from None


def _default_spec(data):
    """The [crane] defaults as a CraneSpec, or None when the fleet lists every crane."""
    crane = data.crane
    stiffness = crane.EA if crane.EA is not None else data.ropes.EA
    if data.cranes and (crane.rope_length is None or crane.swl is None):
        return None
    if stiffness is None:
        raise InvalidScene("crane.EA: missing, expected the rope stiffness EA in t (in [crane] or [ropes])")
    for key in ("rope_length", "swl"):
        if getattr(crane, key) is None:
            raise InvalidScene(f"crane.{key}: missing, expected a number (or one [[cranes]] table per crane)")
    boom = crane.boom_height
    length, length_range = _length(crane.rope_length)
    return CraneSpec(
        EA=stiffness,
        rope_length=length,
        swl=crane.swl,
        boom_min=boom.min if boom else float("-inf"),
        boom_max=boom.max if boom else float("inf"),
        rope_length_range=length_range,
    )


def _length(value):
    """A rope_length number, or a { min, max } range: (length, range or None); a range's
    length is its max until the planner chooses (:mod:`liftplan.planner.plans.lengths`)."""
    if isinstance(value, _Payout):
        return value.max, (value.min, value.max)
    return value, None


def _fleet(data, to_zup):
    """[[cranes]] tables with the [crane] / [ropes] defaults filled in."""
    defaults = data.crane
    fleet = []
    for entry in data.cranes:

        def pick(key, entry=entry):
            value = getattr(entry, key)
            if value is None:
                value = getattr(defaults, key)
            if value is None and key == "EA":
                value = data.ropes.EA
            if value is None:
                raise InvalidScene(
                    f"cranes[{entry.name}].{key}: missing, expected a number (here or in [crane])"
                )
            return value

        boom = entry.boom_height or defaults.boom_height
        chart = entry.load_chart
        swl = entry.swl
        if chart is None and swl is None:
            swl = defaults.swl
        if chart is not None and swl is not None:
            raise InvalidScene(f"cranes[{entry.name}]: both load_chart and swl given; expected one of them")
        if chart is None and swl is None:
            raise InvalidScene(
                f"cranes[{entry.name}]: no load_chart or swl; expected one (here or swl in [crane])"
            )
        length, length_range = _length(pick("rope_length"))
        fleet.append(
            FleetCrane(
                name=entry.name,
                EA=pick("EA"),
                rope_length=length,
                rope_length_range=length_range,
                position=None if entry.position is None else to_zup(entry.position)[:2],
                load_chart=tuple(chart or ()),
                swl=swl,
                boom_min=boom.min if boom else float("-inf"),
                boom_max=boom.max if boom else float("inf"),
                hook_tolerance=entry.hook_tolerance,
                vessel=to_vessel(entry.vessel, data.frame),
                sling=None
                if entry.sling is None
                else SlingSpec(
                    length=entry.sling.length,
                    legs=entry.sling.legs,
                    EA=entry.sling.EA,
                    diameter=entry.sling.diameter,
                    spreader=None
                    if entry.sling.spreader is None
                    else SpreaderSpec(
                        length=entry.sling.spreader.length,
                        top_length=entry.sling.spreader.top_length,
                        weight=entry.sling.spreader.weight,
                    ),
                ),
            )
        )
    return tuple(fleet)


def _to_problem(data, base):
    choi = data.frame == "choi"
    to_zup = choi_to_zup if choi else tuple
    widths = data.plan.cog_tolerance
    # half-widths are magnitudes: the frame change only permutes the axes
    widths = (widths[0], widths[2], widths[1]) if choi else widths
    fleet = _fleet(data, to_zup)
    cranes = data.plan.cranes
    if cranes is None:
        if not fleet:
            raise InvalidScene(
                "plan.cranes: missing, expected how many cranes (3 to 64) or one [[cranes]] table per crane"
            )
        cranes = len(fleet)
    return PlanProblem(
        body=Body(weight=data.body.weight, cog=to_zup(data.body.cog), weight_curve=data.body.weight_curve),
        weight_basis=data.body.weight_basis,
        candidates=tuple(
            Candidate(name=c.name, at=to_zup(c.at), bulkhead=c.bulkhead, capacity=c.capacity)
            for c in data.candidates
        ),
        cranes=cranes,
        crane=_default_spec(data),
        fleet=fleet,
        objective=data.plan.objective,
        gap=data.plan.gap,
        time_limit=data.plan.time_limit,
        work_limit=data.plan.work_limit,
        crane_clearance=data.plan.crane_clearance,
        search=data.plan.search,
        heel_tolerance=data.plan.tolerance.heel,
        trim_tolerance=data.plan.tolerance.trim,
        min_tension=data.plan.min_tension,
        lift_height=data.attitude.lift_height,
        yaw=data.attitude.yaw,
        hook_tolerance=data.plan.hook_tolerance,
        cog_envelope=CogEnvelope(half_widths=widths, shape=data.plan.cog_envelope),
        top=data.plan.top,
        outline=tuple(to_zup(p)[:2] for p in data.plan.outline),
        name=data.name,
        frame=data.frame,
        rules=rules_from_table(data.rules),
        min_sling_angle=data.rigging.min_sling_angle,
        report=ReportInfo(**data.report.model_dump()),
        readings=ReadingsAccuracy(
            load_cell=data.readings.load_cell_accuracy,
            inclinometer=data.readings.inclinometer_accuracy,
            hook=data.readings.hook_accuracy,
        ),
        strength=Strength(**data.strength.model_dump()) if data.strength is not None else None,
        strength_weights=(
            None
            if data.plan.strength_weights is None
            else (data.plan.strength_weights.bending, data.plan.strength_weights.shear)
        ),
        controls=_controls(data, cranes),
        breakout_scene=_breakout_scene(data.plan.breakout_scene, base),
        wind=to_wind(data.wind, data.frame, plan=True),
        hull_stiffness=to_girder(data.hull),
        in_water=_in_water(data, base),
    )


def _in_water(data, base):
    """``[water]``, ``[hull]``'s geometry and ``plan.start_lift_height`` as an :class:`InWater`
    (None without ``[water]``); each missing part refused in one line."""
    start = data.plan.start_lift_height
    if data.water is None:
        if start is not None:
            raise InvalidScene(
                f"plan.start_lift_height = {start!r}: given without [water]; expected [water] and "
                "[hull] (box or mesh) for a lift that starts in water"
            )
        if data.hull is not None and (data.hull.box is not None or data.hull.mesh is not None):
            raise InvalidScene(
                "hull: box or mesh given without [water]; expected [water] (and "
                "plan.start_lift_height) for a lift that starts in water, or only EI / GJ"
            )
        return None
    if data.hull is None or (data.hull.box is None and data.hull.mesh is None):
        raise InvalidScene(
            "water: given without the hull's geometry; expected [hull] box = {min, max} or mesh = "
            '"file.stl" (the buoyancy of the hull in water)'
        )
    if start is None:
        raise InvalidScene(
            "plan.start_lift_height: missing; expected the lift height (m) where the lift starts "
            "with the hull partly submerged in [water]"
        )
    return InWater(
        hull=to_hull(data, base),
        water=Water(**data.water.model_dump()),
        start_lift_height=start,
        hull_lines=_hull_lines(data.hull, base),
    )


def _hull_lines(spec, base):
    """``[hull]``'s geometry as TOML lines (the file's frame; a mesh by its absolute path), and
    its compartments as ``[[hull.compartments]]`` tables (without their openings: the plan's
    held state counts their water full)."""

    def vec(values):
        return "[" + ", ".join(repr(float(v)) for v in values) + "]"

    def box(b):
        return f"{{ min = {vec(b.min)}, max = {vec(b.max)} }}"

    lines = [f"box = {box(spec.box)}"] if spec.box is not None else []
    if spec.mesh is not None:
        lines.append(f"mesh = {json.dumps(str((Path(base) / spec.mesh).resolve()))}")
    lines.append(f"flooding = {json.dumps(spec.flooding)}")
    for key in ("steel_density", "weight_in_water"):
        if getattr(spec, key) is not None:
            lines.append(f"{key} = {float(getattr(spec, key))!r}")
    for c in spec.compartments:
        lines += [
            "",
            "[[hull.compartments]]",
            f"name = {json.dumps(c.name)}",
            f"box = {box(c.box)}",
            f"contents = {json.dumps(c.contents)}",
        ]
    return tuple(lines)


def _controls(data, count):
    """Each crane's control (``[[cranes]] control``, else ``[crane] control``, else hoist)."""
    default = data.crane.control or "hoist"
    if data.cranes:
        return tuple(c.control or default for c in data.cranes)
    return (default,) * count
