"""The bundled ``type = "linkage"`` templates of issue 12, each checked against an independent computation.

Every template analyses and builds through the command line, and its cut sheet's holes lie exactly as far
apart as the drawing's joints on each link. Then each mechanism does what its comment says, every reference
written here from the published dimensions (never through linkgen's general solver): Jansen's and Klann's
foot paths by circle intersections step by step round the crank, the pantograph's scaling, the crank
shaper's stroke and time ratio by the textbook closed form, the single-dwell six-bar's dwell, the pendulum
pump's and the toggle press's strokes.
"""
from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from tests.conftest import ROOT

TEMPLATES = ("jansen", "klann", "watt1", "watt2", "stephenson1", "stephenson3", "shaper", "pendulum-pump",
             "toggle-press", "pantograph", "single-dwell")
#: the crank angles every path is checked at: 3600 a turn
TURN = np.radians(np.arange(3600) / 10.0)


def _path(name: str) -> Path:
    return ROOT / "templates" / f"{name}.toml"


def _table(name: str) -> dict:
    return tomllib.loads(_path(name).read_text(encoding="utf-8"))["linkage"]


def _solve(name: str, values: np.ndarray):
    """linkgen's solution of the template at input values (rad for a crank, mm for a slide)."""
    import linkgen

    design = linkgen.design_linkage(linkgen.load_spec(_path(name)))
    return design.kinematics.linkage.solve(values)


def _meet(p1: np.ndarray, r1: float, p2: np.ndarray, r2: float, side: float) -> np.ndarray:
    """Where circle (p1, r1) meets circle (p2, r2), on the ``side`` (+1 left, -1 right) of the line p1 -> p2;
    p1, p2 (n, 2) or (2,)."""
    p1, p2 = np.broadcast_arrays(np.asarray(p1, float), np.asarray(p2, float))
    d = p2 - p1
    length = np.hypot(d[..., 0], d[..., 1])
    along = (r1**2 - r2**2 + length**2) / (2 * length)
    height = np.sqrt(r1**2 - along**2)
    u = d / length[..., None]
    n = np.stack([-u[..., 1], u[..., 0]], axis=-1)
    return p1 + along[..., None] * u + side * height[..., None] * n


def _side(p1, p2, j) -> float:
    """Which side of the line p1 -> p2 the drawing puts joint j on (+1 left, -1 right)."""
    (ax, ay), (bx, by) = np.subtract(p2, p1), np.subtract(j, p1)
    return math.copysign(1.0, ax * by - ay * bx)


def _on_circle(centre, radius: float, angles: np.ndarray) -> np.ndarray:
    return np.asarray(centre, float) + radius * np.column_stack([np.cos(angles), np.sin(angles)])


# ------------------------------------------------------------------------------------- every template builds


def _expected_parts(table: dict) -> list[np.ndarray]:
    """The hole centres (drawn) of each part the template makes: the frame (its pivots, less any joint sliding
    on a frame guide), each link (every point it lists), and a block for each slider without a sliding link."""
    joints = {k: np.array(v, float) for k, v in table["joints"].items()}
    sliders = table.get("sliders", {})
    guided = {s["point"] for s in sliders.values() if s.get("guide", "ground") == "ground"}
    parts = [np.array([joints[p] for p in table["ground"] if p not in guided])]
    parts += [np.array([joints[p] for p in pts]) for pts in table["links"].values()]
    parts += [np.array([joints[s["point"]]]) for s in sliders.values() if "link" not in s]
    return parts


def _sheet_parts(path: Path) -> list[np.ndarray]:
    """The hole centres of each part on a cut sheet: the circles inside each outline."""
    import ezdxf
    import shapely
    from ezdxf import path as dxfpath

    msp = ezdxf.readfile(path).modelspace()
    outlines = [shapely.Polygon([(v.x, v.y) for v in dxfpath.make_path(e).flattening(0.01)])
                for e in msp.query("LWPOLYLINE") if e.dxf.layer == "OUTLINE"]
    centres = [np.array(e.dxf.center)[:2] for e in msp.query("CIRCLE") if e.dxf.layer == "HOLES"]
    holes: list[list[np.ndarray]] = [[] for _ in outlines]
    for c in centres:
        inside = [i for i, o in enumerate(outlines) if o.contains(shapely.Point(c))]
        assert len(inside) == 1, f"hole at {c} lies in {len(inside)} outlines"
        holes[inside[0]].append(c)
    return [np.array(h) for h in holes]


