"""The counter (issue 34, item 3): a ratchet's units wheel that steps a Geneva tens wheel once a turn.

* The count: after k strokes (k up to three turns of the units wheel, several wheels) the tens wheel has made
  floor(k / N) steps, N the strokes a turn (standing exactly at its step where the stroke ends outside the
  window); the units wheel k index steps.
* The window: the tens wheel moves only while the pin is between its entry and exit, the points where the slot's
  line from the tens wheel's axis is tangent to the pin's circle (acos(a / C) either side of the line of centres,
  from the geometry, not the kinematics' pi - 2 pi / n); in it the tens wheel's turn is the pin's direction from its
  axis (the pin sits on the slot's centre line), and its rate the difference of that turn.
* The parts against closed forms: the tens wheel's slot flanks h off their centre lines from the rim R_w =
  sqrt(b^2 + h^2) to the bottom's half circle about C - a, its locking arcs of radius R_l about C out on each
  bisector; the locking disc's arcs on r_l and on the cutout's circle; the transfer pin's hole a from the axis.
* Locked otherwise: at the dwell's poses the tens wheel clears the locking disc but meets it (or the pin) when
  turned either way by a few degrees at most, less at the strokes' ends (shapely); over the window neither the
  disc nor the transfer pin overlaps the wheel.
* Bad input (teeth 0 or 10,000, a pin circle off the wheel, an index that does not divide the teeth, a tens wheel on
  the pawl's pins) is one line naming the field, exit 2, nothing written.
"""
from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import pytest
import shapely
import shapely.affinity
from click.testing import CliRunner

from camgen.core.spec import apply_overrides
from linkgen.mechanisms import MECHANISMS
from linkgen.mechanisms.counter import geneva_step
from linkgen.parts import Stock
from linkgen.spec import validate_spec
from tests.conftest import ROOT
from tests.support.refusals import assert_refused_sets

TEMPLATE = ROOT / "templates" / "counter.toml"
#: (teeth, lever swing, slots, centre distance, transfer angle): the bundled counter, a 12-tooth wheel indexed two
#: teeth a stroke (6 strokes a turn) with a 6-slot wheel, and a 20-tooth wheel with a 4-slot one to its left
CASES = [(10, 40.0, 10, 97.0, -90.0), (12, 65.0, 6, 70.0, -100.0), (20, 20.0, 4, 54.0, 180.0)]


def _spec(teeth: int = 10, swing: float = 40.0, slots: int = 10, centre: float = 97.0, angle: float = -90.0):
    raw = tomllib.loads(TEMPLATE.read_text(encoding="utf-8"))
    return validate_spec(apply_overrides(raw, [("linkage.teeth", teeth), ("linkage.lever.swing", swing),
                                               ("linkage.transfer.slots", slots),
                                               ("linkage.transfer.centre_distance", centre),
                                               ("linkage.transfer.angle", angle)]))


def _built(case):
    spec = _spec(*case)
    mechanism = MECHANISMS["counter"]
    counter = mechanism.build(spec.linkage)
    return spec, mechanism, counter


