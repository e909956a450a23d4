"""Read sequence files (TOML) into :class:`~liftplan.model.sequence.objects.Sequence`.

A sequence file is a scene's body, lugs and cranes (the scene file's own tables, read by the
same schemas) and either one ``[sequence]`` table or a list of ``[[stages]]``; an optional
``[rules]`` table sets the design-load chain. Every failure is one
:class:`~liftplan.model.errors.InvalidScene` line naming the key, as for scene files.
"""

from __future__ import annotations

import os
from typing import Annotated, Literal

from pydantic import Field, Strict, ValidationError
from pydantic.fields import FieldInfo

from liftplan.model.errors import InvalidScene
from liftplan.model.rules import RulesTable, rules_from_table
from liftplan.model.scene.file import (
    Key,
    Num,
    Point,
    Table,
    Text,
    _Body,
    _Crane,
    _Lug,
    _Ropes,
    _to_crane,
    load_with,
    one_line,
    parse_toml,
    to_lug,
)
from liftplan.model.scene.objects import Body
from liftplan.model.sequence.objects import LugChoice, Move, Sequence, Stage, crane_key


def _aliased(key, alias):
    """A :func:`Key` read from a TOML key that is a Python keyword (``from``)."""
    return FieldInfo.merge_field_infos(key, Field(alias=alias))


class _StrongPoint(_Lug):
    capacity: Num | None = Key(
        None,
        doc=(
            "the lug's allowed load in the plane of its plate; `liftplan sequence` checks the design "
            "lug load (rules' factors x consequence) at every angle against it"
        ),
        unit="t",
        values="number > 0",
        absent="no in-plane lug check",
        example="capacity = 120.0",
    )
    capacity_out_of_plane: Num | None = Key(
        None,
        doc=(
            "the lug's allowed load across its plate (the component along `normal`); `liftplan "
            "sequence` checks the design out-of-plane load (with the rules' lateral allowance) against it"
        ),
        unit="t",
        values="number > 0",
        absent="no out-of-plane lug check",
        example="capacity_out_of_plane = 25.0",
    )
    normal: Point | None = Key(
        None,
        doc="the lug plate's normal (its pin axis), scaled to a unit vector",
        unit="-",
        values="[x, y, z], not all 0",
        frame="body, file frame",
        absent="the turning axis of the sequence (the plate in the plane of the turn)",
        example="normal = [0.0, 1.0, 0.0]",
    )


class _SequenceLug(_StrongPoint):
    at: Point | None = Key(
        None,
        doc="where the lug is; exactly one of `at` and `on`",
        unit="m",
        frame="body, file frame",
        example="at = [16.2, 6.0, 12.0]",
    )
    on: list[Text] | None = Key(
        None,
        doc=(
            "instead of `at`: the `[[candidates]]` the planner may put this lug on; `liftplan sequence` "
            "picks the candidates whose worst design lug load over the whole sequence is least"
        ),
        values="array of strings",
        absent="the lug is at `at`",
        example='on = ["E1", "E2", "E3"]',
    )


class _SequenceCandidate(_StrongPoint):
    pass


class _Move(Table):
    crane: Text = Key(doc="the crane whose boom tip moves (its name, or its lug)", example='crane = "A"')
    hoist: Num = Key(
        0.0,
        doc=(
            "how far the tip rises from the stage's start to its end (+ up); added to `to` when both "
            "are given"
        ),
        unit="m",
        example="hoist = 0.5",
    )
    to: Point | None = Key(
        None,
        doc="where the tip is at the stage's end (slew, luff, trolley travel: the tip's new place)",
        unit="m",
        frame="world, file frame",
        absent="the tip moves only by `hoist`",
        example="to = [12.0, 0.0, 30.0]",
    )


