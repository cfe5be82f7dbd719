"""A barrel cam from a spec: its checks, its developed drawing and its solid. No I/O.

Checks. The developed pitch curve (x = Rm theta, z = z0 + s) is a plate cam's, so the pressure angle is
atan(s' / Rm) (reported too at the floor's and the rim's radii, where the roller's contact also runs:
atan(s' / r)). The walls are the pitch curve's offsets by Rw = Rr + c/2 only at Rm; at radius r the
developed curve is (r theta, zc), steeper and more sharply bent for smaller r, so each wall is checked for
undercut (as a grooved cam's flanks: the lower wall where the curve bulges up, the upper where it bulges down)
on the cylinders from the floor to the rim, and refused, naming the wall, the angle and the radius, where its
radius of curvature falls below Rw. The solid's walls are the exact envelope of the roller (see
:mod:`camgen.kinds.barrel.kinematics`), measured within the tolerance (:mod:`camgen.kinds.barrel.solid`).

An oscillating roller's developed curve on each cylinder is where its axis pierces it, and its pressure angle the
3D one (:class:`~camgen.followers.barrel.DevelopedRoller`); a conical roller's cutter there has the cone's radius
(grown by c/2). The roller's rolling slip at the floor and the rim is reported for either shape
(:func:`rolling_slips`).

The developed drawing (for checking, and to wrap round a turned cylinder as a paper template): the pitch
cylinder unrolled, 2 pi Rm by the length on ``OUTLINE``, the exact walls at Rm on ``GROOVE`` and the pitch
curve on ``PITCH``, as chords within the tolerance; x runs with the program (the way the roller travels over
the cam), from the roller's place at theta = 0.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.analysis import CamAnalysis, analyze
from camgen.kinds.barrel.mesh import SHORTEST_STEPS
from camgen.kinds.barrel.solid import Tube, groove_tube, rib_tube
from camgen.kinds.barrel.kinematics import GrooveWalls
from camgen.cam import Cam
from camgen.core.errors import DesignError, SpecError
from camgen.core.features import bore_reach, keyed_bore
from camgen.core.parts import LAYER_GROOVE, LAYER_OUTLINE, Drawing, Part
from camgen.core.shapes import Circle, Contour, Polyline
from camgen.dynamics import speed_report
from camgen.forces import Contact, drive_speed
from camgen.speed import Speed
from camgen.followers.barrel import BarrelGeometry, DevelopedRoller, rolling_slip, translating_pose
from camgen.followers.plate import PlateRoller
from camgen.groove import Flank, flank_checks
from camgen.program import Jump
from camgen.rig import Rig, developed_mount
from camgen.sizing import pressure_limit
from camgen.kinds.barrel.table import BarrelSpec

#: the layer of the developed pitch curve
LAYER_PITCH = "PITCH"
#: thinnest wall (mm) between the bore (as printed, with its keyway) and the groove's floor before a warning, as for
#: a disc cam
THIN_WALL = 2.0
#: how many cylinders from the floor to the rim the walls are checked on
CHECK_RADII = 9
#: the finest tolerance of the solid, in steps of single precision (what STL and 3MF hold) at the cam's size: a
#: point's rounding, up to 0.87 of a step, stays under a tenth of the tolerance (and the solid within some 18 s of
#: CPU and 1.4 GB: 2.0 million triangles for barrel.toml at that limit, 3.8e-5 mm)
SINGLE_STEPS = 10


@dataclass(frozen=True)
class WallCheck:
    """A wall's undercut check: the smallest radius of curvature of the developed curve bending that wall, over
    the cylinders from the floor to the rim, as a :class:`~camgen.groove.Flank` (its ``side`` the wall's
    name), and the cylinder's radius ``at_radius_mm`` where it is smallest."""

    flank: Flank
    at_radius_mm: float


