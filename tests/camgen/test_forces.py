"""Cams at a speed: the camshaft torque against the moment of the contact force, Hertz pressure against a hand
computation, the spring sizing and lift-off speed at their limits, the weight by orientation, bad values refused."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from camgen.contact_stress import MATERIALS, Material, effective_modulus, line_contact
from camgen.api import design_cam
from camgen.dynamics import G_MM, loading, spec_loading
from camgen.forces import Contact, contact_pressure, normal_force, torque
from camgen.kinds.barrel.design import design_barrel
from camgen.kinds.grooved.design import design_grooved
from camgen.spec import load_spec
from camgen.speed import LoadRange
from tests.support.refusals import assert_refused
from tests.conftest import ROOT

RDRD = ROOT / "templates" / "rdrd.toml"
LOADED = ("cam.rpm=300", "follower.mass=0.2", "follower.spring_rate=0.5", "follower.preload=5",
          "follower.load=3", 'cam.material="pla"')


def _design(template: Path = RDRD, sets: tuple[str, ...] = LOADED):
    return design_cam(load_spec(template, sets))


OSCILLATING = ROOT / "templates" / "oscillating.toml"


@pytest.mark.parametrize("template, sets", [(RDRD, LOADED), (OSCILLATING, ("cam.rpm=300", "follower.load=3"))])
def test_torque_is_the_moment_of_the_contact_force_about_the_axis(template, sets):
    """T = F s' / 1000 (power balance; an arm's s the roller centre's path, L psi) against the moment of the normal
    contact force N = F / cos(phi) acting along the profile's normal through the pitch point: T = sense N (p x n) /
    1000, both clockwise and not, for a translating roller and an oscillating one."""
    for rotation in ("ccw", "cw"):
        design = _design(template, (*sets, f'cam.rotation="{rotation}"'))
        cam, f = design.cam, design.spec.follower
        ld = loading(f.mass, f.spring_rate, f.preload, f.load, arm=f.arm_length if f.oscillating else None)
        theta = np.linspace(0.0, 2 * math.pi, 721)[:-1]
        m, g = cam.program.evaluate(theta), cam.pitch(theta)
        omega = 300 * 2 * math.pi / 60
        assert design.speed.forces.torque_max == pytest.approx(torque(ld, omega, m).max(), rel=1e-3)
        moment = normal_force(ld, omega, g, m) * (g.point[:, 0] * g.normal[:, 1] - g.point[:, 1] * g.normal[:, 0])
        by_energy = torque(ld, omega, m)
        assert np.max(np.abs(cam.follower.sense * moment / 1000.0 - by_energy)) < 1e-9 * np.max(np.abs(by_energy))
        assert np.ptp(by_energy) > 0.3


def test_reported_torque_extremes_and_rms():
    design = _design()
    forces, f = design.speed.forces, design.spec.follower
    ld = loading(f.mass, f.spring_rate, f.preload, f.load)
    theta = np.linspace(0.0, 2 * math.pi, 400001)
    t = torque(ld, 300 * 2 * math.pi / 60, design.cam.program.evaluate(theta))
    assert forces.torque_max == pytest.approx(t.max(), rel=1e-9, abs=1e-12)
    assert forces.torque_min == pytest.approx(t.min(), rel=1e-9, abs=1e-12)
    assert forces.torque_rms == pytest.approx(math.sqrt(np.mean(t[:-1] ** 2)), rel=1e-9)   # periodic: trapezoid
    # a conservative spring and load do no net work over a turn, so the mean torque is the inertia's: zero as well
    assert abs(np.mean(t[:-1])) < 1e-9 * np.max(np.abs(t))


def test_hertz_line_contact_by_hand():
    """Two steel cylinders of 10 and 20 mm radius pressed by 1000 N over 10 mm: E* = 210 000 / (2 (1 - 0.09))
    = 115 384.6 MPa, R = 6.667 mm, p = sqrt(F E* / (pi L R)) = 742.2 MPa, b = 0.08577 mm."""
    steel = MATERIALS["steel"]
    e_star = effective_modulus(steel, steel)
    assert e_star == pytest.approx(115384.615, rel=1e-8)
    p, b = line_contact(np.array([1000.0]), np.array([1 / 10 + 1 / 20]), 10.0, e_star)
    assert p[0] == pytest.approx(742.2, rel=2e-4) and b[0] == pytest.approx(0.08577, rel=2e-4)
    assert p[0] == pytest.approx(2 * 1000.0 / (math.pi * b[0] * 10.0), rel=1e-12)   # p = 2F / (pi b L)
    soft = Material(3000.0, 0.35, 40.0, "")
    assert effective_modulus(steel, soft) == pytest.approx(1 / ((1 - 0.09) / 210000 + (1 - 0.35 ** 2) / 3000))


def test_reported_pressure_is_the_largest_over_the_turn():
    design = _design()
    stress, cam, f = design.speed.forces.stress, design.cam, design.spec.follower
    ld = loading(f.mass, f.spring_rate, f.preload, f.load)
    theta = np.linspace(0.0, 2 * math.pi, 200001)
    g, m = cam.pitch(theta), cam.program.evaluate(theta)
    p, _ = contact_pressure(cam, Contact("pla", "steel", 8.0), g, normal_force(ld, 10 * math.pi, g, m))
    assert stress.pressure_max >= p.max() - 1e-9 and stress.pressure_max - p.max() < 1e-6
    # by hand at the peak: the roller (10 mm) on the profile of radius rho_pitch - 10
    at = math.radians(stress.pressure_max_at_deg)
    g1, m1 = cam.pitch(np.array([at])), cam.program.evaluate(np.array([at]))
    rho = 1 / g1.kappa[0] - 10.0
    n = float(normal_force(ld, 10 * math.pi, g1, m1)[0])
    e = 1 / ((1 - 0.36 ** 2) / 3500 + (1 - 0.3 ** 2) / 210000)
    assert stress.pressure_max == pytest.approx(math.sqrt(n * e * (1 / 10 + 1 / rho) / (math.pi * 8)),
                                                       rel=1e-12)
    assert stress.allowable == 30.0 and stress.holds is True


def test_the_preload_found_holds_exactly_the_margin():
    base = (*LOADED[:3], "follower.contact_margin=2.5")
    need = _design(sets=base).speed.contact.preload_needed
    assert need > 0
    held = _design(sets=(*base, f"follower.preload={need!r}")).speed.contact
    assert held.force_min == pytest.approx(2.5, abs=1e-9)
    assert held.preload_needed == pytest.approx(need, abs=1e-9)


def test_the_spring_lets_go_at_the_liftoff_speed():
    off = _design().speed.contact.liftoff_rpm
    assert 300 < off < 1000
    at = _design(sets=(*LOADED, f"cam.rpm={off!r}")).speed.contact
    assert at.force_min == pytest.approx(0.0, abs=1e-9)
    assert _design(sets=(*LOADED, f"cam.rpm={off * 0.999!r}")).speed.contact.force_min > 0
    assert _design(sets=(*LOADED, f"cam.rpm={off * 1.001!r}")).speed.contact.force_min < 0


def test_weight_counts_by_the_orientation():
    """Upright the weight presses the follower onto the cam, upside down it pulls it off: 2 m g apart."""
    up = _design(sets=(*LOADED, "follower.orientation=0")).speed.contact
    down = _design(sets=(*LOADED, "follower.orientation=180")).speed.contact
    assert up.weight == pytest.approx(0.2 * G_MM / 1000)
    assert up.force_min - down.force_min == pytest.approx(2 * 0.2 * G_MM / 1000, rel=1e-9)


def test_gravity_alone_keeps_its_liftoff_speed():
    """The flat-face template's gravity return: the follower leaves where s'' omega^2 = -g."""
    design = _design(ROOT / "templates" / "flat-face.toml", ())
    contact, cam = design.speed.contact, design.cam
    theta = np.linspace(0.0, 2 * math.pi, 400001)
    decel = -cam.program.evaluate(theta)[2].min()
    assert contact.liftoff_rpm == pytest.approx(math.sqrt(G_MM / decel) * 60 / (2 * math.pi), rel=1e-8)
    assert design.speed.forces is not None and design.speed.forces.stress is None


