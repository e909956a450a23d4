"""The one report writer: report.html (and report.pdf), plan_scene.toml and plan.json.

The page and the scene file come from the plan's kind (:data:`PAGES`, keyed by ``plan.kind``);
what is written, where, and how (the PDF only with the ``[pdf]`` extra) is decided here for
every kind.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

from liftplan.model.version import stamped
from liftplan.planner.output.paths import replaced
from liftplan.planner.output.report import held, slings, strength
from liftplan.planner.output.report.view import for_print
from liftplan.planner.plans.protocol import LiftPlan

#: plan kind (:data:`liftplan.planner.plan.KINDS`) -> ``render(plan) -> (html, scene toml)``.
PAGES = {
    "held": held.render,
    "lengths": held.render,
    "slings": slings.render,
    "strength": strength.render,
}


@dataclass(frozen=True)
class ReportFiles:
    """Files written by :func:`write_report`.

    Parameters
    ----------
    html : Path
    pdf : Path or None
        None when WeasyPrint is not installed.
    scene : Path
        The chosen plan as a scene file (``liftplan solve`` reproduces the tensions).
    json : Path
    """

    html: Path
    pdf: Path | None
    scene: Path
    json: Path


def write_report(plan: LiftPlan, directory: str | os.PathLike[str]) -> ReportFiles:
    """Write the report of any plan into ``directory`` (created if needed).

    Parameters
    ----------
    plan : LiftPlan
    directory : str or os.PathLike

    Returns
    -------
    ReportFiles
    """
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    page, scene_text = PAGES[plan.kind](plan)
    html_path, scene_path, json_path = out / "report.html", out / "plan_scene.toml", out / "plan.json"
    texts = (page, scene_text, json.dumps(stamped(plan.to_json()), indent=1))
    for path, text in zip((html_path, scene_path, json_path), texts):
        with replaced(path) as temporary:  # whole or not at all (a full disk)
            temporary.write_text(text, encoding="utf-8")
    pdf_path = None
    try:
        import weasyprint  # optional (pip install "liftplan[pdf]"), and heavy: only here
    except (ImportError, OSError):  # OSError: installed, but the system's Pango is missing
        pass
    else:
        pdf_path = out / "report.pdf"
        with replaced(pdf_path) as temporary:
            weasyprint.HTML(string=for_print(page)).write_pdf(temporary)
    return ReportFiles(html=html_path, pdf=pdf_path, scene=scene_path, json=json_path)
