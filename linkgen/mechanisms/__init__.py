"""The mechanisms linkgen knows, one module a kind of linkage, registered here once.

A mechanism (:class:`Mechanism`) holds everything linkgen knows of one kind of linkage:
the model of its ``[linkage]`` table, how that table becomes a kinematics object
(:mod:`linkgen.kinematics`), its section of the report, its figures, its parts and its
family thumbnail. :data:`MECHANISMS` maps every ``linkage.type`` to its mechanism; it is
filled from :data:`MODULES`, each module listing its mechanisms in ``REGISTER``. A new
mechanism is a new module added to :data:`MODULES`; nothing else changes.

Conventions every mechanism keeps: the input pivot at the origin, the ground line on +X,
angles counter-clockwise from it; lengths in mm; the report's angles in degrees, the
kinematics' in radians; speeds per second at the table's ``rpm``.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

from camgen.core.registry import registry as shared_registry
from linkgen.mechanisms import (
    counter,
    couplings,
    fourbar,
    gearpair,
    geartrain,
    general,
    quickreturn,
    ratchet,
    slidercrank,
    straightline,
)
from linkgen.mechanisms.common import Figure

if TYPE_CHECKING:
    from camgen.core.parts import Drawing
    from camgen.core.spec import Model
    from linkgen.parts import Layout
    from linkgen.spec import PartsTable

class Mechanism(Protocol):
    """One kind of linkage. ``table`` arguments are validated instances of :attr:`table`; ``kinematics`` is what
    :meth:`build` made of that table."""

    #: the ``linkage.type`` values it answers to
    types: tuple[str, ...]
    #: the model of its ``[linkage]`` table: a ``type`` literal, lengths (unit mm, listed in the report's
    #: ``lengths_mm``) and ``rpm``
    table: type[Model]

    def build(self, table: Any) -> Any:
        """The kinematics object the table describes."""
        ...

    def report(self, table: Any, kinematics: Any, angle: float | None, method: str) -> dict[str, Any]:
        """Its section of the report (JSON-ready, mm and degrees); ``angle`` (input angle, degrees) adds the positions
        there, ``method`` (``closed`` or ``newton``) how they are solved."""
        ...

    def figures(self, name: str, table: Any, kinematics: Any) -> tuple[Figure, ...]:
        """Its figures, drawn only when called (titled with the linkage's ``name``)."""
        ...

    def layout(self, table: Any, kinematics: Any, parts: PartsTable) -> Layout:
        """Its parts and their motion; a :class:`SpecError` on ``linkage.type`` if it has no parts."""
        ...

    def family_row(self, table: Any, kinematics: Any, report: dict[str, Any]) -> dict[str, Any]:
        """What a family's summary adds for one member beyond the report's common keys: its own columns, and a
        ``thumbnail`` (points in mm) with ``thumbnail_kind`` for the overview picture."""
        ...

    def sketch(self, table: Any, kinematics: Any) -> Drawing | None:
        """A drawing of the linkage at one pose with its path (what Jupyter shows), or None."""
        ...

    def __hash__(self) -> int:
        """A mechanism is hashable (a frozen dataclass): :func:`linkgen.spec.spec_model` makes a model once each."""
        ...


@runtime_checkable
class AnimatedMechanism(Protocol):
    """A mechanism that draws its own animation (``linkgen animate`` of a kind it cannot draw as a general linkage):
    its frames function lives beside its module (``linkgen/mechanisms/<m>frames.py``)."""

    def animation_inputs(self, table: Any, kinematics: Any, n: int) -> Any:
        """The ``n`` input values (rad) of one cycle, the last one step before the first comes again."""
        ...

    def animation_frames(self, table: Any, kinematics: Any, values: Any, size: tuple[int, int]) -> Any:
        """The mechanism drawn at input values ``values`` (rad), ``size`` (width, height) pixels: (n, height, width, 3)
        uint8."""
        ...


@runtime_checkable
class MechanismTable(Protocol):
    """What linkgen reads of every mechanism's ``[linkage]`` table (an instance of :attr:`Mechanism.table`)."""

    @property
    def type(self) -> str:
        """The ``linkage.type`` the table was given."""
        ...

    @property
    def rpm(self) -> float:
        """The input speed (rpm)."""
        ...


def registry(*mechanisms: Mechanism, base: Mapping[str, Mechanism] | None = None) -> Mapping[str, Mechanism]:
    """A read-only ``{linkage.type: mechanism}`` of ``base`` and then ``mechanisms``, in order; a type that two
    mechanisms answer to is an error (the registry camgen's cam kinds share, :func:`camgen.core.registry.registry`)."""
    return shared_registry(mechanisms, lambda mechanism: mechanism.types, "linkage.type", "a mechanism", base)


#: the modules of the mechanisms, in the order their types are listed
MODULES = (fourbar, slidercrank, quickreturn, straightline, general, gearpair, ratchet, couplings, geartrain,
           counter)
#: ``linkage.type`` -> its mechanism
MECHANISMS: Mapping[str, Mechanism] = registry(*(m for module in MODULES for m in module.REGISTER))
