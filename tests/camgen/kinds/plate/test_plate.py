"""The linear (plate) cam: profile, report, DXF and STL."""
from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.api import design_cam
from camgen.core.errors import SpecError
from camgen.surface import surface_deviation
from camgen.spec import validate_spec

PLATE = {
    "name": "plate",
    "cam": {"kind": "plate", "travel": 200.0, "base_radius": 20.0, "thickness": 6.0},
    "follower": {"type": "translating-roller", "roller_radius": 8.0},
    "motion": [{"type": "dwell", "angle": 30.0},
               {"type": "rise", "law": "cycloidal", "lift": 15.0, "angle": 120.0},
               {"type": "dwell", "angle": 60.0},
               {"type": "return", "law": "modified-sine", "lift": 15.0, "angle": 120.0},
               {"type": "dwell", "angle": 30.0}],
}


def test_plate_profile_pressure_angle_and_accuracy():
    d = design_cam(validate_spec(PLATE))
    # textbook: tan(phi) = ds/dx; mid-rise of a cycloidal s' = 2h/beta per radian, dx/dtheta = travel / 2 pi
    beta = math.radians(120)
    mid = d.cam.pitch(np.array([math.radians(90)]))
    assert math.tan(mid.pressure_angle[0]) == pytest.approx((2 * 15 / beta) / (200 / (2 * math.pi)), rel=1e-12)
    assert d.analysis.pressure_angle_max_deg == pytest.approx(math.degrees(mid.pressure_angle[0]), abs=1e-6)
    # the profile: within tolerance of the roller's envelope where the roller runs (0 <= x <= travel)
    pts = d.outline.contour.flatten(1e-4)
    top = pts[(pts[:, 0] >= 0) & (pts[:, 0] <= 200) & (pts[:, 1] > 1e-9)]
    assert np.abs(surface_deviation(d.cam, top)).max() <= 0.01
    # flat dwells at the base height, bottom edge on y = 0, ends one roller radius beyond the travel
    assert pts[:, 1].min() == 0.0 and pts[:, 0].min() == pytest.approx(-8.0) and pts[:, 0].max() == pytest.approx(208.0)
    # across the top dwell (150 to 210 degrees: x = 83.3 to 116.7 mm) the plate is flat at base + lift = 35 mm
    dwell = d.outline.contour.vertices
    dwell = dwell[(dwell[:, 0] > 84) & (dwell[:, 0] < 116)]
    assert len(dwell) == 0 or np.abs(dwell[:, 1] - 35.0).max() < 1e-12
    edge = d.cam.pitch(np.radians([150.0, 209.0])).point - 8.0 * d.cam.pitch(np.radians([150.0, 209.0])).normal
    assert edge[:, 1] == pytest.approx([35.0, 35.0], abs=1e-12)


def test_plate_files(tmp_path):
    import ezdxf
    import trimesh

    path = tmp_path / "plate.toml"
    lines = ['name = "plate"', "[cam]", 'kind = "plate"', "travel = 200.0", "base_radius = 20.0", "thickness = 6.0",
             "[follower]", 'type = "translating-roller"', "roller_radius = 8.0"]
    for seg in PLATE["motion"]:
        lines += ["[[motion]]"] + [f"{k} = {v!r}".replace("'", '"') for k, v in seg.items()]
    path.write_text("\n".join(lines) + "\n")
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    doc = ezdxf.readfile(tmp_path / "out" / "plate.dxf")
    assert not doc.audit().has_errors
    mesh = trimesh.load(tmp_path / "out" / "plate.stl")
    assert mesh.is_watertight and mesh.volume == pytest.approx(design_cam(validate_spec(PLATE)).part.area * 6,
                                                               rel=1e-3)


@pytest.mark.parametrize("change, message", [
    ({"travel": None}, "cam.travel: missing: give the distance the plate slides over the program's 360 degrees in mm"),
    ({"bore": 5.0}, 'cam.bore: not a key of a plate cam \\(a key of cam.kind = "disc", "grooved", "barrel" or '
                    '"conjugate"\\); it takes: base_radius, thickness'),
])
def test_plate_errors(change, message):
    import copy

    raw = copy.deepcopy(PLATE)
    for k, v in change.items():
        if v is None:
            raw["cam"].pop(k)
        else:
            raw["cam"][k] = v
    with pytest.raises(SpecError, match=message):
        validate_spec(raw)


def test_plate_refuses_other_followers():
    import copy

    raw = copy.deepcopy(PLATE)
    raw["follower"] = {"type": "translating-flat"}
    with pytest.raises(SpecError, match=r"^follower\.type: a plate cam takes translating-roller or knife-edge "
                                        r"\(got 'translating-flat'\)$"):
        validate_spec(raw)
