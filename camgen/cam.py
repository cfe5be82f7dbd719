"""A cam: its motion program and its follower at one size, with the exact pitch geometry at any angle. No I/O.

Built from a :class:`~camgen.rig.Rig` (the set-up without its size) at a base radius; nothing here reads a spec.
"""
from __future__ import annotations

from collections.abc import Callable, Generator, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from camgen.followers.base import PitchGeometry
from camgen.followers.plate import PlateRoller
from camgen.numeric import drive
from camgen.program import Jump, Program

#: a request for pitch geometry: (the segment of every point, an index or an array (n,); the points (n,); False when
#: they are cam angles in radians, evaluated one-sided on their segment as :meth:`Program.evaluate_on` does, True when
#: they are the law's own variable, see :meth:`Segment.at_law`)
Ask = tuple[int | np.ndarray, np.ndarray, bool]
#: what :meth:`Cam.serve` drives: a generator that yields a list of asks, is sent their pitch geometry (a list, one
#: for each ask) and returns its result
Maker = Generator[list[Ask], list[PitchGeometry], Any]


@dataclass(frozen=True)
class Boundaries:
    """A cam's segment boundaries, evaluated once: the program's motion (s and its first three derivatives, (4, 2n))
    at :attr:`Program.boundary_points` (every segment's end, its left-hand limit, then the next one's start) and the
    pitch geometry there, split into the ends (n) and the starts (n)."""

    motion: np.ndarray
    ends: PitchGeometry
    starts: PitchGeometry


class _Evaluated:
    """Where a cam keeps its :class:`Boundaries` once made, by their own evaluation or by the first round of
    :meth:`Cam.serve` (which evaluates them with its asks, in the same call): set once, read after."""

    __slots__ = ("boundaries",)

    def __init__(self) -> None:
        self.boundaries: Boundaries | None = None


