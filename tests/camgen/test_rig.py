"""A cam's profile from domain objects alone: a Rig of plain segments and a plain follower table on a mount, a Body
and a Finish; no template, no pydantic model. It must equal the design the template gives through the spec (the
same outline, parts and checks within 1e-9 mm) and the bundled template's recorded report (tests/data/golden.json,
written before designs took domain objects), and its sizing the recorded size."""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from camgen.analysis import profile_rho_min
from camgen.core.parts import Allowances
from camgen.api import design_cam
from camgen.profile import Body, Finish, design_profile
from camgen.rig import Rig, disc_mount, plate_mount
from camgen.sizing import Limits, size_cam
from camgen.spec import load_spec
from tests.conftest import ROOT

GOLDEN = json.loads((ROOT / "tests" / "data" / "golden.json").read_text())
#: within what the recorded figures (rounded to 9 digits in the report) and the outlines are compared: mm, degrees
TOL = 1e-9


@dataclass(frozen=True)
class Segment:
    """A segment as the rig reads it: a plain record, not a template's table."""

    type: str
    angle: float
    lift: float | None = None
    law: str | None = None
    params: dict[str, Any] = field(default_factory=dict)
    ratio: float | None = None

    def law_params(self) -> dict[str, Any]:
        return dict(self.params)


def _follower(kind: str, roller: float | None = None, offset: float = 0.0) -> SimpleNamespace:
    """A ``[follower]`` table as a plain object with the attributes the follower types read."""
    return SimpleNamespace(type=kind, roller_radius=roller, offset=offset, contact_radius=roller or 0.0)


def _hub(**keys: Any) -> SimpleNamespace:
    hub = {"keyway": False, "boss_diameter": 0.0, "boss_height": 0.0, "set_screw": 0.0, "bolt_circle": 0.0,
           "bolt_holes": 0, "bolt_hole_diameter": 0.0, "engrave": False}
    return SimpleNamespace(**{**hub, **keys})


def _finish(tolerance: float = 0.01) -> Finish:
    return Finish(tolerance, "polylines", Allowances(kerf=0.0, clearance=0.0, kerf_field="output.kerf"), "lwpolyline")


RDRD = (Segment("rise", 120.0, 20.0, "cycloidal"), Segment("dwell", 60.0),
        Segment("return", 120.0, 20.0, "harmonic"), Segment("dwell", 60.0))
PLATE = (Segment("dwell", 30.0), Segment("rise", 120.0, 15.0, "cycloidal"), Segment("dwell", 60.0),
         Segment("return", 120.0, 15.0, "modified-sine"), Segment("dwell", 30.0))
FLAT = (Segment("rise", 150.0, 12.0, "modified-trapezoid"), Segment("dwell", 30.0),
        Segment("return", 150.0, 12.0, "polynomial-345"), Segment("dwell", 30.0))


def _recorded(template: str) -> dict[str, Any]:
    return GOLDEN[f"camgen build {template}.toml"][f"{template}.json"]


def _same_outline(a: Any, b: Any) -> None:
    """Two outlines alike within TOL mm: vertex for vertex, bulge for bulge."""
    assert a.contour.vertices.shape == b.contour.vertices.shape
    assert np.abs(a.contour.vertices - b.contour.vertices).max() <= TOL
    assert np.abs(a.contour.bulges - b.contour.bulges).max() <= TOL


def _same_as_recorded(profile: Any, recorded: dict[str, Any]) -> None:
    a = profile.analysis
    for key, value in (("pressure_angle_max_deg", a.pressure_angle_max_deg),
                       ("pressure_angle_max_at_deg", a.pressure_angle_max_at_deg),
                       ("pitch_rho_min_mm", a.pitch_rho_min_mm), ("profile_rho_min_mm", a.profile_rho_min_mm),
                       ("area_mm2", profile.part.area), ("outline_max_error_mm", profile.written_error_mm)):
        assert value == pytest.approx(recorded[key], rel=TOL, abs=TOL), key
    assert len(profile.cut_outline.contour.vertices) == recorded["outline_vertices"]
    assert profile.cut_outline.contour.n_arcs == recorded["outline_arcs"]
    assert list(profile.warnings) == recorded["warnings"]