class _Operation(Table):
    kind: Literal["upend", "turnover", "move"] = Key(
        doc=(
            '`"upend"`: the head crane lifts one end while the other rests on the ground at `pivot` '
            'or hangs from a tailing crane; `"turnover"`: the body hangs from two or more cranes and '
            'turns in the air; `"move"`: boom tips move (`moves`) and the body hangs on its elastic '
            "ropes"
        ),
        example='kind = "upend"',
    )
    axis: Literal["x", "y"] = Key(
        "y",
        doc=(
            'the body axis it turns about; for `"y"` the angle is how far the body\'s +x end is raised '
            'above the horizontal, for `"x"` how far its +y side is raised'
        ),
        example='axis = "y"',
    )
    start: Num = _aliased(
        Key(0.0, doc="first angle (0: the body as the file gives it)", unit="deg", example="from = 0.0"),
        "from",
    )
    stop: Num | None = _aliased(
        Key(
            None,
            doc="last angle; equal to `from`: the stage holds that one angle",
            unit="deg",
            absent='required for `"upend"` and `"turnover"`; refused for `"move"`',
            example="to = 90.0",
        ),
        "to",
    )
    step: Num = Key(
        5.0,
        doc="the grid of reported angles; every maximum is searched between its points too",
        unit="deg",
        values="number > 0",
        example="step = 5.0",
    )
    pivot: Point | None = Key(
        None,
        doc=(
            "upend, or move: the body point that rests on the ground (rigid, pushing only); the body "
            "turns about it until, in a move, it lifts off"
        ),
        unit="m",
        frame="body, file frame",
        absent="no ground contact (an upend then needs a tailing crane)",
        example="pivot = [0.0, 0.0, 0.0]",
    )
    friction: Num | None = Key(
        None,
        doc="friction coefficient at the pivot: the horizontal force it can hold is friction x reaction",
        unit="-",
        values="number >= 0",
        absent="no friction limit checked",
        example="friction = 0.3",
    )
    plumb: Annotated[bool, Strict()] = Key(
        True,
        doc="each hook follows its lug (or its sling's apex) so its rope stays vertical; only `true`",
        example="plumb = true",
    )
    moves: list[_Move] | None = Key(
        None,
        doc=(
            '`"move"`: each named crane\'s boom tip moves in a straight line from where the file puts it '
            "(`tip`, else above its lug at `boom_height`) to its end position; the others stay"
        ),
        values="array of {crane, hoist, to} tables",
        absent='required for `"move"`, refused otherwise',
        example='moves = [{crane = "A", hoist = 0.5}]',
    )
    steps: Annotated[int, Strict()] | None = Key(
        None,
        doc=(
            '`"move"`: the grid of reported states over the move (parameter 0 to 1); every maximum '
            "is searched between them too"
        ),
        unit="-",
        values="integer >= 1",
        absent='10 for `"move"`; refused otherwise (a turn has `step`)',
        example="steps = 10",
    )
    cranes: list[Text] | None = Key(
        None,
        doc="the cranes that hold the body (their names, or lugs for unnamed cranes); the rest are released",
        values="array of strings",
        absent="every crane of the file",
        example='cranes = ["Head", "Tail"]',
    )


class _Stage(_Operation):
    name: Text = Key("", doc="the stage's label in outputs", example='name = "turn to 90"')


class _SequenceFile(Table):
    name: Text = Key("", doc="a label for the sequence, shown in outputs", example='name = "Mast upend"')
    frame: Literal["z-up"] = Key(
        "z-up",
        doc="the axes every coordinate is read in; a sequence is written in `z-up` (x fwd, y port, z up)",
        example='frame = "z-up"',
    )
    body: _Body = Key(doc="the lifted body, as in a scene file", example="[body]")
    lugs: list[_SequenceLug] = Key(
        doc="the lugs, as in a scene file (any number), with their capacities and plate normals",
        example="[[lugs]]",
    )
    candidates: list[_SequenceCandidate] = Key(
        [],
        doc=(
            "strong points a lug given `on` may go on, each with its own capacities and plate normal; "
            "the same candidate may serve two lugs that no stage holds at once"
        ),
        example="[[candidates]]",
    )
    ropes: _Ropes = Key(_Ropes(), doc="defaults for every crane's rope", example="[ropes]")
    cranes: list[_Crane] = Key(
        doc="the cranes, each on one `lug` or on a 2-leg `sling`; `name` is its key in the results",
        example="[[cranes]]",
    )
    sequence: _Operation | None = Key(
        None,
        doc="one operation (exactly one of `[sequence]` and `[[stages]]`)",
        example="[sequence]",
    )
    stages: list[_Stage] | None = Key(
        None,
        doc="several operations in order, each with the keys of `[sequence]` and a `name`",
        example="[[stages]]",
    )
    rules: RulesTable | None = Key(
        None,
        doc="the design-load chain's settings, as in a planning file",
        absent="the defaults",
        example="[rules]",
    )


