"""The machine's assembly (issue 35 item 4): a 3MF with every part placed at machine.assembly_angle, the bought
parts one object of their own, and a STEP file of every part as a solid in its place. Each 3MF object's bounds are
the part's outline placed at that angle (a cam's worked here: its outline turned by its program angle about its
shaft) extruded on its plane's height; PrusaSlicer reads every object closed; FreeCAD reads the STEP file's solids,
one a part, of the parts' exact volumes."""
from __future__ import annotations

import json
import math
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from tests.support.refusals import assert_refused
from tests.camgen.kinds.machine.test_machine import AUTOMATON, _design, _raw

#: one worker for the module, so that its module-scoped designs are made once a run
pytestmark = pytest.mark.xdist_group("machine-machine-assembly")

ANGLE = 75.0
CORE = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("assembly")
    result = CliRunner().invoke(camgen, ["build", str(AUTOMATON), "-o", str(out), "--set",
                                         f"machine.assembly_angle={ANGLE}", "--set",
                                         'output.formats=["3mf", "json", "step"]'])
    assert result.exit_code == 0, result.output
    return out, json.loads((out / "automaton.json").read_text())


@pytest.fixture(scope="module")
def automaton():
    raw = _raw()
    raw["machine"]["assembly_angle"] = ANGLE
    return _design(raw)


def _objects(path: Path) -> dict[str, np.ndarray]:
    """Each object of a 3MF by its name: its vertices (n, 3) mm."""
    with zipfile.ZipFile(path) as package:
        root = ET.fromstring(package.read("3D/3dmodel.model"))
    out = {}
    for obj in root.iter(f"{CORE}object"):
        out[obj.get("name")] = np.array([[float(v.get(k)) for k in "xyz"] for v in obj.iter(f"{CORE}vertex")])
    return out


def _box(vertices: np.ndarray) -> list[float]:
    return [*vertices.min(axis=0), *vertices.max(axis=0)]


def _single(values) -> list[float]:
    """``values`` as a mesh file holds them: rounded to single precision (a 3MF's vertices, as every mesh of the
    project, are float32: 7.6e-6 mm apart near 100 mm), so that a comparison to 1e-6 mm is the rounding's own."""
    return [float(v) for v in np.asarray(values, dtype=np.float32)]


def test_each_cam_in_the_3mf_is_its_outline_turned_to_the_assembly_angle(built, automaton):
    out, report = built
    objects = _objects(out / "automaton-assembly.3mf")
    planes = report["frame"]["planes"]
    for cam, mount in zip(automaton.cams, automaton.spec.cams, strict=True):
        design = cam.design
        theta = cam.turns * math.radians(ANGLE) - math.radians(mount.phase)     # its program angle
        turn = design.cam.follower.sense * theta                               # in its sense of rotation
        c, s = math.cos(turn), math.sin(turn)
        outline = design.part.outline.flatten(design.tolerance) @ np.array([[c, s], [-s, c]])
        bottom = planes[2 * mount.layer]["bottom_mm"]
        want = [*outline.min(axis=0), bottom, *outline.max(axis=0), bottom + design.part.thickness]
        assert _box(objects[f"cams.{cam.name}"]) == pytest.approx(_single(want), abs=1e-6), cam.name


def test_every_object_is_its_placed_outline_extruded_on_its_layer(built):
    out, report = built
    objects = _objects(out / "automaton-assembly.3mf")
    pieces = report["assembly"]["pieces"]
    made = [p for p in pieces if not p["bought"]]
    bought = [p for p in pieces if p["bought"]]
    assert set(objects) == {p["name"] for p in made} | {"bought parts (not printed)"}
    for p in made:
        x0, y0, x1, y1 = p["bounds_mm"]
        want = [x0, y0, p["z_mm"], x1, y1, p["z_mm"] + p["thickness_mm"]]
        # the plates' outlines have exact arcs (their bounds the arcs'), which their meshes carry as chords within
        # the tolerance; every other outline is the clash check's polygon, its bounds its vertices'
        tol = report["tolerance_mm"] if p["name"].startswith("frame") else 1e-6
        assert _box(objects[p["name"]]) == pytest.approx(_single(want), abs=tol), p["name"]
    # the bought parts: the shaft, the two pivot pins, the three rollers' axles, together in one object
    assert {p["name"] for p in bought} == {"shafts.camshaft", "pins.0", "pins.1",
                                           *(f"cams.{c}.axle" for c in ("head", "jaw", "arm"))}
    boxes = np.array([[*p["bounds_mm"][:2], p["z_mm"], *p["bounds_mm"][2:], p["z_mm"] + p["thickness_mm"]]
                      for p in bought])
    want = [*boxes[:, :3].min(axis=0), *boxes[:, 3:].max(axis=0)]
    assert _box(objects["bought parts (not printed)"]) == pytest.approx(_single(want), abs=1e-6)


def test_the_pins_and_plates_stand_where_the_frame_puts_them(built):
    _, report = built
    frame = report["frame"]
    pieces = {p["name"]: p for p in report["assembly"]["pieces"]}
    top = frame["top_plate_mm"]
    assert pieces["frame"]["z_mm"] == 0.0 and pieces["frame-top"]["z_mm"] == pytest.approx(top, abs=1e-9)
    seats = {s["name"]: s for s in frame["seats"]}
    for pin in ("pins.0", "pins.1"):
        x0, y0, x1, y1 = pieces[pin]["bounds_mm"]
        assert ((x0 + x1) / 2, (y0 + y1) / 2) == pytest.approx((seats[pin]["x_mm"], seats[pin]["y_mm"]), abs=1e-9)
        # every pin reaches through the top plate: one hangs from it, the other stands in the spacer
        assert pieces[pin]["z_mm"] + pieces[pin]["thickness_mm"] == pytest.approx(top + frame["thickness_mm"])


def test_prusaslicer_reads_the_assembly_each_object_closed(built):
    out, report = built
    program = shutil.which("prusa-slicer")
    if program is None:
        pytest.skip("prusa-slicer is not installed (Debian package; .ci/run installs it)")
    info = subprocess.run([program, "--info", str(out / "automaton-assembly.3mf")], capture_output=True, text=True,
                          timeout=300).stdout
    made = [p for p in report["assembly"]["pieces"] if not p["bought"]]
    assert info.count("manifold = yes") == len(made) + 1 and "manifold = no" not in info
    parts = [int(n) for n in re.findall(r"^number_of_parts =\s+(\d+)$", info, re.M)]
    assert parts == [1] * len(made) + [6]                    # the bought object: six closed shells


def test_freecad_reads_the_step_file_one_solid_a_part(built, automaton):
    from camgen.kinds.machine.assembly import pieces
    from tests.support.freecad import freecad_check

    out, _ = built
    done = freecad_check("step", out / "automaton-assembly.step", [])
    found = json.loads(done.stdout.strip().splitlines()[-1])["solids"]
    want = pieces(automaton)
    assert len(found) == len(want) == 20                     # 14 made, 6 bought
    for solid, piece in zip(found, want, strict=True):
        assert solid["valid"], piece.part.name
        assert solid["volume"] == pytest.approx(piece.part.area * piece.part.thickness, rel=5e-3), piece.part.name
        assert solid["box"][2] == pytest.approx(piece.z, abs=1e-6), piece.part.name


def test_the_assembly_angle_is_bounded(tmp_path):
    assert_refused(AUTOMATON, {"machine.assembly_angle": 360.0}, "machine.assembly_angle: ", tmp_path)
