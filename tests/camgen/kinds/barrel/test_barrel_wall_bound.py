"""The barrel's reported wall error bounds its STL: random barrels (seeded: a groove for a cylindrical and for a
conical roller, one for an arm, a rib) at 0.1, 0.01 and 0.001 mm, each STL read back and its walls measured at 9
radii between the floor and the rim and 120 angles round the cam (between the mesh's rings and loops, wherever the
probes fall) against the exact envelope computed here from the spec alone; the STLs hold no edge shorter than 4
single-precision steps and (at 0.1 and 0.01 mm, and the bundled templates) no self-intersecting triangles.

The exact wall on the vertical line at radius r and angle phi (the program's angle: the polar angle is -sense phi)
is where the rollers' sweep ends along it: each roller, turned by its cam angle theta so that its axis runs along
x at the tangential offset e(theta) and the height zc(theta), meets the line between zc -+ sqrt(R(a)^2 - w^2)
(w = r sin(phi - theta) - e, a = r cos(phi - theta), R(a) = r0 + taper a the cutter's radius), so the lower wall is
the least of zc - sqrt(...) over theta and the upper the largest of zc + sqrt(...): a grid of theta, then golden
section. The mesh's wall is where the same line crosses its triangles. Their distance is the height between
them times the cosine of the wall's slope (the wall's gradient by central differences), a first-order distance
off the true one by at most d^2 / (2 rho) for a wall bent to a radius rho (here at least the cutter's).
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main
from camgen.spec import validate_spec
from tests.conftest import ROOT
from tests.support.mesh_intersections import self_intersections

GOLD = (math.sqrt(5) - 1) / 2
LAWS = ("cycloidal", "harmonic", "polynomial-345", "modified-sine", "polynomial-4567")


class Envelope:
    """The cutter's family from the spec alone: the program's s(theta), the follower's pose, the cutter's size."""

    def __init__(self, spec, shift: float = 0.0):
        cam, f = spec.cam, spec.follower
        self.program = _program(spec)
        cone = f.roller_shape == "conical"
        self.taper = f.roller_radius / cam.pitch_radius if cone else 0.0
        self.cutter = f.roller_radius + cam.running_clearance / 2 * (math.hypot(1.0, self.taper) if cone else 1.0)
        self.r0 = self.cutter - self.taper * cam.pitch_radius
        steps = [{"rise": 1, "return": -1}.get(seg.type, 0) * (seg.lift or 0.0) for seg in spec.motion]
        levels = np.cumsum([0.0, *steps])
        self.sense = 1 if cam.rotation == "ccw" else -1
        self.arm = None
        if f.type == "oscillating-roller":         # square to the cam's axis at mid-swing, its pivot mid-length
            self.arm = (f.arm_length, f.pivot_distance, (levels.max() - levels.min()) / 2, cam.length / 2)
        self.z0 = (cam.length - levels.max() - levels.min()) / 2 + shift

    def pose(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The roller axis's height zc and tangential offset e (mm) at cam angles ``theta``."""
        s = self.program(np.mod(theta, 2 * math.pi))
        if self.arm is None:
            return self.z0 + s, np.zeros_like(s)
        length, pivot, mid, height = self.arm
        psi = np.radians(s - mid)
        return height + length * np.sin(psi), -self.sense * (pivot - length * np.cos(psi))

    def _reach(self, theta, r, phi, side):
        """-side times the height the roller at ``theta`` reaches on the line (r, phi) on its side (inf: misses)."""
        zc, e = self.pose(theta)
        u = phi - theta
        w = r * np.sin(u) - e
        h2 = (self.r0 + self.taper * r * np.cos(u)) ** 2 - w**2
        meets = (h2 >= 0) & (np.cos(u) > 0)
        return np.where(meets, -side * (zc + side * np.sqrt(np.where(meets, h2, 0.0))), np.inf)

    def wall(self, r: np.ndarray, phi: np.ndarray, side: int) -> tuple[np.ndarray, np.ndarray]:
        """The wall's height (mm) on the vertical lines (r, phi) (1-D arrays), side -1 the lower, +1 the upper, and
        the cam angle (rad) of the roller that reaches it: a grid of 121 angles about phi, then golden section."""
        grid = np.linspace(-0.6, 0.6, 121)
        values = self._reach(phi[:, None] + grid[None, :], r[:, None], phi[:, None], side)
        k = np.argmin(values, axis=1)
        assert np.all((k > 0) & (k < len(grid) - 1)), "the touching roller lies outside the search"
        lo, hi = phi + grid[k - 1], phi + grid[k + 1]
        x1, x2 = hi - GOLD * (hi - lo), lo + GOLD * (hi - lo)
        f1, f2 = self._reach(x1, r, phi, side), self._reach(x2, r, phi, side)
        for _ in range(45):
            left = f1 < f2
            lo, hi = np.where(left, lo, x1), np.where(left, x2, hi)
            x1, x2, f2, f1 = (np.where(left, hi - GOLD * (hi - lo), x2), np.where(left, x1, lo + GOLD * (hi - lo)),
                              np.where(left, f1, np.nan), np.where(left, np.nan, f2))
            f1 = np.where(np.isnan(f1), self._reach(x1, r, phi, side), f1)
            f2 = np.where(np.isnan(f2), self._reach(x2, r, phi, side), f2)
        return -side * np.minimum(f1, f2), np.where(f1 < f2, x1, x2)

    def distance(self, r: np.ndarray, phi: np.ndarray, side: int, z: np.ndarray, height: np.ndarray,
                 theta: np.ndarray) -> np.ndarray:
        """The first-order distance (mm) of the points (r, phi, z) from the wall, whose ``height`` there the roller
        at ``theta`` reaches: the height over it times the cosine of its slope. The slope's rates by central
        differences of that roller's reach (the roller that reaches the wall stays the one to first order)."""
        hr, hp = 1e-4, 1e-5
        dr = -side * (self._reach(theta, r + hr, phi, side) - self._reach(theta, r - hr, phi, side)) / (2 * hr)
        dp = -side * (self._reach(theta, r, phi + hp, side) - self._reach(theta, r, phi - hp, side)) / (2 * hp)
        return (z - height) / np.sqrt(1 + dr**2 + (dp / r) ** 2)


