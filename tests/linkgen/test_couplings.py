"""The course's couplings and double sliders as named types (``oldham``, ``trammel``, ``rapson``).

Cross-checks, each independent of :mod:`linkgen.kinematics.couplings`' closed forms:

* Oldham: the coupling drawn as a general linkage (two hubs, the disc sliding in both slots) and solved by the dyad
  solver over a turn: hub 2 turns with hub 1 to 1e-12 rad and the disc's centre is the solver's to 1e-9 mm; the
  centre is the crossing of the two slots (a 2x2 solve written here) and lies on the Thales circle;
* trammel: block B placed by a circle (radius rod about A) meeting the Y axis, the tracer on A-B: the closed form's
  tracer to 1e-9 mm, on the ellipse of semi-axes |rod - point|, |point|; 50-digit mpmath at a few inputs;
* Rapson: the tiller's angle from the block's place, its rates against finite differences, the leverage against
  virtual work (a finite difference of the crosshead's height over the tiller's angle);
* the parts: every pin stays in its slot (in the slotted part's own frame) over the motion, the trammel's slots
  never cross; bad input refused in one line, exit 2, nothing written.
"""
from __future__ import annotations

import json
import math

import mpmath
import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from linkgen.cli import main as linkgen_cli
from linkgen.kinematics.couplings import Oldham, Rapson, Trammel
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.structure import Input, Slider, make_structure
from linkgen.linkage_design import design_linkage
from linkgen.spec import validate_spec

TAU = 2.0 * math.pi
PARTS = {"width": 10.0, "thickness": 3.0, "pin_diameter": 3.0, "sheet": [1000.0, 1000.0]}


def _off(a: np.ndarray, b: np.ndarray, p: np.ndarray) -> np.ndarray:
    """The distances (mm) of points ``p`` (n, 2) from the line through a and b."""
    u = (b - a) / np.linalg.norm(b - a)
    return np.abs(u[0] * (p[:, 1] - a[1]) - u[1] * (p[:, 0] - a[0]))


def _wrap(x: np.ndarray) -> np.ndarray:
    return np.remainder(x + math.pi, TAU) - math.pi


# -------------------------------------------------------------------------------------------------------- Oldham

@pytest.mark.parametrize("d", [20.0, 37.3, 250.0])
def test_oldhams_output_turns_exactly_with_its_input_by_the_general_solver(d):
    """Oldham's coupling drawn at 30 degrees as a general linkage: hub 1 O1-A (its slot along O1-A), hub 2 O2-B (its
    slot along O2-B, square to hub 1's), the disc at C sliding in both. The dyad solver's hub 2 turns with hub 1 to
    1e-12 rad over a whole turn, and its C is the closed form's."""
    o = Oldham(d)
    t0 = math.radians(30.0)
    u1, u2 = np.array([math.cos(t0), math.sin(t0)]), np.array([-math.sin(t0), math.cos(t0)])
    c0 = o.motion([t0], 1.0).centre[0]
    points = {"O1": (0.0, 0.0), "O2": (d, 0.0), "A": tuple(0.6 * d * u1), "B": tuple(np.array([d, 0.0]) + 0.6 * d * u2),
              "C": tuple(c0)}
    sliders = (Slider("slot1", "C", "hub1", t0, link="disc"), Slider("slot2", "C", "hub2", t0 + math.pi / 2,
                                                                    link="disc"))
    s = make_structure(points, {"hub1": ("O1", "A"), "hub2": ("O2", "B"), "disc": ("C",)}, ("O1", "O2"), sliders,
                       (Input("crank", "hub1", "O1"),))
    assert s.mobility == 1
    theta = t0 + np.linspace(0.0, TAU, 20_001)
    sol = Linkage.of(s).solve(theta[None, :])
    b = sol.points["B"] - np.array([d, 0.0])
    hub2 = np.arctan2(b[:, 1], b[:, 0]) - math.pi / 2
    m = o.motion(theta, 1.0)
    assert np.abs(_wrap(hub2 - theta)).max() < 1e-12
    assert np.abs(_wrap(m.output - hub2)).max() < 1e-12
    assert np.hypot(*(sol.points["C"] - m.centre).T).max() < 1e-9 * max(1.0, d / 100)


