"""A cam cut to a profile (a disc or a plate), from domain objects: the :class:`~camgen.rig.Rig` at a base radius,
the :class:`Body` it is cut into and the :class:`Finish` it is made to; its checks, its outline and its parts. No
spec, no sizing, no speed (those are the kinds', see :mod:`camgen.flat`), no I/O.

A grooved cam's island (its inner flank, :mod:`camgen.kinds.grooved.design`) is such a profile too, and a conjugate
pair's members are assembled from the same pieces (:func:`outline_body`, :func:`check_holes`,
:func:`engraving`, :class:`ProfileMaker`).
"""
from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np

from camgen.analysis import CamAnalysis, analysis_maker, face_extent, largest_roller
from camgen.cam import Cam, Maker
from camgen.core.errors import DesignError
from camgen.outline import Outline, envelope_outline, exact_outline, outline_maker, quietly
from camgen.core.parts import LAYER_ENGRAVE, Allowances, Part
from camgen.core.shapes import Circle, Contour, Polyline, Text
from camgen.core.features import bolt_holes, key_for, keyed_bore
from camgen.program import Jump
from camgen.rig import Rig
from camgen.sizing import smallest_for_curvature

if TYPE_CHECKING:
    from camgen.flat_envelope import FaceLeaves, FlatEnvelope
    from camgen.spec import HubTable, OutputTable

#: thinnest wall between the bore and the outline before a warning (mm)
THIN_WALL = 2.0


@dataclass(frozen=True)
class Body:
    """The flat part a profile is cut into: its ``name``, ``thickness`` and ``bore`` (diameter, 0 for none; mm),
    its ``hub`` features (keyway, boss, set screw, bolt holes: :class:`~camgen.spec.HubTable`) and whether it is
    ``engraved`` with its name, the sense of motion and a theta = 0 tick."""

    name: str
    thickness: float
    bore: float
    hub: HubTable
    engraved: bool

    @classmethod
    def of(cls, name: str, cam: Any, hub: HubTable) -> Body:
        """The body a template's ``name``, ``[cam]`` table (its thickness and bore) and ``[hub]`` table give."""
        return cls(name, cam.thickness, cam.bore, hub, hub.engrave)


@dataclass(frozen=True)
class Finish:
    """How the parts are made: every curve within ``tolerance`` mm, curved stretches as ``curves`` ("polylines"
    or "biarcs"), the ``allowances`` of the laser's kerf and the printer's clearance, and the DXF flavour ``dxf``
    ("segments" writes every arc as chords)."""

    tolerance: float
    curves: str
    allowances: Allowances
    dxf: str

    @classmethod
    def of(cls, output: OutputTable) -> Finish:
        """The finish a template's ``[output]`` table asks for."""
        return cls(output.tolerance, output.curves, Allowances(kerf=output.kerf, clearance=output.clearance,
                                                               kerf_field="output.kerf",
                                                               elephant_foot=output.elephant_foot), output.dxf)

    @property
    def outline_curves(self) -> str:
        """How the outline's curved stretches are made: biarcs only where the DXF keeps arcs (the segments flavour
        writes every arc as chords, so it gets chords measured against the surface instead)."""
        return "polylines" if self.dxf == "segments" else self.curves