def _program(spec):
    """s(theta) of the spec's program (mm or degrees), theta in [0, 2 pi)."""
    from camgen.flat import build_cam

    program = build_cam(spec).program
    return lambda theta: program.evaluate(np.asarray(theta, dtype=float).ravel())[0].reshape(np.shape(theta))


def _crossings(tri: np.ndarray, at: np.ndarray, r: np.ndarray, angle: float, near: np.ndarray) -> np.ndarray:
    """For each radius in ``r``, the height where the vertical line at (r, angle) crosses the triangles ``tri``
    (k, 3, 3), whose centroids lie at the polar angles ``at`` (sorted, and repeated 2 pi below and above), nearest
    to ``near`` (nan where it crosses none)."""
    low, high = np.searchsorted(at, [angle - 0.15, angle + 0.15])
    sub = tri[low:high]
    a, b, c = sub[:, None, 0], sub[:, None, 1], sub[:, None, 2]
    x, y = (r * math.cos(angle))[None, :], (r * math.sin(angle))[None, :]
    d = (b[..., 1] - c[..., 1]) * (a[..., 0] - c[..., 0]) + (c[..., 0] - b[..., 0]) * (a[..., 1] - c[..., 1])
    safe = np.where(d == 0, 1.0, d)
    l1 = ((b[..., 1] - c[..., 1]) * (x - c[..., 0]) + (c[..., 0] - b[..., 0]) * (y - c[..., 1])) / safe
    l2 = ((c[..., 1] - a[..., 1]) * (x - c[..., 0]) + (a[..., 0] - c[..., 0]) * (y - c[..., 1])) / safe
    l3 = 1 - l1 - l2
    inside = (l1 >= 0) & (l2 >= 0) & (l3 >= 0) & (d != 0)
    z = np.where(inside, l1 * a[..., 2] + l2 * b[..., 2] + l3 * c[..., 2], np.inf)
    best = np.argmin(np.abs(z - near[None, :]), axis=0)
    found = z[best, np.arange(len(r))]
    return np.where(np.isfinite(found), found, np.nan)


