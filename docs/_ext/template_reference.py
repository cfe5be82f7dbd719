"""The template-key reference, generated from the pydantic models that validate the templates.

``{template-reference} ROOT`` (a MyST directive; ROOT one of :data:`ROOTS`) writes one section a table the template
may hold, and in it one row a key: its type, unit, allowed values or range, default and description, each read from
the model's field (``Field(description=...)``, ``json_schema_extra={"unit": ...}``, the bounds and ``Literal`` values
of its annotation, and the notes of ``camgen.core.spec.notes``: ``"allowed"``, a rule beyond the bounds, and
``"absent"``, what leaving out a key whose default is None means). The models are the one source of these facts:
the error messages, the starter templates' comments and this page all read them. ``tests/project/test_docs.py`` compares
the built page with the models.
"""
from __future__ import annotations

import re
import types
import typing
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import annotated_types
from docutils import nodes
from pydantic import BaseModel
from pydantic_core import PydanticUndefined
from sphinx.util.docutils import SphinxDirective

#: the columns of every table
COLUMNS = ("key", "type", "unit", "allowed", "default", "description")


@dataclass(frozen=True)
class Table:
    """One table of a template: its path (``cam``, ``motion[i]``, ``linkage.sliders.<name>``; ``""`` for the
    top-level keys), its model and a title."""

    path: str
    model: type[BaseModel]
    title: str


def roots() -> dict[str, list[Table]]:
    """Every kind of template, by the name the directive takes, as its tables in order."""
    from camgen.core.coupon import CouponSpec
    from camgen.core.family import _SheetTemplate
    from camgen.kinds.geneva.table import GenevaSpec
    from camgen.kinds.machine.spec import MachineSpec
    from camgen.kinds.disc.table import DiscSpec
    from camgen.spec import cam_specs
    from linkgen.mechanisms import MECHANISMS
    from linkgen.spec import LinkageSpec
    from linkgen.synthesis.task import TASKS, SynthesisSpec

    top = list(tables(LinkageSpec, "", skip={"linkage"}))
    by_table: dict[type, list[str]] = {}
    for name, mechanism in MECHANISMS.items():
        by_table.setdefault(mechanism.table, []).append(name)
    linkage = [top[0], *(Table(t.path, t.model, f"{t.title} (type {', '.join(names)})")
                         for table, names in by_table.items() for t in tables(table, "linkage")), *top[1:]]
    top = list(tables(DiscSpec, "", skip={"cam", "follower"}))      # a disc cam's: with its kit
    specs = cam_specs()
    followers = dict.fromkeys(member for spec in specs.values() if "follower" in spec.model_fields
                              for member in _unwrap(spec.model_fields["follower"].annotation))
    cam = [top[0], *(Table(t.path, t.model, f"{t.title} (kind {kind})")
                     for kind, spec in specs.items() for t in tables(spec.model_fields["cam"].annotation, "cam")),
           *(Table(t.path, t.model, f"{t.title} ({follower.model_config['title']})")
             for follower in followers for t in tables(follower, "follower")), *top[1:]]
    top = list(tables(SynthesisSpec, "", skip={"task"}))
    synthesis = [top[0], *(Table(t.path, t.model, f"{t.title} (kind {kind})")
                           for kind, task in TASKS.items() for t in tables(task, "task")), *top[1:]]
    return {
        "cam": _ordered(cam),
        "geneva": list(tables(GenevaSpec, "")),
        "machine": list(tables(MachineSpec, "")),
        "coupon": list(tables(CouponSpec, "")),
        "family": list(tables(_SheetTemplate, ""))[1:],
        "linkage": _ordered(linkage),
        "synthesis": _ordered(synthesis),
    }


#: every directive argument
ROOTS = ("cam", "geneva", "machine", "coupon", "family", "linkage", "synthesis")


def _ordered(found: list[Table]) -> list[Table]:
    """The top-level keys first, then the tables in order, each once (a path and model met twice kept once)."""
    seen, out = set(), []
    for table in found:
        if (table.path, table.model, table.title) not in seen:
            seen.add((table.path, table.model, table.title))
            out.append(table)
    return out


def _unwrap(annotation: Any) -> list[Any]:
    """The members of a union (``X | None`` gives ``[X]``), or ``[annotation]``; each without its ``Annotated``
    metadata (a tagged union's ``Tag``)."""
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        return [_bare(a) for a in typing.get_args(annotation) if a is not type(None)]
    return [_bare(annotation)]


def _bare(annotation: Any) -> Any:
    """``annotation`` without ``Annotated[...]``'s metadata."""
    return typing.get_args(annotation)[0] if typing.get_origin(annotation) is typing.Annotated else annotation


