"""The graphical construction (issue 30): the follower inverted at each station with its displacement laid off from
the displacement diagram lands on the design's pitch curve (a flat face's profile) to 1e-9 mm, for every follower
type, both senses of rotation and offsets either side; the construction's own geometry holds (its circle points on
the reference circle, an offset axis tangent to the offset circle, an arm of its length turned by the swing at its
pivot, a face tangent to the profile); ``camgen build --construction`` writes a valid PNG and an SVG with one
numbered label a station, and refuses a cam it does not draw in one line, writing nothing."""
from __future__ import annotations

import copy
import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.construction.geometry import construct, station_angles
from camgen.api import design_cam
from camgen.spec import validate_spec
from tests.conftest import ROOT

#: segment starts at 0, 100, 150 and 260 degrees: 100 and 260 off the 15-degree stations
MOTION = [{"type": "rise", "law": "cycloidal", "lift": 18.0, "angle": 100.0}, {"type": "dwell", "angle": 50.0},
          {"type": "return", "law": "harmonic", "lift": 18.0, "angle": 110.0}, {"type": "dwell", "angle": 100.0}]
#: a follower table of each type (an arm's lifts are its swing in degrees, 18 of them)
FOLLOWERS = {"translating-roller": {"type": "translating-roller", "roller_radius": 9.0},
             "knife-edge": {"type": "knife-edge"},
             "translating-flat": {"type": "translating-flat"},
             "oscillating-roller": {"type": "oscillating-roller", "roller_radius": 8.0, "pivot_distance": 110.0,
                                    "arm_length": 90.0},
             "oscillating-flat": {"type": "oscillating-flat", "pivot_distance": 150.0}}
CASES = [(kind, rotation, offset) for kind in FOLLOWERS for rotation in ("ccw", "cw")
         for offset in ((0.0, 11.0, -6.5) if kind in ("translating-roller", "knife-edge") else (0.0,))]
TOL = 1e-9


def _raw(kind: str, rotation: str = "ccw", offset: float = 0.0) -> dict:
    follower = copy.deepcopy(FOLLOWERS[kind])
    if offset:
        follower["offset"] = offset
    base = {"translating-flat": 60.0, "oscillating-flat": "auto"}.get(kind, 40.0)   # no cusp on a flat face
    return {"name": f"c-{kind}", "cam": {"base_radius": base, "thickness": 6.0, "bore": 10.0, "rotation": rotation},
            "follower": follower, "motion": copy.deepcopy(MOTION), "output": {"tolerance": 0.01}}


def _design(kind: str, rotation: str = "ccw", offset: float = 0.0):
    return design_cam(validate_spec(_raw(kind, rotation, offset)))


def test_stations_every_15_degrees_and_at_every_segment_start():
    theta, boundary = station_angles(_design("knife-edge").cam)
    expected = sorted({*range(0, 360, 15), 100, 150, 260})
    assert np.degrees(theta) == pytest.approx(expected, abs=1e-12)
    assert [round(math.degrees(t)) for t, b in zip(theta, boundary, strict=True) if b] == [0, 100, 150, 260]
    theta30, _ = station_angles(_design("knife-edge").cam, 30.0)
    assert np.degrees(theta30) == pytest.approx(sorted({*range(0, 360, 30), 100, 150, 260}), abs=1e-12)


@pytest.mark.parametrize("kind, rotation, offset", CASES)
def test_the_inverted_followers_lie_on_the_designs_pitch_curve(kind, rotation, offset):
    """The construction's points at its stations (and over the turn) are the design's pitch curve there (a flat
    face's profile), to 1e-9 mm; the displacements laid off are the program's."""
    design = _design(kind, rotation, offset)
    c = construct(design.cam)
    st = c.stations
    pitch = design.cam.pitch(st.theta)
    assert np.abs(st.point - pitch.point).max() < TOL
    assert np.abs(c.curve.point - design.cam.pitch(c.curve.theta).point).max() < TOL
    assert st.s == pytest.approx(design.cam.program.evaluate(st.theta)[0], abs=1e-12)
    assert c.numbers.tolist() == list(range(st.theta.size)) and st.theta.size == 26   # 24, 100 and 260
    assert c.arc(np.array([2 * math.pi]))[0] == pytest.approx(2 * math.pi * c.radius, rel=1e-15)


