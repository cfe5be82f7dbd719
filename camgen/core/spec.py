"""The spec machinery of both products: TOML templates, ``base`` includes, ``--set`` overrides, validation.

A *template* is what a user writes (a TOML file, or the same mapping from Python); its
*spec* is the validated, frozen model of it. A template is validated by a pydantic model derived
from :class:`Model`; :func:`validate` turns pydantic's first error into a
:class:`~camgen.core.errors.SpecError` naming the field, the rule and the value given,
with the field's unit (from ``json_schema_extra={"unit": ...}``), e.g.
``motion[2].angle: must be > 0 and <= 360 degrees (got -30)``.
"""
from __future__ import annotations

import copy
import difflib
import json
import re
import tomllib
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, ClassVar, Literal, Self, TypeVar, cast, get_args, get_origin

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator
from pydantic.config import JsonDict

from camgen.core.errors import SpecError
from camgen.core.features import MIN_WEB_MM
from camgen.core.options import not_one_of
from camgen.core.reading import NotRegularFile, read_regular
from camgen.core.writers import (
    DEFAULT_FORMATS, FIGURE_FORMATS, FORMATS, OPTIONAL_FORMATS, DxfFlavour, DxfVersion, TextMode, WriteOptions,
    missing_extra)

M = TypeVar("M", bound=BaseModel)
if TYPE_CHECKING:
    FormatNames = tuple[str, ...]
else:
    #: what ``output.formats`` holds: names of the formats' registry (:data:`camgen.core.writers.REGISTRY`) as
    #: registered when this module is imported, a ``Literal`` for pydantic's check and the key reference
    FormatNames = tuple[Literal[FORMATS + OPTIONAL_FORMATS], ...]

#: pattern of a part name: safe as a file name
NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9._-]{0,99}$"


class Model(BaseModel):
    """Base of every template model: frozen, no unknown keys, no NaN or infinity, no true/false where a
    number is asked for (pydantic would read ``lift = true`` as 1 mm) and nothing but true/false where a switch is
    (it would read ``keyway = 1`` or ``"yes"`` as true), and no length (mm) other than 0 below
    :data:`MIN_LENGTH_MM`. A value derived from a model and kept is a :class:`functools.cached_property`
    (no field: pydantic ignores it)."""

    model_config = ConfigDict(frozen=True, extra="forbid", allow_inf_nan=False, strict=False)

    @model_validator(mode="before")
    @classmethod
    def _plain_numbers(cls, data: Any) -> Any:
        if isinstance(data, Mapping):
            for name, value in data.items():
                info = cls.model_fields.get(name) if isinstance(name, str) else None
                if info is None:
                    continue
                if _mentions(info.annotation, (int, float)) and not _mentions(info.annotation, (bool,)):
                    where = _bool_at(value, _keyed(info.annotation))
                    if where is not None:
                        raise ValueError(f"{name}{where}: must be a number, not true or false")
                if _only_bool(info.annotation) and value is not None and not isinstance(value, bool):
                    raise ValueError(f"{name}: must be true or false (got {value!r})")
                if _tiny_length(info, value):
                    raise ValueError(f"{name}: a length other than 0 must be at least {MIN_LENGTH_MM:g} mm in size "
                                     f"(got {value!r})")
        return data


def _tiny_length(info: Any, value: Any) -> bool:
    """Whether ``value`` is a length (the field's unit is mm) nearer 0 than :data:`MIN_LENGTH_MM` but not 0, in a
    field that sets no least value of its own (as a tolerance does)."""
    extra = info.json_schema_extra
    if not isinstance(extra, dict) or extra.get("unit") != "mm" or isinstance(value, bool) or \
            not isinstance(value, (int, float)) or not 0 < abs(value) < MIN_LENGTH_MM:
        return False
    return not any((getattr(m, "gt", None) or 0) > 0 or (getattr(m, "ge", None) or 0) > 0 for m in info.metadata)


def _mentions(annotation: Any, kinds: tuple[type, ...]) -> bool:
    """Whether a type annotation accepts one of ``kinds`` anywhere (itself, or a union or container of it)."""
    return annotation in kinds or any(_mentions(a, kinds) for a in getattr(annotation, "__args__", ()))


