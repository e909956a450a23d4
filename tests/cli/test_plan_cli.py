"""`liftplan plan` as a user drives it, and the report as a person sees it."""

import html
import html.parser
import json
import re
import shutil
import subprocess
import tomllib

import pytest
from helpers import EXAMPLES
from support.cli import run

TANKER = str(EXAMPLES / "tanker_plan.toml")


@pytest.fixture(scope="module")
def report_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    result = run("plan", TANKER, "--json", "--report", str(out))
    assert result.returncode == 0, result.stderr
    return out, json.loads(result.stdout)


def test_plan_json_has_the_contract_keys(report_dir):
    _, data = report_dir
    for key in ("lugs", "boom_heights", "tensions", "spread", "worst_spread", "ranking"):
        assert key in data
    labels = set(data["lugs"])
    assert labels == set(data["boom_heights"]) == set(data["tensions"])
    tensions = list(data["tensions"].values())
    assert data["spread"] == pytest.approx(max(tensions) - min(tensions), abs=1e-9)
    assert data["worst_spread"] >= data["spread"]
    assert data["ranking"][0]["lugs"] == list(data["lugs"].values())
    assert sum(tensions) == pytest.approx(904.0, abs=1e-4)


def test_written_scene_solves_to_the_plan_tensions(report_dir):
    out, data = report_dir
    result = run("solve", str(out / "plan_scene.toml"), "--json")
    assert result.returncode == 0, result.stderr
    solved = json.loads(result.stdout)
    # the scene keeps the candidate names as lug names: map the plan's labels to them
    by_candidate = {data["lugs"][label]: t for label, t in data["tensions"].items()}
    assert solved["tensions"] == pytest.approx(by_candidate, abs=1e-6)


def test_written_scene_keeps_the_file_frame_names_and_cranes(report_dir):
    out, data = report_dir
    text = (out / "plan_scene.toml").read_text(encoding="utf-8")
    scene = tomllib.loads(text)
    assert scene["frame"] == "choi"  # tanker_plan.toml is in the papers' frame
    assert scene["body"]["cog"] == [35.86, 2.5, 6.0]  # as the planning file writes it
    planning = tomllib.loads(open(TANKER, encoding="utf-8").read())
    at = {c["name"]: c["at"] for c in planning["candidates"]}
    assert [lug["name"] for lug in scene["lugs"]] == list(data["lugs"].values())
    for lug in scene["lugs"]:
        # choi -> z-up -> choi is a sign flip and a swap: exact
        assert lug["at"] == at[lug["name"]]
    assert [(c["name"], c["lug"]) for c in scene["cranes"]] == [
        (data["cranes"][label], name) for label, name in data["lugs"].items()
    ]
    assert "# crane 1 (planned lug L1)" in text


class _Tables(html.parser.HTMLParser):
    """Collects each table's header cells, the first cell of each body row, and the images."""

    def __init__(self):
        super().__init__()
        self.tables, self.row_labels, self.images, self._cell = [], [], [], None
        self._first = False

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append([])
            self.row_labels.append([])
        elif tag == "tr":
            self._first = True
        elif tag == "th" or (tag == "td" and self._first):
            self._cell, self._tag = "", tag
            self._first = False
        elif tag == "img":
            self.images.append(dict(attrs)["src"])

    def handle_endtag(self, tag):
        if self._cell is not None and tag == self._tag:
            (self.tables if tag == "th" else self.row_labels)[-1].append(self._cell)
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data


