"""A barrel cam's solid: the cylinder with its bore, less the groove, whose walls are the exact ones within the
tolerance (measured).

The groove is cut by a closed tube: for each of n cam angles theta a loop of points round the groove's section,
up the lower wall at m + 1 radii from the floor Ri to the rim Ro (and on 1 mm past it, so the cut goes clean
through the rim), down the upper wall, and across the floor on the cylinder of radius Ri. Neighbouring loops are
joined by triangles into a two-manifold tube, which manifold3d subtracts from the blank. Its walls are then
measured: the wall points midway between the loops and between the radii, and the faces' centres, against the
exact walls (:meth:`~camgen.barrel.walls.GrooveWalls.deviation`), the floor's faces against the cylinder Ri; n
and m grow until both are within the tolerance.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.barrel.walls import GrooveWalls
from camgen.core.errors import DesignError

#: past the rim (mm) the cutter reaches
_PAST = 1.0
#: the most loops round the cam (a bound on work and memory)
MAX_LOOPS = 200_000


@dataclass(frozen=True)
class Tube:
    """The groove's cutter as a mesh (``vertices`` (n, 3) mm, outward ``faces``) and the measured largest distance
    (mm) of its walls from the exact walls, and of its floor from the floor's cylinder, inside the cam."""

    vertices: np.ndarray
    faces: np.ndarray
    wall_error_mm: float
    floor_error_mm: float
    loops: int
    radii: int


def _loops(walls: GrooveWalls, theta: np.ndarray, inner: float, outer: float, m: int, floor: int) -> np.ndarray:
    """The loops' points (n, P, 3): the lower wall up, the upper wall down, the floor across."""
    radii = np.append(np.linspace(inner, outer, m + 1), outer + _PAST)
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


def _faces(n: int, p: int) -> np.ndarray:
    """Two triangles for each quad between loop i and loop i + 1 (the last joined to the first)."""
    i, k = np.meshgrid(np.arange(n), np.arange(p), indexing="ij")
    a, b = i * p + k, i * p + (k + 1) % p
    c, d = ((i + 1) % n) * p + (k + 1) % p, ((i + 1) % n) * p + k
    return np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])


def _errors(walls: GrooveWalls, theta: np.ndarray, inner: float, outer: float, m: int, floor: int) -> tuple:
    """(wall error, floor error) in mm: the walls' midpoints between loops and between radii and their quads'
    centres against the exact walls; the floor's quads' centres against the cylinder of radius ``inner``."""
    pts = _loops(walls, theta, inner, outer, m, floor)
    # points 0..m+1 the lower wall up (m + 1 at Ro + 1 mm), m+2..2m+3 the upper wall down, then the floor
    wall = np.r_[0:m + 1, m + 3:2 * m + 4]                          # the wall points inside the cam (r <= Ro)
    up = np.r_[0:m, m + 3:2 * m + 3]                                 # a wall point and its neighbour on the wall
    across = np.r_[2 * m + 3:pts.shape[1], 0]                        # the upper wall's foot, the floor, the lower's
    return _measured(walls.deviation, pts, inner, wall, up, across)


def _measured(deviation: Any, pts: np.ndarray, inner: float, wall: np.ndarray, up: np.ndarray,
              across: np.ndarray) -> tuple[float, float]:
    """(wall error, floor error) in mm of the loops ``pts`` (n, P, 3): the points ``wall`` midway between loops,
    the points ``up`` midway to their next on the wall and the quads' centres there, by ``deviation`` (the signed
    distance from the exact walls); the quads' centres along the chain ``across`` (the floor) against the cylinder
    of radius ``inner``."""
    nxt = np.roll(pts, -1, axis=0)
    probes = [(pts[:, wall] + nxt[:, wall]) / 2, (pts[:, up] + pts[:, up + 1]) / 2,
              (pts[:, up] + pts[:, up + 1] + nxt[:, up] + nxt[:, up + 1]) / 4]
    wall_error = max(float(np.abs(deviation(p.reshape(-1, 3))).max()) for p in probes)
    centres = (pts[:, across[:-1]] + pts[:, across[1:]] + nxt[:, across[:-1]] + nxt[:, across[1:]]) / 4
    floor_error = float(np.abs(np.hypot(centres[..., 0], centres[..., 1]) - inner).max())
    return wall_error, floor_error


def groove_tube(walls: GrooveWalls, inner: float, outer: float, tolerance: float, phase: float = 0.0) -> Tube:
    """The groove's cutter between the floor's radius ``inner`` and the rim's ``outer`` (mm), its walls and floor
    within ``tolerance`` mm of the exact ones (see the module docstring); its loops ``phase`` of a step round from
    theta = 0 (another phase moves every vertex, should the subtraction leave two on one point)."""
    return _fitted(lambda theta, m, floor: _loops(walls, theta, inner, outer, m, floor),
                   lambda theta, m, floor: _errors(walls, theta, inner, outer, m, floor),
                   walls.cutter, outer, tolerance, phase, "the groove's walls")


