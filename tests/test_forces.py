"""Cams at a speed: the camshaft torque against the moment of the contact force, Hertz pressure against a hand
computation, the spring sizing and lift-off speed at their limits, the weight by orientation, bad values refused."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from camgen.contact_stress import MATERIALS, Material, effective_modulus, line_contact
from camgen.design import design_cam
from camgen.dynamics import G_MM, loading
from camgen.forces import Contact, contact_pressure, normal_force, torque
from camgen.spec import load_spec
from tests.refusals import assert_refused

ROOT = Path(__file__).resolve().parent.parent
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
        assert design.speed["forces"]["torque_max_N_m"] == pytest.approx(torque(ld, omega, m).max(), rel=1e-3)
        moment = normal_force(ld, omega, g, m) * (g.point[:, 0] * g.normal[:, 1] - g.point[:, 1] * g.normal[:, 0])
        by_energy = torque(ld, omega, m)
        assert np.max(np.abs(cam.follower.sense * moment / 1000.0 - by_energy)) < 1e-9 * np.max(np.abs(by_energy))
        assert np.ptp(by_energy) > 0.3


def test_reported_torque_extremes_and_rms():
    design = _design()
    forces, f = design.speed["forces"], design.spec.follower
    ld = loading(f.mass, f.spring_rate, f.preload, f.load)
    theta = np.linspace(0.0, 2 * math.pi, 400001)
    t = torque(ld, 300 * 2 * math.pi / 60, design.cam.program.evaluate(theta))
    assert forces["torque_max_N_m"] == pytest.approx(t.max(), rel=1e-9, abs=1e-12)
    assert forces["torque_min_N_m"] == pytest.approx(t.min(), rel=1e-9, abs=1e-12)
    assert forces["torque_rms_N_m"] == pytest.approx(math.sqrt(np.mean(t[:-1] ** 2)), rel=1e-9)   # periodic: trapezoid
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
    stress, cam, f = design.speed["forces"]["stress"], design.cam, design.spec.follower
    ld = loading(f.mass, f.spring_rate, f.preload, f.load)
    theta = np.linspace(0.0, 2 * math.pi, 200001)
    g, m = cam.pitch(theta), cam.program.evaluate(theta)
    p, _ = contact_pressure(cam, Contact("pla", "steel", 8.0), g, normal_force(ld, 10 * math.pi, g, m))
    assert stress["pressure_max_MPa"] >= p.max() - 1e-9 and stress["pressure_max_MPa"] - p.max() < 1e-6
    # by hand at the peak: the roller (10 mm) on the profile of radius rho_pitch - 10
    at = math.radians(stress["pressure_max_at_deg"])
    g1, m1 = cam.pitch(np.array([at])), cam.program.evaluate(np.array([at]))
    rho = 1 / g1.kappa[0] - 10.0
    n = float(normal_force(ld, 10 * math.pi, g1, m1)[0])
    e = 1 / ((1 - 0.36 ** 2) / 3500 + (1 - 0.3 ** 2) / 210000)
    assert stress["pressure_max_MPa"] == pytest.approx(math.sqrt(n * e * (1 / 10 + 1 / rho) / (math.pi * 8)),
                                                       rel=1e-12)
    assert stress["allowable_MPa"] == 30.0 and stress["holds"] is True


def test_the_preload_found_holds_exactly_the_margin():
    base = (*LOADED[:3], "follower.contact_margin=2.5")
    need = _design(sets=base).speed["contact"]["preload_needed_n"]
    assert need > 0
    held = _design(sets=(*base, f"follower.preload={need!r}")).speed["contact"]
    assert held["force_min_n"] == pytest.approx(2.5, abs=1e-9)
    assert held["preload_needed_n"] == pytest.approx(need, abs=1e-9)


def test_the_spring_lets_go_at_the_liftoff_speed():
    off = _design().speed["contact"]["liftoff_rpm"]
    assert 300 < off < 1000
    at = _design(sets=(*LOADED, f"cam.rpm={off!r}")).speed["contact"]
    assert at["force_min_n"] == pytest.approx(0.0, abs=1e-9)
    assert _design(sets=(*LOADED, f"cam.rpm={off * 0.999!r}")).speed["contact"]["force_min_n"] > 0
    assert _design(sets=(*LOADED, f"cam.rpm={off * 1.001!r}")).speed["contact"]["force_min_n"] < 0


def test_weight_counts_by_the_orientation():
    """Upright the weight presses the follower onto the cam, upside down it pulls it off: 2 m g apart."""
    up = _design(sets=(*LOADED, "follower.orientation=0")).speed["contact"]
    down = _design(sets=(*LOADED, "follower.orientation=180")).speed["contact"]
    assert up["weight_n"] == pytest.approx(0.2 * G_MM / 1000)
    assert up["force_min_n"] - down["force_min_n"] == pytest.approx(2 * 0.2 * G_MM / 1000, rel=1e-9)


def test_gravity_alone_keeps_its_liftoff_speed():
    """The flat-face template's gravity return: the follower leaves where s'' omega^2 = -g."""
    design = _design(ROOT / "templates" / "flat-face.toml", ())
    contact, cam = design.speed["contact"], design.cam
    theta = np.linspace(0.0, 2 * math.pi, 400001)
    decel = -cam.program.evaluate(theta)[2].min()
    assert contact["liftoff_rpm"] == pytest.approx(math.sqrt(G_MM / decel) * 60 / (2 * math.pi), rel=1e-8)
    assert "forces" in design.speed and "stress" not in design.speed["forces"]


