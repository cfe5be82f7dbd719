"""Linkage input that issue 30 found accepted wrongly, or refused with a traceback: each class refused in one line
naming the field (``error: <field>: <what is allowed>``, exit code 2, nothing written) through ``linkgen analyze``
and ``linkgen build``, and the valid neighbours of each refusal accepted with figures checked independently.

Classes: a load on a ground joint (the JSON writer met an infinite mechanical advantage); a zero force, or one
across its point's path (the same infinity; now finite numbers and no advantage); a second slider that holds the
linkage still (analysed as if it moved); two inputs on a mobility-1 four-bar (a false "paradoxical"); true/false
read as 1 and 0 mm in a table of numbers; a joint on no link (ignored).
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from linkgen.cli import main as linkgen
from tests.conftest import ROOT

#: a crank-rocker drawn as a general linkage: ground 180, crank 80, coupler 200, rocker 150 mm, crank at 90 degrees
#: (B where the circles of radius 200 about A and 150 about O4 meet, left of A -> O4)
FOURBAR = """name = "fb"
[linkage]
type = "linkage"
ground = ["O2", "O4"]
input = { link = "crank", pivot = "O2" }
tracers = ["B"]
[linkage.joints]
O2 = [0.0, 0.0]
O4 = [180.0, 0.0]
A = [0.0, 80.0]
B = [187.41841978558477, 149.81644451756569]
[linkage.links]
crank = ["O2", "A"]
coupler = ["A", "B"]
rocker = ["O4", "B"]
"""
PARTS = """[parts]
width = 12.0
thickness = 4.0
pin_diameter = 4.0
"""
#: a slider-crank (crank 50, rod 200 mm, the slider on the line through the crank pivot), crank at 90 degrees
SLIDER_CRANK = """name = "sc"
[linkage]
type = "linkage"
ground = ["O2"]
input = { link = "crank", pivot = "O2" }
tracers = ["B"]
[linkage.joints]
O2 = [0.0, 0.0]
A = [0.0, 50.0]
B = [193.64916731037084, 0.0]
[linkage.links]
crank = ["O2", "A"]
rod = ["A", "B"]
[linkage.sliders.ram]
point = "B"
guide = "ground"
angle = 0
"""
#: the Scott Russell straight line: crank O2-A 50 mm, rod B-A-C with AB = AC = 50 mm, B sliding along +X through
#: O2, so that C runs exactly along the Y axis (C = (0, 100 sin t) for the crank at t); drawn at t = 60 degrees
SCOTT_RUSSELL = """name = "scott"
[linkage]
type = "linkage"
ground = ["O2"]
input = { link = "crank", pivot = "O2" }
tracers = ["C"]
[linkage.joints]
O2 = [0.0, 0.0]
A = [25.0, 43.30127018922193]
B = [50.0, 0.0]
C = [0.0, 86.60254037844386]
[linkage.links]
crank = ["O2", "A"]
rod = ["B", "A", "C"]
[linkage.sliders.foot]
point = "B"
guide = "ground"
angle = 0
"""


def _run(tmp_path: Path, text: str, command: str = "analyze", *sets: str) -> tuple[object, Path]:
    template = tmp_path / "t.toml"
    template.write_text(text + (PARTS if command == "build" and "[parts]" not in text else ""))
    out = tmp_path / "out"
    args = [command, str(template), "-o", str(out), "--set", 'output.formats=["json"]']
    for s in sets:
        args += ["--set", s]
    return CliRunner().invoke(linkgen, args), out


def assert_refused(tmp_path: Path, text: str, command: str, sets: tuple[str, ...], message: str) -> None:
    """``linkgen command`` of the template ``text`` with ``sets`` fails with ``error: message...`` on one line, exit
    code 2, and writes nothing."""
    result, out = _run(tmp_path, text, command, *sets)
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    assert result.stderr.startswith(f"error: {message}") and result.stderr.count("\n") == 1, result.stderr
    assert not out.exists()


def _report(tmp_path: Path, text: str, *sets: str) -> dict:
    """The JSON report of ``linkgen analyze``, read as strict JSON (no NaN, no infinity)."""
    result, out = _run(tmp_path, text, "analyze", *sets)
    assert result.exit_code == 0, result.output
    assert "Traceback" not in result.output

    def refuse(constant: str) -> None:
        raise AssertionError(f"the JSON holds {constant}")

    return json.loads(next(out.glob("*.json")).read_text(), parse_constant=refuse)


def _with(text: str, section: str) -> str:
    """``text`` with ``section`` (TOML lines) added under its ``[linkage]`` tables."""
    return text + section


# ---------------------------------------------------------------------------------------------------------- loads

@pytest.mark.parametrize("command", ["analyze", "build"])
@pytest.mark.parametrize("template, sets, message", [
    (FOURBAR, ('loads=[{point="O4", force=[0, 100]}]',),
     "loads[0].point: O4 is fixed to the ground, which holds a force there by itself (it asks nothing of the "
     "input); give a moving joint: A, B"),
    (FOURBAR, ('loads=[{point="A", force=[1, 0]}, {point="O2", force=[0, 0]}]',), "loads[1].point: O2 is fixed to "
     "the ground"),
    (SLIDER_CRANK, ('loads=[{point="O2", force=[0, 1]}]',), "loads[0].point: O2 is fixed to the ground"),
])
def test_a_load_on_a_ground_joint_is_refused_naming_it(tmp_path, command, template, sets, message):
    """A force at a ground joint does no work: it was reported as an effort of 0 and a mechanical advantage of
    |F| / 0, which the JSON writer refused with a traceback. The frame holds it; the input does not (as a torque
    on the ground, already refused)."""
    assert_refused(tmp_path, template, command, sets, message)


def test_the_dedicated_four_bar_refuses_a_load_on_its_pivots(tmp_path):
    template = (ROOT / "templates" / "crank-rocker.toml").read_text()
    assert_refused(tmp_path, template, "analyze", ('loads=[{point="O4", force=[0, 100]}]',),
                   "loads[0].point: O4 is fixed to the ground")


def test_a_zero_force_gives_zero_effort_and_no_advantage(tmp_path):
    """A zero force asks nothing: every effort figure is exactly 0 (not -0, not NaN) and the advantage, 0 / 0, is
    not given; a warning says why."""
    r = _report(tmp_path, FOURBAR, 'loads=[{point="B", force=[0, 0]}]')["statics"]
    assert r["max_N_m"] == r["min_N_m"] == r["rms_N_m"] == r["peak_power_W"] == 0.0
    assert math.copysign(1.0, r["max_N_m"]) == 1.0
    assert "mechanical_advantage_min" not in r and "lever_mm" not in r
    assert r["warnings"] == ["no mechanical advantage: the force is zero"]


def test_a_force_across_its_points_path_gives_zero_effort_and_no_advantage(tmp_path):
    """A vertical force on a slider that runs horizontally: F . v = 0 at every pose (v along the guide), so the
    effort is 0 (the rounding of the solver's v_y, about 1e-17 of |v|, is no effort) and the advantage is
    unbounded everywhere: left out, with a warning."""
    r = _report(tmp_path, SLIDER_CRANK, 'loads=[{point="B", force=[0, 100]}]')["statics"]
    assert r["max_N_m"] == r["min_N_m"] == r["rms_N_m"] == 0.0
    assert "mechanical_advantage_min" not in r
    assert r["warnings"] == ["no mechanical advantage: the force at B lies across its path everywhere, so it asks "
                             "no effort of the input"]


def test_a_force_along_the_slide_keeps_its_advantage(tmp_path):
    """The same slider pushed back along its guide: T = -F . dB/dtheta with B = (x, 0), x = r cos t +
    sqrt(L^2 - r^2 sin^2 t); the least advantage |F| r / |T| is where |dx/dt| is largest: the derivative's zero
    found here by bisection, independently of linkgen."""
    r = _report(tmp_path, SLIDER_CRANK, 'loads=[{point="B", force=[-100, 0]}]')["statics"]
    crank, rod = 50.0, 200.0

    def ddx(t: float) -> float:                           # d^2 x / dt^2
        s, c = math.sin(t), math.cos(t)
        root = math.sqrt(rod ** 2 - (crank * s) ** 2)
        return -crank * c - crank ** 2 * (c * c - s * s) / root - crank ** 4 * s * s * c * c / root ** 3

    lo, hi = 0.5, 1.5                                     # |dx/dt| peaks a little before 90 degrees
    for _ in range(100):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if ddx(mid) < 0 else (lo, mid)
    t = (lo + hi) / 2
    s = math.sin(t)
    dx = -crank * s - crank ** 2 * s * math.cos(t) / math.sqrt(rod ** 2 - (crank * s) ** 2)
    assert r["mechanical_advantage_min"] == pytest.approx(crank / abs(dx), rel=1e-9)
    assert r["lever_mm"] == crank and "warnings" not in r


# ------------------------------------------------------------------------------------------- mobility and inputs

SECOND_SLIDERS = {
    "on the crank pin": '[linkage.sliders.ram2]\npoint = "A"\nguide = "ground"\nangle = 0\n',
    "across the first": '[linkage.sliders.ram2]\npoint = "B"\nguide = "ground"\nangle = 90\n',
}


@pytest.mark.parametrize("command", ["analyze", "build"])
@pytest.mark.parametrize("where, message", [
    ("on the crank pin", "linkage.sliders.ram2: over-constrained (mobility 0): as the input moves, its point A "
                         "cannot stay on its guide on ground (it leaves it by up to 100 mm)"),
    ("across the first", "linkage.sliders.ram2: over-constrained (mobility 0): as the input moves, its point B "
                         "cannot stay on its guide on ground (it leaves it by up to 56.4 mm)"),
])
def test_a_second_slider_that_holds_the_linkage_still_is_refused(tmp_path, command, where, message):
    """A second slider leaves Gruebler's mobility 0: the slider-crank cannot move (A on a horizontal line through
    its drawn place cannot also turn round O2; B on a vertical line cannot also run along the horizontal one). It
    was analysed as if it moved. Its point leaves the guide by the crank pin's drop from the line at the bottom
    (2 x 50 mm), or by the slider's travel from the drawing: 193.649 - 150 / 250 -> 56.35 mm."""
    assert_refused(tmp_path, _with(SLIDER_CRANK, SECOND_SLIDERS[where]), command, (), message)


