"""The example plans' reports, rendered as a person sees them: the printed PDF page by page
(poppler's pdftoppm) and the HTML in headless Chromium.

Run:  python studies/report_screenshot.py
      (writes studies/out/<example>_report/ (report.html, report.pdf, plan.json,
      plan_scene.toml) for each of tanker_plan, tanker_fleet and block_sling_plan, every PDF
      page side by side in studies/out/<example>_pages.png, and the tanker plan's HTML in
      Chromium as studies/out/tanker_report.png; needs the [pdf] extra and the Debian
      packages poppler-utils and chromium; what is missing is skipped and said so)
"""

from __future__ import annotations

import shutil
import subprocess
import tempfile
from pathlib import Path

from liftplan.planner.output.report.write import write_report
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem

HERE = Path(__file__).parent
EXAMPLES = ("tanker_plan", "tanker_fleet", "block_sling_plan")
DPI = 60  # a page is 496 x 702 px: every table and label can be read on screen


def pages(pdf, out):
    """Every page of ``pdf`` as out/page-N.png; the paths in page order."""
    subprocess.run(
        ["pdftoppm", "-png", "-r", str(DPI), str(pdf), str(out / "page")],
        check=True,
        capture_output=True,
        timeout=120,
    )
    return sorted(out.glob("page-*.png"), key=lambda p: int(p.stem.split("-")[-1]))


def contact_sheet(images, path, columns=4):
    """The pages side by side, ``columns`` to a row, as one PNG."""
    from PIL import Image

    opened = [Image.open(p) for p in images]
    width, height = opened[0].size
    rows = -(-len(opened) // columns)
    sheet = Image.new("RGB", (width * min(columns, len(opened)), height * rows), "white")
    for k, image in enumerate(opened):
        sheet.paste(image, ((k % columns) * width, (k // columns) * height))
    sheet.save(path)


def chromium(html_path, shot):
    with tempfile.TemporaryDirectory() as profile:
        subprocess.run(
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
                f"--user-data-dir={profile}",
                "--hide-scrollbars",
                "--window-size=900,3600",
                f"--screenshot={shot}",
                html_path.as_uri(),
            ],
            check=True,
            capture_output=True,
            timeout=120,
        )


def main():
    out = HERE / "out"
    for name in EXAMPLES:
        files = write_report(
            plan(load_problem(HERE.parent / "examples" / f"{name}.toml")), out / f"{name}_report"
        )
        if files.pdf is None:
            print(f"{name}: no PDF (pip install -e '.[pdf]'); wrote {files.html}")
        elif shutil.which("pdftoppm") is None:
            print(f"{name}: wrote {files.pdf}; pdftoppm missing (apt-get install poppler-utils)")
        else:
            with tempfile.TemporaryDirectory() as folder:
                images = pages(files.pdf, Path(folder))
                contact_sheet(images, out / f"{name}_pages.png")
            print(f"{name}: {len(images)} pages -> {out / f'{name}_pages.png'}")
        if name == "tanker_plan":
            if shutil.which("chromium") is None:
                print("tanker_plan: chromium missing (apt-get install chromium); no screenshot")
            else:
                chromium(files.html, out / "tanker_report.png")
                print(f"tanker_plan: HTML in Chromium -> {out / 'tanker_report.png'}")


if __name__ == "__main__":
    main()