def _only_bool(annotation: Any) -> bool:
    """Whether a field takes true or false and nothing else (``bool``, or ``bool | None``): pydantic's lax mode
    would read 1, "yes" or "on" as true."""
    return annotation is bool or set(getattr(annotation, "__args__", ())) == {bool, type(None)}


def _holds_bool(value: Any) -> bool:
    """Whether ``value`` is a boolean or a list of values holding one (not looking into tables: their own
    model checks them)."""
    if isinstance(value, bool):
        return True
    return isinstance(value, (list, tuple)) and any(_holds_bool(v) for v in value)


def _bool_at(value: Any, keyed: bool) -> str | None:
    """Where a field's ``value`` holds a boolean: ``""`` (the value, or a list holding one), ``".<key>"`` (in a
    ``keyed`` field, a table of the user's own keys: the entry whose value holds one, ``joints.A = [true, 0]``),
    or None. A table's entries that are tables themselves are their own model's to check."""
    if _holds_bool(value):
        return ""
    if keyed and isinstance(value, Mapping):
        return next((f".{key}" for key, v in value.items() if _holds_bool(v)), None)
    return None


#: the largest length a template may give (mm): ten metres, past any laser bed or printer, and small enough that
#: every coordinate keeps its digits in the files' single-precision numbers
MAX_LENGTH_MM = 10_000.0
#: the least length other than 0 a template may give (mm): a nanometre, far below what a laser or a printer
#: resolves (a vanishing roller is still a roller), and far enough from 0 that every slope and curvature computed
#: from it stays finite
MIN_LENGTH_MM = 1e-6


def length(description: str, default: Any = ..., *, zero: bool = False, le: float = MAX_LENGTH_MM, allowed: str = "",
           absent: str = "") -> Any:
    """A length field in mm: > 0 (>= 0 with ``zero``) and at most ``le``; required unless a default is given
    (``allowed`` and ``absent`` as :func:`notes` takes them)."""
    return Field(default, ge=0 if zero else None, gt=None if zero else 0, le=le, description=description,
                 json_schema_extra=unit("mm", allowed=allowed, absent=absent))


def unit(name: str, *, allowed: str = "", absent: str = "") -> JsonDict:
    """``json_schema_extra`` naming a field's unit (error messages, the starters' comments and the template reference
    give it), with the :func:`notes` given."""
    return {"unit": name, **notes(allowed=allowed, absent=absent)}


def notes(*, allowed: str = "", absent: str = "") -> JsonDict:
    """``json_schema_extra`` of what the template reference says of a field beyond its bounds and its default, in a
    user's words: ``allowed``, a rule its own bounds do not show (one across keys, or one a validator checks:
    ``> the follower's stroke + the groove's width``), and ``absent``, what leaving out a key whose default is
    None means (``required for a plate cam``, ``follower.roller_radius``)."""
    return {key: text for key, text in (("allowed", allowed), ("absent", absent)) if text}


def name_field(what: str) -> Any:
    """The ``name`` field of a template: safe as a file name."""
    return Field(pattern=NAME_PATTERN, description=f"{what} name, used for file names")


#: the largest process allowance (kerf, clearance, elephant foot; mm)
MAX_ALLOWANCE_MM = 5.0