@dataclass(frozen=True)
class Profile:
    """Everything known about a cam cut to a profile before anything is written (made by :func:`design_profile`).

    Lengths in mm, angles in degrees unless a name says otherwise; the cam centre is the origin, the follower on +Y
    at theta = 0 (see :doc:`/guides/conventions`).

    Attributes
    ----------
    body, finish : Body, Finish
        The part it is cut into and how it is made.
    cam : Cam
        The kinematic cam: its program (``cam.program``), follower (``cam.follower``) and ``base_radius`` (mm), and
        the pitch geometry at any cam angles (``cam.pitch(theta)``, radians).
    analysis : CamAnalysis
        The checks' extremes over the turn: ``pressure_angle_max_deg`` and where, the least convex radii of the
        pitch curve and the cam surface (``pitch_rho_min_mm``, ``profile_rho_min_mm``), the concave ones, and
        ``undercut``.
    jumps : tuple of Jump
        Where velocity, acceleration or jerk jump at a segment boundary (each reported as infinite acceleration or
        jerk).
    outline : Outline
        The nominal outline: the exact cam surface as lines and arcs within the tolerance, with its measured
        ``max_error_mm``.
    part : Part
        The nominal flat part: that outline, the bore and holes, the thickness.
    cut_outline, cut : Outline, Part
        The outline and part as the cut files carry them: the surface moved out by half the kerf, holes shrunk.
    printed : Part
        The part as printed: holes opened by the printing clearance.
    warnings : tuple of str
        The profile's warnings, as the console prints them.
    pressure_limit_deg : float
        The pressure-angle limit the checks used.
    face_extent : tuple of float, or None
        Flat faces: the nearest and farthest contact along the face (mm).
    face_leaves : tuple of FaceLeaves, or None
        A flat face with its folds cut off (an allowed undercut): where the law's face leaves the cut cam.
    """

    body: Body
    finish: Finish
    cam: Cam
    analysis: CamAnalysis
    jumps: tuple[Jump, ...]
    outline: Outline           # the nominal outline
    part: Part                 # the nominal part
    cut_outline: Outline       # the outline the cut files carry: the surface moved out by half the kerf
    cut: Part                  # the part as cut: that outline, holes shrunk by half the kerf
    printed: Part              # the part as printed: holes opened by the clearance
    warnings: tuple[str, ...]
    pressure_limit_deg: float
    face_extent: tuple[float, float] | None       # flat faces: nearest and farthest contact along the face (mm)
    face_leaves: tuple[FaceLeaves, ...] | None = None
    #: :attr:`wall_mm` where the design's checks measured it already (mm); None: measured when first read
    measured_wall_mm: float | None = dataclasses.field(default=None, repr=False, compare=False)

    @cached_property
    def wall_mm(self) -> float:
        """The thinnest material (mm) between the bore and the outline (as chords within :attr:`tolerance`): how
        near the outline comes to the centre less the bore's radius; :attr:`measured_wall_mm` where the checks
        measured it, else measured when first read (the design itself only needs to know that it is positive, and
        whether it is under :data:`THIN_WALL`, which bounds often tell without measuring)."""
        if self.measured_wall_mm is not None:
            return self.measured_wall_mm
        return reach(outline_body(self.outline, self.tolerance)) - self.body.bore / 2.0

    @property
    def allowances(self) -> Allowances:
        """The kerf and clearance applied (mm)."""
        return self.finish.allowances

    @property
    def written_error_mm(self) -> float:
        """A bound (mm) on the distance of the cut file's outline from the exact surface, as written: the
        outline's measured bound, or where the DXF flavour writes chords only (its outline then has no biarcs,
        just exact arcs) the larger of that and the chords' distance from those arcs."""
        chords = self.cut_outline.contour.flatten_error(self.tolerance) if self.finish.dxf == "segments" else 0
        return max(self.cut_outline.max_error_mm, chords)

    @property
    def tolerance(self) -> float:
        """The chord tolerance (mm) every curve of this design was made to."""
        return self.finish.tolerance

    def _repr_svg_(self) -> str:
        """Jupyter shows the cam as it will be cut."""
        return self.cut._repr_svg_()


def _undercut_message(rig: Rig, cam: Cam, a: CamAnalysis) -> str:
    if cam.follower.flat and math.isinf(a.profile_rho_min_mm):
        fold = next(i for i, step in cam.steps() if step < 0)
        return (f"motion[{rig.moving_segment(fold)}]: cusp at {a.pitch_rho_min_at_deg:.4g} degrees: the follower "
                "velocity drops there, so the profile folds back on itself and no flat face can follow it; use a law "
                "with continuous velocity (e.g. modified-uniform or cycloidal), or set cam.allow_undercut = true to "
                "cut the fold off (the follower then leaves the law there)")
    if cam.follower.flat:
        smallest = smallest_for_curvature(rig, near=cam.base_radius)
        return (f"cusp at {a.pitch_rho_min_at_deg:.2f} degrees: the profile's radius of curvature falls to "
                f"{a.profile_rho_min_mm:.4g} mm, so the flat face cannot follow the law there; the smallest "
                f"cam.base_radius that works is {smallest:.4g} mm (or set cam.allow_undercut = true to cut the fold "
                "off: the follower then leaves the law there)")
    rr = cam.contact_radius
    corner = a.pitch_rho_min_mm == 0.0
    where = f"undercut at {a.pitch_rho_min_at_deg:.2f} degrees: "
    if corner:
        jump = next(i for i, turn in cam.corners() if turn > 0)
        return (f"motion[{rig.moving_segment(jump)}]: " + where + "the follower velocity jumps there, so the pitch "
                "curve has a convex corner that no roller can follow; use a law with continuous velocity (e.g. "
                "modified-uniform) or set cam.allow_undercut = true")
    best = largest_roller(rig, cam.base_radius)
    fits = (f"the largest roller that fits is {best:.4g} mm" if best is not None
            else "no roller fits this base radius")
    return (where + f"the pitch curve's radius of curvature is {a.pitch_rho_min_mm:.4g} mm, smaller than "
            f"follower.roller_radius {rr:.4g} mm; {fits} (or enlarge cam.base_radius, or set "
            "cam.allow_undercut = true)")