@dataclass(frozen=True)
class Cam:
    """A disc cam driving a follower (any of :mod:`camgen.followers`), or a plate cam under its roller.

    Lengths in mm, angles in radians. theta = 0 puts the follower on +Y; the cam
    turns counter-clockwise for ``follower.sense`` = +1 (see
    :mod:`camgen.followers.base` for the frame and sign conventions). Made by :meth:`camgen.rig.Rig.cam`.

    Parameters
    ----------
    name : str
        The part's name (``spec.name``).
    program : Program
        The motion program: s and its first three derivatives at any cam angle.
    follower : object
        One of :mod:`camgen.followers`' followers (:class:`~camgen.followers.translating_roller.TranslatingRoller`,
        ...), or a plate cam's :class:`~camgen.followers.plate.PlateRoller`.
    base_radius : float
        The base circle's radius (mm; a plate's height under the profile; a barrel's developed cam's height under
        the roller, None where a barrel's cam was built without one).
    """

    name: str
    program: Program
    follower: Any                  # one of camgen.followers' followers, or a plate's roller
    base_radius: float
    #: the boundaries once evaluated (see :meth:`boundaries`); a copy made by dataclasses.replace starts afresh
    _evaluated: _Evaluated = field(default_factory=_Evaluated, init=False, repr=False, compare=False)

    @property
    def contact_radius(self) -> float:
        """Distance of the cam surface from the pitch curve, inwards (mm): the roller's radius (0 for knife
        edges and flat faces)."""
        return self.follower.contact_radius

    @property
    def steady(self) -> bool:
        """True where the follower's pitch geometry depends on the motion only, not on the cam angle, so that a
        dwell's is constant (the peaks' search then asks a dwell's first point only, see
        :meth:`Program.maxima_steps`)."""
        return bool(getattr(self.follower, "steady", False))

    @property
    def is_plate(self) -> bool:
        """True for a linear (plate) cam, whose frame is the plate's (see :mod:`camgen.followers.plate`)."""
        return isinstance(self.follower, PlateRoller)

    def pitch(self, theta: np.ndarray) -> PitchGeometry:
        """Pitch geometry at any cam angles (radians); a segment boundary takes the later segment."""
        theta = np.asarray(theta, dtype=float)
        return self.follower.pitch(theta, self.program.evaluate(theta))

    def segment_pitch(self, index: int, theta: np.ndarray | float) -> PitchGeometry:
        """Pitch geometry on segment ``index`` only at cam angles ``theta`` (radians, an array or one number, taken
        as an array of one), including its end (one-sided limits at both ends)."""
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        return self.follower.pitch(theta, self.program.segments[index].evaluate(theta))

    def boundaries(self) -> Boundaries:
        """The segment boundaries' motion and pitch geometry (see :class:`Boundaries`): those :meth:`serve`'s first
        round made, else their own evaluation (made once)."""
        known = self._evaluated.boundaries
        if known is None:
            theta, index = self.program.boundary_points
            motion = self.program.evaluate_on(index, theta)
            known = self._keep(motion, self.follower.pitch(theta, motion))
        return known

    def _keep(self, motion: np.ndarray, g: PitchGeometry) -> Boundaries:
        """Keep the boundaries' ``motion`` (4, 2n) and pitch geometry ``g`` (2n) as :meth:`boundaries`."""
        n = len(self.program.segments)
        known = self._evaluated.boundaries = Boundaries(motion.copy(), _own(g, 0, n), _own(g, n, 2 * n))
        return known

    def boundary_geometry(self) -> tuple[PitchGeometry, PitchGeometry]:
        """Pitch geometry at every segment's end (its left-hand limit) and at the next one's start (n each)."""
        b = self.boundaries()
        return b.ends, b.starts

    def jumps(self) -> list[Jump]:
        """The program's jumps (see :meth:`Program.jumps`) from the boundaries' motion as :meth:`boundaries` has
        it."""
        return self.program.jumps(self.boundaries().motion)

    def serve(self, makers: Sequence[Maker]) -> list[Any]:
        """Drive every maker at once (see :func:`together`) and return their results in order: each round evaluates
        what all of them ask in one call of the program and one of the follower (see :meth:`pitch_of`), whose cost
        is mostly per call, not per point. The first round also evaluates the segment boundaries unless they are
        known (:meth:`corners`, :meth:`steps` and the program's jumps need them), so that a maker that looks at them
        after its first ask finds them made."""
        fresh = [self._evaluated.boundaries is None]

        def answer(asks: list[Ask]) -> list[PitchGeometry]:
            out = self.pitch_of(asks, boundaries=fresh[0])
            fresh[0] = False
            return out

        return drive(together(makers), answer)

    def pitch_of(self, asks: Sequence[Ask], boundaries: bool = False) -> list[PitchGeometry]:
        """Pitch geometry at the points of every ask (see :data:`Ask`), each on its own segment (one-sided limits
        at its ends), all from one evaluation; with ``boundaries`` the segment boundaries' too (kept for
        :meth:`corners` and :meth:`Program.jumps`, the same numbers as their own evaluation). The asks in the law's
        variable are evaluated first, then those in cam angles (each point's numbers are its own either way). Asks
        of the very same arrays (the peaks' search grid, which the outline shares: see :meth:`Program.search_grid`)
        are evaluated once, each given the same geometry."""
        program = self.program
        first: list[int] = []                           # the law's variable before, cam angles after
        later: list[int] = []
        same: dict[tuple[int, int, bool], int] = {}     # the identities of each ask's arrays: its first ask
        twin: list[tuple[int, int]] = []                # (an ask, the earlier ask of the same arrays)
        for k, a in enumerate(asks):
            key = (id(a[0]), id(a[1]), a[2])
            if isinstance(a[0], np.ndarray) and key in same:
                twin.append((k, same[key]))
                continue
            same[key] = k
            (first if a[2] else later).append(k)
        order = first + later
        index = [a[0] if isinstance(a[0], np.ndarray) else np.full(a[1].size, a[0]) for a in (asks[k] for k in order)]
        x = [asks[k][1] for k in order]
        if boundaries:
            theta, ends = program.boundary_points
            index.append(ends)
            x.append(theta)
        cut = sum(asks[k][1].size for k in first)
        theta, motion = program._table.on(np.concatenate(index), np.concatenate(x), cut)
        g = self.follower.pitch(theta, motion)
        out: list[Any] = [None] * len(asks)
        at = 0
        for k, part in zip(order, x, strict=False):
            out[k] = g.part(at, at + part.size)
            at += part.size
        for k, earlier in twin:
            out[k] = out[earlier]
        if boundaries:
            self._keep(motion[:, at:], g.part(at, at + 2 * len(program.segments)))
        return out

    def corners(self) -> list[tuple[int, float]]:
        """Corners of the pitch curve at segment ends, where the follower velocity jumps.

        Returns ``(segment index, turn)`` for the end of each segment whose pitch
        tangent turns there by ``turn`` radians, positive for a convex corner (the
        roller cannot follow it: the cam would need a zero radius) and negative for a
        concave one (the roller rolls round it on an arc of its own radius).
        """
        return list(self._corners)

    @cached_property
    def _corners(self) -> tuple[tuple[int, float], ...]:
        """:meth:`corners`, found once a cam (a design asks several times): the turn from each segment's end tangent
        to the next one's start tangent, atan2 of their cross and dot products, where it exceeds 1e-9 radians."""
        ends, starts = self.boundary_geometry()
        return corner_turns(ends.d1, starts.d1, self.follower.sense)

    def steps(self) -> list[tuple[int, float]]:
        """Where a flat face's contact point jumps at a segment end (a velocity jump): ``(segment index, step)``.

        ``step`` (mm) is signed along the way the profile runs: positive where the profile has a straight
        flat there (the velocity rises; the face lies along it), negative where it folds back into a cusp
        (the velocity drops; no face can follow it). Roller and knife-edge pitch curves never jump.
        """
        if not self.follower.flat:
            return []
        out = []
        ends, starts = self.boundary_geometry()
        for i in range(len(self.program.segments)):
            gap = starts.point[i] - ends.point[i]
            if np.linalg.norm(gap) <= 1e-9 * max(1.0, self.base_radius):
                continue
            side = ends if abs(ends.face_rho[i]) >= abs(starts.face_rho[i]) else starts
            ahead = side.d1[i] / side.face_rho[i]                 # the way a sound profile runs there
            out.append((i, float(gap @ ahead / np.linalg.norm(ahead))))
        return out