def _models_in(annotation: Any, path: str) -> Iterator[tuple[str, type[BaseModel]]]:
    """(path, model) of the tables a field's annotation holds: itself, list or tuple items (``path[i]``), dict
    values (``path.<name>``)."""
    for member in _unwrap(annotation):
        origin = typing.get_origin(member)
        if isinstance(member, type) and issubclass(member, BaseModel):
            yield path, member
        elif origin in (list, tuple):
            for arg in typing.get_args(member):
                if arg is not Ellipsis:
                    yield from _models_in(arg, f"{path}[i]")
        elif origin is dict:
            yield from _models_in(typing.get_args(member)[1], f"{path}.<name>")


def tables(model: type[BaseModel], path: str, skip: frozenset | set = frozenset()) -> Iterator[Table]:
    """``model``'s table at ``path`` and the tables its fields hold, depth first; fields named in ``skip`` are
    left out of the walk (a mechanism's or a task's own table, listed by the caller)."""
    yield Table(path, model, heading(path))
    for name, info in model.model_fields.items():
        if name in skip:
            continue
        met = set()
        for sub_path, sub in _models_in(info.annotation, f"{path}.{name}" if path else name):
            if sub not in met:                           # a table, or a list of them: one section
                met.add(sub)
                yield from tables(sub, sub_path)


def heading(path: str) -> str:
    """A table's heading as the template writes it: ``[cam]``, ``[[motion]]``, ``[linkage.sliders.NAME]``."""
    if not path:
        return "top-level keys"
    path = path.replace("<name>", "NAME")
    return f"[[{path[:-3]}]]" if path.endswith("[i]") else f"[{path}]"


def key_of(table: Table, name: str) -> str:
    """The full key of field ``name`` of ``table``: ``cam.base_radius``, ``motion[i].lift``, ``name``."""
    return f"{table.path}.{name}" if table.path else name


def is_table(info: Any) -> bool:
    """Whether a field holds tables only (it is then its own section, not a row)."""
    members = _unwrap(info.annotation)
    return all(any(True for _ in _models_in(m, "x")) for m in members)


def type_of(annotation: Any) -> str:
    """A field's type in a template's words: number, integer, true/false, text, one of, list of ..., table."""
    members = _unwrap(annotation)
    if len(members) > 1:
        return " or ".join(type_of(m) for m in members)
    member = members[0]
    origin = typing.get_origin(member)
    if origin is typing.Annotated:
        return type_of(typing.get_args(member)[0])
    if origin is typing.Literal:
        return "one of"
    if member is bool:
        return "true/false"
    if member is int:
        return "integer"
    if member is float:
        return "number"
    if member is str:
        return "text"
    if isinstance(member, type) and issubclass(member, BaseModel):
        return "table"
    if origin in (list, tuple):
        args = [a for a in typing.get_args(member) if a is not Ellipsis]
        if origin is tuple and Ellipsis not in typing.get_args(member):
            return "[" + ", ".join(type_of(a) for a in args) + "]"
        return f"list of {type_of(args[0])}" if args else "list"
    if origin is dict:
        return f"table of {type_of(typing.get_args(member)[1])}"
    return getattr(member, "__name__", str(member))


def _number(value: float) -> str:
    return f"{value:g}"


def bounds(metadata: list[Any]) -> list[str]:
    """A field's bounds as ``> 0``, ``<= 10000``, ``at least 1 items``, ``pattern ...``, from its metadata."""
    out = []
    for item in metadata:
        for attr, text in (("gt", "> {}"), ("ge", ">= {}"), ("lt", "< {}"), ("le", "<= {}")):
            value = getattr(item, attr, None)
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                out.append(text.format(_number(value)))
        if isinstance(item, annotated_types.MinLen):
            out.append(f"at least {item.min_length} items")
        if isinstance(item, annotated_types.MaxLen):
            out.append(f"at most {item.max_length} items")
        pattern = getattr(item, "pattern", None)
        if isinstance(pattern, str):
            out.append(f"matching {pattern}")
    return out


def _literals(annotation: Any) -> list[str]:
    """The values a ``Literal`` in the annotation allows, quoted as TOML strings."""
    values = []
    for member in _unwrap(annotation):
        if typing.get_origin(member) is typing.Literal:
            values += [f'"{v}"' if isinstance(v, str) else str(v) for v in typing.get_args(member)]
        elif typing.get_origin(member) in (list, tuple):
            for arg in typing.get_args(member):
                if typing.get_origin(arg) is typing.Literal:
                    values += [f'"{v}"' for v in typing.get_args(arg)]
    return values


