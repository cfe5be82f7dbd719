"""Every bad input refused in one line, every result right or refused (issue 19's regressions, one a case)."""
from __future__ import annotations

import json
import re
import zipfile
import xml.etree.ElementTree as ET

import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from tests.conftest import ROOT

RDRD = ROOT / "templates" / "rdrd.toml"
PLATE = ROOT / "templates" / "plate.toml"


def refused(args: list[str], out, words: str, program=camgen) -> None:
    """The command exits 2 with one line naming ``words`` and writes nothing at ``out``."""
    result = CliRunner().invoke(program, args)
    assert result.exit_code == 2, (result.exit_code, result.output, result.exception)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert words in lines[0], lines[0]
    assert out is None or not out.exists()


@pytest.mark.parametrize("sets, words", [
    (["cam.bore=3", "output.kerf=5"], "output.kerf: a kerf of 5 mm closes a hole"),
    (["hub.bolt_holes=36", "hub.bolt_circle=30", "hub.bolt_hole_diameter=5"],
     "hub.bolt_circle: two bolt holes overlap"),
    (["hub.bolt_holes=4", "hub.bolt_circle=14", "hub.bolt_hole_diameter=5"],
     "hub.bolt_circle: a bolt hole cuts into the bore"),
    (["motion.0.lift=true"], "motion[0].lift: must be a number, not true or false"),
    (["cam.thickness=true"], "cam.thickness: must be a number, not true or false"),
    (["hub.keyway=1"], "hub.keyway: must be true or false (got 1)"),            # pydantic would read 1 as true
    (["output.figures='yes'"], "output.figures: must be true or false (got 'yes')"),
    (["output.figures=0"], "output.figures: must be true or false (got 0)"),
    (["motion.0.law='parabolic'", "motion.0.ratio=1e10"], "motion[0].ratio: must be >= 0.01 and <= 100"),
    (["motion.0.law='parabolic'", "motion.0.ratio=1e-17"], "motion[0].ratio: must be >= 0.01 and <= 100"),
    (["cam.base_radius=1e9"], "cam.base_radius: must be > 0 and <= 10000 mm"),
    (["cam.base_radius=1e300"], "cam.base_radius: must be > 0 and <= 10000 mm"),
    (["cam.rpm=1e300"], "cam.rpm: must be > 0 and <= 100000 rpm"),
    (["motion.0.lift=1e300", "motion.2.lift=1e300"], "motion[0].lift: must be > 0 and <= 10000"),
    (["cam.thickness=1e300"], "cam.thickness: must be > 0 and <= 1000 mm"),
    (["cam.max_pressure_angle=1e-9"], "cam.max_pressure_angle: must be >= 1 and < 90 degrees"),
    (["motion.0.conditions=" + "[" * 60 + "]" * 60], "--set motion.0.conditions: the value nests"),
])
def test_bad_values_are_refused_before_anything_is_written(tmp_path, sets, words):
    out = tmp_path / "out" / "deeper"
    args = ["build", str(RDRD), "-o", str(out)]
    for s in sets:
        args += ["--set", s]
    refused(args, tmp_path / "out", words)


def test_a_plate_cam_travel_is_bounded(tmp_path):
    refused(["build", str(PLATE), "-o", str(tmp_path / "o"), "--set", "cam.travel=1e9"], tmp_path / "o",
            "cam.travel: must be > 0 and <= 10000 mm")


@pytest.mark.parametrize("text, words", [
    (None, "/dev/zero is a character device, not a regular file"),     # never read, so never read for ever
    (b"#" * 1_000_001, "is larger than 1000 kB"),
    (b"\xff\xfe\x00\x01binary", "is not a text file"),
    ("a = " + "[" * 5000 + "]" * 5000, "nests arrays or tables more than 32 deep"),
    ('base = 5\nname = "x"', "base: must be the file name of a template"),
    ('base = ["rdrd.toml"]\nname = "x"', "base: must be the file name of a template"),
    ('base = "."\nname = "x"', "is a folder, not a template file"),
    ('base = "missing.toml"\nname = "x"', "base: no such file"),
])
def test_bad_template_files_are_one_line(tmp_path, text, words):
    if text is None:
        path = "/dev/zero"
    else:
        path = tmp_path / "t.toml"
        path.write_bytes(text if isinstance(text, bytes) else text.encode())
    refused(["build", str(path), "-o", str(tmp_path / "o")], tmp_path / "o", words)


