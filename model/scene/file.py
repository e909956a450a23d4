"""Read scene files (TOML, as fixed in CONTRACT.md) into :class:`~liftplan.model.scene.objects.Scene`.

The file's shape (tables, keys, types) is checked by pydantic: it reports unknown keys,
missing keys and wrong types with their location, which a hand-made parser would have to
re-implement. Values (finite, positive, names, statics) are checked by the scene's own
dataclasses, so a scene built in Python obeys the same rules. Every failure is one
:class:`~liftplan.model.errors.InvalidScene` line naming the key, the value and what is
expected; nothing is returned half-read.

Every key of the file schemas (here, in :mod:`liftplan.planner.problem.file`,
:mod:`liftplan.planner.batch.study` and :mod:`liftplan.model.rules.table`) is declared with
:func:`Key`, which carries its documentation: the key tables of ``docs/scene-files.md`` are
generated from it (``python docs/_hooks/file_reference.py --write``). The convention:

``doc``
    What the key means, in Markdown (a sentence fragment, like a table cell).
``unit``
    The unit of the key's numbers: ``m``, ``mm``, ``t``, ``t/m3``, ``deg``, ``kPa``, ``h``,
    ``s``...; a pair's as ``[m, t/m]``; ``-`` for a number without unit (a factor, a count).
    Given for every key whose value holds a number (the generator refuses one without), and
    for no other key.
``values``
    The type column when the annotation alone does not say it: a range (``number > 0``),
    the names of a pair's values. Absent: read from the annotation (``number``, ``string``,
    ``table``...); the choices of a ``Literal`` are always listed from the annotation.
``frame``
    How a coordinate is read (``body, file frame``, ``world height``...).
``absent``
    What leaving the key out means, when its default alone does not say.
``example``
    One line of TOML setting the key.

Descriptions only: :func:`Key` hands the default to pydantic's ``Field`` unchanged, and
nothing reads the rest when a file is read.
"""

from __future__ import annotations

import os
import stat
import tomllib
import types
import typing
from pathlib import Path
from typing import Annotated, Any, Literal, Union

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, Strict, ValidationError
from pydantic_core import PydanticUndefined

from liftplan.model.errors import InvalidScene
from liftplan.model.frames import choi_to_zup
from liftplan.model.scene.hull import Compartment, Hull
from liftplan.model.scene.objects import (
    DISCHARGE,
    HULL_MODELS,
    MODELS,
    Analysis,
    Attitude,
    Body,
    Breakout,
    Crane,
    GirderStiffness,
    Ground,
    Lug,
    Opening,
    Redundant,
    Scene,
    Strength,
    Water,
)
from liftplan.model.scene.rigging_gear import Leg, RiggingLimits, Sling, Spreader
from liftplan.model.scene.tide import Tide
from liftplan.model.scene.vessel import Vessel
from liftplan.model.scene.wind import AIR_DENSITY, Wind, WindArea

# Strict scalars: a TOML string is never silently read as a number (ints still pass as
# floats); arrays may still be read as tuples.
Num = Annotated[float, Strict()]
Text = Annotated[str, Strict()]
Point = tuple[Num, Num, Num]


class Table(BaseModel):
    # Non-finite numbers pass here and are refused by the dataclasses, which say which
    # key held them.
    model_config = ConfigDict(extra="forbid", frozen=True)


def Key(
    default: Any = PydanticUndefined,
    *,
    doc: str,
    unit: str | None = None,
    values: str | None = None,
    frame: str | None = None,
    absent: str | None = None,
    example: str | None = None,
) -> Any:
    """A key of a file schema with its documentation (the module docstring's convention).

    Parameters
    ----------
    default : optional
        The value used when the key is absent; none: the key is required.
    doc : str
        What the key means (Markdown).
    unit : str, optional
        Unit of its numbers (``-``: a number without unit); only for a key holding numbers.
    values, frame, absent, example : str, optional
        The type column's text, how a coordinate is read, what absent means, a TOML line.

    Returns
    -------
    pydantic.fields.FieldInfo
        ``Field(default, description=doc)`` with the rest in ``json_schema_extra``.
    """
    notes = {"unit": unit, "values": values, "frame": frame, "absent": absent, "example": example}
    extra: dict[str, Any] = {name: text for name, text in notes.items() if text is not None}
    return Field(default, description=doc, json_schema_extra=extra)


Pair = tuple[Num, Num]


class _Body(Table):
    weight: Num = Key(
        doc="total weight W (in air; in water when the scene has no `[hull]`, give the weight in water)",
        unit="t",
        values="number > 0",
        example="weight = 904.0",
    )
    cog: Point = Key(
        doc="centre of gravity", unit="m", frame="body, file frame", example="cog = [35.86, 2.5, 6.0]"
    )
    weight_curve: list[Pair] | None = Key(
        None,
        doc=(
            "weight per unit length along the body's x, linear between points, zero outside; its "
            "integral must be `weight` within 0.5 % and its centroid the CG's x within 0.05 m (the "
            "rest is spread linearly over the curve so the curves close); `solve` then reports shear "
            'force and bending moment (see "Hull girder" below)'
        ),
        unit="[m, t/m]",
        values="array of [x, w] pairs, x increasing, w >= 0",
        frame="body x (the same axis in both frames)",
        absent="no hull-girder strength",
        example="weight_curve = [[0.0, 6.0], [40.0, 14.0], [82.0, 4.0]]",
    )


class _Lug(Table):
    name: Text = Key(
        doc="the lug's name, unique; cranes, results and JSON keys refer to it", example='name = "T1"'
    )
    at: Point = Key(
        doc="where the lug is", unit="m", frame="body, file frame", example="at = [16.2, 6.0, 12.0]"
    )


class _Ropes(Table):
    EA: Num | None = Key(
        None,
        doc="rope axial stiffness (modulus x metallic area) for cranes that give none",
        unit="t",
        values="number > 0",
        example="EA = 50000.0",
    )


class _Leg(Table):
    lug: Text = Key(doc="the lug the leg is shackled to", example='lug = "L1"')
    length: Num = Key(
        doc="unstretched leg length, pin to pin", unit="m", values="number > 0", example="length = 18.0"
    )
    EA: Num | None = Key(
        None,
        doc="leg stiffness; exactly one of `EA` and `diameter`",
        unit="t",
        values="number > 0",
        example="EA = 20000.0",
    )
    diameter: Num | None = Key(
        None,
        doc="wire-rope diameter; EA = 80 000 N/mm2 x 0.785 d^2 (Noble Denton 0027/ND 5.6.13)",
        unit="mm",
        values="number > 0",
        example="diameter = 76.0",
    )
    end: Literal[1, 2] | None = Key(
        None,
        doc=(
            "with a spreader: the bar end the leg hangs from (two legs without `end`: ends 1 and 2 in order)"
        ),
        example="end = 1",
    )