def design_profile(rig: Rig, base_radius: float, body: Body, finish: Finish, allow_undercut: bool,
                   pressure_limit: float) -> Profile:
    """Build, check and outline the cam ``rig`` makes on a base circle of ``base_radius`` mm (a plate's height
    under its profile), cut into ``body`` and made to ``finish``; ``pressure_limit`` (degrees) is the limit its
    warning names. No sizing (the base radius is given) and no speed: those are the kind's (:mod:`camgen.flat`).

    Raises :class:`DesignError` for an undercut (unless ``allow_undercut``: a roller's cam is then the cutter's
    envelope, a flat face's the envelope of its lines with the folds cut off, see :mod:`camgen.flat_envelope`) and
    for a bore or holes that leave no material. Messages name the template's keys (``cam.base_radius``,
    ``follower.roller_radius``, ``cam.bore``, ``hub.bolt_circle``, ``output.clearance``, ``hub.engrave``).
    """
    cam = rig.cam(base_radius)
    tol, curves = finish.tolerance, finish.outline_curves
    # the analysis and the exact outline from the same evaluations (one a round); the outline is kept only where
    # it is the one the cam needs (no undercut, no corner of a knife edge), and so are its errors
    a, exact = cam.serve([analysis_maker(cam), _tentative(outline_maker(cam, tol, curves))])
    if a.undercut and not allow_undercut:
        raise DesignError(_undercut_message(rig, cam, a))
    corners = cam.corners()
    sharp = [i for i, turn in corners if turn > 0]
    if sharp and cam.contact_radius == 0 and not allow_undercut:
        at = math.degrees(cam.program.segments[sharp[0]].end) % 360.0
        raise DesignError(f"motion[{rig.moving_segment(sharp[0])}]: the follower velocity jumps at {at:.4g} "
                          "degrees, a sharp corner in the profile where the knife edge's pressure angle jumps; use a "
                          "law with continuous velocity (e.g. modified-uniform), or set cam.allow_undercut = true "
                          "to cut the corner as it is")
    # a knife edge's corners make corners in every offset too: the noded envelope trims and rounds them exactly
    envelope = a.undercut or (cam.contact_radius == 0 and bool(corners))
    cut_off = _flat_envelope(cam, tol, curves) if cam.follower.flat and a.undercut else None
    if cut_off is not None:
        outline = cut_off.outline(0.0)
    else:
        outline = envelope_outline(cam, tol) if envelope else exact
        if isinstance(outline, Exception):
            raise outline

    # the bore and the holes: where bounds make the checks certain (and no marks are to be fitted), nothing more;
    # else shapely on the outline's chords (the same checks, the same errors) and the wall measured
    wall = None                                         # certainly at least THIN_WALL
    holes = body_holes(body, 0.0)
    if body.engraved or not _certainly_clear(body.bore, holes, outline.contour, tol):
        polygon = outline_body(outline, tol)
        near = reach(polygon)
        wall = near - body.bore / 2.0
        _check_bore(body.bore, polygon, near)
        check_holes(body, polygon, tol)
    allowances = finish.allowances
    check_opened_holes(body, allowances.clearance, outline, tol)
    marks = engraving(body, cam, polygon, near) if body.engraved else ()
    maker = ProfileMaker(body, finish, cam, envelope, marks, outline, cut_off, holes)
    part, cut, printed = maker.part(0.0, 0.0), allowances.cut(maker), allowances.printed(maker)
    jumps = tuple(cam.jumps())
    warnings = _warnings(body.bore, a, jumps, wall, cam.program.segments, cut_off, pressure_limit)
    extent = (cut_off.face_extent if cut_off is not None else face_extent(cam)) if cam.follower.flat else None
    return Profile(body=body, finish=finish, cam=cam, analysis=a, jumps=jumps, outline=outline, part=part,
                   cut_outline=maker.outline(allowances.kerf / 2), cut=cut, printed=printed, warnings=warnings,
                   pressure_limit_deg=pressure_limit, face_extent=extent,
                   face_leaves=cut_off.leaves if cut_off is not None else None, measured_wall_mm=wall)


def outline_body(outline: Outline, tolerance: float) -> Any:
    """The outline as shapely's polygon of its chords within ``tolerance`` mm: what the bore and hole checks and
    the wall are measured on."""
    import shapely

    return shapely.Polygon(outline.contour.flatten(tolerance))


def reach(polygon: Any) -> float:
    """How near (mm) the outline ``polygon`` (:func:`outline_body`) comes to the centre."""
    import shapely

    return float(polygon.exterior.distance(shapely.Point(0.0, 0.0)))


def _check_bore(bore: float, polygon: Any, near: float) -> None:
    """The bore (its diameter ``bore`` mm) must leave material: the centre inside the outline ``polygon``
    (:func:`outline_body`), which comes no nearer to it than ``near`` mm, further than the bore's radius."""
    import shapely

    if bore > 0 and not (polygon.contains(shapely.Point(0.0, 0.0)) and near - bore / 2.0 > 0):
        raise DesignError(f"cam.bore: {bore:.4g} mm leaves no material; the outline comes within "
                          f"{near:.4g} mm of the centre, so the bore must be < {2 * near:.4g} mm")


