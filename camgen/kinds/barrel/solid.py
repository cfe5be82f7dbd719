"""A barrel cam's solid: the cylinder with its bore, less the groove, whose walls are the exact ones within the
tolerance (measured on the very triangles written, between their corners as well as at them).

The groove is cut by a closed tube: for each of n cam angles theta a loop of points round the groove's section,
up the lower wall at m + 1 rings from the floor Ri past the rim Ro (ring m lies beyond the rim, which falls midway
between ring m - 1 and ring m, and one more point 1 mm further out so the cut goes clean through the rim), down the
upper wall, and across the floor on the cylinder of radius Ri. Neighbouring loops are joined by triangles into a
two-manifold tube, which manifold3d subtracts from the blank. No ring lies on the rim's radius: a ring there would
run along the blank's rim facets, touching them at their corners, and the cut would leave edges a micrometre long
whose triangles cross once the file rounds them to single precision.

The walls are measured triangle by triangle: the signed distance from the exact walls
(:meth:`~camgen.kinds.barrel.kinematics.GrooveWalls.deviation`) at the triangle's corners and its edges' midpoints
gives the quadratic that takes those six values, whose largest magnitude over the triangle (at a corner, on an edge or
inside) is taken, plus how far the distance at the triangle's centroid is from that quadratic (what the quadratic
misses); so the error between the rings (radially) and between the loops (along the groove), and across a
quad's diagonal where the wall twists, is counted. The floor's triangles, whose corners lie on the cylinder Ri,
are off it by the sagitta of their longest chord seen along the axis, exactly. n and m grow (keeping the sagittas
along the radius and along the groove alike, which needs the fewest triangles) until both are within the
tolerance less what the files' single precision may move a point (``rounding``), which the errors reported
include.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.kinds.barrel.kinematics import GrooveWalls
from camgen.core.errors import DesignError

#: past the rim (mm) the cutter reaches beyond its last ring
_PAST = 1.0
#: the most points a tube may have (a bound on work and memory: some 16 million triangles)
MAX_POINTS = 8_000_000


@dataclass(frozen=True)
class Tube:
    """The groove's cutter as a mesh (``vertices`` (n, 3) mm, outward ``faces``) and the largest distance (mm) of its
    walls from the exact walls, and of its floor from the floor's cylinder, inside the cam (as the files hold it:
    the rounding to single precision included); its ``loops`` round and ``radii``, the rings up each wall."""

    vertices: np.ndarray
    faces: np.ndarray
    wall_error_mm: float
    floor_error_mm: float
    loops: int
    radii: int


def ring_radii(inner: float, outer: float, m: int) -> np.ndarray:
    """The m + 1 rings' radii (mm) up a wall, inner + j h with h = (outer - inner) / (m - 1/2), so that the rim's
    radius ``outer`` falls midway between the last two, and one more ``_PAST`` mm beyond the last."""
    h = (outer - inner) / (m - 0.5)
    radii = inner + h * np.arange(m + 1)
    return np.append(radii, radii[-1] + _PAST)


def _loops(walls: GrooveWalls, theta: np.ndarray, inner: float, outer: float, m: int, floor: int) -> np.ndarray:
    """The loops' points (n, P, 3): the lower wall up, the upper wall down, the floor across."""
    radii = ring_radii(inner, outer, m)
    t = theta[:, None]
    low_psi, low_z = walls.wall(t, radii[None, :], -1)
    up_psi, up_z = walls.wall(t, radii[None, ::-1], 1)
    k = np.arange(1, floor)[None, :] / floor                         # the floor, from the upper wall to the lower
    floor_psi = up_psi[:, -1:] + (low_psi[:, :1] - up_psi[:, -1:]) * k
    floor_z = up_z[:, -1:] + (low_z[:, :1] - up_z[:, -1:]) * k
    psi = np.concatenate([low_psi, up_psi, floor_psi], axis=1)
    z = np.concatenate([low_z, up_z, floor_z], axis=1)
    r = np.concatenate([np.broadcast_to(radii, low_psi.shape), np.broadcast_to(radii[::-1], up_psi.shape),
                        np.full(floor_psi.shape, inner)], axis=1)
    return np.stack([r * np.cos(psi), r * np.sin(psi), z], axis=-1)