def _distances(points: np.ndarray) -> np.ndarray:
    """The sorted pairwise distances of a set of points."""
    return np.sort([math.dist(a, b) for i, a in enumerate(points) for b in points[i + 1:]])


@pytest.mark.parametrize("name", TEMPLATES)
def test_the_template_analyses_builds_and_its_parts_hold_the_drawn_distances(name, tmp_path):
    from linkgen.cli import main

    result = CliRunner().invoke(main, ["analyze", str(_path(name)), "--json", "-o", str(tmp_path / "a")])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "a" / f"{name}.json").read_text())
    assert report["type"] == "linkage" and report["mobility"] == 1
    result = CliRunner().invoke(main, ["build", str(_path(name)), "-o", str(tmp_path / "b"), "--figures"])
    assert result.exit_code == 0, result.output
    for figure in ("assembly", "motion"):
        assert (tmp_path / "b" / f"{name}-{figure}.png").stat().st_size > 0
    cut = _sheet_parts(tmp_path / "b" / f"{name}-sheet.dxf")
    expected = _expected_parts(_table(name))
    assert sorted(len(h) for h in cut) == sorted(len(h) for h in expected)
    # each part's hole distances are one link's joint distances (a bar's one, a plate's three...), to 1e-6 mm
    unmatched = list(cut)
    for want in expected:
        d = _distances(want)
        hit = next((i for i, got in enumerate(unmatched) if len(got) == len(want)
                    and np.allclose(_distances(got), d, rtol=0, atol=1e-6)), None)
        assert hit is not None, f"no part on the sheet has holes {d} mm apart"
        del unmatched[hit]


@pytest.mark.parametrize("name", TEMPLATES)
def test_every_pose_keeps_each_links_lengths_and_each_slider_on_its_guide(name):
    """The solution over the motion, checked against the drawing alone: every link rigid, the frame's pivots
    fixed, each sliding point on its straight guide (the frame's, or a link's carried with it), a sliding link
    square to its guide as drawn."""
    table = _table(name)
    joints = {k: np.array(v, float) for k, v in table["joints"].items()}
    inp = table["input"]
    if "slider" in inp:
        values = np.linspace(-39.999, 39.999, 801)          # the pump's stroke, short of its two toggles
    elif "range" in inp:
        values = np.radians(np.linspace(*inp["range"], 801))
    else:
        values = TURN
    sol = _solve(name, values)
    for pts in table["links"].values():
        for i, a in enumerate(pts):
            for b in pts[i + 1:]:
                got = np.hypot(*(sol.points[a] - sol.points[b]).T)
                assert np.max(np.abs(got - math.dist(joints[a], joints[b]))) < 1e-9, (name, a, b)
    for p in table["ground"]:
        assert np.max(np.abs(sol.points[p] - joints[p])) < 1e-9

    def turn(link: str) -> np.ndarray:
        """How far (rad) a link has turned from the drawing, by its first two points."""
        if link == "ground":
            return np.zeros(len(values))
        g0, g1 = table["links"][link][:2]
        drawn, now = joints[g1] - joints[g0], sol.points[g1] - sol.points[g0]
        return np.arctan2(now[:, 1], now[:, 0]) - math.atan2(drawn[1], drawn[0])

    for s in table.get("sliders", {}).values():
        guide = s.get("guide", "ground")
        phi = turn(guide)
        u = np.column_stack([np.cos(math.radians(s["angle"]) + phi), np.sin(math.radians(s["angle"]) + phi)])
        if guide == "ground":
            through = np.broadcast_to(joints[s["point"]], (len(values), 2))
        else:   # the guide's line through the point's drawn place, carried with the guiding link
            g0 = table["links"][guide][0]
            d = joints[s["point"]] - joints[g0]
            through = sol.points[g0] + np.column_stack([np.cos(phi) * d[0] - np.sin(phi) * d[1],
                                                        np.sin(phi) * d[0] + np.cos(phi) * d[1]])
        off = np.einsum("ij,ij->i", sol.points[s["point"]] - through, np.column_stack([-u[:, 1], u[:, 0]]))
        assert np.max(np.abs(off)) < 1e-9, (name, s)
        if "link" in s:
            assert np.max(np.abs(np.remainder(turn(s["link"]) - phi + math.pi, 2 * math.pi) - math.pi)) < 1e-12

# ----------------------------------------------------------------------------------------------- Jansen


