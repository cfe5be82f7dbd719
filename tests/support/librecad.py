"""LibreCAD's printing of our DXF files, as the tests run it: ``librecad dxf2pdf`` at scale 1, centred on a page,
each PDF rasterised by ``pdftoppm`` and the ink's extent measured."""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

#: the resolution the printed pages are rasterised at (dots per inch): a pixel is 0.508 mm
DPI = 50


def _need(program: str) -> str:
    path = shutil.which(program)
    if path is None:
        pytest.skip(f"{program} is not installed (Debian package; .ci/run installs it)")
    return path


def printed_extents(dxfs: list[Path], folder: Path, page_mm: float) -> dict[Path, tuple[float, float]]:
    """The width and height (mm) of the ink of each of ``dxfs`` as LibreCAD prints it at scale 1, centred on a
    square page ``page_mm`` across, all in one LibreCAD process (its PDFs written into ``folder``); skipped where
    LibreCAD or pdftoppm is not installed. Measured to a pixel (:data:`DPI`)."""
    librecad, pdftoppm = _need("librecad"), _need("pdftoppm")
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen"}
    size = f"{page_mm:.0f}x{page_mm:.0f}"
    # wrapped in timeout: LibreCAD hangs on a file it cannot read; -t sets the folder of <name>.pdf
    subprocess.run(["timeout", "300", librecad, "dxf2pdf", "-s", "1", "-c", "-p", size, "-t", str(folder),
                    *(str(d) for d in dxfs)], env=env, capture_output=True, text=True, timeout=330)
    from PIL import Image

    out = {}
    for dxf in dxfs:
        pdf = folder / f"{dxf.stem}.pdf"
        assert pdf.exists(), f"LibreCAD wrote no PDF of {dxf.name}"
        subprocess.run([pdftoppm, "-r", str(DPI), "-gray", "-png", "-singlefile", str(pdf), str(folder / dxf.stem)],
                       check=True, timeout=120)
        page = np.asarray(Image.open(folder / f"{dxf.stem}.png").convert("L"))
        ink = np.argwhere(page < 128)
        assert len(ink), f"LibreCAD printed nothing of {dxf.name}"
        (y0, x0), (y1, x1) = ink.min(axis=0), ink.max(axis=0)
        out[dxf] = (float(x1 - x0) / DPI * 25.4, float(y1 - y0) / DPI * 25.4)
    return out
