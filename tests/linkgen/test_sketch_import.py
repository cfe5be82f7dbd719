"""``linkgen import``: sketches drawn with ezdxf here read back as the linkage drawn (positions to 1e-9 mm, the same
topology, the same motion over a turn), what is not read named, the project's own assembly read back, bad input."""
from __future__ import annotations

import math
import tomllib

import ezdxf
import numpy as np
import pytest
from click.testing import CliRunner

from linkgen.cli import main
from tests.conftest import ROOT

# a Grashof crank-rocker (crank 40, coupler 120, rocker 100, frame 130 mm) with the crank at 50 degrees; B is where
# the circles of A (120) and O2 (100) meet, above the frame line
O1, O2 = (10.0, 20.0), (140.0, 20.0)
A = (O1[0] + 40 * math.cos(math.radians(50)), O1[1] + 40 * math.sin(math.radians(50)))


def _meet(p, r, q, s):
    """The upper (counter-clockwise of p -> q) intersection of circles (p, r) and (q, s): computed independently of
    the solver."""
    d = math.dist(p, q)
    a = (r * r - s * s + d * d) / (2 * d)
    h = math.sqrt(r * r - a * a)
    ux, uy = (q[0] - p[0]) / d, (q[1] - p[1]) / d
    return p[0] + a * ux - h * uy, p[1] + a * uy + h * ux


B = _meet(A, 120.0, O2, 100.0)


def circle(msp, p, layer="0", r=2.0):
    msp.add_circle(p, r, dxfattribs={"layer": layer})


def fourbar_doc(units=4):
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = units
    msp = doc.modelspace()
    for p in (O1, O2):
        circle(msp, p, "GROUND")
    for p in (A, B):
        circle(msp, p)
    msp.add_line(O1, A)
    msp.add_line(A, B)
    msp.add_line(O2, B)
    return doc


def save(doc, tmp_path, name="sketch.dxf"):
    path = tmp_path / name
    doc.saveas(path)
    return path


def run(*args):
    return CliRunner().invoke(main, ["import", *map(str, args)])


def read(path):
    with open(path, "rb") as f:
        return tomllib.load(f)


def motion(linkage, values):
    from linkgen.kinematics.linkage import Linkage
    from linkgen.mechanisms.general import LinkageTable, structure_of

    return Linkage.of(structure_of(LinkageTable.model_validate(linkage))).solve(values).points


def by_position(joints, drawn):
    """Each drawn joint's name in the imported template (matched by position to 1e-9 mm)."""
    names = {}
    for name, p in drawn.items():
        hits = [k for k, q in joints.items() if math.dist(p, q) <= 1e-9]
        assert len(hits) == 1, (name, p, joints)
        names[name] = hits[0]
    return names


def links_by_position(linkage, names):
    back = {v: k for k, v in names.items()}
    return sorted(tuple(sorted(back[j] for j in pts)) for pts in linkage["links"].values())


def test_fourbar_reads_as_drawn(tmp_path):
    sketch = save(fourbar_doc(), tmp_path)
    out = tmp_path / "fb.toml"
    result = run(sketch, "-o", out)
    assert result.exit_code == 0, result.output
    assert "warning" not in result.output
    t = read(out)["linkage"]
    drawn = {"O1": O1, "O2": O2, "A": A, "B": B}
    names = by_position(t["joints"], drawn)
    assert links_by_position(t, names) == [("A", "B"), ("A", "O1"), ("B", "O2")]
    assert sorted(t["ground"]) == sorted([names["O1"], names["O2"]])
    assert t["input"] == {"link": "crank", "pivot": names["O1"]}
    assert set(t["links"]["crank"]) == {names["O1"], names["A"]}
    # over a turn, the imported linkage moves as the one drawn (built here from our own names)
    mine = {"type": "linkage", "joints": drawn, "ground": ["O1", "O2"], "input": {"link": "c", "pivot": "O1"},
            "links": {"c": ["O1", "A"], "k": ["A", "B"], "r": ["O2", "B"]}}
    values = math.radians(50) + np.linspace(0, 2 * math.pi, 73)
    want, got = motion(mine, values), motion(t, values)
    for name, imported in names.items():
        assert np.asarray(got[imported]) == pytest.approx(np.asarray(want[name]), abs=1e-9)
    # and an independent check: the rocker pin at the drawn angle + 90 degrees is where the two circles meet
    at = np.asarray(got[names["B"]])[18]
    a90 = (O1[0] + 40 * math.cos(values[18]), O1[1] + 40 * math.sin(values[18]))
    assert at == pytest.approx(_meet(a90, 120.0, O2, 100.0), abs=1e-9)
    # the template builds: linkgen build makes its parts, pins as wide as the circles drawn
    assert read(out)["parts"] == {"width": 12.0, "thickness": 3.0, "pin_diameter": 4.0}
    built = CliRunner().invoke(main, ["build", str(out), "-o", str(tmp_path / "a")])
    assert built.exit_code == 0, built.output
    assert (tmp_path / "a" / "sketch-assembly.dxf").exists()


