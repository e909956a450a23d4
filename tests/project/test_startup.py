"""Start-up (issue 14 item 7): the command line imports only what a command needs, and the
packages' lazy exports stay complete."""

import importlib
import subprocess
import sys

from helpers import EXAMPLES
from support.cli import imported_after

import liftplan.model
import liftplan.planner


def test_cli_import_and_help_load_nothing_heavy():
    assert imported_after("import liftplan.planner.cli") == []
    assert imported_after("import liftplan.model, liftplan.planner") == []
    help_code = (
        "from liftplan.planner.cli import main\ntry:\n    main(['--help'])\nexcept SystemExit:\n    pass"
    )
    assert imported_after(help_code) == []


def test_solve_loads_no_cvxpy_dask_or_matplotlib():
    code = (
        "from liftplan.planner.cli import main\n"
        f"assert main(['solve', {str(EXAMPLES / 'tanker_upright.toml')!r}, '--json']) == 0"
    )
    assert imported_after(code) == []


def test_solve_loads_no_3d_view():
    """The 3D view's libraries (plotly, trimesh) load only with --view or liftplan view."""
    code = (
        "import sys\nfrom liftplan.planner.cli import main\n"
        f"assert main(['solve', {str(EXAMPLES / 'tanker_upright.toml')!r}, '--json']) == 0\n"
        "assert 'plotly' not in sys.modules and 'trimesh' not in sys.modules, 'loaded'"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr


def test_lazy_exports_are_complete_and_solve_stays_the_function():
    for package in (liftplan.model, liftplan.planner):
        assert package.__all__ == sorted(package.__all__)
        for name in package.__all__:
            assert getattr(package, name) is not None, name
        assert set(package.__all__) <= set(dir(package))
    # importing the submodule of the same name must not replace the function
    importlib.import_module("liftplan.model.solve")
    importlib.import_module("liftplan.planner.plan")
    from liftplan.model import solve
    from liftplan.planner import plan

    assert callable(solve) and solve.__module__ == "liftplan.model.solve"
    assert callable(plan) and plan.__module__ == "liftplan.planner.plan"


def test_submodule_imported_first_still_leaves_the_function():
    code = (
        "import liftplan.model.solve, liftplan.planner.plan\n"
        "from liftplan.model import solve\nfrom liftplan.planner import plan\n"
        "assert callable(solve) and callable(plan), (solve, plan)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