@dataclass(frozen=True)
class BarrelDesign:
    """Everything known about a barrel cam before anything is written (mm, degrees)."""

    spec: BarrelSpec
    cam: Cam                       # the developed pitch curve at Rm (a plate cam of travel 2 pi Rm)
    analysis: CamAnalysis          # its pressure angle (atan(s'/Rm)) and radii
    jumps: tuple[Jump, ...]
    walls: GrooveWalls
    radii: tuple[float, float, float]          # the floor's, the pitch cylinder's and the rim's
    checks: tuple[WallCheck, WallCheck]        # lower, upper
    pressure_deg: dict[str, float]             # the largest pressure angle at the floor, the pitch and the rim
    drawing: Drawing
    drawing_error_mm: float
    blank: Part                    # the cylinder with its bore (as printed: the clearance applied), before the groove
    tube: Tube | None              # the groove's cutter (None until a solid is asked for)
    speed: Speed | None
    warnings: tuple[str, ...]
    slip: dict[str, float] | None = None       # the roller's largest rolling slip (percent) at the floor and the rim
    #: a rib's two rollers, below it and above it (their walls shifted by -g and +g), and the rib's thinnest
    #: normal width (mm) with the cam angle there (degrees); None for a groove
    rib: tuple[GrooveWalls, GrooveWalls] | None = None
    rib_thinnest: tuple[float, float] | None = None

    @property
    def tolerance(self) -> float:
        return self.spec.output.tolerance

    @property
    def cutter(self) -> float:
        """Rw = Rr + c/2 (mm): the radius the groove is cut with."""
        return self.walls.cutter

    @property
    def solid_tube(self) -> Tube:
        """The groove's cutter :meth:`with_solid` made (a ValueError on a design made without it)."""
        if self.tube is None:
            raise ValueError("the barrel's cutter is made by with_solid(): this design was made without it")
        return self.tube

    @property
    def single_step(self) -> float:
        """The step (mm) of single precision, which the solid's files hold, at the cam's size: the larger of the
        rim's radius and the length."""
        return float(np.spacing(np.float32(max(self.radii[2], self.spec.cam.length))))

    def with_solid(self, phase: float = 0.0) -> "BarrelDesign":
        """The same design with the groove's cutter made (:func:`camgen.kinds.barrel.solid.groove_tube`, its loops
        ``phase`` of a step round), its errors those of the files: within the tolerance once rounded to single
        precision (a point moves by up to sqrt(3)/2 of a step) and its short edges collapsed (by up to
        ``SHORTEST_STEPS`` steps, :func:`camgen.kinds.barrel.mesh.without_short_edges`). Refused
        (:class:`DesignError` naming output.tolerance) below ``SINGLE_STEPS`` steps of single precision at the cam's
        size (the larger of the
        rim's radius and the length, mm)."""
        inner, _, outer = self.radii
        size, step = max(outer, self.spec.cam.length), self.single_step
        if self.tolerance < SINGLE_STEPS * step:
            raise DesignError(f"output.tolerance: the solid's files (STL, 3MF) hold its points in single precision, "
                              f"{step:.3g} mm apart at its size of {size:g} mm; must be >= "
                              f"{SINGLE_STEPS * step:.3g} mm ({SINGLE_STEPS} of those steps) for the solid, up to 1 mm "
                              f"(got {self.tolerance:g}); or leave stl and 3mf out of output.formats")
        # how far a point may move in the files: single precision's rounding, and the collapse of an edge shorter than
        # SHORTEST_STEPS of its steps (camgen.kinds.barrel.mesh)
        rounding = (math.sqrt(3) / 2 + SHORTEST_STEPS) * step
        if self.rib is not None:
            return dataclasses.replace(self, tube=rib_tube(*self.rib, inner, outer, self.spec.cam.length,
                                                           self.tolerance, phase, rounding))
        return dataclasses.replace(self, tube=groove_tube(self.walls, inner, outer, self.tolerance, phase, rounding))

    def thumbnail(self, tolerance: float) -> np.ndarray:
        """The developed groove as a closed ring (mm, points within about ``tolerance``), for a family's overview:
        the lower wall along, the upper wall back."""
        walls = [shape.vertices for layer, shape in self.drawing.items
                 if layer == LAYER_GROOVE and isinstance(shape, Polyline)]
        step = max(1, int(len(walls[0]) * tolerance / (2 * math.pi * self.radii[1])))
        return np.vstack([walls[0][::step], walls[1][::-step]])

    def _repr_svg_(self) -> str:
        return self.drawing._repr_svg_()

    def _repr_html_(self) -> str | None:
        """Jupyter shows the interactive page, as :meth:`camgen.profile.CamDesign._repr_html_` does."""
        from camgen.kinds.barrel.outputs import barrel_bundle
        from camgen.core.page import bundle_frame

        return bundle_frame(barrel_bundle(self)[0])


def _developed_cam(cam: Cam, radius: float, walls: GrooveWalls) -> Cam:
    """The program developed on the cylinder of ``radius``: a plate cam of travel 2 pi radius whose roller is the
    cutter there; for an arm, the curve its roller's axis pierces there
    (:class:`~camgen.followers.barrel.DevelopedRoller`)."""
    if walls.arm is not None:
        return dataclasses.replace(cam, follower=DevelopedRoller(walls.arm, radius, walls.r0, walls.taper))
    cutter = walls.r0 + walls.taper * radius
    return dataclasses.replace(cam, follower=PlateRoller(walls.z0 - cutter, cutter, 2 * math.pi * radius))


