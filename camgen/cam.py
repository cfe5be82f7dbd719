"""A disc cam built from a validated template: kinematics and exact geometry, no I/O."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camgen.errors import SpecError
from camgen.followers.base import PitchGeometry
from camgen.followers.translating_roller import TranslatingRoller
from camgen.laws import make_law
from camgen.program import Program, build_program
from camgen.spec import CamTemplate


@dataclass(frozen=True)
class Cam:
    """A disc cam driving a translating roller follower.

    Lengths in mm, angles in radians. theta = 0 puts the follower on +Y; the cam
    turns counter-clockwise for ``follower.sense`` = +1 (see
    :mod:`camgen.followers.base` for the frame and sign conventions).
    """

    name: str
    program: Program
    follower: TranslatingRoller
    base_radius: float
    thickness: float
    bore: float

    @property
    def roller_radius(self) -> float:
        return self.follower.roller_radius

    def pitch(self, theta: np.ndarray) -> PitchGeometry:
        """Pitch geometry at any cam angles (radians); a segment boundary takes the later segment."""
        theta = np.asarray(theta, dtype=float)
        return self.follower.pitch(theta, self.program.evaluate(theta))

    def segment_pitch(self, index: int, theta: np.ndarray) -> PitchGeometry:
        """Pitch geometry on segment ``index`` only, including its end (one-sided limits at both ends)."""
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        return self.follower.pitch(theta, self.program.segments[index].evaluate(theta))

    def corners(self) -> list[tuple[int, float]]:
        """Corners of the pitch curve at segment ends, where the follower velocity jumps.

        Returns ``(segment index, turn)`` for the end of each segment whose pitch
        tangent turns there by ``turn`` radians, positive for a convex corner (the
        roller cannot follow it: the cam would need a zero radius) and negative for a
        concave one (the roller rolls round it on an arc of its own radius).
        """
        out = []
        segments = self.program.segments
        for i, seg in enumerate(segments):
            j = (i + 1) % len(segments)
            left = self.segment_pitch(i, seg.end).d1[0]
            right = self.segment_pitch(j, segments[j].start).d1[0]
            turn = math.atan2(left[0] * right[1] - left[1] * right[0], float(left @ right))
            if abs(turn) > 1e-9:
                out.append((i, -self.follower.sense * turn))
        return out


def build_cam(template: CamTemplate, roller_radius: float | None = None) -> Cam:
    """The :class:`Cam` a template describes (``roller_radius`` overrides the template's, in mm)."""
    rr = template.follower.roller_radius if roller_radius is None else roller_radius
    prime = template.cam.base_radius + rr
    steps = []
    for i, seg in enumerate(template.motion):
        law = None
        if seg.type != "dwell":
            params = seg.law_params()
            if seg.law == "modified-uniform" and params.get("form") == "drafted":
                params["k"] = prime * math.radians(seg.angle) / seg.lift
            try:
                law = make_law(seg.law, **params)
            except SpecError as exc:
                raise exc.under(f"motion[{i}]") from None
        steps.append((seg.type, seg.angle, seg.lift or 0.0, law))
    sense = 1 if template.cam.rotation == "ccw" else -1
    return Cam(name=template.name, program=build_program(steps),
               follower=TranslatingRoller(prime, rr, template.follower.offset, sense),
               base_radius=template.cam.base_radius, thickness=template.cam.thickness, bore=template.cam.bore)