def measured_wall_error(raw: dict, mesh, rings: int = 9, angles: int = 120) -> tuple[float, float]:
    """The largest distance (mm) of the STL's walls from the exact envelope on the vertical lines at ``rings``
    radii strictly between the floor and the rim and ``angles`` angles, and the first-order measure's own
    allowance there (d^2 / (2 Rw))."""
    spec = validate_spec(raw)
    cam = spec.cam
    inner, outer = cam.pitch_radius - cam.groove_depth / 2, cam.pitch_radius + cam.groove_depth / 2
    tri = np.asarray(mesh.vertices, dtype=float)[mesh.faces]
    ends = (np.abs(tri[..., 2]).max(axis=1) < 1e-4) | (np.abs(tri[..., 2] - cam.length).max(axis=1) < 1e-4)
    tri = tri[~ends]                                                  # the cylinder's end faces are not walls
    at = np.arctan2(tri[..., 1].mean(axis=1), tri[..., 0].mean(axis=1))
    order = np.argsort(at)
    tri, at = np.concatenate([tri[order]] * 3), np.concatenate([at[order] + k * 2 * math.pi for k in (-1, 0, 1)])
    radii = inner + (outer - inner) * (np.arange(rings) + 0.5) / rings
    if cam.barrel_form == "rib":                                      # the rib between the rollers on either side
        g = cam.rib_width / 2 + spec.follower.roller_radius + cam.running_clearance / 2
        walls = ((Envelope(spec, -g), 1), (Envelope(spec, g), -1))
    else:
        walls = ((Envelope(spec), -1), (Envelope(spec), 1))
    angle = 2 * math.pi * (np.arange(angles) + 0.3) / angles - math.pi
    r, a = (x.ravel() for x in np.meshgrid(radii, angle))            # angle by angle, the radii in each
    phi = -walls[0][0].sense * a
    worst = allowance = 0.0
    for envelope, side in walls:
        exact, theta = envelope.wall(r, phi, side)
        z = np.concatenate([_crossings(tri, at, radii, float(t), exact[k * rings:(k + 1) * rings])
                            for k, t in enumerate(angle)])
        assert np.all(np.isfinite(z)) and np.all(np.abs(z - exact) < 0.5), "a probe missed the mesh's wall"
        d = np.abs(envelope.distance(r, phi, side, z, exact, theta))
        worst = max(worst, float(d.max()))
        allowance = max(allowance, float((d**2).max()) / (2 * envelope.cutter))
    return worst, allowance


def random_barrel(rng: np.random.Generator, form: str) -> dict:
    """A barrel template drawn at random: ``form`` "groove", "conical", "arm" or "rib"."""
    rm = float(rng.uniform(24.0, 40.0))
    depth = float(rng.uniform(4.0, 8.0))
    rr = float(rng.uniform(3.0, 5.5))
    clearance = float(rng.uniform(0.1, 0.4))
    rise, ret = (float(a) for a in rng.uniform(130.0, 170.0, 2))
    dwell = float(rng.uniform(0.2, 0.8)) * (360.0 - rise - ret)
    lift = float(rng.uniform(8.0, 18.0)) if form != "arm" else float(rng.uniform(10.0, 22.0))
    laws = rng.choice(LAWS, 2)
    motion = [{"type": "rise", "law": str(laws[0]), "lift": lift, "angle": rise}, {"type": "dwell", "angle": dwell},
              {"type": "return", "law": str(laws[1]), "lift": lift, "angle": ret},
              {"type": "dwell", "angle": 360.0 - rise - ret - dwell}]
    cam = {"kind": "barrel", "pitch_radius": rm, "groove_depth": depth, "running_clearance": clearance,
           "bore": float(rng.uniform(6.0, 2 * (rm - depth / 2) - 8.0)), "rotation": str(rng.choice(["ccw", "cw"]))}
    follower = {"type": "translating-roller", "roller_radius": rr}
    width = 2 * rr + clearance + (2 * rr * (depth / 2) / rm if form == "conical" else 0.0)
    if form == "conical":
        follower["roller_shape"] = "conical"
    if form == "arm":
        arm = float(rng.uniform(60.0, 100.0))
        half = math.radians(lift / 2)
        follower |= {"type": "oscillating-roller", "arm_length": arm, "pivot_distance": arm * (1 + math.cos(half)) / 2}
        stroke = 2 * arm * math.sin(half)
    else:
        stroke = lift
    if form == "rib":
        cam |= {"barrel_form": "rib", "rib_width": float(rng.uniform(6.0, 10.0))}
        width = cam["rib_width"] + 2 * width
    cam["length"] = stroke + width + float(rng.uniform(2.0, 8.0))
    return {"name": f"random-{form}", "cam": cam, "follower": follower, "motion": motion}


def _built(tmp_path, raw: dict, tolerance: float):
    """``camgen build`` of ``raw`` at ``tolerance`` (STL and JSON): its report and the STL as trimesh reads it."""
    import trimesh

    from camgen.core.starter import toml_value

    tmp_path.mkdir()
    path = tmp_path / f"{raw['name']}.toml"
    table = raw | {"output": {"tolerance": tolerance, "formats": ["stl", "json"]}}
    path.write_text("".join(f"{key} = {toml_value(value)}\n" for key, value in table.items()))
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "out" / f"{raw['name']}.json").read_text())
    return report, trimesh.load(tmp_path / "out" / f"{raw['name']}.stl")