def _inner_bounds(annotation: Any) -> list[str]:
    """Bounds of the items of a list or tuple field (``tuple[SheetSide, SheetSide]``: each > 0)."""
    for member in _unwrap(annotation):
        if typing.get_origin(member) in (list, tuple):
            for arg in typing.get_args(member):
                if typing.get_origin(arg) is typing.Annotated:
                    inner = [m for a in typing.get_args(arg)[1:] for m in getattr(a, "metadata", [a])]
                    found = bounds(inner)
                    if found:
                        return [f"each {b}" for b in found]
    return []


def _extra(info: Any) -> dict[str, Any]:
    extra = info.json_schema_extra
    return extra if isinstance(extra, dict) else {}


def allowed_of(info: Any) -> str:
    """What a field allows: its Literal values, then its bounds and those of its items, then its ``allowed`` note."""
    parts = []
    literals = _literals(info.annotation)
    if literals:
        parts.append(", ".join(literals))
    parts += bounds(info.metadata) + _inner_bounds(info.annotation)
    if _extra(info).get("allowed"):
        parts.append(_extra(info)["allowed"])
    return "; ".join(parts)


def unit_of(info: Any) -> str:
    """A field's unit, from its ``json_schema_extra``."""
    return _extra(info).get("unit", "")


def _toml(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return _number(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{}" if not value else "{ " + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + " }"
    if isinstance(value, BaseModel):
        return "its keys' defaults"
    return str(value)


def default_of(info: Any) -> str:
    """A field's default: ``required``, the value as TOML, or for a default of None its ``absent`` note (what
    leaving the key out means), else ``none`` (not given)."""
    if info.is_required():
        return "required"
    if info.default_factory is not None:
        return _toml(info.default_factory())
    if info.default is None or info.default is PydanticUndefined:
        return _extra(info).get("absent", "none")
    return _toml(info.default)


def plain(docstring: str | None) -> str:
    """A docstring's first paragraph as plain text: reST roles and literals reduced to their text."""
    if not docstring:
        return ""
    first = re.split(r"\n\s*\n", docstring.strip())[0]
    first = re.sub(r":\w+:`~?([^`<]*?)(?:\s*<[^>]*>)?`", lambda m: m.group(1).split(".")[-1], first)
    first = first.replace("``", "")
    return " ".join(first.split())


def rows(table: Table) -> list[tuple[str, ...]]:
    """One row a key of ``table`` (fields holding tables are sections of their own)."""
    out = []
    for name, info in table.model.model_fields.items():
        if is_table(info):
            continue
        out.append((key_of(table, name), type_of(info.annotation), unit_of(info), allowed_of(info), default_of(info),
                    info.description or ""))
    return out


def _cell(text: str, literal: bool = False) -> nodes.entry:
    entry = nodes.entry()
    if text:
        entry += nodes.paragraph("", "", nodes.literal(text, text) if literal else nodes.Text(text))
    return entry


def table_node(table: Table) -> nodes.table:
    """The docutils table of ``table``'s rows, with classes the tests find it by."""
    node = nodes.table(classes=["template-keys"])
    group = nodes.tgroup(cols=len(COLUMNS))
    node += group
    for width in (18, 10, 8, 18, 10, 36):
        group += nodes.colspec(colwidth=width)
    head = nodes.thead()
    group += head
    row = nodes.row()
    for title in COLUMNS:
        row += _cell(title)
    head += row
    body = nodes.tbody()
    group += body
    for cells in rows(table):
        row = nodes.row(classes=["template-key"])
        for i, text in enumerate(cells):
            row += _cell(text, literal=i == 0)
        body += row
    return node


class TemplateReference(SphinxDirective):
    """``{template-reference} ROOT``: a section a table of that kind of template."""

    required_arguments = 1

    def run(self) -> list[nodes.Node]:
        root = self.arguments[0]
        if root not in ROOTS:
            raise self.error(f"unknown template kind {root!r}; one of {', '.join(ROOTS)}")
        out: list[nodes.Node] = []
        for table in roots()[root]:
            section = nodes.section(ids=[nodes.make_id(f"keys-{root}-{table.path or 'top'}-{table.title}")])
            section += nodes.title(table.title, table.title)
            intro = plain(table.model.__doc__)
            if intro and table.model.__doc__ is not BaseModel.__doc__:
                section += nodes.paragraph(intro, intro)
            if rows(table):
                section += table_node(table)
            out.append(section)
        return out


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("template-reference", TemplateReference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