def test_a_flat_face_presses_on_the_profiles_radius_alone():
    design = _design(ROOT / "templates" / "flat-face.toml", ('cam.material="acrylic"', 'follower.material="pom"'))
    stress, cam = design.speed.forces.stress, design.cam
    at = math.radians(stress.pressure_max_at_deg)
    g = cam.pitch(np.array([at]))
    f = design.spec.follower
    n = float(normal_force(loading(f.mass, None, None), 200 * math.pi / 30, g, cam.program.evaluate(np.array([at])))[0])
    e = effective_modulus(MATERIALS["acrylic"], MATERIALS["pom"])
    assert stress.pressure_max == pytest.approx(math.sqrt(n * e / g.rho[0] / (math.pi * 6.0)), rel=1e-9)


@pytest.mark.parametrize("change, message", [
    ({"cam.material": "balsa"}, "cam.material: unknown value 'balsa'; one of"),
    ({"follower.load": 2e6}, "follower.load: must be >= -1e+06 and <= 1e+06 N (got 2000000.0)"),
    ({"follower.orientation": 270}, "follower.orientation: must be >= -180 and <= 180 degrees (got 270)"),
])
def test_bad_values_are_refused_by_name(tmp_path, change, message):
    assert_refused(RDRD, change, message, tmp_path)


def test_an_arms_spring_is_sized_at_the_roller_with_its_weights():
    base = ("follower.contact_margin=12", "follower.inertia=1500", "follower.arm_mass=0.1", "follower.arm_com=40",
            "follower.orientation=30")
    need = _design(OSCILLATING, base).speed.contact.preload_needed
    assert need > 5
    held = _design(OSCILLATING, (*base, f"follower.preload={need!r}")).speed.contact
    assert held.force_min == pytest.approx(12.0, abs=1e-9)


ARM = ("cam.rpm=300", "follower.inertia=1500", "follower.arm_mass=0.1", "follower.arm_com=40", "follower.load=3")