def _jansen_reference(theta: np.ndarray, drawn: dict) -> dict[str, np.ndarray]:
    """Jansen's leg from the holy numbers, one circle intersection after another, each on the branch the drawing
    shows (crank m about O at the origin, B at (-a, -l))."""
    # Jansen's own letters, l among them
    a, b, c, d, e, f, g, h, i, j, k, l, m = 38, 41.5, 39.3, 40.1, 55.8, 39.4, 36.7, 65.7, 49, 50, 61.9, 7.8, 15  # noqa: E741
    s = {q: _side(*(drawn[x] for x in key), drawn[q]) for q, key in
         {"C": "AB", "D": "AB", "E": "CB", "F": "ED", "G": "FD"}.items()}
    A = _on_circle((0, 0), m, theta)
    B = np.array([-a, -l])
    C = _meet(A, j, B, b, s["C"])
    D = _meet(A, k, B, c, s["D"])
    E = _meet(C, e, B, d, s["E"])
    F = _meet(E, f, D, g, s["F"])
    G = _meet(F, h, D, i, s["G"])
    return {"A": A, "C": C, "D": D, "E": E, "F": F, "G": G}


def test_jansens_foot_strides_and_lifts_as_the_holy_numbers_give():
    drawn = {k: np.array(v, float) for k, v in _table("jansen")["joints"].items()}
    # the drawing is the holy-number leg with the crank straight up
    at90 = _jansen_reference(np.array([math.pi / 2]), drawn)
    for joint, where in at90.items():
        assert np.allclose(where[0], drawn[joint], rtol=0, atol=1e-8), joint
    ref = _jansen_reference(TURN, drawn)["G"]
    foot = _solve("jansen", TURN).points["G"]
    assert np.max(np.hypot(*(foot - ref).T)) < 1e-8
    stride, lift = np.ptp(foot[:, 0]), np.ptp(foot[:, 1])
    assert stride == pytest.approx(np.ptp(ref[:, 0]), abs=1e-8)
    assert lift == pytest.approx(np.ptp(ref[:, 1]), abs=1e-8)
    assert stride == pytest.approx(67.908, abs=1e-3)          # as the template's comment says
    assert lift == pytest.approx(22.457, abs=1e-3)
    # the ground-contact stretch: the lowest 2 mm of the path is nearly all of its width
    low = foot[:, 1] <= foot[:, 1].min() + 2.0
    assert np.ptp(foot[low, 0]) == pytest.approx(64.940, abs=1e-3)


# ------------------------------------------------------------------------------------------------ Klann


def test_klanns_foot_follows_the_patent_proportions():
    drawn = {k: np.array(v, float) for k, v in _table("klann")["joints"].items()}
    unit = 100.0                                   # the patent's proportions, x100 to mm
    crank, rod_elbow, rod_knee, elbow_knee = 0.268 * unit, 0.590 * unit, 1.105 * unit, 0.522 * unit
    lower, upper, hip_knee, knee_foot, hip_foot = 0.321 * unit, 0.518 * unit, 0.897 * unit, 0.897 * unit, 1.732 * unit
    U, W = np.array([-0.233, 0.616]) * unit, np.array([-0.590, -0.176]) * unit
    assert np.allclose(drawn["U"], U) and np.allclose(drawn["W"], W) and np.allclose(drawn["O"], 0)
    A = _on_circle((0, 0), crank, TURN)
    E = _meet(A, rod_elbow, W, lower, _side(drawn["A"], W, drawn["E"]))
    K = _meet(A, rod_knee, E, elbow_knee, _side(drawn["A"], drawn["E"], drawn["K"]))
    H = _meet(U, upper, K, hip_knee, _side(U, drawn["K"], drawn["H"]))
    F = _meet(H, hip_foot, K, knee_foot, _side(drawn["H"], drawn["K"], drawn["F"]))
    assert np.allclose(F[0], drawn["F"], rtol=0, atol=1e-8)   # drawn at crank angle 0
    foot = _solve("klann", TURN).points["F"]
    assert np.max(np.hypot(*(foot - F).T)) < 1e-8
    assert np.ptp(foot[:, 0]) == pytest.approx(113.662, abs=1e-3)
    assert np.ptp(foot[:, 1]) == pytest.approx(52.910, abs=1e-3)


# ------------------------------------------------------------------------------------------- pantograph


