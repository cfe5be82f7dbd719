"""The slack band (``[slack]``, :mod:`linkgen.slack`, :mod:`linkgen.kinematics.sensitivity`).

* The first-order response against independent references: a four-bar's rocker angle differentiated in its closed
  form (50-digit mpmath) for each link length, a slider-crank's travel in its closed form for the slot's offset and
  the crank's length, and central differences of perturbed linkages solved by the project's solver for every
  parameter of six linkages (the dedicated ones drawn as general linkages, and general ones with plates, sliders,
  blocks and slotted links).
* Monte Carlo: seeded samples of the slack, each linkage assembled and solved over the motion by the project's
  solver, lie inside the band widened by a stated margin for the second-order error; that error, for the same
  samples scaled down, shrinks quadratically; the worst case the band states is reached (to second order) by the
  offsets it picks.
* As the clearance goes to 0 the band shrinks to the nominal path linearly, and so do the samples' offsets.
* Binding: where the band says a dyad may reach its dead point, the worst-case linkage does not reach that pose,
  and a little before it does.
* Bad input: one line naming the field, exit code 2, nothing written; every dedicated type and the general linkage
  report a band (strict JSON), its figure and its page.
"""
from __future__ import annotations

import functools
import json
import math
import tomllib
from pathlib import Path

import mpmath
import numpy as np
import pytest
from click.testing import CliRunner

from camgen.core.spec import apply_overrides
from linkgen.cli import main as linkgen
from linkgen.linkage_design import design_linkage
from linkgen.mechanisms import MECHANISMS
from linkgen.kinematics.sensitivity import perturbed, response, sample, slack_model, worst_case
from linkgen.spec import validate_spec
from tests.conftest import ROOT

#: a crank-rocker with a coupler point (ground 180, crank 80, coupler 200, rocker 150 mm)
FOURBAR = """name = "fb"
[linkage]
type = "four-bar"
ground = 180.0
crank = 80.0
coupler = 200.0
rocker = 150.0
point_distance = 100.0
point_angle = 30.0
[parts]
width = 14.0
thickness = 4.0
pin_diameter = 4.0
clearance = 0.2
kerf = 0.15
[slack]
monte_carlo = 0
"""
#: a slider-crank: crank 50, rod 200 mm, the slider's line 20 mm above the crank's pivot
SLIDER_CRANK = """name = "sc"
[linkage]
type = "slider-crank"
crank = 50.0
rod = 200.0
offset = 20.0
[parts]
width = 12.0
thickness = 4.0
pin_diameter = 4.0
[slack]
monte_carlo = 0
"""
PARTS = {"width": 8.0, "thickness": 3.0, "pin_diameter": 3.0}


def _spec(text: str, **changes: object):
    return validate_spec(apply_overrides(tomllib.loads(text), list(changes.items())))


def _template(name: str, **changes: object):
    raw = tomllib.loads((ROOT / "templates" / f"{name}.toml").read_text())
    raw = {**raw, "parts": raw.get("parts", PARTS), "slack": {"monte_carlo": 0}}
    return validate_spec(apply_overrides(raw, list(changes.items())))


def _band(spec):
    return design_linkage(spec).slack.band


# ------------------------------------------------------------------------------------------ closed forms


def _rocker_angle(l1, l2, l3, l4, t2, side):
    """The four-bar's rocker direction (rad) at crank angle t2 in closed form: O4 = (l1, 0), A = l2 (cos t2,
    sin t2), B on the circles l3 about A and l4 about O4, on ``side`` of the line O4 -> A."""
    ax, ay = l2 * mpmath.cos(t2) - l1, l2 * mpmath.sin(t2)
    z = mpmath.sqrt(ax**2 + ay**2)
    return mpmath.atan2(ay, ax) + side * mpmath.acos((z**2 + l4**2 - l3**2) / (2 * z * l4))


