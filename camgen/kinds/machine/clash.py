"""The clash check of a machine's parts over one turn of the main shaft (shapely, vectorised over the angles).

Every part is a :class:`Body`: an outline in its own frame (mm), the planes it fills (a cam's layer; a pin from
the frame, plane 0, up to its highest part) and its placement at any main shaft angle phi (radians): a 2x2 matrix
and a shift, ``x_machine = M x_local + t``. Two bodies on a common plane clash where their outlines overlap by more
than :data:`AREA_TOL_MM2`, except within a :class:`Joint`'s disc (the parts meeting at their shared pin, or a
roller on its cam). A clash is named by its two parts and the first main shaft angle at which they meet, found on
the sampled angles and refined by bisection to :data:`REFINE_DEG`.
"""
from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import shapely

from camgen.kinds.machine import arms

#: an overlap of at most this area (mm^2) is a touch, not a clash (chordal outlines meeting tangentially)
AREA_TOL_MM2 = 1e-3
#: the width (degrees of the main shaft) to which a clash's first angle is refined by bisection
REFINE_DEG = 0.1

#: phi (n,) radians -> (M (n, 2, 2), t (n, 2) mm)
Placement = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class Body:
    """A part of the machine: its ``name``, the planes ``low`` to ``high`` it fills, its ``outline`` (m, 2) mm in
    its own frame and its ``place`` ment at main shaft angles; its round ``holes`` ((centre, radius) mm in its own
    frame: a cam's bore, a link's pin holes), which the assembly shows and the clash check does not need."""

    name: str
    low: int
    high: int
    outline: np.ndarray
    place: Placement
    holes: tuple[tuple[tuple[float, float], float], ...] = ()


@dataclass(frozen=True)
class Joint:
    """Two bodies that meet by design within ``radius`` mm of ``centre`` (phi -> (n, 2) mm): a pin they share, or
    a roller on its cam."""

    a: str
    b: str
    centre: Callable[[np.ndarray], np.ndarray]
    radius: float


@dataclass(frozen=True)
class Arm:
    """A follower's arm that a coupled linkage's crank lies along (an oscillating roller's, a conjugate's bell
    crank, an oscillating flat face's): its ``follower``, its ``pivot`` (2,) mm in the machine's frame, its top
    ``plane`` (a coupled four-bar's crank's), its ``direction`` (phi (n,) radians -> (n, 2) mm, pivot to the
    roller's centre or along the face to its rest contact, turned by the swing) and ``made`` (the pivot pin's
    diameter and the crank pins' (distance out along the arm, pin diameter) mm -> the arm's body with their
    holes)."""

    follower: Any
    pivot: np.ndarray
    plane: int
    direction: Callable[[np.ndarray], np.ndarray]
    made: Callable[[float, tuple[tuple[float, float], ...]], Body]


@dataclass(frozen=True)
class Clash:
    """Two parts that overlap: their names and the first main shaft angle (degrees, to :data:`REFINE_DEG`)."""

    a: str
    b: str
    angle_deg: float

    def message(self) -> str:
        return f"{self.a} and {self.b} meet at {self.angle_deg:.1f} degrees of the main shaft"


