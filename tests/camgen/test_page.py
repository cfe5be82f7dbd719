"""The interactive page written beside every design (``<name>.html``): self-contained, its figures the JSON report's,
its frames the design's own geometry, and the same page inline in Jupyter."""
from __future__ import annotations

import html
import json
import math
import re

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen_main
from linkgen.cli import main as linkgen_main
from tests.conftest import ROOT

TEMPLATES = ROOT / "templates"
#: (program, command, template) of each kind of page
KINDS = [("camgen", "build", "rdrd"), ("camgen", "build", "oscillating"), ("camgen", "build", "flat-face"),
         ("camgen", "build", "plate"), ("camgen", "build", "grooved"), ("camgen", "build", "barrel"),
         ("camgen", "build", "geneva4"), ("camgen", "build", "conjugate"), ("camgen", "build", "conjugate-arm"),
         ("camgen", "build", "barrel-oscillating"),
         ("linkgen", "analyze", "crank-rocker"), ("linkgen", "analyze", "slider-crank"),
         ("linkgen", "analyze", "jansen"), ("linkgen", "analyze", "hoekens")]
PROGRAMS = {"camgen": camgen_main, "linkgen": linkgen_main}


#: builds already made in this process: (program, command, name, sets) -> (page, report)
_BUILT: dict[tuple, tuple[str, dict]] = {}


def build(tmp_path, program: str, command: str, name: str, *sets: str) -> tuple[str, dict]:
    """Run the command on a bundled template into ``tmp_path`` (once a process for the same arguments); the page's
    text and the JSON report."""
    key = (program, command, name, sets)
    if key not in _BUILT:
        args = [command, str(TEMPLATES / f"{name}.toml"), "-o", str(tmp_path)]
        for s in sets:
            args += ["--set", s]
        result = CliRunner().invoke(PROGRAMS[program], args)
        assert result.exit_code == 0, result.output
        _BUILT[key] = ((tmp_path / f"{name}.html").read_text(encoding="utf-8"),
                       json.loads((tmp_path / f"{name}.json").read_text()))
    return _BUILT[key]


def page_data(text: str) -> dict:
    """The JSON the page's script reads."""
    found = re.search(r'<script type="application/json" id="page-data">(.*?)</script>', text, re.S)
    assert found, "no page data"
    return json.loads(found.group(1).replace("<\\/", "</"))


def at(report: dict, key: str):
    value = report
    for part in key.split("."):
        value = value[int(part)] if isinstance(value, list) else value[part]
    return value


@pytest.mark.parametrize(("program", "command", "name"), KINDS, ids=[k[2] for k in KINDS])
def test_the_page_shows_the_reports_figures_and_needs_no_network(tmp_path, program, command, name):
    text, report = build(tmp_path, program, command, name, 'output.formats=["json", "html"]')
    data = page_data(text)
    figures = data["figures"]
    assert len(figures) >= 3
    for key, value in figures.items():
        assert at(report, key) == value, key                         # the very numbers of the JSON report
    rows = re.findall(r'<tr data-key="([^"]+)"><th>[^<]*</th><td class="num">([^<]*)</td>', text)
    assert [k for k, _ in rows] == list(figures)
    for key, shown in rows:
        value = figures[key]
        if isinstance(value, float):
            assert float(html.unescape(shown)) == pytest.approx(value, rel=1e-5, abs=1e-12), key
    assert report["files"] == {"json": f"{name}.json", "html": f"{name}.html"}
    # self-contained: nothing fetched, no server
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:|//)""", text)
    assert "<link" not in text and "url(" not in text and "@import" not in text
    assert len(data["inputs"]) == 360
    scene = data["scenes"][0]
    assert any(b is not None and len(b) == 3 * 360 for b in scene["bodies"]) or scene["movers"]
    for m in scene["movers"]:
        assert len(m["d"]) == 360 * m["k"] * 2
    assert len(text) < 400_000


def test_a_disc_cams_page_turns_the_cam_under_its_roller(tmp_path):
    """rdrd: the cam turns one degree a frame counter-clockwise, and the roller's centre stands on the follower's
    axis (offset e) at d0 + s above the cam's centre, d0 = sqrt(Rp^2 - e^2), s as the law says."""
    import camgen

    text, report = build(tmp_path, "camgen", "build", "rdrd")
    data = page_data(text)
    cam_motion = np.array(data["scenes"][0]["bodies"][1], dtype=float).reshape(360, 3)
    assert cam_motion[:, 0] == pytest.approx(np.arange(360.0))
    roller = next(m for m in data["scenes"][0]["movers"] if m["r"])
    centre = np.array(roller["d"], dtype=float).reshape(360, 2)
    design = camgen.design_cam(camgen.load_spec(TEMPLATES / "rdrd.toml"))
    s = design.cam.program.evaluate(np.radians(np.arange(360.0)))[0]
    e, prime = report["follower"]["offset_mm"], report["cam"]["prime_radius_mm"]
    assert e == 5.0
    assert centre[:, 0] == pytest.approx(e, abs=1e-9)                          # on the follower's axis
    assert centre[:, 1] == pytest.approx(math.sqrt(prime**2 - e**2) + s, abs=1e-3)
    # every other file is linked from the page, and only they
    links = re.findall(r'<a href="([^"]+)">', text)
    assert sorted(links) == sorted(v for k, v in report["files"].items() if k != "html")


