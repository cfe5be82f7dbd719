"""The course's classification in every linkage report, each class checked against the kinematics' own figures.

Every bundled linkage template is designed once; its report's ``classification`` must hold exactly the classes its
kinematics earn, each recomputed here another way: the swings, strokes and full turns from the circuit's output
motions; a dwell and a straight stretch from 3600 poses a turn by sliding windows (numpy, not the classifier's
loops); a toggle clamp from the three joints' collinearity at the ram's lowest pose; a gear pair's reversal from
its teeth (-z1/z2); a ratchet's index from its lever's swing and the wheel's pitch. The guide's table of examples
(docs/guides/classification.md) is the bundled templates' classes, so it cannot drift.
"""
from __future__ import annotations

import math
import re
import tomllib

import numpy as np
import pytest
from numpy.lib.stride_tricks import sliding_window_view

from linkgen.kinematics import motion
from linkgen.kinematics.structure import GROUND
from linkgen.linkage_design import pose_of
from linkgen.mechanisms import classify
from tests.conftest import ROOT

TEMPLATES = sorted(p.stem for p in (ROOT / "templates").glob("*.toml")
                   if "linkage" in (t := tomllib.loads(p.read_text(encoding="utf-8"))) and "sweep" not in t)
TURN = 3600
#: one worker: the module's designs (every bundled linkage template, some 5 s) are built once
pytestmark = pytest.mark.xdist_group("linkgen-classify")


@pytest.fixture(scope="module")
def designs() -> dict:
    import linkgen

    return {name: linkgen.design_linkage(linkgen.load_spec(ROOT / "templates" / f"{name}.toml"))
            for name in TEMPLATES}


def _turn_solution(a):
    x = a.linkage.revolution + 2 * math.pi * np.arange(TURN) / TURN
    return x, a.linkage.solve(x[None, :], strict=False)


def _floating(a, point: str) -> bool:
    s = a.linkage.structure
    fixed = set(s.bodies[GROUND])
    for body in s.holders(point):
        if body == GROUND or body in {i.link for i in s.inputs} or set(s.bodies[body]) & fixed:
            return False
        if any(sl.body == body and sl.guide == GROUND for sl in s.sliders):
            return False
    return True


def _has_dwell(values: np.ndarray, travel: float) -> bool:
    """Some 30 degree window of the turn (cyclic) over which the output stays within 0.5% of its travel."""
    w = TURN * 30 // 360
    windows = sliding_window_view(np.concatenate([values, values[:w]]), w + 1)
    return bool((windows.max(axis=1) - windows.min(axis=1) <= 0.005 * travel).any())


