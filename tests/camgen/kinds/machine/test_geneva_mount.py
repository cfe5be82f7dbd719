"""A Geneva drive between two of a machine's shafts (issue 35): the wheel shaft's angle over the turn against the
drive's own geometry (the wheel's slot through the pin, written here), a cam on the wheel's shaft moving only while
the wheel indexes, the index and dwell in the timing; the shafts' distance, a coupling loop and a Geneva given as a
cam refused in one line."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from tests.conftest import ROOT
from tests.support.refusals import assert_refused

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-geneva-mount")

#: the driver's shaft turns 4 times a main turn (gears 60:15), so the 4-slot wheel turns once: 4 indexes a turn
MACHINE = f"""
name = "indexer"

[machine]
main = "main"
rpm = 10.0

[[shafts]]
name = "main"
at = [0.0, 0.0]

[[shafts]]
name = "driver"
at = [75.0, 0.0]

[[shafts]]
name = "wheel"
at = [75.0, 80.0]

[[shafts]]
name = "idle"
at = [75.0, 160.0]

[[gears]]
driver = "main"
driven = "driver"
driver_teeth = 60
driven_teeth = 15
module = 2.0

[[genevas]]
name = "index"
driver = "driver"
wheel = "wheel"
phase = 150.0
template = "{ROOT / 'templates' / 'geneva4.toml'}"

[[cams]]
name = "lift"
shaft = "wheel"
phase = 20.0
template = "{ROOT / 'templates' / 'oscillating.toml'}"
"""
SLOTS, CENTRE, DRIVER_TURNS, START = 4, 80.0, 4.0, math.radians(150.0)


@pytest.fixture(scope="module")
def indexer():
    from camgen import api

    return api.design(api.validate(tomllib.loads(MACHINE)))


def _wheel_angle(phi: np.ndarray) -> np.ndarray:
    """The wheel's turn (rad, from the machine's start, in its own sense) from the drive's geometry: the pin at
    a (cos alpha, sin alpha) about the driver, a = C sin(pi/n); while it lies within the wheel's entry radius
    C cos(pi/n), the engaged slot points from the wheel's centre (C, 0) to it, so the wheel stands at
    atan2(y, C - x) from the centre line; outside it dwells. The turns are counted by unwrapping, one index of
    2 pi / n a driver turn."""
    alpha = DRIVER_TURNS * phi + START
    a = CENTRE * math.sin(math.pi / SLOTS)
    x, y = a * np.cos(alpha), a * np.sin(alpha)
    inside = np.hypot(CENTRE - x, y) <= CENTRE * math.cos(math.pi / SLOTS) + 1e-12
    slot = np.arctan2(y, CENTRE - x)                                  # -pi/n .. pi/n while engaged
    turns = np.floor((alpha + math.pi) / (2 * math.pi))               # driver turns completed since alpha = -pi
    wrapped = alpha - 2 * math.pi * turns                             # in [-pi, pi)
    dwell = np.where(wrapped < 0, -math.pi / SLOTS, math.pi / SLOTS)
    turned = turns * 2 * math.pi / SLOTS + np.where(inside, slot, dwell) + math.pi / SLOTS
    return turned - turned[0]


def test_the_wheel_shafts_angle_is_the_drives_own_geometry(indexer):
    phi = indexer.phi
    assert phi[0] == 0.0
    wheel = {o.label: o for o in indexer.outputs}["genevas.index"]
    assert wheel.unit == "deg"
    assert np.abs(np.radians(wheel.values) - _wheel_angle(phi)).max() < 1e-9
    assert np.radians(wheel.values[-1]) == pytest.approx(2 * math.pi, abs=1e-12)   # a turn a main turn: 4 indexes
    # its rate against central differences of the geometry's angle
    h = 1e-6
    numeric = (_wheel_angle(np.concatenate([[0.0], phi + h]))[1:] - _wheel_angle(np.concatenate([[0.0], phi - h]))[1:])
    assert np.abs(np.radians(wheel.rate) - numeric / (2 * h)).max() < 1e-5


def test_a_cam_on_the_wheels_shaft_moves_only_while_it_indexes(indexer):
    cam = indexer.cam("lift")
    program = cam.design.cam.program
    expected = program.evaluate(np.mod(_wheel_angle(indexer.phi) - math.radians(20.0), 2 * math.pi))[0]
    assert np.abs(cam.follower[0] - expected).max() < 1e-9
    indexing = indexer.indexed[0].indexing(indexer.phi)
    assert 0.2 < indexing.mean() < 0.3                               # 4 x 90 degrees of the driver: 1/4 of a turn
    assert np.abs(cam.rate[~indexing]).max() == 0.0                  # still while the wheel dwells
    assert np.abs(cam.rate[indexing]).max() > 1.0                    # and moving while it indexes
    assert np.ptp(cam.follower[0]) == pytest.approx(20.0, abs=1e-6)


def test_the_timing_shows_four_indexes_and_their_dwells(indexer):
    from camgen.kinds.machine.report import timing

    rows = {r["output"]: r for r in timing(indexer)["outputs"]}
    moving = rows["genevas.index"]["moving_deg"]
    assert len(moving) == 4
    # each index lasts a quarter of a driver turn (90 degrees of it, 22.5 of the main shaft)
    assert all(b - a == pytest.approx(22.5, abs=2 * 0.5) for a, b in moving)
    assert not any("genevas.index" in o["outputs"] and "cams.lift" in o["outputs"]
                   for o in timing(indexer)["overlaps"])              # they move together by construction
    assert indexer.unchecked == ()                                    # its parts placed (test_geneva_clash)
    # the pin in a slot while 4 phi + 150 lies within 45 degrees of a whole turn: phi from 41.25 to 63.75, ...
    from camgen.kinds.machine.report import machine_report

    runs = machine_report(indexer)["genevas"]["index"]["indexing_deg"]
    assert runs == [[pytest.approx(41.25 + 90 * k, abs=0.5), pytest.approx(63.75 + 90 * k, abs=0.5)]
                    for k in range(4)]


@pytest.mark.parametrize(("old", "new", "message"), [
    ('at = [75.0, 80.0]', 'at = [75.0, 81.0]', "genevas[0].wheel: the shafts driver and wheel lie 81 mm apart; this "
     "Geneva drive's centre_distance is 80 mm"),
    ('wheel = "wheel"', 'wheel = "main"', "genevas[0].wheel: a coupling loop: shaft main is the main shaft"),
    ('driver = "driver"\nwheel', 'driver = "idle"\nwheel', "genevas[0].driver: shaft idle is not driven: no gear "
     "pair connects it to the main shaft main"),
])
def test_bad_genevas_are_refused_in_one_line(tmp_path, old, new, message):
    path = tmp_path / "m.toml"
    assert old in MACHINE
    path.write_text(MACHINE.replace(old, new, 1))
    assert_refused(path, {}, message, tmp_path)


def test_a_geneva_drive_as_a_cam_is_refused_in_one_line(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(MACHINE.replace("oscillating.toml", "geneva4.toml"))
    assert_refused(path, {}, "cams[0].template: a cam template; a Geneva drive stands between two shafts: give it in "
                   "[[genevas]] (driver, wheel, template)", tmp_path)
