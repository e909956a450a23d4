"""The key tables of docs/scene-files.md, generated from the readers' schemas.

The schemas are the pydantic tables that read the files: ``_SceneFile``
(model/scene/file.py), ``_PlanFile`` (planner/problem/file.py), ``_StudyFile``
(planner/batch/study.py) and the tables they nest. Each key is declared with ``Key``, which
holds its documentation (model/scene/file.py's module docstring gives the convention). Walking
the schemas gives every key path: ``plan.tolerance.heel`` for a nested table, ``lugs[].name``
for a key of each table of an array of tables (``[[lugs]]``), ``x.*.key`` for a table of
tables whose names the user chooses.

The page marks where each table goes, naming the file kind and the top-level keys it lists
(each with every key it nests)::

    <!-- keys: scene ropes cranes rigging -->
    (the generated table)
    <!-- /keys -->

Every top-level key of a schema is in exactly one table. Everything outside the marks is
hand-written and kept as it is. The committed page holds the generated tables, so it also reads
right on GitHub; tests/project/test_docs.py checks that regenerating it changes nothing.

Run from anywhere::

    python docs/_hooks/file_reference.py --write   # regenerate the tables in the page
    python docs/_hooks/file_reference.py --check   # exit 1 when the page is out of date

As a mkdocs hook (mkdocs.yml ``hooks``) it builds the page with freshly generated tables and
warns (an error with ``--strict``) when the committed page differs from them.
"""

from __future__ import annotations

import argparse
import json
import logging
import re
import sys
import types
import typing
from pathlib import Path

from pydantic import BaseModel

from liftplan.model.scene.file import _SceneFile
from liftplan.model.sequence.file import _SequenceFile
from liftplan.planner.batch.study import _StudyFile
from liftplan.planner.problem.file import _PlanFile

PAGE = Path(__file__).resolve().parents[1] / "scene-files.md"
SCHEMAS = {"scene": _SceneFile, "plan": _PlanFile, "study": _StudyFile, "sequence": _SequenceFile}
COLUMNS = ("key", "type", "unit", "default", "frame", "meaning", "example")
BLOCK = re.compile(r"^<!-- keys: (\w+)((?: \w+)+) -->$(.*?)^<!-- /keys -->$", re.MULTILINE | re.DOTALL)
COMMAND = "python docs/_hooks/file_reference.py --write"
BASE_TYPES = {bool: "boolean", str: "string", float: "number", int: "integer"}
EMPTY = "—"  # a cell with nothing to say; as a default: absent means not given

log = logging.getLogger("mkdocs.hooks.file_reference")


# -- the schemas -----------------------------------------------------------------------------


def branches(annotation):
    """The alternatives of a type, with Annotated and None removed."""
    if typing.get_origin(annotation) is typing.Annotated:
        return branches(typing.get_args(annotation)[0])
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        return [b for arg in typing.get_args(annotation) for b in branches(arg)]
    return [] if annotation is type(None) else [annotation]


def is_table(node):
    return isinstance(node, type) and issubclass(node, BaseModel)


def nested(annotation):
    """(table type, separator) for each table a key's value may hold: ``.`` for a table,
    ``[].`` for an array of tables, ``.*.`` for a table of named tables. A table that may
    also be given as an array (``redundant``) is listed once, as a table."""
    found = {}
    for branch in branches(annotation):
        origin, args = typing.get_origin(branch), typing.get_args(branch)
        if is_table(branch):
            found[branch] = "."
        elif origin in (list, tuple) and args:
            for inner in branches(args[0]):
                if is_table(inner):
                    found.setdefault(inner, "[].")
        elif origin is dict and len(args) == 2:
            for inner in branches(args[1]):
                if is_table(inner):
                    found.setdefault(inner, ".*.")
    return found.items()


def schema_keys(model, prefix="", names=None):
    """{key path: pydantic FieldInfo} of a table and every table it nests, in schema order
    (``names``: only these top-level keys, in this order)."""
    out = {}
    for name in model.model_fields if names is None else names:
        field = model.model_fields[name]
        path = prefix + (field.alias or name)
        out[path] = field
        for table, sep in nested(field.annotation):
            out.update(schema_keys(table, path + sep))
    return out


def choices(annotation):
    """Allowed values of a Literal (through Optional and Annotated), else ()."""
    out = []
    for branch in branches(annotation):
        if typing.get_origin(branch) is typing.Literal:
            out.extend(typing.get_args(branch))
    return tuple(out)


def holds_number(annotation):
    """Whether a key's value may hold a number (not a choice; a table's keys have their own)."""
    return any(
        branch in (float, int) or any(holds_number(arg) for arg in typing.get_args(branch))
        for branch in branches(annotation)
        if typing.get_origin(branch) is not typing.Literal
    )


# -- the cells -------------------------------------------------------------------------------


def notes(field):
    """What ``Key`` noted of a key besides its description (unit, values, frame, absent, example)."""
    return field.json_schema_extra or {}