class OutputTable(Model):
    """The ``[output]`` table every product takes: which files to write, and the DXF's flavour and version.

    Products extend it with their own keys (camgen: the outline's tolerance and curves, kerf, clearance).
    """

    formats: FormatNames = Field(
        DEFAULT_FORMATS, min_length=1, description="files to write (png and svg figures, and step with the step "
        "extra installed, only when asked)")
    figures: bool = Field(False, description="also write the figures as PNG and SVG (the same as adding \"png\" "
                          "and \"svg\" to formats; `--figures` on the command line)")
    dxf: DxfFlavour = Field(
        "polyline-bulge", description="DXF flavour: bulged polylines, LINE/ARC entities, or chords only")
    dxf_version: DxfVersion = Field("R2010", description="DXF version (R12 for old controllers)")
    text: TextMode = Field(
        "text", description="engraved text as text, or as the glyphs' outlines (for laser software that drops text)")
    elephant_foot: float = Field(0.0, ge=0, le=MAX_ALLOWANCE_MM, description="printed solids: 45-degree chamfer "
                                 "round the bed face (its outline inset, holes opened), 0 for none",
                                 json_schema_extra=unit("mm", allowed="< each part's thickness, and not closing up "
                                                        "its bed face"))
    tool_radius: float = Field(0.0, ge=0, le=1000.0, description="CNC routing: report every place an outline's "
                               "concave radius is smaller than this tool radius, 0 for no check",
                               json_schema_extra=unit("mm"))

    @model_validator(mode="before")
    @classmethod
    def _figures_as_formats(cls, data: Any) -> Any:
        """``figures = true`` adds the figures' formats to ``formats`` (given or default), so that ``formats``
        always names every file written."""
        if not isinstance(data, Mapping) or data.get("figures") is not True:
            return data
        formats = data.get("formats", DEFAULT_FORMATS)
        if not isinstance(formats, (list, tuple)):
            return data                                 # not a list: the field's own check names it
        return {**data, "formats": [*formats, *(f for f in FIGURE_FORMATS if f not in formats)]}

    @field_validator("formats")
    @classmethod
    def _extras_installed(cls, formats: tuple[str, ...]) -> tuple[str, ...]:
        """Refuse a format whose optional extra is not installed, naming the install command."""
        why = missing_extra(formats)
        if why is not None:
            raise ValueError(why)
        return formats

    @property
    def write_options(self) -> WriteOptions:
        """The writers' options these keys ask for."""
        return WriteOptions(self.dxf_version, self.dxf, self.text)


#: a side of a cut sheet (mm)
SheetSide = Annotated[float, Field(gt=0, le=MAX_LENGTH_MM)]


class CutOutputTable(OutputTable):
    """The ``[output]`` keys of products made as cut and printed parts: the tolerance of curves made into chords,
    the laser's kerf and the printer's clearance (camgen's cams and Geneva drives), and the cut sheet that a
    product of several parts nests them on (:mod:`camgen.core.nesting`)."""

    tolerance: float = Field(0.01, ge=1e-6, le=1.0, description="max distance of the exported curves from the "
                             "exact ones", json_schema_extra=unit("mm", allowed="a barrel cam's solid: at least 10 "
                                                                  "single-precision steps at the cam's size"))
    kerf: float = Field(0.0, ge=0, le=5, description="laser kerf: cut files grow outlines and shrink holes by half",
                        json_schema_extra=unit("mm", allowed="with hub.keyway, < the keyway's width; none on a barrel "
                                               "cam"))
    clearance: float = Field(0.0, ge=0, le=5, description="printing clearance: printed holes grow by this in "
                             "diameter", json_schema_extra=unit("mm", allowed=f"on a cam, the holes so opened stay "
                                                                f"inside it, {MIN_WEB_MM:g} mm apart"))
    sheet: tuple[SheetSide, SheetSide] = Field((600.0, 400.0), description="cut sheet of a product of several "
                                               "parts (Geneva drive, conjugate pair): width and height",
                                               json_schema_extra=unit("mm"))
    margin: float = Field(3.0, ge=0, le=1000, description="cut sheet: gap between parts and to the edges beyond the "
                          "kerf", json_schema_extra=unit("mm"))
    sheet_rotations: float = Field(90.0, ge=0, le=360, description="cut sheet: parts turn in steps of this (0: as "
                                   "drawn only); a divisor of 360", json_schema_extra=unit("degrees"))
    grain: bool = Field(False, description="cut sheet: parts keep along the sheet's width, turned by 0 or 180 "
                        "degrees only")

    @field_validator("sheet_rotations")
    @classmethod
    def _divides_a_turn(cls, step: float) -> float:
        """A rotation step is 0 or divides 360 degrees."""
        if step > 0 and abs(360.0 / step - round(360.0 / step)) > 1e-9:
            raise ValueError(f"must be 0 or divide 360 degrees (e.g. 90, 45, 15) (got {step:g})")
        return step


def parse_overrides(pairs: Iterable[str]) -> list[tuple[str, Any]]:
    """``key=value`` strings as (dotted key, value); values are read as TOML values, else kept as text."""
    out = []
    for pair in pairs:
        key, sep, text = pair.partition("=")
        key = re.sub(r"\[\s*(\d+)\s*\]", r".\1", key)   # motion[0].lift, as errors name it, is motion.0.lift
        if not sep or not key.strip():
            raise SpecError(f"expected key=value, e.g. motion.0.lift=25 (got {pair!r})", "--set")
        if not all(part.strip() for part in key.split(".")):
            raise SpecError("a key is field names joined by single dots, e.g. motion.0.lift (this one has an empty "
                            "name)", f"--set {key.strip()}")
        try:
            value = tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            value = text.strip()
        except RecursionError:
            value = None
        if value is None or _depth(value) > MAX_DEPTH:
            raise SpecError(f"the value nests arrays or tables more than {MAX_DEPTH} deep", f"--set {key.strip()}")
        out.append((key.strip(), value))
    return out