def _tentative(maker: Maker) -> Maker:
    """``maker`` run on the chance that its result is needed: an error it raises is returned instead, for the caller
    to raise where it uses the result; numpy's floating-point warnings are silenced in its steps (a cam with an
    undercut, whose exact outline is not used, may divide by zero in it), set once in a copy of the caller's
    context (see :func:`camgen.outline.quietly`)."""
    try:
        return (yield from quietly(maker, all="ignore"))
    except Exception as error:          # any: raised by the caller where the outline is used
        return error


def step_part(design: Profile) -> tuple[Part, Outline]:
    """The printed part as the STEP file carries it, and the outline it has: the outline made of biarcs (exact arcs
    within ``output.tolerance`` mm of the exact surface, measured), whatever ``output.curves`` and ``output.dxf``
    say, so a CAD program gets a few dozen smooth faces instead of hundreds of flat facets. An envelope of an
    allowed undercut that is not a flat face's (a roller's loops cut away, a knife edge's corners) has no biarc
    maker and keeps its chords. Holes, clearance and elephant foot are the printed part's."""
    outline = design.outline
    if design.finish.outline_curves == "biarcs" or step_chords(design):
        return design.printed, outline
    tol = design.tolerance
    smooth = (_flat_envelope(design.cam, tol, "biarcs").outline(0.0) if design.face_leaves is not None
              else exact_outline(design.cam, tol, "biarcs"))
    return dataclasses.replace(design.printed, outline=smooth.contour), smooth


def _flat_envelope(cam: Cam, tolerance: float, curves: str) -> FlatEnvelope:
    """:func:`camgen.flat_envelope.flat_envelope`, loaded only when a flat face's undercut is cut off."""
    from camgen.flat_envelope import flat_envelope

    return flat_envelope(cam, tolerance, curves)


def step_chords(design: Profile) -> bool:
    """Whether the STEP file keeps the outline's chords (see :func:`step_part`): an envelope of an allowed undercut
    that is not a flat face's has no biarc maker."""
    return design.outline.envelope and design.face_leaves is None


class ProfileMaker:
    """The cam ``cam`` cut into ``body`` as a part at any offset of its surface (a
    :class:`~camgen.core.parts.PartMaker`), made to ``finish``: the outline is made afresh from the exact surface
    moved out by the offset (so kerf stays exact), once per offset; an ``envelope`` (an allowed undercut, a knife
    edge's corners) as the cutter's, a flat face's folds ``cut_off`` as its envelope does. ``marks`` are the
    engraving, ``nominal`` the outline at offset 0, ``holes`` the holes as drawn where the caller made them."""

    def __init__(self, body: Body, finish: Finish, cam: Cam, envelope: bool, marks: tuple, nominal: Outline,
                 cut_off: FlatEnvelope | None = None, holes: tuple | None = None) -> None:
        self.body, self.finish, self.cam, self.envelope, self.marks = body, finish, cam, envelope, marks
        self.cut_off = cut_off
        #: the holes as drawn (:func:`body_holes` grown by 0), where the caller made them already
        self.holes = holes
        self._outlines = {0.0: nominal}
        self._parts: dict[tuple[float, float], Part] = {}

    def outline(self, offset: float) -> Outline:
        """The outline of the surface moved out of the cam by ``offset`` mm."""
        if offset not in self._outlines:
            tol = self.finish.tolerance
            if self.cut_off is not None:                # a flat face's folds cut off: its corners become arcs
                made = self.cut_off.outline(offset)
            elif self.envelope:
                made = envelope_outline(self.cam, tol, offset)
            else:
                made = exact_outline(self.cam, tol, self.finish.outline_curves, offset)
            self._outlines[offset] = made
        return self._outlines[offset]

    def part(self, outline_grow: float, hole_grow: float) -> Part:
        """The part with its outline and holes moved out by these distances (mm), made once for each pair: the
        nominal, cut and printed parts are one where kerf and clearance are 0 (-0.0 the same as 0.0: the outline
        is the same and the holes only add it to their radii)."""
        if (outline_grow, hole_grow) not in self._parts:
            body, hub = self.body, self.body.hub
            boss = (hub.boss_diameter, hub.boss_height) if hub.boss_diameter else None
            self._parts[outline_grow, hole_grow] = Part(
                name=body.name, outline=self.outline(outline_grow).contour, holes=self._grown_holes(hole_grow),
                thickness=body.thickness, tolerance=self.finish.tolerance, marks=self.marks, boss=boss,
                set_screw=hub.set_screw)
        return self._parts[outline_grow, hole_grow]

    def _grown_holes(self, grow: float) -> tuple:
        """:func:`body_holes` grown by ``grow`` mm: those made already where it is 0 (a hole adds it to its radius,
        so -0.0 too)."""
        return self.holes if grow == 0.0 and self.holes is not None else body_holes(self.body, grow)


