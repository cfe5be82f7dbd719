"""A disc cam built from a validated template: kinematics and exact geometry, no I/O."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camgen.core.errors import SpecError
from camgen.followers.base import PitchGeometry
from camgen.followers.oscillating import OscillatingFlat, OscillatingRoller
from camgen.followers.plate import PlateRoller
from camgen.followers.translating import TranslatingFlat, TranslatingRoller
from camgen.laws import make_law
from camgen.program import Program, build_program
from camgen.spec import CamTemplate


@dataclass(frozen=True)
class Cam:
    """A disc cam driving a follower (any of :mod:`camgen.followers`).

    Lengths in mm, angles in radians. theta = 0 puts the follower on +Y; the cam
    turns counter-clockwise for ``follower.sense`` = +1 (see
    :mod:`camgen.followers.base` for the frame and sign conventions).
    """

    name: str
    program: Program
    follower: Follower
    base_radius: float
    thickness: float
    bore: float
    #: how far outside the true cam surface the surface to export lies (mm): half the laser's kerf
    surface_offset: float = 0.0

    @property
    def contact_radius(self) -> float:
        """Distance of the exported surface from the pitch curve, inwards (mm).

        The roller's radius (0 for knife edges and flat faces) less ``surface_offset``.
        """
        return self.follower.contact_radius - self.surface_offset

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


Follower = TranslatingRoller | TranslatingFlat | OscillatingRoller | OscillatingFlat | PlateRoller


def make_follower(template: CamTemplate, base_radius: float, roller_radius: float) -> Follower:
    """The follower a template describes on a cam of ``base_radius`` with a roller of ``roller_radius`` (mm)."""
    f = template.follower
    sense = 1 if template.cam.rotation == "ccw" else -1
    prime = base_radius + roller_radius
    if template.cam.kind == "plate":
        return PlateRoller(base_radius, roller_radius, template.cam.travel)
    if f.type in ("translating-roller", "knife-edge"):
        return TranslatingRoller(prime, roller_radius, f.offset, sense)
    if f.type == "translating-flat":
        return TranslatingFlat(base_radius, sense)
    if f.type == "oscillating-roller":
        return OscillatingRoller(f.pivot_distance, f.arm_length, prime, roller_radius, sense)
    return OscillatingFlat(f.pivot_distance, base_radius, sense)


def _drafted_ratio(template: CamTemplate, angle: float, lift: float, prime: float, index: int) -> float:
    """k = Rp beta / h of the drafted modified-uniform law; h is the rise along the follower's path (mm)."""
    f = template.follower
    if f.type == "oscillating-flat":
        raise SpecError("the drafted form needs a roller, knife-edge or translating follower", f"motion[{index}].form")
    travel = f.arm_length * math.radians(lift) if f.type == "oscillating-roller" else lift
    return prime * math.radians(angle) / travel


def build_cam(template: CamTemplate, roller_radius: float | None = None, base_radius: float | None = None) -> Cam:
    """The :class:`Cam` a template describes; ``roller_radius``, ``base_radius`` (mm) override the template's."""
    rr = template.follower.contact_radius if roller_radius is None else roller_radius
    rb = template.cam.base_radius if base_radius is None else base_radius
    prime = rb + rr
    steps = []
    for i, seg in enumerate(template.motion):
        law = None
        if seg.type != "dwell":
            params = seg.law_params()
            if seg.law == "modified-uniform" and params.get("form") == "drafted":
                params["k"] = _drafted_ratio(template, seg.angle, seg.lift, prime, i)
            try:
                law = make_law(seg.law, **params)
            except SpecError as exc:
                raise exc.under(f"motion[{i}]") from None
        steps.append((seg.type, seg.angle, seg.lift or 0.0, law))
    return Cam(name=template.name, program=build_program(steps), follower=make_follower(template, rb, rr),
               base_radius=rb, thickness=template.cam.thickness, bore=template.cam.bore)
