"""Compile casadi Functions to C once and reuse the binary across processes.

casadi's own JIT compiles in every process and leaves its ``.c``/``.so`` files behind when
a process is killed. Here a Function's C source is generated (``casadi.CodeGenerator``),
compiled by the system C compiler into a shared library in a user cache folder, and loaded
with ``casadi.external``; a later process (or a Dask worker) that builds the same Function
finds the library and loads it without compiling.

Cache folder: ``$LIFTPLAN_CACHE`` if set, else ``$XDG_CACHE_HOME/liftplan``, else
``~/.cache/liftplan``. Each library is an entry ``casadi-<version>/<name>-<hash>/`` holding
``<name>.so`` and its SHA-256; the hash is of the generated source, the compiler command,
its flags and the machine type. Writes are atomic (the entry is made in a private build
folder inside the cache folder, then renamed into place), so two processes compiling the
same Function at once each end with a whole library, and nothing is written to the
temporary or the working folder. An entry whose library fails its checksum, does not
load, or does not reproduce the Function on a probe input is removed and rebuilt. With no
C compiler (or a failed compile) the Function runs in casadi's virtual machine instead:
same results, slower. Remove the cache folder at any time to reclaim the space.

Compiler: ``$CC`` if set (``CC=`` or a missing program means none), else the first of
``cc``, ``gcc``, ``clang`` on the ``PATH``.
"""

from __future__ import annotations

import hashlib
import os
import platform
import shlex
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import casadi as ca
import numpy as np

FLAGS = ("-O2", "-fPIC", "-shared")
#: A build folder older than this was left by a killed process and may be removed  [s].
STALE_BUILD = 3600.0
_BUILD_PREFIX = ".build-"


@dataclass(frozen=True)
class Compiled:
    """A Function ready to evaluate, and how it runs.

    Parameters
    ----------
    function : casadi.Function
        The compiled library's Function, or the original one in casadi's VM.
    backend : {"jit", "casadi-vm"}
        ``jit``: compiled C (from the cache or just built); ``casadi-vm``: no compiler, or
        the compile failed.
    library : pathlib.Path or None
        The shared library loaded (``jit`` only).
    built : bool
        True when this call compiled the library (a cache miss).
    """

    function: ca.Function
    backend: str
    library: Path | None = None
    built: bool = False


def cache_folder():
    """The user cache folder for compiled libraries (not created here).

    Returns
    -------
    pathlib.Path
        ``$LIFTPLAN_CACHE``, else ``$XDG_CACHE_HOME/liftplan``, else ``~/.cache/liftplan``.
    """
    if os.environ.get("LIFTPLAN_CACHE"):
        return Path(os.environ["LIFTPLAN_CACHE"]).expanduser()
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "liftplan"


def compiler():
    """The C compiler command as a list of words, or None when there is none."""
    if "CC" in os.environ:
        try:
            words = shlex.split(os.environ["CC"])
        except ValueError:  # unbalanced quotes: not a command
            return None
        return words if words and shutil.which(words[0]) else None
    for name in ("cc", "gcc", "clang"):
        path = shutil.which(name)
        if path:
            return [path]
    return None


def source(function):
    """The C source of ``function`` (casadi's code generator), as compiled here."""
    generator = ca.CodeGenerator(function.name(), {"with_header": False})
    generator.add(function)
    return generator.dump()


def compile_cached(function, folder=None):
    """``function`` compiled to C, from the cache when it is there.

    Parameters
    ----------
    function : casadi.Function
        An SX or MX Function that casadi can generate C code for.
    folder : str or os.PathLike, optional
        Cache folder (default :func:`cache_folder`).

    Returns
    -------
    Compiled
        Falls back to ``function`` itself (``backend="casadi-vm"``) when there is no C
        compiler, the compiler fails, or the cache folder cannot be written.
    """
    cc = compiler()
    if cc is None:
        return Compiled(function, "casadi-vm")
    code = source(function)
    entry = _entry(function, code, cc, folder)
    loaded = _load(function, entry)
    if loaded is not None:
        return Compiled(loaded, "jit", _library(entry))
    try:
        _build(code, cc, entry)
    except (OSError, subprocess.SubprocessError):
        return Compiled(function, "casadi-vm")
    loaded = _load(function, entry)
    if loaded is None:  # compiled, but it does not reproduce the function: not kept
        return Compiled(function, "casadi-vm")
    return Compiled(loaded, "jit", _library(entry), built=True)