def body_holes(body: Body, grow: float) -> tuple:
    """The body's bore (keyed or round) and mounting holes, their edges moved out by ``grow`` mm."""
    hub, bore = body.hub, body.bore
    out: list = []
    if bore > 0:
        out.append(keyed_bore(bore, grow) if hub.keyway else Circle((0.0, 0.0), bore / 2 + grow))
    if hub.bolt_holes:
        out.extend(bolt_holes(hub.bolt_circle, hub.bolt_holes, hub.bolt_hole_diameter, grow))
    return tuple(out)


#: how far, relative to the sizes involved, a bound must clear what it is checked against to be certain: rounding
#: in the bounds is a few parts in 1e16, so this leaves to the exact test only holes within about 1e-9 of the cam's
#: size of the limit (some 1e-7 mm for a 50 mm cam; the squared bounds of :func:`_inside_clear` in squared units)
_CERTAIN = 1e-9


def _certainly_clear(bore: float, holes: tuple, contour: Contour, tolerance: float) -> bool:
    """Whether bounds make the bore and hole checks (:func:`_check_bore`, :func:`check_holes`) certain to pass with
    at least :data:`THIN_WALL` mm round the bore: the centre of the bore and of every hole inside the outline (as
    chords within ``tolerance`` mm: the polygon those checks test) and further from it than the hole reaches (the bore
    by THIN_WALL more), every two holes further apart than they reach, each with room to spare for rounding. False
    where that is not certain: the exact checks then decide, raise their errors and measure the wall. ``bore``: the
    bore's diameter (mm); ``holes``: the body's holes as drawn (:func:`body_holes` grown by 0)."""
    found = [_hole_circle(hole) for hole in holes]      # the bore first, centred on the origin
    if not found:
        return True
    circles = [c for c in found if c is not None]
    if len(circles) < len(found):                       # a hole that is not a circle: the exact checks decide
        return False
    for (c, r), (d, q) in itertools.combinations(circles, 2):
        if not abs(c - d) - r - q > _CERTAIN * (1.0 + abs(c) + abs(d) + r + q):
            return False
    reach = [r for _, r in circles]
    if bore > 0:
        reach[0] = max(reach[0], bore / 2.0 + THIN_WALL)
    return _inside_clear(contour, tolerance, np.array([c for c, _ in circles]), reach)


def _hole_circle(hole: Any) -> tuple[complex, float] | None:
    """A circle (centre x + iy, radius; mm) holding ``hole`` as flattened: a circle's own, a contour's (a keyed
    bore) about the origin, through its farthest vertex or arc; None for anything else."""
    if isinstance(hole, Circle):
        return complex(*hole.centre), hole.radius * (1.0 + _CERTAIN)
    if isinstance(hole, Contour):
        z = hole.vertices.view(np.complex128)[:, 0]
        arc = hole.bulges.nonzero()[0]
        centre, radius = _arc_circles(hole.bulges[arc], z[arc], (np.concatenate((z[1:], z[:1])) - z)[arc])
        return 0j, float(max(np.abs(z).max(), (np.abs(centre) + radius).max(initial=0.0))) * (1.0 + _CERTAIN)
    return None