def _own(g: PitchGeometry, start: int, stop: int) -> PitchGeometry:
    """The samples ``start`` to ``stop`` of ``g`` in arrays of their own (copies, not views of ``g``'s)."""
    part = g.part(start, stop)
    return PitchGeometry(part.theta.copy(), part.point.copy(), part.d1.copy(), part.d2.copy(), part.normal.copy(),
                         part.kappa.copy(), part.pressure_angle.copy(), None if part.rho is None else part.rho.copy())


def corner_turns(left: np.ndarray, right: np.ndarray, sense: int) -> tuple[tuple[int, float], ...]:
    """:meth:`Cam.corners` from the pitch tangents at every segment's end ``left`` (n, 2) and at the next one's start
    ``right`` (n, 2): the turn from one to the other (radians, atan2 of their cross and dot products, positive for a
    convex corner of a cam turning with ``sense``) where it exceeds 1e-9 radians."""
    cross = left[:, 0] * right[:, 1] - left[:, 1] * right[:, 0]
    turn = np.arctan2(cross, (left * right).sum(axis=1))
    at = (np.abs(turn) > 1e-9).nonzero()[0]
    return tuple(zip(at.tolist(), (-sense * turn[at]).tolist(), strict=True))


def together(makers: Sequence[Maker], first: Callable[[], None] | None = None) -> Maker:
    """The ``makers`` as one: each round it asks what all of them ask (one list) and sends each its own answers;
    it returns their results in order. ``first``, if given, is called when the first answers come, before any
    maker sees them (:meth:`Cam.serve` has made the segment boundaries by then)."""
    results: list[Any] = [None] * len(makers)
    live = []                                           # (place, maker, its asks) of each maker still asking
    for k, maker in enumerate(makers):
        try:
            live.append((k, maker, next(maker)))
        except StopIteration as done:                   # done before asking anything (a tentative maker's error)
            results[k] = done.value
    while live:
        answers = yield [a for _, _, asks in live for a in asks]
        if first is not None:
            first()
            first = None
        asking, at = [], 0
        for k, maker, asks in live:
            count = len(asks)
            try:
                asking.append((k, maker, maker.send(answers[at:at + count])))
            except StopIteration as done:
                results[k] = done.value
            at += count
        live = asking
    return results