def library_path(function, folder=None):
    """Where the compiled library of ``function`` is cached (None without a compiler).

    Parameters
    ----------
    function : casadi.Function
    folder : str or os.PathLike, optional
        Cache folder (default :func:`cache_folder`).

    Returns
    -------
    pathlib.Path or None
        ``<folder>/casadi-<version>/<name>-<hash>/<name>.so``; its folder also holds the
        library's SHA-256 (file ``sha256``), checked before every load.
    """
    cc = compiler()
    return None if cc is None else _library(_entry(function, source(function), cc, folder))


def _entry(function, code, cc, folder):
    """The cache entry (a folder) of a function's library."""
    key = hashlib.sha256("\0".join([code, *cc, *FLAGS, platform.machine()]).encode()).hexdigest()[:24]
    folder = Path(folder if folder is not None else cache_folder()) / f"casadi-{ca.__version__}"
    return folder / f"{function.name()}-{key}"


def _library(entry):
    return entry / (entry.name.rsplit("-", 1)[0] + ".so")


def _build(code, cc, entry):
    """Compile ``code`` into the cache entry ``entry``, atomically.

    The library and its checksum are made in a private build folder and the finished entry
    is renamed into place; if another process got there first, its entry is kept. The
    compiler's own temporary files go to the build folder too, which is always removed.
    """
    entry.parent.mkdir(parents=True, exist_ok=True)
    _remove_stale_builds(entry.parent)
    build = Path(tempfile.mkdtemp(prefix=_BUILD_PREFIX, dir=entry.parent))
    try:
        (build / "function.c").write_text(code, encoding="utf-8")
        staged = build / "entry"
        staged.mkdir()
        library = _library(entry).name
        subprocess.run(
            [*cc, *FLAGS, "function.c", "-o", f"entry/{library}", "-lm"],
            check=True,
            cwd=build,
            env=dict(os.environ, TMPDIR=str(build)),
            stdin=subprocess.DEVNULL,
            capture_output=True,
            timeout=600,
        )
        (staged / "sha256").write_text(_digest(staged / library))
        try:
            os.rename(staged, entry)
        except OSError:
            if not entry.is_dir():  # not a race lost to another process
                raise
    finally:
        shutil.rmtree(build, ignore_errors=True)


def _remove_stale_builds(folder):
    now = time.time()
    for build in folder.glob(_BUILD_PREFIX + "*"):
        try:
            if now - build.stat().st_mtime > STALE_BUILD:
                shutil.rmtree(build, ignore_errors=True)
        except OSError:  # another process removed it first
            pass


def _digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _load(function, entry):
    """The entry's Function if its library is intact, loads and matches ``function`` on a
    probe input; else None, and a damaged entry is removed so that it is rebuilt.

    The checksum comes first: loading a truncated library can kill the process (SIGBUS).
    """
    if not entry.exists():
        return None
    library = _library(entry)
    try:
        intact = (entry / "sha256").read_text().strip() == _digest(library)
    except OSError:
        intact = False
    loaded = None
    if intact:
        try:
            loaded = ca.external(function.name(), str(library))
            if not _same(function, loaded):
                loaded = None
        except RuntimeError as err:  # not a loadable library of this function (ABI, symbol)
            if "KeyboardInterrupt" in str(err):  # casadi's wrapping of a Ctrl-C: not a bad entry
                raise KeyboardInterrupt from None
            loaded = None
    if loaded is None:
        if entry.is_dir():
            shutil.rmtree(entry, ignore_errors=True)
        else:
            entry.unlink(missing_ok=True)
    return loaded


def _same(function, loaded):
    """Same inputs, outputs and values at a fixed probe input (NaN where the original is)."""
    if (loaded.n_in(), loaded.n_out()) != (function.n_in(), function.n_out()):
        return False
    for i in range(function.n_in()):
        if loaded.sparsity_in(i) != function.sparsity_in(i):
            return False
    for i in range(function.n_out()):
        if loaded.sparsity_out(i) != function.sparsity_out(i):
            return False
    rng = np.random.default_rng(0)
    args = [rng.uniform(0.5, 1.5, function.sparsity_in(i).shape) for i in range(function.n_in())]
    expected = function(*args)
    got = loaded(*args)
    expected = [expected] if function.n_out() == 1 else expected
    got = [got] if function.n_out() == 1 else got
    # the same C arithmetic as casadi's VM up to the compiler's reassociation (-O2, no fast-math)
    return all(
        np.allclose(np.array(g), np.array(e), rtol=1e-9, atol=1e-12, equal_nan=True)
        for g, e in zip(got, expected)
    )
