"""The import layers (issue 30 item 2, docs/architecture.md): no circle, at module or function
level; the layer contracts of pyproject.toml's [tool.importlinter]; function-level imports
only where start-up needs them, each with its reason."""

from __future__ import annotations

import ast
import shutil
import subprocess

import grimp
import pytest
from helpers import ROOT

PACKAGES = ("liftplan.model", "liftplan.planner")
#: The command line imports each command's modules in the command (its docstring says why).
LAZY_MODULES = {"planner/cli.py"}


def _cycles(graph):
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = 0
    for root in sorted(graph.modules):
        if root in index:
            continue
        work = [(root, iter(sorted(graph.find_modules_directly_imported_by(root))))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on.add(child)
                    work.append((child, iter(sorted(graph.find_modules_directly_imported_by(child)))))
                elif child in on:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    out.append(sorted(component))
    return out


def test_no_import_circles():
    graph = grimp.build_graph(*PACKAGES, include_external_packages=False)
    assert len(graph.modules) > 50
    assert _cycles(graph) == []


def test_the_cycle_finder_finds_a_circle(tmp_path, monkeypatch):
    for name, body in {"a": "from circ import b\n", "b": "def f():\n    from circ import a\n"}.items():
        (tmp_path / "circ").mkdir(exist_ok=True)
        (tmp_path / "circ" / f"{name}.py").write_text(body)
    (tmp_path / "circ" / "__init__.py").write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    assert _cycles(grimp.build_graph("circ", cache_dir=None)) == [["circ.a", "circ.b"]]


def test_layer_contracts_hold():
    command = shutil.which("lint-imports")
    if command is None:
        pytest.fail("lint-imports (import-linter, in the test extra) is not installed")
    out = subprocess.run([command], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-2000:]
    assert "0 broken" in out.stdout


def _function_level_imports(path):
    src = path.read_text(encoding="utf-8")
    lines = src.splitlines()
    for fn in ast.walk(ast.parse(src)):
        if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        for node in ast.walk(fn):
            first_party = (
                isinstance(node, ast.ImportFrom) and (node.module or "").startswith("liftplan")
            ) or (isinstance(node, ast.Import) and any(a.name.startswith("liftplan") for a in node.names))
            if first_party:
                yield node.lineno, lines[node.lineno - 2] + "\n" + lines[node.lineno - 1]


def test_function_level_imports_only_for_start_up():
    unexplained = []
    for path in sorted([*ROOT.glob("model/**/*.py"), *ROOT.glob("planner/**/*.py")]):
        relative = path.relative_to(ROOT).as_posix()
        if relative in LAZY_MODULES:
            continue
        for line, text in _function_level_imports(path):
            if "start-up" not in text:
                unexplained.append(f"{relative}:{line}")
    assert unexplained == [], "first-party imports inside functions without a start-up reason"
