"""The compile cache (liftplan.model.statics.compiled): compile once per machine, reuse everywhere.

Processes are real subprocesses with their own cache, temporary and working folders
(``LIFTPLAN_CACHE``, ``TMPDIR``, cwd), and a compiler wrapper that logs every call, so
"no compile" means the compiler was not run at all.
"""

from __future__ import annotations

import hashlib
import os
import stat
import subprocess
import sys
import textwrap
import time

import casadi as ca
import numpy as np
import pytest
from helpers import ROOT
from numpy.testing import assert_allclose

from liftplan.model.statics import compiled
from liftplan.model.statics.compiled import compile_cached, library_path
from liftplan.model.statics.model import BLOCK, FastCall, rope_model

needs_compiler = pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler on this machine")

# Builds the three batched maps of the 4-rope model, as `plan` and `batch` do.
BUILD = textwrap.dedent("""
    from liftplan.model.statics.model import rope_model
    m = rope_model(4)
    m.held_block, m.held_columns, m.paper_elastic_block
    print(m.batch_backend)
""")


@pytest.fixture
def logged_cc(tmp_path, monkeypatch):
    """A compiler that appends one line per call to a log, then runs the real one."""
    real = compiled.compiler()
    if real is None:
        pytest.skip("no C compiler on this machine")
    log = tmp_path / "cc.log"
    wrapper = tmp_path / "cc-logged"
    wrapper.write_text(f'#!/bin/sh\necho "$@" >> "{log}"\nexec "{real[0]}" "$@"\n')
    wrapper.chmod(wrapper.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setenv("CC", str(wrapper))
    return log


def compiles(log):
    return len(log.read_text().splitlines()) if log.exists() else 0


def process(tmp_path, code=BUILD, args=None):
    """Start a Python (or ``liftplan``) process with its own cache, temp and working folders."""
    for name in ("cache", "tmp", "work"):
        (tmp_path / name).mkdir(exist_ok=True)
    env = dict(os.environ, LIFTPLAN_CACHE=str(tmp_path / "cache"), TMPDIR=str(tmp_path / "tmp"))
    command = args if args is not None else [sys.executable, "-c", code]
    return subprocess.Popen(
        command, cwd=tmp_path / "work", env=env, text=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )


def finish(proc):
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    return out


def column_function(n=5):
    """The held-hoist column of an n-rope model, built as the model builds it."""
    model = rope_model(n)
    x = ca.SX.sym("x", 3)
    p = ca.SX.sym("p", model.layout.size)
    return ca.Function("held_column", [x, p], list(model.held(x, p)))


def probe_inputs(n, count, seed):
    """Random but well-posed inputs: a ring of n lugs, CG inside, taut ropes."""
    rng = np.random.default_rng(seed)
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False) + rng.uniform(-0.2, 0.2, n)
    lugs = np.stack([10 * np.cos(angles), 6 * np.sin(angles), rng.uniform(-1, 1, n)])
    p = np.concatenate(
        [
            [0.1],
            lugs.ravel(order="F"),
            [0.5, -0.3, 2.0],
            [800.0],
            rng.uniform(38, 42, n),
            np.full(n, 30.0),
            rng.uniform(2e4, 8e4, n),
            [20.0],
        ]
    )
    x = np.stack([np.full(count, 1.0), rng.uniform(-0.05, 0.05, count), rng.uniform(-0.05, 0.05, count)])
    return x, p


@needs_compiler
def test_second_process_loads_the_library_without_compiling(tmp_path, logged_cc):
    # two cold processes at once: both may compile, both must end with whole libraries
    first = [process(tmp_path) for _ in range(2)]
    assert [finish(proc).strip() for proc in first] == ["jit", "jit"]
    cold = compiles(logged_cc)
    assert 2 <= cold <= 4  # two distinct columns (held, paper_elastic), by one or both processes
    libraries = sorted((tmp_path / "cache").rglob("*.so"))
    assert len(libraries) == 2
    stamps = [lib.stat().st_mtime_ns for lib in libraries]
    assert finish(process(tmp_path)).strip() == "jit"
    assert compiles(logged_cc) == cold, "the warm process ran the compiler"
    assert [lib.stat().st_mtime_ns for lib in libraries] == stamps
    # nothing left behind: no build folders in the cache, nothing in the temp or working folder
    entries = [lib.parent for lib in libraries]
    expected = [entries[0].parent, *entries, *libraries, *(e / "sha256" for e in entries)]
    assert sorted((tmp_path / "cache").rglob("*")) == sorted(expected)
    assert list((tmp_path / "tmp").iterdir()) == []
    assert list((tmp_path / "work").iterdir()) == []


@needs_compiler
def test_in_process_second_build_is_a_cache_hit(tmp_path, logged_cc):
    function = column_function()
    first = compile_cached(function, tmp_path)
    second = compile_cached(function, tmp_path)
    assert (first.backend, first.built, second.backend, second.built) == ("jit", True, "jit", False)
    assert first.library == second.library == library_path(function, tmp_path)
    assert compiles(logged_cc) == 1


