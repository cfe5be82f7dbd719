"""A cam's set-up without its size: its motion and how it carries its follower, from which a :class:`Cam` of any
base radius (and roller) is built. No spec: the kinds make these from their templates' tables.

A :class:`Mount` says how the follower sits on the cam: a disc cam's follower of any type (:func:`disc_mount`),
a plate cam's roller or knife edge over the sliding plate (:func:`plate_mount`), or a barrel's roller on its pitch
cylinder developed flat (:func:`developed_mount`). A :class:`Rig` is a name, a motion (the template's segments)
and a mount; ``rig.cam(base_radius)`` is today's cam at that size, the unit the sizing searches over
(:mod:`camgen.sizing`) and the profile is cut from (:mod:`camgen.profile`).
"""
from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from camgen.cam import Cam
from camgen.core.errors import SpecError
from camgen.followers import FOLLOWERS
from camgen.followers.base import FollowerType
from camgen.followers.plate import PlateRoller
from camgen.laws import Law, make_law
from camgen.program import Program, build_program

if TYPE_CHECKING:
    from camgen.followers.barrel import BarrelGeometry


@dataclass(frozen=True)
class Mount:
    """How a disc cam carries its follower: the ``[follower]`` table (any object with its attributes, see
    :mod:`camgen.tables.followers`) and the cam's ``sense`` of rotation (+1 counter-clockwise seen from +Z, -1
    clockwise; see :mod:`camgen.followers.base` for the frames)."""

    table: Any
    sense: int

    @property
    def follower(self) -> FollowerType:
        """The follower's type (:data:`camgen.followers.FOLLOWERS`): its assembly ranges and path length."""
        return FOLLOWERS[self.table.type]

    @property
    def roller_radius(self) -> float | None:
        """The table's roller radius (mm), None for a knife edge or a flat face."""
        return self.table.roller_radius

    @property
    def oscillating(self) -> bool:
        """True for an arm's swing (lifts in degrees)."""
        return self.follower.oscillating

    def at(self, base_radius: float, roller_radius: float) -> Any:
        """The follower on a cam of ``base_radius`` with a roller of ``roller_radius`` (mm)."""
        return self.follower.make(self.table, base_radius, roller_radius, self.sense)

    def prime_radius(self, base_radius: float, roller_radius: float) -> float:
        """The radius (mm) the drafted modified-uniform law's arcs are drawn on: the prime circle's, base + roller."""
        return base_radius + roller_radius

    def base_range(self, roller_radius: float, top: float) -> tuple[float, float]:
        """The (lowest, highest) base radius (mm, exclusive) on which the follower assembles with that roller and
        follows a program rising to ``top`` (mm, or degrees of swing)."""
        return self.follower.base_radius_range(self.table, roller_radius, top)

    def check_fits(self, base_radius: float, program: Program) -> None:
        """Refused (:class:`SpecError` naming the field) where the follower cannot follow ``program``'s largest
        displacement, a law's overshoot included, on a base circle of ``base_radius`` mm (an oscillating flat face
        whose contact would pass its pivot); nothing to check for a follower that follows whatever it assembles
        for."""
        fits = self.follower.fits
        if fits is not None:
            fits(self.table, base_radius, program.top())

    def roller_floor(self, base_radius: float) -> float:
        """The least roller radius (mm) that assembles on that base circle."""
        return self.follower.roller_floor(self.table, base_radius)

    def path_length(self, lift: float, index: int) -> float:
        """The roller's travel (mm) for a ``lift`` of segment ``index`` (mm, or degrees of swing), which the drafted
        modified-uniform law needs; refused naming ``motion[index].form`` for a follower that has none."""
        length = self.follower.path_length
        if length is None:
            raise SpecError("the drafted form needs a roller, knife-edge or translating follower",
                            f"motion[{index}].form")
        return length(self.table, lift)


@dataclass(frozen=True)
class PlateMount(Mount):
    """A plate (linear) cam's roller or knife edge: the program's 360 degrees spread over ``travel`` mm of plate,
    the base radius the plate's height under the profile (see :mod:`camgen.followers.plate`)."""

    travel: float

    def at(self, base_radius: float, roller_radius: float) -> PlateRoller:
        return PlateRoller(base_radius, roller_radius, self.travel)


@dataclass(frozen=True)
class DevelopedMount(Mount):
    """A barrel's roller on its pitch cylinder developed flat (:class:`~camgen.followers.barrel.BarrelGeometry`): a
    translating roller's centre runs as over a plate of travel 2 pi Rm, whose base radius is the height under it
    (the roller's rest height less its radius); an arm's roller where its axis pierces the pitch cylinder (its base
    radius is not used). The drafted law's arcs are drawn on the pitch cylinder's radius Rm."""

    geometry: BarrelGeometry

    def at(self, base_radius: float, roller_radius: float) -> Any:
        return self.geometry.developed(base_radius, roller_radius)

    def prime_radius(self, base_radius: float, roller_radius: float) -> float:
        return self.geometry.pitch_radius


