"""A translating follower's flat face and its stem's guide as clash bodies of a machine
(:func:`camgen.kinds.machine.stem_parts.stem_bodies`).

The face (``cams.<cam>.face``, a translating flat-faced follower's) is a rectangle along its line y = the
follower's contact height, from the least to the most contact position along it (the cam's ``face_extent``: sense
s', mm from the follower's axis, +X) widened by ``follower.face_margin`` each side, :data:`FACE_DEPTH_MM` deep up
the stem, moving with the lift. It rides its cam, so it fills the cam's plane and the stem's (as a roller does): a
joint with its cam at the contact point (a disc of half the stem's width), one with the stem round the stem's foot.

The guide is the still part the stem slides in: two rails (``cams.<cam>.guide.left`` and ``.right``, -X and +X of
the stem), :data:`GUIDE_WALL_MM` wide, :data:`~camgen.core.hardware.RUNNING_PLAY` clear of the stem's sides, on the
stem's plane. They run from :data:`GUIDE_GAP_MM` over the follower's foot (its roller's top, its face's top, a
knife's edge) at the top of the stroke up to the stem's top at the bottom of the stroke: the length of the stem that
stays in them over the whole turn (:func:`guide_span`), so that the stem never leaves its guide and its foot never
meets it. Each rail stands on the frame (plane 0 up to the stem's plane, a printed block) and is held to the bottom
plate by its brackets: a square lug on its outer side at each end (one in its middle where the rail is shorter than
two), :data:`LUG_MM` square, with the clearance hole of an :data:`SCREW_MM` screw in its middle. The clash check
makes each screw a pin of the frame (:func:`guide_screws`), so that the frame's plate has its hole and the kit buys
it (a bolt with its washer and nut, as a pivot pin's).
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from camgen.core.hardware import BOLTS, RUNNING_PLAY
from camgen.kinds.machine.clash import Body, Joint, fixed
from camgen.kinds.machine.slabs import Slab

#: (mm) a flat face's depth up the stem; a guide rail's width; the guide's gap over the foot at the top of the stroke
FACE_DEPTH_MM, GUIDE_WALL_MM, GUIDE_GAP_MM = 3.0, 3.0, 1.0
#: the guide's screws (mm): M3 bolts through the rails' lugs into the bottom plate
SCREW_MM = 3.0
#: a lug's side (mm): the screw's ISO 273 clearance hole with 2 mm of wall each side
LUG_MM = BOLTS["M3"].clearance_hole + 4.0


def box(x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    """(4, 2) mm: the rectangle [x0, x1] x [y0, y1], counter-clockwise."""
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])


def guide_span(rest_y: float, lift_min: float, lift_max: float, length: float, foot: float) -> tuple[float, float]:
    """The guide's bottom and top (mm, the machine's y): :data:`GUIDE_GAP_MM` over the foot (``foot`` mm over the
    follower's point, at ``rest_y`` + lift) at the top of the stroke, up to the stem's top (``length`` mm over the
    point) at its bottom."""
    return rest_y + lift_max + foot + GUIDE_GAP_MM, rest_y + lift_min + length


def rail_slabs(cam: str, width: float, span: tuple[float, float], thickness: float = 0.0,
               tolerance: float = 0.01) -> list[tuple[str, Slab]]:
    """The two rails of cam ``cam``'s stem guide (a ``width`` mm wide stem, over ``span``: :func:`guide_span`) as
    part makers in the guide's frame (x from the stem's axis, y the machine's): ``("left", slab)``, ``("right",
    slab)``, named ``<cam>-guide-left|right``, each the rail with its lugs and their screws' holes."""
    inner = width / 2 + RUNNING_PLAY
    y0, y1 = span
    a = LUG_MM
    ends = (y0, y1 - a) if y1 - y0 >= 2 * a else ((y0 + y1 - a) / 2,)
    out = []
    for side, k in (("left", -1.0), ("right", 1.0)):
        near, far = k * inner, k * (inner + GUIDE_WALL_MM)
        rail = (min(near, far), y0, max(near, far), y1)
        lugs = tuple((min(far, far + k * a), e, max(far, far + k * a), e + a) for e in ends)
        holes = tuple(((far + k * a / 2, e + a / 2), BOLTS["M3"].clearance_hole) for e in ends)
        out.append((side, Slab(f"{cam}-guide-{side}", (rail, *lugs), holes, thickness, tolerance)))
    return out


def guide_bodies(cam: str, plane: int, axis_x: float, width: float, span: tuple[float, float]) -> list[Body]:
    """The two still rails of cam ``cam``'s stem guide (``width`` mm wide stem on x = ``axis_x``), over ``span``
    (:func:`guide_span`), standing on the frame from plane 0 up to the stem's ``plane``, with their lugs' holes."""
    return [Body(f"cams.{cam}.guide.{side}", min(0, plane), plane, slab.outline.vertices, fixed((axis_x, 0.0)),
                 tuple((c, d / 2) for c, d in slab.holes))
            for side, slab in rail_slabs(cam, width, span)]


def guide_screws(body: Body) -> list[tuple[tuple[float, float], float]]:
    """A guide rail's screws: (centre mm in the machine's frame, radius mm) at its lugs' holes; none for any other
    body."""
    if ".guide." not in body.name:
        return []
    origin = np.asarray(body.place(np.zeros(1))[1][0], float)
    return [((float(origin[0] + c[0]), float(origin[1] + c[1])), SCREW_MM / 2) for c, _ in body.holes]


def face_slab(cam: str, extent: tuple[float, float], thickness: float = 0.0, tolerance: float = 0.01) -> Slab:
    """A flat face as a part maker (``<cam>-face``): its strip along the contact line, from ``extent`` (mm from the
    axis, +X) and :data:`FACE_DEPTH_MM` up, in the stem's frame (its contact at y = 0)."""
    return Slab(f"{cam}-face", ((extent[0], 0.0, extent[1], FACE_DEPTH_MM),), (), thickness, tolerance)


def face_bodies(cam: str, plane: int, point: np.ndarray, extent: tuple[float, float], width: float,
                lift: Callable[[np.ndarray], np.ndarray],
                contact: Callable[[np.ndarray], np.ndarray]) -> tuple[list[Body], list[Joint]]:
    """A translating flat face as a clash body, and its joints with its cam and its stem.

    Parameters
    ----------
    cam, plane
        The cam's mount name and plane (2 layer); the face fills ``plane`` and ``plane + 1``.
    point
        (2,) mm: the follower's contact on its axis at lift 0, in the machine's frame.
    extent
        (least, most) mm: the face's ends from the axis along +X (the contact's travel and the face's margins).
    width
        The stem's width (mm): the joints' discs.
    lift, contact
        phi (n,) radians -> the lift s (n,) mm along +Y; -> the contact (n, 2) mm in the machine's frame.
    """
    name = f"cams.{cam}"

    def place(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.broadcast_to(np.eye(2), (len(phi), 2, 2)), np.column_stack(
            [np.full(len(phi), point[0]), point[1] + lift(phi)])

    def foot(phi: np.ndarray) -> np.ndarray:
        return place(phi)[1] + np.array([0.0, FACE_DEPTH_MM / 2])

    body = Body(f"{name}.face", plane, plane + 1, face_slab(cam, extent).outline.vertices, place)
    reach = 1.01 * float(np.hypot(width / 2, FACE_DEPTH_MM / 2)) + 0.05
    return [body], [Joint(name, body.name, contact, 0.51 * width + 0.05),
                    Joint(f"{name}.stem", body.name, foot, reach)]