def _faces(n: int, p: int, flip: np.ndarray | None = None) -> np.ndarray:
    """Two triangles for each quad between loop i and loop i + 1 (the last joined to the first): (a, b, c) and
    (a, c, d), a and b points k and k + 1 of loop i, d and c those of loop i + 1; (a, b, d) and (b, c, d), across
    the other diagonal, where ``flip`` (n, p) is set."""
    i, k = np.meshgrid(np.arange(n), np.arange(p), indexing="ij")
    a, b = i * p + k, i * p + (k + 1) % p
    c, d = ((i + 1) % n) * p + (k + 1) % p, ((i + 1) % n) * p + k
    flip = np.zeros((n, p), dtype=bool) if flip is None else flip
    first = np.where(flip[..., None], np.stack([a, b, d], -1), np.stack([a, b, c], -1))
    second = np.where(flip[..., None], np.stack([b, c, d], -1), np.stack([a, c, d], -1))
    return np.concatenate([first.reshape(-1, 3), second.reshape(-1, 3)])


def _groove_chains(m: int, p: int) -> tuple[np.ndarray, np.ndarray]:
    """Where a groove's loop of ``p`` points holds its walls and its floor: the first points of the walls' quads
    inside the cam (points 0..m+1 run up the lower wall, m + 1 past ring m, and m+2..2m+3 down the upper one: the
    quads from ring 0 to ring m on each), and the floor's chain from the upper wall's foot across to the lower's."""
    return np.r_[0:m, m + 3:2 * m + 3], np.r_[2 * m + 3:p, 0]


def quadratic_peak(corners: np.ndarray, middles: np.ndarray) -> np.ndarray:
    """The largest magnitude over a triangle of the quadratic taking the values ``corners`` (..., 3) at its corners
    and ``middles`` (..., 3) at the midpoints of its edges (corner 0 to 1, 1 to 2, 0 to 2): at a corner, where it
    peaks along an edge, or where its gradient vanishes inside."""
    v1, v2, v3 = np.moveaxis(corners, -1, 0)
    m12, m23, m13 = np.moveaxis(middles, -1, 0)
    # q(s, t) = c0 + c1 s + c2 t + c11 s^2 + c12 s t + c22 t^2, s and t the barycentric weights of corners 1 and 2
    c1, c2 = 4 * m12 - 3 * v1 - v2, 4 * m13 - 3 * v1 - v3
    c11, c22, c12 = 2 * (v1 + v2) - 4 * m12, 2 * (v1 + v3) - 4 * m13, 4 * (v1 - m12 - m13 + m23)

    def on_edge(a0: np.ndarray, a1: np.ndarray, a2: np.ndarray) -> np.ndarray:
        """|a0 + a1 u + a2 u^2| at its vertex in 0 <= u <= 1 (an end where it has none)."""
        u = np.clip(-a1 / np.where(a2 == 0, np.inf, 2 * a2), 0.0, 1.0)
        return np.abs(a0 + u * (a1 + u * a2))

    det = 4 * c11 * c22 - c12**2
    safe = np.where(det == 0, 1.0, det)
    s, t = (c2 * c12 - 2 * c1 * c22) / safe, (c1 * c12 - 2 * c2 * c11) / safe
    inside = (det != 0) & (s >= 0) & (t >= 0) & (s + t <= 1)
    centre = np.where(inside, np.abs(v1 + c1 * s + c2 * t + c11 * s * s + c12 * s * t + c22 * t * t), 0.0)
    return np.max([np.abs(v1), np.abs(v2), np.abs(v3), on_edge(v1, c1, c11), on_edge(v1, c2, c22),
                   on_edge(v1 + c2 + c22, c1 - c2 + c12 - 2 * c22, c11 - c12 + c22), centre], axis=0)


