"""docs/scene-files.md against the validation schemas, so the key reference cannot drift.

The page's key tables are generated from the schemas (the pydantic tables that read the
files, each key declared with its documentation by ``Key``) by docs/_hooks/file_reference.py,
between ``<!-- keys: ... -->`` marks; the prose around them is hand-written. Checked: the
committed page is what the generator gives, byte for byte (else: ``python
docs/_hooks/file_reference.py --write``), and the generator refuses a key without a description
or a number without a unit. The page's own tables are read back as before, which checks the
rendering independently: one section per file kind (``## Scene files``, ``## Planning files``,
``## Study files``) whose tables list one key path per row, in backticks in the first column,
with a ``default`` column; every schema key is documented and every documented key exists, the
default column says ``required`` exactly for the required keys and shows the schema's default
(as a TOML value in backticks), every allowed value of a choice (``Literal``) appears in its
row; and each section's complete example files (the ```toml blocks under "### Example"
headings) are read without error by the real reader.
"""

from __future__ import annotations

import difflib
import importlib.util
import re
import tomllib

import pytest
from helpers import ROOT
from pydantic import BaseModel

from liftplan.model.scene.file import Key, Num, Table, _SceneFile, loads_scene
from liftplan.model.sequence.file import _SequenceFile, loads_sequence
from liftplan.planner.batch.study import _StudyFile, loads_study
from liftplan.planner.problem.file import _PlanFile, loads_problem

DOC = ROOT / "docs" / "scene-files.md"
EXAMPLES = ROOT / "examples"
GENERATOR = ROOT / "docs" / "_hooks" / "file_reference.py"

SECTIONS = {
    "Scene files": (_SceneFile, lambda text: loads_scene(text, base=EXAMPLES)),
    "Planning files": (_PlanFile, loads_problem),
    "Study files": (_StudyFile, lambda text: loads_study(text, base=EXAMPLES, stem="doc")),
    "Sequence files": (_SequenceFile, loads_sequence),
}
ROW = re.compile(r"^\|\s*`([^`]+)`\s*\|(.*)\|\s*$")
REQUIRED = object()


def _generator():
    spec = importlib.util.spec_from_file_location("file_reference", GENERATOR)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


reference = _generator()
schema_keys = reference.schema_keys


def default(field):
    if field.is_required():
        return REQUIRED
    return field.default


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


def test_the_page_is_what_the_schemas_give():
    page = DOC.read_text(encoding="utf-8")
    fresh = reference.render(page)
    diff = "\n".join(
        difflib.unified_diff(page.splitlines(), fresh.splitlines(), "committed", "generated", n=0)
    )
    assert fresh == page, f"docs/scene-files.md is out of date: run {reference.COMMAND}\n{diff[:4000]}"


def test_an_undocumented_key_is_refused():
    class Bare(Table):
        weight: Num = Key(1.0, doc="a weight")  # a number with no unit

    class Silent(Table):
        name: str = ""  # no description

    with pytest.raises(ValueError, match="weight: a number with no unit"):
        reference.table(Bare, ["weight"])
    with pytest.raises(ValueError, match="name: no description"):
        reference.table(Silent, ["name"])


def test_every_top_level_key_has_a_table():
    page = DOC.read_text(encoding="utf-8")
    mark = "<!-- keys: scene ropes cranes rigging -->"
    assert mark in page
    page = page.replace(mark, "<!-- keys: scene ropes cranes -->")
    with pytest.raises(ValueError, match="scene keys in no table: rigging"):
        reference.render(page)


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
        for value in reference.choices(keys[key].annotation) if key in keys else ():
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


def test_every_file_table_is_complete_when_imported():
    """A table that names a later table (a forward reference) is only resolved by pydantic on
    its first validation, so the file reference would differ with what ran before it in the
    same process (it did: a crane vessel's `box`). Checked in a fresh interpreter."""
    import subprocess
    import sys

    script = """
import typing
from pydantic import BaseModel
from liftplan.model.scene.file import _SceneFile
from liftplan.model.sequence.file import _SequenceFile
from liftplan.planner.batch.study import _StudyFile
from liftplan.planner.problem.file import _PlanFile

seen, todo, bad = set(), [_SceneFile, _PlanFile, _StudyFile, _SequenceFile], []
while todo:
    model = todo.pop()
    if model in seen:
        continue
    seen.add(model)
    if not model.__pydantic_complete__:
        bad.append(model.__name__)
        continue
    for field in model.model_fields.values():
        stack = [field.annotation]
        while stack:
            a = stack.pop()
            if isinstance(a, type) and issubclass(a, BaseModel):
                todo.append(a)
            stack.extend(typing.get_args(a))
print(" ".join(sorted(bad)))
"""
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"tables with unresolved annotations at import: {out.stdout.strip()}"
