"""Read scene files (TOML, as fixed in CONTRACT.md) into :class:`~liftplan.model.scene.objects.Scene`.

The file's shape (tables, keys, types) is checked by pydantic: it reports unknown keys,
missing keys and wrong types with their location, which a hand-made parser would have to
re-implement. Values (finite, positive, names, statics) are checked by the scene's own
dataclasses, so a scene built in Python obeys the same rules. Every failure is one
:class:`~liftplan.model.errors.InvalidScene` line naming the key, the value and what is
expected; nothing is returned half-read.
"""

from __future__ import annotations

import os
import stat
import tomllib
import types
import typing
from pathlib import Path
from typing import Annotated, Literal, Union

import numpy as np
from pydantic import BaseModel, ConfigDict, Strict, ValidationError

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

# Strict scalars: a TOML string is never silently read as a number (ints still pass as
# floats); arrays may still be read as tuples.
Num = Annotated[float, Strict()]
Text = Annotated[str, Strict()]
Point = tuple[Num, Num, Num]


class Table(BaseModel):
    # Non-finite numbers pass here and are refused by the dataclasses, which say which
    # key held them.
    model_config = ConfigDict(extra="forbid", frozen=True)


Pair = tuple[Num, Num]


class _Body(Table):
    weight: Num
    cog: Point
    weight_curve: list[Pair] | None = None  # [x m, t/m]; x is the same axis in both frames


class _Lug(Table):
    name: Text
    at: Point


class _Ropes(Table):
    EA: Num | None = None


class _Leg(Table):
    lug: Text
    length: Num
    EA: Num | None = None
    diameter: Num | None = None  # mm
    end: Literal[1, 2] | None = None


class _TopLeg(Table):
    length: Num
    EA: Num | None = None
    diameter: Num | None = None


class _Spreader(Table):
    length: Num
    top: list[_TopLeg]
    weight: Num = 0.0
    EA: Num | None = None


class _Sling(Table):
    legs: list[_Leg]
    spreader: _Spreader | None = None
    equalised: Annotated[bool, Strict()] = False


class _Crane(Table):
    lug: Text | None = None
    name: Text | None = None
    sling: _Sling | None = None
    tip: Point | None = None
    boom_height: Num | None = None
    rope_length: Num | None = None
    swl: Num | None = None
    EA: Num | None = None


class _Attitude(Table):
    heel: Num = 0.0
    trim: Num = 0.0
    yaw: Num = 0.0
    lift_height: Num = 0.0


class _Redundant(Table):
    lug: Text
    tension: Num


class _Analysis(Table):
    # Literal of a tuple of names: Python expands it at run time, a static checker cannot
    model: Literal[MODELS] | None = None  # type: ignore[valid-type]
    redundant: _Redundant | list[_Redundant] | None = None
    hull: Literal[HULL_MODELS] = "auto"  # type: ignore[valid-type]


class _Water(Table):
    density: Num = 1.025
    level: Num = 0.0


class _Box(Table):
    min: Point
    max: Point


class _Opening(Table):
    area: Num  # m2; inf drains at once
    at: Point  # body, file frame
    discharge: Num = DISCHARGE


class _Compartment(Table):
    name: Text
    box: _Box
    contents: Literal["air", "water"] = "air"
    openings: list[_Opening] = []


class _Hull(Table):
    box: _Box | None = None
    mesh: Text | None = None
    flooding: Literal["intact", "flooded"] = "intact"
    steel_density: Num | None = None
    weight_in_water: Num | None = None
    compartments: list[_Compartment] = []
    EI: list[Pair] | None = None  # [x m, t m2]: the hull girder's bending stiffness
    GJ: list[Pair] | None = None  # [x m, t m2]: its torsional stiffness


class _Breakout(Table):
    factor: Num | None = None
    shear_strength: Num | None = None  # kPa
    area: Num | None = None  # m2
    bearing_factor: Num = Breakout.bearing_factor
    pull_time: Num | None = None  # h
    embedded_time: Num | None = None  # h
    clear: Num = Breakout.clear  # m


class _Ground(Table):
    contact: Point
    friction: Num | None = None
    breakout: _Breakout | None = None


class _Rigging(Table):
    min_sling_angle: Num = RiggingLimits.min_sling_angle


class _Strength(Table):
    bending_moment: list[Pair] | None = None  # [x m, t m]
    shear_force: list[Pair] | None = None  # [x m, t]


class _SceneFile(Table):
    name: Text = ""
    frame: Literal["z-up", "choi"] = "z-up"
    body: _Body
    lugs: list[_Lug] = []
    ropes: _Ropes = _Ropes()
    cranes: list[_Crane] = []
    attitude: _Attitude = _Attitude()
    analysis: _Analysis = _Analysis()
    water: _Water | None = None
    hull: _Hull | None = None
    ground: _Ground | None = None
    rigging: _Rigging = _Rigging()
    strength: _Strength | None = None


# Tables of a planning scene (read by liftplan.planner.problem.file; [rules] by model.rules.table).
PLAN_TABLES = ("candidates", "plan", "crane", "rules")


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
    lugs = [Lug(name=lug.name, at=to_zup(lug.at)) for lug in data.lugs]
    cranes = [_to_crane(c, data, to_zup) for c in data.cranes]
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
    )


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


def _to_crane(c, data, to_zup):
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
    )


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