def _arc_circles(b: np.ndarray, start: np.ndarray, run: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The circles of arcs of bulge ``b`` from ``start`` running ``run`` to their ends (complex x + iy, mm): their
    centres, e (1/2 + i (1 - b^2) / 4b) on from the start (e the run), and radii |e| (1 + b^2) / 4|b|; no
    trigonometry."""
    return start + run * (0.5 + 0.25j * (1.0 - b * b) / b), np.abs(run) * (1.0 + b * b) / (4.0 * np.abs(b))


def _inside_clear(contour: Contour, tolerance: float, points: np.ndarray, reach: Sequence[float]) -> bool:
    """Whether each of ``points`` (complex x + iy, mm) certainly lies inside the polygon
    ``contour.flatten(tolerance)`` makes, further than its ``reach`` (mm, one a point: Python floats or an array)
    from it. Bounds, no flattening: an arc of at most half a turn and the chords made for it lie within its sagitta
    |e b| / 2 of its chord (e the chord, b the bulge), and a chord is no nearer to a point than
    sqrt(min(|p|^2, |q|^2) - |e|^2 / 4) (p, q its ends seen from the point: |p + t e|^2 is that minimum less at most
    t (1 - t) |e|^2); where that is not enough, an arc's chords lie between its circle and one tolerance inside it
    (:func:`_arcs_clear`). Clear of every piece, a point lies inside where the pieces wind once round it
    counter-clockwise, each chord sweeping the angle it subtends (winding number 1: odd, as GEOS counts crossings).
    The pieces are first bounded all at once (:func:`_far_from_all`), a few numpy calls fewer, then where that is not
    enough each alone."""
    bulge = np.abs(contour.bulges)
    z = contour.vertices.view(np.complex128)[:, 0]
    ring = np.concatenate((z, z[:1])) - points[:, None]            # the vertices seen from each point
    run = ring[0, 1:] - ring[0, :-1]
    length = np.abs(run)
    near = np.abs(ring)
    extent = float(near.max())
    margin = _CERTAIN * (1.0 + extent * extent)
    widest = float(bulge.max(initial=0.0))
    turn = ring[:, 1:] * ring[:, :-1].conjugate()
    swept = np.arctan2(turn.imag, turn.real)
    if widest > 1.0 or not _far_from_all(near, length, widest, reach, margin):
        half = length * 0.5
        low = np.minimum(near[:, :-1], near[:, 1:])
        far = np.array(reach)
        gap = low * low - half * half - (far[:, None] + half * bulge) ** 2
        if widest > 1.0 or float(gap.min()) <= margin:
            clear = (gap > margin) & (bulge <= 1.0)
            if not _arcs_clear(contour, tolerance, ring[:, :-1], run, far, clear, swept):
                return False
    return all(abs(turns / (2.0 * np.pi) - 1.0) < 1e-3 for turns in swept.sum(axis=1).tolist())


def _far_from_all(near: np.ndarray, length: np.ndarray, widest: float, reach: Sequence[float], margin: float) -> bool:
    """:func:`_inside_clear`'s bound of each piece taken for all at once: a point whose vertices are all at least
    m from it (``near``, (k, n + 1) mm), pieces' chords at most 2 H long (``length``, mm) and bulges at most
    ``widest`` (<= 1) is further from every piece than sqrt(m^2 - H^2) - H widest, each piece's own bound being no
    less; so whether m^2 - H^2 - (reach + H widest)^2 exceeds ``margin`` for every point (``reach``, k of them, mm, the
    squared bounds' room for rounding). Enough where no long chord comes near (a cam's bore), in Python floats."""
    most = float(length.max(initial=0.0)) * 0.5                     # the longest half chord: halving is exact
    for m, r in zip(near.min(axis=1).tolist(), reach, strict=True):
        if not m * m - most * most - (r + most * widest) ** 2 > margin:
            return False
    return True


def _arcs_clear(contour: Contour, tolerance: float, start: np.ndarray, run: np.ndarray, reach: np.ndarray,
                clear: np.ndarray, swept: np.ndarray) -> bool:
    """:func:`_inside_clear` for the pieces a chord's bound leaves unclear (``clear`` False; pieces seen from each
    point from ``start``, running ``run``): whether each is an arc whose chords, which lie between its circle and
    one ``tolerance`` inside it, are further than ``reach`` from the point. An arc seen from inside its circle
    turns the way its bulge says, less than a whole turn: its chord's angle in ``swept`` becomes that angle a turn
    on where it turns the other way (uncertain where it is nearly 0)."""
    arc = contour.bulges.nonzero()[0]
    b = contour.bulges[arc]
    centre, radius = _arc_circles(b, start[:, arc], run[arc])      # seen from each point
    off = np.abs(centre)
    rounding = _CERTAIN * (1.0 + float((off + radius).max(initial=0.0)))
    clear[:, arc] |= np.maximum(off - radius, radius - tolerance - off) - reach[:, None] > rounding
    # whether a point lies inside an arc's circle decides the angle the arc sweeps: not where rounding could
    if not clear.all() or (np.abs(off - radius) <= rounding).any():
        return False
    seen, inner = swept[:, arc], off < radius
    swept[:, arc] = np.where(inner & (seen * b < 0), seen + np.copysign(2.0 * np.pi, b), seen)
    return not (inner & (np.abs(seen) < 1e-9)).any()


def check_holes(body: Body, polygon: Any, tolerance: float) -> None:
    """Every hole of ``body`` must lie inside the cam's outline ``polygon`` (:func:`outline_body`) with material
    round it, and no two holes may meet (holes as chords within ``tolerance`` mm)."""
    import shapely

    holes = body_holes(body, 0.0)
    rings = [shapely.Polygon(hole.flatten(tolerance)) for hole in holes]
    fields = ["hub.bolt_circle" if isinstance(h, Circle) and h.centre != (0.0, 0.0) else "cam.bore" for h in holes]
    for ring, field in zip(rings, fields, strict=True):
        if not polygon.contains_properly(ring):        # inside, its edge clear of the outline (GEOS's predicate)
            raise DesignError(f"{field}: a hole reaches the cam's outline (it comes within "
                              f"{polygon.exterior.distance(ring):.3g} mm); make it smaller or move it in")
    for i, j in itertools.combinations(range(len(rings)), 2):
        gap = rings[i].distance(rings[j])
        if gap <= 0:
            what = "two bolt holes overlap" if fields[i] == fields[j] else "a bolt hole cuts into the bore"
            hub = body.hub
            raise DesignError(f"hub.bolt_circle: {what} ({hub.bolt_holes} holes of {hub.bolt_hole_diameter:g} mm on a "
                              f"{hub.bolt_circle:g} mm circle, bore {body.bore:g} mm); use fewer or smaller "
                              "holes, or another circle")


def check_opened_holes(body: Body, clearance: float, outline: Outline, tolerance: float, cam: str = "the cam") -> None:
    """The printed part's holes, opened by the printing ``clearance`` (``output.clearance``, mm), must stay inside
    the outline as the drawn ones must (:func:`check_holes`): a hole opened through the outline is a notch in the
    printed cam, no hole. Nothing to check without a clearance or holes; bounds settle it where they can
    (:func:`_certainly_clear`), shapely on the outline's chords where they cannot. Every cam cut to an outline with
    its body's holes is checked so (a disc, a plate, a grooved cam's island, each cam of a conjugate pair): ``cam``
    names it in the message."""
    import shapely

    opened = body_holes(body, clearance / 2) if clearance > 0 else ()
    if not opened or _certainly_clear(body.bore, opened, outline.contour, tolerance):
        return
    polygon = outline_body(outline, tolerance)
    for hole, drawn in zip(opened, body_holes(body, 0.0), strict=True):
        if not polygon.contains_properly(shapely.Polygon(hole.flatten(tolerance))):
            gap = polygon.exterior.distance(shapely.Polygon(drawn.flatten(tolerance)))
            raise DesignError(f"output.clearance: must be < {2 * gap:.4g} mm with these holes (got {clearance:g}): "
                              f"it opens a hole through {cam}'s outline (as drawn the hole comes within {gap:.3g} "
                              "mm of it)")


def engraving(body: Body, cam: Cam, polygon: Any, near: float) -> tuple:
    """ENGRAVE marks on ``body``, each clear of the others, of the holes and of the outline ``polygon``
    (:func:`outline_body`, which comes ``near`` mm of the centre; checked): the part's name, an arrow in the sense of
    motion and a tick at theta = 0, towards ``cam``'s follower there. A disc carries them in the band between its
    outermost hole and its outline (the name at the bottom, the arrow upper left, the tick towards the follower); a
    plate in the strip under its profile (the arrow shows the way the plate moves under the follower)."""
    marks = _plate_marks(body, cam) if cam.is_plate else _disc_marks(body, cam, near)
    _check_marks(body, polygon, marks)
    return tuple((LAYER_ENGRAVE, mark) for mark in marks)


def _arrow(tail: np.ndarray, tip: np.ndarray, bulge: float, width: float, back: np.ndarray) -> tuple:
    """A shaft from ``tail`` to ``tip`` (an arc of ``bulge``) and a head ``width`` mm wide, pointing along ``back``
    reversed (a unit vector from the tip back along the shaft)."""
    side = np.array([-back[1], back[0]]) * width / 2
    base = tip + back * width
    return (Polyline(np.array([tail, tip]), np.array([bulge])),
            Polyline(np.array([base + side, tip, base - side]), np.zeros(2)))


def _disc_marks(body: Body, cam: Cam, reach: float) -> tuple:
    hub = body.hub
    inner = body.bore / 2 + (key_for(body.bore)[1] if hub.keyway else 0.0)
    if hub.bolt_holes:
        inner = max(inner, hub.bolt_circle / 2 + hub.bolt_hole_diameter / 2)
    mid = inner + 0.5 * (reach - inner)
    height = max(1.0, min(5.0, 0.3 * (reach - inner), 1.2 * mid / max(1, len(body.name))))
    name = Text(body.name, (-0.3 * height * len(body.name), -mid - 0.5 * height), height)
    sense = cam.follower.sense                           # the cam's sense of rotation (+1 counter-clockwise)

    def at(radius: float, degrees: float) -> np.ndarray:
        return radius * np.array([math.cos(math.radians(degrees)), math.sin(math.radians(degrees))])

    start, end = (135.0, 195.0) if sense > 0 else (195.0, 135.0)
    back = at(1.0, end - sense * 90.0)                   # from the tip back along the arc's tangent
    shaft, head = _arrow(at(mid, start), at(mid, end), math.tan(sense * math.radians(60) / 4), height, back)
    contact = cam.pitch(np.array([0.0])).point[0]
    direction = contact / np.linalg.norm(contact)
    tick = Polyline(np.array([direction * (reach - 2 * height), direction * (reach - height)]), np.zeros(1))
    return name, shaft, head, tick


def _plate_marks(body: Body, cam: Cam) -> tuple:
    strip, travel = cam.base_radius, cam.follower.travel            # the plate under its profile, from y = 0
    height = max(1.0, min(5.0, 0.3 * strip))
    y = 0.5 * strip
    name = Text(body.name, (0.1 * travel, y - 0.5 * height), height)
    tip_x = 0.6 * travel
    shaft, head = _arrow(np.array([tip_x + 4 * height, y]), np.array([tip_x, y]), 0.0, height, np.array([1.0, 0.0]))
    tick = Polyline(np.array([[0.0, strip - 2 * height], [0.0, strip - height]]), np.zeros(1))
    return name, shaft, head, tick


def _check_marks(body: Body, polygon: Any, marks: tuple) -> None:
    """Every mark (name, arrow, tick) lies on the part, off its holes, and clear of the other marks."""
    import shapely

    def footprint(mark: Any) -> Any:
        if isinstance(mark, Text):
            x, y = mark.position
            return shapely.box(x, y, x + 0.6 * mark.height * len(mark.text), y + mark.height)
        return shapely.LineString(mark.flatten(0.05)).buffer(0.2)

    solid = polygon
    for hole in body_holes(body, 0.0):
        solid = solid.difference(shapely.Polygon(hole.flatten(0.05)))
    name, shaft, head, tick = (footprint(m) for m in marks)
    groups = [name, shaft.union(head), tick]
    if not all(solid.contains(g) for g in groups) or any(a.intersects(b) for a, b in itertools.combinations(groups, 2)):
        raise DesignError("hub.engrave: the name, the arrow and the theta = 0 tick do not fit on the part clear of "
                          "each other and of the holes; shorten the name, or leave hub.engrave off")


def _fold_warnings(cut_off: FlatEnvelope) -> list[str]:
    """Where a flat face's folds were cut off: where the law's face leaves the cam and how far the motion departs."""
    if not cut_off.leaves:
        return [f"undercut allowed: the profile's fold is too small to cut off (it strays {cut_off.uncut:.3g} mm at "
                "most); the follower follows the motion law"]
    unit = cut_off.cam.follower.lift_unit
    unit = "degrees" if unit == "deg" else unit
    return [f"undercut allowed: from {f.start_deg:.2f} to {f.end_deg:.2f} degrees the face leaves the law's profile "
            f"(its fold is cut off) and rides on the cam's corner at ({f.corner_mm[0]:.4g}, {f.corner_mm[1]:.4g}) mm, "
            f"the law's face standing up to {f.gap_mm:.4g} mm off the cam (at {f.gap_at_deg:.2f} degrees): there the "
            f"follower's motion falls short of the law by up to {f.deviation:.4g} {unit}" for f in cut_off.leaves]


def _warnings(bore: float, a: CamAnalysis, jumps: tuple[Jump, ...], wall: float | None,
              segments: tuple, cut_off: FlatEnvelope | None, limit: float) -> tuple[str, ...]:
    """The profile's warnings; ``bore`` is the bore's diameter, ``wall`` the wall round it (mm), None where it is
    certainly at least :data:`THIN_WALL`; ``limit`` the pressure-angle limit (degrees)."""
    out = []
    if a.pressure_angle_max_deg > limit:
        out.append(f"pressure angle peaks at {a.pressure_angle_max_deg:.2f} degrees (at "
                   f"{a.pressure_angle_max_at_deg:.2f} degrees), above the {limit:g} degree limit: enlarge the "
                   "base radius, lengthen the segment or add an offset")
    for j in jumps:
        if j.order < 3:
            out.append(f"{j.quantity} jumps at {j.at_deg:.4g} degrees: {j.consequence}")
    if a.undercut and cut_off is not None:
        out.extend(_fold_warnings(cut_off))
    elif a.undercut:
        out.append(f"undercut allowed: the outline is the cutter's envelope, and near {a.pitch_rho_min_at_deg:.2f} "
                   "degrees the follower does not follow the motion law")
    if bore > 0 and wall is not None and wall < THIN_WALL:
        out.append(f"only {wall:.3g} mm of material between the bore and the outline")
    for i, seg in enumerate(segments):
        over = seg.law.overshoot() if hasattr(seg.law, "overshoot") else 0.0
        if over > 1e-9:
            out.append(f"motion[{i}]: the spline through the points overshoots by {100 * over:.3g} % of the lift "
                       "between them; add points where it bulges")
    if a.profile_concave_rho_min_mm is not None and a.profile_concave_rho_min_mm < 1.0:
        out.append(f"concave radius of {a.profile_concave_rho_min_mm:.3g} mm at {a.concave_at_deg:.2f} degrees: "
                   "the cutting tool or laser kerf must be smaller")
    return tuple(out)