class _TopLeg(Table):
    length: Num = Key(
        doc="unstretched top-leg length", unit="m", values="number > 0", example="length = 15.0"
    )
    EA: Num | None = Key(
        None,
        doc="top-leg stiffness; exactly one of `EA` and `diameter`",
        unit="t",
        values="number > 0",
        example="EA = 30000.0",
    )
    diameter: Num | None = Key(
        None,
        doc="wire-rope diameter, as for the legs",
        unit="mm",
        values="number > 0",
        example="diameter = 90.0",
    )


class _Spreader(Table):
    length: Num = Key(
        doc="distance between the bar's end pins", unit="m", values="number > 0", example="length = 20.0"
    )
    top: list[_TopLeg] = Key(
        doc="hook to end 1 and hook to end 2 (no `lug`)",
        values="array of 2 tables",
        example="top = [{ length = 15.0, EA = 30000.0 }, { length = 15.0, EA = 30000.0 }]",
    )
    weight: Num = Key(
        0.0,
        doc="the bar's weight with its shackles, half at each end",
        unit="t",
        values="number >= 0",
        example="weight = 6.5",
    )
    EA: Num | None = Key(
        None,
        doc="the bar's axial stiffness",
        unit="t",
        values="number > 0",
        absent="1.0e6, a stiff strut",
        example="EA = 800000.0",
    )


class _Sling(Table):
    legs: list[_Leg] = Key(
        doc="2 to 4 legs, hook (or spreader end) to lug, each lug once", example="[[cranes.sling.legs]]"
    )
    spreader: _Spreader | None = Key(
        None,
        doc="a spreader bar between the hook's two top legs and the sling legs",
        example="[cranes.sling.spreader]",
    )
    equalised: Annotated[bool, Strict()] = Key(
        False,
        doc=(
            "`true`: the two legs are one continuous rope over a sheave at the hook (or an "
            "equaliser): both carry the same tension whatever the hook height, and their lengths add "
            "up to the rope's (the split follows the equilibrium, so the pair carries no twist); two "
            "legs of one EA, no spreader"
        ),
        example="equalised = true",
    )


class _VesselBox(Table):
    """A crane vessel's hull as a box, in her own axes (not the body's: :class:`_Box`)."""

    min: Point = Key(
        doc="one corner (min < max on every axis)",
        unit="m",
        frame="the vessel's own axes, file frame",
        example="min = [-50.0, -15.0, 0.0]",
    )
    max: Point = Key(
        doc="the opposite corner",
        unit="m",
        frame="the vessel's own axes, file frame",
        example="max = [50.0, 15.0, 8.0]",
    )


class VesselTable(Table):
    mesh: Text | None = Key(
        None,
        doc=(
            "the vessel's hull as a closed, outward-oriented triangle mesh (STL, path relative to the "
            "scene file), in her own axes (x forward, y to port, z up in `z-up`; x forward, y up, z to "
            "starboard in `choi`): her heave, heel and trim under the hook loads from the clipped-mesh "
            "hydrostatics at any angle, solved with the body (the `elastic` model, in air); with it give "
            "`displacement`, `cog` and `origin`, and no waterplane_area, gm_t, gm_l, flotation, ballast "
            "or freeboard. The water surface is at world height 0 (the tips' height over it sets the "
            "arm their loads gain as she heels). Read by `liftplan solve` only: `plan`, `lift` and "
            "the other commands refuse a hull vessel (with `mesh` or `box`) in one line"
        ),
        values="string (path)",
        absent="the small-angle vessel (waterplane_area, gm_t, gm_l, flotation)",
        frame="the vessel's own axes, file frame",
        example='mesh = "barge.stl"',
    )
    box: _VesselBox | None = Key(
        None,
        doc="the vessel's hull as an axis-aligned box in her own axes (as `mesh`; corners in m)",
        values="table { min = [x, y, z], max = [x, y, z] }",
        absent="see `mesh`",
        frame="the vessel's own axes, file frame",
        example="box = { min = [-50, -15, 0], max = [50, 15, 8] }",
    )
    cog: Point | None = Key(
        None,
        doc="with `mesh` or `box`: her centre of gravity (crane and ballast included) in her own axes",
        unit="m",
        absent="required with `mesh` or `box`",
        frame="the vessel's own axes, file frame",
        example="cog = [0.0, 0.0, 12.0]",
    )
    origin: Pair | None = Key(
        None,
        doc="with `mesh` or `box`: where the origin of her own axes lies in plan",
        unit="m",
        values="[x, y] or [x, z]",
        absent="required with `mesh` or `box`",
        frame="world plan, file frame",
        example="origin = [40.0, -30.0]",
    )
    displacement: Num = Key(
        doc="the crane vessel's displacement before the lift (crane and ballast included)",
        unit="t",
        values="number > 0",
        example="displacement = 9000.0",
    )
    waterplane_area: Num | None = Key(
        None,
        doc="A_wp, its waterplane area: the hook load T sinks it by T / (density A_wp)",
        unit="m2",
        values="number > 0",
        absent="required without `mesh` or `box`; refused with them",
        example="waterplane_area = 2800.0",
    )
    gm_t: Num | None = Key(
        None,
        doc="transverse metacentric height GM_T: heel = T y_t / (displacement GM_T)",
        unit="m",
        values="number > 0",
        absent="required without `mesh` or `box`; refused with them",
        example="gm_t = 6.0",
    )
    gm_l: Num | None = Key(
        None,
        doc="longitudinal metacentric height GM_L: trim = T x_t / (displacement GM_L)",
        unit="m",
        values="number > 0",
        absent="required without `mesh` or `box`; refused with them",
        example="gm_l = 180.0",
    )
    flotation: Pair | None = Key(
        None,
        doc=(
            "centre of flotation in plan: (x, y) in `z-up`, (x, z) in `choi`; the boom tip's offset "
            "from it (x_t forward, y_t to starboard, in the vessel's axes) sets the heel and trim"
        ),
        unit="m",
        values="[x, y] or [x, z]",
        frame="world plan, file frame",
        absent="required without `mesh` or `box`; refused with them",
        example="flotation = [20.0, -45.0]",
    )
    heading: Num = Key(
        0.0,
        doc=(
            "the bow's direction in plan, from +x towards the second plan axis of the file's frame "
            "(+y, port, in `z-up`; +z, starboard, in `choi`)"
        ),
        unit="deg",
        frame="world plan, file frame",
        example="heading = 90.0",
    )
    density: Num = Key(
        1.025, doc="water density", unit="t/m3", values="number > 0", example="density = 1.025"
    )
    max_heel: Num | None = Key(
        None,
        doc="the vessel's heel limit under the load (absolute): a check, flagged when exceeded",
        unit="deg",
        values="number in (0, 90)",
        absent="not checked",
        example="max_heel = 3.0",
    )
    max_trim: Num | None = Key(
        None,
        doc="the vessel's trim limit under the load (absolute): a check, flagged when exceeded",
        unit="deg",
        values="number in (0, 90)",
        absent="not checked",
        example="max_trim = 2.0",
    )
    ballast: Pair = Key(
        (0.0, 0.0),
        doc=(
            "ballast moment set before the lift (heeling > 0 starboard down, trimming > 0 bow down); "
            "the vessel's heel and trim under load include it, its tip drop does not change"
        ),
        unit="[t m, t m]",
        values="[heeling, trimming]",
        example="ballast = [-3000.0, 0.0]",
    )
    freeboard: Num | None = Key(
        None,
        doc=(
            "the deck edge's height above the water before the lift (level, no ballast moment); with "
            "`beam` and `length`, the lowest deck corner's freeboard under the load, freeboard - heave "
            "- beam abs(heel) / 2 - length abs(trim) / 2 (small angles, ballast included), is checked "
            "against `min_freeboard`"
        ),
        unit="m",
        values="number > 0",
        absent="not checked",
        example="freeboard = 4.0",
    )
    min_freeboard: Num | None = Key(
        None,
        doc=(
            "the least freeboard allowed at the lowest deck corner under the load: "
            "a check, flagged when below"
        ),
        unit="m",
        values="number; only with `freeboard`",
        absent="0 (the deck edge at the water) when `freeboard` is given",
        example="min_freeboard = 1.0",
    )
    beam: Num | None = Key(
        None,
        doc=(
            "the hull's breadth, centred on the flotation centre (where the deck corners are); "
            "required with `freeboard`"
        ),
        unit="m",
        values="number > 0",
        absent="no freeboard check",
        example="beam = 40.0",
    )
    length: Num | None = Key(
        None,
        doc=(
            "the hull's length, centred on the flotation centre (where the deck corners are); "
            "required with `freeboard`"
        ),
        unit="m",
        values="number > 0",
        absent="no freeboard check",
        example="length = 90.0",
    )


