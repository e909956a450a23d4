"""One run per output table: a lock held for the whole run of a study.

Two ``liftplan batch`` runs on one ``--output`` would share its journal (``OUTPUT.partial``):
the second resumes the first's, the first finishes and removes it, and the second then
overwrites the complete table with part of it. So a run takes ``OUTPUT.lock`` (an exclusive
``flock``, released by the system however the run ends, even by SIGKILL) before it reads the
journal, and a second run is refused in one line naming the holder. POSIX only (``fcntl``),
as the rest of the batch tooling.
"""

from __future__ import annotations

import contextlib
import datetime
import fcntl
import os
import socket
from pathlib import Path

from liftplan.model.errors import LiftPlanError


class OutputLocked(LiftPlanError):
    """Another run is writing the same output table."""


@contextlib.contextmanager
def output_lock(output):
    """Hold ``OUTPUT.lock`` for the ``with`` block; the lock file is removed on the way out.

    Parameters
    ----------
    output : path
        The study's output table.

    Raises
    ------
    OutputLocked
        Another run holds it: one line with its pid, host and start time.
    """
    path = Path(output).with_name(Path(output).name + ".lock")
    while True:
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.read(fd, 200).decode("utf-8", "replace").strip() or "another process"
            os.close(fd)
            raise OutputLocked(
                f"--output {output}: another liftplan batch is writing it ({holder}); expected "
                "one run per output table (wait for it, or write to another file)"
            ) from None
        # the holder may have removed the file between our open and our lock: lock the file
        # that is there now, or try again
        try:
            same = os.fstat(fd).st_ino == os.stat(path).st_ino
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)
    started = datetime.datetime.now().isoformat(timespec="seconds")
    os.ftruncate(fd, 0)
    os.write(fd, f"pid {os.getpid()} on {socket.gethostname()}, started {started}".encode())
    try:
        yield path
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(path)  # while still holding it: a waiting run then locks a new file
        os.close(fd)
