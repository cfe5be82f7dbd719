"""Cam kinds (and the Geneva drive): one package a kind (``camgen/kinds/<kind>/``), registered here by one line,
the one place a kind is looked up; a kind of an installed plugin is registered by its entry point in the group
:data:`GROUP` (:func:`plugins`).

A kind (:class:`~camgen.kinds.base.Kind`) says which table chooses it, which followers it drives, which formats its
files come in, how its spec is designed, bundled into files, summarised on the console and sized, what a family's
summary shows of it and which starter templates ``camgen new`` writes of it. A kind's package holds its kind
(``kind.py``, which ``__init__.py`` exports as ``KIND``), its starters and, as it needs them, its design, files, page,
figures and pure-numpy ``kinematics.py``; its methods import its design and output modules when first called, so
this registry stays light; a cam kind chosen by ``cam.kind`` keeps its ``[cam]`` table and its spec (a
:class:`camgen.spec.CamSpec`) in its ``table.py``. No kind's package imports another's: what kinds share lives outside
them. Disc and plate
cams share one design (a flat plate cut to a profile, :class:`~camgen.kinds.shared.FlatKind`); a grooved cam's
design makes its inner flank that way too (see :mod:`camgen.kinds.grooved`); a barrel cam's developed pitch curve is
a plate cam's (see :mod:`camgen.kinds.barrel`); a conjugate pair's first cam is the disc cam and its second is
designed from the second roller's path (see :mod:`camgen.kinds.conjugate`). A Geneva drive has a ``[geneva]`` table
of its own, which chooses it.

The command line, the family, the starters and the library's calls (:mod:`camgen.api`) ask :data:`KINDS`:
:func:`kind_for` for a raw template, :func:`spec_kind` for a validated spec.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from importlib.metadata import EntryPoint, entry_points
from typing import Any

from camgen.core.errors import SpecError
from camgen.core.options import choose
from camgen.core.registry import registry
from camgen.kinds import barrel, conjugate, disc, geneva, grooved, machine, plate
from camgen.kinds.base import CAM_TABLE, Kind

#: the entry-point group a distribution declares its cam kinds in (``eccentric = my_package.kind:KIND``)
GROUP = "camgen.kinds"
#: the kinds this package holds, in the order ``camgen new`` lists them
BUILT_IN: tuple[Kind[Any, Any], ...] = (disc.KIND, plate.KIND, grooved.KIND, barrel.KIND, conjugate.KIND, geneva.KIND,
                                        machine.KIND)


def plugins(found: Iterable[EntryPoint], taken: Iterable[str]) -> tuple[Kind[Any, Any], ...]:
    """The kinds the entry points ``found`` (of :data:`GROUP`) load, each the object its entry point names.

    Parameters
    ----------
    found : iterable of EntryPoint
        The installed distributions' entry points of :data:`GROUP`, each named as its kind (``cam.kind``'s value,
        or its own table's name).
    taken : iterable of str
        The built-in kinds' names, which no plugin may take.

    Raises
    ------
    SpecError
        One line on ``camgen.kinds``: an entry point named as a built-in kind, one that cannot be loaded, or one
        whose kind has another name than the entry point's.
    """
    taken = set(taken)
    kinds = []
    for entry in sorted(found, key=lambda e: e.name):
        where = f"the plugin kind {entry.name!r} ({entry.value})"
        if entry.name in taken:
            raise SpecError(f"{where} is named as a built-in kind; its distribution must give it another name",
                            GROUP)
        try:
            kind = entry.load()
        except Exception as exc:                         # a plugin's own failure, whatever it is: one line
            raise SpecError(f"{where} cannot be loaded: {type(exc).__name__}: {exc}", GROUP) from None
        if getattr(kind, "name", None) != entry.name:
            raise SpecError(f"{where} loads a kind named {getattr(kind, 'name', None)!r}, not {entry.name!r}", GROUP)
        kinds.append(kind)
    return tuple(kinds)


#: every kind by its name (``cam.kind``'s value, or its own table's name): the built-in ones in the order ``camgen
#: new`` lists them, then those of installed plugins (:func:`plugins`) by name
KINDS: Mapping[str, Kind[Any, Any]] = registry(
    (*BUILT_IN, *plugins(entry_points(group=GROUP), (kind.name for kind in BUILT_IN))),
    lambda kind: (kind.name,), "cam.kind", "a cam kind")

#: the kinds chosen by ``cam.kind``, each with its own ``[cam]`` table and spec (in its package's ``table.py``)
CAM_KINDS: Mapping[str, Kind[Any, Any]] = {name: kind for name, kind in KINDS.items() if kind.table_key == CAM_TABLE}
#: the kind of a ``[cam]`` table without ``kind``
DEFAULT_KIND = "disc"


def kind_for(raw: Mapping[str, Any]) -> Kind[Any, Any]:
    """The kind of the raw template ``raw``: the kind whose own table it has (a ``[geneva]`` table: a Geneva
    drive), else its ``cam.kind`` (a disc without one).

    Raises
    ------
    SpecError
        Two kinds' tables in one template (``template: give [cam] (a cam) or [geneva] (a Geneva drive), not
        both``), or a ``cam.kind`` no kind has (the message lists them, with the closest).
    """
    own = [kind for kind in KINDS.values() if kind.table_key != CAM_TABLE and kind.table_key in raw]
    if len(own) + (CAM_TABLE in raw) > 1:
        raise SpecError(_one_table(raw, own), "template")
    if own:
        return own[0]
    cam = raw.get(CAM_TABLE)
    name = cam.get("kind", DEFAULT_KIND) if isinstance(cam, Mapping) else DEFAULT_KIND
    return KINDS[choose(name, [n for n, kind in KINDS.items() if kind.table_key == CAM_TABLE], "cam.kind")]


def _one_table(raw: Mapping[str, Any], own: list[Kind[Any, Any]]) -> str:
    """What to say of a template holding the tables of several kinds: ``[cam]`` and those of ``own``."""
    tables = [(CAM_TABLE, "a cam")] if CAM_TABLE in raw else []
    given = [f"[{table}] ({what})" for table, what in (*tables, *((k.table_key, k.title) for k in own))]
    return "give " + (" or ".join(given) + ", not both" if len(given) == 2 else "only one of " + ", ".join(given))


def table_keys(kind: Kind[Any, Any]) -> Mapping[str, Any]:
    """The keys of the table ``kind`` is chosen by (:attr:`~camgen.kinds.base.Kind.table_key`: a cam's ``[cam]``, a
    Geneva drive's ``[geneva]``), as its spec's model declares them (imported here)."""
    table = kind.spec.model_fields[kind.table_key].annotation
    return getattr(table, "model_fields", {})


def spec_kind(spec: Any) -> Kind[Any, Any]:
    """The kind of a validated spec (by its ``kind``: a cam's ``cam.kind``, a Geneva drive's ``"geneva"``)."""
    return KINDS[choose(spec.kind, KINDS, "cam.kind")]


def kind_of(kind: str) -> Kind[Any, Any]:
    """The cam kind named ``kind`` (``cam.kind``), or a one-line error listing them."""
    try:
        return CAM_KINDS[kind]          # a registered name (a design asks twice): no list of the names made
    except (KeyError, TypeError):       # not one, or not a name at all: the error says which are
        return CAM_KINDS[choose(kind, CAM_KINDS, "cam.kind")]