class _Tide(Table):
    table: list[Pair] = Key(
        doc=(
            "the water level over the operation, linear between points, times increasing; the boom "
            "heights and `[water] level` are those at its first time"
        ),
        unit="[h, m]",
        values="array of [time, level]",
        frame="world height",
        example="table = [[0.0, 0.0], [3.0, 1.1], [6.0, 1.6]]",
    )
    time: Num | None = Key(
        None,
        doc=(
            "when the scene is solved: every floating crane's tip and the water have risen by the "
            "level then less the level at the table's first time"
        ),
        unit="h",
        absent="the table's first time",
        example="time = 3.0",
    )


class _WindArea(Table):
    area: Num = Key(
        doc="the area exposed to the wind", unit="m2", values="number > 0", example="area = 450.0"
    )
    cd: Num = Key(doc="its drag coefficient", unit="-", values="number > 0", example="cd = 1.2")
    height: Num = Key(
        doc=(
            "its centre of pressure: on the body, its height in the body frame (the file's up "
            "coordinate); on a boom, above the vessel's waterline"
        ),
        unit="m",
        example="height = 9.0",
    )


class _BoomWind(_WindArea):
    crane: Text = Key(
        doc="the floating crane whose boom it is (its name, or its lug)", example='crane = "Sheerleg 1"'
    )


class WindTable(Table):
    speed: Num = Key(
        doc="the wind speed at the exposed areas", unit="m/s", values="number >= 0", example="speed = 20.0"
    )
    direction: Num | None = Key(
        None,
        doc=(
            "where it blows towards, in plan from +x towards the second plan axis of the file's frame "
            "(as a vessel's `heading`); required in a scene file, refused in a planning file (the plan "
            "takes the wind from any direction)"
        ),
        unit="deg",
        frame="world plan, file frame",
        example="direction = 90.0",
    )
    density: Num = Key(
        AIR_DENSITY, doc="air density", unit="t/m3", values="number > 0", example="density = 0.001225"
    )
    body: _WindArea | None = Key(
        None,
        doc=(
            "the body's exposed area: F = 1/2 rho Cd A V^2, its couple about the lugs' mean height "
            "carried by the vertical tensions (the weight acts that much further downwind)"
        ),
        absent="no wind on the body",
        example="body = { area = 450.0, cd = 1.2, height = 9.0 }",
    )
    booms: list[_BoomWind] = Key(
        [],
        doc=(
            "floating cranes' booms: each one's force times its height heels and trims its vessel, "
            "which moves the vessel's tips"
        ),
        example='booms = [{ crane = "Sheerleg 1", area = 120.0, cd = 1.5, height = 50.0 }]',
    )


class _Crane(Table):
    lug: Text | None = Key(
        None, doc="the lug its rope is shackled to; exactly one of `lug` and `sling`", example='lug = "T1"'
    )
    name: Text | None = Key(
        None,
        doc=(
            "the crane's label; required with a `sling` (its results are keyed by it); a single-rope "
            "crane is keyed by its lug"
        ),
        example='name = "Big-P"',
    )
    sling: _Sling | None = Key(
        None,
        doc="a sling set from the hook to 2-4 lugs, instead of `lug`",
        example="sling = { legs = [...] }",
    )
    tip: Point | None = Key(
        None,
        doc=(
            "the boom tip when it is not above the lug: inclined rope, 6-DOF `inclined` model; with a "
            "sling: default above the centroid of its lugs at `boom_height`"
        ),
        unit="m",
        frame="world, file frame",
        example="tip = [16.2, 30.0, 40.0]",
    )
    boom_height: Num | None = Key(
        None,
        doc=(
            "H: height of the boom tip (the rope's upper end) above the datum; with `rope_length` and "
            "`EA`, for the forward `elastic` model"
        ),
        unit="m",
        frame="world height",
        example="boom_height = 40.0",
    )
    rope_length: Num | None = Key(
        None,
        doc="l0: unstretched rope length from tip to lug (with a sling: tip to hook)",
        unit="m",
        values="number > 0",
        example="rope_length = 30.0",
    )
    swl: Num | None = Key(
        None,
        doc="safe working load at the crane's radius; tensions are checked against it",
        unit="t",
        values="number > 0",
        example="swl = 400.0",
    )
    EA: Num | None = Key(
        None,
        doc="this rope's stiffness; default `ropes.EA`",
        unit="t",
        values="number > 0",
        example="EA = 70000.0",
    )
    vessel: VesselTable | Text | None = Key(
        None,
        doc=(
            "a floating crane: its vessel's particulars (the boom tip, above the lug at the level "
            "pose, heaves, heels and trims with it under the hook load), or the name of the crane "
            "whose vessel this crane shares"
        ),
        absent="a crane on land or a jack-up: the tip stays where it is",
        example=(
            "vessel = { displacement = 9000.0, waterplane_area = 2800.0, gm_t = 6.0, gm_l = 180.0, "
            "flotation = [20.0, -45.0], heading = 90.0 }"
        ),
    )


