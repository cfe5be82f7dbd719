"""A Geneva drive's parts as clash bodies (issue 35 item 4, :mod:`camgen.kinds.machine.geneva_bodies`): a lever
sweeping into the dwelling wheel found within 0.1 degree of the angle worked here from the drive's own outline (in a
dwell a locking arc faces the driver's axis); the pin riding in the slot exactly while the wheel indexes, the
wheel's turn the drive's geometry (the slot through the pin), for a driver turning either way; every part of a
framed Geneva machine meeting no other but at its joints at 720 angles, the plate holding the wheel's shaft in a
hole of the drive's wheel bore."""
from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest
import shapely

from tests.conftest import ROOT
from tests.support.machine_meetings import assert_meet_only_at_joints, spans

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-geneva-clash")

GENEVA = ROOT / "templates" / "geneva4.toml"
#: the drive's centre distance (mm), slots and engagement half angle (rad: pi/2 - pi/n)
C, SLOTS = 80.0, 4
ENGAGED = math.pi / 2 - math.pi / SLOTS
PHI = np.arange(720) * (2 * math.pi / 720)
#: the driver's shaft (mm, geared from the main shaft at the origin: 60:15 teeth of module 3) and the wheel's, 80 mm
#: from it at 120 degrees; the lever's length (mm): its round tip (4 mm) reaches 59 mm from the main shaft, past the
#: wheel's rim (43.7 mm from it) and 5.9 mm short of the locking disc (radius 47.57 mm about the driver's shaft); it
#: meets the rim 57 mm out, where a slot's flank ends (the longer the lever, the faster that point moves and the
#: nearer the clash check's chords and area tolerance put the angle)
DRIVER, GAMMA, LEVER = (112.5, 0.0), math.radians(120.0), 55.0
WHEEL = (DRIVER[0] + C * math.cos(GAMMA), C * math.sin(GAMMA))


def _lever(layer: int, length: float = LEVER) -> dict:
    """A crank ``length`` mm long, 8 mm wide, on the main shaft at (0, 0), drawn along +X, turning with it."""
    return {"name": "lever", "shaft": "main", "layer": layer,
            "template": {"linkage": {"type": "linkage", "ground": ["O"], "input": {"link": "crank", "pivot": "O"},
                                     "tracers": ["A"], "joints": {"O": [0.0, 0.0], "A": [length, 0.0]},
                                     "links": {"crank": ["O", "A"]}},
                         "parts": {"width": 8.0, "thickness": 3.0, "pin_diameter": 3.0}}}


def _machine(lever_layer: int, frame: str = "none", geneva: dict | None = None) -> dict:
    """The main shaft at the origin turning a driver shaft at :data:`DRIVER` 4 times a turn (gears 60:15, clockwise),
    whose Geneva drive (phase 150, on layer 0: its crank on plane 0, its disc and wheel on plane 1) indexes the
    wheel's shaft at :data:`WHEEL`; a lever on the main shaft."""
    template = tomllib.loads(GENEVA.read_text()) if geneva is None else geneva
    return {"name": "crossed", "machine": {"main": "main", "rpm": 10.0, "frame": frame},
            "shafts": [{"name": "main", "at": [0.0, 0.0]}, {"name": "driver", "at": list(DRIVER)},
                       {"name": "wheel", "at": list(WHEEL)}],
            "gears": [{"driver": "main", "driven": "driver", "driver_teeth": 60, "driven_teeth": 15, "module": 3.0}],
            "genevas": [{"name": "index", "driver": "driver", "wheel": "wheel", "phase": 150.0, "layer": 0,
                         "template": template}],
            "linkages": [_lever(lever_layer)], "output": {"formats": ["json"]}}


#: a driver on the main shaft (counter-clockwise) and the wheel 80 mm along +X, the drive on the lowest free planes,
#: the lever (a machine has a cam or a shaft's linkage) on plane 5, over it
STRAIGHT = {"name": "straight", "machine": {"main": "main", "rpm": 10.0},
            "shafts": [{"name": "main", "at": [10.0, 5.0]}, {"name": "wheel", "at": [90.0, 5.0]}],
            "genevas": [{"name": "index", "driver": "main", "wheel": "wheel", "phase": -100.0,
                         "template": str(GENEVA)}],
            "linkages": [_lever(2)], "output": {"formats": ["json"]}}


def _design(raw: dict):
    from camgen import api

    return api.design(api.validate(copy.deepcopy(raw)))


@pytest.fixture(scope="module")
def crossed():
    return _design(_machine(0))


