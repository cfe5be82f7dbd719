"""A disc cam's kit: the frame, the follower (a guided slider or an arm), its roller, the shaft, spacers and the
hardware that mount the design so that it runs as designed. No I/O.

The stack, from the frame's bottom face (z = 0, mm) up:

* the frame plate (``kit.thickness``), holding the camshaft in its seat (a ``kit.bearing`` or a plain hole) at
  the origin, the follower's guide bolts (on the follower's axis, ``follower.offset`` to the right of the shaft) or
  its pivot bolt (at the design's pivot, ``follower.pivot_distance`` from the shaft), and two mounting holes;
* a gap as high as the roller's axle nut and washer (plus :data:`~camgen.core.kit.RUNNING_GAP`), filled round the
  shaft by a spacer, and the standoffs round the guide or pivot bolts;
* the cam and its roller, in one plane;
* a washer's height over the cam (over its hub boss, if it has one), the follower: a bar with the roller's axle
  hole and a slot the two guide bolts run in (translating), or an arm with the pivot's hole and the roller's at
  ``follower.arm_length`` (oscillating).

Every solid is placed at :data:`POSES` cam angles by the design's own kinematics (the roller's centre in the fixed
frame is the pitch point turned by the cam's angle, sense as ``cam.rotation``); two solids that share some height
never overlap in plan, and the roller touches the cam (the gap is reported).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import DesignError
from camgen.core.hardware import RUNNING_PLAY, bolt_length
from camgen.core.kit import (RUNNING_GAP, BomLine, CamKitTable, Plate, Solid, assembly_panels, bolt_line, bought,
                             check_clear, disc, fixed, footprint, part_entry, placed_meshes)
from camgen.core.parts import Allowances, Drawing, Part, Placed
from camgen.core.shapes import rounded_hull

#: cam angles over the turn at which the kit is placed and checked
POSES = 720
#: the cam angles (degrees) the assembly drawing shows, one panel each
DRAWN_DEG = (0, 90, 180, 270)
#: the shaft stands this far below the frame, to take a coupling or a pulley (mm)
SHAFT_STUB = 10.0


@dataclass(frozen=True)
class CamKit:
    """A cam's kit: the solids placed over the turn (nominal sizes), the kit's parts as the process makes them
    (with whether each is cut or printed), the bill of materials and the report's ``kit`` section."""

    table: CamKitTable
    solids: tuple[Solid, ...]
    made: tuple[tuple[Part, str], ...]
    bom: tuple[BomLine, ...]
    report: dict[str, Any]
    tolerance: float

    @property
    def drawing(self) -> Drawing:
        """The assembly seen from +Z at each of :data:`DRAWN_DEG` cam angles, a panel each from left to right
        (layers ``KIT-<degrees>-<part>``, see :func:`~camgen.core.kit.assembly_panels`)."""
        return assembly_panels(self.solids, tuple((POSES * d // 360, f"{d}") for d in DRAWN_DEG), self.tolerance)

    def placed(self, cam: Part | None = None) -> tuple[Placed, ...]:
        """The kit's STEP solids as assembled at theta = 0: each part as the process makes it (:attr:`made`; the
        standoffs one a post, ``standoff-1``, ...) turned and moved as the kit places it, at its height, and with
        ``cam`` (the cam's own STEP part) the cam on its shaft; nothing bought."""
        made = {part.name: part for part, _ in self.made}
        out = []
        for solid in self.solids:
            stem = solid.name.rpartition("-")[0] if solid.name.rpartition("-")[2].isdigit() else solid.name
            if solid.bought:
                continue
            part = made.get(solid.name) or made.get(stem)
            if part is not None:
                part = _named(part, solid.name)
            elif not solid.made:                        # a solid of no made part: the cam, when given
                part = cam
            if part is None:
                continue
            angle, (x, y) = solid.pose(0)
            out.append(Placed(solid.name, (part,), angle, (float(x), float(y), solid.z)))
        return tuple(out)

    def meshes(self) -> tuple[Any, ...]:
        """Every solid made (none bought: :func:`~camgen.core.kit.placed_meshes`) in its assembled place at theta = 0
        (the kit's 3MF)."""
        return placed_meshes(self.solids, 0)


def roller_centres(design: Any, theta: np.ndarray) -> np.ndarray:
    """The roller's centre (n, 2) mm in the fixed frame at cam angles ``theta`` (rad): the pitch point (cam frame)
    turned by the cam's angle in its sense of rotation."""
    cam = design.cam
    point = cam.pitch(theta).point
    turn = cam.follower.sense * theta
    c, s = np.cos(turn), np.sin(turn)
    return np.column_stack([c * point[:, 0] - s * point[:, 1], s * point[:, 0] + c * point[:, 1]])


def cam_kit(design: Any) -> CamKit:
    """The kit of a disc cam ``design`` with a translating or oscillating roller follower, for its ``[kit]``.

    Raises :class:`DesignError` naming the field to change when a part would meet another."""
    spec, table = design.spec, design.spec.kit
    bolt, tol, wall = table.hardware, spec.output.tolerance, table.wall
    theta = 2 * math.pi * np.arange(POSES) / POSES
    centres = roller_centres(design, theta)
    rr = spec.follower.roller_radius
    reach = float(np.linalg.norm(design.outline.contour.flatten(tol), axis=1).max())
    standoff_r = bolt.washer_outside / 2
    hole = bolt.clearance_hole
    if rr - hole / 2 < RUNNING_GAP:
        raise DesignError(f"kit.bolt: the roller's {bolt.name} axle hole ({hole:g} mm) leaves less than "
                          f"{RUNNING_GAP:g} mm of material in a roller of follower.roller_radius {rr:g} mm; use a "
                          f"smaller bolt or a roller of at least {hole / 2 + RUNNING_GAP:g} mm radius")
    oscillating = spec.follower.type == "oscillating-roller"
    if oscillating:
        follower, posts, angles, origins = _arm(design, centres, hole, wall, reach, standoff_r)
    else:
        follower, posts, angles, origins = _slider(design, centres, rr, hole, wall, reach, standoff_r)
    t = table.thickness
    seat = table.seat
    seat_hole = seat.outside if seat else table.shaft + RUNNING_PLAY
    width = seat.width if seat else 0.0
    gap = max(bolt.washer_thickness + bolt.nut_height + RUNNING_GAP, width - t + RUNNING_GAP)
    z_cam = t + gap
    roller_width = spec.follower.roller_width or spec.cam.thickness
    # the cam's top face, or its hub boss's (the shaft runs up through it)
    cam_top = z_cam + spec.cam.thickness + (design.part.boss[1] if design.part.boss else 0.0)
    z_follower = max(cam_top, z_cam + roller_width) + bolt.washer_thickness
    mount = seat_hole / 2 + 2 * wall + hole
    mounts = ((-mount, -mount), (mount, -mount))
    frame = Plate("frame", rounded_hull(np.array([(0.0, 0.0), *posts, *mounts]), max(seat_hole, hole) / 2 + wall),
                  (((0.0, 0.0), seat_hole), *((p, hole) for p in posts), *((m, hole) for m in mounts)), t, tol)
    spacer_od = table.shaft + (seat.outside - table.shaft) / 2 if seat else table.shaft + 2 * wall
    spacer = disc("spacer", spacer_od, table.shaft + RUNNING_PLAY, z_cam - max(t, width), tol)
    standoff = disc("standoff", bolt.washer_outside, hole, z_follower - t, tol)
    roller = disc("roller", 2 * rr, hole, roller_width, tol)
    nut = disc("axle-nut", bolt.nut_across_corners, 0.0, bolt.nut_height, tol).part(0.0, 0.0)
    shaft = disc("shaft", table.shaft, 0.0, SHAFT_STUB + cam_top, tol).part(0.0, 0.0)
    turn = design.cam.follower.sense * theta
    solids = [fixed(frame.part(0.0, 0.0), 0.0), fixed(spacer.part(0.0, 0.0), max(t, width)),
              *(fixed(_named(standoff.part(0.0, 0.0), f"standoff-{i + 1}"), t, p) for i, p in enumerate(posts)),
              Solid(design.part, z_cam, turn, np.zeros((POSES, 2)), made=False),
              Solid(roller.part(0.0, 0.0), z_cam, np.zeros(POSES), centres),
              Solid(follower.part(0.0, 0.0), z_follower, angles, origins),
              bought(nut, z_cam - bolt.washer_thickness - bolt.nut_height, np.zeros(POSES), centres),
              *(fixed(_named(nut, f"mount-nut-{i + 1}"), t, m, made=False, bought=True) for i, m in enumerate(mounts)),
              fixed(shaft, -SHAFT_STUB, made=False, bought=True)]
    if seat:
        ring = disc("bearing", seat.outside, seat.bore, seat.width, tol).part(0.0, 0.0)
        solids.append(fixed(ring, 0.0, made=False, bought=True))
    solids_t = tuple(solids)
    fields = {"translating-roller": "follower.offset", "oscillating-roller": "follower.pivot_distance"}
    check_clear(solids_t, POSES, tol, frozenset({frozenset((design.part.name, "roller"))}),
                fields[spec.follower.type])
    gaps = _roller_gaps(design, solids_t, centres, rr, tol)
    printed = Allowances(0.0, table.clearance, "kit.clearance")
    made = ((table.made(frame), table.process), (table.made(follower), table.process),
            (table.made(roller), table.process), (printed.printed(spacer), "fdm"), (printed.printed(standoff), "fdm"))
    # the axle runs down from its head on the follower through the roller to a washer and the nut under it
    grips = {"guide": t + (z_follower - t) + t, "axle": t + (z_follower - z_cam) + bolt.washer_thickness,
             "mount": t}
    bom = _bom(spec, table, made, grips, len(posts), SHAFT_STUB + cam_top, oscillating, design.cam.program.max_lift)
    report = _report(spec, table, solids_t, made, bom, gaps, posts, frame.holes[0][1])
    return CamKit(table, solids_t, made, bom, report, tol)


def _named(part: Part, name: str) -> Part:
    return Part(name, part.outline, part.holes, part.thickness, part.tolerance)


def _slider(design: Any, centres: np.ndarray, rr: float, hole: float, wall: float, reach: float,
            standoff_r: float) -> tuple[Plate, list, np.ndarray, np.ndarray]:
    """The guided slider: a bar along the follower's axis from the roller's axle hole (its origin) up, with one
    slot the two guide bolts run in; the guide bolts on the axis, above the roller's highest reach and clear of
    the cam's; the bar's placement (no turn; its origin on the roller's centre)."""
    e = float(centres[0, 0])
    low, high = float(centres[:, 1].min()), float(centres[:, 1].max())
    clear = reach + standoff_r + RUNNING_GAP
    y1 = max(math.sqrt(max(clear**2 - e**2, 0.0)), high + rr + standoff_r + RUNNING_GAP)
    y2 = y1 + max(2 * standoff_r + wall, high - low)
    slot = ((0.0, y1 - high), (0.0, y2 - low))
    if slot[0][1] - hole < wall:
        raise DesignError(f"kit.bolt: the slot of the follower's guide bolts comes within {slot[0][1] - hole:.3g} mm "
                          f"of the roller's axle hole (kit.wall {wall:g} mm is needed); use a smaller bolt or wall")
    bar = Plate("follower", rounded_hull(np.array([(0.0, 0.0), slot[1]]), hole / 2 + wall), (((0.0, 0.0), hole),),
                design.spec.kit.thickness, design.spec.output.tolerance, slots=((slot, hole),))
    return bar, [(e, y1), (e, y2)], np.zeros(len(centres)), centres


def _arm(design: Any, centres: np.ndarray, hole: float, wall: float, reach: float,
         standoff_r: float) -> tuple[Plate, list, np.ndarray, np.ndarray]:
    """The arm: the pivot's hole at its origin and the roller's at ``follower.arm_length`` on +X; placed turned
    from the pivot towards the roller's centre at each pose. Its pivot's standoff must clear the cam."""
    pivot = design.cam.follower.pivot
    arm = design.spec.follower.arm_length
    clear = reach + standoff_r + RUNNING_GAP
    if not np.linalg.norm(pivot) >= clear:
        raise DesignError(f"follower.pivot_distance: the pivot is {np.linalg.norm(pivot):.4g} mm from the shaft, and "
                          f"its standoff ({2 * standoff_r:g} mm across) clears the cam, which reaches {reach:.4g} mm, "
                          f"only from {clear:.4g} mm (or use a smaller kit.bolt)")
    plate = Plate("follower", rounded_hull(np.array([(0.0, 0.0), (arm, 0.0)]), hole / 2 + wall),
                  (((0.0, 0.0), hole), ((arm, 0.0), hole)), design.spec.kit.thickness, design.spec.output.tolerance)
    towards = centres - pivot
    angles = np.arctan2(towards[:, 1], towards[:, 0])
    return plate, [(float(pivot[0]), float(pivot[1]))], angles, np.tile(pivot, (len(centres), 1))


def _roller_gaps(design: Any, solids: tuple[Solid, ...], centres: np.ndarray, rr: float,
                 tol: float) -> dict[str, float]:
    """The roller's gap to the cam over the turn (mm; its centre's distance to the cam's outline less its radius),
    and the largest overlap of the two plans (mm^2)."""
    import shapely

    cam = next(s for s in solids if s.name == design.part.name)
    roller = next(s for s in solids if s.name == "roller")
    outline = [shapely.LinearRing(design.part.outline.moved(*cam.pose(k)).flatten(tol)) for k in range(POSES)]
    gap = shapely.distance(np.array(outline), shapely.points(centres)) - rr
    overlap = max(footprint(cam.part, *cam.pose(k), tol).intersection(footprint(roller.part, *roller.pose(k), tol)
                                                                      ).area for k in range(0, POSES, 8))
    return {"roller_gap_min_mm": float(gap.min()), "roller_gap_max_mm": float(gap.max()),
            "roller_overlap_max_mm2": float(overlap)}


def _bom(spec: Any, table: CamKitTable, made: tuple, grips: dict[str, float], posts: int, shaft_length: float,
         oscillating: bool, lift: float) -> tuple[BomLine, ...]:
    bolt = table.hardware
    lines = [BomLine(spec.name, 1, f"the cam, {spec.cam.thickness:g} mm (its own files)", "laser or fdm")]
    for part, source in made:
        count = posts if part.name == "standoff" else 1
        what = {"frame": "frame plate", "follower": "follower arm" if oscillating else "follower slider",
                "roller": "roller", "spacer": "shaft spacer", "standoff": "standoff"}[part.name]
        lines.append(BomLine(part.name, count, f"{what}, {part.thickness:g} mm", source))
    lines.append(BomLine("shaft", 1, f"{table.shaft:g} mm ground rod (h6), {math.ceil(shaft_length):g} mm long",
                         "buy", "ISO 286 h6"))
    lines.append(BomLine("shaft collar", 2, f"for the {table.shaft:g} mm shaft, under the frame and over the cam "
                         "(or the cam's hub set screw)", "buy", "DIN 705"))
    if table.seat:
        seat = table.seat
        lines.append(BomLine(f"bearing {seat.name}", 1, f"{seat.bore:g} x {seat.outside:g} x {seat.width:g} mm",
                             "buy", "ISO 15 (deep groove ball bearing)"))
    use = "pivot bolt through frame, standoff and arm" if oscillating else "guide bolts through frame, standoff " \
                                                                           "and the slider's slot"
    lines.append(bolt_line(bolt, bolt_length(bolt, grips["guide"]), posts, use))
    lines.append(bolt_line(bolt, bolt_length(bolt, grips["axle"]), 1, "roller axle through follower and roller"))
    lines.append(bolt_line(bolt, bolt_length(bolt, grips["mount"]), 2, "mounting the frame (add your base's "
                                                                       "thickness to the length)"))
    spring = spring_line(spec.follower, lift, oscillating)
    return tuple(lines) + ((spring,) if spring is not None else ())


#: the standards a return spring is ordered by: cylindrical helical compression and torsion springs of round wire
SPRING_STANDARDS = {False: "EN 13906-1", True: "EN 13906-3"}


def spring_line(follower: Any, lift: float, oscillating: bool) -> BomLine | None:
    """The return spring the ``[follower]`` table has (``spring_rate`` k in N/mm, ``preload`` F0 in N at s = 0,
    either alone meaning the other 0), sized as the design's loading takes it, for the program's largest ``lift`` (mm,
    or degrees of an arm's swing); None without one.

    A translating follower's is a compression spring on its axis: k, F0 at s = 0 and F0 + k h at the full lift h
    (mm); its free length is its installed length at s = 0 plus F0 / k. An oscillating arm's acts along the roller's
    path, so it is a torsion spring at the pivot of k L^2 per radian (L the arm, mm), F0 L N*mm at psi = 0 and
    F0 L + k L^2 psi_h at the full swing psi_h; its free position is F0 / (k L) radians back from psi = 0. A rate of
    0 is a constant-force spring (no free length)."""
    if follower.spring_rate is None and follower.preload is None:
        return None
    k, f0 = follower.spring_rate or 0.0, follower.preload or 0.0
    if not oscillating:
        size = (f"compression spring, rate {k:.4g} N/mm, {f0:.4g} N at s = 0 and {f0 + k * lift:.4g} N at the full "
                f"lift of {lift:.4g} mm; " + (f"free length: its length at s = 0 plus {f0 / k:.4g} mm" if k > 0
                                               else "constant force (rate 0)"))
        return BomLine("return spring", 1, size, "buy", SPRING_STANDARDS[False])
    arm = follower.arm_length
    rate = k * arm**2 * math.pi / 180.0                       # N*mm a degree
    size = (f"torsion spring at the arm's pivot, rate {rate:.4g} N*mm/degree ({k:.4g} N/mm at the roller, {arm:.4g} "
            f"mm out), {f0 * arm:.4g} N*mm at psi = 0 and {f0 * arm + rate * lift:.4g} N*mm at the full swing of "
            f"{lift:.4g} degrees; " + (f"free position {math.degrees(f0 / (k * arm)):.4g} degrees back from psi = 0"
                                       if k > 0 else "constant torque (rate 0)"))
    return BomLine("return spring", 1, size, "buy", SPRING_STANDARDS[True])


def _report(spec: Any, table: CamKitTable, solids: tuple[Solid, ...], made: tuple, bom: tuple[BomLine, ...],
            gaps: dict[str, float], posts: list, seat_nominal: float) -> dict[str, Any]:
    allow = table.allowances
    where = {s.name: s for s in solids}
    parts = []
    for part, source in made:
        solid = where.get(part.name) or where[f"{part.name}-1"]
        used = allow if source == table.process else Allowances(0.0, table.clearance)
        parts.append({**part_entry(Solid(part, solid.z, solid.angles[:1], solid.origins[:1]), used, {}),
                      "source": source})
    frame = parts[0]
    frame["holes"][0]["nominal_mm"] = seat_nominal
    fixed_points = [{"x_mm": round(x, 9), "y_mm": round(y, 9), "from_shaft_mm": round(math.hypot(x, y), 9)}
                    for x, y in posts]
    return {"bolt": table.bolt, "shaft_mm": table.shaft, "bearing": table.bearing, "process": table.process,
            "seat": {"nominal_diameter_mm": seat_nominal,
                     "as_made_diameter_mm": frame["holes"][0]["diameter_mm"]},
            ("pivot" if spec.follower.type == "oscillating-roller" else "guides"): fixed_points,
            "poses_checked": POSES, **{k: round(v, 9) for k, v in gaps.items()},
            "stack": [{"name": s.name, "z_mm": round(s.z, 9), "top_mm": round(s.top, 9), "made": s.made,
                       "bought": s.bought} for s in solids],
            "parts": parts, "bom": [line.row() for line in bom]}