class _Attitude(Table):
    heel: Num = Key(0.0, doc="heel, > 0 starboard side down", unit="deg", example="heel = 2.0")
    trim: Num = Key(0.0, doc="trim, > 0 bow down", unit="deg", example="trim = -1.0")
    yaw: Num = Key(0.0, doc="yaw, > 0 bow to port", unit="deg", example="yaw = 0.0")
    lift_height: Num = Key(
        0.0,
        doc="a: height of the body-frame origin above the datum",
        unit="m",
        frame="world height",
        example="lift_height = 1.0",
    )


class _Redundant(Table):
    lug: Text = Key(doc="the lug whose tension is held", example='lug = "T4"')
    tension: Num = Key(doc="its tension", unit="t", example="tension = 200.0")


class _Analysis(Table):
    # Literal of a tuple of names: Python expands it at run time, a static checker cannot
    model: Literal[MODELS] | None = Key(  # type: ignore[valid-type]
        None,
        doc=(
            'the model to solve (README "Models"): `rigid` holds n - 3 tensions at the given '
            "attitude; `paper-elastic` closes the statics with the 2003 paper's coplanar elongations; "
            "`elastic` finds pose and tensions from H, l0 and EA; `hydrostatic` adds a hull in water; "
            "`inclined` places the crane tips; `rigging` solves sling sets with free hooks and bar "
            "ends; `rigid` and `paper-elastic` also take `[water]` and `[hull]` at the given attitude"
        ),
        absent="the least model the scene needs",
        example='model = "elastic"',
    )
    redundant: _Redundant | list[_Redundant] | None = Key(
        None,
        doc=(
            "`rigid`: the held tensions, n - 3 of them, each lug once; the three lugs left free must "
            "span an area in plan"
        ),
        example='redundant = { lug = "T4", tension = 200.0 }',
    )
    hull: Literal[HULL_MODELS] = Key(  # type: ignore[valid-type]
        "auto",
        doc=(
            "with `hull.EI`, how the `elastic` and `hydrostatic` models take the hull: `auto` solves "
            "it rigid and flexible and keeps the rigid answer when flexibility changes no tension "
            "(and, grounded, not the ground reaction) by more than 1 % (and says which it used, with "
            "the measured change); `rigid` and `flexible` force one. The other models, `paper-newton` "
            "and a breakout scene hold the hull rigid and say so (`flexible` is refused there)"
        ),
        example='hull = "flexible"',
    )


class _Water(Table):
    density: Num = Key(
        1.025, doc="water density", unit="t/m3", values="number > 0", example="density = 1.0273"
    )
    level: Num = Key(
        0.0, doc="free-surface height above the datum", unit="m", frame="world height", example="level = 0.0"
    )


class _Box(Table):
    min: Point = Key(
        doc="one corner (min < max on every axis)",
        unit="m",
        frame="body, file frame",
        example="min = [-50.0, -15.0, -5.0]",
    )
    max: Point = Key(
        doc="the opposite corner", unit="m", frame="body, file frame", example="max = [50.0, 15.0, 5.0]"
    )


class _Opening(Table):
    area: Num = Key(
        doc=(
            "the opening's area: `0` never drains (a trapped compartment), `inf` drains at once (the "
            "inside level follows the outside water, or the opening's sill: free-flooding)"
        ),
        unit="m2",
        values="number >= 0, or `inf`",
        example="area = 0.05",
    )
    at: Point = Key(
        doc="where the opening is (its height is z in the z-up frame); on or inside the compartment's box",
        unit="m",
        frame="body, file frame",
        example="at = [3.0, 0.0, 0.0]",
    )
    discharge: Num = Key(
        DISCHARGE,
        doc=(
            "discharge coefficient C_d; 0.61 is the sharp-edged orifice's (its vena contracta) in "
            "hydraulics textbooks; a short pipe or rounded entry runs 0.8-0.98"
        ),
        unit="-",
        values="number in (0, 1]",
        example="discharge = 0.8",
    )


class _Compartment(Table):
    name: Text = Key(doc="the compartment's name", example='name = "fore tank"')
    box: _Box = Key(doc="its box", example="box = { min = [55, -6, 0], max = [60, 6, 2] }")
    contents: Literal["air", "water"] = Key(
        "air",
        doc=(
            "`air` displaces water while submerged; `water` is trapped: a weight carried at every "
            "hoist; its watertight compartment displaces water while submerged, so under water the "
            "two cancel"
        ),
        example='contents = "water"',
    )
    openings: list[_Opening] = Key(
        [],
        doc=(
            "openings of a `water` compartment through which it drains as the hull rises (`liftplan "
            "lift --speed`; without a speed it is carried full, the conservative bound). The "
            "compartment is taken as vented (air enters above its water); each opening passes C_d x "
            "area x sqrt(2 g head) (Torricelli), the head being the inside level over the opening, or "
            "over the outside water while the opening is below it (then water may flow either way)"
        ),
        example="openings = [{ area = 0.05, at = [3.0, 0.0, 0.0] }]",
    )


