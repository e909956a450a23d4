"""The documentation site builds with warnings as errors (``mkdocs build --strict``).

mkdocs.yml sets ``strict`` and turns broken links, broken anchors and pages left out of the
nav into warnings, so this test fails on any of them, on a snippet of the README that has
gone, and on an API reference name mkdocstrings cannot find. It builds into a temporary
folder (a few seconds) and is skipped, and says so, without the ``docs`` extra
(``pip install -e ".[docs]"``).
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from helpers import ROOT

for module in ("mkdocs", "material", "mkdocstrings", "mkdocstrings_handlers.python"):
    pytest.importorskip(
        module, reason=f"{module} is not installed: pip install -e '.[docs]' to build the docs"
    )


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("docs") / "site"
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(out)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},
    )
    assert done.returncode == 0, f"mkdocs build --strict failed:\n{done.stderr[-4000:]}"
    return out


def test_the_site_builds_with_warnings_as_errors(site):
    assert (site / "index.html").is_file()


def test_the_api_reference_has_the_packages_public_names(site):
    # the hook makes griffe see the lazily exported names; without it the pages would be
    # built (and pass --strict) with nothing but the package docstrings
    for page, names in {
        "api-model": ("liftplan.model.solve", "liftplan.model.load_scene", "liftplan.model.Equilibrium"),
        "api-planner": ("liftplan.planner.plan", "liftplan.planner.load_problem", "liftplan.planner.Plan"),
        "api-rules": ("liftplan.model.rules.DesignLoadChain",),
        "api-strength": ("liftplan.model.strength.hull_girder",),
    }.items():
        html = (site / page / "index.html").read_text(encoding="utf-8")
        missing = [name for name in names if f'id="{name}"' not in html]
        assert not missing, f"docs/{page}.md does not document {', '.join(missing)}"


def test_the_studies_figures_are_on_the_site(site):
    for page, figure in (("planning", "rope_lengths.png"), ("batch", "hook_montecarlo.png")):
        assert f"studies/out/{figure}" in (site / page / "index.html").read_text(encoding="utf-8")
        assert (site / "studies" / "out" / figure).is_file()