@pytest.mark.parametrize("template", ["rdrd", "plate"])
def test_a_profile_from_a_rig_is_the_template_s_design(template):
    """rdrd (an offset translating roller, bored 10 mm) and plate (a roller over a 200 mm plate), each built from a
    rig of plain segments, against the template's design through its spec and against its recorded report."""
    if template == "rdrd":
        rig = Rig.of("rdrd", RDRD, disc_mount(_follower("translating-roller", 10.0, 5.0), "ccw"))
        body, base = Body("rdrd", 8.0, 10.0, _hub(), False), 40.0
    else:
        rig = Rig.of("plate", PLATE, plate_mount(_follower("translating-roller", 8.0), 200.0))
        body, base = Body("plate", 6.0, 0.0, _hub(), False), 20.0
    profile = design_profile(rig, base, body, _finish(), False, 30.0)
    design = design_cam(load_spec(ROOT / "templates" / f"{template}.toml"))
    for mine, theirs in ((profile.outline, design.outline), (profile.cut_outline, design.cut_outline)):
        _same_outline(mine, theirs)
    for name in ("pressure_angle_max_deg", "pressure_angle_max_at_deg", "pitch_rho_min_mm", "pitch_rho_min_at_deg",
                 "profile_rho_min_mm"):
        assert getattr(profile.analysis, name) == pytest.approx(getattr(design.analysis, name), rel=TOL, abs=TOL)
    assert profile.jumps == design.jumps and profile.warnings == design.warnings
    assert len(profile.printed.holes) == len(design.printed.holes) == (1 if template == "rdrd" else 0)
    for mine, theirs in zip(profile.printed.holes, design.printed.holes, strict=True):
        assert np.abs(mine.flatten(0.01) - theirs.flatten(0.01)).max() <= TOL
    _same_as_recorded(profile, _recorded(template))


def test_a_rig_sized_and_profiled_is_the_auto_template_s_design():
    """flat-face.toml sizes a translating flat face by its curvature margin (25 mm): the rig's sizing finds the
    recorded size, and the profile there the recorded checks; the base radius so found keeps rho >= 25 mm, 1e-6
    less does not."""
    rig = Rig.of("flat-face", FLAT, disc_mount(_follower("translating-flat"), "ccw"))
    sizing = size_cam(rig, Limits(30.0, 25.0))
    recorded = _recorded("flat-face")
    assert sizing.decided_by == recorded["sizing"]["decided_by"] == "curvature"
    assert sizing.base_radius_mm == pytest.approx(recorded["sizing"]["base_radius_mm"], rel=TOL, abs=TOL)
    profile = design_profile(rig, sizing.base_radius_mm, Body("flat-face", 6.0, 8.0, _hub(), False), _finish(), False,
                             30.0)
    _same_as_recorded(profile, recorded)
    assert profile.wall_mm == pytest.approx(recorded["wall_mm"], abs=1e-6)        # recorded to 6 digits
    assert profile.face_extent is not None
    assert profile_rho_min(rig.cam(sizing.base_radius_mm)) > 25.0                 # the least size that keeps it
    assert profile_rho_min(rig.cam(sizing.base_radius_mm * (1 - 1e-6))) < 25.0


def test_the_drafted_law_spreads_its_arcs_over_the_mount_s_prime_circle():
    """The drafted modified-uniform law's k = Rp beta / h comes from the mount: base + roller on a disc; the rig
    builds the same law as make_law with that k, and a rig whose prime radius is not known refuses it naming the
    segment's form."""
    from camgen.core.errors import SpecError
    from camgen.laws import make_law

    seg = Segment("rise", 90.0, 10.0, "modified-uniform", {"form": "drafted"})
    motion = (seg, Segment("dwell", 90.0), Segment("return", 90.0, 10.0, "cycloidal"), Segment("dwell", 90.0))
    rig = Rig.of("d", motion, disc_mount(_follower("translating-roller", 5.0), "ccw"))
    law = rig.cam(30.0).program.segments[0].law
    expected = make_law("modified-uniform", form="drafted", k=35.0 * math.radians(90.0) / 10.0)
    u = np.linspace(0.0, 1.0, 11)
    assert np.abs(law.derivatives(u) - expected.derivatives(u)).max() < 1e-12
    with pytest.raises(SpecError, match=r"^motion\[0\]\.form: the drafted form needs the cam's prime radius"):
        rig.program(None)
