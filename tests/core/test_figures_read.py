"""Figures that read (issue 17, item 3): a family's overview at one scale, in the order of its numbers, cams with
their bores; an assembly at several poses a panel each; drawings sized to what they draw, with no empty bands; the
checks figure's radius of curvature signed and finite, a concave stretch not drawn as an undercut (issue 30).
Measured on the figures as drawn (axes limits, positions and patches), not on pixels."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from camgen.core.figures import drawing_figure, natural_key, overview_figure
from camgen.core.parts import POSE_COLOURS, Drawing
from camgen.core.shapes import Circle, Polyline
from camgen.api import design_cam
from camgen.plots import cam_figure
from camgen.spec import validate_spec
from tests.conftest import ROOT


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


#: a centred roller lifted 30 mm in 60 degrees on a 40 mm base circle: its flanks are concave (no undercut), with
#: a convex margin of 2 mm and a 3 mm router asked for
CONCAVE = {"name": "concave", "cam": {"base_radius": 40.0, "thickness": 6.0, "bore": 10.0, "min_rho_margin": 2.0},
           "follower": {"type": "translating-roller", "roller_radius": 5.0},
           "motion": [{"type": "rise", "law": "cycloidal", "lift": 30.0, "angle": 60.0},
                      {"type": "dwell", "angle": 60.0},
                      {"type": "return", "law": "cycloidal", "lift": 30.0, "angle": 60.0},
                      {"type": "dwell", "angle": 180.0}],
           "output": {"tolerance": 0.01, "tool_radius": 3.0}}


def _radius_panel(fig):
    (ax,) = [a for a in fig.axes if a.get_ylabel().startswith(("radius", "profile radius"))]
    return ax


def _limits(ax) -> dict[str, float]:
    """The dashed limit lines of a radius panel by their labels: {label: y (mm)}."""
    return {line.get_label(): float(line.get_ydata()[0]) for line in ax.get_lines()
            if line.get_linestyle() == "--"}


def test_the_checks_figure_draws_a_concave_stretch_signed_and_finite():
    """A concave stretch is drawn below 0 as what it is, not clipped into an undercut: the plotted radius of the cam
    surface is finite everywhere, equals the closed form of the polar pitch curve (rho = (r^2 + r'^2)^(3/2) /
    (r^2 + 2 r'^2 - r r''), r = Rp + s, less the roller's 5 mm) wherever it is drawn as itself, is below -5 mm (the
    concave surface lies the roller's radius beyond its pitch curve) exactly where that denominator is negative, and
    is positive elsewhere; the scale shows both sides; the limits are where the checks put them (convex: the margin,
    pitch radius = roller + margin; concave: the router's radius; the undercut band from -5 mm to the margin)."""
    from camgen.plots import checks_figure, sample_cycle

    design = design_cam(validate_spec(CONCAVE))
    ax = _radius_panel(checks_figure(design))
    line = ax.get_lines()[0]
    theta, motion = sample_cycle(design.cam)
    assert np.asarray(line.get_xdata()) == pytest.approx(np.degrees(theta), abs=1e-12)
    y = np.asarray(line.get_ydata(), dtype=float)
    assert np.isfinite(y).all()
    s, s1, s2 = motion[0], motion[1], motion[2]
    r = 45.0 + s
    below = r**2 + 2 * s1**2 - r * s2
    with np.errstate(divide="ignore"):
        expected = (r**2 + s1**2) ** 1.5 / below - 5.0
    drawn = np.abs(expected) < 0.999 * np.abs(y).max()           # inside the reach: drawn as itself
    assert drawn.mean() > 0.9
    assert y[drawn] == pytest.approx(expected[drawn], rel=1e-9, abs=1e-9)
    concave = below < 0
    assert concave.sum() > 50 and np.all(y[concave] < -5.0) and np.all(y[~concave] > 0.0)
    assert ax.get_yscale() == "symlog"
    low, high = ax.get_ylim()
    assert low < y.min() < 0 < y.max() < high
    limits = _limits(ax)
    assert limits == {"convex limit: pitch radius = roller 5 + margin 2 mm": 2.0,
                      "concave limit: tool radius 3 mm": -3.0}
    (band,) = ax.patches
    assert (band.get_y(), band.get_y() + band.get_height()) == pytest.approx((-5.0, 2.0))
    assert "undercut: -5 to 2 mm" in band.get_label()


def test_a_straight_stretch_is_drawn_at_the_top_not_as_an_undercut():
    """plate.toml: its dwells are straight (no curvature: an infinite radius, whatever the sign of its zero) and its
    rise starts concave. The straight stretches are drawn at the top of the scale (the reach, said in the legend),
    the concave ones below 0 and equal to the closed form of the plate's pitch curve y = Rb + Rr + s(x),
    x = travel theta / 2 pi: rho = -(1 + y_x^2)^(3/2) / y_xx (a hump convex), less the roller's 8 mm."""
    from camgen.plots import checks_figure, sample_cycle

    spec = validate_spec(tomllib.loads((ROOT / "templates" / "plate.toml").read_text(encoding="utf-8")))
    design = design_cam(spec)
    ax = _radius_panel(checks_figure(design))
    y = np.asarray(ax.get_lines()[0].get_ydata(), dtype=float)
    _theta, motion = sample_cycle(design.cam)
    assert np.isfinite(y).all()
    reach = float(np.abs(y).max())
    dwell = motion[1] == 0
    dwell &= motion[2] == 0
    assert dwell.sum() > 4 and np.all(y[dwell] == reach)
    k = 2 * math.pi / 200.0                                   # d theta / dx: 360 degrees over 200 mm
    yx, yxx = motion[1] * k, motion[2] * k**2
    with np.errstate(divide="ignore"):
        expected = -(1 + yx**2) ** 1.5 / yxx - 8.0
    drawn = np.abs(expected) < 0.999 * reach
    assert y[drawn] == pytest.approx(expected[drawn], rel=1e-9)
    assert np.any(y[drawn] < -8.0) and np.any(y[drawn] > 0)
    assert any(f"drawn at ±{reach:g}" in t.get_text() for t in ax.get_legend().get_texts())


def test_a_grooves_flanks_are_drawn_signed_and_finite():
    """grooved-loaded.toml's checks figure: each flank's radius finite and signed (the outer flank concave where the
    inner one is convex), on the scale that shows both, the undercut band the roller's reach (5 + 0.2 / 2 mm)."""
    from camgen.kinds.grooved.design import design_grooved
    from camgen.kinds.grooved.plots import grooved_checks_figure
    from camgen.spec import load_spec

    design = design_grooved(load_spec(ROOT / "templates" / "grooved-loaded.toml", ()))
    ax = _radius_panel(grooved_checks_figure(design))
    inner, outer = (np.asarray(line.get_ydata(), dtype=float) for line in ax.get_lines()[:2])
    assert np.isfinite(inner).all() and np.isfinite(outer).all()
    assert np.any(inner > 0) and np.any(outer < 0) and np.all((inner > 0) | (outer > 0))
    assert ax.get_yscale() == "symlog"
    (band,) = ax.patches
    assert band.get_y() == pytest.approx(-design.spec.follower.roller_radius - design.spec.cam.running_clearance / 2)