def apply_overrides(raw: Mapping[str, Any], overrides: Iterable[tuple[str, Any]]) -> dict[str, Any]:
    """A copy of the raw template with each dotted key set (list items by index: ``motion.0.lift``)."""
    data = copy.deepcopy(dict(raw))
    for key, value in overrides:
        node: Any = data
        parts = key.split(".")
        for depth, part in enumerate(parts):
            last = depth == len(parts) - 1
            where = ".".join(parts[: depth + 1])
            if isinstance(node, list):
                if not part.isdigit() or int(part) >= len(node):
                    raise SpecError(f"no item {part} in '{'.'.join(parts[:depth]) or key}' "
                                    f"(it has {len(node)} items, indexed from 0)", f"--set {key}")
                index: Any = int(part)
            elif isinstance(node, dict):
                index = part
            else:
                raise SpecError(f"'{'.'.join(parts[:depth])}' is a value, not a table", f"--set {key}")
            if last:
                node[index] = value
            else:
                if isinstance(node, dict) and index not in node:
                    node[index] = {}
                node = node[index]
                if not isinstance(node, (dict, list)):
                    raise SpecError(f"'{where}' is a value, not a table", f"--set {key}")
    return data


def validate(model: type[M], raw: Mapping[str, Any]) -> M:
    """``model`` validated from a raw mapping, or a one-line :class:`SpecError`."""
    try:
        return model.model_validate(raw)
    except ValidationError as exc:
        raise _first_error(exc, model) from None


def check_kind(raw: Mapping[str, Any], product: str) -> None:
    """Refuse, naming the command that takes it, a template meant for the other product or a family template
    given to a command that builds one design (``product`` is ``"camgen"`` or ``"linkgen"``)."""
    if "sweep" in raw:
        raise SpecError(f"this is a family template (it has a [sweep] table): build it with `{product} family`",
                        "template")
    if "task" in raw:
        raise SpecError("this is a synthesis task (it has a [task] table): run it with `linkgen synthesize`",
                        "template")
    other = "linkgen" if "linkage" in raw else "camgen" if {"cam", "follower", "motion"} & set(raw) else product
    if other != product:
        raise SpecError(f"this is a {other} template: use `{other} build`" + (
            " or `linkgen analyze`" if other == "linkgen" else ""), "template")


def read_template(path: str | Path, overrides: Iterable[str] = ()) -> dict[str, Any]:
    """A TOML template as a raw mapping: its ``base`` (a template it starts from, path relative to it)
    merged under it, then ``key=value`` overrides merged in, all before any validation."""
    return apply_overrides(_with_base(Path(path), set()), parse_overrides(overrides))