@pytest.mark.parametrize("case", CASES)
def test_the_tens_wheel_counts_floor_k_over_n_for_three_turns(case):
    spec, mechanism, counter = _built(case)
    teeth, swing = case[0], math.radians(case[1])
    per_stroke = math.floor(swing / (2 * math.pi / teeth))
    n = teeth // per_stroke
    assert counter.strokes_per_turn == n
    k = np.arange(3 * n + 1)
    _, units, tens = counter.count(k.astype(float))
    np.testing.assert_allclose(units, k * per_stroke * 2 * math.pi / teeth, rtol=0, atol=1e-12)
    step = 2 * math.pi / case[2]
    np.testing.assert_array_equal(np.floor(tens / step + 1e-9), k // n)         # its completed steps
    start, end = counter.window()
    within = np.remainder(units, 2 * math.pi)
    dwelling = (within <= start) | (within >= end)           # stroke ends outside the window: exactly at its step
    assert dwelling.sum() >= 3 * (n - math.ceil((end - start) / counter.index))
    np.testing.assert_allclose(tens[dwelling], (k // n)[dwelling] * step, rtol=0, atol=1e-12)
    report = mechanism.report(spec.linkage, counter, None, "closed")
    assert report["count"]["strokes"] == 3 * n
    assert report["count"]["tens_index"] == [int(v) % case[2] for v in k // n]
    assert report["count"]["units_index"] == [int(v) % n for v in k]


def _pin_direction_turn(counter, units: np.ndarray) -> np.ndarray:
    """The tens wheel's clockwise turn while the pin drives it, from the geometry: the pin's direction from the tens
    wheel's axis, measured from where the slot is at the pin's entry (pi / n past the line to the units axis)."""
    t = counter.transfer
    psi = counter.angle
    o2 = t.centre_distance * np.array([math.cos(psi), math.sin(psi)])
    rel = t.pin(units, psi) - o2
    seen = np.arctan2(rel[:, 1], rel[:, 0]) - (psi + math.pi)      # from the line O2 -> O1, counter-clockwise
    seen = np.remainder(seen + math.pi, 2 * math.pi) - math.pi
    return math.pi / t.slots - seen


@pytest.mark.parametrize("case", CASES)
def test_the_transfer_happens_exactly_in_its_window(case):
    """The window's edges from the tangent geometry; outside it (to 1e-7 rad) the tens wheel stands, inside it turns
    as the pin's direction says (to 1e-12 rad), monotonically, through one step; its rate is the difference of that
    turn (to 1e-6)."""
    _, _, counter = _built(case)
    t = counter.transfer
    a, c = t.pin_radius, t.centre_distance
    half = math.acos(a / c)                       # the pin's angle from the line of centres where the slot is tangent
    # at rest the pin stands half a stroke's index past its exit: the window in the units wheel's turn
    start = 2 * math.pi - 2 * half - counter.index / 2
    end = 2 * math.pi - counter.index / 2
    lo, hi = counter.window()
    assert lo == pytest.approx(start, abs=1e-12) and hi == pytest.approx(end, abs=1e-12)
    for turn in range(3):
        base = 2 * math.pi * turn
        before = base + np.linspace(0.0, start - 1e-7, 2000)
        after = base + np.linspace(end + 1e-7, 2 * math.pi, 2000)
        tens = t.tens_turn
        np.testing.assert_allclose(tens(before), turn * t.step, rtol=0, atol=1e-12)
        np.testing.assert_allclose(tens(after), (turn + 1) * t.step, rtol=0, atol=1e-12)
        inside = base + np.linspace(start, end, 4001)
        moved = tens(inside) - turn * t.step
        np.testing.assert_allclose(moved, _pin_direction_turn(counter, inside), rtol=0, atol=1e-12)
        assert np.all(np.diff(moved) > 0) and moved[0] == pytest.approx(0, abs=1e-12)
        assert moved[-1] == pytest.approx(t.step, abs=1e-12)
        h = 1e-6
        rate = (tens(inside[1:-1] + h) - tens(inside[1:-1] - h)) / (2 * h)
        np.testing.assert_allclose(t.tens_rate(inside[1:-1]), rate, rtol=0, atol=1e-6)
    np.testing.assert_allclose(t.tens_rate(np.array([start, end])), 0.0, atol=1e-12)      # radial entry and exit


def _arc_mid(p0: np.ndarray, p1: np.ndarray, bulge: float) -> np.ndarray:
    """The midpoint of the arc from p0 to p1 of ``bulge`` (the chord's midpoint pushed off by its sagitta)."""
    chord = p1 - p0
    mid = (p0 + p1) / 2
    return mid - bulge * np.hypot(*chord) / 2 * np.array([-chord[1], chord[0]]) / np.hypot(*chord)


@pytest.mark.parametrize("case", CASES)
def test_the_parts_outlines_are_their_closed_forms(case):
    spec, mechanism, counter = _built(case)
    stock = Stock.of(spec.parts)
    step = geneva_step(counter, stock, spec.linkage.transfer.clearance)
    t = counter.transfer
    n, c = t.slots, t.centre_distance
    a, h = c * math.sin(math.pi / n), (spec.parts.pin_diameter + spec.parts.clearance) / 2
    b = c * math.cos(math.pi / n)
    rw, rl = math.hypot(b, h), a - 2 * h
    vertices, bulges = step.wheel()
    assert len(vertices) == 6 * n
    for k in range(n):
        s = math.pi / n + 2 * math.pi * k / n
        u, v = np.array([math.cos(s), math.sin(s)]), np.array([-math.sin(s), math.cos(s)])
        mouth_in, bottom_in, bottom_out, mouth_out, lock_in, lock_out = vertices[6 * k:6 * k + 6]
        for p, side, along in ((mouth_in, -h, b), (bottom_in, -h, c - a), (bottom_out, h, c - a), (mouth_out, h, b)):
            assert p @ v == pytest.approx(side, abs=1e-9) and p @ u == pytest.approx(along, abs=1e-9)
        for p in (mouth_in, mouth_out, lock_in, lock_out):
            assert math.hypot(*p) == pytest.approx(rw, abs=1e-9)
        bottom = _arc_mid(bottom_in, bottom_out, bulges[6 * k + 1])
        assert bottom == pytest.approx((c - a - h) * u, abs=1e-9)          # the half circle's deepest point
        q = c * np.array([math.cos(s + math.pi / n), math.sin(s + math.pi / n)])
        for p in (lock_in, lock_out, _arc_mid(lock_in, lock_out, bulges[6 * k + 4])):
            assert math.hypot(*(p - q)) == pytest.approx(rl + spec.linkage.transfer.clearance, abs=1e-9)
        nxt = vertices[(6 * k + 6) % (6 * n)]
        for p0, p1, bulge in ((mouth_out, lock_in, bulges[6 * k + 3]), (lock_out, nxt, bulges[6 * k + 5])):
            assert bulge > 0 and math.hypot(*_arc_mid(p0, p1, bulge)) == pytest.approx(rw, abs=1e-9)
    layout = mechanism.layout(spec.linkage, counter, spec.parts)
    parts = {p.name: p for p in layout.parts}
    disc = parts["lock-disc"].shape
    assert disc is not None
    dv, db = disc
    direction = math.atan2(*parts["wheel"].centres[1][::-1])
    cutout = step.cutout_radius()
    q = c * np.array([math.cos(direction), math.sin(direction)])
    for p in dv:
        assert math.hypot(*p) == pytest.approx(rl, abs=1e-9)
    for i in (0, 1):
        assert math.hypot(*_arc_mid(dv[i], dv[i + 1], db[i])) == pytest.approx(rl, abs=1e-9)
    assert math.hypot(*(_arc_mid(dv[2], dv[0], db[2]) - q)) == pytest.approx(cutout, abs=1e-9)
    assert math.hypot(*parts["wheel"].centres[1]) == pytest.approx(a, abs=1e-12)     # the transfer pin's hole
    assert parts["tens-wheel"].centres.tolist() == [[0.0, 0.0]]
    ground = parts["ground"].centres
    assert ground[-1] == pytest.approx(c * np.array([math.cos(counter.angle), math.sin(counter.angle)]))


def _polygon(vertices: np.ndarray, bulges: np.ndarray):
    from camgen.core.shapes import Contour

    return shapely.Polygon(Contour(vertices, bulges).flatten(1e-3))


def _placed(shape, angle: float, shift: np.ndarray):
    return shapely.affinity.translate(shapely.affinity.rotate(shape, angle, origin=(0, 0), use_radians=True),
                                      *shift)


#: the most (degrees) the tens wheel may turn either way at a pose of its dwell (the locking disc's clearance of
#: 0.2 mm lets it rock by up to 0.99, 1.97 and 2.76 degrees in the three cases, most where the cutout is still
#: passing the line of centres next to the window), and at the end of a stroke out of the window (0.38, 0.33 and
#: 1.32 degrees); a step is 36, 60 and 90 degrees
PLAY_DWELL, PLAY_REST = 3.0, 1.5


@pytest.mark.parametrize("case", CASES)
def test_the_tens_wheel_is_locked_but_in_its_window(case):
    spec, mechanism, counter = _built(case)
    t = counter.transfer
    layout = mechanism.layout(spec.linkage, counter, spec.parts)
    parts = {p.name: p for p in layout.parts}
    wheel, disc = (_polygon(*parts[name].shape) for name in ("tens-wheel", "lock-disc"))
    o2 = t.centre_distance * np.array([math.cos(counter.angle), math.sin(counter.angle)])
    pin_centre = parts["wheel"].centres[1]
    pin = shapely.Point(*pin_centre).buffer(spec.parts.pin_diameter / 2, quad_segs=64)
    start, end = counter.window()

    def play(units: float) -> list[float]:
        """How far (degrees) the tens wheel turns either way before it meets the disc or the pin (by bisection to
        1e-4 degrees, up to 10), where it clears both as placed."""
        tens = float(t.tens_turn(np.array([units]))[0])
        disc_at, pin_at = _placed(disc, units, np.zeros(2)), _placed(pin, units, np.zeros(2))
        assert not _placed(wheel, counter.angle + math.pi - tens, o2).intersects(disc_at), math.degrees(units)
        out = []
        for sense in (1.0, -1.0):
            lo, hi = 0.0, 10.0
            while hi - lo > 1e-4:
                mid = (lo + hi) / 2
                turned = _placed(wheel, counter.angle + math.pi - tens + sense * math.radians(mid), o2)
                lo, hi = (lo, mid) if turned.intersects(disc_at) or turned.intersects(pin_at) else (mid, hi)
            out.append(lo)
        return out

    dwell = [play(u) for u in np.linspace(end, 2 * math.pi + start, 37) % (2 * math.pi)]
    assert max(max(p) for p in dwell) < PLAY_DWELL
    ends = [play(k * counter.index) for k in range(counter.strokes_per_turn)
            if not start < k * counter.index < end]
    assert ends and max(max(p) for p in ends) < PLAY_REST
    for units in np.linspace(start, end, 400):
        tens = float(t.tens_turn(np.array([units]))[0])
        placed = _placed(wheel, counter.angle + math.pi - tens, o2)
        assert not placed.intersects(_placed(disc, units, np.zeros(2))), math.degrees(units)
        assert not placed.intersects(_placed(pin, units, np.zeros(2))), math.degrees(units)


def _template_text() -> str:
    return TEMPLATE.read_text(encoding="utf-8")


REFUSALS = [
    (["linkage.teeth=0"], "linkage.teeth: "),
    (["linkage.teeth=10000"], "linkage.teeth: "),
    (["linkage.transfer.slots=2"], "linkage.transfer.slots: "),
    (["linkage.transfer.slots=10000"], "linkage.transfer.slots: "),
    (["linkage.transfer.centre_distance=200"], "linkage.transfer.centre_distance: the transfer pin's circle"),
    (["linkage.transfer.centre_distance=45"], "linkage.transfer.centre_distance: must be > the units wheel's tip"),
    (["linkage.teeth=9", "linkage.lever.swing=85"],
     "linkage.lever.swing: it indexes 2 teeth a stroke, which does not divide the wheel's 9"),
    (["linkage.strokes=0"], "linkage.strokes: "),
    (["linkage.strokes=20000"], "linkage.strokes: "),
]


@pytest.mark.parametrize(("command", "sets", "message"), [
    *(("analyze", s, m) for s, m in REFUSALS), *(("build", s, m) for s, m in REFUSALS),
    ("build", ["linkage.transfer.angle=60"], "linkage.transfer.angle: the tens wheel"),
    ("build", ["parts.pin_diameter=9.5", "parts.width=16"], "linkage.transfer.centre_distance: the locking disc"),
])
def test_bad_input_is_one_line_naming_the_field(tmp_path, command, sets, message):
    from linkgen.cli import main

    path = tmp_path / "c.toml"
    path.write_text(_template_text())
    assert_refused_sets(path, sets, message, tmp_path, main, command)


def test_analyze_and_build_write_the_count_and_the_parts(tmp_path):
    from linkgen.cli import main

    path = tmp_path / "c.toml"
    path.write_text(_template_text())
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["analyze", str(path), "-o", str(tmp_path / "analysis")])
    assert result.exit_code == 0, result.output
    assert ("tens wheel 10 slots: one step of 36 deg every 10 strokes, turning while the units wheel goes 198 to 342 "
            "deg of its turn (strokes 6, 7, 8, 9, 10); after 30 strokes it reads 3 0") in result.output.splitlines()
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(out)])
    assert result.exit_code == 0, result.output

    def refuse(constant: str) -> None:
        raise AssertionError(f"the JSON holds {constant}")

    report = json.loads((out / "counter.json").read_text(), parse_constant=refuse)
    assert report["classification"]["classes"] == ["indexing", "counter"]
    assert report["layers"] == {"ground": 0, "lock-disc": 1, "tens-wheel": 1, "wheel": 2, "pawl": 2,
                                "lever-pawl": 2, "lever": 3}
    for part in ("ground", "wheel", "pawl", "lever", "lever-pawl", "lock-disc", "tens-wheel"):
        assert (out / f"counter-{part}.stl").stat().st_size > 0
    assert (out / "counter-sheet.dxf").stat().st_size > 0


def test_the_angle_asked_is_the_levers_on_its_first_stroke_out():
    """--angle: the lever's angle; the units wheel stands over the lost motion (swing - index = 4 degrees) and then
    turns with it; the tens wheel stands (its window is in the turn's last strokes)."""
    spec, mechanism, counter = _built(CASES[0])
    for angle, wheel in ((2.0, 0.0), (4.0, 0.0), (20.0, 16.0), (40.0, 36.0)):
        positions = mechanism.report(spec.linkage, counter, angle, "closed")["positions"]
        assert positions["wheel_deg"] == pytest.approx(wheel, abs=1e-9) and positions["tens_deg"] == 0.0
        assert positions["teeth_passed"] == (1 if angle == 40.0 else 0)


@pytest.mark.parametrize("case", CASES)
def test_the_figures_draw_without_parts(case):
    """The counter's figures (the count, the wheels at rest) draw for every case, the tens wheel and its disc with
    them."""
    spec, mechanism, counter = _built(case)
    drawing = mechanism.sketch(spec.linkage, counter)
    layers = {layer for layer, _ in drawing.items}
    assert {"tens wheel", "locking disc", "pin circle", "wheel", "pawl"} <= layers
    for _, draw in mechanism.figures("c", spec.linkage, counter):
        assert draw() is not None
