"""One rule for every path the command line writes to (``--report``, ``--figure``, batch
``--output`` and a study's ``output``).

Checked before any computation starts, so a mistake costs nothing: a missing parent folder is
created (when the output is written, not before); an existing file where a folder is wanted,
or a folder where a file is wanted, a figure type matplotlib cannot write, or a location that
cannot be written are refused with one :class:`~liftplan.model.errors.InvalidScene` line
naming the option, the path and what is expected.
"""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from pathlib import Path

from liftplan.model.errors import InvalidScene

#: Figure types the figures can be saved as (matplotlib's Agg, PDF and SVG back-ends).
FIGURE_TYPES = (".png", ".pdf", ".svg")


def output_file(path, option, types=None):
    """Check a file to be written; returns it as a Path.

    Parameters
    ----------
    path : str or os.PathLike
    option : str
        How the user named it (``"--figure"``), for the message.
    types : sequence of str, optional
        Allowed suffixes (lower case, with the dot).

    Raises
    ------
    InvalidScene
        The path is a folder or another non-regular file, has a suffix not in ``types``, or
        cannot be written.
    """
    path = _nonempty(path, option)
    if types is not None and path.suffix.lower() not in types:
        raise InvalidScene(
            f"{option} {path}: unknown file type {path.suffix or '(none)'!r}; "
            f"expected one of {', '.join(types)}"
        )
    mode = _mode(path)
    if mode is not None:
        if stat.S_ISDIR(mode):
            raise InvalidScene(f"{option} {path}: is a folder; expected a file name")
        if not stat.S_ISREG(mode):
            raise InvalidScene(f"{option} {path}: is not a regular file; expected a file name")
        if not os.access(path, os.W_OK):
            raise InvalidScene(f"{option} {path}: the file is read-only; expected a writable file")
    _writable(path.parent, option, path)
    return path


def output_folder(path, option):
    """Check a folder to be written into; returns it as a Path.

    Raises
    ------
    InvalidScene
        The path is an existing file, or the folder cannot be written.
    """
    path = _nonempty(path, option)
    mode = _mode(path)
    if mode is not None and not stat.S_ISDIR(mode):
        raise InvalidScene(f"{option} {path}: is a file; expected a folder (existing or new)")
    _writable(path, option, path)
    return path


def make_parent(path):
    """Create the missing parent folders of a checked output file."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)


def _nonempty(path, option):
    if str(path).strip() == "":
        raise InvalidScene(f"{option} '': expected a path")
    return Path(path)


def _mode(path):
    try:
        return path.stat().st_mode
    except (FileNotFoundError, NotADirectoryError):  # missing, or a file on the way
        return None
    except OSError as err:
        raise InvalidScene(f"{path}: cannot be reached ({err.strerror or err})") from None


def _writable(folder, option, target):
    """The folder (or, if missing, its nearest existing ancestor, which must be a folder)
    accepts a new file: tried by creating one, which also catches read-only file systems and
    permissions that ``os.access`` misjudges for root."""
    existing = Path(folder)
    while _mode(existing) is None and existing != existing.parent:
        existing = existing.parent
    mode = _mode(existing)
    if mode is None or not stat.S_ISDIR(mode):
        raise InvalidScene(
            f"{option} {target}: {existing} is a file, not a folder; expected a path through folders"
        )
    try:
        with tempfile.TemporaryFile(dir=existing):
            pass
    except OSError as err:
        raise InvalidScene(
            f"{option} {target}: cannot write in {existing} "
            f"({err.strerror or err}); expected a writable location"
        ) from None


@contextlib.contextmanager
def replaced(path):
    """Write ``path`` whole or not at all: yields a temporary file beside it, which replaces
    ``path`` when the block ends without an error and is removed otherwise (a full disk or an
    interruption never leaves a half-written report or figure behind).

    Parameters
    ----------
    path : str or os.PathLike
        The file to write (its folder exists).

    Yields
    ------
    pathlib.Path
        Where to write; it has ``path``'s suffix (a figure's format follows it).
    """
    path = Path(path)
    fd, name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    temporary = Path(name)
    try:
        yield temporary
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # as a plain open() would have made it
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