def test_the_disc_centre_is_where_the_slots_cross_and_runs_twice_round_the_thales_circle():
    d = 31.7
    o = Oldham(d)
    theta = np.linspace(0.0, TAU, 3601)
    m = o.motion(theta, 2.0)
    # the slots' crossing: O1 + s u1 = O2 + r u2, solved as a 2x2 system at each input
    u1 = np.column_stack([np.cos(theta), np.sin(theta)])
    u2 = np.column_stack([-np.sin(theta), np.cos(theta)])
    system = np.stack([u1, -u2], axis=2)
    s_r = np.linalg.solve(system, np.broadcast_to([d, 0.0], (len(theta), 2))[..., None])[..., 0]
    crossing = s_r[:, :1] * u1
    assert np.hypot(*(m.centre - crossing).T).max() < 1e-12 * d
    assert np.abs(m.slide[:, 0] - s_r[:, 0]).max() < 1e-12 * d
    assert np.abs(m.slide[:, 1] - s_r[:, 1]).max() < 1e-12 * d
    centre = np.array(o.thales_centre)
    assert np.abs(np.hypot(*(m.centre - centre).T) - d / 2).max() < 1e-12 * d
    # twice round: its direction from the circle's centre gains 4 pi over a turn of the input
    turns = np.unwrap(np.arctan2(*(m.centre - centre).T[::-1]))
    assert turns[-1] - turns[0] == pytest.approx(2 * TAU, abs=1e-9)
    # the velocity and acceleration against central differences of the position (omega = 2 rad/s)
    h = 1e-5
    ahead, behind = o.motion(theta + h, 2.0).centre, o.motion(theta - h, 2.0).centre
    assert np.abs((ahead - behind) / (2 * h) * 2.0 - m.velocity).max() < 1e-6 * d
    assert np.abs((ahead - 2 * m.centre + behind) / h**2 * 4.0 - m.acceleration).max() < 1e-3 * d


def test_oldhams_pins_stay_in_their_hubs_slots_over_a_turn():
    spec = validate_spec({"name": "o", "linkage": {"type": "oldham", "offset": 20.0}, "parts": PARTS})
    build = design_linkage(spec, parts=True).build
    layout = spec.mechanism.layout(spec.linkage, spec.mechanism.build(spec.linkage), spec.parts)
    parts = {p.name: p for p in layout.parts}
    sweep = layout.sweep
    for joint in ("P1", "P2", "P3", "P4"):
        (_, hub), where = sweep.joints[joint]
        angle, origin = sweep.angles[hub], sweep.origins[hub]
        c, s = np.cos(angle), np.sin(angle)
        rel = where - origin
        local = np.column_stack([c * rel[:, 0] + s * rel[:, 1], -s * rel[:, 0] + c * rel[:, 1]])
        # the slot it runs in: the one of the hub's two (on one line) that its travel starts in
        a, b = next((a, b) for a, b in parts[hub].slots if (local[0] - a) @ (b - a) >= -1e-9 and
                    (local[0] - b) @ (a - b) >= -1e-9)
        along = (local - a) @ (b - a) / np.linalg.norm(b - a) ** 2
        assert _off(a, b, local).max() < 1e-9 and along.min() > -1e-9 and along.max() < 1 + 1e-9
        assert along.min() < 1e-6 and along.max() > 1 - 1e-6        # the slot is no longer than the travel
        assert np.hypot(*a) - spec.parts.pin_diameter > 0             # clear of the bore
    assert build.layer_names == ["ground", "hub1", "disc", "hub2", "ground-top"]   # shaft 2 from the other side


# ------------------------------------------------------------------------------------------------------- trammel

