"""The reports as printed: WeasyPrint's PDF rendered page by page with poppler.

Each of the three example plans (four equal cranes, an unequal fleet, a two-crane sling
lift) is written with ``write_report``; every PDF page is rendered to PNG (``pdftoppm``) and
read back as text (``pdftotext``). Checked: the page count, that nothing is printed to the
right of the A4 text width (a table or figure wider than the page overflows into the right
margin), the running header, "page n of N" and liftplan's version on every page, and the
``[report]`` title block in both the HTML and the PDF. Skipped, and said so, without
WeasyPrint or poppler-utils (Debian: ``apt-get install poppler-utils``).
"""

from __future__ import annotations

import html

import pytest
from helpers import EXAMPLES
from support.pdf import A4_WIDTH_MM, EDGE_MM, ink_extent_mm, missing, needs_pdf, render

from liftplan.model.errors import InvalidScene
from liftplan.model.version import __version__
from liftplan.planner.output.report.page import MARGINS_MM, document, table
from liftplan.planner.problem.file import loads_problem
from liftplan.planner.problem.report_info import ReportInfo

SLING_REPORT = """
[report]
project = "Block 12 erection, Müller & Søn <A/S>"
client = "Yard \\"Nord\\""
document = "BLK-12-LP"
revision = "C"
prepared_by = "R. Rigger"
checked_by = "S. Checker"
approved_by = "T. Approver"
date = "2026-04-01"
"""


CASES = {
    # name: (planning file, extra TOML, expected page range)
    "tanker_plan": ("tanker_plan.toml", "", (5, 9)),
    "tanker_fleet": ("tanker_fleet.toml", "", (5, 9)),
    "block_sling_plan": ("block_sling_plan.toml", SLING_REPORT, (2, 5)),  # 5: the 3D view's stills
}


@pytest.fixture(scope="module", params=list(CASES))
def printed(request, tmp_path_factory):
    from liftplan.planner.output.report.write import write_report
    from liftplan.planner.plan import plan

    if missing():
        pytest.skip(missing())
    filename, extra, pages = CASES[request.param]
    text = (EXAMPLES / filename).read_text(encoding="utf-8") + extra
    problem = loads_problem(text)
    out = tmp_path_factory.mktemp(request.param)
    files = write_report(plan(problem), out)
    assert files.pdf is not None
    images, texts = render(files.pdf, out)
    return request.param, problem, files, images, texts, pages


@needs_pdf
def test_page_count_is_in_the_expected_range(printed):
    name, _, _, images, texts, (low, high) = printed
    assert low <= len(images) <= high, f"{name}: {len(images)} pages"
    assert len(texts) == len(images)


@needs_pdf
def test_nothing_is_printed_beyond_the_text_width(printed):
    name, _, _, images, _, _ = printed
    top, right, bottom, left = MARGINS_MM
    for k, png in enumerate(images, start=1):
        extent = ink_extent_mm(png)
        assert extent is not None, f"{name} page {k} is blank"
        first, last = extent
        assert last <= A4_WIDTH_MM - right + EDGE_MM, (
            f"{name} page {k}: ink at {last:.1f} mm, the text ends at {A4_WIDTH_MM - right:.0f} mm "
            "(a table or figure wider than the page)"
        )
        assert first >= left - EDGE_MM, f"{name} page {k}: ink at {first:.1f} mm from the left edge"


@needs_pdf
def test_every_page_has_the_running_header_its_number_and_the_version(printed):
    name, problem, _, _, texts, _ = printed
    header = problem.report.project or problem.name
    for k, text in enumerate(texts, start=1):
        flat = " ".join(text.split())
        assert f"page {k} of {len(texts)}" in flat, f"{name} page {k}"
        assert " ".join(header.split())[:40] in flat, f"{name} page {k}: no running header"
        assert f"liftplan {__version__}" in flat, f"{name} page {k}: no software version in the footer"


