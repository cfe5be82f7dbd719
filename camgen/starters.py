"""Starter templates for ``camgen new NAME``: each kind's own (:attr:`camgen.kinds.base.Kind.starters`: one for each
follower on a disc cam, one for each other cam kind and the Geneva drive), every key commented from the kind's template
models (:mod:`camgen.core.starter`) and, where a kind has rules of its own (what limits its sizes, what it leaves
out), by its starter's rules, so that a comment names only keys that kind takes; each builds as it is."""
from __future__ import annotations

from typing import Any

from camgen.core.options import choose
from camgen.core.starter import render, table_models
from camgen import kinds
from camgen.kinds.base import Kind, Starter

NOTES = {"motion.type": "rise, dwell or return; the angles add up to 360",
         "motion.law": "see `camgen laws` for the laws and their peak factors",
         "motion.lift": "mm: the follower's travel",
         "cam.rotation": "ccw or cw, seen from the side the follower is drawn on",
         "output.formats": "leave out a format to skip its files"}


def starters() -> dict[str, tuple[Kind[Any, Any], Starter]]:
    """Every registered kind's starters by name, each with its kind, in the registry's order (as the registry is
    when called)."""
    return {name: (kind, s) for kind in kinds.KINDS.values() for name, s in kind.starters.items()}


def starter(kind: str, name: str) -> str:
    """The starter template ``kind`` (a name of :func:`starters`) named ``name``, as TOML text; a one-line
    :class:`~camgen.core.errors.SpecError` naming ``KIND`` for another."""
    offered = starters()
    owner, s = offered[choose(kind, offered, "KIND")]
    header = (f"{s.what}\nBuild it with:  camgen build {name}.toml   (files land in out/{name}/)\n"
              "Every key is explained in the documentation's template reference; --set KEY=VALUE changes one for a "
              "run.")
    return render(header, [("", {"name": name}), *s.tables], {"": None, **table_models(owner.spec)},
                  {**NOTES, **s.rules})