def disc_mount(table: Any, rotation: str) -> Mount:
    """A disc cam's follower: the ``[follower]`` table on a cam turning ``rotation`` ("ccw" or "cw")."""
    return Mount(table, 1 if rotation == "ccw" else -1)


def plate_mount(table: Any, travel: float) -> PlateMount:
    """A plate cam's follower: the ``[follower]`` table over ``travel`` mm of plate."""
    return PlateMount(table, 1, travel)


def developed_mount(table: Any, geometry: BarrelGeometry) -> DevelopedMount:
    """A barrel cam's follower (the ``[follower]`` table) on its developed pitch cylinder ``geometry``."""
    return DevelopedMount(table, geometry.sense, geometry)


@dataclass(frozen=True)
class Rig:
    """A cam without its size: its ``name``, its ``motion`` (the template's segments, see
    :class:`camgen.spec.SegmentTable`), its ``mount`` and the ``roller_radius`` (mm) its cams get unless told
    otherwise (the table's; a grooved cam's island has its own, :meth:`with_roller`)."""

    name: str
    motion: tuple[Any, ...]
    mount: Mount
    roller_radius: float

    @classmethod
    def of(cls, name: str, motion: Sequence[Any], mount: Mount) -> Rig:
        """The rig of a template's ``name``, ``motion`` and ``mount``, with the table's roller (0 for none)."""
        return cls(name, tuple(motion), mount, mount.roller_radius or 0.0)

    def with_roller(self, roller_radius: float) -> Rig:
        """The same rig with a roller of ``roller_radius`` mm."""
        return dataclasses.replace(self, roller_radius=roller_radius)

    def cam(self, base_radius: float, roller_radius: float | None = None) -> Cam:
        """The :class:`Cam` on a base circle of ``base_radius`` mm (a plate's height) with a roller of
        ``roller_radius`` mm (the rig's by default)."""
        rr = self.roller_radius if roller_radius is None else roller_radius
        program = self.program(self.mount.prime_radius(base_radius, rr))
        self.mount.check_fits(base_radius, program)
        return Cam(name=self.name, program=program, follower=self.mount.at(base_radius, rr), base_radius=base_radius)

    def program(self, prime_radius: float | None) -> Program:
        """The motion program, its laws made from the segments; ``prime_radius`` (mm) is the drafted
        modified-uniform law's (its arcs' radius depends on it; None where there is none to give, refused then for
        a drafted law)."""
        steps: list[tuple[Any, float, float, Law | None]] = []
        made: dict[Any, Law] = {}                       # the laws made here, by name and parameters
        for i, seg in enumerate(self.motion):
            law = None
            if seg.type != "dwell":
                params = seg.law_params()
                key = _law_key(seg.law, params) if seg.law not in _OWN_LAWS else None
                if key is not None and key in made:     # the same law as an earlier segment's: one object
                    steps.append((seg.type, seg.angle, seg.lift or 0.0, made[key]))
                    continue
                if seg.law == "modified-uniform" and params.get("form") == "drafted":
                    if prime_radius is None:
                        raise SpecError("the drafted form needs the cam's prime radius (a base radius, or a barrel's "
                                        "pitch radius through its rig)", f"motion[{i}].form")
                    params["k"] = prime_radius * math.radians(seg.angle) / self.mount.path_length(seg.lift, i)
                if seg.law == "table":                      # its rows are in degrees and the lift's unit
                    params.update(beta_deg=seg.angle, lift=seg.lift, falling=seg.type == "return")
                try:
                    law = make_law(seg.law, **params)
                except SpecError as exc:
                    raise exc.under(f"motion[{i}]") from None
                if key is not None:
                    made[key] = law
            steps.append((seg.type, seg.angle, seg.lift or 0.0, law))
        return build_program(steps)

    def moving_segment(self, end_of: int) -> int:
        """The segment to name for a jump of the follower's velocity where segment ``end_of`` ends: that segment,
        or the next one when it is a dwell (the jump is the moving segment's start)."""
        return (end_of + 1) % len(self.motion) if self.motion[end_of].type == "dwell" else end_of

    @property
    def level_top(self) -> float:
        """The program's highest level at a segment's end (mm, or degrees of swing), 0 at least: the top it rises
        to before any law's overshoot."""
        steps = (seg.lift if seg.type == "rise" else -seg.lift if seg.type == "return" else 0.0 for seg in self.motion)
        return max(0.0, *itertools.accumulate(steps))

    @property
    def lift_max(self) -> float:
        """The largest single segment's lift (mm, or degrees of swing): where sizing starts its search."""
        return max(seg.lift or 0.0 for seg in self.motion)


#: the laws whose making depends on the segment (a drafted modified-uniform's prime radius, a table's angle and
#: lift): made for each segment
_OWN_LAWS = frozenset({"modified-uniform", "table"})


def _law_key(name: str | None, params: dict[str, Any]) -> Any:
    """What identifies the law ``name`` made with ``params`` among a program's (the name and the parameters' items),
    or None where a parameter cannot be compared so (a list of a polynomial's conditions or a spline's points:
    such a law is made for its segment)."""
    key = (name, tuple(sorted(params.items())))
    try:
        hash(key)
    except TypeError:
        return None
    return key