def test_a_byte_order_mark_is_read_as_utf8(tmp_path):
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + RDRD.read_bytes())
    result = CliRunner().invoke(camgen, ["build", str(path), "-o", str(tmp_path / "o"), "--set",
                                         "output.formats=['json']"])
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize("args, words", [
    (["build"], "Missing argument 'TEMPLATE'"),
    (["build", "/no/such.toml"], "'TEMPLATE': File '/no/such.toml' does not exist"),
    (["family", str(RDRD), "-o", "x", "--jobs", "0"], "'--jobs': 0 is not in the range"),
    (["frobnicate"], "No such command 'frobnicate'"),
])
def test_usage_errors_are_one_line(args, words):
    refused(args, None, words)


def test_an_output_folder_that_cannot_be_made_is_one_line(tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("")
    refused(["build", str(RDRD), "-o", str(afile / "sub")], afile / "sub", "cannot create output folder")
    refused(["family", str(ROOT / "templates" / "automaton-cams.toml"), "-o", str(afile / "sub")], afile / "sub",
            "Not a directory")


def test_a_centred_knife_edge_sizes_itself(tmp_path):
    path = tmp_path / "knife.toml"
    path.write_text(RDRD.read_text().replace('type = "translating-roller"', 'type = "knife-edge"')
                    .replace("roller_radius = 10.0", "").replace("offset = 5.0", "")
                    .replace("base_radius = 40.0", 'base_radius = "auto"').replace("bore = 10.0", ""))
    result = CliRunner().invoke(camgen, ["build", str(path), "-o", str(tmp_path / "o"), "--set",
                                         "output.formats=['json']"])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "o" / "rdrd.json").read_text())
    assert report["sizing"]["decided_by"] == "pressure angle"
    assert report["pressure_angle_max_deg"] == pytest.approx(30.0, abs=1e-6)
    assert result.stderr == ""                                          # no numpy warnings either


def test_the_documented_set_example_builds(tmp_path):
    reference = (ROOT / "docs" / "reference" / "cli.md").read_text()
    example = re.search(r"list items by index: `(--set [^`]+)`", reference).group(1).split()
    result = CliRunner().invoke(camgen, ["build", str(RDRD), "-o", str(tmp_path), *example])
    assert result.exit_code == 0, result.output


def test_dxf_and_svg_give_every_layer_the_same_colour(tmp_path):
    import ezdxf
    from ezdxf.colors import aci2rgb

    result = CliRunner().invoke(camgen, ["build", str(RDRD), "-o", str(tmp_path), "--set", "hub.engrave=true",
                                         "--set", "output.formats=['dxf','cut-svg','3mf']"])
    assert result.exit_code == 0, result.output
    dxf = {layer.dxf.name: "#%02x%02x%02x" % tuple(aci2rgb(layer.color))
           for layer in ezdxf.readfile(tmp_path / "rdrd.dxf").layers if layer.dxf.name in ("OUTLINE", "HOLES",
                                                                                          "ENGRAVE")}
    svg = {g.get("id"): g.get("stroke") for g in ET.parse(tmp_path / "rdrd-cut.svg").getroot()
           if g.tag.endswith("g")}
    assert set(dxf) == {"OUTLINE", "HOLES", "ENGRAVE"}
    assert dxf == {k: svg[k] for k in dxf}
    model = zipfile.ZipFile(tmp_path / "rdrd.3mf").read("3D/3dmodel.model").decode()
    assert re.findall(r'<object [^>]*name="([^"]+)"', model) == ["rdrd"]


def _knife_uniform(tmp_path):
    path = tmp_path / "knife.toml"
    path.write_text(RDRD.read_text().replace('type = "translating-roller"', 'type = "knife-edge"')
                    .replace("roller_radius = 10.0", "").replace('law = "cycloidal"', 'law = "uniform"'))
    return path