def _arm_energy(design, theta: np.ndarray, omega: float, orientation: float | None) -> np.ndarray:
    """The arm's energy (J) at cam angles ``theta``, from its positions alone: kinetic 1/2 (m L^2 + I) psi_dot^2,
    the roller's and the arm's weights m g h (h the height along straight up, the drawing's +Y turned
    ``orientation`` degrees counter-clockwise from it), the spring's preload x + k x^2 / 2 and the load's work
    load x on the roller's path x = L psi."""
    f, fol = design.spec.follower, design.cam.follower
    m = design.cam.program.evaluate(theta)
    psi, length = np.radians(m[0]), f.arm_length
    kinetic = 0.5 * (f.mass * length ** 2 + f.inertia) * (omega * np.radians(m[1])) ** 2 * 1e-6
    pivot = fol.pivot
    w0 = np.array([0.0, fol.prime_radius]) - pivot
    k = 1.0 if np.hypot(*(pivot + w0 @ np.array([[1, 1e-6], [-1e-6, 1]]))) > fol.prime_radius else -1.0  # away
    w = np.column_stack([np.cos(k * psi) * w0[0] - np.sin(k * psi) * w0[1],
                         np.sin(k * psi) * w0[0] + np.cos(k * psi) * w0[1]])
    potential = 0.0
    if orientation is not None:
        up = np.array([math.sin(math.radians(orientation)), math.cos(math.radians(orientation))])
        heights = f.mass * (pivot + w) @ up + f.arm_mass * (pivot + f.arm_com / length * w) @ up
        potential = heights * 9.80665e-3
    x = length * psi
    spring = (f.preload * x + 0.5 * f.spring_rate * x ** 2 + f.load * x) * 1e-3
    return kinetic + potential + spring


@pytest.mark.parametrize("orientation", [None, 0.0, 30.0, -135.0])
@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_an_arms_torque_is_the_rate_of_its_energy(orientation, rotation):
    """Lagrange by energy: the shaft's power T omega is the rate of the arm's kinetic and potential energy, so
    T = dE/dtheta; E from the arm's positions (five-point differences, h = 1e-3 rad, inside each segment) against
    the forces' torque with the arm's inertia I / L^2 at the roller and the weights by the arm's angle (1e-8)."""
    sets = (*ARM, f'cam.rotation="{rotation}"') + (() if orientation is None else (
        f"follower.orientation={orientation}",))
    if orientation is None:
        sets = tuple(s for s in sets if not s.startswith("follower.arm_"))
    design = _design(OSCILLATING, sets)
    omega, h = 300 * 2 * math.pi / 60, 1e-3
    theta = np.concatenate([np.linspace(seg.start + 4 * h, seg.end - 4 * h, 97)
                            for seg in design.cam.program.segments])
    energy = lambda t: _arm_energy(design, t, omega, orientation)  # noqa: E731
    by_energy = (-energy(theta + 2 * h) + 8 * energy(theta + h) - 8 * energy(theta - h) + energy(theta - 2 * h)
                 ) / (12 * h)
    ld = spec_loading(design.spec.follower, design.cam.follower)
    assert ld.mass == pytest.approx(0.2 + 1500 / 90 ** 2, rel=1e-15)
    by_force = torque(ld, omega, design.cam.program.evaluate(theta), theta)
    assert np.max(np.abs(by_force - by_energy)) < 1e-8 * np.max(np.abs(by_force))
    forces = design.speed.forces
    assert forces.torque_max >= by_force.max() - 1e-12
    assert forces.torque_max == pytest.approx(by_force.max(), rel=1e-3)
    if orientation is not None:          # the weights' pull at rest: (m L + m_arm c) g / L along the rising path
        contact = design.speed.contact
        assert abs(contact.weight) <= (0.2 * 90 + 0.1 * 40) / 90 * G_MM / 1000 + 1e-12


def test_an_arms_weight_turns_with_it():
    """Hanging straight down from its pivot the arm's weight has no pull along the path at rest; the drawing turned
    half a turn reverses the pull."""
    design = _design(OSCILLATING, (*ARM, "follower.orientation=0"))
    fol = design.cam.follower
    w0 = np.array([0.0, fol.prime_radius]) - fol.pivot
    hang = math.degrees(math.atan2(-w0[0], -w0[1]))    # up = (sin o, cos o) in the drawing: the arm along -up
    down = _design(OSCILLATING, (*ARM, f"follower.orientation={hang!r}")).speed.contact.weight
    assert abs(down) < 1e-12
    turned = [_design(OSCILLATING, (*ARM, f"follower.orientation={o}")).speed.contact.weight
              for o in (20.0, -160.0)]
    assert turned[0] == pytest.approx(-turned[1], rel=1e-12) and abs(turned[0]) > 0.1


@pytest.mark.parametrize("change, message", [
    ({"follower.inertia": 10.0}, "follower.inertia: not a key of a translating-roller follower; it takes: "),
    ({"follower.arm_mass": 0.1}, "follower.arm_com: give both arm_mass (kg) and arm_com"),
    ({"follower.inertia": -1.0}, "follower.inertia: must be >= 0"),
])
def test_arm_keys_are_refused_where_they_mean_nothing(tmp_path, change, message):
    template = RDRD if "inertia" in str(change) and change["follower.inertia"] > 0 else OSCILLATING
    assert_refused(template, change, message, tmp_path)


def test_an_arms_weight_needs_its_orientation(tmp_path):
    assert_refused(OSCILLATING, {"follower.arm_mass": 0.1, "follower.arm_com": 30.0},
                   "follower.arm_mass: its weight needs follower.orientation", tmp_path)