class TemplateSpec(Model):
    """A whole template, validated: the base of every product's spec (camgen's cams and Geneva drives, linkgen's
    linkages), made from a TOML file, from a mapping, or from another spec with some keys changed::

        spec = CamSpec.from_toml("templates/rdrd.toml").with_changes({"motion.0.lift": 25})

    Each product's spec class says how a raw template is validated (:meth:`validate_raw`: the class its tables
    choose, e.g. a :class:`~camgen.kinds.geneva.table.GenevaSpec` for a ``[geneva]`` table) and which command builds it
    (:attr:`product`); a template of another class is refused in one line naming ``template``.
    """

    #: the command that builds it (``"camgen"`` or ``"linkgen"``): another product's template is refused by name
    product: ClassVar[str] = ""
    #: how a message names a template of this class (``"a cam"``, ``"a Geneva drive"``)
    noun: ClassVar[str] = "a template"

    @classmethod
    def validate_raw(cls, raw: Mapping[str, Any], folder: Path | None = None) -> TemplateSpec:
        """The spec of the raw template ``raw``, of the class its tables choose (here: this class); ``folder`` is
        where relative files named in it lie (the template's folder; None: the current folder)."""
        return validate(cls, raw)

    @classmethod
    def from_toml(cls, path: str | Path, overrides: Iterable[str] = ()) -> Self:
        """The spec of the TOML template ``path`` (and its ``base``) with ``"key=value"`` ``overrides`` merged in, as
        ``--set`` takes them.

        Raises
        ------
        SpecError
            The file cannot be read, is another product's or another class's template (``template: a Geneva
            drive, not a cam``), or fails validation: one line naming the key.
        """
        raw = read_template(path, overrides)
        check_kind(raw, cls.product)
        return cls._own(cls.validate_raw(raw, Path(path).parent))

    @classmethod
    def from_mapping(cls, raw: Mapping[str, Any]) -> Self:
        """The spec of the raw template ``raw`` (the mapping TOML reads, files relative to the current folder);
        a one-line :class:`SpecError` as :meth:`from_toml` gives."""
        check_kind(raw, cls.product)
        return cls._own(cls.validate_raw(raw))

    def with_changes(self, changes: Mapping[str, Any]) -> Self:
        """This spec with each dotted key of ``changes`` set to its value (the keys ``--set`` takes:
        ``{"motion.0.lift": 25}``, list items by index), validated again as a whole; a change that chooses another
        class (a linkage's ``linkage.type``) gives a spec of that class, of this one's product.

        Raises
        ------
        SpecError
            A key that leads nowhere (``motion.9.lift: no item 9 in 'motion' ...``) or a changed template that
            fails validation: one line naming the key.
        """
        raw = self.model_dump(mode="json", exclude_unset=True)
        try:
            changed = apply_overrides(raw, changes.items())
        except SpecError as exc:
            raise SpecError(exc.detail, (exc.field or "").removeprefix("--set ") or None) from None
        spec = type(self).validate_raw(changed)
        chooser = next(c for c in type(self).__mro__                      # the class that dispatches
                       if isinstance(c, type) and issubclass(c, TemplateSpec) and "validate_raw" in c.__dict__)
        if not isinstance(spec, chooser):
            raise SpecError(f"{type(spec).noun}, not {chooser.noun}", "template")
        return cast(Self, spec)             # of this class, or (a linkage's new type) of its chooser's

    @classmethod
    def _own(cls, spec: TemplateSpec) -> Self:
        """``spec`` where it is of this class, else a one-line :class:`SpecError` naming ``template``."""
        if not isinstance(spec, cls):
            raise SpecError(f"{type(spec).noun}, not {cls.noun}", "template")
        return spec


#: the largest template file read (bytes); a template is a few kB, so more is a mistake (or /dev/zero)
MAX_TEMPLATE_BYTES = 1_000_000
#: how many templates a chain of ``base`` includes may hold
MAX_BASES = 16
#: how deeply tables and arrays may nest in a template (the deepest a template needs is about 4)
MAX_DEPTH = 32


def _depth(value: Any) -> int:
    """How deeply ``value``'s tables and arrays nest (0 for a plain value), without recursion."""
    deepest, stack = 0, [(value, 0)]
    while stack:
        node, depth = stack.pop()
        children = node.values() if isinstance(node, dict) else node if isinstance(node, list) else None
        if children is not None:
            deepest = max(deepest, depth + 1)
            stack.extend((child, depth + 1) for child in children)
    return deepest


def _read_toml(path: Path, field: str) -> dict[str, Any]:
    """One TOML file as a mapping (a UTF-8 byte-order mark allowed), or a one-line error naming ``field``."""
    try:
        data = read_regular(path, MAX_TEMPLATE_BYTES)
    except FileNotFoundError:
        raise SpecError(f"no such file: {path}", field) from None
    except IsADirectoryError:
        raise SpecError(f"{path} is a folder, not a template file", field) from None
    except NotRegularFile as exc:
        raise SpecError(f"{path} is {exc.strerror}; a template is a TOML file", field) from None
    except OSError as exc:
        raise SpecError(f"cannot read {path}: {exc.strerror or exc}", field) from None
    if len(data) > MAX_TEMPLATE_BYTES:
        raise SpecError(f"{path} is larger than {MAX_TEMPLATE_BYTES // 1000} kB; a template is a small TOML file",
                        field)
    try:
        raw = tomllib.loads(data.decode("utf-8-sig"))
    except UnicodeDecodeError:
        raise SpecError(f"{path} is not a text file (not UTF-8)", field) from None
    except tomllib.TOMLDecodeError as exc:
        raise SpecError(f"{path} is not valid TOML: {exc}", field) from None
    except RecursionError:
        raw = None
    if raw is None or _depth(raw) > MAX_DEPTH:
        raise SpecError(f"{path} nests arrays or tables more than {MAX_DEPTH} deep; a template needs a few levels",
                        field)
    return raw


