"""The general linkage's motion as issue 30 found it wrong, each against values derived here independently of the
solver (law of cosines, circle intersections written in this file, dense sampling):

* extremes that fall on a grid point (the course's Example 3.3: two scotch yokes on one crank; the bundled
  pantograph; an Oldham coupling, whose disc runs on the Thales circle of its hubs' pivots) and a property
  test over random four-bars, slider-cranks and six-bars drawn at round angles: every reported extent, stroke
  and swing is that of 100 000 poses to 1e-9;
* limits and swings by circuit (the course's Exercise 3.1: a triple rocker's rocker through the ground line, a
  Grashof double rocker's two circuits), the pendulum pump's two circuits;
* four-bars within 1e-6 to 1e-12 of a change point, either side: every pose on the drawing's branch;
* a PRP dyad whose guides turn parallel refused by name, or limited by a range; a slide's range the same wherever
  the drawing sits; a kite drawn 53 degrees from its fold analysed through it; no raw warning on a rhombus, a
  non-Grashof four-bar or a Whitworth-like build; a chain of 40 dyads solved as often as one of 10.
"""
from __future__ import annotations

import json
import math
import tomllib
import warnings

import numpy as np
import pytest
from click.testing import CliRunner

import linkgen
from linkgen.cli import main as linkgen_cli
from linkgen.kinematics import motion
from linkgen.spec import validate_spec
from tests.conftest import ROOT

TAU = 2.0 * math.pi


# ------------------------------------------------------------------------------------------- helpers (independent)


def meet(p1: np.ndarray, r1: float, p2: np.ndarray, r2: float, side: float) -> np.ndarray:
    """Where circle (p1, r1) meets circle (p2, r2), on ``side`` (+1 left, -1 right) of p1 -> p2 (rows)."""
    p1, p2 = np.broadcast_arrays(np.asarray(p1, float), np.asarray(p2, float))
    d = p2 - p1
    length = np.hypot(d[..., 0], d[..., 1])
    along = (r1**2 - r2**2 + length**2) / (2 * length)
    height = np.sqrt(np.maximum(r1**2 - along**2, 0.0))
    u = d / length[..., None]
    n = np.stack([-u[..., 1], u[..., 0]], axis=-1)
    return p1 + along[..., None] * u + side * height[..., None] * n


def side(p1, p2, j) -> float:
    (ax, ay), (bx, by) = np.subtract(p2, p1), np.subtract(j, p1)
    return math.copysign(1.0, ax * by - ay * bx)


def on_circle(centre, radius: float, theta: np.ndarray) -> np.ndarray:
    return np.asarray(centre, float) + radius * np.column_stack([np.cos(theta), np.sin(theta)])


def turned(v: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]])


def table(joints: dict, links: dict, ground: list, sliders: dict | None = None, tracers=(), input_=None,
          name: str = "t") -> dict:
    return {"name": name, "linkage": {"type": "linkage", "ground": ground,
                                      "input": input_ or {"link": "crank", "pivot": "O"},
                                      "tracers": list(tracers),
                                      "joints": {k: [float(v[0]), float(v[1])] for k, v in joints.items()},
                                      "links": links, "sliders": sliders or {}}}


def _value(v) -> str:
    """A TOML value on one line (tables inline)."""
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_value(x)}" for k, x in v.items()) + "}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, str):
        return json.dumps(v)
    return repr(float(v)) if not isinstance(v, bool) else str(v).lower()


def dump(raw: dict) -> str:
    """A template as TOML: each top-level table a section, its values inline."""
    lines = [f"{k} = {_value(v)}" for k, v in raw.items() if not isinstance(v, dict)]
    for k, v in raw.items():
        if isinstance(v, dict):
            lines += [f"[{k}]"] + [f"{key} = {_value(x)}" for key, x in v.items()]
    return "\n".join(lines) + "\n"


def report(raw: dict) -> dict:
    return linkgen.design_linkage(validate_spec(raw)).report


def fourbar_joints(ground, crank, coupler, rocker, theta0, sign=1.0, shift=(0.0, 0.0)):
    """A four-bar O (crank pivot), Q (rocker pivot) on +x, crank pin A at theta0, B on ``sign`` side of A -> Q."""
    o = np.array(shift, float)
    q = o + np.array([ground, 0.0])
    a = o + pin(crank, math.degrees(theta0))
    b = meet(a, coupler, q, rocker, sign)
    return {"O": o, "Q": q, "A": a, "B": b}


def fourbar_table(ground, crank, coupler, rocker, theta0, sign=1.0, **kw) -> dict:
    return table(fourbar_joints(ground, crank, coupler, rocker, theta0, sign),
                 {"crank": ["O", "A"], "coupler": ["A", "B"], "rocker": ["Q", "B"]}, ["O", "Q"], **kw)


# ------------------------------------------------------------------------------------- extremes on grid points


def pin(radius: float, angle: float) -> np.ndarray:
    """A crank pin (about the origin) at ``angle`` degrees, its coordinates exact at multiples of 90 (as a user
    types them: the drawn angle is then exactly a multiple of pi / 2, as are the grid points of its extremes)."""
    quarter = round(angle % 360.0, 9)
    exact = {0.0: (radius, 0.0), 90.0: (0.0, radius), 180.0: (-radius, 0.0), 270.0: (0.0, -radius)}
    return np.array(exact[quarter]) if quarter in exact else on_circle((0, 0), radius, np.radians([angle]))[0]