TABLE = (*LOADED, "follower.load_table=[[0, 0], [120, 12], [240, 12]]")


def test_a_load_table_by_hand():
    """The table 0 N at 0 degrees, 12 N at 120 and 240, back to 0 at 360 (linear, periodic): 6 N at 60 and at 300.
    At 60 degrees (mid-rise of the cycloid, s = 10 mm, s' = 2 h / beta = 60 / pi mm/rad, s'' = 0) the torque is
    (preload 5 + rate 0.5 * 10 + load 3 + table 6) * 60 / pi / 1000 N*m. Over a turn the spring, the load and the
    inertia do no net work, the table does: on the rise 12 * 20 - (18 / pi) * (20 pi / 3) = 120 N*mm, on the return
    -12 * 20 + (18 / pi) * 10 beta (1/2 - 1/pi) = -180 - 120 / pi, so the mean torque is their sum / 2 pi."""
    from camgen.forces import cycle_mean

    design = _design(sets=TABLE)
    ld = spec_loading(design.spec.follower, design.cam.follower)
    at = np.radians([60.0, 300.0, 180.0, 0.0, 360.0])
    assert ld.table(at) == pytest.approx([6.0, 6.0, 12.0, 0.0, 0.0], abs=1e-12)
    omega = 300 * 2 * math.pi / 60
    t60 = torque(ld, omega, design.cam.program.evaluate(at[:1]), at[:1])[0]
    assert t60 == pytest.approx((5 + 0.5 * 10 + 3 + 6) * 60 / math.pi / 1000, rel=1e-12)
    mean = cycle_mean(design.cam, lambda t, m: torque(ld, omega, m, t), ld.table.angles)
    assert mean == pytest.approx((120 - 180 - 120 / math.pi) / (2 * math.pi) / 1000, rel=1e-9)
    theta = np.linspace(0.0, 2 * math.pi, 400001)
    m = design.cam.program.evaluate(theta)
    forces, contact = design.speed.forces, design.speed.contact
    t = torque(ld, omega, m, theta)
    assert forces.torque_max == pytest.approx(t.max(), rel=1e-9)
    assert forces.torque_rms == pytest.approx(math.sqrt(np.mean(t[:-1] ** 2)), rel=1e-7)
    assert contact.force_min == pytest.approx(ld.force(m, omega, theta).min(), abs=1e-6)
    assert contact.load_table == LoadRange(0.0, 12.0, 3)


def test_a_load_table_from_a_csv_beside_the_template(tmp_path):
    (tmp_path / "loads.csv").write_text("angle,load\n0,0\n120,12\n240,12\n360,0\n")
    (tmp_path / "t.toml").write_text(RDRD.read_text().replace('offset = 5.0', 'offset = 5.0\nload_table = '
                                                                               '"loads.csv"'))
    from_file = _design(tmp_path / "t.toml", LOADED).speed.forces
    assert from_file == _design(sets=TABLE).speed.forces


@pytest.mark.parametrize("table, message", [
    ([[0, 5], [180, 1], [360, 4]], "follower.load_table: the row at 360 degrees (4 N) must repeat the one at 0"),
    ([[0, 5], [180, 1], [90, 4]], "follower.load_table: cam angles must increase row by row (row 3: 90 after 180"),
    ([[-10, 5], [180, 1]], "follower.load_table: cam angles must lie in 0 to 360 degrees (got -10 to 180)"),
    ("missing.csv", "follower.load_table: cannot read"),
])
def test_bad_load_tables_are_refused(tmp_path, table, message):
    loaded = {"cam.rpm": 300, "follower.mass": 0.2, "follower.spring_rate": 0.5, "follower.load_table": table}
    assert_refused(RDRD, loaded, message, tmp_path)


def test_gravity_with_a_margin_warns_in_words():
    """A flat face held by gravity with a contact margin is checked as a loading: losing contact is a warning (it
    was a KeyError: the gravity warning read a lift-off angle that only gravity alone gives)."""
    design = _design(ROOT / "templates" / "flat-face.toml", ("follower.contact_margin=5", "cam.rpm=400"))
    assert design.speed.contact.holds is False
    assert any(w.startswith("the follower loses contact near") for w in design.warnings)


@pytest.mark.parametrize("template, sets, lift, scale, unit", [
    (RDRD, ("cam.rpm=300",), "mm", 1e-3, "v (m/s)"),
    (OSCILLATING, (), "deg", math.pi / 180, "v (rad/s)"),
])
def test_svaj_plots_in_the_machines_units(template, sets, lift, scale, unit):
    """At a speed the S-V-A-J figure is in time: its velocity peak is the report's, in m/s (or rad/s for an arm)."""
    from camgen.plots import svaj_figure

    design = _design(template, sets)
    axes = svaj_figure(design).axes
    assert axes[1].get_ylabel() == unit
    peak = float(np.max(np.abs(axes[1].get_lines()[0].get_ydata())))
    assert design.speed.unit == lift
    assert peak == pytest.approx(design.speed.velocity_max * scale, rel=1e-6)