@needs_pdf
def test_title_block_fields_are_in_the_html_and_the_pdf(printed):
    name, problem, files, _, texts, _ = printed
    page = html.unescape(files.html.read_text(encoding="utf-8"))
    first = " ".join(texts[0].split())
    fields = [
        v
        for v in (
            problem.report.project,
            problem.report.client,
            problem.report.document,
            problem.report.revision,
            problem.report.prepared_by,
            problem.report.checked_by,
            problem.report.approved_by,
            problem.report.date,
        )
        if v
    ]
    assert len(fields) >= 5, name  # every example here fills most of its title block
    for value in fields:
        assert value in page, f"{name}: {value!r} not in the HTML"
        assert value in first, f"{name}: {value!r} not on page 1 of the PDF"
    for label in ("Prepared by", "Checked by", "Approved by", "Revision", "Document no."):
        assert label in first


@needs_pdf
def test_engineering_appendix_comes_after_the_recommendation(printed):
    name, _, _, _, texts, _ = printed
    whole = "\f".join(texts)
    assert (
        whole.index("1 Recommendation")
        < whole.index("3 Checks to hand over")
        < whole.index("Engineering appendix")
    ), name
    # the appendix starts a page of its own: its heading is the first line under the header
    page = next(t for t in texts if "Engineering appendix" in t)
    lines = [line.strip() for line in page.splitlines() if line.strip()]
    assert lines[1] == "Engineering appendix", lines[:3]


@needs_pdf
def test_the_margin_check_sees_a_table_wider_than_the_page(tmp_path):
    # the check above must be able to fail: 30 columns of long numbers cannot fit 170 mm
    import weasyprint

    wide = table(
        [f"column {k} [t]" for k in range(30)], [[f"{123456.789 + k:.3f}" for k in range(30)]], "too wide"
    )
    pdf = tmp_path / "wide.pdf"
    weasyprint.HTML(string=document("wide", wide, "header")).write_pdf(pdf)
    images, _ = render(pdf, tmp_path)
    _, last = ink_extent_mm(images[0])
    assert last > A4_WIDTH_MM - MARGINS_MM[1] + EDGE_MM


# -- the [report] table --------------------------------------------------------------------
def test_report_table_is_optional_and_read_as_given():
    text = (EXAMPLES / "tanker_plan.toml").read_text(encoding="utf-8")
    problem = loads_problem(text)
    assert problem.report.project.startswith("Salvage of a 1500 GT tanker")
    assert problem.report.checked_by == ""  # left blank to sign by hand
    block = loads_problem((EXAMPLES / "block_sling_plan.toml").read_text(encoding="utf-8"))
    assert block.report == ReportInfo()


@pytest.mark.parametrize(
    ("table_text", "fragment"),
    [
        ("revision = 3", "report.revision = 3"),
        ('projekt = "X"', "report.projekt"),
        (f'project = "{"x" * 201}"', "report.project"),
    ],
)
def test_report_table_errors_name_the_key(table_text, fragment):
    text = (EXAMPLES / "block_sling_plan.toml").read_text(encoding="utf-8")
    with pytest.raises(InvalidScene) as err:
        loads_problem(text + f"\n[report]\n{table_text}\n")
    message = str(err.value)
    assert fragment in message and "\n" not in message


def test_report_info_refuses_line_breaks_and_defaults_the_date():
    import datetime

    with pytest.raises(InvalidScene, match=r"report.client = .*one line"):
        ReportInfo(client="a\nb")
    rows = dict(ReportInfo(project="P").rows(today=datetime.date(2026, 1, 2)))
    assert rows["Date"] == "2026-01-02" and rows["Project"] == "P" and rows["Checked by"] == ""


def test_the_report_says_how_to_get_the_plan_again():
    """The held report's last section (one function and one row of SECTIONS): the version,
    the search asked for and what ended it, and whether the plan depends on the machine."""
    import dataclasses

    from liftplan.planner.output.report.held import SECTIONS, render_html
    from liftplan.planner.plan import plan
    from liftplan.planner.problem.file import load_problem

    assert SECTIONS[-1].__name__ == "_reproducing"
    problem = load_problem(EXAMPLES / "tanker_plan.toml")
    proved = render_html(plan(problem))
    assert f"liftplan {__version__}" in proved and "Reproducing this plan" in proved
    assert "gives this plan again" in proved
    # a plan the time limit stopped (made so: a time limit now holds from the first second, so
    # a real one would stop before or after the first plan depending on the machine)
    result = plan(problem)
    stopped = dataclasses.replace(result, stats=dataclasses.replace(result.stats, stopped="time_limit"))
    assert "may end at another point" in render_html(stopped)