class _Hull(Table):
    box: _Box | None = Key(
        None, doc="an axis-aligned box hull", example="box = { min = [-50, -15, -5], max = [50, 15, 5] }"
    )
    mesh: Text | None = Key(
        None,
        doc="a closed, outward-oriented triangle mesh (STL), path relative to the scene file",
        values="string (path)",
        frame="body, file frame",
        example='mesh = "hull.stl"',
    )
    flooding: Literal["intact", "flooded"] = Key(
        "intact",
        doc=(
            "`intact`: watertight and empty, displaces up to the waterline; `flooded`: free-flooding, "
            "only the steel (and air compartments) displace water"
        ),
        example='flooding = "flooded"',
    )
    steel_density: Num | None = Key(
        None,
        doc="flooded hull: steel volume = weight / steel_density",
        unit="t/m3",
        values="number > 0",
        absent="7.85",
        example="steel_density = 7.85",
    )
    weight_in_water: Num | None = Key(
        None,
        doc=(
            "flooded hull: instead of `steel_density`, steel volume = (weight - weight_in_water) / "
            "water density"
        ),
        unit="t",
        example="weight_in_water = 523.0",
    )
    compartments: list[_Compartment] = Key(
        [], doc="watertight boxes inside a flooded hull", example="[[hull.compartments]]"
    )
    EI: list[Pair] | None = Key(
        None,
        doc=(
            "the hull girder's vertical bending stiffness (E x the section's moment of inertia), "
            "linear between points, its end values held beyond the first and last; every x on the "
            "body (the weight curve's span); needs `body.weight_curve`, and every lug's x on that "
            "span. The `elastic` model then solves the hull as an elastic beam on the elastic ropes, "
            "and the `hydrostatic` model on its ropes, the water and the ground contact (see "
            '"Flexible hull" below); in water the weight curve must span the hull'
        ),
        unit="[m, t m2]",
        values="array of [x, EI] pairs, x increasing, EI > 0",
        frame="body x",
        absent="a rigid hull",
        example="EI = [[0.0, 5.3e7], [82.05, 5.3e7]]",
    )
    GJ: list[Pair] | None = Key(
        None,
        doc=(
            "the hull girder's torsional stiffness about its x axis (through the CG's y and height), "
            "as `EI`; needs `EI`"
        ),
        unit="[m, t m2]",
        values="array of [x, GJ] pairs, x increasing, GJ > 0",
        frame="body x",
        absent="rigid in torsion",
        example="GJ = [[0.0, 5.2e7], [82.05, 5.2e7]]",
    )


class _Breakout(Table):
    factor: Num | None = Key(
        None,
        doc=(
            "F_b = factor x the submerged weight at rest (W + trapped water - B). A measured salvage "
            "lift of a small vessel peaked at twice its initial lifting force (1.38 MN against 0.69 "
            "MN; Ocean Engineering, 2016): factor 1.0"
        ),
        unit="-",
        values="number >= 0",
        example="factor = 1.0",
    )
    shear_strength: Num | None = Key(
        None,
        doc=(
            "a soil model: the cohesive seabed's undrained shear strength s_u at the hull's base. "
            "Without `pull_time` and `embedded_time` the NCEL immediate breakout (model `ncel`): "
            "F_b = area x s_u x bearing_factor x (1 + 0.2 D/B)(1 + 0.2 B/L), D the `embedment`, B "
            "and L the `width` and `length` (Lee 1973, NCEL R-755; NCEL Handbook for Marine "
            "Geotechnical Engineering, 1985: the force that frees a partly embedded object at once, "
            "full suction under its base; +-50 %; the depth term stops at D/B = 2.5, Skempton). With "
            "`pull_time` and `embedded_time` the model of before (`soil`), kept as it was: F_b = 1.5 "
            "(pull_time / embedded_time)^-0.07 x bearing_factor x s_u x area (Liu 1969, NCEL R-635, "
            "fitted for time ratios 1e-3 to 10, a ratio outside refused); bearing_factor x s_u x area "
            "is already the full-suction immediate force, so it likely counts suction twice and "
            "liftplan warns. Either way liftplan warns when the bed cannot carry the hull at rest "
            "(submerged weight / area above bearing_factor x s_u x the two terms)"
        ),
        unit="kPa",
        values="number >= 0",
        example="shear_strength = 5.0",
    )
    area: Num | None = Key(
        None,
        doc=(
            "soil models: the contact area A (Muga 1968, NCEL R-591: the horizontal projection of "
            "the largest contact area)"
        ),
        unit="m2",
        values="number > 0",
        absent="the plan area of the hull's underside at rest",
        example="area = 600.0",
    )
    bearing_factor: Num = Key(
        Breakout.bearing_factor,
        doc=(
            "soil models: N_c; 5.14 is Prandtl's for a long footing (the `ncel` model adds its own "
            "shape and depth terms; the `soil` model none, so about 6.2, Skempton, for a square or "
            "circle there)"
        ),
        unit="-",
        values="number > 0",
        example="bearing_factor = 6.2",
    )
    pull_time: Num | None = Key(
        None,
        doc="`soil` model: the time allowed for the breakout pull (Liu's T)",
        unit="h",
        values="number > 0",
        example="pull_time = 1.0",
    )
    embedded_time: Num | None = Key(
        None,
        doc="`soil` model: how long the hull has lain bedded (Liu's T_e)",
        unit="h",
        values="number > 0",
        example="embedded_time = 100.0",
    )
    embedment: Num = Key(
        Breakout.embedment,
        doc="`ncel` model: D, how deep the hull's underside lies below the seabed surface",
        unit="m",
        values="number >= 0; not with `pull_time`, `embedded_time`",
        example="embedment = 0.5",
    )
    width: Num | None = Key(
        None,
        doc="`ncel` model: B, the contact's shorter plan side",
        unit="m",
        values="number > 0; not with `pull_time`, `embedded_time`",
        absent="the underside's plan extent across the hull's heading at rest (the shorter of the two)",
        example="width = 12.0",
    )
    length: Num | None = Key(
        None,
        doc="`ncel` model: L, the contact's longer plan side",
        unit="m",
        values="number > 0; not with `pull_time`, `embedded_time`",
        absent="the underside's plan extent along the hull's heading at rest (the longer of the two)",
        example="length = 60.0",
    )
    clear: Num = Key(
        Breakout.clear,
        doc=(
            "the soil holds on with the full F_b until the contact has risen this far above its bed, "
            "then lets go (an assumption: the real hold falls off as the soil fails, so this is on "
            "the safe side; it lengthens the peak's plateau, never raises it)"
        ),
        unit="m",
        values="number >= 0",
        example="clear = 0.2",
    )


class _Ground(Table):
    contact: Point = Key(
        doc=(
            "the body point on the ground; it stays where it sits at the scene's attitude and "
            "`lift_height`, and the body pivots about it"
        ),
        unit="m",
        frame="body, file frame",
        example="contact = [30.0, 0.0, -5.0]",
    )
    friction: Num | None = Key(
        None,
        doc="friction coefficient: freeing force = friction x ground reaction",
        unit="-",
        values="number >= 0",
        example="friction = 0.5",
    )
    breakout: _Breakout | None = Key(
        None,
        doc=(
            "how hard the seabed holds the bedded hull down: `factor`, the NCEL immediate breakout "
            "(`shear_strength`, `embedment`, `width`, `length`) or the soil model of before "
            "(`shear_strength`, `pull_time`, `embedded_time`). The breakout force F_b acts down at "
            "the contact: the hull stays on the bed until the ropes carry W + trapped water - B + F_b "
            "(the peak, `liftplan lift` event `breakout`), then rises with F_b still pulling until "
            "the contact is `clear` m above its bed (event `released`). `breakout_load(scene)` gives "
            "the peak total hook load for a plan's capacity check"
        ),
        absent="the soil lets go at once: today's lift-off",
        example="breakout = { factor = 1.0 }",
    )