@pytest.mark.parametrize("rod, point", [(80.0, 30.0), (120.0, 45.0), (100.0, -20.0), (60.0, 95.0), (50.0, 25.0)])
def test_the_trammels_tracer_runs_on_its_ellipse(rod, point):
    """Block A from the closed form on the X axis, B where the circle of radius rod about A meets the Y axis (on the
    side the input puts it), the tracer ``point`` along A-B: the closed form's tracer to 1e-9 mm, on the ellipse
    (x / |rod - point|)^2 + (y / |point|)^2 = 1."""
    t = Trammel(rod, point)
    phi = np.linspace(0.0, TAU, 10_001)
    m = t.motion(phi, 1.0)
    a = np.column_stack([m.a, np.zeros_like(m.a)])
    by = np.sign(np.sin(phi)) * np.sqrt(np.maximum(rod**2 - m.a**2, 0.0))
    b = np.column_stack([np.zeros_like(by), by])
    p = a + point / rod * (b - a)
    assert np.hypot(*(p - m.point).T).max() < 1e-9
    assert np.abs(np.hypot(*(m.b[:, None] * [0, 1] - a).T) - rod).max() < 1e-9
    ax, ay = t.semi_axes
    assert (ax, ay) == (abs(rod - point), abs(point))
    assert np.abs((m.point[:, 0] / ax) ** 2 + (m.point[:, 1] / ay) ** 2 - 1).max() < 1e-12
    assert m.point[:, 0].max() == pytest.approx(ax, abs=1e-9) and m.point[:, 1].max() == pytest.approx(ay, abs=1e-9)
    # the rod's angle is the direction from A to B
    assert np.abs(_wrap(np.arctan2(m.b, -m.a) - m.rod_angle)).max() < 1e-12
    # rates against central differences, at 3 rad/s
    h = 1e-5
    fwd, back, at = t.motion(phi + h, 3.0), t.motion(phi - h, 3.0), t.motion(phi, 3.0)
    assert np.abs((fwd.point - back.point) / (2 * h) * 3.0 - at.velocity).max() < 1e-6 * rod
    assert np.abs((fwd.point - 2 * at.point + back.point) / h**2 * 9.0 - at.acceleration).max() < 1e-3 * rod
    assert np.abs((fwd.a - back.a) / (2 * h) * 3.0 - at.a_rate).max() < 1e-6 * rod


def test_the_trammels_tracer_against_fifty_digits():
    mpmath.mp.dps = 50
    rod, point = 97.3, 31.9
    t = Trammel(rod, point)
    for phi in (0.1, 1.0, 2.5, 4.0, 5.9):
        a = mpmath.mpf(rod) * mpmath.cos(phi)
        b = mpmath.sqrt(mpmath.mpf(rod) ** 2 - a**2) * mpmath.sign(mpmath.sin(phi))
        x, y = a * (1 - mpmath.mpf(point) / rod), b * mpmath.mpf(point) / rod
        got = t.motion([phi], 1.0).point[0]
        assert abs(float(x) - got[0]) < 1e-9 and abs(float(y) - got[1]) < 1e-9


def test_the_trammels_guides_never_cross_and_its_pins_stay_in_them():
    spec = validate_spec({"name": "t", "linkage": {"type": "trammel", "rod": 80.0, "point": 30.0}, "parts": PARTS})
    layout = spec.mechanism.layout(spec.linkage, spec.mechanism.build(spec.linkage), spec.parts)
    ground = layout.parts[0]
    first, second = (shapely.LineString(slot).buffer(spec.parts.pin_diameter) for slot in ground.slots)
    assert not first.intersects(second)
    for joint, slot in (("block-a-slot", ground.slots[0]), ("block-b-slot", ground.slots[1])):
        _, where = layout.sweep.joints[joint]
        a, b = slot
        along = (where - a) @ (b - a) / np.linalg.norm(b - a) ** 2
        assert _off(a, b, where).max() < 1e-9 and along.min() == pytest.approx(0, abs=1e-9) and \
            along.max() == pytest.approx(1, abs=1e-9)
    assert design_linkage(spec, parts=True).build.layer_names[0] == "ground"


# -------------------------------------------------------------------------------------------------------- Rapson