def test_the_pantographs_pen_doubles_the_tracers_path_about_its_pivot():
    joints = _table("pantograph")["joints"]
    P, O = np.array(joints["P"]), np.array(joints["O"])          # noqa: E741 - the joints' names
    sol = _solve("pantograph", TURN)
    T, Q = sol.points["T"], sol.points["Q"]
    assert np.max(np.abs(np.hypot(*(T - O).T) - 25.0)) < 1e-9          # the crank drives T round its circle
    error = np.max(np.hypot(*((Q - P) - 2.0 * (T - P)).T))
    assert error < 1e-9
    assert np.max(np.abs(np.hypot(*(Q - 2 * O).T) - 50.0)) < 1e-9      # so the pen draws the circle doubled


# ------------------------------------------------------------------------------------------------ shaper


def test_the_shapers_stroke_and_time_ratio_are_the_textbooks(tmp_path):
    """Crank r about O, d above the lever's pivot P; lever L. The lever's limits are where it is tangent to the
    crank circle, the crank square to it: sin(theta) = -r/d, theta = -beta and 180 + beta with sin(beta) = r/d.
    The strokes take 180 + 2 beta and 180 - 2 beta degrees of crank; the ram's x = L sin(phi) + sqrt(rod^2 -
    (h - L cos(phi))^2) at lever angle phi = +-beta differs by 2 L sin(beta) = 2 L r / d."""
    from linkgen.cli import main

    lengths = _table("shaper")["lengths"]
    d, r, L = lengths["P-O"], lengths["O-A"], lengths["P-B"]
    beta = math.asin(r / d)
    stroke = 2 * L * r / d
    ratio = (math.pi + 2 * beta) / (math.pi - 2 * beta)
    assert (stroke, round(ratio, 9)) == (240.0, 1.709952782)
    limits = np.array([-beta, math.pi + beta])
    sol = _solve("shaper", limits)
    ram = sol.points["C"][:, 0]
    assert abs(abs(ram[1] - ram[0]) - stroke) < 1e-9
    assert np.max(np.abs(sol.velocities["C"])) < 1e-9                   # the ram stops there
    everywhere = _solve("shaper", TURN).points["C"][:, 0]               # and goes no further
    assert everywhere.min() >= ram.min() - 1e-9 and everywhere.max() <= ram.max() + 1e-9
    # the report: the lever's swing 2 beta and its time ratio, the ram's stroke (sampled)
    out = CliRunner().invoke(main, ["analyze", str(_path("shaper")), "--json", "-o", str(tmp_path)])
    assert out.exit_code == 0, out.output
    report = json.loads(out.output)
    lever = report["outputs"]["lever"]
    assert lever["swing_deg"] == pytest.approx(math.degrees(2 * beta), abs=1e-6)
    assert lever["time_ratio"] == pytest.approx(ratio, abs=1e-9)
    assert report["outputs"]["ram"]["stroke_mm"] == pytest.approx(stroke, abs=0.01)


# ------------------------------------------------------------------------------------------ single dwell


def test_the_single_dwell_output_stands_still_over_80_degrees_of_crank():
    t = _table("single-dwell")
    j = {k: np.array(v, float) for k, v in t["joints"].items()}
    n = t["lengths"]
    gamma = math.radians(97.5)
    A = _on_circle(j["O2"], n["O2-A"], TURN)
    B = _meet(A, n["A-B"], j["O4"], n["O4-B"], _side(j["A"], j["O4"], j["B"]))
    u = (B - A) / n["A-B"]
    C = A + n["A-C"] * (math.cos(gamma) * u + math.sin(gamma) * np.column_stack([-u[:, 1], u[:, 0]]))
    D = _meet(C, n["C-D"], j["O6"], n["O6-D"], _side(j["C"], j["O6"], j["D"]))
    psi = np.unwrap(np.arctan2(*(D - j["O6"]).T[::-1]))
    sol = _solve("single-dwell", TURN)
    assert np.max(np.hypot(*(sol.points["D"] - D).T)) < 1e-8
    turned = np.unwrap(sol.angles["output"])
    assert np.max(np.abs((turned - turned[0]) - (psi - psi[0]))) < 1e-9
    dwell = (math.radians(148) <= TURN) & (math.radians(228) >= TURN)
    assert math.degrees(np.ptp(psi[dwell])) < 0.15                     # stands still (0.125 degrees)
    assert math.degrees(np.ptp(psi)) > 50.0                            # and swings 51.5 degrees elsewhere


