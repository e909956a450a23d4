"""Packaging (issue 30 item 1): one version, shown by ``--version``, carried by every JSON
output and the report's footer; an optional part that is not installed refused in one line
naming the extra to install; the public API typed. (That the built wheel installs and runs
outside the repository is ``.ci/wheel_smoke``'s job: CI runs it.)"""

import ast
import importlib.metadata
import inspect
import io
import json
import re
import sys
from contextlib import redirect_stderr, redirect_stdout

import pytest
from helpers import EXAMPLES
from support.cli import imported_after, run

import liftplan.model
import liftplan.planner
from liftplan.model.extras import MissingExtra, missing, require
from liftplan.model.version import VERSION_KEY, __version__, stamped
from liftplan.planner.cli import BAD_INPUT, main
from liftplan.planner.output.report.page import running_footer
from liftplan.planner.problem.report_info import ReportInfo

VERSION = importlib.metadata.version("liftplan")


def test_one_version_from_the_installed_metadata():
    assert __version__ == VERSION
    assert liftplan.model.__version__ == liftplan.planner.__version__ == VERSION
    for package in (liftplan.model, liftplan.planner):
        assert "__version__" not in package.__all__  # exported, but no API name for import *
        assert "__version__" in dir(package)


def test_version_option():
    out = run("--version")
    assert out.returncode == 0, out.stderr
    assert out.stdout == f"liftplan {VERSION}\n"


def test_version_costs_nothing_until_asked_for():
    # the installed metadata is read (~25 ms) by --version and the outputs, not at import
    probe = (
        "import sys, liftplan.model, liftplan.planner, liftplan.planner.cli\n"
        "from liftplan.planner.cli import main\n"
        "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
        "assert 'importlib.metadata' not in sys.modules, 'metadata read at start-up'"
    )
    assert imported_after(probe) == []


def test_stamped_adds_the_version_last_and_keeps_the_keys():
    out = stamped({"b": 1, "a": 2})
    assert list(out) == ["b", "a", VERSION_KEY] and out[VERSION_KEY] == VERSION


def _printed_json(capsys, *argv):
    code = main(list(argv))
    captured = capsys.readouterr()
    assert code == 0, captured.err
    data = json.loads(captured.out)
    assert list(data)[-1] == VERSION_KEY and data[VERSION_KEY] == VERSION
    return data, captured.err


def test_solve_and_lift_json_carry_the_version(capsys, tmp_path):
    data, _ = _printed_json(capsys, "solve", str(EXAMPLES / "tanker_upright.toml"), "--json")
    assert data["converged"] is True
    figure = tmp_path / "curve.png"
    data, _ = _printed_json(
        capsys, "lift", str(EXAMPLES / "sunken_block_lift.toml"), "--json", "--figure", str(figure)
    )
    assert data["curve"] and figure.is_file()


@pytest.fixture(scope="module", params=["tanker_plan.toml", "block_sling_plan.toml"])
def planned_without_pdf(request, tmp_path_factory):
    """``plan --json --report`` as if WeasyPrint were not installed (the spread plan's
    report and the sling plan's are written by different modules)."""
    out = tmp_path_factory.mktemp("report")
    stdout, stderr = io.StringIO(), io.StringIO()  # capsys is per test; this runs once a module
    with pytest.MonkeyPatch.context() as patch, redirect_stdout(stdout), redirect_stderr(stderr):
        patch.setitem(sys.modules, "weasyprint", None)  # its import fails as if not installed
        code = main(["plan", str(EXAMPLES / request.param), "--json", "--report", str(out)])
    assert code == 0, stderr.getvalue()
    return out, json.loads(stdout.getvalue()), stderr.getvalue()


def test_plan_json_and_plan_json_file_carry_the_version(planned_without_pdf):
    out, data, _ = planned_without_pdf
    assert list(data)[-1] == VERSION_KEY and data[VERSION_KEY] == VERSION
    written = json.loads((out / "plan.json").read_text(encoding="utf-8"))
    assert list(written)[-1] == VERSION_KEY and written[VERSION_KEY] == VERSION
    assert written["lugs"] == data["lugs"]


