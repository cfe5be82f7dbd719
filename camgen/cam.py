"""A disc cam built from a validated spec: kinematics and exact geometry, no I/O."""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.followers import FOLLOWERS
from camgen.followers.base import PitchGeometry
from camgen.followers.plate import PlateRoller
from camgen.kinds import kind_of
from camgen.laws import make_law
from camgen.program import Program, build_program
from camgen.spec import CamSpec


@dataclass(frozen=True)
class Cam:
    """A disc cam driving a follower (any of :mod:`camgen.followers`).

    Lengths in mm, angles in radians. theta = 0 puts the follower on +Y; the cam
    turns counter-clockwise for ``follower.sense`` = +1 (see
    :mod:`camgen.followers.base` for the frame and sign conventions).
    """

    name: str
    program: Program
    follower: Any                  # one of camgen.followers' followers, or a plate's roller
    base_radius: float
    thickness: float
    bore: float

    @property
    def contact_radius(self) -> float:
        """Distance of the cam surface from the pitch curve, inwards (mm): the roller's radius (0 for knife
        edges and flat faces)."""
        return self.follower.contact_radius

    @property
    def is_plate(self) -> bool:
        """True for a linear (plate) cam, whose frame is the plate's (see :mod:`camgen.followers.plate`)."""
        return isinstance(self.follower, PlateRoller)

    def pitch(self, theta: np.ndarray) -> PitchGeometry:
        """Pitch geometry at any cam angles (radians); a segment boundary takes the later segment."""
        theta = np.asarray(theta, dtype=float)
        return self.follower.pitch(theta, self.program.evaluate(theta))

    def segment_pitch(self, index: int, theta: np.ndarray) -> PitchGeometry:
        """Pitch geometry on segment ``index`` only, including its end (one-sided limits at both ends)."""
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        return self.follower.pitch(theta, self.program.segments[index].evaluate(theta))

    @functools.cached_property
    def _boundaries(self) -> tuple[PitchGeometry, PitchGeometry]:
        """Pitch geometry at every segment's end (its left-hand limit) and at the next one's start."""
        segments = self.program.segments
        g = self.follower.pitch(*self.program.boundaries)
        n = len(segments)
        halves = [{k: None if v is None else v[part] for k, v in vars(g).items()}
                  for part in (slice(0, n), slice(n, 2 * n))]
        return PitchGeometry(**halves[0]), PitchGeometry(**halves[1])

    def corners(self) -> list[tuple[int, float]]:
        """Corners of the pitch curve at segment ends, where the follower velocity jumps.

        Returns ``(segment index, turn)`` for the end of each segment whose pitch
        tangent turns there by ``turn`` radians, positive for a convex corner (the
        roller cannot follow it: the cam would need a zero radius) and negative for a
        concave one (the roller rolls round it on an arc of its own radius).
        """
        out = []
        ends, starts = self._boundaries
        for i in range(len(self.program.segments)):
            left, right = ends.d1[i], starts.d1[i]
            turn = math.atan2(left[0] * right[1] - left[1] * right[0], float(left @ right))
            if abs(turn) > 1e-9:
                out.append((i, -self.follower.sense * turn))
        return out

    def steps(self) -> list[tuple[int, float]]:
        """Where a flat face's contact point jumps at a segment end (a velocity jump): ``(segment index, step)``.

        ``step`` (mm) is signed along the way the profile runs: positive where the profile has a straight
        flat there (the velocity rises; the face lies along it), negative where it folds back into a cusp
        (the velocity drops; no face can follow it). Roller and knife-edge pitch curves never jump.
        """
        if not self.follower.flat:
            return []
        out = []
        ends, starts = self._boundaries
        for i in range(len(self.program.segments)):
            gap = starts.point[i] - ends.point[i]
            if np.linalg.norm(gap) <= 1e-9 * max(1.0, self.base_radius):
                continue
            side = ends if abs(ends.rho[i]) >= abs(starts.rho[i]) else starts
            ahead = side.d1[i] / side.rho[i]                 # the way a sound profile runs there
            out.append((i, float(gap @ ahead / np.linalg.norm(ahead))))
        return out


def _drafted_ratio(spec: CamSpec, angle: float, lift: float, prime: float, index: int) -> float:
    """k = Rp beta / h of the drafted modified-uniform law; h is the rise along the follower's path (mm)."""
    path_length = FOLLOWERS[spec.follower.type].path_length
    if path_length is None:
        raise SpecError("the drafted form needs a roller, knife-edge or translating follower", f"motion[{index}].form")
    return prime * math.radians(angle) / path_length(spec.follower, lift)


def build_cam(spec: CamSpec, roller_radius: float | None = None, base_radius: float | None = None) -> Cam:
    """The :class:`Cam` a spec describes; ``roller_radius``, ``base_radius`` (mm) override the spec's."""
    rr = spec.follower.contact_radius if roller_radius is None else roller_radius
    rb = spec.cam.base_radius if base_radius is None else base_radius
    prime = rb + rr if rb is not None else spec.cam.pitch_radius     # a barrel's: its pitch cylinder
    steps = []
    for i, seg in enumerate(spec.motion):
        law = None
        if seg.type != "dwell":
            params = seg.law_params()
            if seg.law == "modified-uniform" and params.get("form") == "drafted":
                params["k"] = _drafted_ratio(spec, seg.angle, seg.lift, prime, i)
            if seg.law == "table":                      # its rows are in degrees and the lift's unit
                params.update(beta_deg=seg.angle, lift=seg.lift, falling=seg.type == "return")
            try:
                law = make_law(seg.law, **params)
            except SpecError as exc:
                raise exc.under(f"motion[{i}]") from None
        steps.append((seg.type, seg.angle, seg.lift or 0.0, law))
    return Cam(name=spec.name, program=build_program(steps), follower=kind_of(spec.cam.kind).follower(spec, rb, rr),
               base_radius=rb, thickness=spec.cam.thickness, bore=spec.cam.bore)