def test_a_sliding_link_that_cannot_keep_its_angle_is_refused(tmp_path):
    """The four-bar's coupler made to slide along the rocker through B: B is on the rocker's line anyway, but the
    coupler would have to keep its drawn angle to the rocker, which it does not (the four-bar moves)."""
    angle = math.degrees(math.atan2(149.81644451756569, 187.41841978558477 - 180.0))
    slider = f'[linkage.sliders.s]\npoint = "B"\nguide = "rocker"\nlink = "coupler"\nangle = {angle!r}\n'
    assert_refused(tmp_path, _with(FOURBAR, slider), "analyze", (),
                   "linkage.sliders.s: over-constrained (mobility -1): as the input moves, link coupler cannot keep "
                   "its angle to rocker")


def test_a_second_slider_that_its_point_follows_anyway_is_paradoxical(tmp_path):
    """Scott Russell's C runs exactly along the Y axis, so a second slider there holds over the whole motion:
    Gruebler says 0, the linkage moves, and the report says so; C's extent is the closed form's, x = 0 and
    y = 100 sin t over the turn (+-100 mm)."""
    guided = _with(SCOTT_RUSSELL, '[linkage.sliders.head]\npoint = "C"\nguide = "ground"\nangle = 90\n')
    r = _report(tmp_path, guided)
    assert r["mobility"] == 0
    assert ("paradoxical: Gruebler gives mobility 0, yet slider head keeps C on its guide over the whole motion, "
            "so it moves") in r["warnings"]
    (x0, x1), (y0, y1) = r["tracers"]["C"]["x_mm"], r["tracers"]["C"]["y_mm"]
    assert abs(x0) < 1e-9 and abs(x1) < 1e-9
    assert y0 == pytest.approx(-100.0, abs=1e-9) and y1 == pytest.approx(100.0, abs=1e-9)


