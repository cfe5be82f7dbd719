"""A linkage's ``[dynamics]`` table: mass properties from its parts as made (against shapely and closed forms), on
every linkage type, the flywheel as a part, what the holes and pins carry, and bad input refused in one line."""
from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.core.parts import Allowances, Part
from camgen.core.shapes import Circle, rounded_hull
from linkgen.cli import main as linkgen
from linkgen.linkage_design import design_linkage
from linkgen.dynamics.materials import PINS, SHEETS
from linkgen.dynamics.section import part_section
from linkgen.kinematics import equivalents
from linkgen.kinematics.fourbar import FourBar
from linkgen.mechanisms.general import table_of
from linkgen.parts import LinkPart, Stock
from linkgen.spec import validate_spec
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

CRANK_ROCKER = tomllib.loads((ROOT / "templates" / "crank-rocker.toml").read_text())


def _stadium(length: float, radius: float, hole: float) -> tuple[float, float]:
    """A two-hole bar's area (mm^2) and polar second moment about its middle (mm^4) in closed form: the rectangle
    length x 2 radius, the two half discs at its ends (each pi R^4 / 4 about its own centre, its centroid 4 R /
    (3 pi) out), less two holes of radius ``hole`` at the ends."""
    r = radius
    area = 2 * r * length + math.pi * r**2 - 2 * math.pi * hole**2
    polar = (2 * r * length * (length**2 + 4 * r**2) / 12 + math.pi * r**4 / 2 + math.pi * r**2 * length**2 / 4
             + 4 * length * r**3 / 3 - 2 * (math.pi * hole**4 / 2 + math.pi * hole**2 * length**2 / 4))
    return area, polar


def test_a_bars_section_is_the_closed_form_and_a_plates_centroid_shapelys():
    """A two-hole bar (exact arcs, cut with a kerf) against its closed form to 1e-12; a triangular plate with a slot
    against shapely's polygon of its outline flattened to 1e-5 mm (area and centroid within that tolerance)."""
    import shapely

    stock = Stock(4.2, 4.0, 0.01)
    bar = Allowances(kerf=0.15).cut(LinkPart("crank", np.array([[0.0, 0.0], [80.0, 0.0]]), 7.0, stock))
    section = part_section(bar)
    area, polar = _stadium(80.0, 7.0 + 0.075, (4.2 - 0.15) / 2)
    assert section.area == pytest.approx(area, rel=1e-12)
    assert section.centroid == pytest.approx((40.0, 0.0), abs=1e-12)
    assert section.polar_about_centroid == pytest.approx(polar, rel=1e-12)
    plate = Part("plate", rounded_hull(np.array([[0.0, 0.0], [60.0, 0.0], [20.0, 40.0]]), 5.0),
                 (Circle((0.0, 0.0), 1.5), rounded_hull(np.array([[10.0, 5.0], [30.0, 10.0]]), 2.0)), 3.0, 0.01)
    polygon = shapely.Polygon(plate.outline.flatten(1e-5), [h.flatten(1e-5) for h in plate.holes])
    got = part_section(plate)
    assert got.area == pytest.approx(polygon.area, rel=1e-6)
    assert got.centroid == pytest.approx((polygon.centroid.x, polygon.centroid.y), abs=1e-5)
    square = Part("square", rounded_hull(np.array([[0.0, 0.0]]), 1.0), (), 1.0, 0.01)
    rectangle = part_section(Part("r", __import__("camgen.core.shapes", fromlist=["Contour"]).Contour(
        np.array([[0.0, 0.0], [30.0, 0.0], [30.0, 10.0], [0.0, 10.0]])), (), 1.0, 0.01))
    assert rectangle.polar_about_centroid == pytest.approx(30 * 10 * (30**2 + 10**2) / 12, rel=1e-13)
    assert part_section(square).polar_about_centroid == pytest.approx(math.pi / 2, rel=1e-13)


def _crank_rocker(dynamics: dict, parts: bool = True, **more) -> object:
    raw = {**CRANK_ROCKER, "dynamics": dynamics, **more}
    return design_linkage(validate_spec(raw), parts=parts)


