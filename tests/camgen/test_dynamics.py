"""Speed and contact: peaks in the time domain, gravity lift-off and spring contact, against direct checks."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.api import design_cam
from camgen.dynamics import G_MM
from camgen.report import cam_report
from camgen.speed import GravityHold, HeldContact, Speed, Unanalysed
from tests.conftest import template

THETA = np.linspace(0, 2 * math.pi, 720001)


def speed(changes: dict) -> Speed:
    return design_cam(template(changes)).speed


def test_time_domain_peaks():
    """Cycloidal rise h = 20 mm over 120 degrees at 60 rpm: v = 2 h omega / beta, a = 2 pi h omega^2 / beta^2."""
    r = speed({"cam.rpm": 60.0})
    omega, beta = 2 * math.pi, 2 * math.pi / 3
    assert r.unit == "mm"
    assert r.velocity_max == pytest.approx(2 * 20 * omega / beta, rel=1e-12)
    assert r.acceleration_max == pytest.approx(2 * math.pi * 20 * omega**2 / beta**2, rel=1e-12)
    assert r.jerk_max == pytest.approx(4 * math.pi**2 * 20 * omega**3 / beta**3, rel=1e-12)
    assert r.contact is None


def test_parabolic_acceleration_ratio_is_reported():
    r = speed({"cam.rpm": 60.0, "motion.2.law": "parabolic", "motion.2.ratio": 1.5})
    assert r.parabolic == ((2, 1.5),)


def test_gravity_liftoff_speed_against_the_follower_deceleration():
    r = speed({"cam.rpm": 100.0, "follower.mass": 0.3}).contact
    assert isinstance(r, GravityHold)
    limit = r.liftoff_rpm
    s2 = design_cam(template({})).cam.program.evaluate(THETA)[2]
    for factor, holds in ((0.999, True), (1.001, False)):
        omega = factor * limit * 2 * math.pi / 60
        assert (omega**2 * s2 >= -G_MM).all() == holds              # a = omega^2 s'' never below -g
    assert r.holds is True
    assert speed({"cam.rpm": limit * 1.01, "follower.mass": 0.3}).contact.holds is False


def test_spring_contact_force_and_the_spring_that_would_hold():
    changes = {"cam.rpm": 300.0, "follower.mass": 0.5, "follower.spring_rate": 0.2, "follower.preload": 2.0}
    r = speed(changes).contact
    assert isinstance(r, HeldContact) and r.mode == "spring"
    m = design_cam(template({})).cam.program.evaluate(THETA)
    omega = 300 * 2 * math.pi / 60

    def force(rate: float, preload: float) -> np.ndarray:
        return preload + rate * m[0] + 0.5 * omega**2 * m[2] / 1000

    assert r.force_min == pytest.approx(force(0.2, 2.0).min(), abs=1e-6)
    assert r.holds is False
    assert force(0.2, r.preload_needed).min() == pytest.approx(0.0, abs=1e-6)
    assert force(r.rate_needed, 2.0).min() == pytest.approx(0.0, abs=1e-6)
    report = cam_report(design_cam(template(changes)))
    assert any("spring loses contact" in w for w in report["warnings"])


def test_contact_for_an_oscillating_follower_is_not_guessed():
    from tests.camgen.test_followers import OSC_ROLLER, spec

    d = design_cam(spec({**OSC_ROLLER, "cam.rpm": 60.0, "follower.mass": 0.2}))
    assert d.speed.unit == "deg" and isinstance(d.speed.contact, Unanalysed)
    r = cam_report(d)["speed"]                     # the report's keys: the rates in degrees, no contact mode
    assert "velocity_max_deg_s" in r and r["contact"]["mode"] is None
