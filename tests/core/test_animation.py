"""``linkgen animate`` and ``camgen animate``: frame count and size read back, one cycle (the cycle's frame n drawn
again matches frame 0), GIF bytes the same run after run, the inputs of a cycle, bad options refused in one line."""
from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen_main
from camgen.core.frames import cycle
from camgen.core.writers.animation import write_animation
from linkgen.cli import main as linkgen_main
from tests.conftest import ROOT
from tests.support.kind_animation import gif_frames

STEPHENSON = ROOT / "templates" / "stephenson3.toml"
ROCKER = ROOT / "templates" / "crank-rocker.toml"
CAM = ROOT / "templates" / "rdrd.toml"
SIZE = (160, 120)


def animate(main, template, folder, *options):
    return CliRunner().invoke(main, ["animate", str(template), "-o", str(folder), *map(str, options)])


def test_cycle_inputs():
    assert cycle(4, True, 0.5, 0.0) == pytest.approx([0.5, 0.5 + math.pi / 2, 0.5 + math.pi, 0.5 + 1.5 * math.pi])
    # forth and back: from lo to hi at half the cycle, slowing as a cosine at both ends
    assert cycle(4, False, 1.0, 3.0) == pytest.approx([1.0, 2.0, 3.0, 2.0])


def _linkage(template):
    from linkgen.animation import analysis_for_animation
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import load_spec

    return analysis_for_animation(design_linkage(load_spec(template)))


def test_linkage_gif_count_size_and_one_cycle(tmp_path):
    from linkgen.animation import cycle_inputs, frames_at, linkage_frames

    result = animate(linkgen_main, STEPHENSON, tmp_path, "--frames", 12, "--size", "160x120")
    assert result.exit_code == 0, result.output
    path = tmp_path / "stephenson3-animation.gif"
    assert result.output.strip() == f"wrote {path}"
    size, read = gif_frames(path)
    assert size == SIZE and read.shape == (12, 120, 160, 3)
    a = _linkage(STEPHENSON)
    values = cycle_inputs(a, 12)
    step = values[1] - values[0]
    assert step == pytest.approx(2 * math.pi / 12)
    drawn = linkage_frames(a, 12, SIZE).astype(float)
    again = frames_at(a, np.array([values[-1] + step]), SIZE).astype(float)[0]   # the cycle's frame 12
    assert np.abs(again - drawn[0]).mean() < 0.05          # the same pose: only edge pixels may round otherwise
    assert np.abs(drawn[6] - drawn[0]).mean() > 1.0        # half a turn on, the linkage has moved
    assert np.abs(drawn[-1] - drawn[0]).mean() > 0.1       # the last frame is a step before the first, not it
    # the GIF holds those frames (a palette of 256 colours a frame: a small error at every pixel, none far off: median
    # cut's palette had a mean error of 0.01 but left some antialiased pixels over 100 off on a channel)
    assert np.abs(read - drawn).mean() < 3.0 and np.abs(read - drawn).max() <= 16
    one = tmp_path / "again.gif"
    write_animation(again[None].astype(np.uint8), one, "gif", 24)
    assert np.abs(gif_frames(one)[1][0] - read[0]).mean() < 0.5


def test_gif_is_deterministic(tmp_path):
    first, second = tmp_path / "a", tmp_path / "b"
    for folder in (first, second):
        result = animate(linkgen_main, ROCKER, folder, "--frames", 6, "--size", "96x64")
        assert result.exit_code == 0, result.output
    name = "crank-rocker-animation.gif"
    assert (first / name).read_bytes() == (second / name).read_bytes()


def test_limited_input_goes_forth_and_back():
    """An input limited to a range (here linkage.input.range = [10, 100] degrees) goes from one end to the other at
    half the cycle and back, at lo + (hi - lo)(1 - cos(2 pi k / n)) / 2; a full-turning crank makes one turn."""
    from linkgen.animation import analysis_for_animation, cycle_inputs
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import load_spec

    a = analysis_for_animation(design_linkage(load_spec(STEPHENSON, ["linkage.input.range=[10,100]"])))
    values = np.degrees(cycle_inputs(a, 8))
    half = 45 * (1 - math.cos(math.pi / 4))
    assert values == pytest.approx([10, 10 + half, 55, 100 - half, 100, 100 - half, 55, 10 + half], abs=1e-9)
    full = np.degrees(cycle_inputs(_linkage(STEPHENSON), 8))
    assert full == pytest.approx(full[0] + 45 * np.arange(8), abs=1e-9)
    assert full[0] == pytest.approx(60.0, abs=1e-6)                  # from the drawing: the crank at 60 degrees