def yokes(angle_a: float, angle_b: float) -> dict:
    """The course's Example 3.3: one crank O with pins A (75 mm) and B (125 mm), each in the vertical slot of a
    yoke that slides along x (a block on each pin); drawn with the pins at the given angles (degrees)."""
    a, b = pin(75.0, angle_a), pin(125.0, angle_b)
    joints = {"O": (0, 0), "A": a, "B": b, "YA": (300.0, a[1]), "YB": (300.0, b[1])}
    sliders = {"blockA": {"point": "A", "guide": "yokeA", "angle": 90.0},
               "blockB": {"point": "B", "guide": "yokeB", "angle": 90.0},
               "guideA": {"point": "YA", "guide": "ground", "angle": 0.0, "link": "yokeA"},
               "guideB": {"point": "YB", "guide": "ground", "angle": 0.0, "link": "yokeB"}}
    return table(joints, {"crank": ["O", "A", "B"], "yokeA": ["YA"], "yokeB": ["YB"]}, ["O"], sliders,
                 tracers=("A", "B"))


@pytest.mark.parametrize("angle_a, angle_b", [(90, 90), (0, 0), (90, 270), (45, 135), (180, 0), (270, 0)])
def test_example_3_3_two_scotch_yokes_stroke_twice_their_pins(angle_a, angle_b):
    """A yoke's slot stays vertical, so the yoke's travel along x is its pin's x = R cos(theta): the stroke is 2 R,
    150 and 250 mm (the report had yoke B's stroke 125 mm where its extremes fall on the grid)."""
    r = report(yokes(angle_a, angle_b))
    assert r["outputs"]["guideA"]["stroke_mm"] == pytest.approx(2 * 75.0, abs=1e-9)
    assert r["outputs"]["guideB"]["stroke_mm"] == pytest.approx(2 * 125.0, abs=1e-9)
    assert r["tracers"]["A"] == {"x_mm": pytest.approx([-75.0, 75.0], abs=1e-9),
                                 "y_mm": pytest.approx([-75.0, 75.0], abs=1e-9)}
    assert r["tracers"]["B"] == {"x_mm": pytest.approx([-125.0, 125.0], abs=1e-9),
                                 "y_mm": pytest.approx([-125.0, 125.0], abs=1e-9)}
    assert r["outputs"]["guideB"]["time_ratio"] == pytest.approx(1.0, abs=1e-9)


def test_the_pantograph_tracer_and_pen_have_their_circles_extents():
    """The bundled pantograph: T turns on a crank of |OT| about O, so its extent is O +- |OT|; the pen keeps
    Q - P = k (T - P) with k = |PQ| / |PT| (P, T, Q in line), so Q runs on the circle about P + k (O - P) of
    radius k |OT|: x 150 to 250, y 30 to 130 for the template's numbers (it read T as a point and Q's y from 80)."""
    path = ROOT / "templates" / "pantograph.toml"
    j = {k: np.array(v, float) for k, v in tomllib.loads(path.read_text())["linkage"]["joints"].items()}
    radius = math.dist(j["O"], j["T"])
    k = math.dist(j["P"], j["Q"]) / math.dist(j["P"], j["T"])
    centre = j["P"] + k * (j["O"] - j["P"])
    result = CliRunner().invoke(linkgen_cli, ["analyze", str(path), "--json", "-o", "out-unused-pantograph"])
    assert result.exit_code == 0, result.output
    tracers = json.loads(result.output)["tracers"]
    assert tracers["T"]["x_mm"] == pytest.approx([j["O"][0] - radius, j["O"][0] + radius], abs=1e-9)
    assert tracers["T"]["y_mm"] == pytest.approx([j["O"][1] - radius, j["O"][1] + radius], abs=1e-9)
    assert tracers["Q"]["x_mm"] == pytest.approx([centre[0] - k * radius, centre[0] + k * radius], abs=1e-9)
    assert tracers["Q"]["y_mm"] == pytest.approx([centre[1] - k * radius, centre[1] + k * radius], abs=1e-9)
    assert (k, *tracers["Q"]["x_mm"], *tracers["Q"]["y_mm"]) == pytest.approx((2, 150, 250, 30, 130), abs=1e-9)


@pytest.fixture(autouse=True)
def _no_stray_output(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)                   # the command-line runs above write under the test's own folder


def oldham(d: float, slot: float, ground: float, arm: float, shift: tuple[float, float]) -> dict:
    """An Oldham coupling: hub 1 turns about O1 (the input; its arm O1-A at ``arm`` degrees from its slot), hub 2
    about O2, ``d`` mm from O1 at ``ground`` degrees (its arm O2-B along its slot); the middle disc, holding its
    centre C, slides in hub 1's slot (through O1 at ``slot`` degrees) and in hub 2's (through O2, square to it).
    C is drawn where the two slots cross: the foot of O2 on hub 1's slot."""
    o1 = np.array(shift, float)
    o2 = o1 + pin(d, ground)
    u = pin(1.0, slot)
    c = o1 + float(np.dot(o2 - o1, u)) * u
    joints = {"O1": o1, "O2": o2, "A": o1 + pin(0.6 * d, slot + arm), "B": o2 + pin(0.6 * d, slot + 90.0), "C": c}
    sliders = {"slot1": {"point": "C", "guide": "hub1", "angle": slot % 360.0, "link": "disc"},
               "slot2": {"point": "C", "guide": "hub2", "angle": (slot + 90.0) % 360.0, "link": "disc"}}
    return table(joints, {"hub1": ["O1", "A"], "hub2": ["O2", "B"], "disc": ["C"]}, ["O1", "O2"], sliders,
                 tracers=("C",), input_={"link": "hub1", "pivot": "O1"}, name="oldham")