def _shortest_allowed(report: dict) -> float:
    """4 steps of single precision at the cam's size, the larger of the rim's radius and the length (mm)."""
    return 4 * float(np.spacing(np.float32(max(report["cam"]["rim_radius_mm"], report["cam"]["length_mm"]))))


def _barrels(seed: int) -> list[dict]:
    """One barrel of each form, drawn from ``seed``."""
    rng = np.random.default_rng(seed)
    return [random_barrel(rng, form) for form in ("groove", "conical", "arm", "rib")]


@pytest.mark.parametrize("tolerance, seed", [(0.1, 1), (0.01, 2), (0.001, 3)])
def test_the_reported_wall_error_bounds_the_stl_of_random_barrels(tmp_path, tolerance, seed):
    """For each barrel: the reported wall error is at least the error measured on its STL (less the measure's own
    first-order allowance) and within the tolerance; so is the measured error; no edge is shorter than 4 single-
    precision steps at the cam's size; at 0.1 and 0.01 mm no two triangles intersect."""
    for k, raw in enumerate(_barrels(seed)):
        report, mesh = _built(tmp_path / str(k), raw, tolerance)
        measured, allowance = measured_wall_error(raw, mesh)
        reported = report["wall_max_error_mm"]
        assert measured - allowance <= reported <= tolerance, (raw["name"], measured, allowance, reported)
        assert measured <= tolerance, (raw["name"], measured)
        assert measured > 0.3 * reported, (raw["name"], measured, reported)     # the probes do see the facets
        assert mesh.edges_unique_length.min() >= _shortest_allowed(report), raw["name"]
        if tolerance >= 0.01:
            assert len(self_intersections(mesh.vertices, mesh.faces)) == 0, raw["name"]


@pytest.mark.parametrize("name", ["barrel", "barrel-conical", "barrel-oscillating", "barrel-rib"])
def test_the_bundled_barrels_hold_no_short_edge_and_no_self_intersection(tmp_path, name):
    """Each bundled barrel at its own tolerance (0.01 mm): no edge under 4 single-precision steps, no triangles
    that cross or fold onto a neighbour, and the reported wall error bounds the measured one."""
    import tomllib

    import trimesh

    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["build", str(ROOT / "templates" / f"{name}.toml"), "-o", str(out), "--set",
                                       "output.formats=['stl','json']"])
    assert result.exit_code == 0, result.output
    report = json.loads((out / f"{name}.json").read_text())
    mesh = trimesh.load(out / f"{name}.stl")
    assert mesh.edges_unique_length.min() >= _shortest_allowed(report)
    assert len(self_intersections(mesh.vertices, mesh.faces)) == 0
    measured, allowance = measured_wall_error(tomllib.loads((ROOT / "templates" / f"{name}.toml").read_text()), mesh)
    assert measured - allowance <= report["wall_max_error_mm"] <= report["tolerance_mm"]