def test_inches_are_read_as_mm(tmp_path):
    out = tmp_path / "in.toml"
    assert run(save(fourbar_doc(units=1), tmp_path), "-o", out).exit_code == 0
    joints = read(out)["linkage"]["joints"]
    assert joints["O2"] == pytest.approx([140.0 * 25.4, 20.0 * 25.4], abs=1e-9)


def sixbar_doc():
    """The four-bar above, its rocker a ternary link O2-B-C (one polyline through three circles), a rod C-D and D
    sliding on a ground line y = 150 mm (a rectangle round D on the line)."""
    doc = fourbar_doc()
    msp = doc.modelspace()
    for e in [e for e in msp if e.dxftype() == "LINE" and e.dxf.start[0] == O2[0]]:
        msp.delete_entity(e)
    c = (O2[0] + 60.0, O2[1] + 90.0)
    d = (c[0] + math.sqrt(110.0 ** 2 - (150.0 - c[1]) ** 2), 150.0)
    for p in (c, d):
        circle(msp, p)
    msp.add_lwpolyline([O2, B, c])
    msp.add_line(c, d)
    msp.add_line((50.0, 150.0), (350.0, 150.0), dxfattribs={"layer": "ground"})
    msp.add_lwpolyline([(d[0] - 8, 145), (d[0] + 8, 145), (d[0] + 8, 155), (d[0] - 8, 155)], close=True)
    return doc, c, d


def test_sixbar_with_a_slider(tmp_path):
    doc, c, d = sixbar_doc()
    out = tmp_path / "six.toml"
    result = run(save(doc, tmp_path), "-o", out)
    assert result.exit_code == 0, result.output
    t = read(out)["linkage"]
    drawn = {"O1": O1, "O2": O2, "A": A, "B": B, "C": c, "D": d}
    names = by_position(t["joints"], drawn)
    assert links_by_position(t, names) == [("A", "B"), ("A", "O1"), ("B", "C", "O2"), ("C", "D")]
    (slider,) = t["sliders"].values()
    assert slider["point"] == names["D"] and slider["angle"] == pytest.approx(0.0, abs=1e-12)
    mine = {"type": "linkage", "joints": drawn, "ground": ["O1", "O2"], "input": {"link": "c", "pivot": "O1"},
            "links": {"c": ["O1", "A"], "k": ["A", "B"], "r": ["O2", "B", "C"], "rod": ["C", "D"]},
            "sliders": {"S": {"point": "D", "angle": 0.0}}}
    values = math.radians(50) + np.linspace(0, 2 * math.pi, 73)
    want, got = motion(mine, values), motion(t, values)
    for name, imported in names.items():
        assert np.asarray(got[imported]) == pytest.approx(np.asarray(want[name]), abs=1e-9)
    assert np.asarray(got[names["D"]])[:, 1] == pytest.approx(np.full(73, 150.0), abs=1e-9)   # on its guide


def test_loose_line_and_unconnected_circle_are_named(tmp_path):
    doc = fourbar_doc()
    msp = doc.modelspace()
    loose = msp.add_line((300.0, 300.0), (320.0, 310.0))
    lonely = msp.add_circle((400.0, 0.0), 2.0)
    text = msp.add_text("hello")
    out = tmp_path / "fb.toml"
    result = run(save(doc, tmp_path), "-o", out)
    assert result.exit_code == 0, result.output
    warnings = [line for line in result.output.splitlines() if line.startswith("warning: ")]
    assert len(warnings) == 3, result.output
    assert any(f"LINE #{loose.dxf.handle}" in w and "loose" in w for w in warnings)
    assert any(f"CIRCLE #{lonely.dxf.handle}" in w and "(400, 0)" in w and "no link" in w for w in warnings)
    assert any(f"TEXT #{text.dxf.handle}" in w for w in warnings)
    assert len(read(out)["linkage"]["joints"]) == 4                     # the linkage itself is read whole


