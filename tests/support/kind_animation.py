"""Checks the animations of the cam kinds share (``camgen animate`` of a kind drawn from its page's scene): frame
count and size read back from the GIF, the frames the kind's animation hook draws, one cycle, the same bytes twice."""
from __future__ import annotations

import numpy as np
from click.testing import CliRunner
from PIL import Image

from camgen import api
from camgen.cli import main
from camgen.kinds import spec_kind

SIZE = (160, 120)


def gif_frames(path) -> tuple[tuple[int, int], np.ndarray]:
    """The size and the frames (n, height, width, 3 floats) of the GIF at ``path``."""
    with Image.open(path) as im:
        out = []
        for k in range(im.n_frames):
            im.seek(k)
            out.append(np.asarray(im.convert("RGB"), dtype=float))
        return im.size, np.array(out)


def animate(template, folder, n: int, size: tuple[int, int] = SIZE):
    """``camgen animate template`` into ``folder`` at ``n`` frames of ``size``: the path written."""
    result = CliRunner().invoke(main, ["animate", str(template), "-o", str(folder), "--frames", str(n),
                                       "--size", f"{size[0]}x{size[1]}"])
    assert result.exit_code == 0, result.output
    return folder / f"{api.load(template).name}-animation.gif"


def drawn(template, n: int, size: tuple[int, int] = SIZE) -> np.ndarray:
    """The frames the kind of ``template`` draws at ``n`` frames (as floats)."""
    spec = api.load(template)
    return spec_kind(spec).animation(api.design(spec), n, size).astype(float)


def assert_animated(template, tmp_path, moves: bool = True) -> np.ndarray:
    """``camgen animate`` of ``template`` at 12 frames writes a GIF of 12 frames of :data:`SIZE` holding the kind's
    frames; frame k at 12 frames is frame 2k at 24 (the same angle, 30 k degrees, whatever the count); half a cycle
    on the drawing has moved (``moves``); a second run writes the same bytes. Returns the 12 frames."""
    path = animate(template, tmp_path / "a", 12)
    size, read = gif_frames(path)
    assert size == SIZE and read.shape == (12, SIZE[1], SIZE[0], 3)
    twelve, twice = drawn(template, 12), drawn(template, 24)
    assert np.abs(read - twelve).mean() < 3.0                  # a palette of 256 colours a frame
    assert np.abs(twice[::2] - twelve).mean() < 0.05           # the same poses at the same angles
    assert np.abs(twice[1] - twelve[0]).mean() > 0.05          # ... and 24 frames draw poses between them
    if moves:
        assert np.abs(twelve[6] - twelve[0]).mean() > 1.0
    assert animate(template, tmp_path / "b", 12).read_bytes() == path.read_bytes()
    return twelve


def page_frame(template, n: int, k: int):
    """The design of ``template``, its page (as its bundle's report makes it) and the page frame that frame ``k``
    of ``n`` shows."""
    from camgen.core.scene_frames import frame_indices

    spec = api.load(template)
    kind = spec_kind(spec)
    design = api.design(spec)
    return design, kind.bundle(design)[1], int(frame_indices(360, n, kind.title)[k])


#: the colour a roller's circle is drawn in (matplotlib's C2, :data:`camgen.core.scene_frames.CIRCLE`)
GREEN = np.array([0x2C, 0xA0, 0x2C], dtype=float)


def on_circle(frame: np.ndarray, box, centre, radius: float) -> float:
    """The share of 72 points round the circle of ``radius`` (mm) about ``centre`` (x, y mm) that fall within one
    pixel of a pixel drawn green in ``frame`` (height, width, 3), the frame's view being the page's ``box`` fitted as
    :func:`camgen.core.frames.render` fits it (axes over 96 % of the frame, equal scale)."""
    from camgen.core.frames import _fitted

    h, w = frame.shape[:2]
    x0, y0, x1, y1 = _fitted(box, w / h)
    a = np.linspace(0, 2 * np.pi, 72, endpoint=False)
    x = centre[0] + radius * np.cos(a)
    y = centre[1] + radius * np.sin(a)
    col = (0.02 + 0.96 * (x - x0) / (x1 - x0)) * w
    row = (1 - (0.02 + 0.96 * (y - y0) / (y1 - y0))) * h
    green = np.abs(frame - GREEN).max(axis=-1) < 40
    hits = 0
    for c, r in zip(col, row, strict=True):
        ci, ri = int(np.floor(c)), int(np.floor(r))
        hits += bool(green[max(ri - 1, 0):ri + 2, max(ci - 1, 0):ci + 2].any())
    return hits / len(a)