def _with_base(path: Path, seen: set) -> dict:
    if path.resolve() in seen:
        raise SpecError(f"{path.name} includes itself", "base")
    if len(seen) >= MAX_BASES:
        raise SpecError(f"more than {MAX_BASES} templates in a chain of includes", "base")
    field = "base" if seen else "template"             # the first file read is the template itself
    seen.add(path.resolve())
    raw = _read_toml(path, field)
    base = raw.pop("base", None)
    if base is None:
        return raw
    if not isinstance(base, str) or not base.strip():
        raise SpecError(f"must be the file name of a template, relative to {path.name} (got {base!r})", "base")
    return merge(_with_base(path.parent / base, seen), raw)


def merge(base: Mapping[str, Any], top: Mapping[str, Any]) -> dict[str, Any]:
    """``top`` over ``base``: tables merge key by key, everything else (lists included) replaces."""
    out = copy.deepcopy(dict(base))
    for key, value in top.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


_WORDS = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}


def _path(loc: tuple) -> str:
    text = ""
    for part in loc:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


def _unwrap(annotation: Any) -> Any:
    """The model a field holds, inside ``Optional``, lists, tuples and tables (``dict`` values), or the annotation
    itself when it holds none."""
    queue = [annotation]
    while queue:
        inner = queue.pop(0)
        if isinstance(inner, type) and issubclass(inner, BaseModel):
            return inner
        queue.extend(getattr(inner, "__args__", ()))
    return annotation


def _literals(annotation: Any) -> tuple[str, ...]:
    """The strings a field's ``Literal`` allows (inside ``Optional``, lists and tuples), in their order."""
    out: list[str] = []
    queue = [annotation]
    while queue:
        inner = queue.pop(0)
        if get_origin(inner) is Literal:
            out += [a for a in get_args(inner) if isinstance(a, str) and a not in out]
        else:
            queue.extend(getattr(inner, "__args__", ()))
    return tuple(out)


def _list_spelling(loc: tuple, info: Any, given: Any) -> str:
    """How a list-valued field at ``loc`` is written, in a template and with ``--set`` (whose shell needs the quotes),
    for a user who gave ``given``: the value itself in brackets where the list takes it as an item, else the field's
    default, else ``[...]``; just ``[...]`` for a list inside a list."""
    shape = _list_shape(info.annotation) if info is not None else None
    if shape is None or not loc or not isinstance(loc[-1], str):
        return "[...]"
    variable, items = shape
    default = info.default if isinstance(info.default, (list, tuple)) and info.default else None
    fits = _plain(given) and items is not None and (items == () or given in items)
    if variable and fits:
        example = _toml([given])
    elif default is not None:
        example = _toml(default)
    elif fits:
        example = f"[{_toml(given)}, ...]"
    else:
        example = "[...]"
    return f"{loc[-1]} = {example} in the template, --set '{_path(loc)}={example}' on the command line"


def _list_shape(annotation: Any) -> tuple[bool, tuple[str, ...] | None] | None:
    """For the first list or tuple a field's annotation holds (inside ``Optional``): whether it takes any number of
    items, and what its items may be: the strings of a ``Literal``, () for any plain value (a number, a string, true
    or false), None for lists or tables; None for no list at all."""
    queue = [annotation]
    while queue:
        inner = queue.pop(0)
        origin, args = get_origin(inner), get_args(inner)
        if origin in (list, tuple):
            variable = origin is list or (len(args) == 2 and args[1] is Ellipsis)
            item = args[0] if args else Any
            nested = get_origin(item) in (list, tuple, dict) or (isinstance(item, type) and issubclass(item, BaseModel))
            return variable, None if nested else _literals(item)
        queue.extend(args)
    return None


def _plain(value: Any) -> bool:
    """Whether ``value`` is one plain TOML value (a finite number, a string, true or false)."""
    return isinstance(value, (str, bool, int)) or (isinstance(value, float) and value == value and abs(value) < 1e308)