@pytest.mark.parametrize("d, slot, ground, arm, shift, on_grid", [
    (40.0, 0.0, 0.0, 0.0, (0.0, 0.0), True),        # C's y extent was reported -20 to 0: half the disc's range
    (40.0, 45.0, 0.0, 0.0, (0.0, 0.0), True),
    (40.0, 90.0, 0.0, 0.0, (0.0, 0.0), True),
    (37.3, 135.0, 90.0, 30.0, (123.4, -56.7), True),   # a vertical ground line, the arm off the slot, off the origin
    (37.3, 270.0, 45.0, -45.0, (0.0, 0.0), True),
    (40.0, 37.3, 0.0, 0.0, (0.0, 0.0), False),
    (25.0, 11.7, 17.0, 90.0, (-8.0, 5.0), False),
])
def test_an_oldham_couplings_disc_runs_on_the_thales_circle_and_its_hubs_turn_together(d, slot, ground, arm, shift,
                                                                                       on_grid, tmp_path):
    """Oldham coupling, hubs' pivots O1, O2 a distance d apart. The disc keeps its angle to both hubs' slots, which
    are square to each other, so hub 2 turns exactly with hub 1 (the direction of O2-B less that of O1-A stays
    the drawn one) and turns fully with it. C lies on both slots: the foot of O2 on hub 1's slot, which sees
    O1-O2 at a right angle, so C runs on the circle with diameter O1-O2 (Thales), twice a turn: C - O1 =
    d cos(s - g) (cos s, sin s), so C - M = (d / 2) (cos(2 s - g), sin(2 s - g)) (M the midpoint, s hub 1's slot
    direction, g the ground line's), and C's extents are M -+ d / 2 on both axes. Its extremes lie where 2 s - g
    is a multiple of 90 degrees: on the search's grid points when s and g are round angles (checked here),
    between them otherwise."""
    raw = oldham(d, slot, ground, arm, shift)
    path = tmp_path / "oldham.toml"
    path.write_text(dump(raw))
    grid_step = 360.0 / motion.GRID                     # the search's input step from the drawing, degrees
    steps = ((0.5 * ground - slot) % 45.0) / grid_step  # from the drawing to C's extremes, in grid steps
    assert (abs(steps - round(steps)) < 1e-9) is on_grid

    result = CliRunner().invoke(linkgen_cli, ["analyze", str(path), "--json"])
    assert result.exit_code == 0, result.output
    r = json.loads(result.output)
    assert r["input_range_deg"] is None and r["toggles"] == []
    assert r["outputs"]["hub2"] == {"limit_positions": [], "turns_fully": True, "time_ratio": None}
    text = CliRunner().invoke(linkgen_cli, ["analyze", str(path)])
    assert text.exit_code == 0 and "\ninput turns fully\n" in text.output and "  hub2: turns fully\n" in text.output
    j = {k: np.array(v) for k, v in raw["linkage"]["joints"].items()}
    m = 0.5 * (j["O1"] + j["O2"])
    assert r["tracers"]["C"] == {"x_mm": pytest.approx([m[0] - d / 2, m[0] + d / 2], abs=1e-9),
                                 "y_mm": pytest.approx([m[1] - d / 2, m[1] + d / 2], abs=1e-9)}

    a = linkgen.design_linkage(validate_spec(raw)).kinematics
    theta0 = math.radians(slot + arm)                   # the input: hub 1's arm O1-A, counter-clockwise from +x
    x = theta0 + np.linspace(0.0, TAU, 100_001)
    sol = a.linkage.solve(x)
    p = sol.points

    def direction(tip: str, pivot: str) -> np.ndarray:
        return np.arctan2(p[tip][:, 1] - j[pivot][1], p[tip][:, 0] - j[pivot][0])

    drawn = math.atan2(*(j["B"] - j["O2"])[::-1]) - math.atan2(*(j["A"] - j["O1"])[::-1])
    hub1 = np.remainder(direction("A", "O1") - x + math.pi, TAU) - math.pi
    apart = np.remainder(direction("B", "O2") - direction("A", "O1") - drawn + math.pi, TAU) - math.pi
    assert np.degrees(np.abs(hub1)).max() < 1e-9                    # hub 1 turns with the input, a whole turn
    assert np.degrees(np.abs(apart)).max() < 1e-9                   # hub 2 turns exactly with hub 1
    turn = np.remainder(sol.angle("disc") - sol.angle("hub1") + math.pi, TAU) - math.pi
    assert np.degrees(np.abs(turn)).max() < 1e-9                    # the disc keeps hub 1's (and 2's) angle
    s = x - theta0 + math.radians(slot)                 # hub 1's slot direction
    u = np.column_stack([np.cos(s), np.sin(s)])
    foot = j["O1"] + ((j["O2"] - j["O1"]) @ u.T)[:, None] * u
    assert np.hypot(*(p["C"] - foot).T).max() < 1e-9
    assert np.abs(np.hypot(*(p["C"] - m).T) - d / 2).max() < 1e-9    # Thales


# ---------------------------------------------------------------------- every extent equals that of 100 000 poses

#: poses each random linkage is sampled at: uniformly, then around each sampled extreme
UNIFORM, LOCAL = 40_000, 1_500