def test_an_oscillating_followers_arm_keeps_its_length(tmp_path):
    text, report = build(tmp_path, "camgen", "build", "oscillating", 'output.formats=["json", "html"]')
    movers = page_data(text)["scenes"][0]["movers"]
    arm = np.array(movers[0]["d"], dtype=float).reshape(360, 2, 2)
    length = np.linalg.norm(arm[:, 1] - arm[:, 0], axis=1)
    assert length == pytest.approx(report["follower"]["arm_length_mm"], abs=2e-3)
    assert arm[:, 0] == pytest.approx(np.broadcast_to(report["follower"]["pivot_mm"], (360, 2)), abs=1e-3)


def test_a_conjugate_pairs_rollers_keep_the_yoke_span(tmp_path):
    """conjugate.toml: both rollers on the follower's line, yoke_span_mm apart at every frame, on the cams' pitch
    curves (each cam turning with the shaft)."""
    text, report = build(tmp_path, "camgen", "build", "conjugate", 'output.formats=["json", "html"]')
    movers = page_data(text)["scenes"][0]["movers"]
    one, two = (np.array(m["d"], dtype=float).reshape(360, 2) for m in movers if m["r"])
    span = report["follower"]["second_roller"]["yoke_span_mm"]
    assert np.linalg.norm(one - two, axis=1) == pytest.approx(span, abs=2e-3)
    assert one[:, 0] == pytest.approx(report["follower"]["offset_mm"], abs=1e-3)     # on the follower's axis


@pytest.mark.parametrize("name", ["crank-rocker", "jansen"])
def test_a_linkages_links_stay_rigid_through_the_cycle(tmp_path, name):
    """Every moving link's joints keep their drawn distances over the 360 frames (the poses are the solver's)."""
    import linkgen

    text, _ = build(tmp_path, "linkgen", "analyze", name, 'output.formats=["json", "html"]')
    design = linkgen.design_linkage(linkgen.load_spec(TEMPLATES / f"{name}.toml"))
    a = design.page().scene                       # the same page, made in Python
    movers = page_data(text)["scenes"][0]["movers"]
    assert [m.name for m in a.movers][: len(movers)] == [m.name for m in a.movers]
    links = [m for m in a.movers if m.radius == 0]
    assert len(links) >= 3
    for mover, data in zip(a.movers, movers, strict=True):
        pts = np.array([math.nan if v is None else v for v in data["d"]], dtype=float).reshape(360, -1, 2)
        if mover.radius:
            continue
        gaps = np.linalg.norm(np.diff(pts, axis=1), axis=2)
        drawn = np.linalg.norm(np.diff(mover.points[0], axis=0), axis=1)
        assert np.nanmax(np.abs(gaps - drawn)) < 3e-3, mover.name


def test_jupyter_shows_the_same_page_inline(tmp_path):
    import camgen
    import linkgen

    design = camgen.design_cam(camgen.load_spec(TEMPLATES / "rdrd.toml", ['output.formats=["json", "html"]']))
    inline = design._repr_html_()
    assert inline.startswith("<iframe srcdoc=")
    doc = html.unescape(re.search(r'srcdoc="([^"]*)"', inline).group(1))
    written, _ = build(tmp_path, "camgen", "build", "rdrd", 'output.formats=["json", "html"]')
    assert page_data(doc) == page_data(written)
    fourbar = linkgen.design_linkage(linkgen.load_spec(TEMPLATES / "crank-rocker.toml"))
    assert "page-data" in html.unescape(fourbar._repr_html_())
    no_page = camgen.design_cam(camgen.load_spec(TEMPLATES / "rdrd.toml", ['output.formats=["json"]']))
    assert no_page._repr_html_() is None


def test_the_family_page_lists_every_member_at_one_scale_in_swept_order(tmp_path):
    """overview.html: one card and one table row a member, sorted by the swept values as numbers (lift 5 before
    lift 30), every drawing the same size in mm, each linking to the member's own page."""
    path = tmp_path / "fam.toml"
    path.write_text(f'base = "{(TEMPLATES / "rdrd.toml").as_posix()}"\nname = "lifts"\n[output]\n'
                    'formats = ["json", "html"]\n[sweep.zip]\n"motion.0.lift" = [5, 30, 15]\n'
                    '"motion.2.lift" = [5, 30, 15]\n')
    result = CliRunner().invoke(camgen_main, ["family", str(path), "-o", str(tmp_path / "f")])
    assert result.exit_code == 0, result.output
    text = (tmp_path / "f" / "overview.html").read_text(encoding="utf-8")
    names = [f"lifts-0lift{v}-2lift{v}" for v in (5, 15, 30)]
    cards = re.findall(r'<h3><a href="([^"]+)">([^<]+)</a></h3>', text)
    assert cards == [(f"{n}/{n}.html", n) for n in names]
    for link, _ in cards:
        assert (tmp_path / "f" / link).is_file()
    rows = re.findall(r'<tr><td><a href="[^"]+">([^<]+)</a></td>', text)
    assert rows == names
    boxes = [tuple(float(v) for v in b.split()) for b in re.findall(r'<svg class="scene" viewBox="([^"]+)"', text)]
    assert len(boxes) == 3 and len({(b[2], b[3]) for b in boxes}) == 1          # one scale for all
    data = page_data(text)
    assert len(data["scenes"]) == 3 and len(data["inputs"]) == 360
    summary = json.loads((tmp_path / "f" / "summary.json").read_text())
    for row in summary:                                                            # the summary's figures, shown
        assert f'data-v="{row["pressure_angle_max_deg"]}"' in text