@needs_compiler
@pytest.mark.parametrize("n", [3, 4, 6])
def test_compiled_equals_the_uncached_function(tmp_path, n):
    model = rope_model(n)
    x = ca.SX.sym("x", 3)
    p = ca.SX.sym("p", model.layout.size)
    for function in (model.held, model.paper_elastic):
        column = ca.Function(f"{function.name()}_column", [x, p], list(function(x, p)))
        built = compile_cached(column, tmp_path)
        loaded = compile_cached(column, tmp_path)
        assert (built.built, loaded.built) == (True, False)
        xs, params = probe_inputs(n, 50, seed=n)
        for k in range(xs.shape[1]):
            reference = column(xs[:, k], params)
            for compiled_fn in (built.function, loaded.function):
                for got, want in zip(compiled_fn(xs[:, k], params), reference):
                    # the generated C runs casadi's own operation sequence in IEEE double
                    # (-O2, no fast-math): equal to rounding; tensions are O(100 t)
                    assert_allclose(np.array(got), np.array(want), rtol=1e-12, atol=1e-12)


@needs_compiler
def test_batched_map_equals_the_vm_map(tmp_path, monkeypatch):
    # the model's own block (through the cache) against the same map in casadi's VM
    monkeypatch.setenv("LIFTPLAN_CACHE", str(tmp_path))
    n = 4
    model = rope_model(n)
    vm = FastCall(model.held.map("held_vm", "serial", BLOCK, [1], []))
    xs, params = probe_inputs(n, BLOCK, seed=7)
    flat = xs.ravel(order="F")
    for got, want in zip(model.held_block(flat, params), vm(flat, params)):
        # same arithmetic as above; the map only loops over columns
        assert_allclose(got, want, rtol=1e-12, atol=1e-12)


@needs_compiler
@pytest.mark.parametrize("damage", ["truncated", "garbage", "empty", "no checksum", "other function"])
def test_a_corrupt_cache_entry_is_rebuilt(tmp_path, logged_cc, damage):
    function = column_function(n=5)
    library = library_path(function, tmp_path / "cache")
    checksum = library.parent / "sha256"
    library.parent.mkdir(parents=True)
    if damage == "truncated":  # a disk that filled up after the checksum was written
        whole = compile_cached(function, tmp_path / "other").library.read_bytes()
        library.write_bytes(whole[: len(whole) // 2])
        checksum.write_text(hashlib.sha256(whole).hexdigest())
    else:  # the checksum matches: the load itself or the probe must refuse these
        content = {
            "garbage": b"\x7fELF not really a library" * 100,
            "empty": b"",
            "no checksum": b"",
            "other function": compile_cached(column_function(n=4), tmp_path / "other").library.read_bytes(),
        }[damage]
        library.write_bytes(content)
        if damage != "no checksum":
            checksum.write_text(hashlib.sha256(content).hexdigest())
    before = compiles(logged_cc)
    result = compile_cached(function, tmp_path / "cache")
    assert (result.backend, result.built, result.library) == ("jit", True, library)
    assert compiles(logged_cc) == before + 1
    assert checksum.read_text() == hashlib.sha256(library.read_bytes()).hexdigest()
    xs, params = probe_inputs(5, 1, seed=3)
    for got, want in zip(result.function(xs[:, 0], params), function(xs[:, 0], params)):
        assert_allclose(np.array(got), np.array(want), rtol=1e-12, atol=1e-12)  # as above


@pytest.mark.parametrize("cc", ["", "/nonexistent/cc", "'unbalanced", "false"])
def test_without_a_working_compiler_the_vm_gives_the_same_results(tmp_path, monkeypatch, cc):
    # "", a missing program, a malformed command: no compiler; "false": a compiler that fails
    monkeypatch.setenv("CC", cc)
    function = column_function(n=4)
    result = compile_cached(function, tmp_path)
    assert (result.backend, result.library, result.built) == ("casadi-vm", None, False)
    assert result.function is function
    assert list(tmp_path.rglob("*")) in ([], [tmp_path / f"casadi-{ca.__version__}"])


@needs_compiler
def test_stale_build_folders_of_killed_processes_are_removed(tmp_path):
    folder = tmp_path / f"casadi-{ca.__version__}"
    stale = folder / ".build-killed"
    fresh = folder / ".build-running"
    for build in (stale, fresh):
        build.mkdir(parents=True)
        (build / "function.c").write_text("/* half-written */")
    old = time.time() - 2 * compiled.STALE_BUILD
    os.utime(stale, (old, old))
    compile_cached(column_function(n=3), tmp_path)
    assert not stale.exists()
    assert fresh.exists()  # may belong to a process compiling right now


def test_cache_folder_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.setenv("LIFTPLAN_CACHE", str(tmp_path / "mine"))
    assert compiled.cache_folder() == tmp_path / "mine"
    monkeypatch.delenv("LIFTPLAN_CACHE")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert compiled.cache_folder() == tmp_path / "xdg" / "liftplan"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert compiled.cache_folder() == tmp_path / "home" / ".cache" / "liftplan"


@needs_compiler
def test_plan_leaves_no_c_or_library_files(tmp_path):
    # the whole command, cold cache: only the cache folder receives files
    plan = [sys.executable, "-m", "liftplan.planner.cli", "plan", str(ROOT / "examples" / "tanker_plan.toml")]
    finish(process(tmp_path, args=plan))
    assert list((tmp_path / "tmp").iterdir()) == []
    assert list((tmp_path / "work").iterdir()) == []
    assert {p.suffix or p.name for p in (tmp_path / "cache").rglob("*") if p.is_file()} == {".so", "sha256"}