def _wall_errors(deviation: Any, pts: np.ndarray, quads: np.ndarray) -> tuple[float, float, float]:
    """The walls' measure of the loops ``pts`` (n, P, 3) triangulated as :func:`_faces` does (no flips there), in
    mm: the largest over the triangles of the quads from point k to k + 1 for k in ``quads`` of their
    :func:`quadratic_peak` of ``deviation`` (the signed distance from the exact walls) at their corners and their
    edges' midpoints, plus the distance at their centroid less the quadratic's there; and the largest sagittas of
    the chords between rings and between loops (the distance at their midpoints). Each point and midpoint is
    measured once."""
    nxt = np.roll(pts, -1, axis=0)

    def dev(points: np.ndarray) -> np.ndarray:
        return deviation(points.reshape(-1, 3)).reshape(points.shape[:-1])

    def later(values: np.ndarray) -> np.ndarray:
        """The values at loop i + 1 (the next round the cam) for each loop i."""
        return np.roll(values, -1, axis=0)

    wall = np.union1d(quads, quads + 1)                              # the wall's points, and their places there
    low, high = np.searchsorted(wall, quads), np.searchsorted(wall, quads + 1)
    corners, along = dev(pts[:, wall]), dev((pts[:, wall] + nxt[:, wall]) / 2)
    a, b, c, d = pts[:, quads], pts[:, quads + 1], nxt[:, quads + 1], nxt[:, quads]
    va, vb = corners[:, low], corners[:, high]
    vc, vd = later(vb), later(va)
    da, bc = along[:, low], along[:, high]
    ab = dev((a + b) / 2)
    cd, ac = later(ab), dev((a + c) / 2)
    worst = 0.0
    for values, middles, centroid in (((va, vb, vc), (ab, bc, ac), (a + b + c) / 3),
                                      ((va, vc, vd), (ac, cd, da), (a + c + d) / 3)):
        peak = quadratic_peak(np.stack(values, -1), np.stack(middles, -1))
        fitted = (4 * sum(middles) - sum(values)) / 9        # the quadratic at the centroid (weights -1/9 and 4/9)
        worst = max(worst, float((peak + np.abs(dev(centroid) - fitted)).max()))
    return worst, float(np.abs(ab).max()), float(np.abs(da).max())


def _floor(pts: np.ndarray, inner: float, across: np.ndarray) -> tuple[np.ndarray, float, float]:
    """The floor's quads along the chain ``across`` (their corners on the cylinder of radius ``inner``): which to
    split across their other diagonal (the shorter seen along the axis), (n, P), and their error (mm), the sagitta
    of the longest chord of their triangles seen along the axis (the farthest point of such a triangle from the
    cylinder is its longest chord's middle); and the sagitta of their chords from loop to loop alone."""
    xy = pts[..., :2]
    a, b = xy[:, across[:-1]], xy[:, across[1:]]
    c, d = np.roll(b, -1, axis=0), np.roll(a, -1, axis=0)
    length = lambda u, v: np.linalg.norm(u - v, axis=-1)      # noqa: E731
    sides = np.max([length(a, b), length(b, c), length(c, d), length(d, a)], axis=0)
    first, second = length(a, c), length(b, d)
    flip = np.zeros(pts.shape[:2], dtype=bool)
    flip[:, across[:-1]] = second < first
    longest = float(np.maximum(sides, np.minimum(first, second)).max())
    along = float(np.maximum(length(b, c), length(d, a)).max())
    return flip, _sagitta(inner, longest), _sagitta(inner, along)


def _sagitta(radius: float, chord: float) -> float:
    """How far (mm) a chord of length ``chord`` lies inside the circle of ``radius`` at its middle."""
    return radius - math.sqrt(max(radius**2 - chord**2 / 4, 0.0))