# ---------------------------------------------------------------------------------- pump and toggle press


def test_the_pendulum_pump_strokes_twice_the_crank_and_the_pendulum_swings_asin_r_over_l():
    """Handle r = O-A, pendulum l = B-A, B on the piston's line: the piston's pin O lies s = |OB| from B with
    l - r <= s <= l + r (handle and pendulum in line at both ends); the pendulum leans furthest, asin(r / l), where
    handle and pendulum are square, s = sqrt(l^2 - r^2)."""
    import linkgen

    lengths = _table("pendulum-pump")["lengths"]
    r, l = lengths["O-A"], lengths["B-A"]                               # noqa: E741 - the docstring's l
    s0 = _table("pendulum-pump")["joints"]["O"][1]
    analysis = linkgen.design_linkage(linkgen.load_spec(_path("pendulum-pump"))).kinematics
    lo, hi = analysis.ranges[0]
    assert (lo, hi) == (pytest.approx(l - r - s0, abs=1e-6), pytest.approx(l + r - s0, abs=1e-6))
    travel = math.sqrt(l**2 - r**2) - s0
    sol = analysis.linkage.solve(np.array([travel]))
    A = sol.points["A"][0]
    assert math.degrees(math.atan2(abs(A[0]), A[1])) == pytest.approx(math.degrees(math.asin(r / l)), abs=1e-9)
    assert abs(sol.omegas["pendulum"][0]) < 1e-12


def test_the_toggle_press_bottoms_with_its_toggle_straight_and_a_large_mechanical_advantage():
    """The frame pivot O2 puts the rocker's limits at the straight toggle (|O2 K0| = a + b) and at 30 degrees of
    bend (|O2 K1| = b - a): the ram's lowest point is l1 + l2 below Q, where crank and coupler are in line. The
    ram's height, by circle intersections, and its rate by central differences give the ram's force over the crank
    pin's tangential force, a / |dy_R/dtheta|, which grows without bound towards the bottom."""
    t = _table("toggle-press")
    j, n = {k: np.array(v, float) for k, v in t["joints"].items()}, t["lengths"]
    a, b, l1, l2 = n["O2-A"], n["A-K"], n["Q-K"], n["K-R"]
    K0 = j["Q"] + np.array([0, -l1])
    assert math.dist(j["O2"], K0) == pytest.approx(a + b, abs=1e-8)
    K1 = j["Q"] + l1 * np.array([math.sin(math.radians(30)), -math.cos(math.radians(30))])
    assert math.dist(j["O2"], K1) == pytest.approx(b - a, abs=1e-8)
    side = _side(j["A"], j["Q"], j["K"])

    def ram(theta: np.ndarray) -> np.ndarray:
        K = _meet(_on_circle(j["O2"], a, theta), b, j["Q"], l1, side)
        return K[:, 1] - np.sqrt(l2**2 - (K[:, 0] - j["Q"][0])**2)

    theta = np.radians(np.arange(360000) / 1000)
    y = ram(theta)
    rate = (ram(theta + 1e-6) - ram(theta - 1e-6)) / 2e-6
    bottom = math.atan2(*(K0 - j["O2"])[::-1])
    sol = _solve("toggle-press", np.array([bottom]))
    assert sol.points["R"][0] == pytest.approx(j["Q"] + np.array([0, -(l1 + l2)]), abs=1e-9)
    assert y.min() == pytest.approx(j["Q"][1] - l1 - l2, abs=1e-9)
    top = j["Q"][1] - l1 * math.cos(math.radians(30)) - math.sqrt(l2**2 - (l1 * math.sin(math.radians(30)))**2)
    assert np.ptp(y) == pytest.approx(top - (j["Q"][1] - l1 - l2), abs=1e-9)   # 24.310 mm
    assert np.ptp(_solve("toggle-press", theta[::10]).points["R"][:, 1]) == pytest.approx(np.ptp(y), abs=1e-6)
    sampled = _solve("toggle-press", theta[::100])
    assert np.max(np.abs(sampled.velocities["R"][:, 1] - rate[::100])) < 1e-6
    rise = y - y.min()
    with np.errstate(divide="ignore"):
        advantage = a / np.abs(rate)
    # as the template's comment says: at least 6 over the last mm, 30 over the last 0.1, 169 over the last 0.01
    for within, least in ((1.0, 6), (0.1, 30), (0.01, 169)):
        assert advantage[rise <= within].min() > least
