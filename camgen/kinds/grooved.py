"""The grooved face (track) cam: a disc whose face carries a groove the roller runs in, driving it both ways.

The groove's two flanks are the exact offsets of the pitch curve by +/-(Rr + c/2), Rr the
roller's radius and c ``cam.running_clearance``; the groove is a pocket ``cam.groove_depth``
mm deep in the face (see :mod:`camgen.grooved`). Positive drive holds the follower without a
spring, so rollers only, and no spring or preload; at ``cam.rpm`` with a mass the report gives the forces, the
flank that carries them and the torque (:func:`camgen.forces.drive_report`). The pitch curve
is the disc cam's (prime radius = base radius + roller radius).
"""
from __future__ import annotations

from typing import Any

from camgen.kinds import disc
from camgen.kinds.base import CamKind, flat_body

FOLLOWERS = ("translating-roller", "oscillating-roller")


def _check(spec: Any) -> None:
    flat_body(spec)
    cam, follower = spec.cam, spec.follower
    if cam.travel is not None:
        raise ValueError("cam.travel: only for a plate cam (cam.kind = \"plate\")")
    if follower.type not in FOLLOWERS:
        raise ValueError(f"follower.type: a grooved cam takes a translating-roller or oscillating-roller follower "
                         f"(got {follower.type!r})")
    if cam.groove_depth is None:
        raise ValueError("cam.groove_depth: required for a grooved cam (mm, > 0 and < cam.thickness)")
    if not cam.groove_depth < cam.thickness:
        raise ValueError(f"cam.groove_depth: must be < cam.thickness {cam.thickness:g} mm (got {cam.groove_depth:g})")
    for key in ("spring_rate", "preload", "contact_margin"):
        if getattr(follower, key) is not None:
            raise ValueError(f"follower.{key}: a grooved cam drives the follower both ways (positive drive): no "
                             "return spring and no contact check (its forces need only follower.mass)")
    if spec.hub.boss_diameter:
        raise ValueError("hub.boss_diameter: a boss would stand on the grooved face, where the follower runs; mount "
                         "a grooved cam by its bore (hub.keyway) or hub.bolt_circle holes")


KIND = CamKind("grooved", FOLLOWERS, _check, disc.KIND.follower, "camgen.grooved.design:design_grooved",
               "camgen.grooved.outputs:grooved_bundle")