def _sampled_extent(f, circuit: list[tuple[float, float]], angle: bool = False) -> tuple[float, float]:
    """The least and greatest of ``f(theta, piece)`` over the circuit's pieces: sampled uniformly, then densely
    within two steps of each sampled least and greatest. An angle is followed continuously along each piece (and
    from one piece into the next, which starts where the last one ended: the non-Grashof four-bar's second
    piece runs back from its range's end on the other assembly)."""
    out_lo, out_hi = math.inf, -math.inf
    previous_end = None
    for piece, (lo, hi) in enumerate(circuit):
        t = np.linspace(lo, hi, UNIFORM)
        raw = f(t, piece)
        v = np.unwrap(raw) if angle else raw
        if angle and previous_end is not None:        # this piece starts (at hi) where the last one ended
            v = v + TAU * round((previous_end - v[-1]) / TAU)
        if angle:
            previous_end = v[0] if piece % 2 else v[-1]
        step = t[1] - t[0]
        for k in (int(np.argmin(v)), int(np.argmax(v))):
            fine = np.linspace(max(lo, t[k] - 2 * step), min(hi, t[k] + 2 * step), LOCAL)
            w = f(fine, piece)
            if angle:
                w = v[k] + np.remainder(w - raw[k] + math.pi, TAU) - math.pi
            w = np.concatenate([v, w])
            out_lo, out_hi = min(out_lo, float(w.min())), max(out_hi, float(w.max()))
    return out_lo, out_hi


def _fourbar_case(rng: np.random.Generator, grashof: bool):
    """A crank-rocker (Grashof, the crank the shortest) turning fully, or a non-Grashof four-bar over its one
    range: where |A Q| lies between |coupler - rocker| and coupler + rocker (law of cosines), on both assemblies
    (its circuit); drawn at a multiple of 45 degrees inside the range, with a coupler point P."""
    while True:
        ground, crank, coupler, rocker = (float(x) for x in rng.integers(20, 200, 4))
        s, p, q, longest = sorted([ground, crank, coupler, rocker])
        if abs(s + longest - p - q) < 5 or (grashof and not (crank == s and s + longest < p + q)) or (
                not grashof and s + longest < p + q):
            continue
        if grashof:
            lo, hi = 0.0, TAU
        else:
            z_near = abs(ground - crank)                      # |A Q| at theta 0; its largest is at 180
            if abs(coupler - rocker) <= z_near:               # the range holds 0, ends where |A Q| = coupler + rocker
                a = math.acos((ground**2 + crank**2 - (coupler + rocker) ** 2) / (2 * ground * crank))
                lo, hi = -a, a
            else:                                             # it holds 180, ends where |A Q| = |coupler - rocker|
                b = math.acos((ground**2 + crank**2 - (coupler - rocker) ** 2) / (2 * ground * crank))
                lo, hi = b, TAU - b
        inside = [a for a in np.radians(np.arange(-360, 360, 45)) if lo + 0.05 < a < hi - 0.05]
        if inside:
            break
    theta0 = float(rng.choice(inside))
    sign = float(rng.choice([-1.0, 1.0]))
    j = fourbar_joints(ground, crank, coupler, rocker, theta0, sign)
    pd, pa = float(rng.uniform(20, 120)), float(rng.uniform(-1, 1))
    j["P"] = j["A"] + pd * turned((j["B"] - j["A"])[None, :] / coupler, np.array([pa]))[0]
    raw = table(j, {"crank": ["O", "A"], "coupler": ["A", "B", "P"], "rocker": ["Q", "B"]}, ["O", "Q"],
                tracers=("A", "B", "P"))
    local = turned((j["P"] - j["A"])[None, :], -np.array([math.atan2(*(j["B"] - j["A"])[::-1])]))[0]

    def pose(t: np.ndarray, piece: int) -> dict[str, np.ndarray]:
        a = on_circle(j["O"], crank, t)
        b = meet(a, coupler, j["Q"], rocker, sign if piece == 0 else -sign)
        phi = np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0])
        return {"A": a, "B": b, "P": a + turned(np.broadcast_to(local, a.shape), phi),
                "rocker": np.arctan2(b[:, 1] - j["Q"][1], b[:, 0] - j["Q"][0])}

    circuit = [(theta0, theta0 + TAU)] if grashof else [(lo, hi)] * 2
    return raw, pose, circuit, ()


def _slider_crank_case(rng: np.random.Generator):
    crank = float(rng.integers(10, 80))
    offset = float(rng.choice([0.0, float(rng.integers(-30, 30))]))
    rod = float(rng.integers(int(crank + abs(offset) + 20), 300))
    theta0 = float(rng.choice(np.radians(np.arange(0, 360, 45))))

    def x_of(t: np.ndarray) -> np.ndarray:
        return crank * np.cos(t) + np.sqrt(rod**2 - (crank * np.sin(t) - offset) ** 2)

    a = pin(crank, math.degrees(theta0))
    b = (float(x_of(np.array([theta0]))[0]), offset)
    raw = table({"O": (0, 0), "A": a, "B": b}, {"crank": ["O", "A"], "rod": ["A", "B"]}, ["O"],
                {"slider": {"point": "B", "guide": "ground", "angle": 0.0}}, tracers=("A", "B"))

    def pose(t: np.ndarray, piece: int) -> dict[str, np.ndarray]:
        return {"A": on_circle((0, 0), crank, t), "B": np.column_stack([x_of(t), np.full(len(t), offset)]),
                "slider": x_of(t)}

    return raw, pose, [(theta0, theta0 + TAU)], ("slider",)