def groove_tube(walls: GrooveWalls, inner: float, outer: float, tolerance: float, phase: float = 0.0,
                rounding: float = 0.0) -> Tube:
    """The groove's cutter between the floor's radius ``inner`` and past the rim's ``outer`` (mm), its walls and
    floor within ``tolerance`` mm of the exact ones once the files round its points by up to ``rounding`` mm (see
    the module docstring); its loops ``phase`` of a step round from theta = 0 (another phase moves every vertex,
    should the subtraction leave two on one point)."""
    return _fitted(lambda theta, m, floor: _loops(walls, theta, inner, outer, m, floor), _groove_chains,
                   walls.deviation, inner, walls.cutter, outer, tolerance, phase, "the groove's walls", rounding, 4)


def _fitted(loops: Any, chains: Any, deviation: Any, inner: float, cutter: float, outer: float, tolerance: float,
            phase: float, what: str, rounding: float, floor: int) -> Tube:
    """A tube of ``loops(theta, m, floor)`` (n, P, 3), its walls' quads and its floor's chain where ``chains(m,
    P)`` says (see :func:`_groove_chains`), whose walls (:func:`_wall_errors` of ``deviation``) and floor
    (:func:`_floor`, on the cylinder of radius ``inner``) are within ``tolerance`` less ``rounding`` (mm): n and m
    grown together as far as the walls' error needs, their ratio so that the walls' sagittas between rings and
    between loops come out alike (which takes the fewest triangles for an error mostly of the quads' twist, which
    goes as the product of the two steps); more points across the floor while it is off, or more loops where the
    floor's chords between loops are (``floor`` 1 stays: a floor straight across, a rib's core)."""
    n, m = max(64, math.ceil(2 * math.pi * outer / math.sqrt(8 * tolerance * cutter))), 2
    allowed = tolerance - rounding
    wall = None
    for _ in range(60):
        theta = 2 * math.pi * (np.arange(n) + phase) / n
        pts = loops(theta, m, floor)
        quads, across = chains(m, pts.shape[1])
        if wall is None:
            wall = _wall_errors(deviation, pts, quads)
        flip, floor_error, floor_along = _floor(pts, inner, across)
        if wall[0] <= allowed and floor_error <= allowed:
            faces = _faces(n, pts.shape[1], flip)
            verts = pts.reshape(-1, 3)
            if _volume(verts, faces) < 0:
                faces = faces[:, ::-1]
            return Tube(verts, faces, wall[0] + rounding, floor_error + rounding, n, m)
        grow_n = grow_m = 1.0
        if wall[0] > allowed:
            grow_n, grow_m = _growth(*wall, allowed)
        if floor_error > allowed and (floor == 1 or floor_along > allowed / 2):
            grow_n = max(grow_n, 1.05 * math.sqrt(floor_along / (allowed / 2)), 1.2)
        elif floor_error > allowed and wall[0] <= allowed:     # the chords across the floor: as their square
            floor = max(2 * floor, math.ceil(1.05 * floor * math.sqrt(floor_error / allowed)))
        reached = max(wall[0], floor_error) + rounding
        if grow_n > 1.0 or grow_m > 1.0:
            n, m, wall = math.ceil(n * max(grow_n, 1.0)), math.ceil(m * max(grow_m, 1.0)), None
        if n * (2 * m + floor + 4) > MAX_POINTS:
            break
    raise DesignError(f"output.tolerance: {what} cannot be brought within {tolerance:g} mm (reached "
                      f"{reached:.3g} mm); loosen the tolerance")


