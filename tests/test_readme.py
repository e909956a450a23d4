"""The README's code blocks work as written.

Every ```python block runs on its own (a fresh namespace: a block that forgets an import
fails). Every command line starting with ``liftplan`` in a ```bash or plain ``` block is
parsed by the command line's own parser (``a|b|c`` in an option value is the README's
notation for alternatives: each one is parsed); a command whose files exist (the examples)
is also run, except ``batch``, which starts a Dask cluster and is covered by
tests/test_batch.py. A ```toml block with a ``[study]`` table is read as a study file
next to the examples.

Blocks run in a temporary folder holding a copy of ``examples/``, so the README's relative
paths work and anything a block writes (a report, a figure) lands there, not in the
repository.
"""

from __future__ import annotations

import re
import shlex
import shutil
from pathlib import Path

import pytest

from liftplan.planner import cli

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
FENCE = re.compile(r"^```([\w-]*)[^\n]*\n(.*?)^```", re.MULTILINE | re.DOTALL)
# shell operators between commands on one line (a lone | inside a word is an alternative)
OPERATOR = re.compile(r"\s(?:&&|\|\||;|\|)\s")


def blocks(language):
    """(line number, text) of every fenced block in README.md tagged ``language``."""
    text = README.read_text(encoding="utf-8")
    return [
        (text.count("\n", 0, m.start()) + 1, m.group(2))
        for m in FENCE.finditer(text)
        if m.group(1) == language
    ]


def commands():
    """Every ``liftplan ...`` command line in the README's shell blocks, as argv lists."""
    out = []
    for line_no, block in blocks("bash") + blocks(""):
        for offset, line in enumerate(block.splitlines()):
            for part in OPERATOR.split(line):
                words = shlex.split(part, comments=True)
                if words[:1] == ["liftplan"]:
                    out.append((line_no + 1 + offset, words[1:]))
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


def test_the_readme_has_blocks_to_check():
    # a change of fence syntax must not silently turn this file into a no-op
    assert len(blocks("python")) >= 2
    assert len(commands()) >= 10


@pytest.mark.parametrize("line, code", [pytest.param(*b, id=f"line{b[0]}") for b in blocks("python")])
def test_python_block_runs_on_its_own(line, code, workdir):
    exec(compile(code, f"README.md:{line}", "exec"), {"__name__": f"readme_line_{line}"})


@pytest.mark.parametrize("line, argv", [pytest.param(*c, id=f"line{c[0]}") for c in commands()])
def test_command_line_parses(line, argv):
    for variant in alternatives(argv):
        try:
            cli._parser().parse_args(variant)
        except SystemExit as err:
            pytest.fail(
                f"README.md:{line}: `liftplan {shlex.join(variant)}` is refused by the "
                f"parser (exit {err.code})"
            )


def runnable():
    """Commands whose file arguments all exist in examples/ (not placeholders like SCENE)."""
    out = []
    for line, argv in commands():
        files = [w for w in argv[1:] if w.endswith(".toml")]
        if argv[0] != "batch" and files and all((ROOT / f).is_file() for f in files):
            out.extend((line, variant) for variant in alternatives(argv))
    return out


#: Examples whose command takes more than ~20 s on 2 cores: run with ``-m slow``.
SLOW_EXAMPLES = {
    "examples/hull154_plan.toml",
    "examples/ferry_strength_plan.toml",
    "examples/block_8_points_plan.toml",
}


def _param(line, argv):
    slow = any(w in SLOW_EXAMPLES for w in argv)
    return pytest.param(
        line, argv, id=f"line{line}-{'-'.join(argv[:1])}", marks=[pytest.mark.slow] if slow else []
    )


@pytest.mark.parametrize("line, argv", [_param(*c) for c in runnable()])
def test_example_command_runs(line, argv, workdir, capsys):
    code = cli.main(argv)
    err = capsys.readouterr().err
    assert code == 0, f"README.md:{line}: `liftplan {shlex.join(argv)}` exited {code}: {err}"


def test_study_block_is_a_valid_study(workdir):
    from liftplan.planner.batch.study import loads_study

    studies = [(line, code) for line, code in blocks("toml") if "[study]" in code]
    assert studies, "the README's batch section shows a study file"
    for line, code in studies:
        study = loads_study(code, base=workdir / "examples", stem="readme")
        assert study.size >= 1, f"README.md:{line}"