def test_report_footer_names_the_version(planned_without_pdf):
    out, _, _ = planned_without_pdf
    page = (out / "report.html").read_text(encoding="utf-8")
    # on screen once below the body, in print at the bottom of every page
    assert re.search(rf"<footer>[^<]*liftplan {re.escape(VERSION)}</footer>", page)
    assert re.search(rf'@bottom-left {{ content: "[^"]*liftplan {re.escape(VERSION)}";', page)
    info = ReportInfo(document="LP-0042", revision="B")
    assert running_footer(info) == f"LP-0042, rev. B, liftplan {VERSION}"
    assert running_footer(ReportInfo()) == f"liftplan {VERSION}"


def test_report_without_weasyprint_says_which_extra_in_one_line(planned_without_pdf):
    out, _, err = planned_without_pdf
    assert (out / "report.html").is_file() and not (out / "report.pdf").exists()
    lines = [line for line in err.splitlines() if "report.pdf" in line]
    assert len(lines) == 1
    assert lines[0].startswith("liftplan: warning: no report.pdf: needs the pdf extra (")
    assert lines[0].endswith('pip install "liftplan[pdf]"')


def test_batch_without_dask_is_refused_in_one_line(capsys, monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    output = tmp_path / "study.csv"
    code = main(["batch", str(EXAMPLES / "tanker_study.toml"), "--output", str(output), "--no-progress"])
    err = capsys.readouterr().err
    assert code == BAD_INPUT
    assert err.count("\n") == 1, err
    assert err.startswith("liftplan batch: needs the batch extra (")
    assert err.strip().endswith('pip install "liftplan[batch]"')
    assert not output.exists() and not output.with_name(output.name + ".partial").exists()


def test_mesh_hull_without_trimesh_is_refused_in_one_line(capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "trimesh", None)
    code = main(["solve", str(EXAMPLES / "vlcc_case1.toml"), "--json"])
    captured = capsys.readouterr()
    assert code == BAD_INPUT and captured.out == ""
    assert captured.err.count("\n") == 1, captured.err
    assert captured.err.startswith("liftplan solve: hull.mesh = ")
    assert "vlcc_fitted.stl': needs the mesh extra (" in captured.err
    assert captured.err.strip().endswith('pip install "liftplan[mesh]"')


def test_require_and_missing():
    assert missing("batch", "json") is None
    assert require("batch", "json") is json
    reason = missing("batch", "json", "liftplan_no_such_module")
    assert reason == (
        "needs the batch extra (No module named 'liftplan_no_such_module'): pip install \"liftplan[batch]\""
    )
    with pytest.raises(MissingExtra, match=r"^writing 'a\.stl': needs the mesh extra") as caught:
        require("mesh", "liftplan_no_such_module", what="writing 'a.stl'")
    assert isinstance(caught.value, ImportError)  # also caught as what it is


PUBLIC_API = {
    liftplan.model: ("load_scene", "loads_scene", "solve"),
    liftplan.planner: ("plan", "load_problem", "loads_problem", "write_report"),
}


@pytest.mark.parametrize(
    ("package", "name"), [(package, name) for package, names in PUBLIC_API.items() for name in names]
)
def test_public_api_is_annotated(package, name):
    # mypy (.ci/typecheck) checks the annotations; this keeps every parameter annotated
    signature = inspect.signature(getattr(package, name))
    assert signature.return_annotation is not inspect.Signature.empty, name
    for parameter in signature.parameters.values():
        assert parameter.annotation is not inspect.Parameter.empty, f"{name}({parameter.name})"


@pytest.mark.parametrize("package", [liftplan.model, liftplan.planner])
def test_type_checkers_see_the_lazy_exports_where_they_load(package):
    # the `if TYPE_CHECKING:` imports of the package's __init__ name the same modules as its
    # lazy table (a module moved in one and not the other would type one thing, load another)
    tree = ast.parse(inspect.getsource(package))
    block = next(
        node for node in tree.body if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING"
    )
    seen = {}
    for node in block.body:
        assert isinstance(node, ast.ImportFrom), ast.unparse(node)
        for alias in node.names:
            assert alias.asname == alias.name, f"{alias.name}: re-exported as itself"
            seen[alias.name] = node.module
    assert {*PUBLIC_API[package], "__version__"} <= set(seen)
    for name, module in seen.items():
        lazy = package._EXPORTS[name]
        assert module == (lazy if lazy.startswith("liftplan.") else f"{package.__name__}.{lazy}"), name
