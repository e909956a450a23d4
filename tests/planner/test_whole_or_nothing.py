"""Outputs are written whole or not at all (issue 29 item 13: on a full disk --report and
--figure exited 2 but left a half-written report.html / figure behind)."""

from __future__ import annotations

import os

import pytest
from helpers import EXAMPLES

from liftplan.planner import load_problem, plan
from liftplan.planner.output.paths import replaced
from liftplan.planner.output.report.write import write_report


def test_a_failed_write_leaves_nothing_and_keeps_the_old_file(tmp_path):
    target = tmp_path / "report.html"
    target.write_text("the previous report", encoding="utf-8")
    with pytest.raises(OSError, match="No space left"):
        with replaced(target) as temporary:
            temporary.write_text("half a rep", encoding="utf-8")
            raise OSError(28, "No space left on device")
    assert target.read_text(encoding="utf-8") == "the previous report"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.html"]
    with replaced(target) as temporary:
        temporary.write_text("the new report", encoding="utf-8")
    assert target.read_text(encoding="utf-8") == "the new report"
    umask = os.umask(0)
    os.umask(umask)
    assert (target.stat().st_mode & 0o777) == 0o666 & ~umask  # as open() would have made it


def test_a_report_on_a_full_disk_leaves_no_half_written_file(tmp_path, monkeypatch):
    result = plan(load_problem(EXAMPLES / "tanker_plan.toml"))
    real = type(tmp_path).write_text
    written = []

    def full_disk(self, text, *args, **kwargs):  # the second file's write fails half-way
        if written:
            real(self, text[: len(text) // 2], *args, **kwargs)
            raise OSError(28, "No space left on device")
        written.append(self)
        return real(self, text, *args, **kwargs)

    monkeypatch.setattr(type(tmp_path), "write_text", full_disk)
    with pytest.raises(OSError):
        write_report(result, tmp_path / "out")
    names = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert names == ["report.html"]  # the first file whole, the second not at all