def _six_bar_case(rng: np.random.Generator):
    """A Watt II: a crank-rocker O-A-B-Q whose rocker plate carries C, and a dyad C-D-R to a third pivot, its
    lengths chosen from C's path so that it closes over the whole turn."""
    ground, crank, coupler, rocker = 180.0, float(rng.integers(40, 70)), 190.0, 150.0
    theta0 = float(rng.choice(np.radians(np.arange(0, 360, 45))))
    sign = 1.0
    j = fourbar_joints(ground, crank, coupler, rocker, theta0, sign)
    plate = float(rng.uniform(0.5, 1.2))
    c_local = plate * turned((j["B"] - j["Q"])[None, :], np.array([float(rng.uniform(0.3, 1.2))]))[0]
    j["C"] = j["Q"] + c_local
    j["R"] = np.array([float(rng.uniform(280, 360)), float(rng.uniform(20, 120))])
    t = np.linspace(0, TAU, 721)
    b = meet(on_circle(j["O"], crank, t), coupler, j["Q"], rocker, sign)
    turn = np.arctan2(b[:, 1], b[:, 0] - ground) - math.atan2(j["B"][1], j["B"][0] - ground)
    path = j["Q"] + turned(np.broadcast_to(c_local, (len(t), 2)), turn)
    far = float(np.hypot(*(path - j["R"]).T).max())
    near = float(np.hypot(*(path - j["R"]).T).min())
    r5, r6 = 0.5 * far + 0.1 * (far - near) + 5, 0.5 * far + 5
    dside = float(rng.choice([-1.0, 1.0]))
    j["D"] = meet(j["C"], r5, j["R"], r6, dside)
    raw = table(j, {"crank": ["O", "A"], "coupler": ["A", "B"], "rocker": ["Q", "B", "C"], "link5": ["C", "D"],
                    "output": ["R", "D"]}, ["O", "Q", "R"], tracers=("C", "D"))

    def pose(tt: np.ndarray, piece: int) -> dict[str, np.ndarray]:
        bb = meet(on_circle(j["O"], crank, tt), coupler, j["Q"], rocker, sign)
        phi = np.arctan2(bb[:, 1], bb[:, 0] - ground) - math.atan2(j["B"][1], j["B"][0] - ground)
        cc = j["Q"] + turned(np.broadcast_to(c_local, (len(tt), 2)), phi)
        dd = meet(cc, r5, j["R"], r6, dside)
        return {"C": cc, "D": dd, "rocker": phi, "output": np.arctan2(dd[:, 1] - j["R"][1], dd[:, 0] - j["R"][0])}

    if np.any(np.hypot(*(path - j["R"]).T) >= r5 + r6) or np.any(np.hypot(*(path - j["R"]).T) <= abs(r5 - r6)):
        return None
    return raw, pose, [(theta0, theta0 + TAU)], ()


def _cases():
    rng = np.random.default_rng(30)
    made: list = []
    makers = [lambda: _fourbar_case(rng, True), lambda: _fourbar_case(rng, True), lambda: _fourbar_case(rng, False),
              lambda: _slider_crank_case(rng), lambda: _slider_crank_case(rng), lambda: _slider_crank_case(rng),
              lambda: _six_bar_case(rng), lambda: _six_bar_case(rng)]
    for make in makers:
        case = None
        while case is None:
            case = make()
        made.append(case)
    return made


@pytest.mark.parametrize("index", range(8))
def test_every_reported_extent_stroke_and_swing_is_that_of_100000_poses(index):
    """Random four-bars (two crank-rockers, a non-Grashof one over its range on both assemblies: its circuit),
    slider-cranks and Watt II six-bars, drawn at multiples of 45 degrees so that the crank pin's extremes (and a
    centred slider's) fall on the search's grid: each tracer's x and y extent, each slider's stroke and each
    rocker's swing is the one of ~100 000 poses solved here by circle intersections, to 1e-9 mm (and 1e-9
    degrees)."""
    raw, pose, circuit, strokes = _cases()[index]
    r = report(raw)
    total = 0
    for point in raw["linkage"]["tracers"]:
        for axis, key in ((0, "x_mm"), (1, "y_mm")):
            sampled = _sampled_extent(lambda t, k, p=point, a=axis: pose(t, k)[p][:, a], circuit)
            total += len(circuit) * (UNIFORM + 2 * LOCAL)
            assert r["tracers"][point][key] == pytest.approx(list(sampled), abs=1e-9), (point, key)
    for slider in strokes:
        lo, hi = _sampled_extent(lambda t, k, s=slider: pose(t, k)[s], circuit)
        assert r["outputs"][slider]["stroke_mm"] == pytest.approx(hi - lo, abs=1e-9)
    for rocker in ("rocker", "output"):
        if rocker in r["outputs"] and "swing_deg" in r["outputs"][rocker]:
            lo, hi = _sampled_extent(lambda t, k, name=rocker: pose(t, k)[name], circuit, angle=True)
            assert r["outputs"][rocker]["swing_deg"] == pytest.approx(math.degrees(hi - lo), abs=1e-9), rocker
    assert total >= 100_000


# ------------------------------------------------------------------------------------- limits and swings by circuit


