"""Page 1 shows the governing numbers (issue 29 item 7): per crane the design hook load and
its utilisation against the chart SWL (the one utilisation), what governs it, and the hook
accuracy the crew must hold; it showed level T / chart SWL (53.6-59.4 %) while the design
utilisation (76.7-90.2 %) was on page 2."""

from __future__ import annotations

import re
import shutil
import subprocess

import pytest
from helpers import EXAMPLES

from liftplan.planner import load_problem, plan
from liftplan.planner.output.report.held import render_html
from liftplan.planner.output.report.write import write_report

CAPTION = "The loads to sign against"


@pytest.fixture(scope="module")
def fleet():
    return plan(load_problem(EXAMPLES / "tanker_fleet.toml"))


def _rows(page, caption):
    table = page[page.index(caption) :]
    table = table[: table.index("</table>")]
    return [
        [re.sub(r"<[^>]+>", "", cell) for cell in re.findall(r"<td[^>]*>(.*?)</td>", row)]
        for row in re.findall(r"<tr>(.*?)</tr>", table)
        if "<td" in row
    ]


def test_the_recommendation_carries_each_cranes_design_utilisation(fleet):
    page = render_html(fleet)
    section = page[page.index("1 Recommendation") : page.index("2 Basis of the plan")]
    assert CAPTION in section and "level T / chart SWL" not in section
    rows = _rows(section, CAPTION)
    capacity = fleet.to_json()["capacity"]
    assert [r[0] for r in rows] == [f"{c['lug']} ({c['crane']})" for c in capacity]
    for row, crane in zip(rows, capacity):
        assert float(row[2]) == pytest.approx(crane["design_hook_load"], abs=0.005)
        assert float(row[3]) == pytest.approx(100 * crane["utilisation"], abs=0.05)
        assert row[5] == ("ok" if crane["ok"] else "FAIL")
    assert f"+-{fleet.hook_accuracy_needed:.3f} m of its planned height" in section
    # what the design loads stand on (the reviewer: page 1 had no weight, weight basis or DAF
    # location; they were on page 2 only)
    problem = fleet.problem
    assert f"Weight W {problem.body.weight:.2f} t ({problem.weight_basis_text}); location" in section


@pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext (poppler-utils) not installed")
def test_it_is_on_the_first_printed_page(fleet, tmp_path):
    files = write_report(fleet, tmp_path)
    if files.pdf is None:
        pytest.skip("WeasyPrint (the pdf extra) not installed")
    first = subprocess.run(
        ["pdftotext", "-f", "1", "-l", "1", str(files.pdf), "-"], capture_output=True, text=True, check=True
    ).stdout
    assert CAPTION in first and "crew must hold every hook" in first
    assert "the DAF column of 0027/ND Table 5-1" in " ".join(first.split())