def test_the_rocker_angle_band_is_the_closed_form_sensitivity_to_each_length():
    """With no clearance the rocker's band is the sum over the four links of the tolerance times |d theta4 / d L|,
    each derivative of the closed form differentiated at 50 digits, at every one of the 361 poses; one link's own
    tolerance (``slack.links``) weighs its own term."""
    mpmath.mp.dps = 50
    lengths = {"ground": 180.0, "crank": 80.0, "coupler": 200.0, "rocker": 150.0}
    spec = _spec(FOURBAR, **{"parts.clearance": 0.0, "parts.kerf": 0.0, "slack.length_tolerance": 0.05,
                             "slack.links": {"crank": 0.02}})
    band = _band(spec)
    assert band.play.radial == 0
    rocker = next(o for o in band.outputs if o.name == "rocker")
    s = band.analysis.linkage.structure
    columns = {"ground": band.model.length("ground", "O4"), "crank": band.model.length("crank", "A"),
               "coupler": band.model.length("coupler", "B"), "rocker": band.model.length("rocker", "B")}
    b0 = np.asarray(s.points["B"]) - np.asarray(s.points["O4"])
    drawn = math.atan2(b0[1], b0[0])
    tolerance = {"ground": 0.05, "crank": 0.02, "coupler": 0.05, "rocker": 0.05}
    checked = 0
    for k in range(0, len(band.inputs), 8):
        t2 = mpmath.mpf(float(band.inputs[k]))
        theta4 = float(rocker.value[k]) + drawn
        side = min((1, -1), key=lambda sd: abs(math.remainder(float(_rocker_angle(*lengths.values(), t2, sd)) - theta4,
                                                              2 * math.pi)))
        assert abs(math.remainder(float(_rocker_angle(*lengths.values(), t2, side)) - theta4, 2 * math.pi)) < 1e-9
        expected = 0.0
        for link, column in columns.items():
            def angle(value, link=link, t2=t2, side=side):
                return _rocker_angle(*{**lengths, link: value}.values(), t2, side)

            derivative = float(mpmath.diff(angle, lengths[link]))
            assert band.response.turns["rocker"][k, column] == pytest.approx(derivative, rel=1e-9, abs=1e-14)
            expected += tolerance[link] * abs(derivative)
        assert rocker.half_width[k] == pytest.approx(expected, rel=1e-9)
        checked += 1
    assert checked == 46


def test_the_slider_travel_answers_the_slot_and_the_crank_in_closed_form():
    """x = R cos t + sqrt(L^2 - (R sin t - e)^2): the pin's offset across its slot and the slot's line both move e,
    so dx/de = (R sin t - e) / sqrt(L^2 - (R sin t - e)^2); the crank pin's offset along the crank (the crank drawn
    at 0) and the crank's length both move R: dx/dR = cos t - (R sin t - e) sin t / sqrt(...)."""
    band = _band(_spec(SLIDER_CRANK))
    r, big_l, e = 50.0, 200.0, 20.0
    t = band.inputs
    root = np.sqrt(big_l**2 - (r * np.sin(t) - e) ** 2)
    travel = band.response.points["B"][:, 0, :]
    model = band.model
    for column in (model.slot("slider"), model.line("slider")):
        np.testing.assert_allclose(travel[:, column], (r * np.sin(t) - e) / root, rtol=1e-9, atol=1e-12)
    hole = model.hole("crank", "A")
    for column in (hole, model.length("crank", "A")):
        np.testing.assert_allclose(travel[:, column], np.cos(t) - (r * np.sin(t) - e) * np.sin(t) / root,
                                   rtol=1e-9, atol=1e-12)
    # the pin's across-slot offset moves B's y by itself, and nothing else does but the line
    np.testing.assert_allclose(band.response.points["B"][:, 1, model.slot("slider")], 1.0, rtol=1e-12)
    np.testing.assert_allclose(band.tracers[0].half_width, 0.1 + 0.05, rtol=1e-12)   # play + the line's tolerance


CASES = {
    "four-bar": lambda: _spec(FOURBAR),
    "slider-crank": lambda: _spec(SLIDER_CRANK),
    "crank-shaper": lambda: _spec(SLIDER_CRANK.replace('type = "slider-crank"\ncrank = 50.0\nrod = 200.0\n'
                                                       'offset = 20.0', 'type = "crank-shaper"\ncrank = 60.0\n'
                                                       'ground = 150.0\nlever = 300.0')),
    "jansen": lambda: _template("jansen"),
    "shaper": lambda: _template("shaper"),
    "toggle-press": lambda: _template("toggle-press"),
    "eightbar-triad": lambda: _template("eightbar-triad"),      # a class-III group: its links' slack too
}


def _cases(names) -> list:
    """``names`` as parameters, each in its own xdist group: one worker designs a case's band for every test of it."""
    return [pytest.param(name, marks=pytest.mark.xdist_group(f"slack-band-{name}")) for name in names]


@functools.cache
def _case_band(case: str):
    """The band of ``CASES[case]``, designed once for the tests that read it (three of them; none changes it)."""
    return _band(CASES[case]())


def _kinked(band, k):
    """Whether dyad k's transmission angle has a kink at some pose (RRP at 90 degrees, RPR with the slot through
    its pivot): its one-sided derivative is not a central difference's."""
    d = band.dyads[k]
    return d.kind != "RRR" and bool(np.any(np.abs(d.transmission - math.pi / 2) < 1e-6))


