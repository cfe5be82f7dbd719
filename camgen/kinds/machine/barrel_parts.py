"""A barrel cam mounted on a machine's shaft (:mod:`camgen.kinds.barrel`): its drum and its follower as clash bodies,
and why its follower drives no planar linkage.

A machine's frame lies across its shafts, and its parts move in planes across them. A barrel's follower moves along
its shaft (a translating roller, ``mm`` along the axis) or swings about an axis across it (an oscillating roller,
degrees): out of the frame's plane either way. So its motion is an output of the machine (its timing, its report),
but a coupling from it to a planar linkage is refused in one line.

The drum is rotationally symmetric about its shaft: in the frame's plane it is a disc of its rim's radius (the
groove's or rib's outermost, ``BarrelDesign.radii[2]``) about the shaft, with its bore, on its layer's plane, as
high as the drum is long (``cam.length``).

The follower (``cams.<cam>.follower``) is a conservative body: its plan outline over the whole turn, still, on the
drum's plane, which stands as high as the drum and so holds the heights the follower sweeps (its roller runs in the
groove, within the drum's length; an arm's pivot stands at mid-length). In the barrel kind's fixed frame (the
machine's, moved to the shaft) the roller stands on +X, its axle radial: its plan is the rectangle from the floor's
radius out past the rim by :data:`CARRIER_MM` (its axle's carrier), as wide as the roller, across every tangential
offset its centre takes (0 for a translating roller; y = C - L cos(psi) for an arm of length L pivoted C from the
axis, psi from -swing/2 to +swing/2: :class:`~camgen.followers.barrel.Arm`). An arm adds its own plan: the strip
over the carrier from the roller to the pivot (y = C), as wide as the roller. It meets the drum in a joint: a disc
round the part of it inside the rim (the roller in its groove).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from camgen.kinds.machine.clash import Body, Joint, circle, fixed, still

#: why a barrel's follower drives no planar linkage
OUT_OF_PLANE = "moves along the shaft (or swings across it), out of the frame's plane"
#: how far (mm) the follower's axle carrier reaches past the rim
CARRIER_MM = 10.0


def is_barrel(cam_design: Any) -> bool:
    """Whether a cam kind's design is a barrel cam's."""
    return getattr(getattr(cam_design, "spec", None), "kind", None) == "barrel"


def drum(name: str, cam_design: Any, plane: int, centre: np.ndarray, tolerance: float) -> Body:
    """The barrel ``cams.<name>``'s drum: a disc of its rim's radius (mm) about the shaft's ``centre`` with its bore,
    on ``plane``."""
    rim = float(max(cam_design.radii))
    bore = float(cam_design.spec.cam.bore) / 2
    return Body(f"cams.{name}", plane, plane, circle(rim, tolerance), fixed(centre), (((0.0, 0.0), bore),))


def follower(name: str, cam_design: Any, plane: int, centre: np.ndarray) -> tuple[Body, Joint]:
    """The barrel ``cams.<name>``'s follower as a still, conservative body on the drum's ``plane`` (see the module
    docstring), about the shaft's ``centre`` (mm), and its joint with the drum."""
    import shapely

    from camgen.followers.barrel import BarrelGeometry
    from camgen.kinds.machine.stem_guide import box

    spec = cam_design.spec
    g = BarrelGeometry.of(spec.cam, spec.follower, spec.motion)
    floor, _, rim = (float(r) for r in cam_design.radii)
    r, out = float(g.roller_radius), rim + CARRIER_MM
    if g.arm_length is not None and g.pivot_distance is not None:      # an arm
        psi = np.radians(np.linspace(-g.swing / 2, g.swing / 2, 721))
        pivot = float(g.pivot_distance)
        y = pivot - float(g.arm_length) * np.cos(psi)
        lo, hi = float(y.min()), float(y.max())
        arm = box(rim, min(lo, pivot) - r, out, max(hi, pivot) + r)
    else:
        lo = hi = 0.0
        arm = None
    plan = shapely.Polygon(box(floor, lo - r, out, hi + r))
    if arm is not None:
        plan = shapely.union(plan, shapely.Polygon(arm))
    ring = np.asarray(shapely.geometry.polygon.orient(plan, 1.0).exterior.coords)[:-1]
    body = Body(f"cams.{name}.follower", plane, plane, ring, fixed(centre))
    middle = centre + np.array([(floor + rim) / 2, (lo + hi) / 2])
    reach = 1.01 * float(np.hypot((rim - floor) / 2, (hi - lo) / 2 + r)) + 0.05
    return body, Joint(f"cams.{name}", body.name, still(middle), reach)


def thicknesses(design: Any) -> dict[str, float]:
    """Each barrel drum's height along its shaft (mm) by its clash body's name: its ``cam.length``."""
    return {f"cams.{c.name}": float(c.design.spec.cam.length) for c in design.cams if is_barrel(c.design)}


def check_coupling(cam_spec: Any, index: int, cam: str) -> None:
    """Refuse coupling ``couplings[index]`` from the barrel ``cams.<cam>`` to a planar linkage (a
    :class:`ValueError` naming ``couplings[i].cam``); nothing for another kind's cam."""
    if getattr(cam_spec.cam, "kind", None) == "barrel":
        raise ValueError(f"couplings[{index}].cam: cams.{cam} is a barrel cam: its follower {OUT_OF_PLANE}, so it "
                         "drives no planar linkage; couple a disc, plate, grooved or conjugate cam's follower")
