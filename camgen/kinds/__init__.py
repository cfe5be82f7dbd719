"""Cam kinds: one module a kind, registered here, the one place a kind is looked up.

A kind says which followers it drives, how its ``[cam]`` table is checked, how a follower
sits on it, and which functions design it and turn its design into a bundle of files
(named as ``"module:function"`` and imported when first used, so this registry stays
light). Disc and plate cams share one design (a flat plate cut to a profile); a grooved cam's design
makes its inner flank that way too (see :mod:`camgen.grooved`); a barrel cam's developed pitch curve
is a plate cam's (see :mod:`camgen.barrel`); a conjugate pair's first cam is the disc cam and its second is
designed from the second roller's path (see :mod:`camgen.conjugate`).
"""
from __future__ import annotations

from camgen.core.options import choose
from camgen.kinds import barrel, conjugate, disc, grooved, plate
from camgen.kinds.base import CamKind

#: every cam kind by its template name (``cam.kind``)
CAM_KINDS: dict[str, CamKind] = {m.KIND.name: m.KIND for m in (disc, plate, grooved, barrel, conjugate)}


def kind_of(kind: str) -> CamKind:
    """The registered kind ``kind`` (``cam.kind``), or a one-line error listing them."""
    try:
        return CAM_KINDS[kind]          # a registered name (a design asks twice): no list of the names made
    except (KeyError, TypeError):       # not one, or not a name at all: the error says which are
        return CAM_KINDS[choose(kind, CAM_KINDS, "cam.kind")]
