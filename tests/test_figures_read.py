"""Figures that read (issue 17, item 3): a family's overview at one scale, in the order of its numbers, cams with
their bores; an assembly at several poses a panel each; drawings sized to what they draw, with no empty bands.
Measured on the figures as drawn (axes limits, positions and patches), not on pixels."""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from camgen.core.figures import drawing_figure, natural_key, overview_figure
from camgen.core.parts import POSE_COLOURS, Drawing
from camgen.core.shapes import Circle, Polyline
from camgen.design import design_cam
from camgen.plots import cam_figure
from camgen.spec import validate_spec

ROOT = Path(__file__).resolve().parent.parent


def _disc(radius: float, n: int = 90) -> list[list[float]]:
    t = np.linspace(0, 2 * math.pi, n, endpoint=False)
    return np.column_stack([radius * np.cos(t), radius * np.sin(t)]).tolist()


def test_natural_order_reads_numbers_as_numbers():
    names = ["f-lift30", "f-lift5", "f-lift10", "f-lift2.5", "g-lift1"]
    assert sorted(names, key=natural_key) == ["f-lift2.5", "f-lift5", "f-lift10", "f-lift30", "g-lift1"]


def test_overview_one_scale_numeric_order_and_bores():
    rows = [{"name": f"cams-lift{h}", "thumbnail": _disc(40 + h), "thumbnail_bore": 10.0} for h in (30, 5, 10)]
    rows.append({"name": "cams-lift20", "status": "failed"})
    fig = overview_figure(rows, "cams")
    axes = fig.axes
    assert [ax.get_title() for ax in axes] == ["lift5", "lift10", "lift20", "lift30"]   # the family's name dropped
    drawn = [ax for ax in axes if ax.patches]
    limits = {(ax.get_xlim(), ax.get_ylim()) for ax in drawn}
    assert len(limits) == 1                                  # one region, so one scale: 70 mm looks larger than 45
    (x0, x1), _ = limits.pop()
    assert x1 == pytest.approx(-x0) and x1 == pytest.approx(70 * 1.05, rel=1e-3)   # about the centre
    for ax in drawn:
        _outline, bore = ax.patches                          # the cam, then its bore in white
        radii = np.hypot(*bore.get_xy().T)
        assert radii == pytest.approx(5.0, abs=1e-9) and bore.get_facecolor()[:3] == (1.0, 1.0, 1.0)
    assert "147 mm across" in fig._suptitle.get_text()       # the scale said: 2 x 70 mm x 1.05


def test_overview_paths_share_their_frame_and_titles_wrap():
    arcs = [np.column_stack([c + r * np.cos(np.linspace(0.5, 2.5, 50)), r * np.sin(np.linspace(0.5, 2.5, 50))])
            for c, r in ((50, 30), (120, 80))]
    rows = [{"name": f"crank-rockers-ground{g}-crank{g // 2}-coupler{g + 10}-rocker{g - 5}", "thumbnail": a.tolist(),
             "thumbnail_kind": "path"} for g, a in zip((90, 180), arcs, strict=True)]
    fig = overview_figure(rows, "crank-rockers")
    titles = [ax.get_title() for ax in fig.axes]
    assert titles[0].startswith("ground90") and all("\n" in t and max(map(len, t.split("\n"))) <= 30 for t in titles)
    (lim,) = {(ax.get_xlim(), ax.get_ylim()) for ax in fig.axes}
    every = np.vstack(arcs)
    (x0, x1), (y0, y1) = lim
    assert x0 <= every[:, 0].min() and x1 >= every[:, 0].max() and y0 <= every[:, 1].min() and y1 >= every[:, 1].max()
    assert (x1 - x0) <= 1.2 * np.ptp(every[:, 0])             # the region is the paths', not a square round them


def _strip(poses: int) -> Drawing:
    """A long, low assembly (300 x 40 mm) at ``poses`` poses that lie on one another, and a path."""
    bar = np.array([[0.0, 0.0], [300.0, 0.0], [300.0, 40.0], [0.0, 40.0]])
    items = [(f"DC{i + 1}-pose", Polyline(bar.copy(), np.zeros(3))) for i in range(poses)]
    items += [(f"DC{i + 1}-pose", Circle((10.0 * i, 20.0), 5.0)) for i in range(poses)]
    return Drawing(tuple([*items, ("PATH", Polyline(np.array([[0.0, 20.0], [300.0, 20.0]]), np.zeros(1)))]), 0.01)