def test_a_flat_face_presses_on_the_profiles_radius_alone():
    design = _design(ROOT / "templates" / "flat-face.toml", ('cam.material="acrylic"', 'follower.material="pom"'))
    stress, cam = design.speed["forces"]["stress"], design.cam
    at = math.radians(stress["pressure_max_at_deg"])
    g = cam.pitch(np.array([at]))
    f = design.spec.follower
    n = float(normal_force(loading(f.mass, None, None), 200 * math.pi / 30, g, cam.program.evaluate(np.array([at])))[0])
    e = effective_modulus(MATERIALS["acrylic"], MATERIALS["pom"])
    assert stress["pressure_max_MPa"] == pytest.approx(math.sqrt(n * e / g.rho[0] / (math.pi * 6.0)), rel=1e-9)


@pytest.mark.parametrize("change, message", [
    ({"cam.material": "balsa"}, "cam.material: must be one of"),
    ({"follower.load": 2e6}, "follower.load: must be >= -1e+06 and <= 1e+06 N (got 2000000.0)"),
    ({"follower.orientation": 270}, "follower.orientation: must be >= -180 and <= 180 degrees (got 270)"),
])
def test_bad_values_are_refused_by_name(tmp_path, change, message):
    assert_refused(RDRD, change, message, tmp_path)


def test_an_arms_weight_is_refused_and_its_spring_sized_at_the_roller(tmp_path):
    assert_refused(OSCILLATING, {"follower.orientation": 0}, "follower.orientation: only for a translating", tmp_path)
    base = ("follower.contact_margin=1",)
    need = _design(OSCILLATING, base).speed["contact"]["preload_needed_n"]
    held = _design(OSCILLATING, (*base, f"follower.preload={need!r}")).speed["contact"]
    assert held["force_min_n"] == pytest.approx(1.0, abs=1e-9)


def test_gravity_with_a_margin_warns_in_words():
    """A flat face held by gravity with a contact margin is checked as a loading: losing contact is a warning (it
    was a KeyError: the gravity warning read a lift-off angle that only gravity alone gives)."""
    design = _design(ROOT / "templates" / "flat-face.toml", ("follower.contact_margin=5", "cam.rpm=400"))
    assert design.speed["contact"]["holds"] is False
    assert any(w.startswith("the follower loses contact near") for w in design.warnings)


@pytest.mark.parametrize("template, sets, key, scale, unit", [
    (RDRD, ("cam.rpm=300",), "velocity_max_mm_s", 1e-3, "v (m/s)"),
    (OSCILLATING, (), "velocity_max_deg_s", math.pi / 180, "v (rad/s)"),
])
def test_svaj_plots_in_the_machines_units(template, sets, key, scale, unit):
    """At a speed the S-V-A-J figure is in time: its velocity peak is the report's, in m/s (or rad/s for an arm)."""
    from camgen.plots import svaj_figure

    design = _design(template, sets)
    axes = svaj_figure(design).axes
    assert axes[1].get_ylabel() == unit
    peak = float(np.max(np.abs(axes[1].get_lines()[0].get_ydata())))
    assert peak == pytest.approx(design.speed[key] * scale, rel=1e-6)


def test_the_checks_figure_draws_the_reported_figures():
    """The checks figure: its pressure angle peaks at the report's, its torque at the forces' extremes, its Hertz
    pressure at the stress's peak (the dense plot within 0.5 % of the refined peaks)."""
    from camgen.plots import checks_figure

    design = _design()
    axes = checks_figure(design).axes
    pressure = np.max(np.abs(axes[0].get_lines()[0].get_ydata()))
    assert pressure == pytest.approx(design.analysis.pressure_angle_max_deg, rel=5e-3)
    torque_line = next(a for a in axes if a.get_ylabel().startswith("shaft torque")).get_lines()[0].get_ydata()
    assert np.max(torque_line) == pytest.approx(design.speed["forces"]["torque_max_N_m"], rel=5e-3)
    hertz = next(a for a in axes if a.get_ylabel().startswith("Hertz")).get_lines()[0].get_ydata()
    assert np.max(hertz) == pytest.approx(design.speed["forces"]["stress"]["pressure_max_MPa"], rel=5e-3)
    flat = checks_figure(_design(ROOT / "templates" / "flat-face.toml", ())).axes[0]
    assert not flat.get_lines() and "0 by definition" in flat.texts[0].get_text()
