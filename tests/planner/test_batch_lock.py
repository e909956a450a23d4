"""One run per output table (issue 29 item 14): a second `liftplan batch` on the same
--output is refused in one line naming the run that holds it, and leaves the table alone."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest
from helpers import EXAMPLES

from liftplan.planner.batch.lock import OutputLocked, output_lock
from liftplan.planner.cli import main

STUDY = EXAMPLES / "tanker_study.toml"


def test_a_second_run_on_a_held_output_is_refused_in_one_line(tmp_path, capsys):
    out = tmp_path / "study.csv"
    out.write_text("a complete table\n", encoding="utf-8")
    with output_lock(out) as lock:
        assert lock.exists()
        code = main(["batch", str(STUDY), "--output", str(out), "--no-progress"])
        err = capsys.readouterr().err.strip().splitlines()
        assert code == 2
        assert len(err) == 1 and "another liftplan batch is writing it (pid " in err[0]
        assert out.read_text(encoding="utf-8") == "a complete table\n"
        assert not (tmp_path / "study.csv.partial").exists()
        with pytest.raises(OutputLocked):
            with output_lock(out):
                pass
    assert not lock.exists()  # released and removed on the way out
    with output_lock(out):  # free again
        pass


def test_the_lock_holds_across_processes(tmp_path):
    """A run in another process holds the lock: this one is refused until it ends."""
    out = tmp_path / "study.csv"
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            textwrap.dedent(
                f"""
                import sys
                from liftplan.planner.batch.lock import output_lock
                with output_lock({str(out)!r}):
                    print("locked", flush=True)
                    sys.stdin.readline()
                """
            ),
        ],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert holder.stdout.readline().strip() == "locked"
        with pytest.raises(OutputLocked, match=f"pid {holder.pid} on "):
            with output_lock(out):
                pass
    finally:
        holder.communicate("\n", timeout=60)
    with output_lock(out):  # the holder ended: the lock is free
        pass
