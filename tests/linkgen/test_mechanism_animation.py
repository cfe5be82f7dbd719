"""``linkgen animate`` of the dedicated mechanisms that draw themselves (the gear pair, the gear trains, the
ratchet): frame count and size read back, one cycle (frame n drawn again is frame 0, frame n/2 is not), the parts drawn
where their kinematics puts them to a pixel, the same bytes twice, and the ``gif`` of ``output.formats`` as
``animate`` writes it."""
from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.core.frames import _fitted, bounds
from linkgen.cli import main as linkgen_main
from tests.conftest import ROOT
from tests.support.kind_animation import gif_frames

PAIR = ROOT / "templates" / "gear-pair.toml"
PLANETARY = ROOT / "templates" / "planetary-train.toml"
RATCHET = ROOT / "templates" / "ratchet.toml"
SIZE = (160, 120)
#: matplotlib's C4 (the ratchet's lever), C3 (the input's tooth-0 mark) and C2 (the gear's fill, drawn at alpha 0.45
#: on white)
PURPLE = np.array([0x94, 0x67, 0xBD], dtype=float)
RED = np.array([0xD6, 0x27, 0x28], dtype=float)
GREEN = 255 - 0.45 * (255 - np.array([0x2C, 0xA0, 0x2C], dtype=float))


def _design(template):
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import load_spec

    return design_linkage(load_spec(template))


def _animate(template, folder, n: int, size=SIZE):
    result = CliRunner().invoke(linkgen_main, ["animate", str(template), "-o", str(folder), "--frames", str(n),
                                               "--size", f"{size[0]}x{size[1]}"])
    assert result.exit_code == 0, result.output
    return folder / f"{template.stem}-animation.gif"


def _pixel(box, size, xy) -> tuple[int, int]:
    """(row, column) of the point ``xy`` (mm) in a frame of ``size`` showing ``box`` as render fits it."""
    w, h = size
    x0, y0, x1, y1 = _fitted(box, w / h)
    col = (0.02 + 0.96 * (xy[0] - x0) / (x1 - x0)) * w
    row = (1 - (0.02 + 0.96 * (xy[1] - y0) / (y1 - y0))) * h
    return int(np.floor(row)), int(np.floor(col))


def _near(frame, rc, colour, within: float = 40.0) -> bool:
    """Whether a pixel within one of ``rc`` in ``frame`` is ``colour`` (each channel within ``within``)."""
    r, c = rc
    patch = frame[max(r - 1, 0):r + 2, max(c - 1, 0):c + 2].astype(float)
    return bool((np.abs(patch - colour).max(axis=-1) < within).any())


@pytest.mark.parametrize(("template", "n"), [(PAIR, 12), (PLANETARY, 8), (RATCHET, 6)])
def test_count_size_drawn_frames_and_same_bytes(tmp_path, template, n):
    from linkgen.animation import design_frames

    path = _animate(template, tmp_path / "a", n)
    size, read = gif_frames(path)
    assert size == SIZE and read.shape == (n, SIZE[1], SIZE[0], 3)
    drawn = design_frames(_design(template), n, SIZE).astype(float)
    assert np.abs(read - drawn).mean() < 3.0                     # a palette of 256 colours a frame
    assert _animate(template, tmp_path / "b", n).read_bytes() == path.read_bytes()


def test_gear_pair_cycle_is_one_pinion_turn():
    from linkgen.animation import design_frames_at, design_inputs

    d = _design(PAIR)
    values = design_inputs(d, 12)
    # 15 teeth driving 36: in a pinion turn the gear turns 15 of its 36 pitches, so its teeth are back in place
    assert values == pytest.approx(2 * math.pi * np.arange(12) / 12, abs=1e-12)
    frames = design_frames_at(d, np.append(values, 2 * math.pi), SIZE).astype(float)
    assert np.abs(frames[12] - frames[0]).mean() < 0.05
    assert np.abs(frames[6] - frames[0]).mean() > 1.0
    # half a gear pitch later the gear's teeth stand where its spaces stood
    half = design_frames_at(d, np.array([math.pi / 15]), SIZE).astype(float)
    assert np.abs(half[0] - frames[0]).mean() > 1.0