def test_rapsons_tiller_rates_and_leverage_by_virtual_work():
    r = Rapson(100.0)
    y = np.linspace(-70.0, 70.0, 2001)
    speed = 20.0
    m = r.motion(y, speed)
    assert np.abs(np.tan(m.angle) * 100.0 - y).max() < 1e-12 * 100
    # the block sits where the tiller's line meets the guide: |(100, y)|
    assert np.abs(m.radius - np.hypot(100.0, y)).max() < 1e-12 * 100
    h = 1e-4
    fwd, back = r.motion(y + h, speed), r.motion(y - h, speed)
    dtheta_dy = (fwd.angle - back.angle) / (2 * h)
    assert np.abs(dtheta_dy * speed - m.rate).max() < 1e-8
    assert np.abs((fwd.rate - back.rate) / (2 * h) * speed - m.acceleration).max() < 1e-8
    # virtual work: F dy = T dtheta, so the torque per unit force is dy / dtheta
    assert np.abs(1 / dtheta_dy - m.leverage).max() < 1e-6 * 100
    assert m.leverage.min() == pytest.approx(100.0, abs=1e-9)          # amidships, the guide's distance


def test_rapsons_report_gives_the_hard_over_leverage():
    spec = validate_spec({"name": "r", "linkage": {"type": "rapson", "distance": 100.0, "max_angle": 35.0,
                                                   "speed": 20.0}})
    r = design_linkage(spec, angle=30.0).report
    a = math.radians(35.0)
    assert r["input_range_mm"] == pytest.approx([-100 * math.tan(a), 100 * math.tan(a)], abs=1e-9)
    assert r["leverage_gain_hard_over"] == pytest.approx(1 / math.cos(a) ** 2, abs=1e-9)
    p = r["positions"]
    assert p["tiller_deg"] == pytest.approx(math.degrees(math.atan(0.3)), abs=1e-9)
    assert p["leverage_mm"] == pytest.approx(100 * (1 + 0.09), abs=1e-9)
    assert r["rpm"] is None


# ---------------------------------------------------------------------------------------------------- bad input

def _run(tmp_path, text: str, *args: str) -> tuple[int, str]:
    path = tmp_path / "bad.toml"
    path.write_text(text)
    result = CliRunner().invoke(linkgen_cli, ["analyze", str(path), "-o", str(tmp_path / "out"), *args])
    return result.exit_code, result.output


@pytest.mark.parametrize("table, field", [
    ('type = "oldham"\noffset = 0.0', "linkage.offset"),
    ('type = "oldham"\noffset = 20000.0', "linkage.offset"),
    ('type = "trammel"\nrod = -1.0\npoint = 3.0', "linkage.rod"),
    ('type = "trammel"\nrod = 80.0', "linkage.point"),
    ('type = "rapson"\ndistance = 80.0\nmax_angle = 80.0', "linkage.max_angle"),
    ('type = "rapson"\ndistance = 80.0\nspeed = 0.0', "linkage.speed"),
])
def test_bad_input_is_one_line_naming_the_field_and_writes_nothing(tmp_path, table, field):
    code, output = _run(tmp_path, f'name = "bad"\n[linkage]\n{table}\n')
    assert code == 2 and output.startswith(f"error: {field}: ") and output.count("\n") == 1, output
    assert not (tmp_path / "out").exists()


def test_an_angle_outside_rapsons_travel_is_refused(tmp_path):
    code, output = _run(tmp_path, 'name = "bad"\n[linkage]\ntype = "rapson"\ndistance = 80.0\n', "--angle", "60")
    assert code == 2 and output == ("error: --angle: the crosshead travels from -56.0166 to 56.0166 mm (the input "
                                    "is its height; got 60)\n")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("kind, line", [
    ("oldham", "the disc's centre runs on the circle centre [12.5, 0.0] mm, radius 12.5 mm"),
    ("trammel", "the tracer's ellipse: semi-axes 75 mm (X) and 45 mm (Y)"),
])
def test_the_text_report_names_the_circle_and_the_ellipse(tmp_path, kind, line):
    name = {"oldham": "oldham-coupling", "trammel": "elliptic-trammel"}[kind]
    from tests.conftest import ROOT

    result = CliRunner().invoke(linkgen_cli, ["analyze", str(ROOT / "templates" / f"{name}.toml"), "--json"])
    assert result.exit_code == 0
    report = json.loads(result.output)
    assert report["type"] == kind
    text = CliRunner().invoke(linkgen_cli, ["analyze", str(ROOT / "templates" / f"{name}.toml"), "-o",
                                            str(tmp_path)])
    assert text.exit_code == 0 and line in text.output
