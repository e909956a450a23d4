"""Sling plans print coordinates in the planning file's frame and name it (review finding 7):
a ``choi`` copy of examples/block_sling_plan.toml gives the worst CG offset in choi axes on the
console, as the JSON does, and the console says which frame its coordinates are in."""

from __future__ import annotations

import re

import pytest
from helpers import EXAMPLES

from liftplan.model.frames import FRAME_TEXT, zup_to_choi
from liftplan.planner import load_problem, plan
from liftplan.planner.output.console.slings import sling_table

POINT = re.compile(r"^(\s*(?:at|cog|position) = )\[([^\]]*)\]", re.MULTILINE)


def _choi_copy(path):
    """examples/block_sling_plan.toml with every body point and crane position in choi axes (its
    CG half-widths (0.3, 0.2, 0.2) read the same in both frames)."""
    text = (EXAMPLES / "block_sling_plan.toml").read_text()
    assert 'frame = "z-up"' in text and "cog_tolerance = [0.3, 0.2, 0.2]" in text

    def turned(match):
        point = zup_to_choi([float(v) for v in match.group(2).split(",")])
        return f"{match.group(1)}[{', '.join(repr(float(v)) for v in point)}]"

    text, count = POINT.subn(turned, text.replace('frame = "z-up"', 'frame = "choi"'))
    assert count == 1 + 24 + 2  # the CG, the candidates, the cranes
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def plans(tmp_path_factory):
    choi = _choi_copy(tmp_path_factory.mktemp("choi") / "block_sling_choi.toml")
    return plan(load_problem(EXAMPLES / "block_sling_plan.toml")), plan(load_problem(choi))


def test_the_console_gives_the_worst_cg_offset_in_the_file_s_frame(plans):
    zup, choi = plans
    assert choi.chosen.pairs == zup.chosen.pairs  # the same lift
    offset = zup_to_choi(zup.chosen.worst_cog_offset)
    assert tuple(offset) != tuple(zup.chosen.worst_cog_offset)  # the frames differ here
    expected = "CG offset (" + ", ".join(f"{v:+.2f}" for v in offset) + ") m"
    text = " ".join(sling_table(choi).split())
    assert expected in text
    assert choi.to_json()["worst_attitude"]["cog_offset"] == pytest.approx(list(offset))
    z_text = " ".join(sling_table(zup).split())
    assert "CG offset (" + ", ".join(f"{v:+.2f}" for v in zup.chosen.worst_cog_offset) + ") m" in z_text


@pytest.mark.parametrize("which", [0, 1])
def test_the_console_names_the_frame(plans, which):
    result = plans[which]
    lines = sling_table(result).splitlines()
    assert lines[1].startswith(f"coordinates: the file's frame, {FRAME_TEXT[result.frame]}")