def _fitted(loops: Any, errors: Any, cutter: float, outer: float, tolerance: float, phase: float,
            what: str) -> Tube:
    """A tube of ``loops(theta, m, floor)`` (n, P, 3) whose ``errors(theta, m, floor)`` (wall, floor; mm) are
    within ``tolerance``: more loops round (n) or more radii up the walls (m) as the errors say, more points
    across the floor while it is off."""
    n, m, floor = max(64, math.ceil(2 * math.pi * outer / math.sqrt(8 * tolerance * cutter))), 2, 4
    for _ in range(40):
        theta = 2 * math.pi * (np.arange(n) + phase) / n
        wall_error, floor_error = errors(theta, m, floor)
        if wall_error <= tolerance and floor_error <= tolerance:
            pts = loops(theta, m, floor)
            faces = _faces(n, pts.shape[1])
            verts = pts.reshape(-1, 3)
            if _volume(verts, faces) < 0:
                faces = faces[:, ::-1]
            return Tube(verts, faces, wall_error, floor_error, n, m)
        along = errors(theta, 2 * m, floor)[0]                     # is the error along the radii or round?
        if along < 0.5 * wall_error:
            m *= 2
        else:
            n = math.ceil(n * max(1.2, math.sqrt(wall_error / tolerance)))
        if floor_error > tolerance:
            floor *= 2
        if n > MAX_LOOPS:
            break
    raise DesignError(f"output.tolerance: {what} cannot be brought within {tolerance:g} mm (reached "
                      f"{wall_error:.3g} mm); loosen the tolerance")


def _side_loops(walls: GrooveWalls, theta: np.ndarray, inner: float, outer: float, m: int, floor: int, side: int,
                end: float) -> np.ndarray:
    """The loops (n, P, 3) of what a rib's roller sweeps on one side of the rib: the wall the roller of ``walls``
    touches on its ``side`` up from the core's radius ``inner`` to 1 mm past the rim's ``outer``, out to the height
    ``end`` (past the cylinder's end), and back along the core's cylinder to the wall's foot."""
    radii = np.append(np.linspace(inner, outer, m + 1), outer + _PAST)
    psi, z = walls.wall(theta[:, None], radii[None, :], side)
    k = np.arange(floor)[None, :] / floor                            # the core, from the end to the wall's foot
    core_psi = np.broadcast_to(psi[:, :1], (len(theta), floor))
    core_z = end + (z[:, :1] - end) * k
    psi = np.concatenate([psi, psi[:, -1:], core_psi], axis=1)
    z = np.concatenate([z, np.full((len(theta), 1), end), core_z], axis=1)
    r = np.concatenate([np.broadcast_to(radii, (len(theta), m + 2)), np.full((len(theta), 1), outer + _PAST),
                        np.full(core_z.shape, inner)], axis=1)
    return np.stack([r * np.cos(psi), r * np.sin(psi), z], axis=-1)


def rib_tube(below: GrooveWalls, above: GrooveWalls, inner: float, outer: float, length: float, tolerance: float,
             phase: float = 0.0) -> Tube:
    """What to cut from the cylinder of radius ``outer`` (mm) to leave a rib on a core of radius ``inner``: the two
    rollers' sweeps either side of it, the roller of ``below`` (its upper side the rib's lower wall) from below
    z = 0 and the roller of ``above`` (its lower side the rib's upper wall) from above z = ``length``; each within
    ``tolerance`` of its exact wall and of the core's cylinder (:func:`_side_loops`), one mesh of two tubes."""
    tubes = []
    for walls, side, end in ((below, 1, -_PAST), (above, -1, length + _PAST)):
        def loops(theta: np.ndarray, m: int, floor: int, walls: GrooveWalls = walls, side: int = side,
                  end: float = end) -> np.ndarray:
            return _side_loops(walls, theta, inner, outer, m, floor, side, end)

        def errors(theta: np.ndarray, m: int, floor: int, walls: GrooveWalls = walls, loops: Any = loops) -> tuple:
            pts = loops(theta, m, floor)
            # points 0..m+1 the wall up (m + 1 past the rim), m+2 the corner past the end, then the core
            return _measured(walls.deviation, pts, inner, np.r_[0:m + 1], np.r_[0:m], np.r_[m + 3:pts.shape[1], 0])

        tubes.append(_fitted(loops, errors, walls.cutter, outer, tolerance, phase, "the rib's walls"))
    first, second = tubes
    return Tube(np.vstack([first.vertices, second.vertices]),
                np.vstack([first.faces, second.faces + len(first.vertices)]),
                max(first.wall_error_mm, second.wall_error_mm), max(first.floor_error_mm, second.floor_error_mm),
                max(first.loops, second.loops), max(first.radii, second.radii))


def _volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Signed volume (mm^3) of a closed triangle mesh: positive for outward faces."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)
