"""The report as printed: whether the PDF can be made and read back here, and each page rendered
with poppler (``pdftoppm`` to PNG, ``pdftotext`` for the text)."""

import shutil
import subprocess

import numpy as np
import pytest

DPI = 40  # enough to see a column of ink; 8 pages render in well under a second
A4_WIDTH_MM = 210.0
# anti-aliasing spreads ink by up to a pixel (0.64 mm at 40 dpi) past an edge
EDGE_MM = 1.0


def missing():
    try:
        import weasyprint  # noqa: F401
    except (ImportError, OSError):
        return "WeasyPrint (the [pdf] extra) not installed or its Pango library missing"
    for tool in ("pdftoppm", "pdftotext"):
        if shutil.which(tool) is None:
            return f"{tool} not found (Debian package poppler-utils)"
    return None


needs_pdf = pytest.mark.skipif(missing() is not None, reason=missing() or "")


def ink_extent_mm(png):
    """(leftmost, rightmost) column with ink on a rendered page  [mm from the left edge];
    None for a blank page."""
    from PIL import Image

    with Image.open(png) as image:
        grey = np.asarray(image.convert("L"))
    columns = np.flatnonzero((grey < 200).any(axis=0))
    if columns.size == 0:
        return None
    mm_per_px = 25.4 / DPI
    return columns[0] * mm_per_px, (columns[-1] + 1) * mm_per_px


def render(pdf, out):
    """Every page of ``pdf`` as PNG at DPI, in page order; and the text of each page."""
    subprocess.run(
        ["pdftoppm", "-png", "-r", str(DPI), str(pdf), str(out / "page")],
        check=True,
        capture_output=True,
        timeout=120,
    )
    pages = sorted(out.glob("page-*.png"), key=lambda p: int(p.stem.split("-")[-1]))
    text = subprocess.run(
        ["pdftotext", "-layout", str(pdf), "-"], check=True, capture_output=True, text=True, timeout=120
    ).stdout
    return pages, text.split("\f")[: len(pages)]
