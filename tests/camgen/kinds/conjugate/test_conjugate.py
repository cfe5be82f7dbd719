"""Conjugate (dual) cams: two discs on one shaft, each driving one of the two rollers of one follower (a translating
yoke or a bell crank), checked as a pair against an independent placing of the follower and read back from the
files."""
from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.core.errors import DesignError
from camgen.api import design_cam
from camgen.spec import validate_spec
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

#: how a refusal names the follower's table
YOKE_TABLE = "a positive-drive translating-roller follower (driven both ways, no spring)"
ARM_TABLE = "a positive-drive oscillating-roller follower (driven both ways, no spring)"


YOKE = ROOT / "templates" / "conjugate.toml"
ARM = ROOT / "templates" / "conjugate-arm.toml"
RAW = {path: tomllib.loads(path.read_text()) for path in (YOKE, ARM)}


def _raw(path=YOKE, follower: dict | None = None, **cam) -> dict:
    raw = copy.deepcopy(RAW[path])
    raw["cam"].update(cam)
    raw["follower"].update(follower or {})
    return raw


def _build(tmp_path, template=YOKE, *overrides: str) -> tuple[dict, object]:
    out = tmp_path / "out"
    args = ["build", str(template), "-o", str(out)] + [a for o in overrides for a in ("--set", o)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return json.loads((out / f"{template.stem}.json").read_text()), out


def _layer(path, layer: str, step: float = 1e-3) -> list[np.ndarray]:
    """The polylines on ``layer`` of a DXF read back with ezdxf, each bulge drawn as its exact arc (points at most
    ``step`` radians apart; ezdxf's own paths draw arcs as cubic Bezier curves, 0.018 mm off a 65 mm arc)."""
    import ezdxf

    out = []
    for e in ezdxf.readfile(path).modelspace():
        if e.dxf.layer != layer or e.dxftype() != "LWPOLYLINE":
            continue
        verts = np.array([(x, y) for x, y, _ in e.get_points("xyb")])
        bulges = np.array([b for _, _, b in e.get_points("xyb")])
        ends = np.roll(verts, -1, axis=0) if e.closed else verts[1:]
        points = []
        for a, b, bulge in zip(verts, ends, bulges, strict=False):
            turn = 4 * math.atan(bulge)
            n = max(1, math.ceil(abs(turn) / step))
            if turn == 0:
                points.append(a[None, :])
                continue
            chord = b - a
            radius = np.hypot(*chord) / (2 * math.sin(turn / 2))
            centre = a + chord / 2 + np.array([-chord[1], chord[0]]) / np.hypot(*chord) * radius * math.cos(turn / 2)
            start = math.atan2(*(a - centre)[::-1])
            angle = start + turn * np.arange(n) / n
            points.append(centre + abs(radius) * np.column_stack([np.cos(angle), np.sin(angle)]))
        if not e.closed:
            points.append(verts[-1:])
        out.append(np.concatenate(points))
    return out


def _turn(points: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Points (n, 2) turned counter-clockwise by ``angle`` (n,) radians."""
    z = (points[:, 0] + 1j * points[:, 1]) * np.exp(1j * angle)
    return np.column_stack([z.real, z.imag])


def _rollers(raw: dict, s: np.ndarray, place: dict) -> tuple[np.ndarray, np.ndarray]:
    """Both roller centres in the fixed frame at follower displacements ``s``, placed from the template's numbers
    alone (not the design's code): a yoke's rollers on x = e, ``place["span"]`` apart; a bell crank's on arms about
    the pivot that puts the first roller on +Y at rest, the second arm ``place["angle"]`` (rad) from the first
    towards the cam centre."""
    f = raw["follower"]
    rp = raw["cam"]["base_radius"] + f["roller_radius"]
    if f["type"] == "translating-roller":
        e = f.get("offset", 0.0)
        one = np.column_stack([np.full_like(s, e), math.sqrt(rp * rp - e * e) + s])
        return one, one - [0.0, place["span"]]
    c, arm = f["pivot_distance"], f["arm_length"]
    py = (c * c + rp * rp - arm * arm) / (2 * rp)
    pivot = complex(math.sqrt(c * c - py * py), py)
    rest = 1j * rp - pivot
    k = 1.0 if abs(pivot + rest * np.exp(1e-6j)) > rp else -1.0      # the way the crank turns on a rise
    swing = np.exp(1j * k * np.radians(s))
    second = rest * place["length"] / arm * np.exp(-1j * k * place["angle"])
    return (np.column_stack([(pivot + rest * swing).real, (pivot + rest * swing).imag]),
            np.column_stack([(pivot + second * swing).real, (pivot + second * swing).imag]))


def _place(raw: dict, report: dict) -> dict:
    """The second roller's place from the template and closed forms: a yoke's span 2 d0 + h for equal base circles
    (or as given), a bell crank's arm angle 2 psi0 + psi_max for equal arms and base circles."""
    f, cam = raw["follower"], raw["cam"]
    rp = cam["base_radius"] + f["roller_radius"]
    lift = max(seg.get("lift", 0.0) for seg in raw["motion"])
    if f["type"] == "translating-roller":
        e = f.get("offset", 0.0)
        span = cam.get("yoke_span", 2 * math.sqrt(rp * rp - e * e) + lift)
        assert report["follower"]["second_roller"]["yoke_span_mm"] == pytest.approx(span, abs=1e-9)
        return {"span": span}
    c, arm = f["pivot_distance"], f["arm_length"]
    psi0 = math.acos((c * c + arm * arm - rp * rp) / (2 * c * arm))
    angle = math.radians(cam["arm_angle"]) if "arm_angle" in cam else 2 * psi0 + math.radians(lift)
    assert report["follower"]["second_roller"]["arm_angle_deg"] == pytest.approx(math.degrees(angle), abs=1e-9)
    return {"angle": angle, "length": cam.get("second_arm_length", arm)}


CASES = {
    "yoke": (YOKE, {}, ()),
    "yoke offset cw": (YOKE, {"follower": {"offset": 7.5}, "rotation": "cw"},
                       ("follower.offset=7.5", 'cam.rotation="cw"')),
    "yoke span": (YOKE, {"yoke_span": 130.0}, ("cam.yoke_span=130",)),
    "bell crank": (ARM, {}, ()),
    "bell crank cw, unequal arms": (ARM, {"rotation": "cw", "arm_angle": 80.0, "second_arm_length": 80.0},
                                    ('cam.rotation="cw"', "cam.arm_angle=80", "cam.second_arm_length=80")),
}


@pytest.mark.parametrize("case", CASES)
def test_both_rollers_touch_their_cams_over_the_whole_turn(case, tmp_path):
    """The issue's test: both rollers, placed at 720 cam angles by the follower's kinematics (the template's numbers
    and closed forms, not the design's code), touch their cams' outlines read back from the two DXFs within the
    tolerance, and never cut into them by more than it (the chords of a concave stretch stand that much proud)."""
    import shapely

    template, change, overrides = CASES[case]
    raw = _raw(template, change.pop("follower", None), **change)
    report, out = _build(tmp_path, template, "output.formats=['dxf','json']", *overrides)
    tol, rr = report["tolerance_mm"], raw["follower"]["roller_radius"]
    theta = np.radians(np.arange(720) / 2)
    s = design_cam(validate_spec(raw)).cam.program.evaluate(theta)[0]
    sense = 1 if raw["cam"].get("rotation", "ccw") == "ccw" else -1
    centres = _rollers(raw, s, _place(raw, report))
    for which, centre in enumerate(centres):
        (ring,) = _layer(out / f"{template.stem}-{which + 1}.dxf", "OUTLINE")
        body = shapely.Polygon(ring)
        at = _turn(centre, -sense * theta)                   # into the cam's frame
        gap = shapely.distance(body.exterior, shapely.points(at)) - rr
        assert not shapely.contains_xy(body, at[:, 0], at[:, 1]).any()
        assert np.abs(gap).max() <= tol, (which, gap.min(), gap.max())
        assert report["contact"][f"cam{which + 1}_gap_max_mm"] <= tol
    assert report["contact"]["worst_mm"] <= tol and report["outline_max_error_mm"] <= tol


def test_yoke_keeps_the_pitch_radii_at_opposite_angles_adding_up_to_the_span(tmp_path):
    """A centred yoke: r1(phi) + r2(phi + 180 degrees) = span, on the design's pitch curves at 1e4 angles and on the
    exported outlines (the breadth of the pair, roller to roller, is the span less both roller radii)."""
    report, out = _build(tmp_path, YOKE, "output.formats=['dxf','json']")
    design = design_cam(validate_spec(RAW[YOKE]))
    span = report["follower"]["second_roller"]["yoke_span_mm"]
    theta = np.linspace(0, 2 * math.pi, 10_001)
    p1, p2 = design.cam.pitch(theta).point, design.second.pitch(theta).point
    assert np.abs(np.hypot(*p1.T) + np.hypot(*p2.T) - span).max() < 1e-11
    cross = p1[:, 0] * p2[:, 1] - p1[:, 1] * p2[:, 0]
    assert np.abs(cross).max() < 1e-9 and ((p1 * p2).sum(axis=1) < 0).all()         # at opposite polar angles
    assert report["follower"]["second_roller"]["pitch_radius_sum_error_mm"] < 1e-11
    # the exported pair: along every direction, cam 1's outline and cam 2's outline the other way add up to the
    # span less 2 Rr wherever the roller touches there (on the dwells, whose contacts lie on the follower's line)
    import shapely

    rr = RAW[YOKE]["follower"]["roller_radius"]
    rings = [shapely.Polygon(_layer(out / f"conjugate-{i}.dxf", "OUTLINE")[0]) for i in (1, 2)]
    for angle in np.radians([100.0, 150.0, 175.0, 310.0, 350.0]):              # dwells at 90-180 and 300-360
        direction = np.array([math.sin(angle), math.cos(angle)])                 # roller 1 at theta = angle
        reach = [shapely.intersection(ring.exterior, shapely.LineString([(0, 0), 200 * sign * direction]))
                 for ring, sign in zip(rings, (1, -1), strict=True)]
        total = sum(math.hypot(p.x, p.y) for p in reach)
        assert total == pytest.approx(span - 2 * rr, abs=2 * report["tolerance_mm"])


def _pressure_fd(centre, theta: np.ndarray, sense: int, h: float = 1e-6) -> np.ndarray:
    """|pressure angle| (rad) of the cam under a roller whose centre is ``centre(theta)`` (fixed frame), by central
    differences: the pitch curve's tangent in the cam frame gives the contact normal, the centre's own motion the
    way the roller is driven (both in the fixed frame)."""
    pitch = [_turn(centre(theta + d), -sense * (theta + d)) for d in (-h, h)]
    tangent = _turn((pitch[1] - pitch[0]) / (2 * h), sense * theta)               # back to the fixed frame
    normal = np.column_stack([tangent[:, 1], -tangent[:, 0]])
    motion = (centre(theta + h) - centre(theta - h)) / (2 * h)
    cos = np.abs((normal * motion).sum(axis=1)) / np.hypot(*normal.T) / np.hypot(*motion.T)
    return np.arccos(np.clip(cos, -1, 1))


@pytest.mark.parametrize("offset, rotation", [(0.0, "ccw"), (9.0, "cw")])
def test_second_cams_pressure_angle_in_closed_form_and_by_differences(offset, rotation):
    """The yoke's second cam: |phi2| = |atan((s' - sense e) / (span - d0 - s))| (the first cam's formula for a roller
    span - d0 - s from the centre driven the other way), and the same by finite differences of the second roller's
    path; the first cam's against its own closed form."""
    raw = _raw(YOKE, {"offset": offset}, rotation=rotation)
    design = design_cam(validate_spec(raw))
    sense = 1 if rotation == "ccw" else -1
    rp = raw["cam"]["base_radius"] + raw["follower"]["roller_radius"]
    d0 = math.sqrt(rp * rp - offset * offset)
    span = design.second.follower.span
    theta = np.linspace(0.01, 2 * math.pi - 0.01, 4001)
    s, s1 = design.cam.program.evaluate(theta)[:2]
    second = np.abs(design.second.pitch(theta).pressure_angle)
    assert second == pytest.approx(np.abs(np.arctan((s1 - sense * offset) / (span - d0 - s))), abs=1e-12)
    assert np.abs(design.cam.pitch(theta).pressure_angle) == pytest.approx(
        np.abs(np.arctan((s1 - sense * offset) / (d0 + s))), abs=1e-12)

    def centre(t: np.ndarray) -> np.ndarray:
        return _rollers(raw, design.cam.program.evaluate(t)[0], {"span": span})[1]

    moving = np.abs(s1) > 1e-3                       # a dwell's motion has no direction to difference
    assert second[moving] == pytest.approx(_pressure_fd(centre, theta[moving], sense), abs=1e-6)
    assert design.cams[1].analysis.pressure_angle_max_deg == pytest.approx(
        math.degrees(second.max()), abs=1e-4)


def test_bell_cranks_second_cam_by_differences():
    """The bell crank's second cam: pressure angle (from the way the second roller moves as the arm swings back) and
    curvature against finite differences of the second roller's path placed independently."""
    raw = _raw(ARM, arm_angle=75.0, second_arm_length=85.0)
    design = design_cam(validate_spec(raw))
    theta = np.linspace(0.01, 2 * math.pi - 0.01, 3001)
    theta = theta[np.abs(np.degrees(theta)[:, None] - [120, 180, 280]).min(axis=1) > 0.1]   # off the segments' ends
    place = {"angle": math.radians(75.0), "length": 85.0}

    def centre(t: np.ndarray) -> np.ndarray:
        return _rollers(raw, design.cam.program.evaluate(t)[0], place)[1]

    g = design.second.pitch(theta)
    assert g.point == pytest.approx(_turn(centre(theta), -theta), abs=1e-9)
    moving = np.abs(design.cam.program.evaluate(theta)[1]) > 0.1               # degrees of swing per radian
    assert np.abs(g.pressure_angle[moving]) == pytest.approx(_pressure_fd(centre, theta[moving], 1), abs=1e-6)
    h = 1e-4
    p = [_turn(centre(theta + d), -(theta + d)) for d in (-h, 0.0, h)]
    d1, d2 = (p[2] - p[0]) / (2 * h), (p[2] - 2 * p[1] + p[0]) / h**2
    kappa = -(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.hypot(*d1.T) ** 3      # clockwise: convex > 0
    assert g.kappa == pytest.approx(kappa, abs=1e-6)


def test_second_cams_curvature_against_the_polar_formula():
    """A centred yoke's second pitch curve in polar form, r = span - d0 - s with r' = -s', r'' = -s'':
    kappa = (r^2 + 2 r'^2 - r r'') / (r^2 + r'^2)^(3/2), at 2e4 angles, as the design's analytic curvature."""
    design = design_cam(validate_spec(RAW[YOKE]))
    theta = np.linspace(0, 2 * math.pi, 20_001)
    s, s1, s2 = design.cam.program.evaluate(theta)[:3]
    f = design.cam.follower
    r, r1, r2 = design.second.follower.span - f.d0 - s, -s1, -s2
    polar = (r * r + 2 * r1 * r1 - r * r2) / (r * r + r1 * r1) ** 1.5
    assert design.second.pitch(theta).kappa == pytest.approx(polar, rel=1e-10, abs=1e-14)


def _limit_roller(raw: dict) -> float:
    """The largest roller (mm) neither of whose cams undercuts, independently: the polar formula's least convex
    radius of each pitch curve (a centred yoke: r = rb + Rr + s for the first, rb2 + Rr + s_max - s for the second)
    on 2e5 angles, bisected on the roller radius."""
    from camgen.flat import build_cam

    theta = np.linspace(0, 2 * math.pi, 200_001)
    s, s1, s2 = build_cam(validate_spec(raw)).program.evaluate(theta)[:3]           # the program alone
    bases = (raw["cam"]["base_radius"], raw["cam"].get("second_base_radius", raw["cam"]["base_radius"]))

    def margin(rr: float) -> float:
        worst = math.inf
        for r, sign in ((bases[0] + rr + s, 1.0), (bases[1] + rr + s.max() - s, -1.0)):
            kappa = (r * r + 2 * s1 * s1 - sign * r * s2) / (r * r + s1 * s1) ** 1.5
            worst = min(worst, 1 / kappa.max())
        return worst - rr

    lo, hi = 0.1, 100.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if margin(mid) > 0 else (lo, mid)
    return lo


@pytest.mark.parametrize("bases, which", [((10.0, None), 1), ((30.0, 10.0), 2)])
def test_undercut_is_refused_naming_the_cam_and_the_largest_roller_that_fits_both(bases, which):
    """A small pair (a steep 45 degree rise, a 12 mm roller) whose nose undercuts: refused naming the cam that does,
    with the largest roller that fits both cams as an independent bisection on the polar formula finds it; 1e-6 of
    it under that roller the pair builds, 1e-6 over it is refused."""
    raw = _raw(base_radius=bases[0], bore=0.0)
    if bases[1] is not None:
        raw["cam"]["second_base_radius"] = bases[1]
    raw["hub"], raw["follower"]["roller_radius"] = {}, 12.0
    raw["motion"][0]["angle"], raw["motion"][1]["angle"] = 45.0, 135.0
    best = _limit_roller(raw)
    assert 7.0 < best < 8.0
    with pytest.raises(DesignError, match=rf"^undercut of cam {which} at .*the largest roller that fits both cams is "
                                          rf"{best:.4g} mm"):
        design_cam(validate_spec(raw))
    for rr, ok in ((best * (1 - 1e-6), True), (best * (1 + 1e-6), False)):
        trial = {**raw, "follower": {**raw["follower"], "roller_radius": rr}}
        if ok:
            design_cam(validate_spec(trial))
        else:
            with pytest.raises(DesignError, match=f"undercut of cam {which}"):
                design_cam(validate_spec(trial))


def test_yoke_span_at_and_either_side_of_its_least():
    """The span's least value, d0 + h + Rr (the second roller touching the shaft's axis at the top of the lift), in
    closed form: at it and 1e-12 mm below it refused naming cam.yoke_span; 1e-12 mm above it the second roller is
    placed (and its vanishing cam is refused for what it lacks instead)."""
    raw = RAW[YOKE]
    rp = raw["cam"]["base_radius"] + raw["follower"]["roller_radius"]
    least = rp + 25.0 + raw["follower"]["roller_radius"]
    for span, named in ((least - 1e-12, True), (least, True), (least + 1e-12, False)):
        with pytest.raises(DesignError) as info:
            design_cam(validate_spec(_raw(yoke_span=span)))
        assert str(info.value).startswith("cam.yoke_span: must be > 81 mm") == named, str(info.value)


def test_both_cams_share_bore_keyway_and_the_timing_tick(tmp_path):
    """Stacked on their key the two cams' holes coincide and their theta = 0 ticks line up: the HOLES and the tick
    (the ENGRAVE layer's short radial line) read back from both DXFs; each is engraved with its own name."""
    import ezdxf

    _, out = _build(tmp_path, YOKE, "output.formats=['dxf','json']")
    holes = [_layer(out / f"conjugate-{i}.dxf", "HOLES") for i in (1, 2)]
    assert len(holes[0]) == 1 and holes[0][0] == pytest.approx(holes[1][0], abs=1e-9)
    ticks = []
    for i in (1, 2):
        lines = [r for r in _layer(out / f"conjugate-{i}.dxf", "ENGRAVE") if len(r) == 2
                 and abs(r[0][0] * r[1][1] - r[0][1] * r[1][0]) < 1e-9]           # radial: the tick
        (tick,) = lines
        ticks.append(math.atan2(*(tick[1] - tick[0])[::-1]))
        texts = [e.dxf.text for e in ezdxf.readfile(out / f"conjugate-{i}.dxf").modelspace().query("TEXT")]
        assert texts == [f"conjugate-{i}"]
    assert ticks[0] == pytest.approx(ticks[1], abs=1e-12) == pytest.approx(math.pi / 2, abs=1e-12)


def test_solids_and_summary(tmp_path):
    """Each cam's STL is a closed solid of its plan area x thickness (within the chords), and `camgen build` says
    what it built."""
    import trimesh

    report, out = _build(tmp_path, YOKE, "output.formats=['stl','json']")
    for i in (1, 2):
        mesh = trimesh.load(out / f"conjugate-{i}.stl")
        cam = report["cams"][str(i)]
        assert mesh.is_watertight and mesh.is_winding_consistent
        assert mesh.volume == pytest.approx(cam["area_mm2"] * RAW[YOKE]["cam"]["thickness"], rel=2e-4)
        assert cam["mesh"]["watertight"]
    assert report["mesh"]["watertight"]
    result = CliRunner().invoke(main, ["build", str(YOKE), "-o", str(tmp_path / "b"),
                                       "--set", "output.formats=['json']"])
    lines = result.output.splitlines()
    assert lines[0] == "conjugate: conjugate pair, translating-roller follower on a yoke of span 121.000 mm"
    assert lines[1].startswith("cam 1: base radius 40.000 mm; pressure angle max")
    assert lines[4].startswith("contact: both rollers within")


def test_auto_sizes_both_cams_alike_to_the_pressure_limit(tmp_path):
    """base_radius = "auto": both cams at the smallest equal base radius keeping both within the pressure-angle
    limit (a symmetric program makes them peak alike); `camgen size` finds the same radius."""
    report, _ = _build(tmp_path, YOKE, 'cam.base_radius="auto"', "output.formats=['json']")
    assert report["pressure_angle_max_deg"] == pytest.approx(30.0, abs=1e-6)
    cams = report["cams"]
    assert cams["1"]["base_radius_mm"] == pytest.approx(cams["2"]["base_radius_mm"], abs=1e-9)
    result = CliRunner().invoke(main, ["size", str(YOKE), "--json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.output)["base_radius_mm"] == pytest.approx(cams["1"]["base_radius_mm"], rel=1e-8)
    report, _ = _build(tmp_path / "arm", ARM, 'cam.second_base_radius="auto"', "output.formats=['json']")
    assert report["cams"]["2"]["pressure_angle_max_deg"] == pytest.approx(40.0, abs=1e-6)


def test_a_conjugate_family(tmp_path):
    fam = tmp_path / "fam.toml"
    fam.write_text(f'base = "{YOKE.as_posix()}"\nname = "cfam"\n[sweep]\n"cam.base_radius" = [40.0, 50.0]\n'
                   '"output.formats" = [["json", "dxf"]]\n')
    result = CliRunner().invoke(main, ["family", str(fam), "-o", str(tmp_path / "f"), "--jobs", "1"])
    assert result.exit_code == 0, result.output
    rows = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert [r["status"] for r in rows] == ["ok", "ok"]
    assert rows[0]["pressure_angle_max_deg"] > rows[1]["pressure_angle_max_deg"]


@pytest.mark.parametrize("template, change, message", [
    (YOKE, {"follower.spring_rate": 2.0}, f"follower.spring_rate: not a key of {YOKE_TABLE}; it takes: "
                                          "roller_radius, offset, roller_width, mass, "),
    (YOKE, {"follower.preload": 10.0}, f"follower.preload: not a key of {YOKE_TABLE} (did you "
                                       "mean 'load'?); it takes: "),
    (ARM, {"follower.contact_margin": 1.0}, f"follower.contact_margin: not a key of {ARM_TABLE}; "
                                            "it takes: roller_radius, pivot_distance, arm_length, "),
    (YOKE, {"cam.allow_undercut": True}, "cam.allow_undercut: both contacts of a conjugate pair must hold"),
    (YOKE, {"cam.groove_depth": 3.0}, 'cam.groove_depth: not a key of a conjugate cam (a key of cam.kind = '
                                      '"grooved" or "barrel"); it takes: base_radius, thickness, '),
    (YOKE, {"cam.arm_angle": 80.0}, "cam.arm_angle: only for a conjugate cam with an oscillating-roller follower"),
    (ARM, {"cam.yoke_span": 130.0}, "cam.yoke_span: only for a conjugate cam with a translating-roller follower"),
    (YOKE, {"cam.yoke_span": 130.0, "cam.second_base_radius": 30.0}, "cam.yoke_span: give cam.yoke_span or "
                                                                      "cam.second_base_radius"),
    (YOKE, {"cam.yoke_span": 80.0}, "cam.yoke_span: must be > 81 mm, so the second roller stays beyond the shaft"),
    (YOKE, {"cam.yoke_span": 130.0, "cam.base_radius": "auto"}, 'cam.base_radius: "auto" sizes each cam'),
    (YOKE, {"cam.second_base_radius": -5.0}, "cam.second_base_radius: must be > 0"),
    (YOKE, {"cam.bore": 100.0}, "cam.bore: 100 mm leaves no material in cam 1"),
    (YOKE, {"motion.0.law": "uniform"}, "motion[0]: undercut of cam "),
    (ARM, {"cam.arm_angle": 20.0}, "cam.arm_angle: must be between"),
    (ARM, {"cam.second_base_radius": 500.0}, "cam.second_base_radius: must be between"),
    (ARM, {"cam.arm_angle": 400.0}, "cam.arm_angle: must be > 0 and < 360 degrees"),
])
def test_bad_values_are_one_line_exit_2(template, change, message, tmp_path):
    assert_refused(template, change, message, tmp_path)


def test_a_follower_without_rollers_is_refused(tmp_path):
    template = tmp_path / "flat.toml"
    template.write_text(YOKE.read_text().replace('type = "translating-roller"', 'type = "translating-flat"')
                        .replace("roller_radius = 8.0        # mm, both rollers", ""))
    assert_refused(template, {}, "follower.type: a conjugate cam takes translating-roller or oscillating-roller "
                                 "(got 'translating-flat')", tmp_path)


def test_other_kinds_refuse_the_pairs_keys(tmp_path):
    assert_refused(ROOT / "templates" / "rdrd.toml", {"cam.yoke_span": 100.0},
                   'cam.yoke_span: not a key of a disc cam (a key of cam.kind = "conjugate"); it takes: ', tmp_path)


def test_auto_sizes_an_arm_whose_pressure_angle_grows_again_towards_the_top_of_its_range(tmp_path):
    """An arm's pressure angle falls and then grows again as the base circle grows (the arm turns radial towards the
    top of the range it assembles on): the search for a radius that holds steps up through that range rather than
    halving towards its top, where none holds. A disc cam on such an arm (refused before: 'no base radius meets it')
    and the bell-crank pair both size to the limit, and 1e-6 of the radius smaller is over it."""
    from camgen.analysis import pressure_angle_max
    from camgen.flat import build_cam

    disc = {**RAW[ARM], "cam": {k: v for k, v in RAW[ARM]["cam"].items() if k != "kind"},
            "follower": {**RAW[ARM]["follower"], "pivot_distance": 150.0, "arm_length": 120.0}}
    disc["cam"]["base_radius"] = "auto"
    design = design_cam(validate_spec(disc))
    radius = design.cam.base_radius
    assert design.analysis.pressure_angle_max_deg == pytest.approx(40.0, abs=1e-6)
    assert pressure_angle_max(build_cam(validate_spec(disc), base_radius=radius * (1 - 1e-6))) > 40.0
    report, _ = _build(tmp_path, ARM, 'cam.base_radius="auto"', "output.formats=['json']")
    for cam in report["cams"].values():
        assert cam["base_radius_mm"] == pytest.approx(32.479024, abs=1e-6)
        assert cam["pressure_angle_max_deg"] == pytest.approx(40.0, abs=1e-6)


def test_a_cam_reaching_past_the_cranks_pivot_is_warned_of(tmp_path):
    """Arms 150 degrees apart put the second roller far out: its cam reaches past the pivot, whose shaft would cross
    its plane (a warning, as the pair can still be built with the crank on the other side); the bundled crank's
    cams stay inside it."""
    report, _ = _build(tmp_path, ARM, "cam.arm_angle=150", "output.formats=['json']")
    import shapely

    design = design_cam(validate_spec(_raw(ARM, arm_angle=150.0)))
    reach = shapely.Polygon(design.cams[1].outline.contour.flatten(1e-4)).exterior.hausdorff_distance(
        shapely.Point(0, 0))
    assert reach > 110
    assert [w for w in report["warnings"] if "pivot" in w] == [
        f"cam 2 reaches {reach:.4g} mm from the shaft, past the crank's pivot (110 mm away): the pivot's shaft cannot "
        "pass its plane"]
    report, _ = _build(tmp_path / "b", ARM, "output.formats=['json']")
    assert not [w for w in report["warnings"] if "pivot" in w]


def test_kerf_moves_both_outlines_out_by_half_of_it(tmp_path):
    """With a laser's kerf both cut outlines stand half the kerf proud of their exact cams, so each roller, placed
    by the kinematics, overlaps its cut outline by kerf/2 (within the tolerance) all the way round, and the common
    bore shrinks by the kerf in both files."""
    import shapely

    report, out = _build(tmp_path, YOKE, "output.kerf=0.3", "output.formats=['dxf','json']")
    raw, tol = RAW[YOKE], report["tolerance_mm"]
    theta = np.radians(np.arange(720) / 2)
    s = design_cam(validate_spec(raw)).cam.program.evaluate(theta)[0]
    for which, centre in enumerate(_rollers(raw, s, _place(raw, report))):
        ring, = _layer(out / f"conjugate-{which + 1}.dxf", "OUTLINE")
        gap = shapely.distance(shapely.LinearRing(ring), shapely.points(_turn(centre, -theta))) - 8.0
        assert np.abs(gap + 0.15).max() <= tol, (gap.min(), gap.max())
        hole, = _layer(out / f"conjugate-{which + 1}.dxf", "HOLES")
        assert np.hypot(*hole.T).min() == pytest.approx(6.0 - 0.15, abs=1e-9)


@pytest.mark.parametrize("template, setting, remedy", [
    (YOKE, "cam.yoke_span=100", "lengthen cam.yoke_span"), (YOKE, "cam.second_base_radius=19", "enlarge "
                                                                      "cam.second_base_radius"),
    (ARM, "cam.arm_angle=60", "widen cam.arm_angle")])
def test_a_steep_second_cam_is_warned_of_in_the_templates_terms(template, setting, remedy, tmp_path):
    """A second cam over the pressure-angle limit is a warning naming the key that sizes it in the template."""
    report, _ = _build(tmp_path, template, setting, "output.formats=['json']")
    (warning,) = [w for w in report["warnings"] if w.startswith("cam 2: pressure angle")]
    assert warning.endswith(f"limit: {remedy} or lengthen the segment")