def _has_straight(path: np.ndarray, size: float) -> bool:
    """Some 90 degree window (every 1 degree, cyclic) within 0.25% of its chord of its best line (the minor axis
    of its points' covariance), the chord at least a tenth of the drawing's size."""
    w = TURN // 4
    ext = np.concatenate([path, path[:w]])
    for start in range(0, TURN, TURN // 360):
        pts = ext[start:start + w]
        c = pts - pts.mean(axis=0)
        _, vecs = np.linalg.eigh(c.T @ c)
        along, across = c @ vecs[:, 1], c @ vecs[:, 0]
        chord = along.max() - along.min()
        if chord >= 0.1 * size and np.abs(across).max() <= 0.0025 * chord:
            return True
    return False


def _toggles_at_extreme(a, sol, slider: str, value: np.ndarray) -> bool:
    """At the slider's lowest or highest sampled pose, a link holding its point and another link (neither the
    input, the ground nor the block) meeting it at a joint lie in line within 1 degree, through that joint."""
    s = a.linkage.structure
    sl = s.slider_by_name[slider]
    skip = {GROUND, sl.body, *(i.link for i in s.inputs)}
    for k in (int(np.argmin(value)), int(np.argmax(value))):
        for near in (b for b in s.holders(sl.point) if b not in skip):
            for joint in (p for p in s.bodies[near] if p != sl.point):
                for far_link in (b for b in s.holders(joint) if b not in skip and b != near):
                    for far in (p for p in s.bodies[far_link] if p != joint):
                        u = sol.points[far][k] - sol.points[joint][k]
                        v = sol.points[sl.point][k] - sol.points[joint][k]
                        if abs(u[0] * v[1] - u[1] * v[0]) <= math.sin(math.radians(1.0)) * np.hypot(*u) * np.hypot(*v):
                            return True
    return False


def _expected(name: str, design) -> set[str]:
    """The classes the template's kinematics earn, recomputed."""
    rep, table = design.report, design.spec.linkage
    if table.type == "gear-pair":
        z1, z2 = rep["gears"]["pinion"]["teeth"], rep["gears"]["gear"]["teeth"]
        assert rep["speed_ratio"] == pytest.approx(-z1 / z2 if rep["kind"] == "external" else z1 / z2, rel=1e-8)
        return {"coupling"} | ({"reversing"} if rep["kind"] == "external" else set())
    if table.type == "ratchet":
        lever, wheel = rep["lever"], rep["wheel"]
        assert lever["teeth_per_stroke"] == math.floor(lever["swing_deg"] / wheel["pitch_deg"])
        return {"indexing"} if lever["teeth_per_stroke"] >= 1 and rep["holds"] else set()
    if table.type == "counter":                              # the tens wheel's index after k strokes: floor(k / N)
        lever, wheel, count = rep["lever"], rep["wheel"], rep["count"]
        n = wheel["teeth"] // lever["teeth_per_stroke"]
        assert count["tens_index"] == [k // n % rep["transfer"]["slots"] for k in range(count["strokes"] + 1)]
        return {"indexing", "counter"} if rep["holds"] else {"counter"}
    if table.type == "gear-train":
        if rep["kind"] == "planetary":                        # Willis: the ratio from the members' own speeds
            speeds = rep["planetary"]["speeds"]
            assert rep["ratio"] == pytest.approx(speeds[rep["planetary"]["output"]] / speeds[rep["planetary"]["input"]],
                                                 rel=1e-8)
        return {"coupling"} | ({"reversing"} if rep["ratio"] < 0 else set())
    if table.type == "oldham":
        assert rep["speed_ratio"] == 1.0 and rep["offset_mm"] == pytest.approx(table.offset)
        return {"coupling"}
    if table.type == "trammel":                               # the tracer on its ellipse, the blocks on their slots
        assert rep["ellipse"]["semi_axis_x_mm"] == pytest.approx(abs(table.rod - table.point))
        assert rep["ellipse"]["semi_axis_y_mm"] == pytest.approx(abs(table.point))
        assert rep["block_stroke_mm"] == pytest.approx(2 * table.rod)
        return {"reciprocator", "curve generator"}
    if table.type == "rapson":
        lo, hi = rep["input_range_mm"]
        assert rep["stroke_mm"] == pytest.approx(hi - lo) and rep["stroke_mm"] > 0
        return {"linear actuator"}
    a, _ = pose_of(design.kinematics, table, 0.0)
    out = set()
    full = a.crank and a.ranges is None
    _, sol = _turn_solution(a)
    sliders = a.linkage.structure.slider_by_name
    for out_name, om in a.outputs.items():
        if not a.crank and om.travel > 0:
            out.add("linear actuator")
        if not full:
            continue
        if om.turns:
            out.add("coupling")
            if out_name not in sliders and float(np.mean(sol.omegas[out_name])) < 0:
                out.add("reversing")                          # a geared crank turning the other way
            continue
        out.add("reciprocator" if out_name in sliders else "oscillator")
        value, _, _ = motion.values_of(a.linkage, sol, out_name)
        if _has_dwell(np.unwrap(value) if out_name not in sliders else value, om.travel):
            out.add("hesitation")
        if out_name in sliders and _toggles_at_extreme(a, sol, out_name, value):
            out.add("clamp")
    for point in a.table.tracers:
        if _floating(a, point) and full:
            straight = _has_straight(sol.points[point], a.linkage.structure.size)
            out.add("straight-line generator" if straight else "curve generator")
    return out


@pytest.mark.parametrize("name", TEMPLATES)
def test_each_template_gets_the_classes_its_kinematics_earn(designs, name):
    got = designs[name].report["classification"]
    assert set(got["classes"]) == _expected(name, designs[name])
    assert len(got["rules"]) >= len(got["classes"]) and all(r["because"] for r in got["rules"])
    assert got["classes"] == [c for c in classify.CLASSES if c in got["classes"]]      # the documented order


def test_the_toggle_press_clamps_in_line_and_the_slider_crank_does_not(designs):
    """The ram's lowest pose puts Q, K and R in line (the template's toggle); the slider-crank's dead centres put
    its crank, the input, in line with its rod, which is no clamp."""
    a, _ = pose_of(designs["toggle-press"].kinematics, designs["toggle-press"].spec.linkage, 0.0)
    _, sol = _turn_solution(a)
    k = int(np.argmin(sol.points["R"][:, 1]))
    u, v = sol.points["Q"][k] - sol.points["K"][k], sol.points["R"][k] - sol.points["K"][k]
    assert abs(u[0] * v[1] - u[1] * v[0]) / (np.hypot(*u) * np.hypot(*v)) < math.sin(math.radians(0.2))
    assert "clamp" in designs["toggle-press"].report["classification"]["classes"]
    assert "clamp" not in designs["slider-crank"].report["classification"]["classes"]


def test_every_class_of_the_list_has_its_rule_and_the_single_dwell_its_dwell(designs):
    """The single-dwell six-bar's comment: its output turns 0.127 degrees over 80 degrees of crank."""
    rules = designs["single-dwell"].report["classification"]["rules"]
    dwell = next(r["because"] for r in rules if r["class"] == "hesitation")
    assert float(re.search(r"over ([0-9.]+) degrees", dwell).group(1)) >= 80.0
    hoekens = next(r["because"] for r in designs["hoekens"].report["classification"]["rules"]
                   if r["class"] == "straight-line generator")
    assert float(re.search(r"over ([0-9.]+) degrees", hoekens).group(1)) >= 180.0


def _table(designs) -> str:
    rows = []
    for cls in classify.CLASSES:
        names = [n for n in TEMPLATES if cls in designs[n].report["classification"]["classes"]]
        rows.append(f"| {cls} | {', '.join(f'`{n}`' for n in names) or 'none bundled'} |")
    return "\n".join(["| class | bundled templates |", "|---|---|", *rows])


def test_the_guide_lists_the_bundled_templates_of_each_class(designs):
    text = (ROOT / "docs" / "guides" / "classification.md").read_text(encoding="utf-8")
    block = text.split("<!-- classes: begin -->")[1].split("<!-- classes: end -->")[0].strip()
    assert block == _table(designs), "regenerate the table between the markers:\n" + _table(designs)