def _wall_checks(cam: Cam, radii: np.ndarray, walls: GrooveWalls) -> tuple[WallCheck, WallCheck]:
    """Both walls' checks over ``radii``: the worst (smallest radius of curvature) of each."""
    worst: list = [None, None]
    for r in map(float, radii):
        developed = _developed_cam(cam, r, walls)
        for k, flank in enumerate(flank_checks(developed, developed.contact_radius)):
            if worst[k] is None or flank.pitch_rho_min_mm < worst[k].flank.pitch_rho_min_mm:
                worst[k] = WallCheck(dataclasses.replace(flank, side=("lower wall", "upper wall")[k]), r)
    return worst[0], worst[1]


def rolling_slips(walls: GrooveWalls, roller: float, radii: tuple[float, float, float]) -> dict[str, float]:
    """The roller's largest slip (percent of the cam's surface speed) along the way it rolls, at the floor and at the
    rim, over the cycle and both walls, rolling without slip on the pitch cylinder (see
    :func:`camgen.followers.barrel.rolling_slip`); ``roller`` is Rr."""
    r0 = roller - walls.taper * radii[1]            # the roller itself: Rr on the pitch cylinder, no clearance
    program = walls.program

    def worst(radius: float) -> float:
        def slip(i: int, t: np.ndarray) -> np.ndarray:
            m = program.segments[i].evaluate(t)
            pose = translating_pose(m, walls.z0) if walls.arm is None else walls.arm.pose(m)
            return np.maximum(*(np.abs(rolling_slip(pose, radius, radii[1], r0, walls.taper, side))
                                for side in (-1, 1)))
        return 100 * program.peak(slip)[0]

    return {"floor": worst(radii[0]), "rim": worst(radii[2])}


def _undercut_message(check: WallCheck) -> str:
    f = check.flank
    wall = f.side if f.side.startswith("rib") else f"groove's {f.side}"
    where = (f"undercut of the {wall} at {f.at_deg:.2f} degrees, on the cylinder of radius "
             f"{check.at_radius_mm:.4g} mm: ")
    if f.pitch_rho_min_mm == 0.0:
        return (where + "the follower velocity jumps there, a corner the wall cannot follow; use a law with "
                "continuous velocity")
    bend = "up" if f.side in ("lower wall", "rib's upper wall") else "down"
    return (where + f"the developed pitch curve bends {bend} there with a radius of {f.pitch_rho_min_mm:.4g} mm, "
            f"smaller than follower.roller_radius + cam.running_clearance / 2 = {f.offset_mm:.4g} mm; use a smaller "
            "roller, a shallower groove (cam.groove_depth), a larger cam.pitch_radius or a longer segment")


def _polyline_error(exact: Any, theta: np.ndarray, points: np.ndarray) -> float:
    """The largest distance (mm) of the exact curve ``exact(theta) -> (n, 2)`` from the chords between ``points``
    (the curve at ``theta``), at 8 probes a chord."""
    frac = np.arange(1, 9) / 9
    probes = exact((theta[:-1, None] + np.diff(theta)[:, None] * frac[None, :]).ravel()).reshape(-1, 8, 2)
    a, b = points[:-1, None, :], points[1:, None, :]
    ab = b - a
    t = np.clip(((probes - a) * ab).sum(-1) / np.maximum((ab**2).sum(-1), 1e-300), 0, 1)
    return float(np.linalg.norm(a + t[..., None] * ab - probes, axis=-1).max())


def _clipped(points: np.ndarray, width: float) -> np.ndarray:
    """A polyline cut to 0 <= x <= ``width`` (its ends found on the edges by straight interpolation)."""
    x = points[:, 0]
    keep = (x >= 0) & (x <= width)
    first, last = np.flatnonzero(keep)[[0, -1]]
    out = [points[first:last + 1]]
    for edge, i, j in ((0.0, first - 1, first), (width, last, last + 1)):
        if i >= 0 and j < len(points) and (x[i] - edge) * (x[j] - edge) < 0:
            t = (edge - x[i]) / (x[j] - x[i])
            end = (points[i] + t * (points[j] - points[i]))[None, :]
            out = [end, *out] if edge == 0.0 else [*out, end]
    return np.concatenate(out)


