"""docs/scene-files.md against the validation schemas, so the key reference cannot drift.

The schemas are the pydantic tables that read the files (``Table`` subclasses in
model/scene/file.py, planner/problemfile.py, planner/study.py and the tables they nest).
Walking them gives every key path: ``plan.tolerance.heel`` for a nested table,
``lugs[].name`` for a key of each table of an array of tables (``[[lugs]]``), and
``x.*.key`` for a table of tables whose names the user chooses. The doc has one section per
file kind (``## Scene files``, ``## Planning files``, ``## Study files``) whose tables list
one key path per row, in backticks in the first column, with a ``default`` column.

Checked, per file kind: every schema key is documented and every documented key exists;
the default column says ``required`` exactly for the required keys and shows the schema's
default (as a TOML value in backticks) for scalar and array defaults; every allowed value
of a choice (``Literal``) appears in its row; and each section's complete example files
(the ```toml blocks under "### Example" headings) are read without error by the real reader.
"""

from __future__ import annotations

import re
import tomllib
import types
import typing

import pytest
from helpers import ROOT
from pydantic import BaseModel

from liftplan.model.scene.file import _SceneFile, loads_scene
from liftplan.planner.batch.study import _StudyFile, loads_study
from liftplan.planner.problem.file import _PlanFile, loads_problem

DOC = ROOT / "docs" / "scene-files.md"
EXAMPLES = ROOT / "examples"

SECTIONS = {
    "Scene files": (_SceneFile, lambda text: loads_scene(text, base=EXAMPLES)),
    "Planning files": (_PlanFile, loads_problem),
    "Study files": (_StudyFile, lambda text: loads_study(text, base=EXAMPLES, stem="doc")),
}
ROW = re.compile(r"^\|\s*`([^`]+)`\s*\|(.*)\|\s*$")
REQUIRED = object()


# -- the schemas -----------------------------------------------------------------------------


def _branches(annotation):
    """The alternatives of a type, with Annotated and None removed."""
    if typing.get_origin(annotation) is typing.Annotated:
        return _branches(typing.get_args(annotation)[0])
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        return [b for arg in typing.get_args(annotation) for b in _branches(arg)]
    return [] if annotation is type(None) else [annotation]


def _is_table(node):
    return isinstance(node, type) and issubclass(node, BaseModel)


def _nested(annotation):
    """(table type, separator) for each table a key's value may hold: ``.`` for a table,
    ``[].`` for an array of tables, ``.*.`` for a table of named tables. A table that may
    also be given as an array (``redundant``) is listed once, as a table."""
    found = {}
    for branch in _branches(annotation):
        origin, args = typing.get_origin(branch), typing.get_args(branch)
        if _is_table(branch):
            found[branch] = "."
        elif origin in (list, tuple) and args:
            for inner in _branches(args[0]):
                if _is_table(inner):
                    found.setdefault(inner, "[].")
        elif origin is dict and len(args) == 2:
            for inner in _branches(args[1]):
                if _is_table(inner):
                    found.setdefault(inner, ".*.")
    return found.items()


def schema_keys(model, prefix=""):
    """{key path: pydantic FieldInfo} of a table and every table it nests."""
    out = {}
    for name, field in model.model_fields.items():
        path = prefix + (field.alias or name)
        out[path] = field
        for table, sep in _nested(field.annotation):
            out.update(schema_keys(table, path + sep))
    return out


def default(field):
    if field.is_required():
        return REQUIRED
    return field.default


def choices(annotation):
    """Allowed values of a Literal (through Optional and Annotated), else ()."""
    out = []
    for branch in _branches(annotation):
        if typing.get_origin(branch) is typing.Literal:
            out.extend(typing.get_args(branch))
    return tuple(out)


# -- the doc ---------------------------------------------------------------------------------


def doc_sections():
    """{section: (text, {key path: (line number, {column: cell})})} of the doc."""
    lines = DOC.read_text(encoding="utf-8").splitlines()
    sections, current, header = {}, None, None
    for number, line in enumerate(lines, start=1):
        if line.startswith("## "):
            title = line[3:].strip()
            current = next((s for s in SECTIONS if title.startswith(s)), None)
            if current is not None:
                sections[current] = ([], {})
            continue
        if current is None:
            continue
        sections[current][0].append(line)
        if line.startswith("|") and not ROW.match(line):
            cells = [c.strip().lower() for c in line.strip().strip("|").split("|")]
            if cells and cells[0] == "key":
                header = cells
            continue
        match = ROW.match(line)
        if match:
            key = match.group(1)
            cells = [c.strip() for c in match.group(2).split("|")]
            rows = sections[current][1]
            assert key not in rows, f"docs/scene-files.md:{number}: `{key}` is listed twice"
            rows[key] = (number, dict(zip(header[1:], cells, strict=False)), line)
    return {name: ("\n".join(text), rows) for name, (text, rows) in sections.items()}


