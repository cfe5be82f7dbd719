"""A machine's page and its figures at chosen angles (issue 35 item 5). Headless Chromium loads the page of each
bundled machine without a console error, and its frame at each of ``machine.figure_angles`` shows every part where
the report's ``poses`` put it and every named point at the report's position (to 1e-6 mm), the timing diagram's
cursors at that angle; the page's timing rows are the design's outputs; the figures' geometry at an angle is the
kinematics (the automaton's rocker against an independent circle intersection, the toy's feet against
``linkgen analyze``); the report's poses agree with both."""
from __future__ import annotations

import json
import math
import re
import tomllib

import numpy as np
import pytest
import shapely

from tests.conftest import ROOT
from tests.camgen.kinds.machine.conftest import DESIGNS
from tests.camgen.kinds.machine.test_machine import _rocker, _swing
from tests.camgen.test_page import page_data
from tests.project.test_page_browser import CHROMIUM, DRIVER, browser  # noqa: F401  (the fixture, shared)

TEMPLATES = ROOT / "templates"
MACHINES = ("automaton", "walking-toy", "pick-and-place")
#: figure angles on whole degrees (the page's frames) for each machine's page test
ANGLES = {"automaton": [0.0, 37.0, 200.0, 311.0], "walking-toy": [0.0, 45.0, 90.0, 135.0],
          "pick-and-place": [0.0, 60.0, 150.0, 240.0]}

#: one worker for the modules that read the bundled machines' shared designs (conftest.py)
pytestmark = pytest.mark.xdist_group(DESIGNS)


def _design(name: str, **machine):
    from camgen import api

    with (TEMPLATES / f"{name}.toml").open("rb") as stream:
        raw = tomllib.load(stream)
    raw["machine"].update(machine)
    return api.design(api.validate(raw))


@pytest.fixture(scope="module")
def automaton():
    return _design("automaton", figure_angles=ANGLES["automaton"])


@pytest.fixture(scope="module")
def built(tmp_path_factory, automaton):
    """Each machine built with json, html and its figures at the angles of :data:`ANGLES`: (page text, report,
    folder). The files are written from the design (the automaton's the module's own): the bytes ``camgen build
    NAME.toml --set output.formats=[...] --set machine.figure_angles=[...]`` writes, without designing the
    automaton twice."""
    from camgen import api

    out = {}
    for name in MACHINES:
        folder = tmp_path_factory.mktemp(name)
        design = automaton if name == "automaton" else _design(name, figure_angles=ANGLES[name])
        api.write(design, folder, formats=["json", "html", "png", "svg"])
        out[name] = ((folder / f"{name}.html").read_text(encoding="utf-8"),
                     json.loads((folder / f"{name}.json").read_text()), folder)
    return out


@pytest.fixture(scope="module")
def toy(bundled_design):
    return bundled_design("walking-toy")


# ---- in the browser


_TRANSFORM = re.compile(r"translate\(([-\d.e]+) ([-\d.e]+)\) rotate\(([-\d.e]+)\)")


@pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="headless browser test: Debian's chromium and "
                    "chromium-driver are not installed (apt-get install chromium chromium-driver)")
@pytest.mark.parametrize("name", MACHINES)
def test_the_page_shows_the_reported_poses_in_chromium(browser, built, name):  # noqa: F811
    from selenium.webdriver.common.by import By

    _, report, folder = built[name]
    browser.get((folder / f"{name}.html").as_uri())
    assert browser.execute_script("return window.camgenPage && window.camgenPage.frames") == 360
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == []
    scene = browser.find_element(By.CSS_SELECTOR, "svg.scene")
    assert scene.size["width"] > 300 and scene.size["height"] > 100
    plots = browser.find_elements(By.CSS_SELECTOR, "svg.plot")
    assert len(plots) == len(report["timing"]["outputs"])
    read = """
    var svg=document.querySelector("svg.scene"),out={bodies:{},points:{},cursors:[],guides:{}};
    svg.querySelectorAll("[data-body]").forEach(function(g){var t=g.querySelector("title").textContent;
      out.bodies[t]=g.getAttribute("transform");
      if(/[.]guide$/.test(t)){var p=g.querySelector("path.guide"),n=p.getTotalLength();
        var a=p.getPointAtLength(0),b=p.getPointAtLength(n);out.guides[t]=[[a.x,a.y],[b.x,b.y]];}});
    svg.querySelectorAll("[data-mover]").forEach(function(g){var c=g.querySelector("circle");
      out.points[g.querySelector("title").textContent]=[+c.getAttribute("cx"),+c.getAttribute("cy")];});
    document.querySelectorAll("svg.plot").forEach(function(p){var c=p.querySelector(".cursor");
      out.cursors.push([+c.getAttribute("x1"),+p.dataset.x0,+p.dataset.x1]);});
    return out;"""
    for pose in report["poses"]:
        frame = round(pose["angle_deg"])
        browser.execute_script(f"window.camgenPage.show({frame})")
        shown = browser.execute_script(read)
        assert set(pose["parts"]) <= set(shown["bodies"])
        for part, placed in pose["parts"].items():
            x, y, turn = (float(v) for v in _TRANSFORM.fullmatch(shown["bodies"][part]).groups())
            assert [x, y] == pytest.approx(placed["at_mm"], abs=1e-6), (frame, part)
            assert math.remainder(turn - placed["turn_deg"], 360.0) == pytest.approx(0.0, abs=1e-6), (frame, part)
        assert set(shown["guides"]) == set(pose["guides"])              # the sliders' guides stand still
        for guide, ends in pose["guides"].items():
            assert shown["bodies"][guide] is None
            assert np.abs(np.array(shown["guides"][guide]) - np.array(ends)).max() < 1e-3, (frame, guide)
        assert set(shown["points"]) == set(pose["points"])
        for point, at in pose["points"].items():
            assert shown["points"][point] == pytest.approx(at, abs=1e-6), (frame, point)
        for x, x0, x1 in shown["cursors"]:
            assert x == pytest.approx(x0 + (x1 - x0) * frame / 359, abs=1e-6)
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == []


@pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="headless browser test: Debian's chromium and "
                    "chromium-driver are not installed (apt-get install chromium chromium-driver)")
def test_the_slider_moves_the_machine_and_the_cursors(browser, built):  # noqa: F811
    """Moving the slider by keys, as a person does, turns the main shaft a degree a key: the machine moves, the
    timing diagram's cursor follows and the key figures stand still."""
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    from tests.project.test_page_browser import _changed

    browser.get((built["walking-toy"][2] / "walking-toy.html").as_uri())
    scene, plot, facts = (browser.find_element(By.CSS_SELECTOR, css) for css in ("svg.scene", "svg.plot",
                                                                                 "table.figures"))
    before = (scene.screenshot_as_png, plot.screenshot_as_png, facts.screenshot_as_png)
    slider = browser.find_element(By.ID, "frame")
    slider.send_keys(Keys.ARROW_RIGHT * 30)
    assert slider.get_attribute("value") == "30"
    assert browser.find_element(By.ID, "shown").text == "30 deg"
    after = (scene.screenshot_as_png, plot.screenshot_as_png, facts.screenshot_as_png)
    assert _changed(before[0], after[0]) > 0.002
    assert _changed(before[1], after[1]) > 0.0005
    assert _changed(before[2], after[2]) == 0.0
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == []


# ---- the page's data without a browser


def test_the_pages_timing_rows_are_the_designs_outputs(built, automaton, toy):
    """The page's timing rows, one a degree, against the design's outputs at its 720 samples (every other one)."""
    for name, design in (("automaton", automaton), ("walking-toy", toy)):
        page = built[name][0]
        titles = re.findall(r'<text class="ptitle"[^>]*>([^<]+) \(([^)]+)\)</text>', page)
        assert [t for t, _ in titles] == [o.label for o in design.outputs]
        assert [u for _, u in titles] == [o.unit for o in design.outputs]
        from camgen.kinds.machine.page import frame_angles, outputs_at

        rows = outputs_at(design, frame_angles())
        for o in design.outputs:
            assert np.allclose(rows[o.label][1], o.values[::2], rtol=0, atol=1e-9), o.label


def test_the_pages_frames_are_the_placed_parts(built, automaton):
    """Frame k of the page's data holds each part's turn and shift at k degrees, to its 1e-8 rounding."""
    from camgen.kinds.machine import poses
    from camgen.kinds.machine.page import frame_angles

    data = page_data(built["automaton"][0])
    placed = sorted(poses.placed_parts(automaton, frame_angles()), key=lambda p: (p.low, p.high))
    bodies = data["scenes"][0]["bodies"][1:]                         # the first is what stands still
    assert len(bodies) == len(placed)
    for motion, p in zip(bodies, placed, strict=True):
        frames = np.asarray(motion, dtype=float).reshape(-1, 3)
        assert np.allclose(frames[:, 1:], p.shift, rtol=0, atol=1e-8)
        assert np.allclose(np.remainder(frames[:, 0] - p.turn + 180.0, 360.0) - 180.0, 0.0, atol=1e-8)


# ---- the figures and the report's poses


def _figure_points(fig) -> list[dict[str, np.ndarray]]:
    """Each panel's named points ({gid: (x, y)}) of a machine figure."""
    out = []
    for ax in fig.axes:
        named = {line.get_gid(): np.array([line.get_xdata()[0], line.get_ydata()[0]], dtype=float)
                 for line in ax.get_lines() if line.get_gid()}
        if named:
            out.append(named)
    return out


def _figure_parts(fig) -> list[dict[str, np.ndarray]]:
    return [{p.get_gid(): np.asarray(p.get_xy(), dtype=float) for p in ax.patches if p.get_gid()}
            for ax in fig.axes if ax.patches]