def test_the_cranks_mass_is_its_cut_part_and_its_pins():
    """The crank-rocker's crank in plywood: its part is the cut stadium (kerf applied) times thickness and density;
    the pin at A (steel, as long as the stack and 1 mm, under its head) sits at A; the ground pivot's pin does not
    move and is not counted."""
    design = _crank_rocker({"material": "plywood"})
    p = design.spec.parts
    m = design.dynamics.masses.links["crank"]
    area, polar = _stadium(design.spec.linkage.crank, p.width_of("crank") / 2 + p.kerf / 2,
                           (p.pin_diameter + p.clearance - p.kerf) / 2)
    rho = SHEETS["plywood"].density * 1e-9 * p.thickness
    assert m.part.mass == pytest.approx(rho * area, rel=1e-12)
    assert m.part.centre == pytest.approx((design.spec.linkage.crank / 2, 0.0), abs=1e-12)
    assert m.part.inertia == pytest.approx(rho * polar, rel=1e-12)
    top = max(design.build.layers.values()) + 1
    d = p.pin_diameter
    pin = PINS["steel"].density * 1e-9 * (math.pi * d**2 / 4 * (top * p.thickness + 1) + math.pi * (0.9 * d) ** 2
                                          * d / 2)
    assert [(what, h.mass, h.centre) for what, h in m.hardware] == [
        ("pin A", pytest.approx(pin, rel=1e-12), pytest.approx((design.spec.linkage.crank, 0.0)))]
    assert m.total.mass == pytest.approx(m.part.mass + pin, rel=1e-12)
    assert "hardware" not in design.report["dynamics"]["masses"]["rocker"]  # its pins: O4 fixed, B the coupler's
    assert design.report["dynamics"] == _crank_rocker({"material": "plywood"}, parts=False).report["dynamics"]


def test_given_values_replace_the_parts_and_a_mass_alone_scales_the_inertia():
    computed = _crank_rocker({}).dynamics.masses.links["coupler"].total
    given = _crank_rocker({"links": {"coupler": {"mass": 2 * computed.mass}}}).dynamics.masses.links["coupler"]
    assert given.total.mass == pytest.approx(2 * computed.mass, rel=1e-15)
    assert given.total.inertia == pytest.approx(2 * computed.inertia, rel=1e-12)
    assert given.total.centre == computed.centre and given.given == ("mass",)
    full = _crank_rocker({"links": {"coupler": {"mass": 0.1, "centre": [50.0, 10.0], "inertia": 300.0}}}).dynamics
    assert full.masses.links["coupler"].total.inertia == 300.0
    report = full.masses.links["coupler"]
    assert report.total.centre == (50.0, 10.0) and report.given == ("mass", "centre", "inertia")


def _fourbar_masses() -> dict:
    return {"crank": {"mass": 0.02, "centre": [12.0, 3.0], "inertia": 9.0},
            "coupler": {"mass": 0.05, "centre": [90.0, -8.0], "inertia": 80.0},
            "rocker": {"mass": 0.04, "centre": [60.0, 5.0], "inertia": 40.0}}


def test_the_dedicated_four_bar_runs_as_the_same_general_linkage():
    """The crank-rocker as ``four-bar`` and drawn as ``type = "linkage"``, the same masses given (in each link's
    frame): the same driving torque at every pose and the same joint forces (1e-12 of their peaks)."""
    dynamics = {"links": _fourbar_masses(), "incline": 60.0}
    dedicated = design_linkage(validate_spec({"name": "fb", "linkage": CRANK_ROCKER["linkage"], "dynamics": dynamics}))
    fb = FourBar(*(CRANK_ROCKER["linkage"][k] for k in ("ground", "crank", "coupler", "rocker")))
    table = table_of(equivalents.fourbar(fb, 0.0)).model_dump(exclude_none=True)
    table["lengths"] = {}
    general = design_linkage(validate_spec({"name": "fb", "linkage": table, "dynamics": dynamics}))
    a, b = dedicated.dynamics.result, general.dynamics.result
    assert np.abs(a.effort - b.effort).max() <= 1e-12 * np.abs(a.effort).max()
    for x, y in zip(a.pairs, b.pairs, strict=True):
        assert x.pair == y.pair and np.abs(x.force - y.force).max() <= 1e-12 * np.abs(x.force).max()


EVERY_TYPE = {
    "four-bar": {"type": "four-bar", "ground": 100.0, "crank": 30.0, "coupler": 90.0, "rocker": 70.0},
    "slider-crank": {"type": "slider-crank", "crank": 30.0, "rod": 100.0, "offset": 10.0},
    "scotch-yoke": {"type": "scotch-yoke", "crank": 30.0},
    "crank-shaper": {"type": "crank-shaper", "crank": 60.0, "ground": 150.0, "lever": 300.0},
    "whitworth": {"type": "whitworth", "crank": 40.0, "ground": 20.0, "arm": 60.0, "rod": 150.0},
    "hoekens": {"type": "hoekens", "size": 40.0},
    "chebyshev": {"type": "chebyshev", "size": 40.0},
    "roberts": {"type": "roberts", "size": 40.0},
    "watt": {"type": "watt", "size": 40.0},
    "linkage": tomllib.loads((ROOT / "templates" / "stephenson3.toml").read_text())["linkage"],
}