def test_the_checks_figure_draws_the_reported_figures():
    """The checks figure: its pressure angle peaks at the report's, its torque at the forces' extremes, its Hertz
    pressure at the stress's peak (the dense plot within 0.5 % of the refined peaks)."""
    from camgen.plots import checks_figure

    design = _design()
    axes = checks_figure(design).axes
    pressure = np.max(np.abs(axes[0].get_lines()[0].get_ydata()))
    assert pressure == pytest.approx(design.analysis.pressure_angle_max_deg, rel=5e-3)
    torque_line = next(a for a in axes if a.get_ylabel().startswith("shaft torque")).get_lines()[0].get_ydata()
    assert np.max(torque_line) == pytest.approx(design.speed.forces.torque_max, rel=5e-3)
    hertz = next(a for a in axes if a.get_ylabel().startswith("Hertz")).get_lines()[0].get_ydata()
    assert np.max(hertz) == pytest.approx(design.speed.forces.stress.pressure_max, rel=5e-3)
    flat = checks_figure(_design(ROOT / "templates" / "flat-face.toml", ())).axes[0]
    assert not flat.get_lines() and "0 by definition" in flat.texts[0].get_text()


GROOVED = ROOT / "templates" / "grooved.toml"
BARREL = ROOT / "templates" / "barrel.toml"


def _sides_hold(design, ld, omega, forces) -> None:
    """Between the reported changes of side the force has the sign of the side reported to carry it."""
    changes = forces.drive.changes
    pairs = list(zip(changes, changes[1:] + changes[:1], strict=True))
    assert len(changes) >= 2 and all(a.to != b.to for a, b in pairs)
    positive = forces.drive.force_positive
    for a, b in pairs:
        span = (b.at_deg - a.at_deg) % 360.0
        theta = np.radians(a.at_deg + span * np.linspace(0.02, 0.98, 200))
        f = ld.force(design.cam.program.evaluate(theta), omega, theta)
        carried = f[np.abs(f) > 1e-9] * (1 if a.to == positive else -1)
        assert (carried > 0).all()
        edge = math.radians(a.at_deg)               # the force changes sign there (or jumps across a segment end)
        near = ld.force(design.cam.program.evaluate(np.array([edge - 1e-7, edge + 1e-7])), omega,
                        np.array([edge - 1e-7, edge + 1e-7]))
        assert near[0] * near[1] <= 0 or abs(near).min() < 1e-5


@pytest.mark.parametrize("sets", [("follower.load=-2",), ("follower.load_table=[[0, 3], [180, -3]]",
                                                          "follower.orientation=90")])
@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_a_grooved_cams_torque_is_the_moment_of_the_flank_force(sets, rotation):
    """Positive drive: the force F on the follower (inertia, load, weight) is carried by the inner flank where it
    presses the follower towards the cam and by the outer where it pulls it away; either way the normal force
    N = F / cos(phi) acts along the pitch curve's normal, and the shaft's torque F s' / 1000 is its moment about
    the axis, sense N (p x n) / 1000 (1e-9), both turning senses."""
    design = design_grooved(load_spec(GROOVED, ("cam.rpm=200", "follower.mass=0.3", f'cam.rotation="{rotation}"',
                                                *sets)))
    cam, forces = design.profile.cam, design.profile.speed.forces
    ld = spec_loading(design.spec.follower, cam.follower, positive=True)
    omega = 200 * 2 * math.pi / 60
    theta = np.linspace(0.0, 2 * math.pi, 1441)[:-1]
    m, g = cam.program.evaluate(theta), cam.pitch(theta)
    n = normal_force(ld, omega, g, m)
    moment = cam.follower.sense * n * (g.point[:, 0] * g.normal[:, 1] - g.point[:, 1] * g.normal[:, 0]) / 1000.0
    by_power = torque(ld, omega, m, theta)
    assert np.max(np.abs(moment - by_power)) < 1e-9 * np.max(np.abs(by_power))
    assert forces.torque_max == pytest.approx(by_power.max(), rel=1e-3)
    assert forces.contact_force_max == pytest.approx(np.abs(n).max(), rel=1e-3)
    assert (forces.drive.force_positive, forces.drive.force_negative) == ("inner flank", "outer flank")
    _sides_hold(design.profile, ld, omega, forces)


def test_a_barrels_torque_is_the_moment_of_the_wall_force_at_the_pitch_radius():
    """A barrel: the roller pushes the groove's wall along the developed pitch curve's normal n = (-s', Rm) / |.|
    (x = Rm theta round the cylinder, z along the axis); the tangential part -N n_x at the pitch radius Rm is the
    shaft's torque, T = -N n_x Rm / 1000 = F s' / 1000 (1e-9); the lower wall carries F > 0 (pressing the roller
    towards z = 0), the upper F < 0. With a load table as well."""
    design = design_barrel(load_spec(BARREL, ("cam.rpm=120", "follower.mass=0.5", "follower.load=4",
                                              "follower.load_table=[[0, 0], [90, -30], [270, 10]]")))
    cam, forces = design.cam, design.speed.forces
    ld = spec_loading(design.spec.follower, cam.follower, positive=True)
    omega = 120 * 2 * math.pi / 60
    theta = np.linspace(0.0, 2 * math.pi, 1441)[:-1]
    m, g = cam.program.evaluate(theta), cam.pitch(theta)
    n = normal_force(ld, omega, g, m)
    assert np.allclose(np.tan(g.pressure_angle), m[1] / 30.0, rtol=1e-12, atol=1e-15)     # atan(s' / Rm)
    moment = -n * g.normal[:, 0] * 30.0 / 1000.0
    by_power = torque(ld, omega, m, theta)
    assert np.max(np.abs(moment - by_power)) < 1e-9 * np.max(np.abs(by_power))
    assert forces.torque_min == pytest.approx(by_power.min(), rel=1e-3)
    assert forces.drive.force_positive == "lower wall"
    _sides_hold(design, ld, omega, forces)


