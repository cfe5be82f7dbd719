"""Geneva drives: the law against its closed form, finite differences, mpmath and the textbook; the parts read back
from the exported files (radial slots, tangential entry, the wheel's motion from the geometry); the assembly's
clearances over a whole turn measured independently; the solids; bad values."""
from __future__ import annotations

import copy
import json
import math
import tomllib

import mpmath
import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.core.errors import SpecError
from camgen.api import design_cam
from camgen.kinds.geneva.kinematics import GenevaLaw
from camgen.kinds.geneva.table import GenevaSpec, GenevaTable
from camgen.spec import validate_spec
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

G4, G6 = (ROOT / "templates" / f"geneva{n}.toml" for n in (4, 6))


def _closed_form(n: int, alpha: np.ndarray) -> np.ndarray:
    """tan(beta) = sin(alpha) / (C/a - cos(alpha)), C/a = 1 / sin(pi/n), written out afresh."""
    ratio = 1.0 / math.sin(math.pi / n)
    return np.arctan(np.sin(alpha) / (ratio - np.cos(alpha)))


@pytest.mark.parametrize("n", [3, 4, 5, 6, 8, 12, 36])
def test_the_wheel_angle_is_the_closed_form_and_turns_2pi_over_n(n):
    law = GenevaLaw(n, 100.0)
    e = math.pi / 2 - math.pi / n
    alpha = np.linspace(-e, e, 2001)
    assert np.abs(law.motion(alpha)[0] - _closed_form(n, alpha)).max() < 1e-14
    ends = law.motion(np.array([-e, e]))[0]
    assert ends[1] - ends[0] == pytest.approx(2 * math.pi / n, abs=1e-15)     # the index
    assert law.crank_radius == pytest.approx(100.0 * math.sin(math.pi / n), rel=1e-15)
    # the dwell: the wheel stands still before entry and after exit (the next cycle starts from the next slot)
    dwell = law.motion(np.array([-math.pi + 1e-9, -e - 1e-9, e + 1e-9, math.pi, 3 * math.pi]))
    assert np.all(dwell[1:] == 0) and np.allclose(dwell[0], [-math.pi / n, -math.pi / n, math.pi / n,
                                                             math.pi / n, math.pi / n], atol=0)


def _stencil(f, x: np.ndarray, h: float) -> np.ndarray:
    """The first derivative of ``f`` by the eighth-order central difference (error ~ h^8 f^(9))."""
    w = [4 / 5, -1 / 5, 4 / 105, -1 / 280]
    return sum(c * (f(x + k * h) - f(x - k * h)) for k, c in enumerate(w, start=1)) / h


@pytest.mark.parametrize("n", [3, 4, 6, 8])
def test_velocity_acceleration_and_jerk_against_finite_differences_and_mpmath(n):
    law = GenevaLaw(n)
    e = law.engagement
    alpha = np.linspace(-e + 0.01, e - 0.01, 301)
    m = law.motion(alpha)
    for k in (1, 2, 3):
        fd = _stencil(lambda x, k=k: law.motion(x)[k - 1], alpha, 1e-3)
        assert np.abs(fd - m[k]).max() < 1e-9 * max(1.0, np.abs(m[k]).max()), k
    # and at 40-digit precision, by mpmath's own differentiation of the closed form
    mpmath.mp.dps = 40
    lam = mpmath.sin(mpmath.pi / n)

    def beta(x):
        return mpmath.atan(mpmath.sin(x) / (1 / lam - mpmath.cos(x)))

    for x in (alpha[3], alpha[150], alpha[-7]):
        ref = [float(mpmath.diff(beta, mpmath.mpf(float(x)), k)) for k in (1, 2, 3)]
        got = law.motion(np.array([x]))[1:, 0]
        assert got == pytest.approx(ref, rel=1e-13, abs=1e-14)