def _toml(value: Any) -> str:
    """``value`` (plain values and lists of them) as TOML text."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    if isinstance(value, float):
        return f"{value:g}" if value == int(value) and abs(value) < 1e15 else repr(value)
    return json.dumps(value) if isinstance(value, str) else str(value)


def _keyed(annotation: Any) -> bool:
    """Whether a field is a table of the user's own keys (a ``dict``, maybe ``Optional``)."""
    return get_origin(annotation) is dict or any(get_origin(a) is dict for a in getattr(annotation, "__args__", ()))


def _field(root: type[BaseModel], loc: tuple, chosen: Mapping[tuple, Any] | None = None) -> Any:
    """The pydantic FieldInfo at ``loc`` below the ``root`` model, or None (list indices and the user's own keys of
    a table of tables are passed over); ``chosen`` holds the member a tagged union's field took, by its location
    (:func:`_tagged_members`)."""
    model: Any = root
    info = None
    key = False
    for depth, part in enumerate(loc):
        if isinstance(part, int) or key:
            key = False
            continue
        fields = getattr(model, "model_fields", None)
        if not fields or part not in fields:
            return None
        info = fields[part]
        model, key = _unwrap(info.annotation), _keyed(info.annotation)
        model = (chosen or {}).get(loc[:depth + 1], model)
    return info


def _either(names: list[str]) -> str:
    """``a``, ``a or b``, ``a, b or c``."""
    return " or ".join((", ".join(names[:-1]), names[-1])) if len(names) > 1 else "".join(names)


def _tag_members(info: Any) -> dict[str, Any]:
    """The members of a field's union chosen by a discriminating key (a follower's ``type``), by their tag; empty
    for any other field."""
    if info is None or not isinstance(info.discriminator, str):
        return {}
    members = {}
    for member in get_args(info.annotation):
        tag = getattr(member, "model_fields", {}).get(info.discriminator)
        for value in get_args(tag.annotation) if tag is not None else ():
            members[value] = member
    return members


def _tagged_members(root: type[BaseModel], loc: tuple) -> tuple[tuple, dict[tuple, Any]]:
    """``loc`` without the tags pydantic puts after a tagged union's field (``('follower', 'knife-edge', 'offset')``
    is ``('follower', 'offset')``), and the member each such field took, by its location in the location returned."""
    out: list[Any] = []
    chosen: dict[tuple, Any] = {}
    members: dict[str, Any] = {}
    for part in loc:
        if isinstance(part, str) and part in members:
            chosen[tuple(out)] = members[part]
            members = {}
            continue
        out.append(part)
        members = _tag_members(_field(root, tuple(out), chosen))
    return tuple(out), chosen


def _models_below(root: Any) -> set[str]:
    """The class names of every model a field of ``root`` may hold (through unions, lists and dicts)."""
    names, stack = set(), [root]
    while stack:
        annotation = stack.pop()
        if isinstance(annotation, type) and issubclass(annotation, BaseModel):
            if annotation.__name__ in names:
                continue
            names.add(annotation.__name__)
            stack.extend(f.annotation for f in annotation.model_fields.values())
        stack.extend(getattr(annotation, "__args__", ()))
    return names


#: the tags pydantic gives a union's plain members in an error's location (``str | list[...]``); no template key is
#: named so
_PLAIN_TAGS = frozenset({"str", "int", "float", "bool", "none", "list", "dict"})


#: the keys that choose a table (a cam's ``kind``, a follower's ``type``), left out of what a kind's table takes
TAGS = frozenset({"kind", "type"})


def _union_tag(part: Any, root: type[BaseModel]) -> bool:
    """Whether a pydantic error location's ``part`` names a member of a union (``function-after[...]``,
    ``tuple[...]``, a model's class name) rather than a key of the template."""
    return isinstance(part, str) and (re.fullmatch(r"[\w-]+\[.*\]", part) is not None or part in _PLAIN_TAGS
                                      or part in _models_below(root))