@pytest.mark.parametrize("fmt", ["mp4", "webm"])
def test_video_count_size_and_one_cycle(tmp_path, fmt):
    iio = pytest.importorskip("imageio.v3")
    from linkgen.animation import cycle_inputs, frames_at

    result = animate(linkgen_main, ROCKER, tmp_path, "--frames", 10, "--size", "128x96", "--format", fmt)
    assert result.exit_code == 0, result.output
    read = iio.imread(tmp_path / f"crank-rocker-animation.{fmt}").astype(float)
    assert read.shape == (10, 96, 128, 3)
    a = _linkage(ROCKER)
    values = cycle_inputs(a, 10)
    again = frames_at(a, np.array([2 * values[-1] - values[-2]]), (128, 96)).astype(float)[0]
    assert np.abs(read[0] - again).mean() < 4.0            # lossy video: a few levels a pixel
    assert np.abs(read[5] - again).mean() > np.abs(read[0] - again).mean() + 1.0
    assert [p.name for p in tmp_path.iterdir()] == [f"crank-rocker-animation.{fmt}"]   # no temporary left


def test_cam_gif_count_size_and_one_turn(tmp_path):
    from camgen import api
    from camgen.animation import cam_angles, disc_design, frames_at

    result = animate(camgen_main, CAM, tmp_path, "--frames", 8, "--size", "120x120")
    assert result.exit_code == 0, result.output
    size, read = gif_frames(tmp_path / "rdrd-animation.gif")
    assert size == (120, 120) and len(read) == 8
    design = disc_design(api.design(api.load(CAM)))
    theta = cam_angles(8)
    assert theta[1] == pytest.approx(math.pi / 4)
    drawn = frames_at(design, np.append(theta, 2 * math.pi), (120, 120)).astype(float)
    assert np.abs(drawn[8] - drawn[0]).mean() < 0.05
    assert np.abs(drawn[4] - drawn[0]).mean() > 1.0
    assert np.abs(read - drawn[:8]).mean() < 3.0


def test_follower_rides_the_lift():
    """The roller centre drawn at cam angle theta sits at the prime radius + s(theta) on the follower's axis (an
    in-line translating roller): the frame's follower comes from the cam's own motion, not a constant."""
    from camgen import api
    from camgen.animation import disc_design
    from camgen.followers.base import rotate

    design = disc_design(api.design(api.load(CAM)))
    cam = design.cam
    sense = 1.0 if design.spec.cam.rotation == "ccw" else -1.0
    theta = np.linspace(0, 2 * math.pi, 37)
    centre = rotate(cam.pitch(theta).point, sense * theta)
    s = cam.program.evaluate(theta)[0]
    offset = getattr(cam.follower, "offset", 0.0)
    assert centre[:, 0] == pytest.approx(np.full(37, offset), abs=1e-9)
    prime = math.sqrt((cam.base_radius + cam.contact_radius) ** 2 - offset ** 2)
    assert centre[:, 1] == pytest.approx(prime + s, abs=1e-9)


@pytest.mark.parametrize(("main", "template", "args", "option"), [
    (linkgen_main, ROCKER, ["--frames", "1"], "--frames"),
    (linkgen_main, ROCKER, ["--frames", "721"], "--frames"),
    (linkgen_main, ROCKER, ["--size", "640"], "--size"),
    (linkgen_main, ROCKER, ["--size", "641x480"], "--size"),
    (linkgen_main, ROCKER, ["--size", "4000x480"], "--size"),
    (linkgen_main, ROCKER, ["--fps", "0"], "--fps"),
    (linkgen_main, ROCKER, ["--fps", "nan"], "--fps"),
    (linkgen_main, ROCKER, ["--format", "avi"], "--format"),
    (camgen_main, CAM, ["--frames", "0"], "--frames"),
    (linkgen_main, ROOT / "templates" / "counter.toml", [], "linkage.type"),
    (camgen_main, ROOT / "templates" / "barrel.toml", ["--frames", "7"], "--frames"),
])
def test_bad_options_refused(tmp_path, main, template, args, option):
    folder = tmp_path / "out"
    result = CliRunner().invoke(main, ["animate", str(template), "-o", str(folder), "--frames", "4", *args])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and option in lines[0], result.output
    assert not folder.exists()