def rotation(angle: np.ndarray) -> np.ndarray:
    """(n, 2, 2) counter-clockwise rotations by ``angle`` (n,) radians."""
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def still(at: Sequence[float] | np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """A joint centre that does not move: ``at`` (mm) at every angle."""
    def centre(phi: np.ndarray) -> np.ndarray:
        return np.tile(np.asarray(at, float), (len(phi), 1))
    return centre


def fixed(at: Sequence[float] | np.ndarray) -> Placement:
    """The placement of a part that does not move, its frame's origin at ``at`` (mm)."""
    def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        n = len(phi)
        return np.broadcast_to(np.eye(2), (n, 2, 2)), np.broadcast_to(np.asarray(at, float), (n, 2))
    return place


def circle(radius: float, tolerance: float = 0.01) -> np.ndarray:
    """A polygon (m, 2) round a circle of ``radius`` mm about the origin, chords within ``tolerance`` mm."""
    steps = max(16, math.ceil(math.pi / math.acos(max(1.0 - tolerance / radius, -1.0))))
    a = np.arange(steps) * (2 * math.pi / steps)
    return radius * np.column_stack([np.cos(a), np.sin(a)])


def bar(length: float, half_width: float, tolerance: float = 0.01) -> np.ndarray:
    """A straight bar's outline (m, 2) mm: round ends of ``half_width`` about (0, 0) and (``length``, 0)."""
    ring = circle(half_width, tolerance)
    a = np.arctan2(ring[:, 1], ring[:, 0])
    right = ring[np.abs(a) <= math.pi / 2] + (length, 0.0)
    left = ring[np.abs(a) > math.pi / 2]
    return np.concatenate([right[np.argsort(np.arctan2(right[:, 1], right[:, 0] - length))],
                           left[np.argsort(np.mod(np.arctan2(left[:, 1], left[:, 0]), 2 * math.pi))]])


def _moved(m: np.ndarray, t: np.ndarray, xy: np.ndarray) -> np.ndarray:
    """Points ``xy`` (k, 2) mm of a body's frame at each of its placements ``m`` (n, 2, 2), ``t`` (n, 2): (n, k, 2),
    x_machine = M x_local + t written out per row (the same products and sums as an einsum, ~15 times faster)."""
    x, y = xy[:, 0], xy[:, 1]
    return np.stack([m[:, 0, 0, None] * x + m[:, 0, 1, None] * y + t[:, 0, None],
                     m[:, 1, 0, None] * x + m[:, 1, 1, None] * y + t[:, 1, None]], -1)


def _valid(body: Body) -> bool:
    """Whether ``body``'s own outline is a valid polygon (a rigid motion keeps it so: its placed copies then need no
    repair, and make_valid of every copy was a third of a machine's clash check)."""
    return bool(shapely.is_valid(shapely.polygons(body.outline)))


def _shapes(body: Body, phi: np.ndarray) -> np.ndarray:
    m, t = body.place(phi)
    placed = shapely.polygons(_moved(np.asarray(m), np.asarray(t), body.outline))
    return placed if _valid(body) else shapely.make_valid(placed)


def outlines(body: Body, phi: np.ndarray) -> np.ndarray:
    """``body``'s outline placed at each of the main shaft angles ``phi`` (rad): shapely polygons (n,), mm."""
    return _shapes(body, phi)


#: how far (mm) a joint's centre may wander in a body's own frame over the angles and still be taken as fixed there
FIXED_TOL_MM = 1e-6


def _placed(m: np.ndarray, t: np.ndarray, local: Any) -> np.ndarray:
    """A geometry ``local`` in a body's own frame (any shapely geometry: a polygon with holes, several) placed by
    each of its placements ``m`` (n, 2, 2), ``t`` (n, 2) mm: (n,) geometries, mm."""
    moved = _moved(m, t, shapely.get_coordinates(local))
    # set_coordinates fills the copies' coordinates in order, one copy's after another's: moved's rows
    return shapely.set_coordinates(np.full(len(m), local, dtype=object), moved.reshape(-1, 2))


def _cut(a: Body, b: Body, joint: Joint, phi: np.ndarray, placed: tuple[np.ndarray, np.ndarray] | None
         ) -> tuple[np.ndarray, np.ndarray] | None:
    """The pair's shapes with the joint's disc taken out of one of them in its own frame, where the joint's centre
    is fixed in that body's frame (within :data:`FIXED_TOL_MM` over ``phi``: a pin through it, a roller's centre):
    (that body less the disc, the other body: ``placed``'s where given) at ``phi``, whose overlap is the pair's
    outside the disc. None where the centre moves in both bodies' frames."""
    centre = joint.centre(phi)
    for side, (cut, other) in enumerate(((a, b), (b, a))):
        m, t = (np.asarray(v) for v in cut.place(phi))
        local = np.linalg.solve(m, (centre - t)[:, :, None])[:, :, 0]          # M^-1 (centre - t), its own frame
        if np.max(np.abs(local - local[0]), initial=0.0) > FIXED_TOL_MM:
            continue
        outline = shapely.polygons(cut.outline)
        if not _valid(cut):
            outline = shapely.make_valid(outline)
        disc = shapely.buffer(shapely.points(local[0]), joint.radius, quad_segs=32)
        return (_placed(m, t, shapely.difference(outline, disc)),
                _shapes(other, phi) if placed is None else placed[1 - side])
    return None


def _overlap(a: Body, b: Body, joint: Joint | None, phi: np.ndarray,
             placed: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Where (bool (n,)) bodies ``a`` and ``b`` overlap at angles ``phi``, outside their joint's disc; ``placed``:
    their outlines at ``phi`` (:func:`outlines`) where the caller has them already.

    With a joint whose centre is fixed in one body's frame, the disc is taken out of that body once, in its frame
    (:func:`_cut`; (A and B) less D is (A less D) and B): most angles of a pair meeting only at its pin then need
    no intersection at all, where each needed one, a disc and a difference."""
    cut = _cut(a, b, joint, phi, placed) if joint is not None else None
    pa, pb = cut if cut is not None else placed if placed is not None else (_shapes(a, phi), _shapes(b, phi))
    near = shapely.intersects(pa, pb)
    out = np.zeros(len(phi), bool)
    if not near.any():
        return out
    common = shapely.intersection(pa[near], pb[near])
    if joint is not None and cut is None:
        discs = shapely.buffer(shapely.points(joint.centre(phi[near])), joint.radius, quad_segs=32)
        common = shapely.difference(common, discs)
    out[near] = shapely.area(common) > AREA_TOL_MM2
    return out


def _refine(a: Body, b: Body, joint: Joint | None, lo: float, hi: float) -> float:
    """The first angle (radians) in (lo, hi] at which ``a`` and ``b`` overlap: clear at lo, overlapping at hi."""
    while hi - lo > math.radians(REFINE_DEG) / 2:
        mid = 0.5 * (lo + hi)
        if _overlap(a, b, joint, np.array([mid]))[0]:
            hi = mid
        else:
            lo = mid
    return hi


def clashes(bodies: Sequence[Body], joints: Sequence[Joint], samples: int) -> tuple[Clash, ...]:
    """Every pair of ``bodies`` sharing a plane that overlaps at one of ``samples`` main shaft angles over a turn
    (outside their joints), with the first angle at which it does, refined to :data:`REFINE_DEG`."""
    phi = np.arange(samples) * (2 * math.pi / samples)
    pairs = {frozenset((j.a, j.b)): j for j in joints}
    found = []
    placed: dict[int, np.ndarray] = {}                    # each body's outlines at phi, placed once for all its pairs

    def at_phi(i: int) -> np.ndarray:
        if i not in placed:
            placed[i] = _shapes(bodies[i], phi)
        return placed[i]

    for i, a in enumerate(bodies):
        for k, b in enumerate(bodies[i + 1:], i + 1):
            if a.high < b.low or b.high < a.low:
                continue
            joint = pairs.get(frozenset((a.name, b.name)))
            hit = _overlap(a, b, joint, phi, (at_phi(i), at_phi(k)))
            if not hit.any():
                continue
            if hit.all():
                found.append(Clash(a.name, b.name, 0.0))
                continue
            k = int(np.argmax(hit & ~np.roll(hit, 1)))            # the first angle entering a clash
            lo = phi[k - 1] if k else phi[-1] - 2 * math.pi
            angle = math.degrees(_refine(a, b, joint, float(lo), float(phi[k])))
            found.append(Clash(a.name, b.name, round(angle % 360.0, 6)))
    return tuple(found)


#: the pin diameter (mm) of a follower's pivot where no linkage's parts give one
PIVOT_PIN_MM = 4.0


def arm_frame(follower: object, rest_deg: float) -> np.ndarray:
    """The 2x2 matrix taking a coupled four-bar's frame (its crank's pivot at the origin, its ground line along +x)
    into the machine's, about the follower's pivot: the crank lies along the arm (the follower's rest direction at
    crank angle ``rest_deg``: to the roller's centre, or along a flat face to its rest contact), mirrored where the arm
    swings clockwise (:mod:`camgen.kinds.machine.arms`)."""
    k, base = arms.swing_sign(follower), arms.rest_vector(follower)
    alpha = math.atan2(base[1], base[0]) - k * math.radians(rest_deg)
    return rotation(np.array([alpha]))[0] @ np.diag([1.0, k])
def _round_holes(holes: Sequence[object]) -> tuple[tuple[tuple[float, float], float], ...]:
    """The round ones of a part's ``holes`` as (centre, radius) pairs (mm)."""
    from camgen.core.shapes import Circle

    return tuple(((float(h.centre[0]), float(h.centre[1])), float(h.radius)) for h in holes if isinstance(h, Circle))


def _margin(radius: float) -> float:
    """A joint's disc: ``radius`` mm and room for the chords of the outlines meeting in it."""
    return 1.01 * radius + 0.05


def machine_parts(design: object, one_plate: bool = False) -> tuple[tuple[Body, ...], tuple[Joint, ...],
                                                                   tuple[str, ...]]:
    """The bodies and joints of a :class:`~camgen.kinds.machine.design.MachineDesign`, and the parts not checked.
    With ``one_plate`` (``machine.frame = "one"``) every pin stands on the frame, a rocker's pivot too (else it
    hangs from a top plate).

    Each cam (its part's outline as cut, turned by sense x its program angle about its shaft) and, for an
    oscillating roller, its follower's arm (a bar from its pivot to its roller, as wide as the roller) and roller,
    on the cam's layer (an oscillating flat face's arm along its face, :mod:`camgen.kinds.machine.flat_arm`); each
    coupled four-bar's coupler and rocker (their parts as cut, the crank being the arm: a roller's, a bell crank's or
    a flat face's, an :class:`Arm`), the four-bar placed with its crank pin on the arm, ``crank`` mm from the pivot,
    and mirrored where the arm swings clockwise, on the arm's top plane plus its own layer over its crank's, the arm
    drilled for its crank pin; the shafts and pins from plane 0 up.
    The four-bar's ground link is the frame's and is not a moving part."""
    from camgen.followers.oscillating_flat import OscillatingFlat
    from camgen.followers.oscillating_roller import OscillatingRoller
    from camgen.followers.translating_flat import TranslatingFlat
    from camgen.followers.translating_roller import TranslatingRoller
    from camgen.kinds.machine import barrel_parts, conjugate_parts, kinematics
    from camgen.kinds.machine.design import _cam_of
    from camgen.kinds.machine.flat_arm import flat_arm
    from camgen.kinds.machine.follower_parts import arm_outline, made_radius, roller_hole, roller_outline

    d = design
    spec = d.spec                                          # type: ignore[attr-defined]
    at = {s.name: np.asarray(s.at, float) for s in spec.shafts}
    bodies: list[Body] = []
    joints: list[Joint] = []
    skipped: list[str] = []
    arms: dict[str, Arm] = {}                               # each follower's arm a coupled linkage's crank may be
    shafts: dict[str, list[tuple[int, float]]] = {}
    for cam, mount in zip(d.cams, spec.cams, strict=True):  # type: ignore[attr-defined]
        kin = _cam_of(cam.design)
        part = next(iter(dict(conjugate_parts.plates(cam.design)).values()), None)
        if barrel_parts.is_barrel(cam.design):              # its drum, and its follower's plan on its plane
            at_shaft, bore = at[mount.shaft], float(cam.design.spec.cam.bore) / 2
            bodies.append(barrel_parts.drum(cam.name, cam.design, 2 * mount.layer, at_shaft,
                                            float(cam.design.tolerance)))
            shafts.setdefault(mount.shaft, []).append((2 * mount.layer, bore))
            joints.append(Joint(f"cams.{cam.name}", f"shafts.{mount.shaft}", still(at_shaft), _margin(bore)))
            carried, grooved = barrel_parts.follower(cam.name, cam.design, 2 * mount.layer, at_shaft)
            bodies.append(carried)                          # its plan over the turn, as high as the drum
            joints.append(grooved)
            continue
        if part is None:
            skipped.append(f"cams.{cam.name}")
            continue
        centre, tol = at[mount.shaft], float(cam.design.tolerance)
        sense = kin.follower.sense

        def theta(phi: np.ndarray, cam: Any = cam) -> np.ndarray:
            return cam.program_angles(phi)

        def place_cam(phi: np.ndarray, theta: Callable = theta, sense: int = sense,
                      centre: np.ndarray = centre) -> tuple[np.ndarray, np.ndarray]:
            return rotation(sense * theta(phi)), np.broadcast_to(centre, (len(phi), 2))

        name = f"cams.{cam.name}"
        bodies.append(Body(name, 2 * mount.layer, 2 * mount.layer, part.outline.flatten(tol), place_cam,
                           _round_holes(part.holes)))
        bore = float(cam.design.spec.cam.bore) / 2                 # a keyed bore's round part: the shaft
        shafts.setdefault(mount.shaft, []).append((2 * mount.layer, bore))
        joints.append(Joint(name, f"shafts.{mount.shaft}", still(centre), _margin(bore)))
        f = kin.follower
        if conjugate_parts.is_conjugate(cam.design):        # its second plate and its follower's two rollers
            made, met, arm_of = conjugate_parts.follower_bodies(
                cam.name, cam.design, 2 * mount.layer, centre, theta, tol, mount.shaft, bore)
            bodies += made
            joints += met
            shafts[mount.shaft].append((2 * mount.layer + 2, bore))
            if arm_of is not None:                          # its linkage over both plates
                arms[cam.name] = Arm(f, arm_of[0], 2 * mount.layer + 3, arm_of[1],
                                     _drilled(next(b for b in made if b.name == f"{name}.arm"), f.arm_length))
                continue
        if isinstance(f, TranslatingRoller | TranslatingFlat):
            _stem(d, cam, kin, f, 2 * mount.layer, centre, theta, tol, bodies, joints)
            continue
        if isinstance(f, OscillatingFlat):                  # its arm along the face, on a pin at its pivot
            arms[cam.name], riding = flat_arm(cam.name, cam.design, kin, 2 * mount.layer, centre, theta, tol)
            bodies.append(arms[cam.name].made(PIVOT_PIN_MM, ()))
            joints.append(riding)
            continue
        if not isinstance(f, OscillatingRoller):
            skipped.append(f"cams.{cam.name}'s follower")
            continue
        pivot = centre + f.pivot
        rest = np.array([0.0, f.prime_radius]) - f.pivot

        def arm(phi: np.ndarray, theta: Callable = theta, program: object = kin.program, k: float = f._swing_sign,
                rest: np.ndarray = rest) -> np.ndarray:
            psi = np.radians(program.evaluate(theta(phi))[0])   # type: ignore[attr-defined]
            c, s = np.cos(k * psi), np.sin(k * psi)
            return np.column_stack([c * rest[0] - s * rest[1], s * rest[0] + c * rest[1]])

        def place_arm(phi: np.ndarray, arm: Callable = arm, pivot: np.ndarray = pivot) -> tuple[np.ndarray, np.ndarray]:
            w = arm(phi)
            return rotation(np.arctan2(w[:, 1], w[:, 0])), np.broadcast_to(pivot, (len(phi), 2))

        def roller(phi: np.ndarray, arm: Callable = arm, pivot: np.ndarray = pivot) -> np.ndarray:
            return pivot + arm(phi)

        def place_roller(phi: np.ndarray, roller: Callable = roller) -> tuple[np.ndarray, np.ndarray]:
            return np.broadcast_to(np.eye(2), (len(phi), 2, 2)), roller(phi)

        r = f.roller_radius
        plane = 2 * mount.layer
        lever = Body(f"{name}.arm", plane + 1, plane + 1, arm_outline(f.arm_length, r / 2).flatten(tol), place_arm)
        bodies += [lever, Body(f"{name}.roller", plane, plane + 1,
                               roller_outline(made_radius(cam.design, r)).flatten(tol), place_roller, (roller_hole(),))]
        joints += [Joint(name, f"{name}.roller", roller, _margin(r)),
                   Joint(f"{name}.arm", f"{name}.roller", roller, _margin(r))]
        arms[cam.name] = Arm(f, pivot, plane + 1, arm, _drilled(lever, f.arm_length))
    pins: dict[tuple[float, float], tuple[list[str], int, float]] = {}
    crank_pins: dict[str, list[tuple[float, float]]] = {}     # a coupled four-bar's crank pin on its cam's arm
    for m in d.linkages:                                   # type: ignore[attr-defined]
        build, table = m.design.build, m.design.spec.linkage
        if build is None or m.cam not in arms:              # no [parts] table: no outlines to place
            skipped.append(f"linkages.{m.name}")
            continue
        f, pivot, layer = arms[m.cam].follower, arms[m.cam].pivot, arms[m.cam].plane
        frame = arm_frame(f, m.coupling.rest)
        hw = max(p.half_width for p in build.parts)
        cut = {p.name: p for p in build.cut}
        fb, assembly = m.fourbar, table.assembly
        crank_layer = build.layers["crank"]

        def poses(phi: np.ndarray, m: object = m, f: object = f, assembly: str = assembly,
                  fb: object = fb) -> object:
            cam = d.cam(m.cam)                              # type: ignore[attr-defined]
            kin = _cam_of(cam.design)
            swing = kin.program.evaluate(cam.program_angles(phi))[:3]
            chain = kinematics.crank_chain(m.coupling.rest, swing, cam.turns)   # type: ignore[attr-defined]
            return fb.positions(chain.theta2, assembly), chain.theta2           # type: ignore[attr-defined]

        def crank_pin(phi: np.ndarray, poses: Callable = poses, fb: object = fb, frame: np.ndarray = frame,
                      pivot: np.ndarray = pivot) -> np.ndarray:
            t2 = poses(phi)[1]
            local = fb.crank * np.column_stack([np.cos(t2), np.sin(t2)])        # type: ignore[attr-defined]
            return pivot + local @ frame.T

        def rocker_pin(phi: np.ndarray, poses: Callable = poses, fb: object = fb, frame: np.ndarray = frame,
                       pivot: np.ndarray = pivot) -> np.ndarray:
            p = poses(phi)[0]
            local = fb.ground * np.column_stack([np.ones(len(phi)), np.zeros(len(phi))])   # type: ignore
            local = local + fb.rocker * np.column_stack([np.cos(p.theta4), np.sin(p.theta4)])  # type: ignore
            return pivot + local @ frame.T

        o4 = pivot + np.array([fb.ground, 0.0]) @ frame.T

        def place_link(phi: np.ndarray, which: str, poses: Callable = poses, frame: np.ndarray = frame,
                       crank_pin: Callable = crank_pin, o4: np.ndarray = o4) -> tuple[np.ndarray, np.ndarray]:
            p = poses(phi)[0]
            angle = p.theta3 if which == "coupler" else p.theta4
            shift = crank_pin(phi) if which == "coupler" else np.broadcast_to(o4, (len(phi), 2))
            return frame @ rotation(angle), shift

        names = {}
        for which in ("coupler", "rocker"):
            plane = layer + build.layers[which] - crank_layer
            name = f"linkages.{m.name}.{which}"
            names[which] = (name, plane)
            bodies.append(Body(name, plane, plane, cut[which].outline.flatten(0.01),
                               functools.partial(place_link, which=which),
                               _round_holes(cut[which].holes)))
        joints += [Joint(f"cams.{m.cam}.arm", names["coupler"][0], crank_pin, _margin(hw)),
                   Joint(names["coupler"][0], names["rocker"][0], rocker_pin, _margin(hw))]
        pin_r = m.design.spec.parts.pin_diameter / 2 if m.design.spec.parts else PIVOT_PIN_MM / 2
        crank_pins.setdefault(m.cam, []).append((float(fb.crank), 2 * pin_r))
        pins.setdefault((float(o4[0]), float(o4[1])), ([], 1, pin_r))[0].append(names["rocker"][0])
        entry = pins.setdefault((float(pivot[0]), float(pivot[1])), ([], 0, pin_r))
        entry[0].append(f"cams.{m.cam}.arm")
    for m in getattr(d, "cranked", ()):
        if m.design.build is None:                          # no [parts] table: no outlines to place
            skipped.append(f"linkages.{m.name}")
            continue
        _cranked_parts(m, bodies, joints, pins, shafts)
    for m in getattr(d, "slid", ()):                       # a translating follower's linkage: as a shaft's
        if m.design.build is None:
            skipped.append(f"linkages.{m.name}")
            continue
        _cranked_parts(m, bodies, joints, pins, shafts)
        slider = m.ground_slider
        if m.cam not in arms and slider is not None:        # its stem carries its slider
            block = next(b for b in bodies if b.name == f"linkages.{m.name}.{slider.name}")
            joints += [Joint(b.name, block.name, functools.partial(_slid_point, m=m, point=slider.point),
                             _margin(float(np.hypot(*block.outline.T).max())))
                       for b in bodies if b.name in (f"cams.{m.cam}.{p}" for p in ("stem", "roller", "face",
                                                                                "yoke"))]   # a conjugate's yoke too
        if m.cam in arms and m.analysis.crank:              # its crank and the arm: one bell crank
            link, pivot = m.analysis.table.inputs[0].link, arms[m.cam].pivot
            joints.append(Joint(f"cams.{m.cam}.arm", f"linkages.{m.name}.{link}", still(pivot),
                                _margin(max(p.half_width for p in m.design.build.parts))))
    for holder, pivot in ((f"cams.{name}.arm", a.pivot) for name, a in arms.items()):
        key = next((k for k in pins if math.dist(k, pivot) < 1e-9), (float(pivot[0]), float(pivot[1])))
        entry = pins.setdefault(key, ([], 0, PIVOT_PIN_MM / 2))
        if holder not in entry[0]:
            entry[0].append(holder)
    from camgen.kinds.machine.ratchet_bodies import ratchet_bodies

    ratchet_bodies(d, arms, bodies, joints, pins, crank_pins)   # each ratchet's wheel on its arm's pivot, its pawls
    for name, lever_arm in arms.items():            # the arm's holes: its pivot's, a roller's axle's, crank pins'
        pin_d = 2 * next(r for k, (_, _, r) in pins.items() if math.dist(k, lever_arm.pivot) < 1e-9)
        drilled = lever_arm.made(pin_d, tuple(crank_pins.get(name, ())))
        bodies = [drilled if b.name == drilled.name else b for b in bodies]
    from camgen.kinds.machine.geneva_bodies import geneva_bodies
    from camgen.kinds.machine.machine_gears import gear_bodies

    geneva_bodies(d, bodies, joints, shafts)                # the Geneva drives, then the gear pairs
    gear_bodies(d, bodies, joints, shafts)                  # the gear pairs, over the other parts by default
    from camgen.kinds.machine.stem_guide import guide_screws

    for rail in [b for b in bodies if ".guide." in b.name]:      # a stem guide's screws: pins into the frame
        for at_xy, screw in guide_screws(rail):
            pins.setdefault(at_xy, ([], 0, screw))[0].append(rail.name)
    plane_of = {b.name: b.high for b in bodies}
    roof = max(plane_of.values(), default=0) + 1                       # the top plate's plane
    for i, ((x, y), (held, from_top, r)) in enumerate(pins.items()):
        name = f"pins.{i}"
        planes = [plane_of[h] for h in held]
        hangs = from_top and not one_plate
        low, high = (min(planes), roof) if hangs else (min(0, *planes), max(0, *planes))
        bodies.append(Body(name, low, high, circle(r), fixed((x, y))))
        joints += [Joint(h, name, still((x, y)), _margin(r)) for h in held]
    for shaft, seats in shafts.items():
        top = max(0, *(layer for layer, _ in seats))
        bottom = min(0, *(layer for layer, _ in seats))             # below 0: through the frame to its back
        r = min(radius for _, radius in seats)
        if r > 0:
            bodies.append(Body(f"shafts.{shaft}", bottom, top, circle(r), fixed(at[shaft])))
    return tuple(bodies), tuple(joints), tuple(skipped)


def _drilled(arm: Body, length: float) -> Callable[[float, tuple[tuple[float, float], ...]], Body]:
    """An oscillating roller's (or a bell crank's) ``arm`` with its holes
    (:func:`camgen.kinds.machine.follower_parts.arm_holes`: its pivot pin's, its roller's axle ``length`` mm out,
    its crank pins'), given the pivot pin's diameter and the crank pins (mm)."""
    from camgen.kinds.machine.follower_parts import arm_holes

    def made(pivot_pin: float, pins: tuple[tuple[float, float], ...]) -> Body:
        return replace(arm, holes=arm_holes(float(length), pivot_pin, pins))

    return made


def _slid_point(phi: np.ndarray, m: Any, point: str) -> np.ndarray:
    """Joint ``point`` of the slider-driven linkage ``m`` at main shaft angles ``phi`` (mm, the machine's frame)."""
    return np.asarray(m.solve(phi).points[point], float) + m.offset


def _stem(d: Any, cam: Any, kin: Any, f: Any, plane: int, centre: np.ndarray, theta: Callable, tol: float,
          bodies: list[Body], joints: list[Joint]) -> None:
    """Add cam ``cam``'s translating follower's stem and roller (:func:`camgen.kinds.machine.stem_parts.stem_bodies`):
    as wide as the parts of the linkage its stem drives, if any."""
    from camgen.kinds.machine.slider_coupling import rest_point
    from camgen.kinds.machine.stem_parts import WIDTH_MM, stem_bodies

    from camgen.kinds.machine.stem_kit import slider_joint

    driven = [m for m in getattr(d, "slid", ()) if m.cam == cam.name and m.design.spec.parts is not None]
    width = float(driven[0].design.spec.parts.width) if driven else WIDTH_MM

    def lift(phi: np.ndarray, theta: Callable = theta, program: Any = kin.program) -> np.ndarray:
        return np.asarray(program.evaluate(theta(phi))[0], float)

    face = None
    extent = getattr(cam.design, "face_extent", None)
    if extent is not None:                                  # a flat face: its ends, its contact over the turn
        margin = float(cam.design.spec.follower.face_margin)

        def contact(phi: np.ndarray, theta: Callable = theta, kin: Any = kin) -> np.ndarray:
            t = np.asarray(theta(phi), float)
            return centre + kin.follower.fixed(t, kin.follower.pitch(t, kin.program.evaluate(t)))

        face = ((float(extent[0]) - margin, float(extent[1]) + margin), contact)
    point = centre + rest_point(f)
    made, met = stem_bodies(cam.name, f, plane, point, lift, width, tol, face,
                            slider_joint(driven[0], point) if driven else None)
    bodies += made
    joints += met


def cranked_placement(m: Any) -> Callable[..., tuple[np.ndarray, np.ndarray]]:
    """(phi, link) -> the placement (M, t) of link ``link`` of the shaft-driven linkage ``m``
    (:class:`~camgen.kinds.machine.cranked.CrankedMotion`) in the machine's frame: its part's frame (its first joint,
    turned as the line to its second) as :func:`linkgen.mechanisms.general.general_placement` places it, moved by
    the mount's offset. The last angles' solution is kept, as every link is placed at the same angles in turn."""
    from linkgen.mechanisms.general import general_placement

    last: list[tuple[bytes, Any]] = []

    def place(phi: np.ndarray, link: str) -> tuple[np.ndarray, np.ndarray]:
        key = np.asarray(phi, float).tobytes()
        if not last or last[0][0] != key:
            last[:] = [(key, general_placement(m.analysis, m.solve(phi)))]
        placed = last[0][1]
        shift = placed.origins[link] + m.offset
        return rotation(placed.angles[link]), shift

    return place


def _cranked_parts(m: Any, bodies: list[Body], joints: list[Joint],
                   pins: dict[tuple[float, float], tuple[list[str], int, float]],
                   shafts: dict[str, list[tuple[int, float]]]) -> None:
    """The parts of a shaft-driven linkage ``m`` (:class:`~camgen.kinds.machine.cranked.CrankedMotion`): each moving
    link's part as cut on plane 2 layer + its own layer, a joint at each pin two of them share, its crank on its
    shaft and its other ground joints as pins from the frame (merged with any pin at the same place)."""
    a, build = m.analysis, m.design.build
    s = a.linkage.structure
    cut = {p.name: p for p in build.cut}
    hw = max(p.half_width for p in build.parts)
    pin_r = m.design.spec.parts.pin_diameter / 2
    place = cranked_placement(m)
    prefix = f"linkages.{m.name}"
    for link in s.bodies:
        if link != "ground":
            plane = m.side * (2 * m.layer + build.layers[link])
            bodies.append(Body(f"{prefix}.{link}", plane, plane, cut[link].outline.flatten(0.01),
                               functools.partial(place, link=link)))

    def centre(phi: np.ndarray, point: str) -> np.ndarray:
        return np.asarray(m.solve(phi).points[point], float) + m.offset

    pivot = a.table.inputs[0].pivot
    for point, holders in s.revolutes.items():
        moving = [f"{prefix}.{h}" for h in holders if h != "ground"]
        joints += [Joint(x, y, functools.partial(centre, point=point), _margin(hw))
                   for i, x in enumerate(moving) for y in moving[i + 1:]]
        if "ground" not in holders:
            continue
        at = np.asarray(s.points[point], float) + m.offset
        if point == pivot and m.shaft:
            shaft = f"shafts.{m.shaft}"
            planes = [next(b.high for b in bodies if b.name == h) for h in moving]
            far = max(planes, key=abs)
            shafts.setdefault(m.shaft, []).append((far, pin_r))
            joints += [Joint(h, shaft, still(at), _margin(hw)) for h in moving]
        else:                                               # a pin at the same place (to 1e-9 mm) is one pin
            key = next((k for k in pins if math.dist(k, at) < 1e-9), (float(at[0]), float(at[1])))
            entry = pins.setdefault(key, ([], 0, pin_r))
            entry[0].extend(moving)