def test_planetary_cycle_is_six_sun_turns():
    from linkgen.animation import design_frames_at, design_inputs

    d = _design(PLANETARY)
    # Willis with the ring fixed: the carrier turns 30 / (30 + 78) = 5/18 of the sun's speed, its 3 planets' spacing
    # coming back every 5/6 of a spacing a sun turn: 6 turns; each planet turns 5/18 - (1 - 5/18) 30/24 = -5/8, i.e.
    # -15 of its 24 pitches a turn (whole). So the cycle is 6 sun turns, not 1 or 3.
    values = design_inputs(d, 12)
    assert values == pytest.approx(6 * 2 * math.pi * np.arange(12) / 12, abs=1e-9)
    turns = 2 * math.pi * np.array([0.0, 1.0, 3.0, 6.0])
    frames = design_frames_at(d, turns, SIZE).astype(float)
    assert np.abs(frames[3] - frames[0]).mean() < 0.05
    assert np.abs(frames[1] - frames[0]).mean() > 1.0
    assert np.abs(frames[2] - frames[0]).mean() > 1.0


@pytest.mark.parametrize("k", [1, 4, 7])
def test_gear_pair_parts_where_the_kinematics_puts_them(k):
    from linkgen.animation import design_frames_at

    d = _design(PAIR)
    pair, size = d.kinematics, (480, 360)
    r1, r2 = pair.working_pitch_radii                           # m z / 2 with the shifts summing to 0: 11.25, 27
    assert (r1, r2) == pytest.approx((1.5 * 15 / 2, 1.5 * 36 / 2))
    c, m = pair.centre_distance, pair.module
    theta = 2 * math.pi * k / 12
    # the gear turns the other way at 15/36 of the pinion's speed, a space facing the pinion's tooth 0 at angle 0
    gear = math.pi - math.pi / 36 - theta * 15 / 36
    assert float(pair.gear_angle(np.array([theta]))[0]) == pytest.approx(gear, abs=1e-12)
    frame = design_frames_at(d, np.array([theta]), size)[0]
    tips = (pair.pinion_tooth.tip_radius, pair.gear_tooth.tip_radius)
    box = bounds(np.array([[-tips[0], -tips[0]], [tips[0], tips[0]]]),
                 np.array([[c - tips[1], -tips[1]], [c + tips[1], tips[1]]]))
    u = np.array([math.cos(theta), math.sin(theta)])
    for share in (0.4, 0.6, 0.8):                                # the pinion's tooth-0 radius
        assert _near(frame, _pixel(box, size, share * r1 * u), RED)
        assert not _near(frame, _pixel(box, size, -share * r1 * u), RED)
    # a gear tooth on its far side (facing +X) centred at its angle + j pitches, a space half a pitch on
    pitch = 2 * math.pi / 36
    j = round(-gear / pitch)
    radius = r2 - 0.4 * m                                        # above its root (r2 - 1.25 m), below its pitch line
    for offset, tooth in ((0.0, True), (0.5, False)):
        a = gear + (j + offset) * pitch
        rc = _pixel(box, size, (c + radius * math.cos(a), radius * math.sin(a)))
        assert frame[rc][1] > 0 and (np.abs(frame[rc].astype(float) - GREEN).max() < 40) == tooth


@pytest.mark.parametrize("k", [1, 5])
def test_planetary_carrier_where_willis_puts_it(k):
    from linkgen.animation import design_frames_at

    d = _design(PLANETARY)
    size = (480, 360)
    theta = 6 * 2 * math.pi * k / 12
    carrier = theta * 30 / 108
    frame = design_frames_at(d, np.array([theta]), size)[0]
    a = 2.0 * (30 + 24) / 2                                      # the planets' centres from the sun's, mm
    tip = 2.0 * (78 / 2 + 1.25)                                  # the ring's root: its master's tip circle
    box = bounds(np.array([[-tip, -tip], [tip, tip]]))
    dark = np.zeros(3)
    for planet in range(3):
        u = carrier + 2 * math.pi * planet / 3
        on = _pixel(box, size, 0.5 * a * np.array([math.cos(u), math.sin(u)]))
        off = _pixel(box, size, 0.5 * a * np.array([math.cos(u + math.pi / 3), math.sin(u + math.pi / 3)]))
        assert _near(frame, on, dark, 90.0) and not _near(frame, off, dark, 90.0)


def test_page_gif_is_the_animation(tmp_path):
    analysed = CliRunner().invoke(linkgen_main, ["analyze", str(PAIR), "-o", str(tmp_path / "p"), "--set",
                                                 'output.formats=["json", "gif"]'])
    assert analysed.exit_code == 0, analysed.output
    animated = CliRunner().invoke(linkgen_main, ["animate", str(PAIR), "-o", str(tmp_path / "a")])
    assert animated.exit_code == 0, animated.output
    name = "gear-pair-animation.gif"
    assert (tmp_path / "p" / name).read_bytes() == (tmp_path / "a" / name).read_bytes()


