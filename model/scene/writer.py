"""Write a :class:`~liftplan.model.scene.objects.Scene` as a scene file (TOML): the one writer.

:func:`scene_toml` is the inverse of :func:`~liftplan.model.scene.file.loads_scene` for a body
in air: ``loads_scene(scene_toml(scene)) == scene``. Coordinates are written in the frame the
scene carries (``scene.frame``; the scene itself is always ``z-up``), numbers at full
precision (``repr``), so the file reads back to the same floats. The attitude is written
whole; an optional key the scene leaves at the reader's default (a crane's missing
``tip``, ``analysis.hull = "auto"``, a sling that is not ``equalised``, the ``[rigging]``
limits of a scene without slings, an empty ``name``) is left out, and reads back the same.

What it writes: ``name``, ``frame``, ``[body]`` (weight, cog, weight_curve), ``[[lugs]]``,
``[[cranes]]`` (lug or sling, name, boom_height, rope_length, EA, swl, tip, vessel; a sling's legs,
spreader bar and ``equalised``), ``[attitude]``, ``[analysis]`` (model, redundant tensions,
hull), ``[rigging]``, ``[strength]`` and the hull girder's stiffness (``[hull] EI``, ``GJ``).

What it refuses (:class:`~liftplan.model.errors.InvalidScene`, one line naming the part): a
hull mesh or box, water and a ground contact (and so compartments and their openings). A
:class:`~liftplan.model.scene.hull.Hull` holds triangles, not the box or the STL file it was
made from, so it cannot be written back as the file that made it; the scenes of lift plans
never have one.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence

from liftplan.model.errors import InvalidScene
from liftplan.model.frames import zup_to_choi
from liftplan.model.scene.objects import Analysis, Scene
from liftplan.model.scene.rigging_gear import RiggingLimits

_ANALYSIS, _RIGGING = Analysis(), RiggingLimits()


def scene_toml(scene: Scene, header: Sequence[str] = (), crane_notes: Mapping[str, str] | None = None) -> str:
    """A scene as the text of a scene file that reads back to it.

    Parameters
    ----------
    scene : Scene
        A body in air (no ``hull`` mesh or box, ``water`` or ``ground``).
    header : sequence of str
        Comment lines written first, each prefixed ``# `` (a line holding newlines becomes
        several comment lines).
    crane_notes : mapping of str to str, optional
        A comment written after a crane's ``[[cranes]]`` header, keyed by the crane's label
        (its lug, or its name with a sling); one line each.

    Returns
    -------
    str
        TOML in the frame ``scene.frame``: lengths in m, forces in t, EA in t, angles in deg,
        sling diameters in mm; ``loads_scene`` of it equals ``scene``.

    Raises
    ------
    InvalidScene
        The scene has a hull mesh or box, water or a ground contact (named), or a name that
        cannot be written as UTF-8 text.
    """
    _refuse_unwritable(scene)
    vec = _vector if scene.frame == "z-up" else (lambda values: _vector(zup_to_choi(values)))
    lines = [f"# {part}".rstrip() for line in header for part in _comment(line).split("\n")]
    if scene.name:
        lines.append(f"name = {_string(scene.name)}")
    lines.append(f"frame = {_string(scene.frame)}")
    body = scene.body
    lines += ["", "[body]", f"weight = {_number(body.weight)}", f"cog = {vec(body.cog)}"]
    if body.weight_curve is not None:
        lines.append(f"weight_curve = {_pairs(body.weight_curve)}")
    if scene.strength is not None:
        lines += ["", "[strength]"]
        for key in ("bending_moment", "shear_force"):
            curve = getattr(scene.strength, key)
            if curve is not None:
                lines.append(f"{key} = {_pairs(curve)}")
    if scene.girder is not None:
        lines += ["", "[hull]", f"EI = {_pairs(scene.girder.EI)}"]
        if scene.girder.GJ is not None:
            lines.append(f"GJ = {_pairs(scene.girder.GJ)}")
    for lug in scene.lugs:
        lines += ["", "[[lugs]]", f"name = {_string(lug.name)}", f"at = {vec(lug.at)}"]
        for key in ("capacity", "capacity_out_of_plane"):
            if getattr(lug, key) is not None:
                lines.append(f"{key} = {_number(getattr(lug, key))}")
        if lug.normal is not None:
            lines.append(f"normal = {vec(lug.normal)}")
    notes = crane_notes or {}
    for crane in scene.cranes:
        note = notes.get(crane.label)
        title = "[[cranes]]" if note is None else f"[[cranes]]                   # {_comment(note, ' ')}"
        lines += ["", title, *_crane(crane, vec, scene.frame)]
    lines += ["", "[attitude]", *_attitude(scene.attitude)]
    analysis = _analysis(scene.analysis)
    if analysis:
        lines += ["", "[analysis]", *analysis]
    if scene.slings or scene.rigging != _RIGGING:
        lines += ["", "[rigging]", f"min_sling_angle = {_number(scene.rigging.min_sling_angle)}"]
    if scene.wind is not None:
        lines += ["", "[wind]", *_wind(scene.wind, scene.frame)]
    if scene.tide is not None:
        lines += ["", "[tide]", f"table = {_pairs(scene.tide.table)}"]
        if scene.tide.time is not None:
            lines.append(f"time = {_number(scene.tide.time)}")
    return "\n".join(lines) + "\n"


def _refuse_unwritable(scene):
    """One line naming the first part the writer cannot write faithfully."""
    for part, value in (("water", scene.water), ("ground", scene.ground), ("hull", scene.hull)):
        if value is not None:
            raise InvalidScene(
                f"[{part}]: a scene with a hull mesh or box, water or a ground contact cannot be "
                "written as a scene file (a hull is kept as triangles, not as the file that made it); "
                "expected a body in air"
            )


def _crane(crane, vec, frame):
    lines = []
    if crane.name is not None:
        lines.append(f"name = {_string(crane.name)}")
    if crane.lug is not None:
        lines.append(f"lug = {_string(crane.lug)}")
    for key in ("boom_height", "rope_length", "EA", "swl"):
        value = getattr(crane, key)
        if value is not None:
            lines.append(f"{key} = {_number(value)}")
    if crane.tip is not None:
        lines.append(f"tip = {vec(crane.tip)}")
    if crane.vessel is not None:
        lines.append(f"vessel = {_vessel(crane.vessel, frame)}")
    sling = crane.sling
    if sling is None:
        return lines
    if sling.equalised:
        lines += ["", "[cranes.sling]", "equalised = true"]
    for leg in sling.legs:
        lines += ["", "[[cranes.sling.legs]]", f"lug = {_string(leg.lug)}", *_leg(leg)]
        if leg.end is not None:
            lines.append(f"end = {int(leg.end)}")
    bar = sling.spreader
    if bar is not None:
        lines += ["", "[cranes.sling.spreader]", f"length = {_number(bar.length)}"]
        lines += [f"weight = {_number(bar.weight)}", f"EA = {_number(bar.EA)}"]
        for leg in bar.top:
            lines += ["", "[[cranes.sling.spreader.top]]", *_leg(leg)]
    return lines


def _vessel(vessel, frame):
    """A crane's vessel as an inline table in the file's frame (or the shared vessel's name)."""
    if isinstance(vessel, str):
        return _string(vessel)
    if vessel.hull is not None:  # its hull, cog and origin: refused, as the lifted hull is
        raise InvalidScene(
            "cranes.vessel: a vessel given by her hull (mesh or box) cannot be written as a scene file "
            "(a hull is kept as triangles, not as the file that made it); expected a small-angle vessel"
        )
    flotation, heading = vessel.flotation, vessel.heading
    if frame == "choi":  # (x, y port) -> (x, z starboard); the heading turns the other way
        flotation, heading = (flotation[0], 0.0 - flotation[1]), 0.0 - heading
    items = [
        f"{key} = {_number(getattr(vessel, key))}"
        for key in ("displacement", "waterplane_area", "gm_t", "gm_l")
    ]
    items += [f"flotation = {_vector(flotation)}", f"heading = {_number(heading)}"]
    items += [f"density = {_number(vessel.density)}", f"ballast = {_vector(vessel.ballast)}"]
    items += [
        f"{key} = {_number(getattr(vessel, key))}"
        for key in ("max_heel", "max_trim", "freeboard", "min_freeboard", "beam", "length")
        if getattr(vessel, key) is not None
    ]
    return "{ " + ", ".join(items) + " }"


def _wind(wind, frame):
    """``[wind]`` in the file's frame (the direction turns the other way in ``choi``)."""
    direction = 0.0 - wind.direction if frame == "choi" else wind.direction
    lines = [
        f"speed = {_number(wind.speed)}",
        f"direction = {_number(direction)}",
        f"density = {_number(wind.density)}",
    ]

    def area(a):
        return f"area = {_number(a.area)}, cd = {_number(a.cd)}, height = {_number(a.height)}"

    if wind.body is not None:
        lines.append(f"body = {{ {area(wind.body)} }}")
    if wind.booms:
        rows = ", ".join(f"{{ crane = {_string(b.crane)}, {area(b)} }}" for b in wind.booms)
        lines.append(f"booms = [{rows}]")
    return lines


def _leg(leg):
    """A leg's length and its stiffness as given (EA in t or diameter in mm)."""
    stiffness = f"EA = {_number(leg.EA)}" if leg.EA is not None else f"diameter = {_number(leg.diameter)}"
    return [f"length = {_number(leg.length)}", stiffness]


def _attitude(attitude):
    return [f"{key} = {_number(getattr(attitude, key))}" for key in ("lift_height", "heel", "trim", "yaw")]


def _analysis(analysis):
    lines = []
    if analysis.model is not None:
        lines.append(f"model = {_string(analysis.model)}")
    if analysis.redundant:
        lines.append("redundant = [")
        lines += [
            f"    {{ lug = {_string(r.lug)}, tension = {_number(r.tension)} }}," for r in analysis.redundant
        ]
        lines.append("]")
    if analysis.hull != _ANALYSIS.hull:
        lines.append(f"hull = {_string(analysis.hull)}")
    return lines


def _number(value):
    """A float at full precision (``repr`` reads back to the same float; TOML takes its form)."""
    return repr(float(value))


def _vector(values):
    return "[" + ", ".join(_number(v) for v in values) + "]"


def _pairs(values):
    return "[" + ", ".join(f"[{_number(a)}, {_number(b)}]" for a, b in values) + "]"


def _string(text):
    """A TOML basic string: JSON's escapes (which TOML shares) and DEL, which TOML escapes and
    JSON does not; text that is not Unicode (a lone surrogate) is refused."""
    try:
        str(text).encode("utf-8")
    except UnicodeEncodeError:
        raise InvalidScene(
            f"{text!r}: not writable as UTF-8 text; expected a name of Unicode characters"
        ) from None
    return json.dumps(str(text), ensure_ascii=False).replace("\x7f", "\\u007f")


def _comment(text, newline="\n"):
    """Text a TOML comment may hold: line breaks as ``newline``, other control characters
    (which TOML refuses in a comment) and what is not Unicode (a lone surrogate) as spaces."""
    lines = str(text).splitlines() or [""]
    return newline.join(
        "".join(" " if _control(ch) or 0xD800 <= ord(ch) <= 0xDFFF else ch for ch in line) for line in lines
    )


def _control(ch):
    return ch != "\t" and (ord(ch) < 0x20 or ord(ch) == 0x7F)