@pytest.mark.parametrize("rocker", [88.0, 125.0, 163.0])
def test_exercise_3_1_swings_by_circuit(rocker):
    """The course's Exercise 3.1, ground 100, crank 125, coupler 75 (drawn at 60 degrees, open): the rocker's
    limits are where crank and coupler lie in line, |O B| = 125 + 75 = 200 or 125 - 75 = 50 (law of cosines at
    Q in the triangle O Q B). Rocker 163 (triple rocker): only |O B| = 200 closes, at +-83.96 degrees from Q's +x,
    and the rocker sweeps between them through 180 (the ground line): 192.08 degrees. Rocker 88 (triple rocker):
    only |O B| = 50, at +-150.01 degrees, through 0: 300.02 degrees. Rocker 125 (Grashof double rocker): the
    circuit drawn in the upper half reaches both, 54.90 and 157.67 degrees: 102.77; the lower half is a separate
    circuit. Each limit lies on its own branch of the one dyad."""
    ground, crank, coupler = 100.0, 125.0, 75.0

    def at_q(ob: float) -> float | None:
        c = (ground**2 + rocker**2 - ob**2) / (2 * ground * rocker)
        return math.degrees(math.pi - math.acos(c)) if abs(c) <= 1 else None   # from +x at Q, upper half

    limits = [a for a in (at_q(crank + coupler), at_q(crank - coupler)) if a is not None]
    if rocker == 125.0:
        swing = abs(limits[0] - limits[1])
    else:
        (limit,) = limits
        swing = 360.0 - 2 * limit if limit < 90 else 2 * limit
    raw = fourbar_table(ground, crank, coupler, rocker, math.radians(60.0))
    r = report(raw)
    out = r["outputs"]["rocker"]
    assert out["swing_deg"] == pytest.approx(swing, abs=1e-9)
    drawn = math.degrees(math.atan2(*(np.array(raw["linkage"]["joints"]["B"]) - (ground, 0.0))[::-1]))
    found = sorted(math.remainder(drawn + e["angle_from_drawing_deg"], 360.0) for e in out["limit_positions"])
    want = sorted([limits[0], -limits[0]] if len(limits) == 1 else limits)
    assert found == pytest.approx(want, abs=1e-9)
    assert {e["branches"] for e in out["limit_positions"]} == {"as drawn", "other branch at B"}
    assert r["circuit"]["closed"] is True and len(r["circuit"]["pieces"]) == 2
    assert len(r["circuit"]["separate_deg"]) == (1 if rocker == 125.0 else 0)
    if rocker != 125.0:
        assert swing > 180.0                                    # through the ground line


def test_the_pendulum_pumps_circuits():
    """The pendulum pump: the piston's range on the drawing's branch is the stroke -40..40 mm (and a second piece,
    -280..-200 mm, with the piston on the pendulum's other side: a separate circuit); over its circuit the
    pendulum leans asin(r / l) either way of the piston's line, 2 asin(40 / 120) = 38.94 degrees."""
    r = report(tomllib.loads((ROOT / "templates" / "pendulum-pump.toml").read_text()))
    assert r["outputs"]["pendulum"]["swing_deg"] == pytest.approx(2 * math.degrees(math.asin(40 / 120)), abs=1e-9)
    assert r["circuit"]["separate_mm"] == [pytest.approx([-280.0, -200.0], abs=1e-6)]
    assert [p["input_mm"] for p in r["circuit"]["pieces"]] == [pytest.approx([-40.0, 40.0], abs=1e-6)] * 2


# ------------------------------------------------------------------------------------ branches near change points


def _near_class_three(rng: np.random.Generator, eps: float, grashof: bool):
    """Integer lengths with S + L = P + Q (no two equal), the longest moved by eps of itself: shorter is Grashof,
    longer is not."""
    while True:
        s, p, q = sorted(int(x) for x in rng.integers(5, 200, 3))
        if len({s, p, q, p + q - s}) == 4 and s > 0:
            break
    longest = float(p + q - s) * (1.0 - eps if grashof else 1.0 + eps)
    return [float(x) for x in rng.permutation([float(s), float(p), float(q), longest])]