def test_report_embeds_figures_and_every_table_has_units(report_dir):
    out, _ = report_dir
    page = (out / "report.html").read_text(encoding="utf-8")
    parsed = _Tables()
    parsed.feed(page)
    assert len(parsed.images) == 4  # three figures and the 3D view's stills (printed in the PDF)
    assert all(src.startswith("data:image/png;base64,") for src in parsed.images)
    assert 'src="http' not in page and "<link" not in page  # self-contained
    assert len(parsed.tables) >= 7
    for headers, labels in zip(parsed.tables, parsed.row_labels):
        if not headers:
            continue  # the title block: fields, not numbers
        # a units column, a unit in brackets on every numeric column's header, or (a table
        # with one column per crane) on every row's label
        has_unit_column = "unit" in headers
        with_units = [h for h in headers if re.search(r"\[[^\]]+\]", h)]
        labelled = [r for r in labels if re.search(r"\[[^\]]+\]", r)]
        assert (
            has_unit_column
            or len(with_units) >= len(headers) - 3
            or (headers[0] == "quantity" and len(labelled) >= len(labels) - 1)
        ), headers
    page = html.unescape(page)
    for text in (
        "Assumptions",
        "Operator guidance",
        "Skew loads",
        "Design loads per crane",
        "Where each crane's worst static load occurs",
        "Design-load factors",
    ):
        assert text in page
    # the frame is named once, at the top, and the coordinates follow it
    assert page.count("All coordinates are in the planning file's frame") == 1
    assert page.index("All coordinates are in") < page.index("<caption")  # before any data table
    # the client-facing part first, the engineering appendix (bounds, search) last
    sections = [
        page.index(f">{h}<")
        for h in (
            "1 Recommendation",
            "3 Checks to hand over",
            "4 Figures",
            "5 Alternatives",
            "Engineering appendix",
        )
    ]
    assert sections == sorted(sections)
    appendix = sections[-1]
    for jargon in ("lower bound from the optimisation", "Search<", "Admissible tensions"):
        assert page.index(jargon) > appendix, jargon
    assert "convex bound" not in page.lower() and "LP optimum" not in page
    assert "papers' frame (x forward, y up, z to starboard)" in page


def test_report_pdf_when_weasyprint_is_installed(report_dir):
    pytest.importorskip("weasyprint")
    out, _ = report_dir
    pdf = (out / "report.pdf").read_bytes()
    assert pdf[:5] == b"%PDF-" and len(pdf) > 50_000


@pytest.mark.skipif(shutil.which("chromium") is None, reason="Debian chromium not installed")
def test_report_renders_in_headless_chromium(report_dir, tmp_path):
    out, _ = report_dir
    shot = tmp_path / "report.png"
    result = subprocess.run(
        [
            "chromium",
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            f"--user-data-dir={tmp_path / 'profile'}",
            "--hide-scrollbars",
            "--window-size=1200,1600",
            f"--screenshot={shot}",
            (out / "report.html").as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 0, result.stderr[-500:]
    data = shot.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(data) > 50_000  # a blank page compresses to a few kB


@pytest.mark.parametrize(
    ("change", "fragment"),
    [
        ("swl = 400.0", "more than the crane SWL"),
        ("heel = 2.0, trim = 2.0", "falls below min_tension"),
    ],
)
def test_infeasible_plan_exits_non_zero_with_one_line(tmp_path, change, fragment):
    text = open(TANKER, encoding="utf-8").read()
    replacement = {"swl = 400.0": "swl = 150.0", "heel = 2.0, trim = 2.0": "heel = 80.0, trim = 2.0"}[change]
    scene = tmp_path / "scene.toml"
    scene.write_text(text.replace(change, replacement), encoding="utf-8")
    result = run("plan", str(scene), "--json")
    assert result.returncode == 1
    assert result.stdout == ""
    # a unit-slip warning may come first (an 80 deg box); the failure itself is one line
    lines = [line for line in result.stderr.strip().splitlines() if not line.startswith("liftplan: warning:")]
    assert len(lines) == 1 and "no feasible plan" in lines[0] and fragment in lines[0]


def test_bad_plan_file_is_one_line_exit_2(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(open(TANKER, encoding="utf-8").read().replace("cranes = 4", "cranes = 65"))
    result = run("plan", str(scene))
    assert result.returncode == 2
    assert "plan.cranes = 65: expected 3 to 64" in result.stderr
    assert "Traceback" not in result.stderr