@pytest.mark.parametrize("case", _cases(sorted(CASES)))
def test_the_response_is_the_solvers_own_to_central_differences(case):
    """Every column of the response (every point, every body's turn, every dyad's transmission angle but at a
    kink) against central differences (+-1e-5 mm) of the perturbed linkages solved by the project's solver: to
    1e-6 of the response's size."""
    band = _case_band(case)
    linkage, model = band.analysis.linkage, band.model
    x = band.inputs[None, ::6]
    r = response(linkage, linkage.solve(x, strict=False, derivatives=False), model)
    h = 1e-5
    for j in range(model.size):
        step = np.zeros(model.size)
        step[j] = h
        up, down = perturbed(linkage, step, model), perturbed(linkage, -step, model)
        su, sd = up.solve(x), down.solve(x)
        assert su.ok.all() and sd.ok.all()
        for p, grad in r.points.items():
            fd = (su.points[p] - sd.points[p]) / (2 * h)
            np.testing.assert_allclose(grad[:, :, j], fd, atol=1e-6 * max(1.0, np.abs(grad).max()), err_msg=p)
        for b, grad in r.turns.items():
            turn = np.remainder(su.angle(b) + up.turns[b] - sd.angle(b) - down.turns[b] + math.pi, 2 * math.pi)
            fd = (turn - math.pi) / (2 * h)
            np.testing.assert_allclose(grad[:, j], fd, atol=1e-6 * max(1.0, np.abs(grad).max()), err_msg=b)
        for k, grad in enumerate(r.transmission):
            if not _kinked(band, k):
                fd = (su.dyads[k].transmission - sd.dyads[k].transmission) / (2 * h)
                np.testing.assert_allclose(grad[:, j], fd, atol=1e-6 * max(1.0, np.abs(grad).max()))


# ------------------------------------------------------------------------------------------- Monte Carlo

#: the margin (a fraction of the widest band) stated for the second-order error at each case's own slack (play
#: 0.1 mm, lengths +-0.05 mm): Jansen's leg passes a transmission angle of 8.6 degrees, where its sensitivities
#: grow sixfold and their curvature with them
MARGIN = {"four-bar": 0.01, "slider-crank": 0.01, "crank-shaper": 0.01, "jansen": 0.2, "shaper": 0.01,
          "toggle-press": 0.01, "eightbar-triad": 0.08}
#: the eight-bar's triad hangs on bars of 70 to 96 mm from a coupler point 45 mm off its bar, and every one of its
#: 52 parameters at its bound adds to the second-order error alike: at the worst case's offsets it reaches 6.2 % of
#: the tracer F's widest band (0.024 of 0.39 mm; 2 % in Monte Carlo) and falls by 4 as they halve (checked)
#: Monte Carlo samples a case
COUNT = 30
#: the fraction of the band the samples must reach: a third, but for the eight-bar, whose 52 parameters (20 pin
#: holes) its 30 samples line up less often (its largest reach is 0.33 of the worst case's sum)
REACH = {"eightbar-triad": 0.3}


def _offsets(band, params):
    """A sample's offsets from the nominal motion over the band's inputs: each tracer's (n, 2) mm and each output's
    (n,), and the poses compared (reached from the drawing without binding, and reached by the sample)."""
    linkage, s = band.analysis.linkage, band.analysis.linkage.structure
    made = perturbed(linkage, params, band.model)
    sol = made.solve(band.inputs[None, :])
    out = {t.name: sol.points[t.name] - t.path for t in band.tracers}
    for o in band.outputs:
        if o.rocker:
            turned = sol.angle(o.name) + made.turns[o.name] - o.value
            out[o.name] = np.remainder(turned + math.pi, 2 * math.pi) - math.pi
        else:
            sl = s.slider_by_name[o.name]
            u = np.array([math.cos(sl.angle), math.sin(sl.angle)])
            out[o.name] = (sol.points[sl.point] - band.solution.points[sl.point]) @ u
    return out, band.reached & sol.ok


def _predicted(band, params):
    r = band.response
    out = {t.name: r.points[t.name] @ params for t in band.tracers}
    for o in band.outputs:
        if o.rocker:
            out[o.name] = r.turns[o.name] @ params
        else:
            sl = band.analysis.linkage.structure.slider_by_name[o.name]
            out[o.name] = r.points[sl.point] @ params @ np.array([math.cos(sl.angle), math.sin(sl.angle)])
    return out