def test_a_knife_edge_at_a_velocity_jump_is_refused_by_name(tmp_path):
    refused(["build", str(_knife_uniform(tmp_path)), "-o", str(tmp_path / "o")], tmp_path / "o",
            "motion[0]: the follower velocity jumps at 120 degrees, a sharp corner")


@pytest.mark.parametrize("kerf", [0.0, 0.3])
def test_a_knife_edge_corner_allowed_is_cut_as_its_exact_envelope(tmp_path, kerf):
    """The knife's profile keeps its corners; half a kerf outside it, the offset rounds the convex corner and
    trims the concave one. Checked against the exact surface and for self-intersection."""
    import shapely

    from camgen.api import design_cam
    from camgen.spec import load_spec
    from camgen.surface import surface_deviation

    d = design_cam(load_spec(_knife_uniform(tmp_path), ["cam.allow_undercut=true", f"output.kerf={kerf}"]))
    pts = d.cut_outline.contour.flatten(1e-4)
    assert shapely.Polygon(pts).is_valid
    assert abs(surface_deviation(d.cam, pts, kerf / 2)).max() <= d.tolerance
    assert d.cut_outline.max_error_mm <= d.tolerance
    assert "envelope" in " ".join(d.warnings) or d.cut_outline.envelope


def test_a_plate_cam_takes_no_sense_of_rotation(tmp_path):
    refused(["build", str(PLATE), "-o", str(tmp_path / "o"), "--set", "cam.rotation='cw'"], tmp_path / "o",
            'cam.rotation: not a key of a plate cam (a key of cam.kind = "disc", "grooved", "barrel" or "conjugate"); '
            "it takes: base_radius, thickness, ")


FLAT = ROOT / "templates" / "flat-face.toml"


@pytest.mark.parametrize("follower", [[], ["follower.type='oscillating-flat'", "follower.pivot_distance=150",
                                           "motion.0.lift=8", "motion.2.lift=8"]])
def test_a_flat_face_where_the_velocity_drops_is_refused_as_a_cusp(tmp_path, follower):
    args = ["build", str(FLAT), "-o", str(tmp_path / "o"), "--set", "cam.base_radius=60",
            "--set", "motion.0.law='uniform'"]
    for s in follower:
        args += ["--set", s]
    refused(args, tmp_path / "o", "cusp at 150 degrees: the follower velocity drops there")


def test_a_flat_face_where_the_velocity_rises_gets_its_straight_flat(tmp_path):
    """A rise leaving a dwell at speed: the face lies along the profile from one contact to the next. The outline
    is measured against the exact envelope (contact curve and flats) by the independent measure."""
    from camgen.convergence_study import contour_error
    from camgen.api import design_cam
    from camgen.spec import validate_spec

    raw = {"name": "flatspot", "cam": {"base_radius": 60.0, "thickness": 6.0},
           "follower": {"type": "translating-flat"},
           "motion": [{"type": "dwell", "angle": 60.0},
                      {"type": "rise", "law": "polynomial", "lift": 12.0, "angle": 150.0,
                       "conditions": [[0, 0, 0], [0, 1, 0.6], [1, 0, 1], [1, 1, 0], [1, 2, 0]]},
                      {"type": "return", "law": "cycloidal", "lift": 12.0, "angle": 150.0}]}
    d = design_cam(validate_spec(raw))
    (index, step), = d.cam.steps()
    # the contact jumps along the face by s' = 0.6 h / beta (mm per radian), here 2.75 mm
    assert index == 0 and step == pytest.approx(0.6 * 12.0 / (150 * 3.141592653589793 / 180), rel=1e-9)
    assert contour_error(d.cam, d.outline.contour, d.tolerance) <= d.tolerance


