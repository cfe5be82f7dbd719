"""Gear trains (``type = "gear-train"``): ratios against closed forms written here (Willis' formula for each choice of
fixed and driven member, products of stage ratios), positions against rolling without slip (the pitch circles'
arcs rolled relative to the carrier are equal, and the two gears' material points at each pitch point move alike,
by finite differences of the poses), the gears in mesh with no overlap (shapely) at many inputs, the parts, and bad
input refused in one line naming the field with nothing written."""
from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from camgen.core.shapes import Contour
from linkgen.cli import main as linkgen_cli
from linkgen.linkage_design import design_linkage
from linkgen.mechanisms.geartrain import Train, _outline
from linkgen.spec import validate_spec

PARTS = {"width": 10.0, "thickness": 3.0, "pin_diameter": 3.0, "sheet": [1000.0, 1000.0]}


def _train(checked: bool = False, **linkage) -> Train:
    """The train of a ``[linkage]`` table of module 2; ``checked``: built as the commands build it (every mesh's
    outlines rolled for overlap, which takes seconds), else straight from the validated table."""
    spec = validate_spec({"name": "t", "linkage": {"type": "gear-train", "module": 2.0, **linkage}})
    return spec.mechanism.build(spec.linkage) if checked else Train(spec.linkage)


PLANETARY = {"kind": "planetary", "sun": 30, "planet": 24, "ring": 78, "planets": 3}
ZS, ZR = 30, 78
WILLIS = {("ring", "sun"): ZS / (ZS + ZR), ("ring", "carrier"): (ZS + ZR) / ZS,
          ("sun", "ring"): ZR / (ZS + ZR), ("sun", "carrier"): (ZS + ZR) / ZR,
          ("carrier", "sun"): -ZS / ZR, ("carrier", "ring"): -ZR / ZS}


@pytest.mark.parametrize("fixed, driven", list(WILLIS))
def test_a_planetary_trains_ratio_is_willis(fixed, driven):
    """Willis: (w_s - w_c) / (w_r - w_c) = -z_r / z_s; ring fixed, sun driven: w_c / w_s = z_s / (z_s + z_r), and so
    on for each choice (closed forms above)."""
    train = _train(**PLANETARY, fixed=fixed, input=driven)
    assert train.ratio == pytest.approx(WILLIS[fixed, driven], rel=1e-12)
    s = train.kinematics.speeds
    assert s[fixed] == 0 and s[driven] == 1
    assert (s["sun"] - s["carrier"]) * ZS == pytest.approx(-(s["ring"] - s["carrier"]) * ZR, abs=1e-12)


def test_simple_and_compound_ratios():
    assert _train(kind="simple", teeth=[18, 24, 36]).ratio == pytest.approx(18 / 36, rel=1e-12)   # one idler
    assert _train(kind="simple", teeth=[18, 40]).ratio == pytest.approx(-18 / 40, rel=1e-12)
    assert _train(kind="compound", stages=[[18, 40], [18, 36], [20, 30]]).ratio == \
        pytest.approx(-(18 / 40) * (18 / 36) * (20 / 30), rel=1e-12)


def _rates(train: Train, theta: np.ndarray, h: float = 1e-6) -> tuple[dict, dict, dict, dict]:
    """Angles, centres, angular speeds (per unit input speed) and centre velocities, by central differences."""
    a, c = train.poses(theta)
    a1, c1 = train.poses(theta + h)
    a0, c0 = train.poses(theta - h)
    w = {k: (a1[k] - a0[k]) / (2 * h) for k in a}
    v = {k: (c1[k] - c0[k]) / (2 * h) for k in c}
    return a, c, w, v


def _material(centre: np.ndarray, v: np.ndarray, w: np.ndarray, point: np.ndarray) -> np.ndarray:
    """The velocity of a gear's material point at ``point``: v + w x (point - centre)."""
    r = point - centre
    return v + np.column_stack([-w * r[:, 1], w * r[:, 0]])