@pytest.mark.parametrize("command", ["analyze", "build"])
@pytest.mark.parametrize("inputs, message", [
    ('[{ link = "crank", pivot = "O2", range = [80, 100] }, { link = "rocker", pivot = "O4", range = [80, 90] }]',
     "linkage.input: mobility 1 (Gruebler) takes 1 input, not 2: give one input (not a list)"),
    ('[{ link = "crank", pivot = "O2", range = [80, 100] }, { link = "coupler", pivot = "A", relative_to = "crank",'
     ' range = [0, 10] }]', "linkage.input: mobility 1 (Gruebler) takes 1 input, not 2"),
])
def test_two_inputs_on_a_mobility_1_linkage_are_refused(tmp_path, command, inputs, message):
    """A four-bar has mobility 1: its crank sets every pose, and a second input pulls it apart. It was solved as two
    independent inputs, the coupler fixed by both, and then called paradoxical."""
    text = FOURBAR.replace('input = { link = "crank", pivot = "O2" }', f"input = {inputs}")
    assert_refused(tmp_path, text, command, (), message)


def test_two_inputs_on_a_structure_are_refused(tmp_path):
    guided = _with(SLIDER_CRANK, SECOND_SLIDERS["on the crank pin"]).replace(
        'input = { link = "crank", pivot = "O2" }',
        'input = [{ link = "crank", pivot = "O2", range = [80, 100] }, { slider = "ram", range = [0, 1] }]')
    assert_refused(tmp_path, guided, "analyze", (), "linkage.input: mobility 0 (Gruebler): a structure, or a "
                                                    "paradoxical linkage that one input may move, not 2 inputs")


# --------------------------------------------------------------------------------------------- numbers and joints

