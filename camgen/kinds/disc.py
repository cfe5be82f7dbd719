"""The disc cam: a plate turning about its centre, cut to a profile; every follower type drives it."""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from camgen.kinds.base import Starter
from camgen.kinds.shared import FlatKind
from camgen.kinds.starting import FLAT_AUTO, OUTPUT, ROLLER, SPRUNG, SWING, cam_table, motion
from camgen.rig import Mount, disc_mount

if TYPE_CHECKING:
    from camgen.spec import DiscSpec
    from camgen.core.bundle import Item
    from camgen.flat import FlatCamDesign


def _check(spec: Any) -> None:
    """Nothing beyond its tables: a disc cam's follower tables are the spring-held ones
    (:mod:`camgen.tables.followers`)."""


#: a disc cam's starters, one a follower type
STARTERS = {
    "translating-roller": Starter(
        "A disc cam driving a translating roller follower, held on by a spring.",
        (cam_table("disc"), ("follower", {"type": "translating-roller", "roller_radius": 10.0, "offset": 0.0,
                                          **SPRUNG}), *motion(), ("hub", {"keyway": True}), OUTPUT),
        {"cam": "a disc cam under a translating roller: its pressure angle is held to 30 degrees (max_pressure_angle "
                "sets another limit)",
         **ROLLER,
         "follower.offset": "mm: the axis's offset, + to the right (+X); |offset| < base_radius + roller_radius; on "
                            "a ccw cam + lowers the rise's pressure angle and raises the return's"}),
    "knife-edge": Starter(
        "A disc cam driving a knife-edge follower (a point: the profile is the pitch curve).",
        (cam_table("disc"), ("follower", {"type": "knife-edge", "offset": 0.0, **SPRUNG}), *motion(), OUTPUT),
        {"cam": "a disc cam under a point: the profile is the pitch curve itself (prime radius = base_radius)",
         "follower.offset": "mm: the axis's offset, + to the right (+X); |offset| < base_radius"}),
    "translating-flat": Starter(
        "A disc cam driving a translating flat-faced follower; its base radius sized by camgen.",
        (cam_table("disc", base_radius="auto", min_rho_margin=5.0),
         ("follower", {"type": "translating-flat", "face_margin": 3.0, **SPRUNG}), *motion(), OUTPUT),
        {"follower": "a flat face square to its motion: pressure angle 0; it touches the cam s' mm from its axis",
         **FLAT_AUTO,
         "follower.face_margin": "mm: face beyond the contact's travel (from least to most s'), each side"}),
    "oscillating-roller": Starter(
        "A disc cam swinging an arm with a roller; the lifts are the arm's swing in degrees.",
        (cam_table("disc"), ("follower", {"type": "oscillating-roller", "roller_radius": 8.0,
                                          "pivot_distance": 110.0, "arm_length": 90.0, **SPRUNG}),
         *motion(20.0), OUTPUT),
        {"follower": "the arm puts the roller on the prime circle: |pivot_distance - arm_length| < base_radius + "
                     "roller_radius < pivot_distance + arm_length; the pressure-angle limit is 40 degrees",
         **ROLLER, **SWING,
         "follower.pivot_distance": "mm: cam centre to the arm's pivot (to the right of the roller at rest)",
         "follower.arm_length": "mm: pivot to the roller's centre"}),
    "oscillating-flat": Starter(
        "A disc cam swinging a flat-faced arm; the lifts are the arm's swing in degrees.",
        (cam_table("disc", base_radius="auto", min_rho_margin=5.0),
         ("follower", {"type": "oscillating-flat", "pivot_distance": 120.0, "face_margin": 3.0}),
         *motion(15.0), OUTPUT),
        {"follower": "a flat face through the pivot, touching the base circle at rest: pivot_distance > "
                     "base_radius / cos(the largest swing), so that the face touches the cam between the pivot and "
                     "the rest contact; the pressure-angle limit is 40 degrees",
         **FLAT_AUTO, **SWING,
         "cam.base_radius": "\"auto\": the smallest whose profile radius stays above min_rho_margin and that meets "
                            "the pressure-angle limit; below pivot_distance * cos(the largest swing)",
         "follower.pivot_distance": "mm: cam centre to the pivot the face turns about; > base_radius / cos(the "
                                    "largest swing)",
         "follower.face_margin": "mm: face beyond the contact's travel along it, each side"}),
}


class DiscKind(FlatKind["DiscSpec"]):
    """A disc cam (``cam.kind = "disc"``, the default); the one kind with a graphical construction."""

    name: str = "disc"
    title: str = "a disc cam"
    check: Callable[[DiscSpec], None] = staticmethod(_check)
    starters: Mapping[str, Starter] = STARTERS

    @property
    def spec(self) -> type[DiscSpec]:
        from camgen.spec import DiscSpec

        return DiscSpec

    def mount(self, spec: DiscSpec) -> Mount:
        return disc_mount(spec.follower, spec.cam.rotation)

    def construction(self, design: FlatCamDesign) -> tuple[Item, ...]:
        from camgen.construction.figure import construction_files

        return construction_files(design)


KIND = DiscKind()