@pytest.mark.parametrize("fixed, driven", [("ring", "sun"), ("sun", "carrier"), ("carrier", "ring")])
def test_a_planetary_train_rolls_without_slip(fixed, driven):
    train = _train(**PLANETARY, fixed=fixed, input=driven)
    theta = np.linspace(0.0, 2 * math.pi, 721)
    a, c, w, v = _rates(train, theta)
    rs, rp, rr = (2.0 * z / 2 for z in (30, 24, 78))
    zero = np.zeros((len(theta), 2))
    for k in range(1, 4):
        p = f"planet{k}"
        u = c[p] / np.hypot(*c[p].T)[:, None]
        assert np.abs(np.hypot(*c[p].T) - (rs + rp)).max() < 1e-9
        inner, outer = rs * u, c[p] + rp * u                 # the pitch points with the sun and with the ring
        sun_point = _material(zero, zero, w["sun"], inner)
        planet_in = _material(c[p], v[p], w[p], inner)
        assert np.abs(sun_point - planet_in).max() < 1e-6 * rr
        ring_point = _material(zero, zero, w["ring"], outer)
        planet_out = _material(c[p], v[p], w[p], outer)
        assert np.abs(ring_point - planet_out).max() < 1e-6 * rr
        # the arcs rolled relative to the carrier are equal (integrated, not differentiated)
        sun_arc = (a["sun"] - a["sun"][0] - (a["carrier"] - a["carrier"][0])) * rs
        planet_arc = (a[p] - a[p][0] - (a["carrier"] - a["carrier"][0])) * rp
        ring_arc = (a["ring"] - a["ring"][0] - (a["carrier"] - a["carrier"][0])) * rr
        assert np.abs(sun_arc + planet_arc).max() < 1e-9 * rr
        assert np.abs(ring_arc - planet_arc).max() < 1e-9 * rr


def test_a_simple_trains_pitch_circles_roll_on_each_other():
    train = _train(kind="simple", teeth=[18, 24, 36, 20])
    theta = np.linspace(0.0, 4 * math.pi, 301)
    a, _, _, _ = _rates(train, theta)
    radii = [2.0 * z / 2 for z in (18, 24, 36, 20)]
    for k in range(3):
        first, second = f"gear{k + 1}", f"gear{k + 2}"
        rolled = (a[first] - a[first][0]) * radii[k] + (a[second] - a[second][0]) * radii[k + 1]
        assert np.abs(rolled).max() < 1e-9


def _outlines(train: Train) -> dict[str, tuple[np.ndarray, float, bool]]:
    """Each gear's outline (flattened within 2 micrometres) in its own frame, its pitch radius, whether internal."""
    return {g.name: (Contour(*_outline(g, 0.002)).flatten(0.002), g.tooth.pitch_radius, g.internal)
            for g in train.gears}


def _polygon(shapes: dict, name: str, angle: float, centre: np.ndarray) -> shapely.Geometry:
    points, radius, internal = shapes[name]
    c, s = math.cos(angle), math.sin(angle)
    placed = points @ np.array([[c, s], [-s, c]]) + centre
    if internal:
        return shapely.Polygon(shapely.Point(*centre).buffer(radius + 5).exterior.coords, [placed])
    return shapely.Polygon(placed)


@pytest.mark.parametrize("linkage", [dict(PLANETARY), dict(PLANETARY, fixed="carrier", input="sun"),
                                     {"kind": "simple", "teeth": [18, 25, 36]},
                                     {"kind": "compound", "stages": [[18, 40], [18, 36]]}])