@pytest.mark.parametrize("kind", sorted(EVERY_TYPE))
def test_every_linkage_type_takes_a_dynamics_table(kind):
    """Each dedicated type, and a Stephenson six-bar drawn as ``type = "linkage"``, with each of its links given a
    mass: a dynamics section whose links are the type's general drawing's, whose every link balances (1e-9), and
    whose mean torque over a crank's turn is 0 (no loads: what the links' energy and weights take, they give back);
    the double rockers (Chebyshev, Roberts, Watt) are analysed inside the toggles that end their crank's range, and
    say so."""
    from linkgen.linkage_design import general_drawing

    table = EVERY_TYPE[kind]
    spec = validate_spec({"name": "x", "linkage": table})
    analysis = general_drawing(spec.mechanism.build(spec.linkage), spec.linkage)
    links = [b for b in analysis.linkage.structure.bodies if b != "ground"]
    given = {b: {"mass": 0.01 * (k + 1), "centre": [3.0, 1.0], "inertia": 2.0} for k, b in enumerate(links)}
    design = design_linkage(validate_spec({"name": "x", "linkage": table, "dynamics": {"links": given}}))
    d = design.report["dynamics"]
    assert list(d["masses"]) == links
    assert d["balance_residual"] <= 1e-9
    assert d["moving_mass_kg"] == pytest.approx(sum(0.01 * (k + 1) for k in range(len(links))), rel=1e-12)
    if design.dynamics.turns:
        assert abs(d["mean_effort_N_m"]) <= 1e-9 * max(abs(d["max_N_m"]), abs(d["min_N_m"]))
    else:
        assert kind in ("chebyshev", "roberts", "watt") and "mean_effort_N_m" not in d
        assert len(design.dynamics.toggles) == 2 and d["warnings"][0].startswith("the input's range ends at a toggle")
    assert len(d["joints"]) == len(design.dynamics.result.pairs) >= 3


def test_a_rocker_driven_four_bar_is_refused_on_dynamics(tmp_path):
    _refused("crank-rocker", {"linkage.input": "rocker", "dynamics": {}},
             "dynamics: linkgen computes the dynamics of a linkage drawn as a general one", tmp_path)


def _refused(template: str, change: dict, message: str, tmp_path, command: str = "analyze") -> None:
    """``linkgen analyze`` (or ``command``) of a bundled template with ``change`` (dotted keys, as --set) fails with
    ``error: message...`` on one line, exit code 2, and writes no folder."""
    assert_refused(ROOT / "templates" / f"{template}.toml", change, message, tmp_path, linkgen, command, _inline)