def _growth(error: float, radial: float, along: float, allowed: float) -> tuple[float, float]:
    """By how much to multiply the loops (n) and the rings (m) to bring a wall ``error`` (mm) within ``allowed``:
    the error taken as radial / gm^2 + along / gn^2 + twist / (gm gn) (the sagittas between rings and between loops,
    and the rest, a quad's twist), the fewest triangles (the least gn gm) that make it ``allowed`` / 1.05 where
    both grow (the sagittas alike, as scaled by the twist's share), else the one that must grow alone."""
    target = allowed / 1.05
    a, c = max(radial, 1e-6 * error), max(along, 1e-6 * error)
    b = max(error - radial - along, 0.0)
    u = math.sqrt(target / (2 + b / math.sqrt(a * c)))           # gm = sqrt(a) / u, gn = sqrt(c) / u
    gm, gn = math.sqrt(a) / u, math.sqrt(c) / u

    def alone(first: float, cross: float, second: float) -> float:
        """The growth g of one step that brings first / g^2 + cross / g + second within the target."""
        room = target - second
        return max(1.0, 2 * first / (-cross + math.sqrt(cross * cross + 4 * first * room))) if room > 0 else 2.0

    if gn < 1.0:
        return 1.0, alone(a, b, c)
    if gm < 1.0:
        return alone(c, b, a), 1.0
    return gn, gm


def _side_loops(walls: GrooveWalls, theta: np.ndarray, inner: float, outer: float, m: int, side: int,
                end: float) -> np.ndarray:
    """The loops (n, m + 4, 3) of what a rib's roller sweeps on one side of the rib: the wall the roller of ``walls``
    touches on its ``side`` up its rings (:func:`ring_radii`) from the core's radius ``inner`` past the rim's
    ``outer``, out to the height ``end`` (past the cylinder's end), down to the core's cylinder there and back along
    it to the wall's foot (a straight line: no point between)."""
    radii = ring_radii(inner, outer, m)
    psi, z = walls.wall(theta[:, None], radii[None, :], side)
    psi = np.concatenate([psi, psi[:, -1:], psi[:, :1]], axis=1)
    z = np.concatenate([z, np.full((len(theta), 2), end)], axis=1)
    r = np.concatenate([np.broadcast_to(radii, (len(theta), m + 2)), np.full((len(theta), 1), radii[-1]),
                        np.full((len(theta), 1), inner)], axis=1)
    return np.stack([r * np.cos(psi), r * np.sin(psi), z], axis=-1)


def _side_chains(m: int, p: int) -> tuple[np.ndarray, np.ndarray]:
    """Where a rib's side loop (:func:`_side_loops`) holds its wall and its floor: points 0..m+1 run up the wall
    (m + 1 past ring m), m + 2 is the corner past the end and m + 3 the core there, from which the core's chain
    runs back to the wall's foot."""
    return np.r_[0:m], np.r_[m + 3, 0]


def rib_tube(below: GrooveWalls, above: GrooveWalls, inner: float, outer: float, length: float, tolerance: float,
             phase: float = 0.0, rounding: float = 0.0) -> Tube:
    """What to cut from the cylinder of radius ``outer`` (mm) to leave a rib on a core of radius ``inner``: the two
    rollers' sweeps either side of it, the roller of ``below`` (its upper side the rib's lower wall) from below
    z = 0 and the roller of ``above`` (its lower side the rib's upper wall) from above z = ``length``; each within
    ``tolerance`` of its exact wall and of the core's cylinder once the files round its points by up to
    ``rounding`` mm (:func:`_side_loops`), one mesh of two tubes."""
    tubes = []
    for walls, side, end in ((below, 1, -_PAST), (above, -1, length + _PAST)):
        def loops(theta: np.ndarray, m: int, floor: int, walls: GrooveWalls = walls, side: int = side,
                  end: float = end) -> np.ndarray:
            return _side_loops(walls, theta, inner, outer, m, side, end)

        tubes.append(_fitted(loops, _side_chains, walls.deviation, inner, walls.cutter, outer, tolerance, phase,
                             "the rib's walls", rounding, 1))
    first, second = tubes
    return Tube(np.vstack([first.vertices, second.vertices]),
                np.vstack([first.faces, second.faces + len(first.vertices)]),
                max(first.wall_error_mm, second.wall_error_mm), max(first.floor_error_mm, second.floor_error_mm),
                max(first.loops, second.loops), max(first.radii, second.radii))


def _volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Signed volume (mm^3) of a closed triangle mesh: positive for outward faces."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)