def _first_error(exc: ValidationError, root: type[BaseModel]) -> SpecError:
    errors = exc.errors(include_url=False)
    # an unknown key first: a misspelt required key is also reported missing, and the spelling is the news
    err = next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])
    # the first part is always a key of the template (a user's key may look like a tag: motion[0])
    tagless, chosen = _tagged_members(root, tuple(err["loc"]))
    loc = tuple(part for i, part in enumerate(tagless) if i == 0 or not _union_tag(part, root))
    kind, ctx = err["type"], err.get("ctx", {})
    given = err.get("input")
    info = _field(root, loc, chosen)
    unit = ((info.json_schema_extra or {}) if info is not None else {}).get("unit", "")
    got = f" (got {given!r})" if not isinstance(given, (dict, list)) else ""
    if kind in _WORDS:
        bound = ctx[{"greater_than": "gt", "greater_than_equal": "ge", "less_than": "lt",
                     "less_than_equal": "le"}[kind]]
        bounds = [f"{_WORDS[k]} {getattr(m, a):g}" for k, a in (("greater_than", "gt"), ("greater_than_equal", "ge"),
                                                               ("less_than", "lt"), ("less_than_equal", "le"))
                  for m in (info.metadata if info is not None else []) if getattr(m, a, None) is not None]
        rule = " and ".join(bounds) if bounds else f"{_WORDS[kind]} {bound:g}"
        msg = f"must be {rule}{' ' + unit if unit else ''}{got}"
    elif kind == "finite_number":
        msg = f"must be a finite number{' of ' + unit if unit else ''}{got}"
    elif kind == "missing":
        what = info.description if info is not None and info.description else "a value"
        msg = f"missing: give {what}{' in ' + unit if unit else ''}"
    elif kind == "extra_forbidden":
        parent = _field(root, loc[:-1], chosen)
        model = chosen.get(loc[:-1], _unwrap(parent.annotation) if parent is not None else root)
        known = list(getattr(model, "model_fields", {}))
        close = difflib.get_close_matches(str(loc[-1]), known, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        title = getattr(model, "model_config", {}).get("title")
        if title:           # a kind's own table: it names the kind and what it takes (not its tag)
            takes = ", ".join(k for k in known if k not in TAGS)
            msg = f"not a key of {title}{hint}; it takes: {takes}"
        else:
            msg = f"unknown key{hint}; known keys here: {', '.join(known)}"
    elif kind == "union_tag_invalid":       # a follower's type the kind does not drive, or a misspelt one
        tag, tags = ctx.get("discriminator", "'type'").strip("'"), list(_tag_members(info))
        value = ctx.get("tag")
        # a typo of one of them is as near as 0.9 ('translating-rolle'); another type is not ('translating-flat' is
        # 0.76 from 'translating-roller')
        msg = not_one_of(value, tags) if difflib.get_close_matches(str(value), tags, n=1, cutoff=0.9) else \
            f"{getattr(root, 'noun', 'this template')} takes {_either(tags)} (got {value!r})"
        loc = (*loc, tag)
    elif kind == "union_tag_not_found":
        tag = ctx.get("discriminator", "'type'").strip("'")
        msg = f"missing: give one of {', '.join(_tag_members(info))}"
        loc = (*loc, tag)
    elif kind == "literal_error":
        allowed = _literals(info.annotation) if info is not None else ()
        msg = not_one_of(given, allowed) if allowed else f"must be one of {ctx.get('expected')}{got}"
    elif kind in ("float_type", "float_parsing", "int_type", "int_parsing", "int_from_float"):
        msg = f"must be a {'whole ' if kind.startswith('int') else ''}number{' of ' + unit if unit else ''}{got}"
    elif kind in ("tuple_type", "list_type"):
        msg = f"must be a list, e.g. {_list_spelling(loc, info, given)}{got}"
    elif kind in ("model_type", "model_attributes_type", "dict_type"):
        msg = f"must be a table of keys, e.g. {{...}}{got}"
    elif kind == "too_short":
        msg = f"needs at least {ctx.get('min_length')} item(s)"
    elif kind == "string_pattern_mismatch":
        msg = f"must be letters, digits, '.', '_' or '-', starting with a letter or digit{got}"
    elif kind == "value_error":
        text = str(ctx.get("error", err["msg"]))
        head, sep, rest = text.partition(": ")
        if sep and " " not in head:  # the validator named a field below loc
            loc = loc + tuple(int(p) if p.isdigit() else p for p in head.replace("[", ".").replace("]", "")
                              .split("."))
            text = rest
        return SpecError(text, _path(loc) or None)
    else:
        msg = f"{err['msg'][0].lower()}{err['msg'][1:]}{got}"
    return SpecError(msg, _path(loc) or None)

