"""The tanker plan's report, rendered as a person sees it: headless Chromium screenshot.

Run:  python studies/report_screenshot.py
      (writes studies/out/tanker_report/ and studies/out/tanker_report.png; needs the
      Debian package chromium)
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from liftplan.planner.plan import plan
from liftplan.planner.problemfile import load_problem
from liftplan.planner.report import write_report

HERE = Path(__file__).parent


def main():
    browser = shutil.which("chromium")
    if browser is None:
        sys.exit("report_screenshot: Debian's chromium is needed (apt-get install chromium)")
    problem = load_problem(HERE.parent / "examples" / "tanker_plan.toml")
    files = write_report(plan(problem), HERE / "out" / "tanker_report")
    shot = HERE / "out" / "tanker_report.png"
    with tempfile.TemporaryDirectory() as profile:
        subprocess.run(
            [browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
             "--no-first-run", "--disable-background-networking", "--disable-component-update",
             "--disable-sync", f"--user-data-dir={profile}", "--hide-scrollbars",
             "--window-size=1200,3600", f"--screenshot={shot}", files.html.as_uri()],
            check=True, capture_output=True, timeout=120,
        )
    print(f"wrote {files.html} and {shot}")


if __name__ == "__main__":
    main()