@pytest.mark.parametrize("case", _cases(sorted(CASES)))
def test_monte_carlo_lies_inside_the_band_and_its_second_order_error_shrinks_quadratically(case):
    """COUNT seeded samples, each solved over the 361 poses: (1) the band's first-order offset of each sample is
    within the band at every pose (the worst case bounds it); (2) the solved offsets, across each tracer's path and
    of each output, lie within the band widened by MARGIN of its widest place, and so does their difference from
    the first-order offsets (the second-order error); (3) that difference (a tracer's in any direction), for the
    same samples halved and quartered, falls by 4 each time (3.5 to 4.5: second order); (4) the samples reach a
    fair part of the band (at least a third)."""
    band = _case_band(case)
    assert band.reached.any()
    widest = {t.name: float(np.max(t.half_width[band.reached])) for t in band.tracers}
    widest.update({o.name: float(np.max(o.half_width[band.reached])) for o in band.outputs})
    half = {t.name: t.half_width for t in band.tracers} | {o.name: o.half_width for o in band.outputs}
    normal = {t.name: t.normal for t in band.tracers}
    errors = {scale: dict.fromkeys(half, 0.0) for scale in (1.0, 0.5, 0.25)}
    across_error = dict.fromkeys(half, 0.0)
    reach = dict.fromkeys(half, 0.0)
    for params in sample(band.model, band.bounds, np.random.default_rng(2), COUNT):
        for scale in errors:
            offsets, ok = _offsets(band, scale * params)
            predicted = _predicted(band, scale * params)
            assert ok[band.reached].mean() > 0.95
            for name, offset in offsets.items():
                linear, error = predicted[name], offset - predicted[name]
                if name in normal:
                    linear, offset = (np.einsum("ni,ni->n", v, normal[name]) for v in (linear, offset))
                    error = np.linalg.norm(error, axis=1)          # along the path too
                across = np.abs(offset - linear)
                bound = scale * half[name][ok]
                assert np.all(np.abs(linear[ok]) <= bound * (1 + 1e-12)), name
                if scale == 1.0:
                    assert np.all(np.abs(offset[ok]) <= bound + MARGIN[case] * widest[name]), name
                    reach[name] = max(reach[name], float(np.max(np.abs(offset[ok]) / bound)))
                    across_error[name] = max(across_error[name], float(np.max(across[ok])))
                errors[scale][name] = max(errors[scale][name], float(np.max(np.abs(error[ok]))))
    for name in half:
        e1, e2, e4 = (errors[s][name] for s in (1.0, 0.5, 0.25))
        assert across_error[name] <= MARGIN[case] * widest[name], name
        assert 3.5 <= e1 / e2 <= 4.5 and 3.5 <= e2 / e4 <= 4.5, (name, e1, e2, e4)
        assert reach[name] >= REACH.get(case, 1 / 3), (name, reach[name])


@pytest.mark.parametrize("case", _cases(["four-bar", "jansen", "shaper", "eightbar-triad"]))
def test_the_band_is_reached_by_the_offsets_it_picks(case):
    """At each of a few poses, the slack that the band's worst case picks for a tracer's offset across its path (each
    pin's offset along its gradient, each other slack at its bound with the gradient's sign) gives a linkage that,
    solved by the project's solver, lands on the band's edge there: within the stated margin, and closer by 4 each
    time the slack is halved (second order), unless it lands there to rounding (a ram on its straight guide)."""
    band = _case_band(case)
    k2 = 2 * len(band.model.holes)
    for t in band.tracers:
        widest = float(np.max(t.half_width[band.reached]))
        for i in np.flatnonzero(band.reached)[::45]:
            g = np.einsum("i,ip->p", t.normal[i], band.response.points[t.name][i])
            worst = np.sign(g) * band.bounds
            pairs = np.hypot(g[0:k2:2], g[1:k2:2])
            for axis in (0, 1):
                worst[axis:k2:2] = band.bounds[axis:k2:2] * np.divide(g[axis:k2:2], pairs, out=np.zeros_like(pairs),
                                                                      where=pairs > 0)
            assert g @ worst == pytest.approx(t.half_width[i], rel=1e-12)
            gaps = []
            for scale in (1.0, 0.5, 0.25):
                offsets, ok = _offsets(band, scale * worst)
                assert ok[i]
                gaps.append(float(offsets[t.name][i] @ t.normal[i]) - scale * t.half_width[i])
            assert abs(gaps[0]) <= MARGIN[case] * widest, (i, gaps)
            if abs(gaps[1]) > 1e-9:
                assert 3.3 <= gaps[1] / gaps[2] <= 4.7, (i, gaps)


def test_the_band_shrinks_to_the_nominal_path_linearly_in_the_clearance():
    """With no length tolerance the band is the play times a fixed shape (to 1e-12), its edges reach the path as
    the clearance goes to 0, and the samples' largest offsets shrink in proportion (within 1 % from 0.02 to
    0.002 mm); with no clearance at all the samples are the nominal linkage (to 1e-9 mm)."""
    shapes, offsets = {}, {}
    for clearance in (0.2, 0.02, 0.002, 0.0):
        band = _band(_spec(FOURBAR, **{"parts.clearance": clearance, "parts.kerf": 0.0,
                                       "slack.length_tolerance": 0.0}))
        tracer = band.tracers[0]
        assert band.play.radial == pytest.approx(clearance / 2, rel=1e-12, abs=0)
        largest = 0.0
        for params in sample(band.model, band.bounds, np.random.default_rng(5), 10):
            moved, ok = _offsets(band, params)
            largest = max(largest, float(np.max(np.linalg.norm(moved[tracer.name][ok], axis=1))))
        if clearance == 0.0:
            assert np.all(tracer.half_width == 0) and largest < 1e-9
            continue
        shapes[clearance] = tracer.half_width / clearance
        offsets[clearance] = largest / clearance
    np.testing.assert_allclose(shapes[0.02], shapes[0.2], rtol=1e-12)
    np.testing.assert_allclose(shapes[0.002], shapes[0.2], rtol=1e-12)
    assert offsets[0.02] == pytest.approx(offsets[0.002], rel=0.01)
    assert offsets[0.2] == pytest.approx(offsets[0.002], rel=0.1)