def test_the_segments_flavour_reports_the_error_of_the_lines_it_writes(tmp_path):
    """Read back from the DXF and measured against the exact surface, the lines stay within the tolerance and
    within the reported figure (biarcs make no sense as chords: the segments flavour gets measured chords)."""
    import ezdxf
    import numpy as np

    from camgen.flat import build_cam
    from camgen.spec import load_spec
    from camgen.surface import surface_deviation

    result = CliRunner().invoke(camgen, ["build", str(RDRD), "-o", str(tmp_path), "--set", "output.dxf='segments'",
                                         "--set", "output.curves='biarcs'", "--set", "output.formats=['dxf','json']"])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "rdrd.json").read_text())
    lines = [(np.array(e.dxf.start)[:2], np.array(e.dxf.end)[:2]) for e in ezdxf.readfile(tmp_path / "rdrd.dxf")
             .modelspace() if e.dxftype() == "LINE" and e.dxf.layer == "OUTLINE"]
    pts = np.concatenate([a + (b - a) * np.linspace(0, 1, 17)[:, None] for a, b in lines])
    measured = abs(surface_deviation(build_cam(load_spec(RDRD)), pts)).max()
    assert measured <= report["outline_max_error_mm"] * (1 + 1e-9) <= report["tolerance_mm"]


@pytest.mark.parametrize("curves", ["polylines", "biarcs"])
def test_the_reported_outline_error_bounds_the_true_one(curves):
    """Over cams of every standard law, roller and tolerance, the reported error is never below the error
    measured independently (dense points on every piece, projected onto the exact pitch curve)."""
    import random

    from camgen.convergence_study import contour_error
    from camgen.core.spec import apply_overrides
    from camgen.api import design_cam
    from camgen.spec import validate_spec
    from tests.conftest import RDRD as RAW

    rng = random.Random(7)
    laws = ["cycloidal", "harmonic", "polynomial-345", "polynomial-4567", "modified-sine", "modified-trapezoid"]
    for _ in range(12):
        tol, lift = 10 ** rng.uniform(-4, -1), rng.uniform(5, 25)
        spec = validate_spec(apply_overrides(RAW, [
            ("motion.0.law", rng.choice(laws)), ("motion.2.law", rng.choice(laws)), ("output.curves", curves),
            ("output.tolerance", tol), ("follower.roller_radius", rng.uniform(2, 9)), ("motion.0.lift", lift),
            ("motion.2.lift", lift)]))
        d = design_cam(spec)
        true = contour_error(d.cam, d.outline.contour, tol)
        assert true <= d.outline.max_error_mm * (1 + 1e-9) <= tol


@pytest.mark.parametrize("m, p", [(20, 5), (2, 18), (20, 6), (13, 13), (1, 25)])
def test_two_point_conditions_always_fix_their_polynomial(m, p):
    """Orders 0..m-1 at u = 0 and 0..p-1 at u = 1 have exactly one polynomial of degree m + p - 1: with f = 0 and
    its derivatives zero at 0, f = 1 and the rest zero at 1 it is u^m sum_k C(m - 1 + k, k) (1 - u)^k."""
    import math

    import numpy as np

    from camgen.laws import from_conditions

    conds = [(0, k, 0) for k in range(m)] + [(1, 0, 1)] + [(1, k, 0) for k in range(1, p)]
    law = from_conditions(conds)
    u = np.linspace(0, 1, 2001)
    exact = u**m * sum(math.comb(m - 1 + k, k) * (1 - u) ** k for k in range(p))
    assert law.degree == m + p - 1
    assert np.abs(law.derivatives(u)[0] - exact).max() < 1e-12


def test_two_point_conditions_with_slopes_are_met():
    import numpy as np

    from camgen.laws import from_conditions

    conds = [(0, 0, 0), (0, 1, 0.6), (0, 2, -1.5), (1, 0, 1), (1, 1, 0.25), (1, 2, 0), (1, 3, 2)]
    law = from_conditions(conds)
    d = law.derivatives(np.array([0.0, 1.0]))
    for u, k, v in conds:
        assert d[k][int(u)] == pytest.approx(v, abs=1e-11)


@pytest.mark.parametrize("template, sets", [(RDRD, []), (RDRD, ["cam.rotation='cw'"]), (PLATE, []),
                                            (RDRD, ["hub.bolt_holes=4", "hub.bolt_circle=30",
                                                    "hub.bolt_hole_diameter=4", "name='a-much-longer-cam-name'"])])