def _inline(value: object) -> str:
    """A value as TOML writes it inline (tables as {k = v}, lists, strings, numbers)."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_inline(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_inline(v) for v in value) + "]"
    return json.dumps(value)


@pytest.mark.parametrize("dynamics, message", [
    ({"density": -5}, "dynamics.density: must be > 0 and <= 25000 kg/m^3 (got -5)"),
    ({"material": "plywod"}, "dynamics.material: unknown value 'plywod' (did you mean 'plywood'?)"),
    ({"pins": "wood"}, "dynamics.pins: unknown value 'wood'"),
    ({"infill": 0.3}, "dynamics.infill: is for printed parts (pla, petg)"),
    ({"links": {"foot": {"mass": 1.0}}}, "dynamics.links.foot: no moving link 'foot' (links: crank, coupler, rocker)"),
    ({"links": {"crank": {"mass": -1}}}, "dynamics.links.crank.mass: must be >= 0 and <= 10000 kg (got -1)"),
    ({"springs": [{"between": ["A", "Q"], "stiffness": 1.0, "free_length": 10.0}]},
     "dynamics.springs[0].between: no joint 'Q'"),
    ({"springs": [{"between": ["A", "B"], "stiffness": 0.0, "free_length": 10.0}]},
     "dynamics.springs[0].stiffness: must be > 0 and <= 1e+06 N/mm (got 0"),
    ({"poses": 10**6}, "dynamics.poses: must be >= 36 and <= 20000"),
    ({"flywheel": {"fluctuation": 0.0}}, "dynamics.flywheel.fluctuation: must be > 0 and <= 0.5"),
    ({"incline": 120.0}, "dynamics.incline: must be >= 0 and <= 90 degrees"),
])
def test_bad_dynamics_input_is_one_line_naming_the_field(dynamics, message, tmp_path):
    _refused("crank-rocker", {"dynamics": dynamics}, message, tmp_path)


def test_masses_without_parts_must_be_given(tmp_path):
    _refused("slider-crank", {"dynamics": {"links": {"crank": {"mass": 0.1}}}},
             "dynamics.links.crank: give its centre and inertia", tmp_path)
    _refused("slider-crank", {"dynamics": {}}, "dynamics.links.crank: give its mass, centre and inertia", tmp_path)


def test_a_flywheel_needs_a_crank_that_turns_fully(tmp_path):
    _refused("pendulum-pump", {"dynamics": {"flywheel": {"fluctuation": 0.05}}},
             "dynamics.flywheel: a flywheel is sized over a crank's full turn", tmp_path)


@pytest.mark.parametrize("shape", ["disc", "rim"])
def test_the_flywheel_part_gives_the_inertia_needed(shape, tmp_path):
    """Jansen's leg's flywheel as made (cut: its outline grown and its hole shrunk by half the kerf) gives the inertia
    the coefficient asks (the total less the leg's own mean) to 1e-9; a disc's is 1/2 rho t pi (R^4 - r^4) in closed
    form; a rim is lighter; the plate is on the cut sheet and printed (STL) with the other parts."""
    raw = tomllib.loads((ROOT / "templates" / "jansen-dynamics.toml").read_text())
    raw["dynamics"]["flywheel"]["shape"] = shape
    design = design_linkage(validate_spec(raw), parts=True)
    f = design.dynamics.flywheel
    assert f.total == pytest.approx(f.energy / (0.05 * (2 * math.pi) ** 2), rel=1e-12)
    assert f.needed == pytest.approx(f.total - float(np.mean(design.dynamics.inertia)), rel=1e-12)
    assert f.inertia == pytest.approx(f.needed, rel=1e-9)
    p = design.spec.parts
    if shape == "disc":
        big, small = f.radius + p.kerf / 2, (p.pin_diameter + p.clearance - p.kerf) / 2
        closed = 0.5 * SHEETS["plywood"].density * 1e-9 * p.thickness * math.pi * (big**4 - small**4) * 1e-6
        assert closed == pytest.approx(f.needed, rel=1e-9)
    else:
        disc = design_linkage(validate_spec(tomllib.loads((ROOT / "templates" / "jansen-dynamics.toml").read_text())))
        assert f.mass < 0.8 * disc.dynamics.flywheel.mass
    assert "flywheel" in [part.name for part in design.build.cut] and design.build.layers["flywheel"] == -1
    assert "flywheel" in {placed["name"] for placed in design.build.nesting.report["parts"]}
    files = __import__("linkgen.outputs", fromlist=["write_linkage"]).write_linkage(design, tmp_path)
    assert "flywheel_stl" in files


def test_holes_bear_their_joints_forces():
    """The toggle press in acrylic holding its 1 kN: each hole's pressure is its peak force over pin diameter x
    thickness, each pin's shear that over pi d^2 / 4; those above acrylic's allowable are warned of by joint."""
    raw = tomllib.loads((ROOT / "templates" / "toggle-press.toml").read_text())
    design = design_linkage(validate_spec({**raw, "dynamics": {"material": "acrylic"}}))
    d = design.report["dynamics"]
    p = design.spec.parts
    allowable = SHEETS["acrylic"].allowable_bearing
    for hole in d["holes"]:
        assert hole["bearing_MPa"] == pytest.approx(hole["peak_N"] / (p.pin_diameter * p.thickness), rel=1e-9)
        assert hole["allowable_MPa"] == pytest.approx(allowable)
    worst = max(d["holes"], key=lambda h: h["bearing_MPa"])
    assert worst["bearing_MPa"] > allowable
    assert any(w.startswith(f"hole of {worst['part']} at {worst['joint']}: bearing pressure") for w in d["warnings"])
    for pin in d["pins"]:
        peak = max(h["peak_N"] for h in d["holes"] if h["joint"] == pin["joint"])
        assert pin["shear_MPa"] == pytest.approx(peak / (math.pi * p.pin_diameter**2 / 4), rel=1e-9)
    joint = {j["joint"]: j for j in d["joints"]}
    assert max(j["peak_N"] for j in joint.values()) >= 1000.0 > 0                 # the press's own load


def test_the_summary_page_and_family_carry_the_peaks(tmp_path):
    path = ROOT / "templates" / "jansen-dynamics.toml"
    result = CliRunner().invoke(linkgen, ["analyze", str(path), "-o", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert "dynamics at 60 rpm: moving links" in result.output and "flywheel for Cs 0.05" in result.output
    report = json.loads((tmp_path / "jansen-dynamics.json").read_text())["dynamics"]
    design = design_linkage(validate_spec(tomllib.loads(path.read_text())))
    row = design.family_row()
    assert row["effort_peak_N_m"] == max(abs(report["max_N_m"]), abs(report["min_N_m"]))
    assert row["flywheel_kg_m2"] == report["flywheel"]["flywheel_kg_m2"]
    page = (tmp_path / "jansen-dynamics.html").read_text()
    assert "driving torque" in page and "joint forces" in page and "peak shaking force" in page


def test_a_flywheel_larger_than_the_sheet_is_warned_of_and_refused_by_build(tmp_path):
    """A rim for Cs 1e-4 at 60 rpm (4.4 kg*m^2) is about 4 m across: the report sizes it and warns that it does not
    fit the 600 x 400 mm sheet; ``linkgen build`` refuses it in one line naming the key, exit 2, nothing written.
    With almost no density even the largest plate falls short of the inertia, and says so."""
    rim = {"flywheel": {"fluctuation": 1e-4, "shape": "rim"}}
    d = _crank_rocker(rim, parts=False).report["dynamics"]
    assert d["flywheel"]["diameter_mm"] > 600 and not d["flywheel"]["fits_sheet"]
    assert d["flywheel"]["inertia_as_made_kg_m2"] == pytest.approx(d["flywheel"]["flywheel_kg_m2"], rel=1e-6)
    assert [w for w in d["warnings"] if w.startswith("the flywheel:")] == [
        f"the flywheel: 1 plate(s) {d['flywheel']['diameter_mm']:.6g} mm across do not fit the sheet; linkgen build "
        "refuses it: stack more plates (dynamics.flywheel.plates), or choose the rim shape or a denser material"]
    _refused("crank-rocker", {"dynamics": rim}, "dynamics.flywheel.plates: 1 plate(s)", tmp_path, "build")
    light = _crank_rocker({"density": 1e-6, "flywheel": {"fluctuation": 1e-3}}, parts=False).report["dynamics"]
    assert light["flywheel"]["inertia_as_made_kg_m2"] < 1e-3 * light["flywheel"]["flywheel_kg_m2"]
    assert any(w.startswith("the flywheel: the largest plate (10000 mm across) gives") for w in light["warnings"])


def test_a_kits_pins_are_its_steel_bolts():
    """With a ``[kit]`` the pins are its M4 bolts: each moving pivot carries the steel of its bolt, nut and washer
    (ISO 4762, 4032, 7089) instead of a printed pin, and each pin's shear is against steel's allowable (an 8.8
    bolt's 192 MPa) whatever ``dynamics.pins`` says."""
    from camgen.core.hardware import bolt_length

    raw = tomllib.loads((ROOT / "templates" / "kit-crank-rocker.toml").read_text())
    design = design_linkage(validate_spec({**raw, "dynamics": {"pins": "pla"}}), parts=True)
    d = design.report["dynamics"]
    assert d["pins"] and [p["allowable_MPa"] for p in d["pins"]] == [pytest.approx(0.6 * 640 / 2)] * len(d["pins"])
    bolt = validate_spec(raw).kit.hardware
    (what, hardware), *_ = design.dynamics.masses.links["crank"].hardware
    assert what == "bolt A"
    grip = 2 * design.spec.parts.thickness               # the crank and the coupler at A, one plate each
    shank = math.pi * bolt.diameter**2 / 4 * bolt_length(bolt, grip)
    assert hardware.mass > PINS["steel"].density * 1e-9 * shank > 0
    plain = design_linkage(validate_spec({**{k: v for k, v in raw.items() if k != "kit"},
                                          "dynamics": {"pins": "pla"}}), parts=True)
    pins = plain.report["dynamics"]["pins"]
    assert pins and [p["allowable_MPa"] for p in pins] == [pytest.approx(0.6 * 45 / 3)] * len(pins)
