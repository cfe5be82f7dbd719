"""Ratchet and pawl (issue 34, item 3): the wheel's teeth as drawn, the holding check against the statics of the
friction cone worked out here, the index per stroke, the pawl clear of the wheel, and bad input refused."""
from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
import shapely.ops
from click.testing import CliRunner

from camgen.core.errors import SpecError
from linkgen.gears.ratchet import Pawl, RatchetWheel, teeth_per_stroke
from linkgen.spec import validate_spec
from tests.support.refusals import assert_refused_sets


def _raw(**linkage) -> dict:
    table = {"type": "ratchet", "teeth": 24, "tip_diameter": 80.0, "depth": 6.0, "face_angle": 12.0,
             "friction": 0.15, "pawl": {"length": 30.0}, "lever": {"swing": 40.0, "length": 75.0}}
    for key, value in linkage.items():
        if "." in key:
            head, tail = key.split(".")
            table[head] = {**table[head], tail: value}
        else:
            table[key] = value
    return {"name": "r", "linkage": table}


@pytest.mark.parametrize(("z", "r", "h", "theta"), [(24, 40.0, 6.0, 12.0), (12, 25.0, 5.0, 0.0),
                                                    (40, 60.0, 4.0, 25.0), (8, 30.0, 8.0, -5.0)])
def test_the_teeth_are_as_asked(z, r, h, theta):
    wheel = RatchetWheel(z, r, h, math.radians(theta))
    vertices, bulges = wheel.outline()
    assert len(vertices) == 2 * z and not bulges.any()
    roots, tips = vertices[0::2], vertices[1::2]
    assert np.hypot(*tips.T) == pytest.approx(np.full(z, r), abs=1e-12)
    assert np.hypot(*roots.T) == pytest.approx(np.full(z, r - h), abs=1e-12)
    angles = np.arctan2(tips[:, 1], tips[:, 0])
    assert np.diff(np.unwrap(angles)) == pytest.approx(np.full(z - 1, 2 * math.pi / z), abs=1e-12)
    # each face leans theta from the radial line through its tip, its root counter-clockwise of it (hooked)
    face = roots - tips
    inward = -tips / r
    lean = np.arctan2(inward[:, 0] * face[:, 1] - inward[:, 1] * face[:, 0], np.sum(inward * face, axis=1))
    assert lean == pytest.approx(np.full(z, math.radians(-theta)), abs=1e-12)   # clockwise from inwards: hooked
    assert shapely.Polygon(vertices).is_valid


def _pulled_in(theta_deg: float, gamma_deg: float, mu: float, r: float = 40.0, length: float = 30.0) -> bool:
    """Worked out here: every contact force in the friction cone about the face's normal turns the pawl so that
    its nose moves towards the wheel's centre (or not at all). The face is tooth 0's, taken from the wheel's outline;
    its normal the one pointing out of the tooth (to the pawl's side)."""
    wheel = RatchetWheel(24, r, 6.0, math.radians(theta_deg))
    v, _ = wheel.outline()
    root, tip = v[0], v[1]
    along = (tip - root) / np.hypot(*(tip - root))
    normal = np.array([along[1], -along[0]])
    if normal[0] < 0:                                  # out of the tooth: towards the pawl, clockwise of the face
        normal = -normal
    c = tip
    p = c + length * np.array([math.cos(math.radians(gamma_deg)), math.sin(math.radians(gamma_deg))])
    arm = c - p
    inward = np.sign(arm[0] * (-c[1]) - arm[1] * (-c[0]))    # the pawl's turning sense that moves C towards O
    phi = math.atan(mu)
    for b in np.linspace(-phi, phi, 2001):
        f = np.array([math.cos(b) * normal[0] - math.sin(b) * normal[1],
                      math.sin(b) * normal[0] + math.cos(b) * normal[1]])
        if (arm[0] * f[1] - arm[1] * f[0]) * inward < -1e-12:
            return False
    return True


@pytest.mark.parametrize(("mu", "gamma"), [(0.15, 0.0), (0.3, 0.0), (0.2, 5.0), (0.1, -3.0), (0.5, 10.0)])
def test_the_holding_check_flips_where_the_face_meets_the_friction_angle(mu, gamma):
    limit = math.degrees(math.atan(mu)) - gamma          # the face angle at which psi = theta + gamma = atan mu
    for theta, holds in ((limit + 1e-6, True), (limit - 1e-6, False), (limit + 2.0, True), (limit - 2.0, False)):
        assert _pulled_in(theta, gamma, mu) == holds
        pawl = Pawl(RatchetWheel(24, 40.0, 6.0, math.radians(theta)), 30.0, math.radians(gamma))
        assert pawl.holds(mu) == holds
        assert math.degrees(pawl.engagement_angle) == pytest.approx(theta + gamma, abs=1e-9)
        raw = _raw(face_angle=theta, friction=mu, **{"pawl.angle": gamma})
        if holds:
            assert validate_spec(raw).linkage.holding_pawl.holds(mu)
        else:
            with pytest.raises(SpecError, match=r"^linkage.face_angle: the pawl does not hold: its engagement angle"):
                validate_spec(raw)