# ----------------------------------------------------------------------------------------------- binding

#: a non-Grashof triple rocker (ground 200, crank 80, coupler 90, rocker 100 mm): its crank stops where the
#: coupler and rocker come in line
TRIPLE_ROCKER = FOURBAR.replace("ground = 180.0\ncrank = 80.0\ncoupler = 200.0\nrocker = 150.0\n"
                                "point_distance = 100.0\npoint_angle = 30.0",
                                "ground = 200.0\ncrank = 80.0\ncoupler = 90.0\nrocker = 100.0")


def _closing(band, where):
    """The slack that brings the triple rocker's dyad nearest in line at crank angle ``where`` (rad) fastest towards
    it (each pin's offset against the gradient of that distance from in line, the lengths at their bounds), and
    that distance (mm) and its band there."""
    linkage = band.analysis.linkage
    inline = response(linkage, linkage.solve(np.array([[where]]), derivatives=False), band.model).inline[0]
    margin, g = min(((inline.extended[0], inline.d_extended[0]), (inline.folded[0], inline.d_folded[0])),
                    key=lambda pair: pair[0])
    k2 = 2 * len(band.model.holes)
    worst = -np.sign(g) * band.bounds
    pairs = np.hypot(g[0:k2:2], g[1:k2:2])
    for axis in (0, 1):
        worst[axis:k2:2] = -band.bounds[axis:k2:2] * np.divide(g[axis:k2:2], pairs, out=np.zeros_like(pairs),
                                                               where=pairs > 0)
    return worst, float(margin), float(-g @ worst)


def test_where_it_binds_the_worst_case_linkage_stops():
    """The triple rocker binds next to each end of its crank's range (its toggles, at +-71.2236 degrees), over
    0.682 degrees: twice what the transmission angle's band gives (the angle goes like the square root of the
    distance to the toggle; the bars' distance from in line, whose band decides, like the distance itself). The
    linkage whose slack brings it in line fastest at the range's edge stops there, to 1e-3 of the range's width
    (second order); half-way into the range, the one for that angle does not reach it; a degree outside, it
    does."""
    design = design_linkage(_spec(TRIPLE_ROCKER))
    band = design.slack.band
    binds = design.report["slack"]["binds"]
    assert len(binds) == 2 and all(b["joint"] == "B" for b in binds)
    assert any("binds: dyad coupler-rocker (joint B)" in w for w in design.report["slack"]["warnings"])
    x = band.inputs
    linkage = band.analysis.linkage
    for b in binds:
        lo, hi = (math.remainder(math.radians(v) - x[0], 2 * math.pi) + x[0] for v in b["input_deg"])
        toggle = min((lo, hi), key=lambda v: min(abs(v - x[0]), abs(v - x[-1])))
        edge = hi if toggle == lo else lo
        assert math.degrees(abs(edge - toggle)) == pytest.approx(0.682, abs=1e-3)
        worst, margin, h = _closing(band, edge)
        assert h == pytest.approx(margin, rel=1e-4)
        made = perturbed(linkage, worst, band.model)
        reached, stopped = edge + (edge - toggle), toggle
        assert made.solve(np.array([[reached]])).ok[0] and not made.solve(np.array([[stopped]])).ok[0]
        for _ in range(50):
            middle = 0.5 * (reached + stopped)
            if made.solve(np.array([[middle]])).ok[0]:
                reached = middle
            else:
                stopped = middle
        assert abs(reached - edge) <= 1e-3 * abs(edge - toggle)
        for where, reaches in ((0.5 * (edge + toggle), False), (edge + (edge - toggle) / abs(edge - toggle)
                                                                 * math.radians(1), True)):
            made = perturbed(linkage, _closing(band, where)[0], band.model)
            assert bool(made.solve(np.array([[where]])).ok[0]) is reaches, (b, math.degrees(where))


# ------------------------------------------------------------------------------------------------- input


def _run(tmp_path: Path, text: str, command: str, *sets: str, flags: tuple[str, ...] = ()):
    template = tmp_path / "t.toml"
    template.write_text(text)
    out = tmp_path / "out"
    args = [command, str(template), "-o", str(out), *flags]
    for s in sets:
        args += ["--set", s]
    return CliRunner().invoke(linkgen, args), out