def test_the_intersection_check_finds_a_crossing_and_a_fold():
    """The check itself: two triangles crossing, a sliver folded onto its neighbour (1e-6 mm across), and two
    triangles sharing a corner that overlap, are found; the same shapes laid apart, flat or bent, are not."""
    crossing = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.2, 0.2, -0.5], [0.3, 0.2, 0.5], [0.2, 0.4, 0.5]], float)
    faces = np.array([[0, 1, 2], [3, 4, 5]])
    assert self_intersections(crossing, faces).tolist() == [[0, 1]]
    assert len(self_intersections(crossing + np.array([[0, 0, 0]] * 3 + [[0, 0, 1]] * 3), faces)) == 0
    for apex, hit in (((2.5, 5e-7, 0.0), True), ((2.5, -5e-7, 0.0), False), ((2.5, -1.0, 0.3), False)):
        fold = np.array([[0, 0, 0], [5, 0, 0], [2.5, 1e-6, 0], apex], float)
        assert len(self_intersections(fold, np.array([[0, 1, 2], [1, 0, 3]]))) == int(hit), apex
    corner = np.array([[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [1.5, 1, 0], [0.5, 0.3, 0]], float)
    assert len(self_intersections(corner, np.array([[0, 1, 2], [1, 3, 4]]))) == 1
    corner[4] = (2.0, 0.0, 0.0)
    assert len(self_intersections(corner, np.array([[0, 1, 2], [1, 3, 4]]))) == 0


def test_the_quadratic_peak_over_a_triangle():
    """quadratic_peak of random quadratics (seeded; their values at the corners and the edges' midpoints) against
    the largest magnitude on a barycentric grid of 201 steps a side: never below it, and above it by no more than
    the grid's step can hide (a quadratic's peak moves its value by at most its second rates times a step squared)."""
    from camgen.kinds.barrel.solid import quadratic_peak

    rng = np.random.default_rng(7)
    c = rng.normal(size=(200, 6))
    q = lambda s, t: (c[:, 0] + c[:, 1] * s + c[:, 2] * t + c[:, 3] * s * s + c[:, 4] * s * t  # noqa: E731
                      + c[:, 5] * t * t)
    corners = np.stack([q(0.0, 0.0), q(1.0, 0.0), q(0.0, 1.0)], axis=-1)
    middles = np.stack([q(0.5, 0.0), q(0.5, 0.5), q(0.0, 0.5)], axis=-1)
    peak = quadratic_peak(corners, middles)
    i, j = np.meshgrid(np.arange(201), np.arange(201), indexing="ij")
    keep = i + j <= 200
    s, t = i[keep] / 200, j[keep] / 200
    grid = np.abs(q(s[:, None], t[:, None])).max(axis=0)
    assert np.all(peak >= grid - 1e-12)
    assert np.all(peak - grid <= 2 * np.abs(c[:, 3:]).sum(axis=1) / 200**2 + 1e-12)


def test_the_floor_error_is_the_floor_triangles_own():
    """barrel.toml's cutter at 0.01 mm: its floor's triangles (every corner on the floor's cylinder, 27 mm),
    sampled on a barycentric grid of 30 steps a side, lie inside the cylinder by at most the reported floor error
    (less the files' rounding and the collapse allowance, which the fit adds), and by nearly as much."""
    from camgen.kinds.barrel.mesh import SHORTEST_STEPS
    from camgen.api import design_cam
    from camgen.spec import load_spec

    design = design_cam(load_spec(ROOT / "templates" / "barrel.toml"))
    tube = design.with_solid().tube
    tri = tube.vertices[tube.faces]
    on_floor = np.all(np.abs(np.hypot(tri[..., 0], tri[..., 1]) - 27.0) < 1e-9, axis=1)
    i, j = np.meshgrid(np.arange(31), np.arange(31), indexing="ij")
    keep = i + j <= 30
    bary = np.stack([i[keep], j[keep], 30 - i[keep] - j[keep]], axis=1) / 30
    points = np.einsum("bk,tkc->tbc", bary, tri[on_floor])
    sunk = float((27.0 - np.hypot(points[..., 0], points[..., 1])).max())
    own = tube.floor_error_mm - (math.sqrt(3) / 2 + SHORTEST_STEPS) * design.single_step
    assert sunk <= own + 1e-12 and sunk >= 0.98 * own, (sunk, own)


def test_a_short_edge_is_collapsed_and_a_long_one_kept():
    """A tetrahedron at 30 mm whose edge from vertex 0 to 1 carries a vertex ``gap`` from vertex 0: at 5e-6 mm
    (2.6 single-precision steps, under the 4 asked for) that vertex goes into vertex 0 and the two triangles on
    the short edge go, leaving the closed tetrahedron of 1/6 mm^3; at 1e-4 mm the mesh is kept as it is; a
    collapse that would leave no closed solid (the short edge is a tetrahedron's own, and the bound its size)
    is refused (None)."""
    from camgen.kinds.barrel.mesh import shortest_edge, without_short_edges
    from camgen.core.solids import check_mesh
    from tests.camgen.kinds.barrel.test_barrel_tolerances import _split_edge

    step = float(np.spacing(np.float32(30.0)))
    mesh = _split_edge(5e-6)
    assert shortest_edge(mesh) == pytest.approx(5e-6, abs=step)
    fixed = without_short_edges(mesh, 4 * step)
    assert fixed is not None and len(fixed.vertices) == 4 and len(fixed.faces) == 4
    assert check_mesh(fixed).ok and check_mesh(fixed).volume_mm3 == pytest.approx(1 / 6, rel=1e-9)
    assert shortest_edge(fixed) == pytest.approx(1.0, abs=1e-6)
    kept = _split_edge(1e-4)
    assert without_short_edges(kept, 4 * step) is kept
    assert without_short_edges(fixed, 1.5) is None