def test_engraved_marks_lie_on_the_part_clear_of_each_other(template, sets):
    """Read from the design as a laser would get them: the name's box, the arrow and the tick lie inside the
    part, off the holes, and apart."""
    import shapely

    from camgen.core.spec import read_template
    from camgen.api import design_cam
    from camgen.spec import validate_spec

    d = design_cam(validate_spec(read_template(template, ["hub.engrave=true", *sets])))
    part = shapely.Polygon(d.cut.outline.flatten(0.01), [h.flatten(0.01) for h in d.cut.holes])
    marks = [m for _, m in d.cut.marks]
    name = marks[0]
    box = shapely.box(name.position[0], name.position[1], name.position[0] + 0.6 * name.height * len(name.text),
                      name.position[1] + name.height)
    arrow = shapely.MultiLineString([m.flatten(0.01) for m in marks[1:3]])
    tick = shapely.LineString(marks[3].flatten(0.01))
    assert all(part.contains(g) for g in (box, arrow, tick))
    assert not box.intersects(arrow) and not box.intersects(tick) and not arrow.intersects(tick)
    assert min(shapely.LineString(m.flatten(0.01)).length for m in marks[1:]) > 1.0    # no dot fired in one place


def test_marks_that_cannot_fit_are_refused(tmp_path):
    refused(["build", str(RDRD), "-o", str(tmp_path / "o"), "--set", "hub.engrave=true", "--set", "cam.bore=57",
             "--set", "cam.base_radius=30"], tmp_path / "o", "hub.engrave: the name, the arrow and the theta = 0 tick")


@pytest.mark.parametrize("program, command, template, words", [
    ("camgen", "build", "automaton-cams.toml", "template: this is a family template (it has a [sweep] table): "
                                               "build it with `camgen family`"),
    ("camgen", "build", "crank-rocker.toml", "template: this is a linkgen template"),
    ("linkgen", "analyze", "rdrd.toml", "template: this is a camgen template: use `camgen build`"),
    ("linkgen", "build", "crank-rockers.toml", "build it with `linkgen family`"),
])
def test_a_template_for_another_command_says_which(tmp_path, program, command, template, words):
    from linkgen.cli import main as linkgen

    refused([command, str(ROOT / "templates" / template), "-o", str(tmp_path / "o")], tmp_path / "o", words,
            {"camgen": camgen, "linkgen": linkgen}[program])


def test_a_misspelt_required_key_is_named_with_its_likely_spelling(tmp_path):
    path = tmp_path / "typo.toml"
    path.write_text(RDRD.read_text().replace("base_radius", "base_radus"))
    refused(["build", str(path), "-o", str(tmp_path / "o")], tmp_path / "o",
            "cam.base_radus: not a key of a disc cam (did you mean 'base_radius'?); it takes: base_radius, ")


def test_a_list_given_as_a_word_says_list(tmp_path):
    refused(["build", str(RDRD), "-o", str(tmp_path / "o"), "--set", "output.formats=dxf"], tmp_path / "o",
            "output.formats: must be a list")


def _closed_shapes(path):
    """Every closed cut entity of a DXF (outlines and holes) as a shapely polygon, read back with ezdxf."""
    import ezdxf
    import numpy as np
    import shapely
    from ezdxf import path as dxfpath

    shapes = []
    for e in ezdxf.readfile(path).modelspace():
        if e.dxf.layer in ("OUTLINE", "HOLES") and e.dxftype() in ("LWPOLYLINE", "CIRCLE", "POLYLINE"):
            pts = np.array([(v.x, v.y) for v in dxfpath.make_path(e).flattening(0.001)])
            shapes.append((e.dxftype(), shapely.Polygon(pts)))
    return shapes