def test_the_automaton_figure_is_the_cam_fed_into_a_four_bar(automaton):
    """At each figure angle the figure's crank pin A lies crank mm from the follower's pivot, its rocker pin B
    rocker mm from the rocker's pivot O4, and B's angle about O4 from the ground line O2 -> O4 is the rocker angle
    of an independent circle intersection fed the cam's swing (mirrored where the arm swings clockwise), to 1e-9."""
    from camgen.kinds.machine.plots import machine_figure

    fig = machine_figure(automaton)
    panels = _figure_points(fig)
    angles = automaton.spec.machine.figure_angles
    assert len(panels) == len(angles)
    table = automaton.linkages[0].design.spec.linkage
    rest = automaton.spec.couplings[0].rest
    signs = set()
    for named, angle in zip(panels, angles, strict=True):
        o2, a, b, o4 = (named[f"{k}"] for k in ("cams.arm.pivot", "linkages.arm-bars.A", "linkages.arm-bars.B",
                                                  "linkages.arm-bars.O4"))
        assert math.dist(o2, a) == pytest.approx(table.crank, abs=1e-9)
        assert math.dist(o4, b) == pytest.approx(table.rocker, abs=1e-9)
        assert math.dist(a, b) == pytest.approx(table.coupler, abs=1e-9)
        assert math.dist(o2, o4) == pytest.approx(table.ground, abs=1e-9)
        theta2 = np.radians(rest + _swing(automaton, "arm", np.radians([angle])))
        theta4 = float(_rocker((table.ground, table.crank, table.coupler, table.rocker), theta2)[0])
        seen = math.atan2(*(b - o4)[::-1]) - math.atan2(*(o4 - o2)[::-1])
        sign = 1 if abs(math.remainder(seen - theta4, 2 * math.pi)) < 1e-9 else -1
        assert abs(math.remainder(seen - sign * theta4, 2 * math.pi)) < 1e-9, angle
        signs.add(sign)
    assert len(signs) == 1                                           # one mirror for every angle
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_the_toy_figure_puts_each_foot_where_linkgen_analyze_does(toy):
    """Each panel's foot G against linkgen analyze at the leg's crank angle (90 + phase - 2 phi), to 1e-9 mm; and
    every joint of a leg lies inside each drawn part it joins."""
    from linkgen import api

    from camgen.kinds.machine.plots import machine_figure

    fig = machine_figure(toy)
    panels, parts = _figure_points(fig), _figure_parts(fig)
    leg = api.load(TEMPLATES / "jansen.toml")
    links = tomllib.loads((TEMPLATES / "jansen.toml").read_text())["linkage"]["links"]
    for named, drawn, angle in zip(panels, parts, toy.spec.machine.figure_angles, strict=True):
        for m in toy.cranked:
            crank = (90.0 + m.phase_deg - 2 * angle) % 360.0
            joints = api.design(leg, angle=crank).report["positions"]["joints"]
            g = joints["G"]
            assert named[f"linkages.{m.name}.G"] == pytest.approx([g["x_mm"], g["y_mm"]], abs=1e-9)
            for link, held in links.items():
                outline = shapely.Polygon(drawn[f"linkages.{m.name}.{link}"])
                for joint in held:
                    if joint in ("O", "B"):
                        continue
                    at = shapely.Point(joints[joint]["x_mm"], joints[joint]["y_mm"])
                    assert outline.contains(at), (m.name, link, joint, angle)
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_the_reports_poses_are_the_kinematics(built, toy):
    """The report's poses of the toy's feet are linkgen's (1e-9 mm); the automaton's arm roller lies arm_length
    from its pivot at every figure angle."""
    from linkgen import api

    report = built["walking-toy"][1]
    leg = api.load(TEMPLATES / "jansen.toml")
    assert [p["angle_deg"] for p in report["poses"]] == ANGLES["walking-toy"]
    for pose in report["poses"]:
        for name, phase in (("left", 0.0), ("right", 180.0)):
            g = api.design(leg, angle=(90.0 + phase - 2 * pose["angle_deg"]) % 360.0).report["positions"]["joints"]["G"]
            assert pose["points"][f"linkages.{name}.G"] == pytest.approx([g["x_mm"], g["y_mm"]], abs=1e-9)
    automaton = built["automaton"][1]
    for pose in automaton["poses"]:
        roller, pivot = (np.array(pose["points"][f"cams.arm.{k}"]) for k in ("roller", "pivot"))
        assert math.dist(roller, pivot) == pytest.approx(90.0, abs=1e-9)
        assert pose["parts"]["cams.arm.roller"]["at_mm"] == pytest.approx(list(roller), abs=1e-9)


def test_the_figures_are_written_and_read_back(built):
    from PIL import Image

    for name in MACHINES:
        folder = built[name][2]
        report = built[name][1]
        assert report["files"]["machine_png"] == f"{name}-machine.png"
        with Image.open(folder / f"{name}-machine.png") as image:
            assert image.size[0] > 800 and image.size[1] > 300
        svg = (folder / f"{name}-machine.svg").read_text()
        assert svg.count("main shaft at") == len(ANGLES[name])