def test_every_mesh_stays_in_mesh_with_no_overlap(linkage):
    """At 12 input angles over a turn (not a multiple of any tooth pitch), every meshing pair's outlines are disjoint
    and closer than the backlash: the phases put each tooth in its mate's space."""
    train = _train(checked=True, **linkage)
    shapes = _outlines(train)
    meshes = {"simple": [("gear1", "gear2"), ("gear2", "gear3")], "compound": [("gear1", "gear2"), ("gear3", "gear4")],
              "planetary": [("sun", f"planet{k}") for k in (1, 2, 3)] + [(f"planet{k}", "ring") for k in (1, 2, 3)]}
    theta = np.linspace(0.0, 2 * math.pi, 12, endpoint=False) + 0.0123
    a, c = train.poses(theta)
    for i in range(len(theta)):
        for first, second in meshes[linkage["kind"]]:
            p = _polygon(shapes, first, float(a[first][i]), c[first][i])
            q = _polygon(shapes, second, float(a[second][i]), c[second][i])
            assert not p.intersects(q), (first, second, theta[i])
            assert p.distance(q) < 0.1, (first, second, theta[i])     # in mesh: the backlash's gap at most


def test_the_planetary_trains_parts_and_layers():
    spec = validate_spec({"name": "p", "linkage": {"type": "gear-train", "module": 2.0, **PLANETARY},
                          "parts": PARTS})
    build = design_linkage(spec, parts=True).build
    assert build.layers == {"ground": 0, "ring-web": 1, "ring": 2, "sun": 2, "carrier": 3, "planet1": 2,
                            "planet2": 2, "planet3": 2}
    carrier = next(p for p in build.parts if p.name == "carrier")
    assert np.hypot(*carrier.centres[1:].T) == pytest.approx([54.0] * 3, abs=1e-12)   # m (sun + planet) / 2


def test_a_compound_trains_shared_shafts_are_bolted():
    spec = validate_spec({"name": "c", "linkage": {"type": "gear-train", "module": 2.0, "kind": "compound",
                                                   "stages": [[18, 40], [18, 36]]}, "parts": PARTS})
    build = design_linkage(spec, parts=True).build
    assert build.layers == {"ground": 0, "gear1": 1, "gear2": 1, "gear3": 2, "gear4": 2}
    gears = {p.name: p for p in build.parts}
    assert len(gears["gear2"].centres) == len(gears["gear3"].centres) == 3      # the shaft's hole and two bolts
    np.testing.assert_allclose(gears["gear2"].centres, gears["gear3"].centres, atol=1e-12)


@pytest.mark.parametrize("extra, message", [
    ('kind = "simple"\nteeth = [0, 20]', "error: linkage.teeth[0]: must be >= 4 (got 0)"),
    ('kind = "simple"\nteeth = [10000, 20]', "error: linkage.teeth[0]: must be <= 1000 (got 10000)"),
    ('kind = "planetary"\nsun = 30\nplanet = 24\nring = 80',
     "error: linkage.ring: must have sun + 2 planet = 78 teeth for the planets to mesh with both (got 80)"),
    ('kind = "planetary"\nsun = 30\nplanet = 24\nring = 78\ncarrier_radius = 55.0',
     "error: linkage.carrier_radius: mesh 1's teeth mesh at 54.000000 mm (got 55); leave it out or give that"),
    ('kind = "simple"\nteeth = [20, 30]\ncentre_distances = [51.0]',
     "error: linkage.centre_distances: mesh 1's teeth mesh at 50.000000 mm (got 51); leave it out or give that"),
    ('kind = "planetary"\nsun = 30\nplanet = 24\nring = 78\nplanets = 5',
     "error: linkage.planets: 5 planets cannot be spaced equally: (sun + ring) / planets = 21.6 must be whole"),
    ('kind = "planetary"\nsun = 30\nplanet = 24\nring = 78\nfixed = "sun"\ninput = "sun"',
     "error: linkage.input: the sun is held still: drive another member (sun, carrier, ring)"),
    ('kind = "compound"\nteeth = [20, 30]', "error: linkage.stages: a compound train needs stages = [[15, 45], "
                                            "[15, 40]] (each stage's driver and driven teeth)"),
])
def test_bad_input_is_one_line_naming_the_field(tmp_path, extra, message):
    path = tmp_path / "bad.toml"
    path.write_text(f'name = "bad"\n[linkage]\ntype = "gear-train"\nmodule = 2.0\n{extra}\n')
    result = CliRunner().invoke(linkgen_cli, ["analyze", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and result.output == message + "\n"
    assert not (tmp_path / "out").exists()