NO_PARTS = FOURBAR[:FOURBAR.index("[parts]")] + "[slack]\n"
REFUSED = [
    (FOURBAR, ("parts.clearance=4.5",), "parts.clearance: with [slack], must be >= 0 and < the pin's diameter (4 mm)"),
    (FOURBAR, ("slack.clearance=4",), "slack.clearance: with [slack], must be >= 0 and < the pin's diameter (4 mm)"),
    (FOURBAR, ("slack.clearance=6",), "slack.clearance: must be >= 0 and <= 5 mm (got 6)"),
    (FOURBAR, ("slack.length_tolerance=-0.05",), "slack.length_tolerance: must be >= 0 and <= 5 mm (got -0.05)"),
    (FOURBAR, ("slack.links.crank=-1",), "slack.links.crank: must be >= 0 and <= 5 mm (got -1"),
    (FOURBAR, ("slack.links.foot=0.1",), "slack.links.foot: no link 'foot' in this linkage (links: ground, crank"),
    (FOURBAR, ("slack.monte_carlo=1000000000",), "slack.monte_carlo: must be >= 0 and <= 10000 (got 1000000000)"),
    (FOURBAR, ("slack.monte_carlo=-1",), "slack.monte_carlo: must be >= 0 and <= 10000 (got -1)"),
    (FOURBAR, ("slack.seed=-3",), "slack.seed: must be >= 0 (got -3)"),
    (FOURBAR, ('slack.process="laser"',), "slack.process: unknown value 'laser'; one of cut, printed"),
    (FOURBAR, ("slack.lenght_tolerance=0.1",), "slack.lenght_tolerance: unknown key (did you mean 'length_tolerance'"),
    (FOURBAR, ('linkage.input="rocker"',), "slack: a four-bar of this kind cannot be drawn as a general linkage"),
    (NO_PARTS, (), "slack: the joints' play comes from the [parts] table's pin_diameter, clearance and kerf"),
]


@pytest.mark.parametrize("command", ["analyze", "build"])
@pytest.mark.parametrize(("text", "sets", "message"), REFUSED)
def test_bad_slack_is_one_line_naming_the_field_and_writes_nothing(tmp_path, command, text, sets, message):
    result, out = _run(tmp_path, text, command, *sets)
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    assert result.stderr.startswith(f"error: {message}") and result.stderr.count("\n") == 1, result.stderr
    assert not out.exists()


#: a five-bar of two inputs, and a parallelogram with a redundant link (paradoxical)
FIVE_BAR = """name = "five"
[linkage]
type = "linkage"
ground = ["O1", "O2"]
input = [{ link = "left", pivot = "O1", range = [80, 100] }, { link = "right", pivot = "O2", range = [80, 100] }]
[linkage.joints]
O1 = [0.0, 0.0]
O2 = [60.0, 0.0]
A = [0.0, 50.0]
B = [60.0, 50.0]
C = [30.0, 120.0]
[linkage.links]
left = ["O1", "A"]
right = ["O2", "B"]
la = ["A", "C"]
lb = ["B", "C"]
[parts]
width = 12.0
thickness = 4.0
pin_diameter = 4.0
[slack]
"""
PARALLELOGRAM = """name = "par"
[linkage]
type = "linkage"
ground = ["O1", "O2", "O3"]
input = { link = "a", pivot = "O1" }
[linkage.joints]
O1 = [0.0, 0.0]
O2 = [50.0, 0.0]
O3 = [100.0, 0.0]
A = [0.0, 40.0]
B = [50.0, 40.0]
C = [100.0, 40.0]
[linkage.links]
a = ["O1", "A"]
b = ["O2", "B"]
c = ["O3", "C"]
top = ["A", "B", "C"]
[parts]
width = 12.0
thickness = 4.0
pin_diameter = 4.0
[slack]
"""


@pytest.mark.parametrize(("text", "message"), [
    (FIVE_BAR, "slack: the band is for a linkage of one input"),
    (PARALLELOGRAM, "slack: the linkage has redundant constraints"),
])
def test_linkages_no_first_order_band_describes_are_refused(tmp_path, text, message):
    result, out = _run(tmp_path, text, "analyze")
    assert result.exit_code == 2 and result.stderr.startswith(f"error: {message}"), result.output
    assert result.stderr.count("\n") == 1 and not out.exists()