def test_an_assembly_gets_a_panel_per_pose_at_one_scale_sized_to_it():
    fig = drawing_figure(_strip(2), "strip")
    assert len(fig.axes) == 2
    assert [ax.get_title() for ax in fig.axes] == ["DC1-pose", "DC2-pose"]
    assert len({(ax.get_xlim(), ax.get_ylim()) for ax in fig.axes}) == 1
    for k, ax in enumerate(fig.axes):
        colours = {line.get_color() for line in ax.lines}
        assert POSE_COLOURS[k][1] in colours and POSE_COLOURS[1 - k][1] not in colours   # its own pose only
    width, height = fig.get_size_inches()
    fig.canvas.draw()
    for ax in fig.axes:                                     # equal scale: the box is as wide as the drawing asks
        box = ax.get_position()
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        assert box.height * height / (box.width * width) == pytest.approx((y1 - y0) / (x1 - x0), rel=0.02)
    drawn = sum(ax.get_position().height for ax in fig.axes) * height
    assert drawn / height > 0.25 and height < 6             # a strip gets a low figure, not 7 in. of white


def test_one_pose_stays_one_panel():
    fig = drawing_figure(_strip(1), "one")
    assert len(fig.axes) == 1


@pytest.mark.parametrize("template", ["rdrd", "plate", "oscillating"])
def test_cam_figure_fills_its_height(template):
    spec = validate_spec(tomllib.loads((ROOT / "templates" / f"{template}.toml").read_text(encoding="utf-8")))
    fig = cam_figure(design_cam(spec))
    width, height = fig.get_size_inches()
    (ax,) = fig.axes
    fig.canvas.draw()
    box = ax.get_position()
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert box.height * height / (box.width * width) == pytest.approx((y1 - y0) / (x1 - x0), rel=0.02)
    # what is not the drawing is its title, tick labels, x label and legend: under 2.2 inches
    assert height - box.height * height < 2.2


def test_a_kits_panels_list_each_part_once_in_one_colour_and_write_their_labels():
    """A kit's assembly at several cam angles (layers ``KIT-<degrees>-<part>``): the legend lists each part once,
    every panel draws a part in the same colour, parts beyond matplotlib's ten colours still differ, and the panels'
    labels (``KIT-LABELS``) are written as words, not listed."""
    from camgen.core.shapes import Text

    names = [f"part{i}" for i in range(12)]
    items = [(f"KIT-{deg}-{name}", Circle((100.0 * j, 10.0 * i), 3.0 + i))
             for j, deg in enumerate((0, 90, 180)) for i, name in enumerate(names)]
    items += [("KIT-LABELS", Text(f"{deg} deg", (100.0 * j, -20.0), 4.0)) for j, deg in enumerate((0, 90, 180))]
    fig = drawing_figure(Drawing(tuple(items), 0.01), "kit")
    legend = fig.legends[0]
    assert [t.get_text() for t in legend.get_texts()] == names
    lines = [line for ax in fig.axes for line in ax.lines]
    by_part: dict[float, set] = {}
    for line in lines:                                      # a part's circles have its radius (3 + i)
        radius = float(np.ptp(line.get_xdata())) / 2
        by_part.setdefault(round(radius), set()).add(line.get_color())
    assert all(len(colours) == 1 for colours in by_part.values()) and len(by_part) == 12
    assert len({next(iter(c)) for c in by_part.values()}) == 12
    words = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert words == ["0 deg", "90 deg", "180 deg"]


@pytest.mark.parametrize("output, figures", [("", 0), ("[output]\nfigures = true\n", 12),
                                             ('[output]\nformats = ["json", "png"]\n', 6),
                                             ('[output]\nformats = ["json", "svg"]\n', 6)])
def test_a_familys_overview_figure_comes_with_its_members_figures(output, figures, tmp_path):
    """Figures are on request (``output.figures`` or ``"png"`` in ``output.formats``): a family draws its overview
    figure only when its members draw theirs; its page and summaries come either way."""
    from click.testing import CliRunner

    from camgen.cli import main

    family = tmp_path / "fam.toml"
    family.write_text(f'base = "{(ROOT / "templates" / "rdrd.toml").as_posix()}"\nname = "fam"\n'
                      f'[sweep]\n"cam.base_radius" = [40, 50]\n{output}')
    result = CliRunner().invoke(main, ["family", str(family), "-o", str(tmp_path / "out"), "--jobs", "1"])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "out" / "overview.png").exists() is bool(figures)
    assert (tmp_path / "out" / "summary.csv").exists()
    drawn = [p for p in (tmp_path / "out").glob("*/*") if p.suffix in (".png", ".svg") and "-cut" not in p.name]
    assert len(drawn) == figures                          # three figures a member, in each figure format asked