def _drawing(spec: BarrelSpec, lines: tuple[tuple[GrooveWalls, int, str], ...], tolerance: float
             ) -> tuple[Drawing, float]:
    """The developed drawing at Rm and the largest distance (mm) of its chords from the exact curves: each of
    ``lines`` a roller's walls and a side (-1 its lower wall, +1 its upper, 0 where its axis pierces the pitch
    cylinder) on a layer."""
    rm, length = spec.cam.pitch_radius, spec.cam.length
    width = 2 * math.pi * rm

    def curve(walls: GrooveWalls, side: int):
        def exact(theta: np.ndarray) -> np.ndarray:
            if side == 0:                        # where the roller's axis pierces the pitch cylinder
                pose = walls.pose(np.mod(theta, 2 * math.pi))
                return np.column_stack([rm * (theta + np.arcsin(pose[3] / rm)), pose[0]])
            phi, z = walls.developed(np.mod(theta, 2 * math.pi), rm, side)
            return np.column_stack([rm * (phi + theta - np.mod(theta, 2 * math.pi)), z])
        return exact

    cutter = lines[0][0].cutter
    n, margin = max(64, math.ceil(width / math.sqrt(8 * tolerance * cutter))), 2 * cutter / rm
    for _ in range(30):
        theta = np.linspace(-margin, 2 * math.pi + margin, n + 1)
        points = [curve(walls, side)(theta) for walls, side, _ in lines]
        error = max(_polyline_error(curve(walls, side), theta, pts)
                    for (walls, side, _), pts in zip(lines, points, strict=True))
        if error <= tolerance:
            break
        n = math.ceil(n * max(1.2, math.sqrt(error / tolerance)))
    else:
        raise DesignError(f"output.tolerance: the developed drawing cannot be brought within {tolerance:g} mm")
    frame = Contour(np.array([[0.0, 0.0], [width, 0.0], [width, length], [0.0, length]]))
    items: list[tuple[str, Contour | Polyline]] = [(LAYER_OUTLINE, frame)]
    for (_, _, layer), pts in zip(lines, points, strict=True):
        pts = _clipped(pts, width)
        items.append((layer, Polyline(pts, np.zeros(len(pts) - 1))))
    return Drawing(tuple(items), tolerance), error


def _rib_thinnest(cam: Cam, span: float, cutter: float, core: float) -> tuple[float, float]:
    """A rib's thinnest normal width (mm) and where (degrees): the rollers' axes, the same track shifted 2 g along
    the cam's axis, lie 2 g cos(alpha) apart square to it where it slopes at alpha, steepest on the core's cylinder
    (tan alpha = s' / r there), and the rib between them is that less 2 Rw."""
    steep = cam.program.peak(lambda i, t: np.abs(cam.program.segments[i].evaluate(t)[1]))
    return 2 * span * math.cos(math.atan(steep[0] / core)) - 2 * cutter, steep[1]


def _rib(spec: BarrelSpec, span: float | None, cam: Cam, walls: GrooveWalls, core: float
         ) -> tuple[tuple[GrooveWalls, GrooveWalls], tuple[float, float]] | tuple[None, None]:
    """A rib's two rollers' walls (below it, above it, ``span`` mm either side of the track) and its thinnest
    width, refused where the rollers leave it no width; (None, None) for a groove (no span)."""
    if span is None:
        return None, None
    thinnest = _rib_thinnest(cam, span, walls.cutter, core)
    if not thinnest[0] > 0:
        slope = math.acos(min(1.0, (thinnest[0] + 2 * walls.cutter) / (2 * span)))
        need = 2 * walls.cutter / math.cos(slope) - 2 * walls.cutter
        raise DesignError(f"cam.rib_width: the rollers leave the rib no width near {thinnest[1]:.2f} degrees, where "
                          f"the track slopes at {math.degrees(slope):.2f} degrees on the core (radius {core:g} mm); "
                          f"must be > {need:.6g} mm (got {spec.cam.rib_width:g})")
    rollers = (dataclasses.replace(walls, z0=walls.z0 - span), dataclasses.replace(walls, z0=walls.z0 + span))
    return rollers, thinnest


def barrel_rig(spec: BarrelSpec, geometry: BarrelGeometry) -> Rig:
    """The rig of a barrel cam's developed pitch curve: the template's motion on its developed mount
    (:func:`camgen.rig.developed_mount` of its ``geometry``); its cam is ``rig.cam(z0 - Rr)``, the plate's height
    under the roller's centre at rest."""
    return Rig.of(spec.name, spec.motion, developed_mount(spec.follower, geometry))