DEDICATED = {
    "four-bar": 'type = "four-bar"\nground = 180.0\ncrank = 80.0\ncoupler = 200.0\nrocker = 150.0\n'
                'point_distance = 100.0',
    "slider-crank": 'type = "slider-crank"\ncrank = 50.0\nrod = 200.0\noffset = 20.0',
    "scotch-yoke": 'type = "scotch-yoke"\ncrank = 40.0',
    "whitworth": 'type = "whitworth"\ncrank = 60.0\nground = 30.0\narm = 50.0\nrod = 150.0',
    "crank-shaper": 'type = "crank-shaper"\ncrank = 60.0\nground = 150.0\nlever = 300.0',
    "chebyshev": 'type = "chebyshev"\nsize = 25.0',
    "hoekens": 'type = "hoekens"\nsize = 25.0',
    "roberts": 'type = "roberts"\nsize = 25.0',
    "watt": 'type = "watt"\nsize = 25.0',
}


#: mechanisms not drawn as bars and pins (gears, pawls, the couplings' slotted discs and blocks), by the bundled
#: template of each: no slack band (refused in one line)
HIGHER_PAIRS = {"gear-pair": "gear-pair", "ratchet": "ratchet", "gear-train": "planetary-train",
                "oldham": "oldham-coupling", "trammel": "elliptic-trammel", "rapson": "rapson-slide",
                "counter": "counter"}


def test_every_dedicated_type_is_covered():
    assert set(DEDICATED) == set(MECHANISMS) - {"linkage", *HIGHER_PAIRS}