@pytest.mark.parametrize("template, program, sets", [
    ("rdrd.toml", "camgen", ["hub.bolt_holes=4", "hub.bolt_circle=30", "hub.bolt_hole_diameter=4"]),
    ("oscillating.toml", "camgen", []), ("flat-face.toml", "camgen", []), ("plate.toml", "camgen", []),
    ("crank-rocker.toml", "linkgen", []),
    ("slider-crank.toml", "linkgen", ["parts.width=12", "parts.thickness=4", "parts.pin_diameter=4"]),
    ("hoekens.toml", "linkgen", ["parts.width=10", "parts.thickness=3", "parts.pin_diameter=3"]),
])
def test_cut_files_hold_no_duplicate_or_crossing_entities(tmp_path, template, program, sets):
    """Read back as a laser program would: no two cut contours touch or cross, so nothing is cut twice (the
    slider-crank's slot used to come with a hole at each end, cut over its caps)."""
    from linkgen.cli import main as linkgen

    args = ["build", str(ROOT / "templates" / template), "-o", str(tmp_path), "--set", "output.formats=['dxf']"]
    for s in sets:
        args += ["--set", s]
    result = CliRunner().invoke({"camgen": camgen, "linkgen": linkgen}[program], args)
    assert result.exit_code == 0, result.output
    dxfs = [p for p in tmp_path.glob("*.dxf") if "assembly" not in p.name]
    assert dxfs
    for dxf in dxfs:
        shapes = _closed_shapes(dxf)
        assert shapes and all(s.is_valid and s.area > 0 for _, s in shapes)
        for i, (_, a) in enumerate(shapes):
            for _, b in shapes[i + 1:]:
                assert not a.boundary.intersects(b.boundary), dxf.name


# Found by the property-based suite (tests/project/test_properties.py), one regression a case.

def set_options(sets: list[str]) -> list[str]:
    """A ``--set`` option for each of ``sets``."""
    return [option for s in sets for option in ("--set", s)]


def test_a_plate_cam_of_straight_ramps_is_refused_by_segment_not_by_a_traceback(tmp_path):
    """Uniform ramps on a plate: nowhere convex (no radius of curvature to invert); the roller's corner is named."""
    refused(["build", str(PLATE), "-o", str(tmp_path / "o"), "--set", "motion.1.law='uniform'"], tmp_path / "o",
            "motion[1]: undercut at 150.00 degrees: the follower velocity jumps there")


def test_a_plate_cam_that_is_nowhere_convex_reports_no_radius(tmp_path):
    result = CliRunner().invoke(camgen, ["build", str(PLATE), "-o", str(tmp_path), "--set", "motion=[{type='dwell', "
                                         "angle=360}]", "--set", "output.formats=['json']"])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "plate.json").read_text())        # strict JSON: no Infinity
    assert report["pitch_rho_min_mm"] is None and report["profile_rho_min_mm"] is None


@pytest.mark.parametrize("template, sets, words", [
    (RDRD, ["motion.2.law='uniform'"], "motion[2]: undercut at 180.00 degrees: the follower velocity jumps there"),
    (RDRD, ["motion.2.law='uniform'", "cam.base_radius='auto'"], "motion[2]: the follower velocity jumps (a convex"),
    (ROOT / "templates" / "flat-face.toml", ["motion.2.law='uniform'", "cam.base_radius=60"],
     "motion[2]: cusp at 180 degrees: the follower velocity drops there"),
])
def test_a_velocity_jump_names_its_segment(tmp_path, template, sets, words):
    args = ["build", str(template), "-o", str(tmp_path / "o"), *set_options(sets)]
    refused(args, tmp_path / "o", words)


def test_a_plate_cam_offset_is_named_as_the_followers(tmp_path):
    refused(["build", str(PLATE), "-o", str(tmp_path / "o"), "--set", "follower.offset=2"], tmp_path / "o",
            "follower.offset: not a key of a plate cam's translating-roller follower; it takes: roller_radius, ")


def test_a_set_key_with_an_empty_name_is_refused_as_the_override(tmp_path):
    refused(["build", str(RDRD), "-o", str(tmp_path / "o"), "--set", "cam..bore=3"], tmp_path / "o",
            "--set cam..bore: a key is field names joined by single dots")