@pytest.mark.parametrize("z", [6, 13, 24, 100])
def test_the_lever_indexes_whole_teeth_per_stroke(z):
    pitch = 2 * math.pi / z
    for k in (1, 2, 3):
        assert teeth_per_stroke(z, k * pitch) == k
        assert teeth_per_stroke(z, k * pitch - 1e-6) == k - 1
        assert teeth_per_stroke(z, (k + 0.5) * pitch) == k
    swing = 360.0 / z
    if swing <= 180.0:
        spec = validate_spec(_raw(teeth=z, tip_diameter=200.0, depth=6.0, **{"lever.swing": min(1.5 * swing, 180.0)}))
        from linkgen.linkage_design import design_linkage

        report = design_linkage(spec).report
        assert report["lever"]["teeth_per_stroke"] == 1
        assert report["lever"]["index_deg"] == pytest.approx(swing, abs=1e-9)
        assert report["wheel_rpm"] == pytest.approx(30.0 / z, abs=1e-9)     # 30 strokes a minute, a tooth each
    with pytest.raises(SpecError, match=rf"^linkage.lever.swing: must be at least a tooth's pitch, 360 / {z} = "):
        validate_spec(_raw(teeth=z, tip_diameter=200.0, **{"lever.swing": 0.999 * swing}))


def test_the_pawls_clear_the_wheel_by_the_nose_gap_and_bear_on_the_face():
    from linkgen.linkage_design import design_linkage
    from linkgen.mechanisms.ratchet import NOSE_GAP_MM

    spec = validate_spec({**_raw(), "parts": {"width": 10.0, "thickness": 4.0, "pin_diameter": 4.0}})
    build = design_linkage(spec, parts=True).build
    shapes = {p.name: shapely.Polygon(p.outline().flatten(1e-4)) for p in build.parts}
    assert shapely.distance(shapes["pawl"], shapes["wheel"]) == pytest.approx(NOSE_GAP_MM, abs=1e-6)
    assert shapely.distance(shapes["lever-pawl"], shapes["wheel"]) == pytest.approx(NOSE_GAP_MM, abs=1e-6)
    # the nearest points lie along tooth 0's face, down from its tip: the nose bears on the face, not on a tip
    wheel = spec.linkage.wheel
    near, _ = shapely.ops.nearest_points(shapes["wheel"], shapes["pawl"])
    root, tip = wheel.face_root(0), wheel.tip(0)
    t = float((np.array(near.coords[0]) - tip) @ (root - tip)) / float((root - tip) @ (root - tip))
    assert 0.0 <= t <= 0.6 + 1e-9
    assert build.layer_names[0] == "ground" and set(build.layers) == {"ground", "wheel", "pawl", "lever",
                                                                       "lever-pawl"}


BASE = """name = "r"
[linkage]
type = "ratchet"
teeth = 24
tip_diameter = 80.0
depth = 6.0
[linkage.pawl]
length = 30.0
[linkage.lever]
swing = 40.0
length = 75.0
[parts]
width = 10.0
thickness = 4.0
pin_diameter = 4.0
"""


REFUSALS = [
    (["linkage.teeth=0"], "linkage.teeth: "),
    (["linkage.teeth=10000"], "linkage.teeth: "),
    (["linkage.face_angle=5"], "linkage.face_angle: the pawl does not hold"),
    (["linkage.lever.swing=10"], "linkage.lever.swing: must be at least a tooth's pitch"),
    (["linkage.depth=45"], "linkage.depth: must be < the tip radius"),
]


@pytest.mark.parametrize(("command", "sets", "message"), [
    *(("analyze", s, m) for s, m in REFUSALS), *(("build", s, m) for s, m in REFUSALS),
    ("build", ["linkage.lever.length=40"], "linkage.lever.length: the handle must lie"),   # a part's figure
])
def test_bad_input_is_one_line_naming_the_field(tmp_path, command, sets, message):
    from linkgen.cli import main

    path = tmp_path / "r.toml"
    path.write_text(BASE)
    assert_refused_sets(path, sets, message, tmp_path, main, command)


def test_analyze_prints_the_check_and_the_index(tmp_path):
    from linkgen.cli import main

    path = tmp_path / "r.toml"
    path.write_text(BASE)
    result = CliRunner().invoke(main, ["analyze", str(path), "--angle", "20", "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    friction = math.degrees(math.atan(0.15))
    assert f"pawl holds: engagement angle 10 deg >= friction angle {friction:.6g} deg (margin {10 - friction:.4g})" \
        in lines
    assert "lever swing 40 deg indexes 2 teeth (30 deg) a stroke, 10 deg lost; wheel 2.5 rpm" in lines
    assert "at lever 20.0000 deg: wheel 20.0000 deg, 1 teeth passed" in lines