@pytest.mark.parametrize("kind", sorted(HIGHER_PAIRS))
def test_a_mechanism_of_gears_or_pawls_refuses_slack_in_one_line(tmp_path, kind):
    from linkgen.cli import main

    path = tmp_path / "t.toml"
    path.write_text((ROOT / "templates" / f"{HIGHER_PAIRS[kind]}.toml").read_text(encoding="utf-8") + "\n[slack]\n")
    result = CliRunner().invoke(main, ["analyze", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: slack: ") and result.output.count("\n") == 1, result.output
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("kind", sorted(DEDICATED))
def test_every_dedicated_type_reports_its_band(tmp_path, kind):
    """Each dedicated type (drawn as a general linkage) reports a band for its tracer and outputs in strict JSON,
    a Monte Carlo check with no pose outside the band, the slack figure and the band on its page."""
    text = (f'name = "x"\n[linkage]\n{DEDICATED[kind]}\n[parts]\nwidth = 12.0\nthickness = 4.0\npin_diameter = 4.0\n'
            "[slack]\nmonte_carlo = 20\n")
    result, out = _run(tmp_path, text, "analyze", flags=("--figures",))
    assert result.exit_code == 0, result.output

    def refuse(constant: str) -> None:
        raise AssertionError(f"the JSON holds {constant}")

    report = json.loads((out / "x.json").read_text(), parse_constant=refuse)["slack"]
    assert report["tracers"] and report["outputs"]
    assert all(t["width_max_mm"] > 0 for t in report["tracers"].values())
    mc = report["monte_carlo"]
    assert mc["assembled"] == 20 and mc["compared_poses"] > 0 and mc["outside"] == 0
    assert (out / "x-slack.png").stat().st_size > 0 and (out / "x-slack.svg").stat().st_size > 0
    page = (out / "x.html").read_text()
    assert "slack band width" in page and "slack band round the tracers" in page
    assert "slack:" in result.output and "Monte Carlo:" in result.output


def test_a_general_linkage_reports_its_band_and_the_console_says_it(tmp_path):
    text = (ROOT / "templates" / "jansen.toml").read_text() + "\n[slack]\nmonte_carlo = 10\nlength_tolerance = 0.02\n"
    result, out = _run(tmp_path, text, "analyze", 'output.formats=["json"]')
    assert result.exit_code == 0, result.output
    report = json.loads((out / "jansen.json").read_text())["slack"]
    assert set(report["tracers"]) == {"G"} and set(report["outputs"]) == {"hip", "bar_c"}
    assert report["parameters"] == {"holes": 17, "slots": 0, "lengths": 10, "lines": 0}
    g = report["tracers"]["G"]
    assert f"tracer G: band up to {g['width_max_mm']:.4g} mm wide" in result.output


def test_the_console_summary_states_the_reports_band_in_user_units(tmp_path):
    """The console's slack lines repeat the report's figures in mm and degrees: the pins' fit, each tracer's widest
    band and where (input and place), each output's band and change of swing or stroke, the Monte Carlo count and
    reach; a slider-crank's slider in mm; a triple rocker warns where it binds."""
    result, out = _run(tmp_path, FOURBAR, "analyze", "slack.monte_carlo=5", 'output.formats=["json"]')
    assert result.exit_code == 0, result.output
    sl = json.loads((out / "fb.json").read_text())["slack"]
    p, rocker, mc = sl["tracers"]["P"], sl["outputs"]["rocker"], sl["monte_carlo"]
    assert sl["play_mm"] == pytest.approx(0.1, rel=1e-12)
    lines = [
        "slack: pins 4 mm in holes of 4.2 mm (cut), play 0.1 mm; lengths within +-0.05 mm",
        f"  tracer P: band up to {p['width_max_mm']:.4g} mm wide at input {p['at_input_deg']:.6g} deg "
        f"({p['x_mm']:.4g}, {p['y_mm']:.4g} mm), {p['width_mean_mm']:.4g} mm on average",
        f"  rocker: within +-{rocker['band_max_deg']:.4g} deg (most at input {rocker['at_input_deg']:.6g} deg); its "
        f"swing by up to {rocker['swing_change_deg']:.4g} deg",
        f"  Monte Carlo: 5 of 5 samples (seed 1), {mc['compared_poses']} poses, reach "
        f"{100 * max(mc['reach'].values()):.3g} % of the band; 0 poses outside it",
    ]
    assert "\n".join(lines) in result.output
    assert 0 < rocker["band_max_deg"] < 5 and 0 < p["width_max_mm"] < 10
    result, out = _run(tmp_path, SLIDER_CRANK, "analyze", 'output.formats=["json"]')
    assert result.exit_code == 0, result.output
    slider = json.loads((out / "sc.json").read_text())["slack"]["outputs"]["slider"]
    assert (f"  slider: within +-{slider['band_max_mm']:.4g} mm (most at input {slider['at_input_deg']:.6g} deg); "
            f"its stroke by up to {slider['stroke_change_mm']:.4g} mm") in result.output
    result, _ = _run(tmp_path, TRIPLE_ROCKER, "analyze", 'output.formats=["json"]')
    assert result.exit_code == 0, result.output
    assert result.output.count("warning: binds: dyad coupler-rocker (joint B) may reach its dead point") == 2


def test_the_holes_as_made_follow_the_process_and_a_measured_clearance():
    """A cut hole is drawn pin + clearance - kerf and burnt open by the kerf, a printed one is drawn as made: both
    pin + clearance; a measured clearance overrides both."""
    cut = _band(_spec(FOURBAR)).play
    printed = _band(_spec(FOURBAR, **{"slack.process": "printed"})).play
    measured = _band(_spec(FOURBAR, **{"slack.clearance": 0.5})).play
    assert (cut.drawn, cut.made, cut.radial) == pytest.approx((4.05, 4.2, 0.1), rel=1e-12)
    assert (printed.drawn, printed.made) == pytest.approx((4.2, 4.2), rel=1e-12)
    assert measured.made == pytest.approx(4.5, rel=1e-12) and measured.measured
    b1, b2 = _band(_spec(FOURBAR)), _band(_spec(FOURBAR, **{"slack.clearance": 0.4}))
    assert worst_case(b2.response.turns["rocker"], b2.model, b2.bounds)[0] > \
        worst_case(b1.response.turns["rocker"], b1.model, b1.bounds)[0]


def test_the_model_counts_a_hole_at_every_pin_of_every_part():
    """A four-bar with a coupler point: two holes at each of its four joints, the coupler point a part's own point;
    a length at every point but each part's first."""
    model = slack_model(_band(_spec(FOURBAR)).analysis.linkage.structure)
    assert sorted(model.holes) == sorted([("ground", "O2"), ("crank", "O2"), ("crank", "A"), ("coupler", "A"),
                                          ("coupler", "B"), ("rocker", "B"), ("ground", "O4"), ("rocker", "O4")])
    assert sorted(model.lengths) == sorted([("ground", "O4"), ("crank", "A"), ("coupler", "B"), ("coupler", "P"),
                                            ("rocker", "B")])


@pytest.mark.xdist_group("slack-band-eightbar-triad")        # the case's band, designed once
def test_a_class_iii_groups_links_have_their_band_in_the_report(tmp_path):
    """The eight-bar's triad (a class-III group) analysed with [slack]: strict JSON with a band for each tracer on the
    triad, wider than the play alone (0.1 mm) where the bars' slack adds to it, Monte Carlo inside it; every pin of
    the triad's links is a hole of the model."""
    text = (ROOT / "templates" / "eightbar-triad.toml").read_text(encoding="utf-8") + "\n[slack]\nmonte_carlo = 10\n"
    result, out = _run(tmp_path, text, "analyze")
    assert result.exit_code == 0, result.output
    def refuse(constant: str) -> None:
        raise AssertionError(f"the JSON holds {constant}")

    report = json.loads((out / "eightbar-triad.json").read_text(), parse_constant=refuse)["slack"]
    assert set(report["tracers"]) == {"C", "E", "F", "G"}
    assert all(report["tracers"][p]["width_max_mm"] > 2 * 0.1 for p in ("E", "F", "G"))
    assert report["binds"] == [] and report["monte_carlo"]["outside"] == 0
    model = _case_band("eightbar-triad").model
    for link, points in (("bar1", ("C", "E")), ("bar2", ("O6", "F")), ("bar3", ("O8", "G")),
                         ("triad", ("E", "F", "G"))):
        assert all(model.hole(link, p) is not None for p in points), link