def load_sequence(path: str | os.PathLike[str]) -> Sequence:
    """Read and validate a sequence file.

    Parameters
    ----------
    path : str or os.PathLike
        TOML sequence file.

    Returns
    -------
    Sequence
        In the ``z-up`` frame.

    Raises
    ------
    InvalidScene
        One line naming the file, the key, the value and what is expected.
    """
    return load_with(path, loads_sequence)


def loads_sequence(text: str) -> Sequence:
    """Validate a sequence given as TOML text; see :func:`load_sequence`.

    Raises
    ------
    InvalidScene
        Also when a lug is to be planned (``on``): :func:`loads_lug_choice` reads those.
    """
    read = _read(text)
    if isinstance(read, LugChoice):
        name = read.open[0][0]
        raise InvalidScene(
            f"lugs[{name}].on: the file plans its lugs; expected `liftplan sequence` (which plans them) "
            "or load_lug_choice / loads_lug_choice"
        )
    return read


def loads_lug_choice(text: str):
    """A sequence file as a :class:`LugChoice` (lugs given ``on`` candidates) or, when every
    lug has its ``at``, as a :class:`Sequence`."""
    return _read(text)


def load_lug_choice(path: str | os.PathLike[str]):
    """Read a sequence file that may plan its lugs; see :func:`loads_lug_choice`."""
    return load_with(path, loads_lug_choice)


def _read(text):
    raw = parse_toml(text)
    try:
        data = _SequenceFile.model_validate(raw)
    except ValidationError as err:
        raise InvalidScene(one_line(err, _SequenceFile)) from None
    if (data.sequence is None) == (data.stages is None):
        raise InvalidScene("sequence: expected exactly one of a [sequence] table and [[stages]]")
    to_zup = tuple
    cranes = tuple(_to_crane(c, data, to_zup) for c in data.cranes)
    keys = [crane_key(c) for c in cranes]
    if data.sequence is not None:
        stages = (_to_stage(data.sequence, "", keys, to_zup),)
    else:
        stages = tuple(_to_stage(s, s.name or f"{k + 1}", keys, to_zup) for k, s in enumerate(data.stages))
    parts = dict(
        body=Body(weight=data.body.weight, cog=to_zup(data.body.cog), weight_curve=data.body.weight_curve),
        cranes=cranes,
        stages=stages,
        rules=rules_from_table(data.rules),
        name=data.name,
        frame=data.frame,
    )
    fixed, open_lugs = [], []
    for lug in data.lugs:
        if (lug.at is None) == (lug.on is None):
            raise InvalidScene(
                f"lugs[{lug.name}]: expected exactly one of at = [x, y, z] and on = [candidates]"
            )
        if lug.at is not None:
            fixed.append(to_lug(lug, to_zup))
        else:
            open_lugs.append((lug.name, tuple(lug.on)))
    candidates = {c.name: to_lug(c, to_zup) for c in data.candidates}
    if len(candidates) != len(data.candidates):
        raise InvalidScene("candidates.name: duplicate, expected unique candidate names")
    if not open_lugs:
        if candidates:
            raise InvalidScene(
                "candidates: given but no lug is placed on them; expected on = [...] in a [[lugs]] table"
            )
        return Sequence(lugs=tuple(fixed), **parts)
    return LugChoice(parts=parts, fixed=tuple(fixed), open=tuple(open_lugs), candidates=candidates)


#: Keys of a turning stage a move stage has no use for (its hooks move, it turns no angle).
TURN_ONLY = {"start": "from", "step": "step", "plumb": "plumb"}


def _to_stage(spec, name, keys, to_zup):
    if spec.kind == "move":
        given = [key for field, key in TURN_ONLY.items() if field in spec.model_fields_set]
        if given:
            raise InvalidScene(
                f"{'stages[' + name + ']' if name else 'sequence'}.{given[0]}: a move stage turns no "
                "angle (its grid is `steps`, its hooks move by `moves`); expected no "
                + ", ".join(TURN_ONLY.values())
            )
    return Stage(
        kind=spec.kind,
        axis=spec.axis,
        start=spec.start,
        stop=spec.stop,
        step=spec.step,
        cranes=tuple(spec.cranes) if spec.cranes is not None else tuple(keys),
        pivot=to_zup(spec.pivot) if spec.pivot is not None else None,
        friction=spec.friction,
        plumb=spec.plumb,
        name=name,
        moves=tuple(
            Move(crane=m.crane, hoist=m.hoist, to=to_zup(m.to) if m.to is not None else None)
            for m in spec.moves or ()
        ),
        steps=spec.steps,
    )
