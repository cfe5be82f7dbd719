"""Hub features: DIN 6885-1 keyways, mounting holes, engraving, and the printed boss with its set screw."""
from __future__ import annotations

import math

import numpy as np
import pytest

from camgen.api import design_cam
from camgen.core.errors import DesignError
from camgen.api import write_cam
from camgen.core.shapes import Contour
from camgen.core.features import key_for
from tests.conftest import template

BASE = {"cam.base_radius": 40.0, "output.formats": ["dxf", "stl"]}


def keyway_dims(contour: Contour) -> tuple[float, float, float]:
    """(width between the keyway's sides, height of its floor above the centre, radius of the bore's arc)."""
    v = contour.vertices
    width = v[:, 0].max() - v[:, 0].min()
    return width, v[:, 1].max(), float(contour.arcs()[2][0])


@pytest.mark.parametrize("bore, b, t2", [(10.0, 3.0, 1.4), (20.0, 6.0, 2.8), (40.0, 12.0, 3.3)])
def test_keyway_dimensions_for_three_bores_read_back_from_the_dxf(tmp_path, bore, b, t2):
    """DIN 6885-1: bores over 8 to 10 take a 3 mm key with a 1.4 mm hub keyseat; 17-22: 6 and 2.8; 38-44: 12, 3.3."""
    import ezdxf

    assert key_for(bore) == (b, t2)
    for kerf in (0.0, 0.2):
        out = tmp_path / f"k{kerf}"
        write_cam(design_cam(template({**BASE, "cam.base_radius": 60.0, "cam.bore": bore, "hub.keyway": True,
                                       "output.kerf": kerf})), out)
        holes = ezdxf.readfile(out / "rdrd.dxf").modelspace().query('LWPOLYLINE[layer=="HOLES"]')
        assert len(holes) == 1
        pts = np.array([(x, y, g) for x, y, _, _, g in holes[0].get_points("xyseb")])
        width, floor, radius = keyway_dims(Contour(pts[:, :2], pts[:, 2]))
        # kerf shrinks the hole: every edge moves into the hole by kerf / 2
        assert width == pytest.approx(b - kerf, abs=1e-12)
        assert floor == pytest.approx(bore / 2 + t2 - kerf / 2, abs=1e-12)
        assert radius == pytest.approx(bore / 2 - kerf / 2, abs=1e-12)


def test_bolt_holes_and_engraving(tmp_path):
    import ezdxf

    d = design_cam(template({**BASE, "cam.bore": 12.0, "hub.bolt_circle": 50.0, "hub.bolt_holes": 4,
                             "hub.bolt_hole_diameter": 4.0, "hub.engrave": True}))
    write_cam(d, tmp_path)
    msp = ezdxf.readfile(tmp_path / "rdrd.dxf").modelspace()
    circles = sorted((round(c.dxf.center[0], 9), round(c.dxf.center[1], 9), c.dxf.radius)
                     for c in msp.query('CIRCLE[layer=="HOLES"]'))
    assert circles == sorted([(0.0, 0.0, 6.0), (25.0, 0.0, 2.0), (0.0, 25.0, 2.0), (-25.0, 0.0, 2.0),
                              (0.0, -25.0, 2.0)])
    engraved = msp.query('*[layer=="ENGRAVE"]')
    assert [e.dxf.text for e in engraved.query("TEXT")] == ["rdrd"]
    assert len(engraved.query("LWPOLYLINE")) == 3
    assert all(not e.closed for e in engraved.query("LWPOLYLINE"))
    import trimesh

    mesh = trimesh.load(tmp_path / "rdrd.stl")                      # engraving is not cut, nor printed
    assert mesh.volume == pytest.approx(d.printed.area * 8.0, rel=1e-3)


def test_bolt_circle_outside_the_cam_is_refused():
    with pytest.raises(DesignError, match=r"hub\.bolt_circle: a hole reaches the cam's outline"):
        design_cam(template({**BASE, "cam.bore": 12.0, "hub.bolt_circle": 80.0, "hub.bolt_holes": 3,
                             "hub.bolt_hole_diameter": 4.0}))


def test_printed_boss_and_set_screw(tmp_path):
    import trimesh

    common = {**BASE, "cam.bore": 20.0, "hub.keyway": True, "hub.boss_diameter": 34.0, "hub.boss_height": 10.0}
    plain = design_cam(template(common))
    write_cam(plain, tmp_path / "plain")
    m0 = trimesh.load(tmp_path / "plain" / "rdrd.stl")
    ring = math.pi * 17.0**2 - abs(plain.printed.holes[0].area)
    assert m0.is_watertight and m0.volume == pytest.approx(plain.printed.area * 8.0 + ring * 10.0, rel=1e-3)
    assert m0.bounds[1][2] == pytest.approx(18.0)
    write_cam(design_cam(template({**common, "hub.set_screw": 4.0})), tmp_path / "screw")
    m1 = trimesh.load(tmp_path / "screw" / "rdrd.stl")
    assert m1.is_watertight and m1.is_winding_consistent
    removed = m0.volume - m1.volume
    # the screw runs over the keyway: through the boss wall from the keyseat floor (12.8) to the outside (17)
    area = math.pi * 2.0**2
    assert area * (17.0 - 12.8) * 0.9 < removed < area * (17.0 - 10.0) * 1.1