@pytest.mark.parametrize("command", ["analyze", "build"])
@pytest.mark.parametrize("sets, message", [
    (("linkage.joints.A=[true, 80.0]",), "linkage.joints.A: must be a number, not true or false"),
    (("linkage.joints.B=false",), "linkage.joints.B: must be a number, not true or false"),
    (('linkage.lengths={"O2-A" = true}',), "linkage.lengths.O2-A: must be a number, not true or false"),
    (("linkage.rpm=true",), "linkage.rpm: must be a number, not true or false"),
    (('linkage.input={link = "crank", pivot = "O2", range = [0, true]}',),
     "linkage.input.range: must be a number, not true or false"),
    (('loads=[{point="B", force=[true, 0]}]',), "loads[0].force: must be a number, not true or false"),
    (('loads=[{link="rocker", torque=false}]',), "loads[0].torque: must be a number, not true or false"),
    (("parts.margin=false",), "parts.margin: must be a number, not true or false"),
    (("parts.sheet=[true, 400]",), "parts.sheet: must be a number, not true or false"),
])
def test_true_and_false_are_not_numbers(tmp_path, command, sets, message):
    """pydantic reads a boolean as 1 or 0 wherever a number is asked: in a table of the user's own keys of numbers
    (linkage.joints, linkage.lengths) it was taken as 1 and 0 mm. Every number field refuses it, naming the key."""
    assert_refused(tmp_path, FOURBAR + PARTS, command, sets, message)


def test_true_and_false_are_not_numbers_in_a_slider():
    from camgen.core.errors import SpecError
    from linkgen.spec import validate_spec
    import tomllib

    raw = tomllib.loads(SLIDER_CRANK)
    raw["linkage"]["sliders"]["ram"]["angle"] = True
    with pytest.raises(SpecError, match=r"^linkage\.sliders\.ram\.angle: must be a number, not true or false$"):
        validate_spec(raw)


@pytest.mark.parametrize("command", ["analyze", "build"])
@pytest.mark.parametrize("extra, tracer, message", [
    ("C = [50.0, 50.0]", None, "linkage.joints.C: joint C is on no link: list it in a link of linkage.links"),
    ("P = [100.0, 150.0]", "P", "linkage.joints.P: joint P is on no link"),
])
def test_a_joint_on_no_link_is_refused(tmp_path, command, extra, tracer, message):
    """A joint drawn but held by no link was ignored (a tracer on none traced nothing): refused, naming it. A tracer
    moves with a link, so it must be on one too."""
    text = FOURBAR.replace("[linkage.links]", f"{extra}\n[linkage.links]")
    if tracer:
        text = text.replace('tracers = ["B"]', f'tracers = ["{tracer}"]')
    assert_refused(tmp_path, text, command, (), message)


def test_a_tracer_on_a_link_is_traced(tmp_path):
    """The same point put on the coupler is traced: its extent is that of an independent circle intersection, B
    where the circles of 200 mm about A and 150 mm about O4 meet left of A -> O4 (the drawn side; a crank-rocker
    keeps it), P carried with the line A-B, at 200 001 crank angles."""
    import numpy as np

    text = FOURBAR.replace("[linkage.links]", "P = [100.0, 150.0]\n[linkage.links]").replace(
        'coupler = ["A", "B"]', 'coupler = ["A", "B", "P"]').replace('tracers = ["B"]', 'tracers = ["P"]')
    r = _report(tmp_path, text)
    t = np.linspace(0.0, 2 * math.pi, 200001)
    a = 80.0 * np.column_stack([np.cos(t), np.sin(t)])
    d = np.array([180.0, 0.0]) - a
    dist = np.hypot(*d.T)
    along = (dist ** 2 + 200.0 ** 2 - 150.0 ** 2) / (2 * dist)
    e = d / dist[:, None]
    b = a + along[:, None] * e + np.sqrt(200.0 ** 2 - along ** 2)[:, None] * np.column_stack([-e[:, 1], e[:, 0]])
    a0, b0, p0 = np.array([0.0, 80.0]), np.array([187.41841978558477, 149.81644451756569]), np.array([100.0, 150.0])
    turn = np.arctan2(*(b - a).T[::-1]) - math.atan2(*(b0 - a0)[::-1])
    q = p0 - a0
    p = a + np.column_stack([np.cos(turn) * q[0] - np.sin(turn) * q[1], np.sin(turn) * q[0] + np.cos(turn) * q[1]])
    (x0, x1), (y0, y1) = r["tracers"]["P"]["x_mm"], r["tracers"]["P"]["y_mm"]
    # the dense grid misses an extreme by at most about |P''| h^2 / 8 (h = 3.1e-5 rad): 1e-6 mm is ample
    assert [x0, x1, y0, y1] == pytest.approx([p[:, 0].min(), p[:, 0].max(), p[:, 1].min(), p[:, 1].max()], abs=1e-6)
    assert x0 <= p[:, 0].min() + 1e-12 and x1 >= p[:, 0].max() - 1e-12