class _Rigging(Table):
    min_sling_angle: Num = Key(
        RiggingLimits.min_sling_angle,
        doc="lowest leg angle from the horizontal; legs below it are flagged",
        unit="deg",
        values="number in (0, 90]",
        example="min_sling_angle = 45.0",
    )


class _Strength(Table):
    bending_moment: list[Pair] | None = Key(
        None,
        doc=(
            "allowable absolute bending moment, linear between points, its end values held beyond the "
            "first and last"
        ),
        unit="[m, t m]",
        values="array of [x, M] pairs, x increasing, M > 0",
        frame="body x",
        example="bending_moment = [[0.0, 2000.0], [82.0, 2000.0]]",
    )
    shear_force: list[Pair] | None = Key(
        None,
        doc="allowable absolute shear force, as `bending_moment`",
        unit="[m, t]",
        values="array of [x, Q] pairs, x increasing, Q > 0",
        frame="body x",
        example="shear_force = [[0.0, 300.0], [82.0, 300.0]]",
    )


class _SceneFile(Table):
    name: Text = Key("", doc="a label for the scene, shown in outputs", example='name = "1500 GT tanker"')
    frame: Literal["z-up", "choi"] = Key(
        "z-up", doc="the axes every coordinate of the file is read in (see above)", example='frame = "choi"'
    )
    body: _Body = Key(doc="the lifted body", example="[body]")
    lugs: list[_Lug] = Key(
        [], doc="the lift points, three or more (none for a stranded ship with no cranes)", example="[[lugs]]"
    )
    ropes: _Ropes = Key(_Ropes(), doc="defaults for every crane's rope", example="[ropes]")
    cranes: list[_Crane] = Key([], doc="the cranes, one per lug (or per sling set)", example="[[cranes]]")
    attitude: _Attitude = Key(
        _Attitude(),
        doc=(
            "the body's attitude for the given-attitude models (`rigid`, `paper-elastic`); the start "
            "of the others"
        ),
        example="[attitude]",
    )
    analysis: _Analysis = Key(
        _Analysis(), doc="which model, and the held tensions of `rigid`", example="[analysis]"
    )
    water: _Water | None = Key(None, doc="still water around the body", absent="no water", example="[water]")
    hull: _Hull | None = Key(
        None,
        doc=(
            "the displacing envelope: exactly one of `box` and `mesh` (in water); a body in air may "
            "give only `EI` (and `GJ`)"
        ),
        absent="no hull",
        example="[hull]",
    )
    ground: _Ground | None = Key(
        None,
        doc="a contact point resting on the seabed (a stranded ship, a wreck before lift-off)",
        absent="no ground",
        example="[ground]",
    )
    rigging: _Rigging = Key(_Rigging(), doc="limits checked on sling sets", example="[rigging]")
    strength: _Strength | None = Key(
        None,
        doc=(
            "allowable envelopes of the hull girder; needs `body.weight_curve`; each is checked where "
            "the absolute value over the allowable is largest along the body, flagged like every "
            "other check"
        ),
        absent="no envelope checks",
        example="[strength]",
    )
    tide: _Tide | None = Key(
        None,
        doc=(
            "the tide over the operation: the water level at times; floating cranes (`cranes[].vessel`) "
            "and `[water]` rise with it"
        ),
        absent="no tide: the water stays at its level",
        example="[tide]",
    )
    wind: WindTable | None = Key(
        None,
        doc="wind on the body and on the floating cranes' booms (vertical-rope models)",
        absent="no wind",
        example="[wind]",
    )


# Tables of a planning scene (read by liftplan.planner.problem.file; [rules] by model.rules.table).
PLAN_TABLES = ("candidates", "plan", "crane", "rules")
# Tables of a lift sequence file (read by liftplan.model.sequence.file).
SEQUENCE_TABLES = ("stages", "sequence")


def refuse_sequence(raw, command):
    """Refuse a lift sequence file (``[[stages]]`` or ``[sequence]``) given to another
    command, in one line that names the command it is for."""
    for key in SEQUENCE_TABLES:
        if key in raw:
            brackets = f"[[{key}]]" if key == "stages" else f"[{key}]"
            raise InvalidScene(
                f"{brackets}: this is a lift sequence file, not {command}; expected "
                "`liftplan sequence FILE` for it"
            )


def load_scene(path: str | os.PathLike[str]) -> Scene:
    """Read and validate a scene file.

    Parameters
    ----------
    path : str or os.PathLike
        TOML scene file.

    Returns
    -------
    Scene
        In the ``z-up`` frame, whatever frame the file was written in.

    Raises
    ------
    InvalidScene
        One line naming the file, the key, the value and what is expected.
    """
    return load_with(path, lambda text: loads_scene(text, base=Path(path).parent))


def load_with(path, loads):
    """Read a TOML file and validate it with ``loads``; errors start with the path.

    Only regular files are read: a FIFO would block for ever, and a folder or device is a
    mistake that deserves its own line.
    """
    if str(path) == "":
        raise InvalidScene("'': expected a scene file path, got an empty one")
    path = Path(path)
    try:
        mode = path.stat().st_mode
    except FileNotFoundError:
        raise InvalidScene(f"{path}: no such scene file") from None
    except OSError as err:
        raise InvalidScene(f"{path}: cannot read the scene file ({err.strerror or err})") from None
    if not stat.S_ISREG(mode):
        kind = "a folder" if stat.S_ISDIR(mode) else "not a regular file"
        raise InvalidScene(f"{path}: is {kind}; expected a TOML scene file")
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InvalidScene(f"{path}: no such scene file") from None
    except UnicodeDecodeError:
        raise InvalidScene(f"{path}: not a text file (not UTF-8); expected a TOML scene file") from None
    except OSError as err:
        raise InvalidScene(f"{path}: cannot read the scene file ({err.strerror or err})") from None
    try:
        return loads(text)
    except InvalidScene as err:
        raise InvalidScene(f"{path}: {err}") from None


# Deeper than any scene needs (a scene is at most ~5 levels); bounds the recursion of the
# validators and of error messages that print the offending value.
MAX_TOML_DEPTH = 32