def test_ratchet_cycle_is_one_stroke_a_tooth_on():
    from linkgen.animation import design_frames_at
    from linkgen.mechanisms.ratchetframes import lever_wheel

    d = _design(RATCHET)
    # a 15 degree swing over 30 teeth (12 degrees a pitch) indexes one tooth: the wheel is 12 degrees on after a
    # stroke, 15 at the stroke's end, and back on the holding pawl at 12 as the lever returns
    lever, wheel = lever_wheel(d.kinematics, np.array([0.0, math.pi / 2, math.pi, 1.5 * math.pi, 2 * math.pi]))
    assert np.degrees(lever) == pytest.approx([0.0, 7.5, 15.0, 7.5, 0.0], abs=1e-9)
    assert np.degrees(wheel) == pytest.approx([0.0, 7.5, 15.0, 12.0, 12.0], abs=1e-9)
    frames = design_frames_at(d, np.array([0.0, math.pi, 2 * math.pi]), SIZE).astype(float)
    assert np.abs(frames[2] - frames[0]).mean() < 0.05
    assert np.abs(frames[1] - frames[0]).mean() > 1.0


@pytest.mark.parametrize("u", [1.5, 5.0])
def test_ratchet_lever_and_pawls(u):
    import shapely

    from camgen.core.shapes import Contour
    from linkgen.animation import design_frames_at
    from linkgen.mechanisms.ratchet import pawl_shape
    from linkgen.mechanisms.ratchetframes import _turned, lever_wheel, lift

    d = _design(RATCHET)
    r, size = d.kinematics, (480, 360)
    phi = math.radians(15.0) * (1 - math.cos(u)) / 2
    # the lever's pawl is the holding one turned by tooth 15's 180 degrees: its pivot at -((0, 45) + 32 (1, 0)),
    # the handle 85 mm out along that line
    rest = -np.array([32.0, 45.0])
    handle = 85.0 * rest / np.hypot(*rest)
    at = _turned(handle[None], phi)[0]
    frame = design_frames_at(d, np.array([u]), size)[0]
    drawn = np.argwhere(np.abs(frame.astype(float) - PURPLE).max(axis=-1) < 40)
    rows, cols = drawn[:, 0], drawn[:, 1]
    # the handle is the end of the purple lever farthest from the wheel's axis (the axis's pixel found the same way)
    axis = _pixel_of(frame, size, d, np.zeros(2))
    tip = drawn[np.argmax(np.hypot(rows - axis[0], cols - axis[1]))]
    assert np.hypot(*(tip - np.array(_pixel_of(frame, size, d, at)))) <= 4.0      # the marker's radius, 2 px, + 2
    # the pawls clear the wheel; half way out (u = 1.5: the wheel 7 degrees on) the lever's pawl drives (no lift)
    # and the holding one rides over tooth 1's back; half way back (u = 5: the lever 5.4 degrees out, the wheel held
    # at 12) the holding pawl holds and the lever's rides over a tooth's back
    wheel_turn = float(lever_wheel(r, np.array([u]))[1][0])
    teeth = _turned(Contour(*r.wheel.outline()).flatten(0.05), wheel_turn)
    pawl = Contour(*pawl_shape(r, 1.5 * 5.0, 0.05)).flatten(0.05)
    on_lever = _turned(_turned(pawl, math.pi), phi)
    pivot = _turned(_turned(r.pawl.pivot[None], math.pi), phi)[0]
    held, driven = lift(pawl, r.pawl.pivot, teeth), lift(on_lever, pivot, teeth)
    for xy, about, beta in ((pawl, r.pawl.pivot, held), (on_lever, pivot, driven)):
        assert not shapely.Polygon(_turned(xy, beta, about)).intersects(shapely.Polygon(teeth))
    if u < math.pi:
        assert driven == 0.0 and held != 0.0
    else:
        assert held == 0.0 and driven != 0.0


def _pixel_of(frame, size, design, xy):
    """The pixel of ``xy`` (mm) in a ratchet frame of ``size`` (the region its frames show: wheel, pawls, arc)."""
    from linkgen.mechanisms.ratchetframes import view

    return _pixel(view(design.kinematics, 1.5 * 5.0), size, xy)