@pytest.mark.parametrize("n, velocity, acceleration, at_deg", [
    (4, 1 + math.sqrt(2), 5.41, 11.46),      # the textbook four-slot drive: 2.41 omega, 5.41 omega^2
    (6, 1.0, 1.35, 22.90),                   # and six slots: 1.00 omega, 1.35 omega^2
])
def test_textbook_peaks(n, velocity, acceleration, at_deg):
    law = GenevaLaw(n)
    v, v_at = law.velocity_peak()
    acc, acc_at = law.acceleration_peak()
    assert v == pytest.approx(velocity, rel=1e-14) and v_at == 0.0
    assert acc == pytest.approx(acceleration, abs=5e-3) and math.degrees(acc_at) == pytest.approx(at_deg, abs=5e-3)
    # the closed forms against a brute search over 2e6 driver angles
    alpha = np.linspace(-law.engagement, law.engagement, 2_000_001)
    m = law.motion(alpha)
    assert np.abs(m[1]).max() == pytest.approx(v, rel=1e-12)
    assert np.abs(m[2]).max() == pytest.approx(acc, rel=1e-10)
    assert abs(alpha[np.argmax(m[2])]) == pytest.approx(acc_at, abs=2e-6)


@pytest.mark.parametrize("n", [3, 4, 5, 6, 8, 12, 36])
def test_the_acceleration_jumps_at_entry_and_exit(n):
    """At and within 1e-12 of entry and exit: the velocity is 0 either side, the acceleration jumps between 0 and
    tan(pi/n) (the crank square to the slot: beta'' = lambda cos(pi/n) / (1 - lambda^2))."""
    law = GenevaLaw(n)
    e, jump = law.engagement, math.tan(math.pi / n)
    for side, sign in ((-e, 1.0), (e, -1.0)):
        inside, outside = side + sign * 1e-12, side - sign * 1e-12
        at, within, beyond = law.motion(np.array([side, inside, outside])).T
        assert at[2] == pytest.approx(sign * jump, rel=1e-12) and within[2] == pytest.approx(sign * jump, rel=1e-9)
        assert beyond[2] == 0.0 and beyond[1] == 0.0
        assert abs(at[1]) < 1e-15 and abs(within[1]) < 1e-11
        assert at[0] == pytest.approx(-sign * math.pi / n, abs=1e-15) == beyond[0]
    assert law.acceleration_jump == pytest.approx(jump, rel=1e-15)
    assert law.acceleration_peak()[0] > jump                        # the peak is inside, not at the ends
    assert 0 < law.acceleration_peak()[1] < e