@pytest.mark.parametrize("kind, rotation, offset", CASES)
def test_the_constructions_own_geometry(kind, rotation, offset):
    """What the drawing shows, measured on its points: each station's rest point on the reference circle (prime,
    or base for a flat face) at the station's angle turned against the rotation; for a translating follower the axis
    at |e| from the centre and the displacement s laid off along it from the circle (a face's foot Rb + s out); for
    an arm, the pivot on the pivot circle, the roller L from it and the swing psi the angle turned at the pivot from
    the rest position; a flat face tangent to the design's profile at its contact."""
    design = _design(kind, rotation, offset)
    c = construct(design.cam)
    st = c.stations
    sense = 1 if rotation == "ccw" else -1
    rb, rr = design.cam.base_radius, design.cam.contact_radius
    assert c.radius == pytest.approx(rb if kind.endswith("flat") else rb + rr, abs=0)
    assert np.hypot(*st.circle.T) == pytest.approx(np.full(st.theta.size, c.radius), abs=TOL)
    at_zero = st.circle[0]
    expected = np.angle((at_zero[0] + 1j * at_zero[1]) * np.exp(-1j * sense * st.theta))   # turned against the cam
    assert np.abs(np.angle(np.exp(1j * (np.arctan2(st.circle[:, 1], st.circle[:, 0]) - expected)))).max() < 1e-12
    if kind in ("translating-roller", "knife-edge"):
        normal = np.column_stack([st.direction[:, 1], -st.direction[:, 0]])
        assert np.abs((st.point * normal).sum(axis=1)).max() == pytest.approx(abs(offset), abs=TOL)  # |e| off
        assert np.hypot(*(st.point - st.circle).T) == pytest.approx(st.s, abs=TOL)
        assert ((st.point - st.circle) * st.direction).sum(axis=1) == pytest.approx(st.s, abs=TOL)
    elif kind == "translating-flat":
        assert np.hypot(*st.foot.T) == pytest.approx(rb + st.s, abs=TOL)
    else:
        assert np.hypot(*st.foot.T) == pytest.approx(np.full(st.theta.size, c.pivot_distance), abs=TOL)
        rest, now = st.circle - st.foot, st.point - st.foot
        # the swing psi is the angle turned at the pivot from the rest position: by the arm, or by the face
        moved = now if kind == "oscillating-roller" else st.direction
        turned = np.arctan2(rest[:, 0] * moved[:, 1] - rest[:, 1] * moved[:, 0], (rest * moved).sum(axis=1))
        assert np.abs(np.abs(turned) - np.radians(st.s)).max() < 1e-12
        if kind == "oscillating-roller":
            assert np.hypot(*now.T) == pytest.approx(np.full(st.theta.size, c.arm_length), abs=TOL)
    if kind.endswith("flat"):                             # the face touches the profile: on it, along its tangent
        g = design.cam.pitch(st.theta)
        off = g.point - st.foot
        assert np.abs(off[:, 0] * st.direction[:, 1] - off[:, 1] * st.direction[:, 0]).max() < TOL
        assert np.abs((g.normal * st.direction).sum(axis=1)).max() < 1e-12


def test_an_arms_swing_is_the_angle_turned_at_its_pivot():
    design = _design("oscillating-roller", "cw")
    st = construct(design.cam).stations
    rest, now = st.circle - st.foot, st.point - st.foot
    turned = np.arctan2(rest[:, 0] * now[:, 1] - rest[:, 1] * now[:, 0], (rest * now).sum(axis=1))
    assert np.abs(turned) == pytest.approx(np.radians(st.s), abs=1e-12)
    assert np.abs(turned).max() == pytest.approx(math.radians(18.0), abs=1e-12)   # the dwell at full swing