def toml(value):
    """A default as TOML (what a user would write to give it)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, tuple | list):
        return "[" + ", ".join(toml(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{toml(k)} = {toml(v)}" for k, v in value.items()) + " }" if value else "{}"
    return repr(value)


def _either(texts):
    """'a', 'a or b', 'a, b or c'."""
    return texts[0] if len(texts) == 1 else ", ".join(texts[:-1]) + " or " + texts[-1]


def _type_name(node):
    """The type of one alternative, or None when the annotation cannot name it."""
    origin, args = typing.get_origin(node), typing.get_args(node)
    if is_table(node):
        return "table"
    if node in BASE_TYPES:
        return BASE_TYPES[node]
    if origin is tuple and len(args) == 3 and all(branches(a) == [float] for a in args):
        return "[x, y, z]"
    if origin is list:
        inner = "tables" if is_table(args[0]) else _type_name(args[0])
        return None if inner is None else f"array of {inner}"
    return None


def type_cell(path, field):
    """The allowed values: a choice's, listed; else ``values``, else named from the annotation."""
    values = notes(field).get("values")
    listed = choices(field.annotation)
    if listed:
        if values is not None:
            raise ValueError(f"{path}: a choice lists its values from the annotation; give no values=")
        return _either([f"`{toml(v)}`" for v in listed])
    if values is not None:
        return values
    names = [_type_name(b) for b in branches(field.annotation)]
    if None in names:
        raise ValueError(f"{path}: the annotation does not name its type; give Key(values=...)")
    return ", or ".join(names)


def unit_cell(path, field):
    """The unit of a key's numbers (``—``: none, or no number)."""
    unit = notes(field).get("unit")
    if holds_number(field.annotation) and unit is None:
        raise ValueError(f"{path}: a number with no unit; give Key(unit=...) ('-' for none)")
    if unit is not None and not holds_number(field.annotation):
        raise ValueError(f"{path}: holds no number, but gives unit={unit!r}")
    return EMPTY if unit in (None, "-") else unit


def default_cell(field):
    """``required``; ``all defaults`` for a table; else the default in backticks (``—``:
    absent means not given) and what absent means."""
    if field.is_required():
        return "required"
    absent = notes(field).get("absent")
    if isinstance(field.default, BaseModel):
        shown = "all defaults"
    else:
        shown = EMPTY if field.default is None else f"`{toml(field.default)}`"
    return shown if absent is None else f"{shown} ({absent})"


def row(path, field):
    """One key's row of a table (Markdown, the cells' pipes escaped)."""
    if not field.description:
        raise ValueError(f"{path}: no description; declare it with Key(doc=...)")
    example = notes(field).get("example")
    cells = (
        f"`{path}`",
        type_cell(path, field),
        unit_cell(path, field),
        default_cell(field),
        notes(field).get("frame", EMPTY),
        field.description,
        EMPTY if example is None else f"`{example}`",
    )
    return "| " + " | ".join(cell.replace("|", "\\|") for cell in cells) + " |"


def table(model, names):
    """The Markdown table of the given top-level keys of a schema and the keys they nest."""
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    lines += [row(path, field) for path, field in schema_keys(model, names=names).items()]
    return "\n".join(lines)


# -- the page --------------------------------------------------------------------------------


def render(page):
    """The page with every marked table generated afresh from the schemas.

    Raises
    ------
    ValueError
        A mark names an unknown file kind or key, a top-level key is in no table or in two,
        or a key is not documented (no description, a number without unit).
    """
    placed = {kind: [] for kind in SCHEMAS}

    def fill(match):
        kind, names = match[1], match[2].split()
        if kind not in SCHEMAS:
            raise ValueError(f"<!-- keys: {kind} ...: expected one of {', '.join(SCHEMAS)}")
        unknown = [n for n in names if n not in SCHEMAS[kind].model_fields]
        if unknown:
            raise ValueError(f"<!-- keys: {kind} ...: {', '.join(unknown)} not in the {kind} file's schema")
        placed[kind] += names
        return f"<!-- keys: {kind} {' '.join(names)} -->\n\n{table(SCHEMAS[kind], names)}\n\n<!-- /keys -->"

    out = BLOCK.sub(fill, page)
    for kind, model in SCHEMAS.items():
        missing = [n for n in model.model_fields if n not in placed[kind]]
        twice = sorted({n for n in placed[kind] if placed[kind].count(n) > 1})
        if missing or twice:
            raise ValueError(
                f"docs/scene-files.md: {kind} keys in no table: {', '.join(missing) or 'none'}; "
                f"in two: {', '.join(twice) or 'none'}"
            )
    return out


def on_page_markdown(markdown, page, config, files):
    """mkdocs hook: the file reference with its tables generated from the schemas."""
    if page.file.src_uri != PAGE.name:
        return markdown
    fresh = render(markdown)
    if fresh != markdown:
        log.warning(f"docs/{PAGE.name}: its key tables differ from the schemas; run {COMMAND}")
    return fresh


def main(argv=None):
    parser = argparse.ArgumentParser(description=f"Generate the key tables of docs/{PAGE.name}.")
    action = parser.add_mutually_exclusive_group(required=True)
    action.add_argument("--write", action="store_true", help="regenerate the tables in the page")
    action.add_argument("--check", action="store_true", help="exit 1 when the page is out of date")
    args = parser.parse_args(argv)
    page = PAGE.read_text(encoding="utf-8")
    fresh = render(page)
    if args.check:
        if fresh != page:
            print(f"docs/{PAGE.name} is out of date: run {COMMAND}", file=sys.stderr)
            return 1
        return 0
    PAGE.write_text(fresh, encoding="utf-8")
    print(f"docs/{PAGE.name}: {'rewritten' if fresh != page else 'already up to date'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
