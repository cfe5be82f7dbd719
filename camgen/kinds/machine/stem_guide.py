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
meets it.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from camgen.core.hardware import RUNNING_PLAY
from camgen.kinds.machine.clash import Body, Joint, fixed

#: (mm) a flat face's depth up the stem; a guide rail's width; the guide's gap over the foot at the top of the stroke
FACE_DEPTH_MM, GUIDE_WALL_MM, GUIDE_GAP_MM = 3.0, 3.0, 1.0


def box(x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    """(4, 2) mm: the rectangle [x0, x1] x [y0, y1], counter-clockwise."""
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])


def guide_span(rest_y: float, lift_min: float, lift_max: float, length: float, foot: float) -> tuple[float, float]:
    """The guide's bottom and top (mm, the machine's y): :data:`GUIDE_GAP_MM` over the foot (``foot`` mm over the
    follower's point, at ``rest_y`` + lift) at the top of the stroke, up to the stem's top (``length`` mm over the
    point) at its bottom."""
    return rest_y + lift_max + foot + GUIDE_GAP_MM, rest_y + lift_min + length


def guide_bodies(cam: str, plane: int, axis_x: float, width: float, span: tuple[float, float]) -> list[Body]:
    """The two still rails of cam ``cam``'s stem guide (``width`` mm wide stem on x = ``axis_x``), over ``span``
    (:func:`guide_span`), on the stem's ``plane``."""
    inner = width / 2 + RUNNING_PLAY
    y0, y1 = span
    sides = (("left", -inner - GUIDE_WALL_MM, -inner), ("right", inner, inner + GUIDE_WALL_MM))
    return [Body(f"cams.{cam}.guide.{side}", plane, plane, box(x0, y0, x1, y1), fixed((axis_x, 0.0)))
            for side, x0, x1 in sides]


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

    body = Body(f"{name}.face", plane, plane + 1, box(extent[0], 0.0, extent[1], FACE_DEPTH_MM), place)
    reach = 1.01 * float(np.hypot(width / 2, FACE_DEPTH_MM / 2)) + 0.05
    return [body], [Joint(name, body.name, contact, 0.51 * width + 0.05),
                    Joint(f"{name}.stem", body.name, foot, reach)]