def parse_toml(text):
    """TOML text to a dict; a syntax error is an InvalidScene naming the line.

    Nesting deeper than ``MAX_TOML_DEPTH`` tables/arrays is refused (tomllib itself recurses
    on inline arrays and tables and would overflow the stack).
    """
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise InvalidScene(f"TOML syntax error: {err}") from None
    except RecursionError:
        raise InvalidScene(
            f"TOML nested too deeply: expected at most {MAX_TOML_DEPTH} levels of tables and arrays"
        ) from None
    stack = [(raw, 1)]
    while stack:  # iterative, so a deep document cannot overflow the check itself
        node, depth = stack.pop()
        if depth > MAX_TOML_DEPTH:
            raise InvalidScene(
                f"TOML nested too deeply: expected at most {MAX_TOML_DEPTH} levels of tables and arrays"
            )
        children = node.values() if isinstance(node, dict) else node if isinstance(node, list) else ()
        stack.extend((c, depth + 1) for c in children if isinstance(c, dict | list))
    return raw


def loads_scene(text: str, base: str | os.PathLike[str] | None = None) -> Scene:
    """Validate a scene given as TOML text; see :func:`load_scene`.

    ``base`` is the folder that a relative ``hull.mesh`` path is read from (default: the
    working directory).
    """
    raw = parse_toml(text)
    refuse_sequence(raw, "a scene file")
    for key in PLAN_TABLES:
        if key in raw:
            raise InvalidScene(
                f"[{key}]: this is a planning scene (candidates, not fixed lugs); "
                "expected `liftplan plan` / liftplan.planner.plans.held for it"
            )
    try:
        data = _SceneFile.model_validate(raw)
    except ValidationError as err:
        raise InvalidScene(one_line(err, _SceneFile)) from None
    return _to_scene(data, Path(base) if base is not None else Path.cwd())


def _to_hull(data, to_zup, base):
    spec = data.hull
    if spec.box is None and spec.mesh is None and (spec.EI, spec.GJ) != (None, None) and data.water is None:
        return None  # a hull girder's stiffness alone, for a body in air
    if (spec.box is None) == (spec.mesh is None):
        raise InvalidScene('hull: expected exactly one of box = {min, max} or mesh = "file.stl"')
    options = dict(
        flooding=spec.flooding,
        steel_density=spec.steel_density,
        weight_in_water=spec.weight_in_water,
        compartments=tuple(
            Compartment(name=c.name, box=_zup_box(c.box, to_zup), contents=c.contents)
            for c in spec.compartments
        ),
    )
    if spec.box is not None:
        box = _zup_box(spec.box, to_zup)
        return Hull.box(box["min"], box["max"], **options)
    hull = Hull.from_stl(base / spec.mesh, **options)
    if data.frame == "choi":
        tris = np.array([[choi_to_zup(v) for v in tri] for tri in hull.triangles])
        hull = Hull(tris, source=hull.source, **options)
    return hull


def _zup_box(box, to_zup):
    """A box's corners in z-up (the frame change can swap which corner is lower)."""
    if not all(lo < hi for lo, hi in zip(box.min, box.max)):
        raise InvalidScene(
            f"hull box = {{min = {list(box.min)}, max = {list(box.max)}}}: expected min < max on every axis"
        )
    a, b = np.array(to_zup(box.min)), np.array(to_zup(box.max))
    return {"min": tuple(np.minimum(a, b).tolist()), "max": tuple(np.maximum(a, b).tolist())}


def _to_scene(data, base):
    to_zup = choi_to_zup if data.frame == "choi" else tuple
    lugs = [to_lug(lug, to_zup) for lug in data.lugs]
    cranes = [_to_crane(c, data, to_zup, base) for c in data.cranes]
    red = data.analysis.redundant
    red = [] if red is None else [red] if isinstance(red, _Redundant) else red
    return Scene(
        name=data.name,
        body=Body(weight=data.body.weight, cog=to_zup(data.body.cog), weight_curve=data.body.weight_curve),
        lugs=tuple(lugs),
        cranes=tuple(cranes),
        attitude=Attitude(**data.attitude.model_dump()),
        analysis=Analysis(
            model=data.analysis.model,
            redundant=tuple(Redundant(lug=r.lug, tension=r.tension) for r in red),
            hull=data.analysis.hull,
        ),
        water=Water(**data.water.model_dump()) if data.water is not None else None,
        hull=_to_hull(data, to_zup, base) if data.hull is not None else None,
        ground=_to_ground(data.ground, to_zup) if data.ground is not None else None,
        rigging=RiggingLimits(min_sling_angle=data.rigging.min_sling_angle),
        frame=data.frame,
        strength=Strength(**data.strength.model_dump()) if data.strength is not None else None,
        openings=tuple(
            Opening(compartment=c.name, area=o.area, at=to_zup(o.at), discharge=o.discharge)
            for c in (data.hull.compartments if data.hull is not None else ())
            for o in c.openings
        ),
        girder=_to_girder(data.hull),
        tide=Tide(table=tuple(map(tuple, data.tide.table)), time=data.tide.time)
        if data.tide is not None
        else None,
        wind=to_wind(data.wind, data.frame),
    )


def to_lug(spec, to_zup):
    """One ``[[lugs]]`` table to a :class:`Lug` in z-up; a sequence file's lugs also carry
    ``capacity``, ``capacity_out_of_plane`` and ``normal`` (its normal turned like a point)."""
    normal = getattr(spec, "normal", None)
    return Lug(
        name=spec.name,
        at=to_zup(spec.at),
        capacity=getattr(spec, "capacity", None),
        capacity_out_of_plane=getattr(spec, "capacity_out_of_plane", None),
        normal=to_zup(normal) if normal is not None else None,
    )


def to_wind(spec, frame, plan=False):
    """``[wind]`` in ``z-up`` (None without); a scene's needs its direction, a plan's has none
    (the plan takes the wind from any direction)."""
    if spec is None:
        return None
    if plan and spec.direction is not None:
        raise InvalidScene(
            f"wind.direction = {spec.direction!r}: a plan takes the wind from any direction over the "
            "operation; expected no direction in a planning file"
        )
    if not plan and spec.direction is None:
        raise InvalidScene(
            "wind.direction: missing; expected where the wind blows towards (a scene is solved for one wind)"
        )
    direction = 0.0 if plan else 0.0 - spec.direction if frame == "choi" else spec.direction
    body = WindArea(**spec.body.model_dump()) if spec.body is not None else None
    booms = tuple(WindArea(**b.model_dump()) for b in spec.booms)
    return Wind(speed=spec.speed, direction=direction, body=body, booms=booms, density=spec.density)