def test_a_barrel_arms_torque_is_the_rate_of_its_energy():
    """An arm on a barrel, its inertia alone: T = dE/dtheta with E = (m L^2 + I) psi_dot^2 / 2 (1e-8)."""
    template = ROOT / "templates" / "barrel-oscillating.toml"
    design = design_barrel(load_spec(template, ("cam.rpm=90", "follower.mass=0.2", "follower.inertia=3000")))
    f, omega, h = design.spec.follower, 90 * 2 * math.pi / 60, 1e-3
    ld = spec_loading(f, design.cam.follower, positive=True)

    def energy(t):
        return 0.5 * (0.2 * f.arm_length ** 2 + 3000) * (omega * np.radians(design.cam.program.evaluate(t)[1])) ** 2 \
            * 1e-6

    theta = np.concatenate([np.linspace(seg.start + 4 * h, seg.end - 4 * h, 97)
                            for seg in design.cam.program.segments])
    by_energy = (-energy(theta + 2 * h) + 8 * energy(theta + h) - 8 * energy(theta - h) + energy(theta - 2 * h)
                 ) / (12 * h)
    by_force = torque(ld, omega, design.cam.program.evaluate(theta), theta)
    assert np.max(np.abs(by_force - by_energy)) < 1e-8 * np.max(np.abs(by_force))
    assert design.speed.forces.torque_max == pytest.approx(by_force.max(), rel=1e-3)


@pytest.mark.parametrize("template, sets", [
    ("conjugate.toml", ("follower.load=-3",)),
    ("conjugate-arm.toml", ("follower.inertia=2000", "follower.load_table=[[0, 5], [200, -5]]")),
])
@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_a_conjugate_pairs_torque_is_the_sum_of_both_contacts_moments(template, sets, rotation):
    """A conjugate pair: cam 1 pushes the follower where F > 0, cam 2 where F < 0 with N2 = -F (L1 / L2) / cos(phi2)
    along its own pitch normal at the second roller; the sum of both contacts' moments about the shaft, sense N (p x
    n) / 1000 each, is the shaft's torque F s' / 1000 (1e-9), for a yoke and a bell crank, both turning senses."""
    from camgen.kinds.conjugate.design import design_conjugate

    design = design_conjugate(load_spec(ROOT / "templates" / template,
                                        ("cam.rpm=150", "follower.mass=0.25", f'cam.rotation="{rotation}"', *sets)))
    pair = tuple(d.cam for d in design.cams)
    forces = design.cams[0].speed.forces
    ld = spec_loading(design.spec.follower, pair[0].follower, positive=True)
    omega = 150 * 2 * math.pi / 60
    theta = np.linspace(0.0, 2 * math.pi, 1441)[:-1]
    m = pair[0].program.evaluate(theta)
    f = ld.force(m, omega, theta)
    ratio = getattr(pair[0].follower, "arm_length", 1.0) / getattr(pair[1].follower, "arm_length", 1.0)
    total = np.zeros_like(theta)
    for cam, push in zip(pair, (np.maximum(f, 0.0), ratio * np.maximum(-f, 0.0)), strict=True):
        g = cam.pitch(theta)
        n = push / np.cos(g.pressure_angle)
        assert (np.cos(g.pressure_angle) > 0).all()
        total += cam.follower.sense * n * (g.point[:, 0] * g.normal[:, 1] - g.point[:, 1] * g.normal[:, 0]) / 1000
    by_power = torque(ld, omega, m, theta)
    assert np.max(np.abs(total - by_power)) < 1e-9 * np.max(np.abs(by_power))
    assert forces.torque_max == pytest.approx(by_power.max(), rel=1e-3)
    g2 = pair[1].pitch(theta)
    assert forces.pair[1].value == pytest.approx(
        np.max(ratio * np.maximum(-f, 0.0) / np.cos(g2.pressure_angle)), rel=1e-3)
    assert (forces.drive.force_positive, forces.drive.force_negative) == ("cam 1", "cam 2")
    _sides_hold(design.cams[0], ld, omega, forces)


def test_the_console_says_which_side_carries_the_force(tmp_path):
    """``camgen build`` of a barrel at a speed with a mass prints the torque and where the contact changes wall."""
    from click.testing import CliRunner

    from camgen.cli import main

    result = CliRunner().invoke(main, ["build", str(BARREL), "-o", str(tmp_path / "out"), "--set", "cam.rpm=200",
                                       "--set", "follower.mass=0.3", "--set", "follower.load=-1"])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "out" / "barrel.json").read_text())
    changes = report["speed"]["forces"]["side_changes"]
    assert [c["to"] for c in changes] == ["lower wall", "upper wall", "lower wall", "upper wall"]
    assert ("positive drive: lower wall carries the force where it presses the follower against its rise, upper "
            "wall where it pulls; the contact changes side at " + ", ".join(f"{c['at_deg']:.4g}" for c in changes)
            ) in result.output
    assert "camshaft torque" in result.output