def test_own_assembly_reads_back(tmp_path):
    """The bundled crank-rocker (crank 80, coupler 200, rocker 150, frame 180 mm), built by linkgen build, reads
    back from its assembly drawing (first pose) as the same linkage: the same links, the frame where it was, and
    the same motion over a turn as the four-bar's closed form."""
    from linkgen.kinematics.fourbar import FourBar

    built = CliRunner().invoke(main, ["build", str(ROOT / "templates" / "crank-rocker.toml"), "-o", str(tmp_path)])
    assert built.exit_code == 0, built.output
    out = tmp_path / "back.toml"
    result = run(tmp_path / "crank-rocker-assembly.dxf", "-o", out)
    assert result.exit_code == 0, result.output
    t = read(out)["linkage"]
    j = {k: np.array(v) for k, v in t["joints"].items()}
    assert sorted(t["ground"]) == ["O1", "O2"]
    assert j["O1"] == pytest.approx([0.0, 0.0], abs=1e-9) and j["O2"] == pytest.approx([180.0, 0.0], abs=1e-9)
    lengths = sorted(round(math.dist(j[a], j[b]), 6) for a, b in t["links"].values())
    assert lengths == [80.0, 150.0, 200.0]
    crank = next(p for p in t["links"]["crank"] if p != "O1")
    start = math.atan2(j[crank][1], j[crank][0])
    values = start + np.linspace(0, 2 * math.pi, 37)
    got = motion(t, values)
    fb = FourBar(180.0, 80.0, 200.0, 150.0)
    rocker_pin = next(p for p in t["links"][next(k for k, v in t["links"].items() if "O2" in v)] if p != "O2")
    assembly = "open" if np.allclose(fb.positions(np.array([start]), "open").b[0], j[rocker_pin], atol=1e-6) \
        else "crossed"
    want = fb.positions(values, assembly)
    assert np.asarray(got[rocker_pin]) == pytest.approx(np.asarray(want.b), abs=1e-8)


@pytest.mark.parametrize("case", ["not-dxf", "no-ground", "nothing", "no-circles"])
def test_bad_input_refused(tmp_path, case):
    path = tmp_path / "bad.dxf"
    if case == "not-dxf":
        path.write_text("this is not a drawing\n")
    else:
        doc = ezdxf.new()
        msp = doc.modelspace()
        if case == "no-ground":
            for p in (O1, A):
                circle(msp, p)
            msp.add_line(O1, A)
        elif case == "nothing":
            circle(msp, O1, "ground")
            circle(msp, O2, "ground")
        doc.saveas(path)
    out = tmp_path / "out.toml"
    result = run(path, "-o", out)
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: sketch: "), result.output
    assert not out.exists()


def test_red_ground_and_input_layer(tmp_path):
    """The ground drawn in red (colour 1) instead of on layer ground, and the input marked by layer 'input': here
    the link at O2, which the first-ground-pivot rule would not pick."""
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 4                     # mm (ezdxf's new drawings are in metres)
    msp = doc.modelspace()
    for p in (O1, O2):
        msp.add_circle(p, 2.0, dxfattribs={"color": 1})
    for p in (A, B):
        circle(msp, p)
    msp.add_line(O1, A)
    msp.add_line(A, B)
    msp.add_line(O2, B, dxfattribs={"layer": "Input"})
    out = tmp_path / "red.toml"
    result = run(save(doc, tmp_path), "-o", out)
    assert result.exit_code == 0, result.output
    t = read(out)["linkage"]
    names = by_position(t["joints"], {"O1": O1, "O2": O2, "A": A, "B": B})
    assert sorted(t["ground"]) == sorted([names["O1"], names["O2"]])
    assert set(t["links"]["crank"]) == {names["O2"], names["B"]}
    assert t["input"] == {"link": "crank", "pivot": names["O2"]}
    assert run(save(doc, tmp_path), "-o", out).exit_code == 2          # never overwrites the template


@pytest.mark.parametrize("name", ["stephenson3", "jansen"])
def test_own_assembly_of_a_general_linkage_reads_back(tmp_path, name):
    """A six-bar (ternary frame and coupler) and Jansen's leg (eight links) read back from their assembly drawings:
    the same links (each link's joint-to-joint distances, to 1e-6 mm) and the same ground pivots, to 1e-9 mm."""
    import itertools

    template = ROOT / "templates" / f"{name}.toml"
    built = CliRunner().invoke(main, ["build", str(template), "-o", str(tmp_path)])
    assert built.exit_code == 0, built.output
    out = tmp_path / "back.toml"
    result = run(tmp_path / f"{name}-assembly.dxf", "-o", out)
    assert result.exit_code == 0, result.output

    def links(table):
        j = table["joints"]
        return sorted(tuple(sorted(round(math.dist(j[a], j[b]), 6) for a, b in itertools.combinations(pts, 2)))
                      for pts in table["links"].values())

    want, got = read(template)["linkage"], read(out)["linkage"]
    assert links(got) == links(want)
    assert np.array(sorted(got["joints"][p] for p in got["ground"])) == pytest.approx(
        np.array(sorted(want["joints"][p] for p in want["ground"])), abs=1e-9)
