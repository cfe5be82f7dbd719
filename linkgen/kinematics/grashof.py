"""Grashof classification of a four-bar chain, for any link as ground and any neighbour as input.

With shortest S, longest L and the others P, Q:

* class I   (S + L < P + Q, Grashof): the shortest link turns fully against both neighbours;
* class II  (S + L > P + Q, non-Grashof): no link turns fully (triple rocker);
* class III (S + L = P + Q, change point): the chain can fold flat and switch assembly.

S + L = P + Q counts as class III within 1e-10 of the longest link: lengths that
differ from a change point by rounding or by far less than any part can be made
to are named, and solved, as change points.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from camgen.core.errors import SpecError

#: relative tolerance (of the longest link) of the change-point test S + L = P + Q
CHANGE_POINT_TOL = 1e-10


@dataclass(frozen=True)
class Grashof:
    """Class and inversion of a four-bar with links in loop order ground, input, coupler, output.

    ``inversion`` is ``crank-rocker`` (input turns fully, output rocks),
    ``rocker-crank`` (the reverse), ``double-crank``, ``double-rocker`` or
    ``triple-rocker``; class III names are prefixed ``change-point``. ``form`` names
    the special change-point shapes ``parallelogram``, ``deltoid`` (kite) and
    ``rhombus`` (all four equal). ``margin`` is (P + Q) - (S + L) in mm.
    """

    grashof_class: str
    inversion: str
    form: str | None
    input_turns_fully: bool
    output_turns_fully: bool
    margin: float


def check_lengths(lengths: dict[str, float]) -> None:
    """Refuse lengths that are not positive and finite, or that cannot close a loop."""
    for name, value in lengths.items():
        if not (value > 0 and value < float("inf")):
            raise SpecError(f"must be a finite length > 0 mm (got {value})", name)
    longest = max(lengths, key=lengths.__getitem__)
    others = sum(lengths.values()) - lengths[longest]
    if lengths[longest] >= others * (1 - CHANGE_POINT_TOL):
        raise SpecError(f"{lengths[longest]:.6g} mm is not shorter than the other three links together "
                        f"({others:.6g} mm): the chain cannot close except flat", longest)


def check_finite(values: ArrayLike, what: str, field: str = "angle", unit: str = "degrees",
                 said: Callable[[float], float] = math.degrees) -> None:
    """Refuse input values that are not finite numbers (NaN, +-inf), where every pose would be NaN: a
    :class:`SpecError` on ``field`` naming ``what`` (e.g. ``"crank angle"``) and the first such value as the user
    means it, ``said(value)`` in ``unit`` (radians said in degrees by default)."""
    v = np.asarray(values, dtype=float)
    if not np.isfinite(v).all():
        bad = said(float(v[~np.isfinite(v)].flat[0]))
        raise SpecError(f"{what} {bad:g} {unit} is not a finite number (any finite number of {unit})", field)


def classify(ground: float, driven: float, coupler: float, output: float) -> Grashof:
    """Classify the four-bar with links in loop order ground, driven (input), coupler, output (mm).

    Parameters
    ----------
    ground, driven, coupler, output : float
        The links' lengths in loop order (mm): the fixed link, the input, the coupler, the output.

    Returns
    -------
    Grashof
        The class (``"I"``: S + L < P + Q, ``"II"``: S + L > P + Q, ``"III"``: equal within 1e-10 of the longest
        link, a change point), the inversion (``"crank-rocker"``, ...), the change-point form (parallelogram,
        deltoid, rhombus) or None, whether the input and the output turn fully, and the margin (P + Q) - (S + L)
        in mm.
    """
    links = [ground, driven, coupler, output]
    s, big = min(links), max(links)
    p_q = sum(links) - s - big
    margin = p_q - (s + big)
    tol = CHANGE_POINT_TOL * big
    if margin > tol:
        cls = "I"
    elif margin < -tol:
        cls = "II"
    else:
        cls = "III"
    if cls == "II":
        return Grashof("II", "triple-rocker", None, False, False, margin)
    shortest = [abs(x - s) <= tol for x in links]
    ground_s, input_s, _, output_s = shortest
    input_full = ground_s or input_s
    output_full = ground_s or output_s
    if input_full and output_full:
        name = "double-crank"
    elif input_full:
        name = "crank-rocker"
    elif output_full:
        name = "rocker-crank"
    else:
        name = "double-rocker"
    form = None
    if cls == "III":
        name = f"change-point {name}"
        eq = [[abs(a - b) <= tol for b in links] for a in links]
        if eq[0][1] and eq[0][2] and eq[0][3]:
            form = "rhombus"
        elif eq[0][2] and eq[1][3]:
            form = "parallelogram"
        elif (eq[0][1] and eq[2][3]) or (eq[0][3] and eq[1][2]):
            form = "deltoid"
    return Grashof(cls, name, form, input_full, output_full, margin)


def classify_chain(lengths: tuple[float, float, float, float], ground: int, driven: int) -> Grashof:
    """Classify a chain of four links given in loop order, with link ``ground`` fixed and link ``driven`` as input.

    The input must be a neighbour of the ground (index difference 1 modulo 4).

    Parameters
    ----------
    lengths : tuple of float
        The four links' lengths in loop order (mm).
    ground : int
        The index (0 to 3) of the fixed link.
    driven : int
        The index of the input link, next to the ground.

    Returns
    -------
    Grashof
        As :func:`classify` gives it for the links read from the ground through the input.

    Raises
    ------
    SpecError
        Naming ``input``: an input link that is not next to the ground.
    """
    if (driven - ground) % 4 not in (1, 3):
        raise SpecError(f"the input link must be next to the ground link (ground {ground}, input {driven})", "input")
    step = 1 if (driven - ground) % 4 == 1 else -1
    g, i, c, o = (lengths[(ground + k * step) % 4] for k in range(4))
    return classify(g, i, c, o)