def test_a_grooved_cams_flank_pressure_by_hand():
    """grooved.toml (base 40, roller 5, running clearance 0.2, groove 5 deep; PLA on steel, E* = 1 / ((1 - 0.36^2)
    / 3500 + (1 - 0.3^2) / 210 000) = 3952.27 MPa) on its top dwell (130 degrees: the pitch circle 40 + 5 + 20 = 65
    mm, the flanks 5.1 mm either side). A load of 10 N presses the roller on the inner flank, convex of radius 59.9:
    p = sqrt(10 E* (1/5 + 1/59.9) / (pi 5)) = 23.350 MPa, b = 0.054528 mm; -10 N on the outer, concave of radius
    70.1: p = sqrt(10 E* (1/5 - 1/70.1) / (pi 5)) = 21.618 MPa, b = 0.058898 mm. The report's peak is the largest
    over the turn (dense sampling of the same function), on the side carrying the force there."""
    from camgen.forces import flank_pressure

    for load, side, (p, b) in ((10, "inner flank", (23.35003, 0.0545284)), (-10, "outer flank", (21.61772, 0.0588980))):
        design = design_grooved(load_spec(GROOVED, ("cam.rpm=300", "follower.mass=0.2", f"follower.load={load}",
                                                    'cam.material="pla"')))
        stress = design.profile.speed.forces.stress
        contact = Contact("pla", "steel", 5.0)
        assert stress.length == 5.0 and stress.e_star == pytest.approx(3952.2716, rel=1e-8)
        cam = design.cam
        at = np.radians([130.0])
        g = cam.pitch(at)
        assert float(np.hypot(*g.point[0])) == pytest.approx(65.0, rel=1e-12)
        ld = spec_loading(design.spec.follower, cam.follower, positive=True)
        got = flank_pressure(contact, g, normal_force(ld, 10 * math.pi, g, cam.program.evaluate(at)), 5.1, 5.0)
        assert (got[0][0], got[1][0]) == pytest.approx((p, b), rel=2e-6)
        theta = np.linspace(0, 2 * math.pi, 72001)
        gg = cam.pitch(theta)
        dense = flank_pressure(contact, gg, normal_force(ld, 10 * math.pi, gg, cam.program.evaluate(theta)), 5.1, 5.0)
        assert stress.pressure_max == pytest.approx(dense[0].max(), rel=1e-5)
        assert stress.pressure_max >= dense[0].max() * (1 - 1e-12)
        peak = np.radians([stress.pressure_max_at_deg])
        pressing = float(ld.force(cam.program.evaluate(peak), 10 * math.pi, peak)[0]) > 0
        assert stress.on == ("inner flank" if pressing else "outer flank")
        assert getattr(design.profile.speed.forces.drive, "force_positive" if load > 0 else "force_negative") == side


CONJUGATE = ROOT / "templates" / "conjugate.toml"


def test_a_conjugate_pairs_pressure_by_hand():
    """conjugate.toml (yoke of span 121, rollers 8, PLA on steel) on its top dwell (135 degrees: cam 1's pitch circle
    40 + 8 + 25 = 73 mm, its profile 65; cam 2's 121 - 73 = 48, its profile 40). +10 N on cam 1: p = sqrt(10 E*
    (1/8 + 1/65) / (pi 8)) = 14.858 MPa, b = 0.053558 mm; -10 N on cam 2: sqrt(10 E* (1/8 + 1/40) / (pi 8)) =
    15.359 MPa, b = 0.051813 mm. Each cam's peak is the largest over the turn of its own roller's pressure."""
    from camgen.kinds.conjugate.design import design_conjugate

    for load, which, (p, b) in ((10, 0, (14.85810, 0.0535583)), (-10, 1, (15.35851, 0.0518133))):
        design = design_conjugate(load_spec(CONJUGATE, ("cam.rpm=300", "follower.mass=0.2", f"follower.load={load}",
                                                        'cam.material="pla"')))
        stress = design.cams[0].speed.forces.stress
        cam = design.cams[which].cam
        at = np.radians([135.0])
        g = cam.pitch(at)
        assert float(np.hypot(*g.point[0])) == pytest.approx((73.0, 48.0)[which], rel=1e-12)
        ld = spec_loading(design.spec.follower, design.cams[0].cam.follower, positive=True)
        push = abs(normal_force(ld, 10 * math.pi, g, cam.program.evaluate(at)))
        got = contact_pressure(cam, Contact("pla", "steel", 8.0), g, push)
        assert (got[0][0], got[1][0]) == pytest.approx((p, b), rel=2e-6)
        own = stress.cams[which]
        assert own.on == f"cam {which + 1}" and own.pressure_max >= p * (1 - 1e-12)
        assert stress.pressure_max == max(c.pressure_max for c in stress.cams)


def _barrel_checks(design):
    from camgen import plots
    from camgen.sizing import pressure_limit

    w = design.walls
    return plots.groove_checks_plot(design.spec, design.cam, design.speed.forces, pressure_limit(design.spec),
                                    w.r0 + w.taper * design.radii[1], 5.0, ("lower wall", "upper wall"))