@pytest.fixture(scope="module")
def doc():
    return doc_sections()


def test_every_file_kind_has_a_section(doc):
    assert set(doc) == set(SECTIONS)


@pytest.mark.parametrize("section", SECTIONS)
def test_every_schema_key_is_documented(doc, section):
    keys = schema_keys(SECTIONS[section][0])
    missing = sorted(set(keys) - set(doc[section][1]))
    assert not missing, (
        f"keys read by the {section.lower()} reader but missing from "
        f"docs/scene-files.md '## {section}': {', '.join(missing)}"
    )


@pytest.mark.parametrize("section", SECTIONS)
def test_every_documented_key_exists(doc, section):
    keys = schema_keys(SECTIONS[section][0])
    unknown = sorted(set(doc[section][1]) - set(keys))
    assert not unknown, (
        f"docs/scene-files.md '## {section}' documents keys that the reader "
        f"does not accept: {', '.join(unknown)}"
    )


def _toml_value(literal):
    try:
        return tomllib.loads(f"v = {literal}")["v"]
    except tomllib.TOMLDecodeError:
        return REQUIRED  # never equal to a default


def _same(doc_value, value):
    if isinstance(value, tuple | list):
        return (
            isinstance(doc_value, list)
            and len(doc_value) == len(value)
            and all(_same(d, v) for d, v in zip(doc_value, value))
        )
    if isinstance(value, bool) or isinstance(doc_value, bool):
        return doc_value is value
    return doc_value == value


@pytest.mark.parametrize("section", SECTIONS)
def test_defaults_match_the_schema(doc, section):
    keys = schema_keys(SECTIONS[section][0])
    wrong = []
    for key, (line, cells, _) in doc[section][1].items():
        if key not in keys:
            continue  # reported by test_every_documented_key_exists
        assert "default" in cells, f"docs/scene-files.md:{line}: the table has no 'default' column"
        cell = cells["default"]
        value = default(keys[key])
        if value is REQUIRED or cell.lower().startswith("required"):
            if (value is REQUIRED) != cell.lower().startswith("required"):
                says = "requires" if value is REQUIRED else "does not require"
                wrong.append(f"line {line} `{key}`: the schema {says} it, the doc says {cell!r}")
        elif isinstance(value, bool | int | float | str | tuple | list) and not (
            isinstance(value, tuple | list) and any(isinstance(v, BaseModel) for v in value)
        ):
            shown = re.findall(r"`([^`]+)`", cell)
            if not any(_same(_toml_value(s), value) for s in shown):
                wrong.append(f"line {line} `{key}`: default {value!r}, doc says {cell!r}")
    assert not wrong, "docs/scene-files.md defaults differ from the schema:\n" + "\n".join(wrong)


@pytest.mark.parametrize("section", SECTIONS)
def test_every_choice_is_listed(doc, section):
    keys = schema_keys(SECTIONS[section][0])
    missing = []
    for key, (line, _, text) in doc[section][1].items():
        for value in choices(keys[key].annotation) if key in keys else ():
            shown = f'`"{value}"`' if isinstance(value, str) else f"`{value}`"
            if shown not in text:
                missing.append(f"line {line} `{key}`: {shown}")
    assert not missing, "choices not listed in docs/scene-files.md: " + ", ".join(missing)


def examples(text):
    """The ```toml blocks under the '### Example...' headings of a section's text."""
    out = []
    for part in re.split(r"^### ", text, flags=re.MULTILINE)[1:]:
        if part.startswith("Example"):
            out.extend(re.findall(r"^```toml\n(.*?)^```", part, re.MULTILINE | re.DOTALL))
    return out


@pytest.mark.parametrize("section", SECTIONS)
def test_the_sections_example_files_are_valid(doc, section):
    found = examples(doc[section][0])
    assert found, f"docs/scene-files.md '## {section}' has no '### Example' with a ```toml block"
    for text in found:
        SECTIONS[section][1](text)  # raises InvalidScene with the key if an example is wrong


def test_the_walk_sees_nested_tables_and_arrays():
    # guards the walker itself: a table, an array of tables and a table inside an array
    scene = schema_keys(_SceneFile)
    assert {
        "body.weight",
        "lugs[].name",
        "hull.compartments[].box.min",
        "analysis.redundant.lug",
        "ground.contact",
    } <= set(scene)
    plan = schema_keys(_PlanFile)
    assert {"plan.tolerance.heel", "candidates[].at", "crane.boom_height.min"} <= set(plan)
    assert {"study.problem", "sweep", "sample.count"} <= set(schema_keys(_StudyFile))
