"""Follower motion laws and their registry.

Every law is a normalised rise f(u) on u in [0, 1] (see :mod:`camgen.laws.base`).
``make_law(name, **params)`` builds one from its registry name and parameters, and
``LAW_PARAMS`` says which template keys each law takes.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any, Literal

from camgen.core.errors import SpecError
from camgen.laws.accel import AccelerationLaw, modified_sine, modified_trapezoid
from camgen.laws.base import Law
from camgen.laws.fitted import FittedLaw, table_law
from camgen.laws.piecewise import BlendedUniform, DraftedUniform, Parabolic, Uniform
from camgen.laws.polynomial import PolynomialLaw, from_conditions, poly345, poly4567
from camgen.laws.spline import SplineLaw, spline_law
from camgen.laws.trig import Cycloidal, DoubleHarmonic, Harmonic


def _modified_uniform(form: str = "blended", blend: float = 0.25,
                      blend_law: Literal["cycloidal", "parabolic"] = "cycloidal",
                      k: float | None = None) -> Law:
    """Blended by default; the drafted form needs ``k`` = prime radius x angle / lift."""
    if form == "blended":
        return BlendedUniform(blend=blend, blend_law=blend_law)
    if form == "drafted":
        if k is None:
            raise SpecError("the drafted form needs the cam's prime radius; build it as part of a cam", "form")
        return DraftedUniform(k=k)
    raise SpecError(f"must be 'blended' or 'drafted' (got {form!r})", "form")


#: registry name -> (factory, template keys it takes)
REGISTRY: Mapping[str, tuple[Callable[..., Law], tuple[str, ...]]] = {
    "uniform": (Uniform, ()),
    "modified-uniform": (_modified_uniform, ("form", "blend", "blend_law")),
    "parabolic": (Parabolic, ("ratio",)),
    "harmonic": (Harmonic, ()),
    "cycloidal": (Cycloidal, ()),
    "polynomial-345": (poly345, ()),
    "polynomial-4567": (poly4567, ()),
    "modified-trapezoid": (modified_trapezoid, ()),
    "modified-sine": (modified_sine, ()),
    "double-harmonic": (DoubleHarmonic, ()),
    "polynomial": (from_conditions, ("conditions", "degree")),
    "spline": (spline_law, ("points", "ends")),
    "table": (table_law, ("data", "continuity", "fit_tolerance", "ends")),
}

LAW_NAMES: tuple[str, ...] = tuple(REGISTRY)
#: the names of :data:`REGISTRY`, written out for the type checker (a template's ``law``)
LawName = Literal["uniform", "modified-uniform", "parabolic", "harmonic", "cycloidal", "polynomial-345",
                  "polynomial-4567", "modified-trapezoid", "modified-sine", "double-harmonic", "polynomial", "spline",
                  "table"]
LAW_PARAMS: Mapping[str, tuple[str, ...]] = {name: keys for name, (_, keys) in REGISTRY.items()}
#: the laws of the standard comparison table (the general polynomial, the spline and the table need data)
TABLE_LAWS: tuple[str, ...] = tuple(n for n in LAW_NAMES if n not in ("polynomial", "spline", "table"))


def make_law(name: str, **params: Any) -> Law:
    """The law registered as ``name``, built with ``params`` (template keys, plus ``k`` for drafted forms).

    Parameters
    ----------
    name : str
        A registry name, one of :data:`LAW_NAMES` (``"cycloidal"``, ``"polynomial"``, ...).
    **params
        The law's parameters as a template's segment gives them beside ``law`` (:data:`LAW_PARAMS` names each
        law's: ``ratio`` for ``"parabolic"``, ``conditions`` and ``degree`` for ``"polynomial"``, ...), and for the
        drafted modified-uniform form ``k``, the prime radius times the segment's angle over its lift.

    Returns
    -------
    Law
        The normalised rise: f and its first three derivatives of u in [0, 1] (:meth:`Law.derivatives`), from
        f(0) = 0 to f(1) = 1; a segment scales it by its lift and angle.

    Raises
    ------
    SpecError
        An unknown ``name`` (naming ``law``), or a parameter's value the law refuses (naming the parameter).
    TypeError
        A parameter the law does not take (a template's is refused before, by its validation).
    """
    try:
        factory, _ = REGISTRY[name]
    except KeyError:
        raise SpecError(f"unknown law {name!r}; known laws: {', '.join(LAW_NAMES)}", "law") from None
    return factory(**params)


__all__ = ["LAW_NAMES", "LAW_PARAMS", "TABLE_LAWS", "AccelerationLaw", "BlendedUniform", "Cycloidal",
           "DoubleHarmonic", "DraftedUniform", "FittedLaw", "Harmonic", "Law", "LawName", "Parabolic", "PolynomialLaw",
           "SplineLaw", "Uniform", "from_conditions", "make_law", "modified_sine", "modified_trapezoid", "poly345",
           "poly4567", "spline_law", "table_law"]