def _to_girder(spec):
    """``[hull] EI`` and ``GJ`` (None without EI; GJ alone is refused)."""
    if spec is None or (spec.EI is None and spec.GJ is None):
        return None
    if spec.EI is None:
        raise InvalidScene(
            "hull.GJ: given without hull.EI; expected EI = [[x m, t m2], ...] too "
            "(the flexible hull bends and twists)"
        )
    return GirderStiffness(EI=spec.EI, GJ=spec.GJ)


def _to_ground(spec, to_zup):
    breakout = Breakout(**spec.breakout.model_dump()) if spec.breakout is not None else None
    return Ground(contact=to_zup(spec.contact), friction=spec.friction, breakout=breakout)


def _to_crane(c, data, to_zup, base=None):
    """One crane; errors of its sling are prefixed with the crane's key."""
    try:
        sling = _to_sling(c.sling) if c.sling is not None else None
    except InvalidScene as err:
        raise InvalidScene(f"cranes[{c.name or c.lug}].{err}") from None
    return Crane(
        lug=c.lug,
        EA=c.EA if c.EA is not None else data.ropes.EA,
        boom_height=c.boom_height,
        rope_length=c.rope_length,
        swl=c.swl,
        tip=to_zup(c.tip) if c.tip is not None else None,
        name=c.name,
        sling=sling,
        vessel=to_vessel(c.vessel, data.frame, base),
    )


def to_vessel(spec, frame, base=None):
    """A crane's ``vessel`` (table or shared name) in ``z-up``; None for none. ``base``: the scene
    file's folder, a relative ``mesh`` path is read from; None (a planning file): a hull is refused."""
    if spec is None or isinstance(spec, str):
        return spec
    fields = spec.model_dump()
    mesh, box = fields.pop("mesh"), fields.pop("box")
    if base is None and (mesh is not None or box is not None):
        raise InvalidScene(
            f"vessel.{'mesh' if mesh is not None else 'box'}: a vessel given by her hull is solved by "
            "liftplan solve (the elastic model in air), not planned; expected her small-angle particulars "
            "(waterplane_area, gm_t, gm_l, flotation) in a planning file"
        )
    choi = frame == "choi"
    for key in ("flotation", "origin"):
        if choi and spec.model_dump()[key] is not None:  # plan (x, z starboard) -> (x, y port)
            fields[key] = (fields[key][0], 0.0 - fields[key][1])
    if choi:  # the heading turns the other way
        fields["heading"] = 0.0 - spec.heading
    if choi and spec.cog is not None:
        fields["cog"] = choi_to_zup(spec.cog)
    if mesh is not None and box is not None:
        raise InvalidScene('vessel: expected one of mesh = "file.stl" or box = {min, max}, not both')
    if box is not None:
        corners = _zup_box(spec.box, choi_to_zup if choi else tuple)
        fields["hull"] = Hull.box(corners["min"], corners["max"])
    elif mesh is not None:
        hull = Hull.from_stl(Path(base or Path.cwd()) / mesh)
        if choi:
            hull = Hull(
                np.array([[choi_to_zup(v) for v in tri] for tri in hull.triangles]), source=hull.source
            )
        fields["hull"] = hull
    return Vessel(**fields)


def _to_sling(spec):
    legs = tuple(Leg(lug=g.lug, length=g.length, EA=g.EA, diameter=g.diameter, end=g.end) for g in spec.legs)
    spreader = None
    if spec.spreader is not None:
        bar = spec.spreader
        top = tuple(Leg(lug=None, length=g.length, EA=g.EA, diameter=g.diameter) for g in bar.top)
        options = {"EA": bar.EA} if bar.EA is not None else {}
        spreader = Spreader(length=bar.length, top=top, weight=bar.weight, **options)
    return Sling(legs=legs, spreader=spreader, equalised=spec.equalised)


def one_line(err, root):
    """The first pydantic error as 'key = value: what is expected'.

    Parameters
    ----------
    err : pydantic.ValidationError
    root : type
        The schema that was validated (to name the keys and types expected).
    """
    first = err.errors()[0]
    loc = first["loc"]
    path = _path(loc)
    kind = first["type"]
    if kind == "missing":
        return f"{path}: missing, expected {_expected(loc, root)}"
    if kind == "extra_forbidden":
        allowed = _allowed_keys(loc[:-1], root)
        hint = f"expected one of {', '.join(allowed)}" if allowed else "expected no such key"
        return f"{path} = {first['input']!r}: unknown key, {hint}"
    message = first["msg"][0].lower() + first["msg"][1:]
    return f"{path} = {first['input']!r}: {message}"


def _path(loc):
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif part in {"_Redundant", "list[_Redundant]"} or part.startswith(("tuple[", "list[")):
            continue  # union branch labels that pydantic puts in the location
        else:
            out += f".{part}" if out else part
    return out or "scene"


def _resolve(loc, root):
    """The schema type at a location, or None."""
    node = root
    for part in loc:
        node = _strip(node)
        if isinstance(part, int):
            args = typing.get_args(node)
            node = args[0] if args else None
        elif isinstance(node, type) and issubclass(node, BaseModel) and part in node.model_fields:
            node = node.model_fields[part].annotation
        else:
            return None
    return _strip(node)


def _strip(node):
    """Drop None from an Optional and pick the table branch of a union."""
    if typing.get_origin(node) in (Union, types.UnionType):
        args = [a for a in typing.get_args(node) if a is not type(None)]
        tables = [a for a in args if isinstance(a, type) and issubclass(a, BaseModel)]
        return tables[0] if tables else args[0]
    return node


def _allowed_keys(loc, root):
    node = _resolve(loc, root)
    if isinstance(node, type) and issubclass(node, BaseModel):
        return list(node.model_fields)
    return []


def _expected(loc, root):
    node = _resolve(loc, root)
    if node in (float, Num):
        return "a number"
    if node in (str, Text):
        return "a string"
    if node == Point:
        return "[x, y, z] in m"
    if isinstance(node, type) and issubclass(node, BaseModel):
        return f"a table with keys {', '.join(node.model_fields)}"
    if typing.get_origin(node) is list:
        return "an array of tables"
    return "a value"


#: The scene's ``[hull]`` and ``[water]`` tables: a planning file reads the same keys.
HullTable = _Hull
WaterTable = _Water


def to_hull(data, base):
    """The ``[hull]`` geometry of a file's validated tables (``data.hull``, ``data.water``,
    ``data.frame``), in z-up; None for a stiffness alone in air. ``base``: the folder a
    relative ``hull.mesh`` is read from."""
    return _to_hull(data, choi_to_zup if data.frame == "choi" else tuple, Path(base))


def to_girder(spec):
    """``[hull] EI`` and ``GJ`` as a :class:`GirderStiffness` (None without them)."""
    return _to_girder(spec)