def design_barrel(spec: BarrelSpec) -> BarrelDesign:
    """Build and check the barrel cam ``spec`` describes: refused where a wall undercuts (see the module
    docstring). Its solid's cutter is made by :meth:`BarrelDesign.with_solid`."""
    g = BarrelGeometry.of(spec.cam, spec.follower, spec.motion)
    rig = barrel_rig(spec, g)
    cam = rig.cam(g.rest_height - rig.roller_radius)
    rm, depth, tol = spec.cam.pitch_radius, spec.cam.groove_depth, spec.output.tolerance
    radii = (rm - depth / 2, rm, rm + depth / 2)
    walls = GrooveWalls(cam.program, g.rest_height, g.cutter, g.sense, g.arm, g.taper, rm)
    checks = _wall_checks(cam, np.linspace(radii[0], radii[2], CHECK_RADII), walls)
    rib, thinnest = _rib(spec, g.rib_span, cam, walls, radii[0])
    if rib is not None:       # the rib's lower wall is the lower roller's upper side, bent as a groove's upper wall
        lower, upper = (WallCheck(dataclasses.replace(c.flank, side=name), c.at_radius_mm)
                        for c, name in ((checks[1], "rib's lower wall"), (checks[0], "rib's upper wall")))
        checks = lower, upper
    for check in sorted(checks, key=lambda c: c.flank.rho_min_mm):      # the worse wall first (stable: ties, lower)
        if check.flank.undercut:
            raise DesignError(_undercut_message(check))
    a = analyze(cam)
    pressure = {name: analyze(_developed_cam(cam, r, walls)).pressure_angle_max_deg
                for name, r in zip(("floor", "pitch", "rim"), radii, strict=True)}
    lines = (((walls, -1, LAYER_GROOVE), (walls, 1, LAYER_GROOVE), (walls, 0, LAYER_PITCH)) if rib is None else
             ((rib[0], 1, LAYER_GROOVE), (rib[1], -1, LAYER_GROOVE), (rib[0], 0, LAYER_PITCH),
              (rib[1], 0, LAYER_PITCH)))
    drawing, error = _drawing(spec, lines, tol)
    bore = spec.cam.bore
    grow = spec.output.clearance / 2
    holes = (() if bore == 0 else
             (keyed_bore(bore, grow) if spec.hub.keyway else Circle((0.0, 0.0), bore / 2 + grow),))
    rim = radii[2]
    blank = Part(spec.name, Contour(np.array([[rim, 0.0], [-rim, 0.0]]), np.array([1.0, 1.0])), holes,
                 spec.cam.length, tol, elephant_foot=spec.output.elephant_foot)
    jumps = tuple(cam.program.jumps())
    speed = None if spec.cam.rpm is None else speed_report(cam, spec.cam.rpm, None, None, None, [])
    if speed is not None and spec.follower.mass is not None:  # the roller's centre along the axis (an arm's arc)
        if spec.cam.material is not None and rib is not None:
            raise SpecError("a rib's contact pressure is not made yet; leave it out", "cam.material")
        stressed = None if spec.cam.material is None else (   # line contact along the depth, the walls at Rm
            Contact(spec.cam.material, spec.follower.material, depth), walls.r0 + walls.taper * rm,
            spec.follower.roller_radius)
        forces, speeds = drive_speed(spec, cam, ("lower wall", "upper wall") if rib is None else
                                     ("rib's upper wall", "rib's lower wall"), stressed)
        speed = dataclasses.replace(speed, forces=forces, speeds=speeds)
    warnings = [f"{j.quantity} jumps at {j.at_deg:.4g} degrees: {j.consequence}" for j in jumps if j.order < 3]
    wall = radii[0] - bore_reach(bore, spec.hub.keyway, spec.output.clearance)
    if bore and wall < THIN_WALL:
        warnings.append(f"only {wall:.3g} mm of material between the bore and "
                        f"{'the rib' if rib else 'the groove'}'s {'core' if rib else 'floor'}")
    limit = pressure_limit(spec)
    if pressure["floor"] > limit:
        warnings.append(f"pressure angle peaks at {pressure['floor']:.2f} degrees at the groove's floor "
                        f"({a.pressure_angle_max_deg:.2f} at the pitch cylinder), above the {limit:g} degree limit: "
                        "a larger cam.pitch_radius or a longer segment lowers it")
    return BarrelDesign(spec, cam, a, jumps, walls, radii, checks, pressure, drawing, error, blank, None, speed,
                        tuple(warnings), rolling_slips(walls, spec.follower.roller_radius, radii), rib, thinnest)