@pytest.mark.parametrize("template, figure", [(GROOVED, "camgen.kinds.grooved.plots:grooved_checks_figure"),
                                              (CONJUGATE, "camgen.kinds.conjugate.plots:pair_checks_figure"),
                                              (BARREL, None)])
def test_a_positive_drives_checks_figure_draws_the_reported_figures(template, figure, tmp_path):
    """A grooved cam's, a pair's and a barrel's checks figure at a speed with a mass: its normal forces peak at the
    report's largest, its Hertz pressures at the stress's peak, its torque at the extremes (the dense plot within
    0.5 % of the refined peaks); a build writes <name>-checks.png/.svg only then."""
    from click.testing import CliRunner

    import importlib

    from camgen.cli import main
    from camgen.kinds.conjugate.design import design_conjugate

    sets = ("cam.rpm=300", "follower.mass=0.2", "follower.load=-5", 'cam.material="pla"')
    spec = load_spec(template, sets)
    design = {GROOVED: design_grooved, CONJUGATE: design_conjugate, BARREL: design_barrel}[template](spec)
    forces = {GROOVED: lambda: design.profile.speed, CONJUGATE: lambda: design.cams[0].speed,
              BARREL: lambda: design.speed}[template]().forces
    if figure:
        module, name = figure.split(":")
        axes = getattr(importlib.import_module(module), name)(design).axes
    else:
        axes = _barrel_checks(design).axes
    peak = lambda ax: max(float(np.max(line.get_ydata())) for line in ax.get_lines()[:2])   # noqa: E731
    largest = forces.contact_force_max if template != CONJUGATE else max(
        forces.pair[0].value, forces.pair[1].value)   # each on its own cam's normal
    assert peak(axes[2]) == pytest.approx(largest, rel=5e-3)
    assert peak(axes[3]) == pytest.approx(forces.stress.pressure_max, rel=5e-3)
    torque_line = axes[-1].get_lines()[0].get_ydata()
    assert float(np.max(torque_line)) == pytest.approx(forces.torque_max, rel=5e-3)
    name = spec.name
    for extra, expected in (((), False), (sets, True)):
        args = ["build", str(template), "-o", str(tmp_path / str(expected)), "--figures"]
        for s in extra:
            args += ["--set", s]
        assert CliRunner().invoke(main, args).exit_code == 0
        assert (tmp_path / str(expected) / f"{name}-checks.png").exists() is expected
        assert (tmp_path / str(expected) / f"{name}-checks.svg").exists() is expected


def test_a_barrels_wall_pressure_by_hand():
    """barrel.toml (pitch radius 30, roller 5, groove 6 deep; PLA on steel) on its top dwell (165 degrees): the
    developed walls are straight there, so a line contact of the roller on a flat wall along the groove's depth:
    10 N, p = sqrt(10 E* (1/5) / (pi 6)) = 20.478 MPa, b = 0.051813 mm, on the lower wall for +10 N and the upper
    for -10 N. Where the developed pitch curve bends (curvature kappa at Rm, convex towards the lower wall
    positive) the lower wall's is kappa / (1 - d kappa), the upper's -kappa / (1 + d kappa), d the cutter's radius
    at Rm (roller + clearance / 2): checked at 20 degrees against that formula written out."""
    from camgen.forces import flank_pressure

    for load, side in ((10, "lower wall"), (-10, "upper wall")):
        design = design_barrel(load_spec(BARREL, ("cam.rpm=300", "follower.mass=0.2", f"follower.load={load}",
                                                  'cam.material="pla"')))
        stress = design.speed.forces.stress
        assert stress.length == 6.0
        cam = design.cam
        ld = spec_loading(design.spec.follower, cam.follower, positive=True)
        contact = Contact("pla", "steel", 6.0)
        at = np.radians([165.0, 20.0])
        g, m = cam.pitch(at), cam.program.evaluate(at)
        force = normal_force(ld, 10 * math.pi, g, m)
        p, b = flank_pressure(contact, g, force, 5.1, 5.0)
        assert (p[0], b[0]) == pytest.approx((20.47801, 0.0518133), rel=2e-6)
        k = g.kappa[1]
        wall = k / (1 - 5.1 * k) if force[1] > 0 else -k / (1 + 5.1 * k)
        assert p[1] == pytest.approx(math.sqrt(abs(force[1]) * contact.e_star * (0.2 + wall) / (math.pi * 6)),
                                     rel=1e-12)
        assert stress.pressure_max >= p.max() * (1 - 1e-12)
        assert getattr(design.speed.forces.drive, "force_positive" if load > 0 else "force_negative") == side


def test_a_barrels_material_needs_its_forces_and_no_rib(tmp_path):
    assert_refused(BARREL, {"cam.material": "pla"}, "cam.material: a barrel cam's contact pressure is at cam.rpm "
                   "with follower.mass; give both", tmp_path)
    assert_refused(ROOT / "templates" / "barrel-rib.toml", {"cam.material": "pla", "cam.rpm": 300,
                                                            "follower.mass": 0.2},
                   "cam.material: a rib's contact pressure is not made yet", tmp_path)
