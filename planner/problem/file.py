"""Read planning scene files (TOML, CONTRACT.md "Planning") into :class:`PlanProblem`.

The file's shape is checked by pydantic, its values by the dataclasses, with the scene
reader's one-line messages; ``[rules]`` (the design-load chain's settings) is read by
:mod:`liftplan.model.rules.table`. Coordinates (candidates, CG, outline, CG tolerance) are read in
the file's frame and converted to ``z-up``.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Annotated, Literal

from pydantic import Field, Strict, ValidationError

from liftplan.model.errors import InvalidScene
from liftplan.model.frames import choi_to_zup
from liftplan.model.rules import RulesTable, rules_from_table
from liftplan.model.scene.file import (
    Num,
    Pair,
    Point,
    Table,
    Text,
    load_scene,
    load_with,
    one_line,
    parse_toml,
)
from liftplan.model.scene.objects import Body, Strength
from liftplan.planner.problem.definition import Candidate, CogEnvelope, CraneSpec, PlanProblem
from liftplan.planner.problem.fleet import FleetCrane, SlingSpec, SpreaderSpec
from liftplan.planner.problem.report_info import ReportInfo

Count = Annotated[int, Strict(), Field(ge=1)]


class _Body(Table):
    weight: Num
    cog: Point
    weight_curve: list[Pair] | None = None  # [x m, t/m]; x is the same axis in both frames


class _Strength(Table):
    bending_moment: list[Pair] | None = None  # [x m, t m]
    shear_force: list[Pair] | None = None  # [x m, t]


class _StrengthWeights(Table):
    bending: Num = 1.0
    shear: Num = 1.0


class _Candidate(Table):
    name: Text
    at: Point
    bulkhead: Text = ""
    capacity: Num | None = None


class _Tolerance(Table):
    heel: Num = 2.0
    trim: Num = 2.0


class _Plan(Table):
    cranes: Count | None = None
    # the choices of OBJECTIVES (tests/project/test_registries.py checks they agree; a type checker
    # needs them written out)
    objective: Literal["spread", "utilisation", "reserve", "bending", "shear", "strength"] | None = None
    strength_weights: _StrengthWeights | None = None
    gap: Num = 0.0
    time_limit: Num | None = None
    work_limit: Count | None = None
    search: Literal["auto", "exact", "local", "mip"] = "auto"
    tolerance: _Tolerance = _Tolerance()
    min_tension: Num = 0.0
    hook_tolerance: Num = 0.0
    cog_tolerance: Point = (0.0, 0.0, 0.0)
    cog_envelope: Literal["box", "cross"] = "box"
    top: Count = 5
    outline: list[Point] = []
    crane_clearance: Num = 3.0  # m, between booms and hoist lines in plan (0027/ND 16.2)
    breakout_scene: Text | None = None  # scene file of the hull on the seabed, relative path


class _Range(Table):
    min: Num
    max: Num


class _Crane(Table):
    EA: Num | None = None
    rope_length: Num | _Range | None = None
    swl: Num | None = None
    boom_height: _Range | None = None
    control: Literal["hoist", "force"] | None = None


class _Spreader(Table):
    length: Num
    top_length: Num
    weight: Num = 0.0


class _Sling(Table):
    legs: Count = 2
    length: Num
    EA: Num | None = None
    diameter: Num | None = None
    spreader: _Spreader | None = None


class _Rigging(Table):
    min_sling_angle: Num = 60.0


class _FleetCrane(Table):
    name: Text
    position: Point | None = None
    load_chart: list[tuple[Num, Num]] | None = None
    swl: Num | None = None
    EA: Num | None = None
    rope_length: Num | _Range | None = None
    boom_height: _Range | None = None
    sling: _Sling | None = None
    hook_tolerance: Num | None = None
    control: Literal["hoist", "force"] | None = None


class _Ropes(Table):
    EA: Num | None = None


class _Report(Table):
    project: Text = ""
    client: Text = ""
    document: Text = ""
    revision: Text = ""
    prepared_by: Text = ""
    checked_by: Text = ""
    approved_by: Text = ""
    date: Text = ""


class _Attitude(Table):
    lift_height: Num = 0.0
    yaw: Num = 0.0


class _PlanFile(Table):
    name: Text = ""
    frame: Literal["z-up", "choi"] = "z-up"
    body: _Body
    candidates: list[_Candidate]
    plan: _Plan
    crane: _Crane = _Crane()
    cranes: list[_FleetCrane] = []
    ropes: _Ropes = _Ropes()
    attitude: _Attitude = _Attitude()
    rules: RulesTable | None = None
    rigging: _Rigging = _Rigging()
    report: _Report = _Report()
    strength: _Strength | None = None


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


def problem_from_dict(raw, base=None):
    """Validate a planning scene given as the dict its TOML file parses to (``base``: see
    :func:`loads_problem`)."""
    if "candidates" not in raw and "lugs" in raw:
        raise InvalidScene(
            "[[lugs]]: a scene with fixed lugs; expected [[candidates]] and [plan] for "
            "planning (use `liftplan solve` for a fixed scene)"
        )
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
    if isinstance(value, _Range):
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
        strength=Strength(**data.strength.model_dump()) if data.strength is not None else None,
        strength_weights=(
            None
            if data.plan.strength_weights is None
            else (data.plan.strength_weights.bending, data.plan.strength_weights.shear)
        ),
        controls=_controls(data, cranes),
        breakout_scene=_breakout_scene(data.plan.breakout_scene, base),
    )


def _controls(data, count):
    """Each crane's control (``[[cranes]] control``, else ``[crane] control``, else hoist)."""
    default = data.crane.control or "hoist"
    if data.cranes:
        return tuple(c.control or default for c in data.cranes)
    return (default,) * count