def _dwelling_wheel() -> shapely.Polygon:
    """The wheel in a dwell, worked from the drive's outline alone: a locking arc faces the driver's axis, so the
    bisector of slots 0 and 1 (pi/n from slot 0 in the wheel's frame) points from the wheel's axis at the driver's:
    the wheel's outline (chords within 1e-4 mm) turned by pi + GAMMA - pi/n about its axis. (Any slot may face it:
    the outline is the same turned by 2 pi / n.)"""
    from shapely import affinity

    from camgen.kinds.geneva.geometry import GenevaGeometry

    raw = tomllib.loads(GENEVA.read_text())["geneva"]
    g = GenevaGeometry(raw["slots"], raw["centre_distance"], raw["pin_diameter"], raw["slot_clearance"],
                       raw["lock_clearance"], _lock_radius(), 14.0, raw["driver_bore"], raw["wheel_bore"])
    ring = shapely.Polygon(g.wheel().flatten(1e-4))
    turned = affinity.rotate(ring, math.pi + GAMMA - math.pi / SLOTS, origin=(0, 0), use_radians=True)
    return affinity.translate(turned, *WHEEL)


def _lock_radius() -> float:
    """The template's locking disc radius (its default when the template gives none): the Geneva kind's own."""
    from camgen import api

    return api.design(api.validate(tomllib.loads(GENEVA.read_text()))).geometry.lock_radius


def _lever_at(deg: float) -> shapely.Geometry:
    """The lever (a segment :data:`LEVER` mm long from the origin at ``deg`` degrees, 4 mm round it)."""
    a = math.radians(deg)
    return shapely.LineString([(0.0, 0.0), (LEVER * math.cos(a), LEVER * math.sin(a))]).buffer(4.0, quad_segs=256)


def _first_touch_deg() -> float:
    """The first main shaft angle (degrees) at which the lever overlaps the dwelling wheel (by 1e-6 mm^2): scanned
    every 0.05 degrees from 0, then bisected to 1e-6 degrees."""
    wheel = _dwelling_wheel()

    def meets(deg: float) -> bool:
        return shapely.intersection(_lever_at(deg), wheel).area > 1e-6

    assert not meets(0.0)
    hi = next(d for d in np.arange(0.05, 90.0, 0.05) if meets(float(d)))
    lo = hi - 0.05
    while hi - lo > 1e-6:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if meets(mid) else (mid, hi)
    return hi


def test_a_lever_sweeping_into_the_wheel_is_found_at_its_angle(crossed):
    """The lever (plane 1, the wheel's) meets the wheel first at the angle worked from the dwelling wheel's outline,
    within 0.1 degree; the wheel dwells there (the driver's pin, at 150 - 4 phi degrees clockwise, is 45 degrees
    or more from the centre line from 2 degrees before); the wheel is the first part it meets; nothing goes
    unchecked."""
    assert crossed.unchecked == ()
    expected = _first_touch_deg()
    for deg in (expected - 2.0, expected):
        a = math.remainder(math.radians(150.0 + 4 * deg), 2 * math.pi)
        assert abs(a) > ENGAGED, deg
    met = {frozenset((c.a, c.b)): c.angle_deg for c in crossed.clashes}
    first = met[frozenset(("linkages.lever.crank", "genevas.index.wheel"))]
    assert abs(first - expected) <= 0.1, (first, expected)
    assert first == min(met.values())
    assert all("linkages.lever.crank" in pair for pair in met), met


def test_a_lever_on_the_plane_over_passes_the_drive():
    """The same lever a layer up (plane 3) meets nothing: the drive fills planes 0 and 1, the gears take the lowest
    free plane (2) and the shafts end under the lever, which turns with its own."""
    moved = _design(_machine(1))
    assert moved.clashes == () and moved.unchecked == ()
    planes = {b.name: (b.low, b.high) for b in moved.bodies}
    assert planes["genevas.index.crank"] == (0, 0)
    assert planes["genevas.index.lock"] == planes["genevas.index.wheel"] == (1, 1)
    assert planes["genevas.index.pin"] == (0, 1)
    assert planes["linkages.lever.crank"] == (3, 3)


def _wheel_turn(phi: np.ndarray, start: float, sense: float) -> np.ndarray:
    """The wheel's turn (rad, counter-clockwise, from the start) from the drive's geometry alone, for a driver
    whose pin stands ``start`` rad from the centre line at phi = 0 and advances |4| or 1 times phi... (see
    :func:`tests.camgen.kinds.machine.test_geneva_mount._wheel_angle`, the same construction): the slot through the
    pin while it lies within the wheel's entry radius, else the dwell, unwrapped; the wheel turns against the
    driver, so by -sense times it."""
    a = C * math.sin(math.pi / SLOTS)
    x, y = a * np.cos(phi + start), a * np.sin(phi + start)
    inside = np.hypot(C - x, y) <= C * math.cos(math.pi / SLOTS) + 1e-12
    slot = np.arctan2(y, C - x)
    turns = np.floor((phi + start + math.pi) / (2 * math.pi))
    wrapped = phi + start - 2 * math.pi * turns
    dwell = np.where(wrapped < 0, -math.pi / SLOTS, math.pi / SLOTS)
    turned = turns * 2 * math.pi / SLOTS + np.where(inside, slot, dwell)
    return -sense * (turned - turned[0])


