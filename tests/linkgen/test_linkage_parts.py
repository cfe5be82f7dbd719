"""``linkgen build``: bars, plates and blocks re-read from the DXF and STL, layers checked over the motion."""
from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from linkgen.cli import main
from linkgen.linkage_design import design_linkage
from linkgen.spec import load_spec
from tests.conftest import ROOT

TEMPLATE = ROOT / "templates" / "crank-rocker.toml"
PIN, CLEARANCE, KERF = 4.0, 0.2, 0.15


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("crank-rocker")
    result = CliRunner().invoke(main, ["build", str(TEMPLATE), "-o", str(out), "--set", "linkage.point_distance=120",
                                       "--set", "linkage.point_angle=30"])
    assert result.exit_code == 0, result.output
    return out, json.loads((out / "crank-rocker.json").read_text())


def _sheet_parts(path):
    """Each part on the sheet: its outline polygon and its hole circles (centre, radius)."""
    import ezdxf

    from camgen.core.shapes import Contour

    msp = ezdxf.readfile(path).modelspace()
    outlines = []
    for pl in msp.query('LWPOLYLINE[layer=="OUTLINE"]'):
        pts = np.array([(x, y, b) for x, y, _, _, b in pl.get_points("xyseb")])
        outlines.append(shapely.Polygon(Contour(pts[:, :2], pts[:, 2]).flatten(1e-3)))
    holes = [(np.array(c.dxf.center)[:2], c.dxf.radius) for c in msp.query('CIRCLE[layer=="HOLES"]')]
    return outlines, holes


def test_sheet_hole_distances_diameters_and_gaps(built):
    out, report = built
    outlines, holes = _sheet_parts(out / "crank-rocker-sheet.dxf")
    assert len(outlines) == 4
    lengths = {"ground": 180.0, "crank": 80.0, "coupler": 200.0, "rocker": 150.0}
    found = {}
    for poly in outlines:
        inside = [c for c, _ in holes if poly.contains(shapely.Point(c))]
        found.setdefault(len(inside), []).append(inside)
    two = sorted(float(np.linalg.norm(a - b)) for a, b in found[2])
    assert two == pytest.approx(sorted([180.0, 80.0, 150.0]), abs=1e-6)
    plate = found[3][0]                                              # the coupler plate: A, B and the point
    distances = sorted(float(np.linalg.norm(a - b)) for a, b in itertools.combinations(plate, 2))
    third = math.sqrt(200**2 + 120**2 - 2 * 200 * 120 * math.cos(math.radians(30)))   # law of cosines: B to P
    assert distances == pytest.approx(sorted([200.0, 120.0, third]), abs=1e-6)
    assert {round(2 * r, 9) for _, r in holes} == {round(PIN + CLEARANCE - KERF, 9)}
    gap = KERF + 3.0
    for a, b in itertools.combinations(outlines, 2):
        assert not a.intersects(b) and a.distance(b) >= gap - 1e-9
    minx, miny, maxx, maxy = shapely.unary_union(outlines).bounds
    assert maxx - minx <= 600 and maxy - miny <= 400
    assert {p["name"]: p["hole_distance_mm"] for p in report["parts"]} == lengths | {"coupler": 200.0}


def test_stl_per_part_watertight_with_printing_clearance(built):
    import trimesh

    out, report = built
    for part in report["parts"]:
        mesh = trimesh.load(out / f"crank-rocker-{part['name']}.stl")
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0
        centre = np.array([part["holes"][0]["x_mm"], part["holes"][0]["y_mm"]])
        near = np.linalg.norm(mesh.vertices[:, :2] - centre, axis=1)
        assert near.min() == pytest.approx((PIN + CLEARANCE) / 2, abs=1e-5)     # float32 in STL
    pin = trimesh.load(out / "crank-rocker-pin.stl")
    assert pin.is_watertight and pin.volume > math.pi * 4 * 8
    assert report["layer_order"][0] == "ground"


def test_dead_centre_drawings_sit_where_the_kinematics_puts_them(built):
    import ezdxf

    from linkgen.kinematics.fourbar import FourBar

    out, report = built
    fb = FourBar(180, 80, 200, 150, 120, math.radians(30))
    msp = ezdxf.readfile(out / "crank-rocker-assembly.dxf").modelspace()
    dead = fb.dead_centres("open")
    assert report["assembly_layers"] == [f"DC{i + 1}-{d.kind}" for i, d in enumerate(dead)]
    for layer, d in zip(report["assembly_layers"], dead, strict=True):
        pose = fb.positions([d.crank])
        joints = [np.zeros(2), pose.a[0], pose.b[0], np.array([180.0, 0.0]), pose.point[0]]
        centres = [np.array(c.dxf.center)[:2] for c in msp.query(f'CIRCLE[layer=="{layer}"]')]
        for joint in joints:
            assert min(np.linalg.norm(c - joint) for c in centres) < 1e-9
        # crank and coupler in line at a dead centre
        a, b = pose.a[0], pose.b[0]
        d = b - a
        assert abs(a[0] * d[1] - a[1] * d[0]) < 1e-6 * np.linalg.norm(d) * np.linalg.norm(a)
    assert len(msp.query('LWPOLYLINE[layer=="PATH"]')) == 1


def test_parts_on_one_layer_never_meet_over_a_full_sweep():
    t = load_spec(TEMPLATE)
    b = design_linkage(t, parts=True).build
    from linkgen.kinematics.fourbar import FourBar
    from linkgen.mechanisms.fourbar import placement

    fb = FourBar(180, 80, 200, 150)
    place = placement(fb, np.linspace(0, 2 * math.pi, 721), "open")
    moving = [p for p in b.parts if p.moving]
    for p, q in itertools.combinations(moving, 2):
        if b.layers[p.name] != b.layers[q.name]:
            continue
        def at(part, k):
            return shapely.Polygon(part.outline().moved(place.angles[part.name][k],
                                             place.origins[part.name][k]).flatten(0.01))

        for k in range(721):
            assert not at(p, k).intersects(at(q, k)), (p.name, q.name, k)
    assert b.layers["crank"] != b.layers["coupler"] and b.layers["coupler"] != b.layers["rocker"]


def test_slider_crank_parts(tmp_path):
    path = tmp_path / "sc.toml"
    path.write_text('name = "sc"\n[linkage]\ntype = "slider-crank"\ncrank = 40.0\nrod = 150.0\noffset = 10.0\n'
                    "[parts]\nwidth = 12.0\nthickness = 4.0\npin_diameter = 4.0\n")
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "o")])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "o" / "sc.json").read_text())
    assert [p["name"] for p in report["parts"]] == ["ground", "crank", "rod", "slider"]
    assert {p["name"]: p.get("hole_distance_mm") for p in report["parts"]}["rod"] == pytest.approx(150.0)
    import ezdxf

    slot = [pl for pl in ezdxf.readfile(tmp_path / "o" / "sc-sheet.dxf").modelspace().query(
        'LWPOLYLINE[layer=="HOLES"]')]
    assert len(slot) == 1                                           # the slider's guide slot in the base plate


def test_parts_errors():
    runner = CliRunner()
    result = runner.invoke(main, ["build", str(TEMPLATE), "--set", "parts.pin_diameter=20"])
    assert result.exit_code == 2 and "parts.pin_diameter: holes of" in result.stderr
    result = runner.invoke(main, ["build", str(TEMPLATE), "--set", "parts.sheet=[100.0, 50.0]"])
    assert result.exit_code == 2 and "parts.sheet: the parts do not fit" in result.stderr