@pytest.mark.parametrize("program, args", [
    ("camgen", ["build", str(RDRD)]), ("camgen", ["family", str(ROOT / "templates" / "automaton-cams.toml")]),
    ("camgen", ["bench", "--quick"]), ("linkgen", ["analyze", str(ROOT / "templates" / "crank-rocker.toml")]),
    ("linkgen", ["build", str(ROOT / "templates" / "crank-rocker.toml")]),
])
def test_an_output_folder_under_a_file_is_refused_as_the_option_before_any_work(tmp_path, program, args):
    from linkgen.cli import main as linkgen

    afile = tmp_path / "afile"
    afile.write_text("")
    refused([*args, "-o", str(afile / "sub")], afile / "sub", "Invalid value for '-o' / '--output': cannot create "
            "output folder", {"camgen": camgen, "linkgen": linkgen}[program])
    assert afile.read_text() == ""


def test_an_angle_out_of_reach_names_the_option(tmp_path):
    from linkgen.cli import main as linkgen

    refused(["analyze", str(ROOT / "templates" / "crank-rocker.toml"), "-o", str(tmp_path / "o"), "--angle", "0",
             "--set", "linkage.crank=150"], tmp_path / "o", "--angle: crank angle 0 degrees is out of reach", linkgen)


@pytest.mark.parametrize("sets", [["motion.1.law='uniform'"], ["follower.roller_radius=20", "motion.1.angle=40",
                                                               "motion.2.angle=140", "output.kerf=0.3"],
                                  ["follower={type='knife-edge'}", "motion.1.law='uniform'", "output.kerf=0.2"]])
def test_a_plate_cams_undercut_envelope_is_closed_by_the_plate(sets):
    """allow_undercut on a plate used to measure the plate's own edges against the surface and densify without
    end (minutes, gigabytes); the profile alone is measured now, and it is within the tolerance."""
    import numpy as np
    import shapely

    from camgen.api import design_cam
    from camgen.spec import load_spec
    from camgen.surface import surface_deviation

    d = design_cam(load_spec(PLATE, ["cam.allow_undercut=true", *sets]))
    # bounded work, not wall time: the outline keeps a few dozen vertices (it densified without end before)
    assert max(len(o.contour.vertices) for o in (d.outline, d.cut_outline)) < 500
    assert d.outline.envelope
    for outline, offset in ((d.outline, 0.0), (d.cut_outline, d.spec.output.kerf / 2)):
        pts = outline.contour.flatten(1e-4)
        assert shapely.Polygon(pts).is_valid
        profile = pts[(pts[:, 1] > 1e-6 - offset) & (pts[:, 0] >= 0) & (pts[:, 0] <= 200)]
        assert np.abs(surface_deviation(d.cam, profile, offset)).max() <= d.tolerance


@pytest.mark.parametrize("sets, words", [
    (["parts.clearance=12"], "parts.clearance: must be >= 0 and <= 5 mm (got 12)"),
    (["parts.width=5", "parts.clearance=1.5"], "parts.clearance: must be >= 0 and < 1 mm (width - pin_diameter)"),
    (["parts.kerf=100"], "parts.kerf: must be >= 0 and <= 5 mm (got 100)"),
    (["parts.kerf=4.3"], "parts.kerf: must be >= 0 and < 4.2 mm (pin_diameter + clearance)"),
    (["parts.sheet=[-1, 400]"], "parts.sheet[0]: must be > 0 mm (got -1)"),
    (["parts.margin=1e9"], "parts.margin: must be >= 0 and <= 1000 mm"),
])
def test_linkage_allowances_name_the_field_that_is_too_large(tmp_path, sets, words):
    """A huge clearance was blamed on parts.pin_diameter and a huge kerf came out as a sheet too small."""
    from linkgen.cli import main as linkgen

    args = ["build", str(ROOT / "templates" / "crank-rocker.toml"), "-o", str(tmp_path / "o"), *set_options(sets)]
    refused(args, tmp_path / "o", words, linkgen)