@pytest.mark.parametrize("which", ["straight", "crossed"])
def test_the_pin_rides_in_the_slot_while_the_wheel_indexes(which, crossed):
    """The pin is half the slot clearance (0.1 mm) from the wheel, to the chords (0.01 mm), exactly while the
    pin's angle lies within the engagement (45 degrees of the centre line), and farther in the dwell (the locking
    disc holds the wheel); the placed wheel turns as the drive's geometry turns it (the slot through the pin), for a
    driver turning counter-clockwise (on the main shaft, mirrored not) and clockwise (4 times a turn through
    gears, mirrored)."""
    from camgen.kinds.machine import clash

    design = _design(STRAIGHT) if which == "straight" else crossed
    speed, start, sense = (1.0, math.radians(-100.0), 1.0) if which == "straight" else (4.0, math.radians(150), -1.0)
    bodies = {b.name: b for b in clash.machine_parts(design)[0]}
    pin, wheel = (bodies[f"genevas.index.{w}"] for w in ("pin", "wheel"))
    gap = shapely.distance(clash.outlines(pin, PHI), clash.outlines(wheel, PHI))
    pin_angle = np.remainder(speed * PHI + start + math.pi, 2 * math.pi) - math.pi
    engaged = np.abs(pin_angle) < ENGAGED - 1e-3
    dwelling = np.abs(pin_angle) > ENGAGED + 1e-3
    assert engaged.sum() > 50 and dwelling.sum() > 300
    assert np.abs(gap[engaged] - 0.1).max() < 0.015
    assert gap[dwelling].min() > 0.1 + 0.015
    m, _ = wheel.place(PHI)
    turn = np.unwrap(np.arctan2(m[:, 1, 0], m[:, 0, 0]))
    if np.linalg.det(m[0]) < 0:                          # mirrored: R diag(1, -1); its turn is R's
        turn = np.unwrap(np.arctan2(-m[:, 0, 1], m[:, 1, 1]))
    expected = _wheel_turn(speed * PHI, start, sense)
    assert np.abs((turn - turn[0]) - expected).max() < 1e-9
    # the pin on its circle about the driver's shaft, at the driver's angle in its sense
    driver = np.array([10.0, 5.0]) if which == "straight" else np.array(DRIVER)
    line = math.atan2(*(np.array(design.spec.shafts[1 if which == "straight" else 2].at) - driver)[::-1])
    angle = line + sense * (speed * PHI + start)
    centres = shapely.get_coordinates(shapely.centroid(clash.outlines(pin, PHI)))
    assert np.abs(centres - driver - 56.5685424949238 * np.column_stack([np.cos(angle), np.sin(angle)])).max() < 1e-6


@pytest.mark.slow
def test_a_framed_geneva_machine_meets_only_at_its_joints_and_its_plate_holds_the_wheel_shaft():
    """With one plate and the drive's wheel bore 6 mm (its shaft carrying the wheel alone): the plate's hole at the
    wheel's shaft is 6 + 0.2 mm (the running play), at the shaft, as the driver's is its bore 8 + 0.2; every part at
    720 angles meets no other but at its joints (heights from the assembly), nothing unchecked, no clash; the kit
    lists the drive's wheel, locking disc and crank."""
    from camgen.kinds.machine import clash

    geneva = tomllib.loads(GENEVA.read_text())
    geneva["geneva"]["wheel_bore"] = 6.0
    design = _design(_machine(1, "one", geneva))
    assert design.clashes == () and design.unchecked == ()
    holes = {(round(c[0], 9), round(c[1], 9)): d for c, d in design.frame.plate.holes}
    assert holes[(round(WHEEL[0], 9), round(WHEEL[1], 9))] == pytest.approx(6.2, abs=1e-12)
    assert holes[DRIVER] == pytest.approx(8.2, abs=1e-12)
    bodies, joints, _ = clash.machine_parts(design, one_plate=True)
    shaft = next(b for b in bodies if b.name == "shafts.wheel")
    assert float(np.abs(shaft.outline).max()) == pytest.approx(3.0, abs=1e-9)
    checked = assert_meet_only_at_joints(bodies, joints, spans(design, bodies), PHI)
    assert checked >= 8
    from camgen.kinds.machine.framekit import bom

    made = {line.item: line for line in bom(design.frame, design) if line.source != "buy"}
    for part in ("wheel", "lock", "crank"):                 # the kit lists the drive's parts, as thick as made
        assert f"{design.indexed[0].name}-{part}" in made
        assert f"{design.indexed[0].design.cut[part].thickness:g} mm" in made[f"{design.indexed[0].name}-{part}"].size