def _build(tmp_path, template, *overrides: str) -> tuple[dict, object]:
    out = tmp_path / "out"
    args = ["build", str(template), "-o", str(out)] + [a for o in overrides for a in ("--set", o)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    name = tomllib.loads(template.read_text())["name"]
    return json.loads((out / f"{name}.json").read_text()), out


def _entities(path):
    import ezdxf

    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    return list(doc.modelspace())


def _slots(path, n: int) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """The wheel's slot flanks read back (LINE entities of the lines-arcs flavour), slot k's two (each as start,
    end) found by their midpoints' direction from the axis, nearest 2 pi k / n."""
    lines = [(np.array(e.dxf.start)[:2], np.array(e.dxf.end)[:2]) for e in _entities(path)
             if e.dxftype() == "LINE"]
    slot = [round(math.atan2(*((a + b) / 2)[::-1]) / (2 * math.pi / n)) % n for a, b in lines]
    assert sorted(slot) == sorted(list(range(n)) * 2)
    return [tuple(p for line, k in zip(lines, slot, strict=True) if k == j for p in line) for j in range(n)]


@pytest.mark.parametrize("template, n", [(G4, 4), (G6, 6)])
def test_the_exported_slots_are_radial_and_the_pin_enters_tangentially(tmp_path, template, n):
    """From the DXF read back: each slot's flanks are parallel, the slot's width is pin + clearance and its centre
    line passes through the wheel's axis; the pin's hole in the crank is a = C sin(pi/n) from the bore; at entry
    the crank is square to the slot and the pin's centre on its centre line, b = C cos(pi/n) from the axis."""
    report, out = _build(tmp_path, template, "output.dxf='lines-arcs'")
    raw = tomllib.loads(template.read_text())["geneva"]
    c, pin, clear = raw["centre_distance"], raw["pin_diameter"], raw["slot_clearance"]
    for k, (a0, a1, b0, b1) in enumerate(_slots(out / f"{template.stem}-wheel.dxf", n)):
        da, db = (a1 - a0) / np.linalg.norm(a1 - a0), (b1 - b0) / np.linalg.norm(b1 - b0)
        assert abs(da[0] * db[1] - da[1] * db[0]) < 1e-12                     # parallel
        normal = np.array([-da[1], da[0]])
        width = abs(float((b0 - a0) @ normal))
        assert width == pytest.approx(pin + clear, abs=1e-9)
        middle = (a0 @ normal + b0 @ normal) / 2                              # the centre line's offset
        assert abs(middle) < 1e-9                                             # through the wheel's axis
        outward = math.atan2(*((a0 + a1 + b0 + b1) / 4)[::-1])
        assert math.remainder(outward - 2 * math.pi * k / n, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    circles = [e for e in _entities(out / f"{template.stem}-crank.dxf") if e.dxftype() == "CIRCLE"]
    bore = next(e for e in circles if abs(e.dxf.center[0]) < 1e-12)
    pin_hole = next(e for e in circles if e is not bore)
    a = math.hypot(pin_hole.dxf.center[0] - bore.dxf.center[0], pin_hole.dxf.center[1] - bore.dxf.center[1])
    assert a == pytest.approx(c * math.sin(math.pi / n), rel=1e-12)
    assert 2 * pin_hole.dxf.radius == pytest.approx(pin, abs=1e-12)
    # entry: the crank at -alpha_e, the wheel's slot 0 (on +X in its file) turned by pi + pi/n about (C, 0)
    e = math.pi / 2 - math.pi / n
    crank = np.array([math.cos(-e), math.sin(-e)])
    slot = np.array([math.cos(math.pi + math.pi / n), math.sin(math.pi + math.pi / n)])
    pin_centre = a * crank
    assert abs(float(crank @ slot)) < 1e-12                                   # square: tangential entry
    to_pin = pin_centre - np.array([c, 0.0])
    assert abs(float(to_pin[0] * slot[1] - to_pin[1] * slot[0])) < 1e-9      # on the slot's centre line
    assert np.linalg.norm(to_pin) == pytest.approx(c * math.cos(math.pi / n), rel=1e-12)
    assert report["assembly"]["entry_angle_deg"] == pytest.approx(90.0, abs=1e-9)
    assert report["assembly"]["slot_offset_mm"] < 1e-12


def test_the_wheels_motion_from_the_exported_geometry(tmp_path):
    """The wheel angle that keeps the exported slot's centre line on the exported pin (the crank's hole), at driver
    angles over the engagement, and its finite differences: the closed form, beta' and beta''."""
    report, out = _build(tmp_path, G4, "output.dxf='lines-arcs'")
    c = tomllib.loads(G4.read_text())["geneva"]["centre_distance"]
    a0, a1, _, _ = _slots(out / "geneva4-wheel.dxf", 4)[0]
    axis = (a1 - a0) / np.linalg.norm(a1 - a0)
    own = math.atan2(axis[1], axis[0]) % math.pi                          # the slot's direction in the wheel's file
    circles = [e for e in _entities(out / "geneva4-crank.dxf") if e.dxftype() == "CIRCLE"]
    a = max(math.hypot(e.dxf.center.x, e.dxf.center.y) for e in circles)

    def wheel(alpha: np.ndarray) -> np.ndarray:
        """beta from the geometry: the slot turned onto the line from the wheel's axis to the pin."""
        to_pin = np.arctan2(a * np.sin(alpha), a * np.cos(alpha) - c)     # the line's direction, about (C, 0)
        beta = math.pi - (to_pin - own)                                   # beta = pi - the wheel's turn
        return math.pi / 2 - np.mod(math.pi / 2 - beta, math.pi)          # a slot is a line: modulo pi

    law = GenevaLaw(4, c)
    alpha = np.linspace(-law.engagement + 0.02, law.engagement - 0.02, 181)
    m = law.motion(alpha)
    assert np.abs(wheel(alpha) - m[0]).max() < 1e-12
    assert np.abs(_stencil(wheel, alpha, 1e-3) - m[1]).max() < 1e-9
    assert np.abs(_stencil(lambda x: _stencil(wheel, x, 1e-3), alpha, 1e-3) - m[2]).max() < 1e-6
    assert report["motion"]["velocity_ratio_max"] == pytest.approx(1 + math.sqrt(2), rel=1e-11)   # 12 digits
    assert [j["size"] for j in report["motion"]["jumps"]] == pytest.approx([1.0, 1.0], rel=1e-12)


def _ring(path, tolerance: float = 5e-4) -> np.ndarray:
    """The OUTLINE polyline read back from the DXF with its bulges made chords here (within ``tolerance`` mm of the
    arcs), independently of the project's own flattening."""
    entity = next(e for e in _entities(path) if e.dxf.layer == "OUTLINE" and e.dxftype() == "LWPOLYLINE")
    pts = np.array(entity.get_points("xyb"))
    out = []
    for (x0, y0, bulge), (x1, y1, _) in zip(pts, np.roll(pts, -1, axis=0), strict=True):
        p, q = np.array([x0, y0]), np.array([x1, y1])
        out.append(p[None, :])
        if bulge:
            sweep = 4 * math.atan(bulge)
            chord = np.linalg.norm(q - p)
            radius = chord / (2 * abs(math.sin(sweep / 2)))
            d = (q - p) / chord
            centre = (p + q) / 2 + np.array([-d[1], d[0]]) * chord / (2 * math.tan(sweep / 2))
            steps = max(2, math.ceil(abs(sweep) / (2 * math.acos(1 - tolerance / radius))))
            start = math.atan2(*(p - centre)[::-1])
            a = start + sweep * np.arange(1, steps) / steps
            out.append(centre + radius * np.column_stack([np.cos(a), np.sin(a)]))
    return np.concatenate(out)


@pytest.mark.parametrize("template", [G4, G6], ids=["geneva4", "geneva6"])
def test_the_assembly_clears_over_a_whole_turn(tmp_path, template):
    """The exported wheel and locking disc (the DXF read back, its arcs made chords within 5e-4 mm here) placed by
    the law at 3600 driver angles, their distance measured by shapely: the locking disc never comes nearer the
    wheel than the lock clearance (less the tolerance) and is that far in the dwell (concentric); the pin keeps
    half the slot clearance in the slot and never touches."""
    import shapely

    report, out = _build(tmp_path, template)
    raw = tomllib.loads(template.read_text())["geneva"]
    c, n, tol = raw["centre_distance"], raw["slots"], report["tolerance_mm"]
    wheel, lock = _ring(out / f"{template.stem}-wheel.dxf"), shapely.Polygon(_ring(out / f"{template.stem}-lock.dxf"))
    law = GenevaLaw(n, c)
    alpha = np.linspace(-math.pi, math.pi, 3601)[1:]
    turn = math.pi - law.motion(alpha)[0] - alpha          # the wheel's frame seen from the driver's
    cs, sn = np.cos(turn)[:, None], np.sin(turn)[:, None]
    x = cs * wheel[:, 0] - sn * wheel[:, 1] + (c * np.cos(-alpha))[:, None]
    y = sn * wheel[:, 0] + cs * wheel[:, 1] + (c * np.sin(-alpha))[:, None]
    placed = shapely.polygons(np.stack([x, y], axis=-1))
    pin = shapely.Point(law.crank_radius, 0.0).buffer(raw["pin_diameter"] / 2, quad_segs=256)
    gap, pin_gap = shapely.distance(placed, lock), shapely.distance(placed, pin)
    assert not shapely.intersects(placed, pin).any() and not shapely.intersects(placed, lock).any()
    lock_clear, slot_clear = raw["lock_clearance"], raw["slot_clearance"]
    assert gap.min() >= lock_clear - tol
    dwell = np.abs(alpha) > law.engagement + 0.2
    assert np.abs(gap[dwell] - lock_clear).max() < 1e-3                         # concentric: the clearance
    assert pin_gap.min() == pytest.approx(slot_clear / 2, abs=1e-3)
    assert report["assembly"]["lock_clearance_min_mm"] == pytest.approx(gap.min(), abs=1e-3)
    assert report["assembly"]["pin_clearance_min_mm"] == pytest.approx(slot_clear / 2, abs=1e-4)
    assert report["assembly"]["lock_overlap_deg"] > 0


def test_the_solids(tmp_path):
    """The printed wheel and driver read back: watertight, outward, the driver two plates high, and their volumes
    the parts' exact areas x thickness within the chords' bound."""
    import trimesh

    report, out = _build(tmp_path, G4, "output.clearance=0.3")
    t = tomllib.loads(G4.read_text())["geneva"]["thickness"]
    parts = report["parts"]
    for solid in ("wheel", "driver"):
        mesh = trimesh.load(out / f"geneva4-{solid}.stl")
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
        checks = report["mesh"]["solids"][solid]
        assert abs(mesh.volume - checks["volume_expected_mm3"]) <= checks["volume_bound_mm3"]
        assert mesh.bounds[1][2] - mesh.bounds[0][2] == pytest.approx(t if solid == "wheel" else 2 * t, abs=1e-6)
    # printed holes open by the clearance: the exact areas less the larger holes
    design = design_cam(validate_spec(tomllib.loads(G4.read_text()) | {"output": {"clearance": 0.3}}))
    wheel = design.printed["wheel"]
    assert report["mesh"]["solids"]["wheel"]["volume_expected_mm3"] == pytest.approx(wheel.area * t, abs=1e-6)
    assert wheel.area == pytest.approx(parts["wheel"]["area_mm2"] - math.pi * ((8.3 / 2) ** 2 - 4**2), rel=1e-12)
    assert report["mesh"]["watertight"] and report["outline_max_error_mm"] == 0.0


def test_kerf_grows_every_outline_by_half_exactly(tmp_path):
    """With a kerf the cut wheel's slots are the kerf narrower, its locking arcs' radius half the kerf smaller, the
    rim half the kerf larger, and the bore the kerf smaller; all still exact lines and arcs."""
    report, out = _build(tmp_path, G4, "output.kerf=0.2", "output.dxf='lines-arcs'")
    raw = tomllib.loads(G4.read_text())["geneva"]
    for a0, a1, b0, _ in _slots(out / "geneva4-wheel.dxf", 4):
        d = (a1 - a0) / np.linalg.norm(a1 - a0)
        assert abs(float((b0 - a0) @ np.array([-d[1], d[0]]))) == pytest.approx(6.0, abs=1e-9)   # 6.2 - 0.2
    arcs = [e for e in _entities(out / "geneva4-wheel.dxf") if e.dxftype() == "ARC"]
    radii = sorted({round(e.dxf.radius, 9) for e in arcs})
    g = validate_spec(tomllib.loads(G4.read_text())).geometry
    assert radii == pytest.approx(sorted([3.1 - 0.1, g.wheel_radius + 0.1, g.lock_arc_radius - 0.1]), abs=1e-9)
    bore = next(e for e in _entities(out / "geneva4-wheel.dxf") if e.dxftype() == "CIRCLE")
    assert 2 * bore.dxf.radius == pytest.approx(raw["wheel_bore"] - 0.2, abs=1e-12)
    assert report["parts"]["wheel"]["holes_cut_mm"] == pytest.approx([raw["wheel_bore"] - 0.2])


GOOD = tomllib.loads(G4.read_text())


def test_the_locking_disc_at_and_within_1e_12_of_its_limits():
    """Inside the wheel's rim (R > C - R_w) and its arcs clear of the slots (R + lock clearance < a - h): 1e-12
    inside either limit builds (at the top with a warning: the tips shrink to nothing), at or beyond is refused."""
    g = validate_spec(GOOD).geometry
    low, high = g.lock_radius_range
    c, a, h = 80.0, 80.0 * math.sin(math.pi / 4), 3.1
    assert low == pytest.approx(c - math.hypot(c * math.cos(math.pi / 4), h), rel=1e-15)
    assert high == pytest.approx(a - h - 0.2, rel=1e-15)
    for radius, ok in ((low * (1 + 1e-12), True), (high * (1 - 1e-12), True), (low, False), (high, False),
                       (high * (1 + 1e-12), False)):
        raw = copy.deepcopy(GOOD)
        raw["geneva"]["lock_radius"] = radius
        if not ok:
            with pytest.raises(SpecError, match=r"^geneva\.lock_radius: must be > 23\.3466 and < 53\.2685 mm"):
                validate_spec(raw)
            continue
        design = design_cam(validate_spec(raw | {"output": {"formats": ["json"]}}))
        assert design.assembly.lock_clearance_min_mm >= 0.2 - 1e-3 and design.assembly.lock_overlap_deg > 0
        assert (radius > c / 2) == any("tips are only" in w for w in design.warnings)


@pytest.mark.parametrize("key, value, message", [
    ("geneva.slots", 2, "geneva.slots: must be >= 3 and <= 36 (got 2)"),
    ("geneva.slots", 4.5, "geneva.slots: must be a whole number (got 4.5)"),
    ("geneva.centre_distance", 0, "geneva.centre_distance: must be > 0 and <= 10000 mm (got 0)"),
    ("geneva.pin_diameter", 40, "geneva.pin_diameter: a slot 40.2 mm wide (pin_diameter + slot_clearance) leaves no "
                                "wheel between neighbouring slots; for 4 slots 80 mm apart it must be < 33.1371 mm"),
    ("geneva.slot_clearance", -0.1, "geneva.slot_clearance: must be >= 0 and <= 5 mm (got -0.1)"),
    ("geneva.lock_radius", 60, "geneva.lock_radius: must be > 23.3466 and < 53.2685 mm, so the disc reaches inside "
                               "the wheel's rim and its arcs meet the rim clear of the slots (got 60)"),
    ("geneva.wheel_bore", 45, "geneva.wheel_bore: must be < 40.6629 mm, inside the slots' bottoms (got 45)"),
    ("geneva.driver_bore", 50, "geneva.driver_bore: must be < 45.8512 mm, inside the locking disc clear of its cutout "
                               "and inside the crank (got 50)"),
    ("geneva.crank_width", 5, "geneva.crank_width: must be > pin_diameter 6 mm, so the crank holds the pin (got 5)"),
    ("geneva.rpm", -1, "geneva.rpm: must be > 0 and <= 100000 rpm (got -1)"),
    ("geneva.teeth", 3, "geneva.teeth: not a key of a Geneva drive; it takes: slots, "),
    ("output.kerf", 5, "output.kerf: a kerf of 5 mm closes the wheel's slots (3.2 mm wide)"),
])
def test_bad_values_are_one_line_exit_2_nothing_written(tmp_path, key, value, message):
    extra = {"geneva.pin_diameter": 3} if key == "output.kerf" else {}
    assert_refused(G4, {key: value, **extra}, message, tmp_path)


def test_a_missing_key_and_a_cam_table_are_refused():
    raw = copy.deepcopy(GOOD)
    del raw["geneva"]["pin_diameter"]
    with pytest.raises(SpecError, match=r"^geneva\.pin_diameter: missing: give diameter of the driver's pin in mm$"):
        validate_spec(raw)
    raw = copy.deepcopy(GOOD) | {"cam": {"base_radius": 10.0}}
    with pytest.raises(SpecError, match=r"^template: give \[cam\] \(a cam\) or \[geneva\] \(a Geneva drive\), not "
                                        r"both$"):
        validate_spec(raw)


def test_a_geneva_template_has_its_three_tables():
    """(tests/project/test_docs.py checks the template reference lists every key of GenevaTable.)"""
    assert set(GenevaSpec.model_fields) == {"name", "geneva", "output"}
    assert {"slots", "centre_distance", "pin_diameter", "thickness"} <= set(GenevaTable.model_fields)


def test_the_command_prints_the_key_figures(tmp_path):
    result = CliRunner().invoke(main, ["build", str(G6), "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    assert lines[0] == ("geneva6: 6 slots, centre distance 100 mm, crank radius 50.0000 mm; the wheel turns 60 deg "
                        "while the driver turns 120 deg, then dwells 240 deg")
    assert lines[1].startswith("wheel velocity max 1.0000 x the driver's at 0 deg; acceleration max 1.3496 x omega^2 "
                               "at +/-22.90 deg; it jumps by 0.5774 x omega^2 at entry (-60 deg) and exit (60 deg)")
    report = json.loads((tmp_path / "geneva6.json").read_text())
    speed = report["speed"]
    omega = 2 * math.pi * 30 / 60
    assert speed["wheel_acceleration_max_rad_s2"] == pytest.approx(1.3496372759 * omega**2, rel=1e-9)
    assert speed["acceleration_jump_rad_s2"] == pytest.approx(math.tan(math.pi / 6) * omega**2, rel=1e-11)
    assert sorted(report["files"]) == sorted(
        [f"{p}_{k}" for p in ("wheel", "lock", "crank") for k in ("dxf", "cut_svg")]
        + [f"{s}_{k}" for s in ("wheel", "driver") for k in ("stl", "3mf")]
        + ["json", "html"] + ["sheet_dxf", "sheet_svg"])      # the three parts nested on one cut sheet; no figures
    assert not {"motion_png", "assembly_svg"} & set(report["files"])   # unless asked (--figures)


def test_a_geneva_family_and_the_python_api(tmp_path):
    import camgen

    path = tmp_path / "fam.toml"
    path.write_text(f'base = "{G4.as_posix()}"\nname = "gfam"\n[sweep]\n"geneva.slots" = [3, 5]\n'
                    '"output.formats" = [["json"]]\n')
    result = CliRunner().invoke(main, ["family", str(path), "-o", str(tmp_path / "f")])
    assert result.exit_code == 0, result.output
    rows = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert [r["status"] for r in rows] == ["ok", "ok"]
    assert [r["velocity_ratio_max"] for r in rows] == pytest.approx([GenevaLaw(3).velocity_peak()[0],
                                                                      GenevaLaw(5).velocity_peak()[0]], rel=1e-11)
    design = camgen.design_cam(camgen.load_spec(G6, ["geneva.slots=8", "output.formats=['json']"]))
    assert design.law.slots == 8
    assert camgen.write_cam(design, tmp_path / "api")["motion"]["index_deg"] == 45.0


def test_size_refuses_a_geneva_template_in_one_line():
    result = CliRunner().invoke(main, ["size", str(G4)])
    assert result.exit_code == 2
    assert result.output == "error: template: a Geneva drive has no base radius to size; `camgen build` it\n"