def _build(tmp_path, raw: dict, *args: str):
    path = tmp_path / f"{raw['name']}.toml"
    path.write_text(_toml(raw))
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "out"), *args])
    return result.exit_code, result.output


def _toml(raw: dict) -> str:
    from camgen.core.starter import toml_value

    lines = [f"name = {toml_value(raw['name'])}"]
    for table in ("cam", "follower", "output"):
        lines += [f"[{table}]", *(f"{k} = {toml_value(v)}" for k, v in raw[table].items())]
    for seg in raw["motion"]:
        lines += ["[[motion]]", *(f"{k} = {toml_value(v)}" for k, v in seg.items())]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("kind", ["translating-roller", "oscillating-flat"])
def test_build_writes_the_construction_as_png_and_svg(tmp_path, kind):
    from PIL import Image

    raw = _raw(kind, "cw", 11.0 if kind == "translating-roller" else 0.0)
    code, output = _build(tmp_path, raw, "--construction")
    assert code == 0, output
    out = tmp_path / "out"
    name = raw["name"]
    png, svg = out / f"{name}-construction.png", out / f"{name}-construction.svg"
    assert f"wrote {png}" in output and f"wrote {svg}" in output
    report = json.loads((out / f"{name}.json").read_text())
    assert report["files"]["construction_png"] == png.name and report["files"]["construction_svg"] == svg.name
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with Image.open(png) as image:
        image.verify()
    with Image.open(png) as image:
        width, height = image.size
        assert width == 1200 and height > 1200          # 10 inches at 120 dpi, the diagram above the drawing
        assert len(image.convert("L").getcolors(1 << 16)) > 50   # drawn, not blank
    root = ET.parse(svg).getroot()
    ids = [e.get("id") for e in root.iter() if e.get("id", "").startswith("station-")]
    count = construct(design_cam(validate_spec(raw)).cam).stations.theta.size
    assert sorted(ids, key=lambda i: int(i.split("-")[1])) == [f"station-{k}" for k in range(count)]
    text = svg.read_text()
    for k in range(count):                               # each label reads its number (matplotlib's comment)
        start = text.index(f'<g id="station-{k}">')
        assert text[start:start + 80].split("<!--")[1].split("-->")[0].strip() == str(k)
    diagram = [e.get("id") for e in root.iter() if e.get("id", "").startswith("diagram-station-")]
    assert len(diagram) == count
    assert "graphical construction" in text


def test_without_the_option_no_construction_is_drawn(tmp_path):
    code, output = _build(tmp_path, _raw("knife-edge"))
    assert code == 0, output
    assert not list((tmp_path / "out").glob("*construction*"))


@pytest.mark.parametrize("template, what", [("barrel.toml", "a barrel cam"), ("plate.toml", "a plate cam"),
                                            ("geneva4.toml", "a Geneva drive"), ("grooved.toml", "a grooved cam")])
def test_a_cam_it_does_not_draw_is_refused_in_one_line(tmp_path, template, what):
    result = CliRunner().invoke(main, ["build", str(ROOT / "templates" / template), "-o", str(tmp_path / "o"),
                                       "--construction"])
    assert result.exit_code == 2
    assert result.output == f"error: --construction: the graphical construction is drawn for a disc cam, not {what}\n"
    assert not (tmp_path / "o").exists()


def test_the_option_is_documented():
    result = CliRunner().invoke(main, ["build", "--help"])
    assert result.exit_code == 0
    assert "--construction" in result.output and "construction.png" in result.output.replace("\n", "")
    reference = (ROOT / "docs" / "reference" / "cli.md").read_text(encoding="utf-8")
    assert "--construction" in reference and "construction.png" in reference
