"""The code blocks of the README and of every docs/*.md page work as written.

Every ```python block runs on its own (a fresh namespace: a block that forgets an import
fails), unless its fence says ``not run`` (``python title="...: not run"``, shown on the
site as the block's title: a sketch with values left out). Every command line starting with
``liftplan`` in a ```bash, ```console (after ``$ ``) or plain ``` block is parsed by the
command line's own parser (``a|b|c`` in an option value is the docs' notation for
alternatives: each one is parsed); a command whose files exist (the examples) is also run,
once however many pages show it, except ``batch``, which starts a Dask cluster and is
covered by tests/planner/test_batch.py. A ```console block is a command and its output: the command
is run and must print that output (numbers that differ from run to run, a solve's residual
and a search's seconds, are compared as placeholders). A ```toml block with a ``[study]``
table is read as a study file next to the examples.

Blocks run in a temporary folder holding a copy of ``examples/``, so the pages' relative
paths work and anything a block writes (a report, a figure) lands there, not in the
repository.
"""

from __future__ import annotations

import re
import shlex
import shutil

import pytest
from helpers import ROOT

from liftplan.planner import cli

PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
FENCE = re.compile(r"^```([\w-]*)([^\n]*)\n(.*?)^```", re.MULTILINE | re.DOTALL)
# shell operators between commands on one line (a lone | inside a word is an alternative)
OPERATOR = re.compile(r"\s(?:&&|\|\||;|\|)\s")
PROMPT = "$ "


def _where(page, text, match):
    return f"{page.relative_to(ROOT)}:{text.count(chr(10), 0, match.start()) + 1}"


def blocks(language, *, skipped=False):
    """(page:line, text) of every fenced block tagged ``language`` in the README and docs.

    Blocks whose fence says ``not run`` are left out, or with ``skipped`` the only ones kept.
    """
    out = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for m in FENCE.finditer(text):
            if m.group(1) == language and ("not run" in m.group(2)) == skipped:
                out.append((_where(page, text, m), m.group(3)))
    return out


def _line(where, offset):
    page, line = where.rsplit(":", 1)
    return f"{page}:{int(line) + 1 + offset}"


def commands():
    """Every ``liftplan ...`` command line in the shell blocks, as (page:line, argv, shown)
    with ``shown`` the output a ```console block prints under it (else None)."""
    out = []
    for where, block in blocks("bash") + blocks(""):
        for offset, line in enumerate(block.splitlines()):
            for part in OPERATOR.split(line):
                if part.split()[:1] != ["liftplan"]:
                    continue  # prose in a plain block (the design-load chain's formulas)
                words = shlex.split(part, comments=True)
                if words[:1] == ["liftplan"]:
                    out.append((_line(where, offset), words[1:], None))
    for where, block in blocks("console"):
        first, _, shown = block.partition("\n")
        assert first.startswith(PROMPT), f"{where}: a console block starts with '{PROMPT}command'"
        words = shlex.split(first[len(PROMPT) :])
        assert words[:1] == ["liftplan"], f"{where}: a console block shows a liftplan command"
        out.append((_line(where, 0), words[1:], shown))
    return out


def alternatives(argv):
    """Expand ``--model rigid|elastic`` into one argv per alternative."""
    for i, word in enumerate(argv):
        if "|" in word and not word.startswith("-"):
            return [v for alt in word.split("|") for v in alternatives(argv[:i] + [alt] + argv[i + 1 :])]
    return [argv]


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_the_pages_have_blocks_to_check():
    # a change of fence syntax must not silently turn this file into a no-op
    assert len(blocks("python")) >= 3
    assert len(commands()) >= 40
    assert len(blocks("console")) >= 2
    readme = [c for c in commands() if c[0].startswith("README.md:")]
    assert len(readme) >= 2, "the README shows the set-up command and an example"


def test_few_blocks_are_left_unrun():
    # a sketch is the exception: each one is named here, so another cannot slip in unseen
    assert [where.split(":")[0] for where, _ in blocks("python", skipped=True)] == ["docs/design-loads.md"]


@pytest.mark.parametrize("where, code", [pytest.param(*b, id=b[0]) for b in blocks("python")])
def test_python_block_runs_on_its_own(where, code, workdir):
    exec(compile(code, where, "exec"), {"__name__": "docs_" + re.sub(r"\W", "_", where)})


@pytest.mark.parametrize("where, argv", [pytest.param(c[0], c[1], id=c[0]) for c in commands()])
def test_command_line_parses(where, argv):
    for variant in alternatives(argv):
        try:
            cli._parser().parse_args(variant)
        except SystemExit as err:
            pytest.fail(
                f"{where}: `liftplan {shlex.join(variant)}` is refused by the parser (exit {err.code})"
            )


def runnable():
    """Commands whose file arguments all exist in examples/ (not placeholders like SCENE),
    each once, and not those a console block runs (test_console_block_prints_its_output)."""
    shown = {tuple(argv) for _, argv, output in commands() if output is not None}
    out, seen = [], set(shown)
    for where, argv, output in commands():
        files = [w for w in argv[1:] if w.endswith(".toml")]
        if output is None and argv[0] != "batch" and files and all((ROOT / f).is_file() for f in files):
            for variant in alternatives(argv):
                if tuple(variant) not in seen:
                    seen.add(tuple(variant))
                    out.append((where, variant))
    return out


#: Examples whose command takes more than ~20 s on 2 cores: run with ``-m slow``.
SLOW_EXAMPLES = {
    "examples/hull154_plan.toml",
    "examples/ferry_strength_plan.toml",
    "examples/block_8_points_plan.toml",
}


def _param(where, argv):
    slow = any(w in SLOW_EXAMPLES for w in argv)
    return pytest.param(
        where, argv, id=f"{where}-{'-'.join(argv[:1])}", marks=[pytest.mark.slow] if slow else []
    )


@pytest.mark.parametrize("where, argv", [_param(*c) for c in runnable()])
def test_example_command_runs(where, argv, workdir, capsys):
    code = cli.main(argv)
    err = capsys.readouterr().err
    assert code == 0, f"{where}: `liftplan {shlex.join(argv)}` exited {code}: {err}"


#: What differs between runs of one command: a solve's residual, a search's seconds.
VARIES = [
    (re.compile(r"\b\d(?:\.\d+)?e[-+]\d+\b"), "<small>"),
    (re.compile(r"\(\d+(?:\.\d+)? s\)"), "(<time>)"),
]


def _steady(text):
    for pattern, placeholder in VARIES:
        text = pattern.sub(placeholder, text)
    return [line.rstrip() for line in text.strip("\n").splitlines()]


@pytest.mark.parametrize(
    "where, argv, shown", [pytest.param(*c, id=c[0]) for c in commands() if c[2] is not None]
)
def test_console_block_prints_its_output(where, argv, shown, workdir, capsys):
    code = cli.main(argv)
    printed = capsys.readouterr().out
    assert code == 0, f"{where}: `liftplan {shlex.join(argv)}` exited {code}"
    assert _steady(printed) == _steady(shown), (
        f"{where}: `liftplan {shlex.join(argv)}` no longer prints what the page shows; "
        f"paste its output:\n{printed}"
    )


def test_study_blocks_are_valid_studies(workdir):
    from liftplan.planner.batch.study import loads_study

    studies = [(where, code) for where, code in blocks("toml") if "[study]" in code]
    assert any(where.startswith("docs/batch.md") for where, _ in studies), "the batch page shows a study file"
    for where, code in studies:
        study = loads_study(code, base=workdir / "examples", stem="docs")
        assert study.size >= 1, where