@pytest.mark.parametrize("eps", [1e-6, 1e-8, 1e-10, 1e-12])
@pytest.mark.parametrize("grashof", [True, False])
def test_four_bars_near_a_change_point_stay_on_the_drawings_branch(eps, grashof):
    """Random four-bars within eps (of the longest link) of a change point, either side, drawn at a random angle
    of their range on either assembly: no change point is reported, and every pose over the range (to within
    1e-9 rad of its ends) has B where the circles about A and Q meet on the drawing's side of A -> Q."""
    rng = np.random.default_rng(int(-math.log10(eps)) * 2 + grashof)
    for _ in range(4):
        ground, crank, coupler, rocker = _near_class_three(rng, eps, grashof)
        t = np.linspace(0, TAU, 20001)
        z = np.hypot(*(on_circle((0, 0), crank, t) - (ground, 0)).T)
        reach = (z <= coupler + rocker) & (z >= abs(coupler - rocker))
        if not reach.any():
            continue
        theta0 = float(rng.choice(t[reach][len(t[reach]) // 10: -len(t[reach]) // 10 or None]))
        sign = float(rng.choice([-1.0, 1.0]))
        raw = fourbar_table(ground, crank, coupler, rocker, theta0, sign)
        a = linkgen.design_linkage(validate_spec(raw)).kinematics
        assert not [k for k in a.toggles if k.kind == "change point"], (ground, crank, coupler, rocker)
        lo, hi = a.ranges[0] if a.ranges else (theta0, theta0 + TAU)
        x = np.concatenate([np.linspace(lo, hi, 4001), lo + np.geomspace(1e-9, 1e-2, 30),
                            hi - np.geomspace(1e-9, 1e-2, 30)])
        sol = a.linkage.solve(x)
        b = meet(on_circle((0, 0), crank, x), coupler, np.array([ground, 0.0]), rocker, sign)
        err = np.hypot(*(sol.points["B"] - b).T)
        assert err.max() < 1e-6, (ground, crank, coupler, rocker, theta0, float(x[np.argmax(err)]))


# ------------------------------------------------------------------------------ runaways, slides, kites, warnings


def _shaper_prp(crank: float, ground: float, height: float, theta0: float, input_range=None) -> dict:
    """A crank O-A, a lever about Q = (ground, 0) with a block on the crank pin sliding in it, and a ram pin R
    sliding along the lever and along the line y = height (a PRP dyad). With crank > ground the lever turns fully
    and lies along the ram's guide where A is on the x axis (theta 0 and 180): R runs to infinity there."""
    a = on_circle((0, 0), crank, np.array([theta0]))[0]
    q = np.array([ground, 0.0])
    slot = math.atan2(*(a - q)[::-1])
    along = np.array([math.cos(slot), math.sin(slot)])
    r = q + (height / along[1]) * along
    joints = {"O": (0, 0), "Q": q, "A": a, "E": q + 50 * along, "R": r}
    sliders = {"block": {"point": "A", "guide": "lever", "angle": math.degrees(slot)},
               "ram": {"point": "R", "guide": "ground", "angle": 0.0},
               "ramblock": {"point": "R", "guide": "lever", "angle": math.degrees(slot)}}
    inp = {"link": "crank", "pivot": "O", **({"range": list(input_range)} if input_range else {})}
    return table(joints, {"crank": ["O", "A"], "lever": ["Q", "E"]}, ["O", "Q"], sliders, input_=inp)


def test_a_prp_dyad_whose_guides_turn_parallel_is_refused_by_name_or_limited_by_a_range(tmp_path):
    """Never "input turns fully" with a finite stroke: one line naming linkage.input and the range to give; with
    a range the ram's stroke is the closed form's, R's x = ground + height / tan(lever angle)."""
    raw = _shaper_prp(120.0, 60.0, 200.0, 0.7)
    path = tmp_path / "prp.toml"
    path.write_text(dump(raw))
    result = CliRunner().invoke(linkgen_cli, ["analyze", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 2 and not (tmp_path / "out").exists()
    assert result.stderr.count("\n") == 1
    assert result.stderr.startswith("error: linkage.input: at input 0 degrees the guides of")
    assert "R runs to infinity" in result.stderr and "range = [from, to]" in result.stderr
    r = report(_shaper_prp(120.0, 60.0, 200.0, 0.7, (20.0, 160.0)))
    t = np.radians(np.linspace(20, 160, 200001))
    a = on_circle((0, 0), 120.0, t)
    lever = np.arctan2(a[:, 1], a[:, 0] - 60.0)
    x = 60.0 + 200.0 / np.tan(lever)
    assert r["outputs"]["ram"]["stroke_mm"] == pytest.approx(x.max() - x.min(), abs=1e-6)


def _slide(shift: tuple[float, float]) -> dict:
    """A slide input K moving a carriage whose pin P slides in a lever's slot (the lever about Q), the lever's end
    R driving a rod to S on a vertical guide: no toggle ever ends the input's travel."""
    k, p, q = np.array([0.0, 0.0]), np.array([30.0, 0.0]), np.array([0.0, 100.0])
    u = (p - q) / np.hypot(*(p - q))
    r = q + 80 * u
    s = np.array([150.0, r[1] + math.sqrt(250.0**2 - (150.0 - r[0]) ** 2)])
    joints = {name: v + shift for name, v in {"K": k, "P": p, "Q": q, "R": r, "S": s}.items()}
    sliders = {"feed": {"point": "K", "guide": "ground", "angle": 0.0, "link": "carriage"},
               "slot": {"point": "P", "guide": "lever", "angle": math.degrees(math.atan2(u[1], u[0]))},
               "out": {"point": "S", "guide": "ground", "angle": 90.0}}
    return table(joints, {"carriage": ["K", "P"], "lever": ["Q", "R"], "rod": ["R", "S"]}, ["Q"], sliders,
                 tracers=("S",), input_={"slider": "feed"})


def test_a_slides_range_does_not_move_with_the_drawing():
    """The same linkage drawn 300 mm further out reports the same ranges and strokes (the search's bound is 4 times
    the drawing's own size, 4 x 281.92 mm here, not its distance from the origin), and says that no toggle ends the
    range there."""
    near, far = report(_slide(np.array([0.0, 0.0]))), report(_slide(np.array([300.0, 300.0])))
    assert np.allclose(near["input_range_mm"], far["input_range_mm"], rtol=0, atol=1e-9)
    assert near["outputs"]["out"]["stroke_mm"] == pytest.approx(far["outputs"]["out"]["stroke_mm"], abs=1e-9)
    size = max(math.dist(a, b) for a in _slide(np.zeros(2))["linkage"]["joints"].values()
               for b in _slide(np.zeros(2))["linkage"]["joints"].values())
    assert near["input_bound_mm"] == pytest.approx(4 * size, abs=1e-9)
    assert near["input_range_mm"] == [pytest.approx([-4 * size, 4 * size], abs=1e-9)]
    assert any("no toggle ends the slide's range" in w for w in near["warnings"])


def test_a_kite_drawn_53_degrees_from_its_fold_analyses_through_it(tmp_path):
    """A deltoid 114/114/178/178 drawn at 53 degrees (its fold at 0, where A sits on Q) builds and analyses: its
    change point is reported at 0, and over two turns (its branches swap once a turn) the rocker turns fully, B
    running round the whole circle of 178 mm about Q."""
    raw = fourbar_table(114.0, 114.0, 178.0, 178.0, math.radians(53.0), tracers=("B",))
    raw["parts"] = {"width": 8.0, "thickness": 3.0, "pin_diameter": 3.0, "sheet": [1500.0, 1500.0]}
    path = tmp_path / "kite.toml"
    path.write_text(dump(raw))
    for command in ("analyze", "build"):
        result = CliRunner().invoke(linkgen_cli, [command, str(path), "-o", str(tmp_path / command), "--json"]
                                    if command == "analyze" else [command, str(path), "-o", str(tmp_path / command)])
        assert result.exit_code == 0, result.stderr
    r = report(raw)
    assert [(t["kind"], t["input_deg"]) for t in r["toggles"]] == [("change point", pytest.approx(0.0, abs=1e-9))]
    assert r["outputs"]["rocker"].get("turns_fully") is True
    assert [p["branches"] for p in r["circuit"]["pieces"]] == ["as drawn", "other branch at B"]     # two turns
    assert r["tracers"]["B"] == {"x_mm": pytest.approx([114 - 178, 114 + 178], abs=1e-9),
                                 "y_mm": pytest.approx([-178, 178], abs=1e-9)}


def _whitworth_like(crank: float, ground: float, arm: float, rod: float, theta0: float) -> dict:
    a = on_circle((0, 0), crank, np.array([theta0]))[0]
    q = np.array([ground, 0.0])
    slot = math.atan2(*(a - q)[::-1])
    c = q + arm * np.array([math.cos(slot), math.sin(slot)])
    d = np.array([ground, c[1] + math.sqrt(rod**2 - (c[0] - ground) ** 2)])
    sliders = {"block": {"point": "A", "guide": "slotted", "angle": math.degrees(slot)},
               "ram": {"point": "D", "guide": "ground", "angle": 90.0}}
    return table({"O": (0, 0), "Q": q, "A": a, "C": c, "D": d},
                 {"crank": ["O", "A"], "slotted": ["Q", "C"], "rod": ["C", "D"]}, ["O", "Q"], sliders)


@pytest.mark.parametrize("raw", [
    fourbar_table(20.0, 20.0, 20.0, 20.0, math.radians(30.0)),                      # a rhombus
    fourbar_table(20.0, 20.0, 20.0, 20.0, math.radians(90.0), tracers=("B",)),
    fourbar_table(100.0, 70.0, 60.0, 80.0, math.radians(30.0), tracers=("B",)),     # non-Grashof
    fourbar_table(100.0, 125.0, 75.0, 88.0, 0.0, tracers=("B",)),
    _whitworth_like(100.0, 40.0, 50.0, 180.0, 0.3),
    _whitworth_like(60.0, 60.0, 50.0, 180.0, math.pi / 2),                          # the pin over the pivot
], ids=["rhombus-30", "rhombus-90", "non-grashof", "triple-rocker", "whitworth", "whitworth-crank-is-ground"])
def test_no_raw_warning_on_degenerate_linkages(raw, tmp_path):
    """Analysed with figures and built with parts, as warnings-as-errors: nothing but the report."""
    raw = {**raw, "parts": {"width": 8.0, "thickness": 3.0, "pin_diameter": 3.0, "sheet": [3000.0, 3000.0]}}
    path = tmp_path / "case.toml"
    path.write_text(dump(raw))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for args in (["analyze", str(path), "--figures", "--angle", "45"], ["build", str(path)]):
            result = CliRunner().invoke(linkgen_cli, [*args, "-o", str(tmp_path / args[0])])
            assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
            assert result.exit_code in (0, 2) and "Warning" not in result.stderr, result.stderr
            assert result.exit_code == 0 or result.stderr.count("\n") == 1


def chain(n: int) -> dict:
    """A crank and n four-bar loops in a row, each rocker's pin driving the next loop's coupler."""
    joints = {"O": (0.0, 0.0), "J0": (10.0, 0.0)}
    links = {"crank": ["O", "J0"]}
    for k in range(1, n + 1):
        joints[f"G{k}"], joints[f"J{k}"] = (60.0 * k, 0.0), (60.0 * k + 10.0, 50.0)
        links[f"c{k}"], links[f"r{k}"] = [f"J{k - 1}", f"J{k}"], [f"G{k}", f"J{k}"]
    return table(joints, links, ["O"] + [f"G{k}" for k in range(1, n + 1)], tracers=(f"J{n}",))


def test_a_chain_of_40_dyads_takes_no_more_solves_than_a_few_dozen(monkeypatch):
    """Every search refines all its dyads' or outputs' events at once, so the number of solves does not grow with
    the number of dyads (each solve's work grows linearly with them): 10 or 40 chained dyads take a few dozen to a
    few hundred solves (Newton's iterations vary), where each dyad took 160 golden-section solves of the whole
    linkage and each rocker up to 60 more (quadratic: 40 dyads ran about 90 s)."""
    from linkgen.kinematics.linkage import Linkage

    calls = []
    solve = Linkage.solve

    def counted(self, *args, **kwargs):
        calls.append(1)
        return solve(self, *args, **kwargs)

    monkeypatch.setattr(Linkage, "solve", counted)
    counts = []
    for n in (10, 40):
        calls.clear()
        r = report(chain(n))
        assert len(r["dyads"]) == n
        counts.append(len(calls))
    assert max(counts) < 300
