"""`camgen new walking-toy` (issue 35 item 6): two four-bar legs in antiphase through a gear pair. Each foot is
checked against a circle intersection written here (the crank pin A and the rocker's pivot Q, the coupler's point P
placed from A and B), the transmission angle against its closed form at the crank's two in-line positions, and the
step's figures the machines guide states."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from camgen import api
from camgen.starters import starter

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-walking-toy-starter")

GROUND, CRANK, COUPLER, ROCKER = 60.0, 15.0, 50.0, 50.0
POINT, POINT_ANGLE, TURNED = 110.0, math.radians(-70.0), math.radians(330.0)


@pytest.fixture(scope="module")
def toy():
    return api.design(api.validate(tomllib.loads(starter("walking-toy", "toy"))))


def _foot(theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The foot P (n, 2) mm and the transmission angle (rad) at crank angles ``theta`` (from the leg's ground line
    O -> Q), in the leg's drawing: the four-bar's frame turned by 330 degrees, O at the origin."""
    a = CRANK * np.column_stack((np.cos(theta), np.sin(theta)))
    q = np.array([GROUND, 0.0])
    d_vec = q - a
    d = np.hypot(*d_vec.T)
    along = (COUPLER ** 2 - ROCKER ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(COUPLER ** 2 - along ** 2)
    u = d_vec / d[:, None]
    b = a + along[:, None] * u + h[:, None] * np.column_stack((-u[:, 1], u[:, 0]))
    coupler = np.arctan2(*(b - a).T[::-1])
    p = a + POINT * np.column_stack((np.cos(coupler + POINT_ANGLE), np.sin(coupler + POINT_ANGLE)))
    cb, rb = a - b, q - b
    gamma = np.arccos(np.sum(cb * rb, axis=1) / (COUPLER * ROCKER))
    turn = np.array([[math.cos(TURNED), -math.sin(TURNED)], [math.sin(TURNED), math.cos(TURNED)]])
    return p @ turn.T, gamma


def test_the_starter_builds_with_no_warning(toy):
    assert toy.warnings == () and toy.clashes == ()


def test_each_foot_is_the_four_bars_coupler_point(toy):
    """At main shaft angle phi the legs' shaft has turned -2 phi: each crank stands at its drawn 60 degrees (90 in
    the four-bar's frame) + its phase - 2 phi; the feet agree with the circle intersection to 1e-9 mm."""
    for leg in toy.cranked:
        theta = math.radians(90.0 + leg.phase_deg) - 2.0 * toy.phi
        expected, _ = _foot(theta)
        assert np.abs(leg.points["P"] - leg.offset - expected).max() < 1e-9


def test_the_transmission_angle_stays_within_its_closed_form_band(toy):
    """gamma at B: cos gamma = (b^2 + r^2 - (g -+ c)^2) / (2 b r) at the crank in line with the ground, 53.49 and
    97.18 degrees; inside the 40-140 band that a starter must keep."""
    low = math.degrees(math.acos((COUPLER ** 2 + ROCKER ** 2 - (GROUND - CRANK) ** 2) / (2 * COUPLER * ROCKER)))
    high = math.degrees(math.acos((COUPLER ** 2 + ROCKER ** 2 - (GROUND + CRANK) ** 2) / (2 * COUPLER * ROCKER)))
    _, gamma = _foot(np.linspace(0.0, 2 * math.pi, 3601))
    assert np.degrees(gamma).min() == pytest.approx(low, abs=1e-6)
    assert np.degrees(gamma).max() == pytest.approx(high, abs=1e-6)
    assert 40.0 < low < high < 140.0
    assert (round(low, 1), round(high, 1)) == (53.5, 97.2)


def test_the_step_is_as_the_guide_says(toy):
    """The foot's low run (the 40 % of the turn it spends lowest) is about 33 mm long and within 2.3 mm of level;
    the foot lifts about 20 mm (docs/guides/machines.md)."""
    p, _ = _foot(np.linspace(0.0, 2 * math.pi, 720, endpoint=False))
    low = p[:, 1] <= np.quantile(p[:, 1], 0.4)
    assert np.ptp(p[low, 0]) == pytest.approx(33.2, abs=0.1)
    assert np.ptp(p[low, 1]) == pytest.approx(2.3, abs=0.05)
    assert np.ptp(p[:, 1]) == pytest.approx(20.1, abs=0.1)
    left = next(leg for leg in toy.cranked if leg.phase_deg == 0.0)           # the machine's 360 samples a leg turn
    assert np.ptp(left.points["P"][:, 1]) == pytest.approx(np.ptp(p[:, 1]), abs=0.01)