@pytest.mark.parametrize("template, sets, words", [
    ("crank-rocker.toml", ["linkage.rpm=1e300"], "linkage.rpm: must be > 0 and <= 100000 rpm"),
    ("crank-rocker.toml", ["linkage.crank=1e300", "linkage.coupler=1e300", "linkage.rocker=1e300",
                           "linkage.ground=1e300"], "linkage.ground: must be at most 10000 mm in size"),
    ("crank-rocker.toml", ["linkage.crank=1e-300"], "linkage.crank: a length other than 0 must be at least 1e-06 mm"),
    ("hoekens.toml", ["linkage.size=1e-300"], "linkage.size: a length other than 0 must be at least 1e-06 mm"),
    ("crank-rocker.toml", ["linkage.point_distance=1e300"], "linkage.point_distance: must be at most 10000 mm"),
    ("slider-crank.toml", ["linkage.offset=-1e5"], "linkage.offset: must be at most 10000 mm in size"),
])
def test_linkage_lengths_and_speeds_are_bounded(tmp_path, template, sets, words):
    """Huge speeds and lengths overflowed in the kinematics (a traceback), a vanishing one was blamed on a field of
    another linkage type (linkage.links.crank)."""
    from linkgen.cli import main as linkgen

    args = ["analyze", str(ROOT / "templates" / template), "-o", str(tmp_path / "o"), "--angle", "30",
            *set_options(sets)]
    refused(args, tmp_path / "o", words, linkgen)


@pytest.mark.parametrize("program, template, sets, words", [
    ("linkgen", "jansen.toml", ["linkage.input=5"], "linkage.input: must be a table of keys, e.g. {...} (got 5)"),
    ("linkgen", "jansen.toml", ["linkage.input={link='crank', pivot='O', range=[0, 'a']}"],
     "linkage.input.range[1]: must be a number (got 'a')"),
    ("linkgen", "jansen.toml", ["linkage.input=true"], "linkage.input: must be a table of keys"),
    ("camgen", "rdrd.toml", ["cam=5"], "cam: must be a table of keys, e.g. {...} (got 5)"),
    ("camgen", "rdrd.toml", ["name=true"], "name: input should be a valid string (got True)"),
])
def test_an_error_inside_a_union_names_the_key_not_the_union_member(tmp_path, program, template, sets, words):
    """pydantic puts the union member it tried into the error's location (linkage.input.function-after[_one_kind(),
    InputTable]: ...); the path is the template's keys only, and true where no number is asked is not called one."""
    from linkgen.cli import main as linkgen

    args = ["analyze" if program == "linkgen" else "build", str(ROOT / "templates" / template),
            "-o", str(tmp_path / "o"), *set_options(sets)]
    refused(args, tmp_path / "o", words, {"camgen": camgen, "linkgen": linkgen}[program])


@pytest.mark.parametrize("template, sets, words", [
    ("flat-face.toml", ["cam.base_radius=5e-324"], "cam.base_radius: a length other than 0 must be at least 1e-06 mm"),
    ("plate.toml", ["cam.travel=7e-214"], "cam.travel: a length other than 0 must be at least 1e-06 mm"),
    ("rdrd.toml", ["cam.bore=1e-300"], "cam.bore: a length other than 0 must be at least 1e-06 mm"),
])
def test_a_vanishing_length_is_refused_by_name(tmp_path, template, sets, words):
    """A flat face on a base circle of 5e-324 mm, or a plate 7e-214 mm long, overflowed into numpy warnings on
    stderr and an error blaming output.tolerance."""
    refused(["build", str(ROOT / "templates" / template), "-o", str(tmp_path / "o"), *set_options(sets)],
            tmp_path / "o", words)


@pytest.mark.parametrize("sets, words", [
    (["linkage.sliders.ram={point='C', guide='ground'}"],
     "linkage.sliders.ram.angle: missing: give the guide's direction in the drawing"),
    (["linkage.sliders.ram.bogus=1"], "linkage.sliders.ram.bogus: unknown key; known keys here: point, guide, angle"),
])
def test_a_field_under_the_users_own_key_is_described(tmp_path, sets, words):
    """A table of the user's own keys (sliders by name) hid its fields' descriptions: 'missing: give a value'."""
    from linkgen.cli import main as linkgen

    refused(["analyze", str(ROOT / "templates" / "shaper.toml"), "-o", str(tmp_path / "o"), *set_options(sets)],
            tmp_path / "o", words, linkgen)
