"""Cam specs: the validated, frozen description of one cam.

A template is a TOML file (or the same mapping from Python); :func:`load_spec`
reads it, merges ``--set`` overrides into the raw mapping, then validates it all at
once into the spec of the kind it names (:func:`validate_spec`: the registry, :func:`camgen.kinds.kind_for`,
chooses the kind, whose package holds its spec, a :class:`CamSpec`); every problem becomes a
:class:`~camgen.core.errors.SpecError` whose message names the field, what is allowed and what was given, e.g.
``motion[2].angle: must be > 0 degrees (got -30)``. No kind is named here: this module and the registry form one
layer of the flow, the specs of the kinds deriving from :class:`CamSpec`, whose validation dispatches through the
registry.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Literal

from pydantic import Field, model_validator

from camgen.laws import LAW_NAMES, LAW_PARAMS
from camgen.laws.base import MAX_NORMALISED
from camgen.core.spec import (MAX_LENGTH_MM, Model, check_kind, length, name_field, notes, read_template, unit,
                              validate)
from camgen.core.errors import SpecError
from camgen.core.features import MIN_WEB_MM, key_for, web_refusal
from camgen.core.spec import CutOutputTable, TemplateSpec
from camgen.kinds import CAM_TABLE, KINDS, kind_for, table_keys
from camgen.rig import Mount, disc_mount
from camgen.tables import CamBody, FlatCamBody
from camgen.tables.followers import AnyFollower, Offset
from camgen.tables.rows import MAX_TABLE_ROWS, read_table

if TYPE_CHECKING:
    from camgen.kinds.base import Kind

LawName = Literal[LAW_NAMES]  # type: ignore[valid-type]
#: every law parameter key a segment may carry
LAW_PARAMS_ALL = sorted({k for keys in LAW_PARAMS.values() for k in keys})


class SegmentTable(Model):
    """One segment of the motion program; law parameters sit beside the law name."""

    type: Literal["rise", "dwell", "return"] = Field(description="segment type")
    angle: float = Field(gt=0, le=360, description="cam angle of the segment",
                         json_schema_extra=unit("degrees", allowed="the segments' angles add up to 360"))
    lift: float | None = Field(None, gt=0, le=MAX_LENGTH_MM, description="follower travel (rise and return)",
                               json_schema_extra=unit("mm, or degrees of arm swing for an oscillating follower",
                                                      allowed="an arm's swing < 90 degrees",
                                                      absent="required for a rise or return"))
    law: LawName | None = Field(None, description="motion law (rise and return)",
                                json_schema_extra=notes(absent="required for a rise or return"))
    ratio: float | None = Field(None, ge=0.01, le=100, description="parabolic: acceleration ratio a1/a2",
                                json_schema_extra=notes(absent="1"))
    form: Literal["blended", "drafted"] | None = Field(None, description="modified-uniform: form",
                                                       json_schema_extra=notes(absent='"blended"'))
    blend: float | None = Field(None, gt=0, le=0.5, description="modified-uniform blended: blend fraction of the angle",
                                json_schema_extra=notes(absent="0.25"))
    blend_law: Literal["cycloidal", "parabolic"] | None = Field(None, description="modified-uniform blended: blends",
                                                                json_schema_extra=notes(absent='"cycloidal"'))
    conditions: list[tuple[float, int, float]] | None = Field(
        None, max_length=26, description="polynomial: [u, derivative order, value] in normalised units",
        json_schema_extra=notes(allowed="the order-th derivative of f = s / h with respect to u = theta / beta "
                                "equals value at u; must include [0, 0, 0] and [1, 0, 1] and fix the polynomial; f, "
                                f"f', f'', f''' within {MAX_NORMALISED:g} on [0, 1]",
                                absent='required for law "polynomial"'))
    degree: int | None = Field(None, ge=1, le=25, description="polynomial: degree (default: conditions - 1)",
                               json_schema_extra=notes(absent="the number of conditions - 1"))
    points: list[tuple[float, float]] | None = Field(
        None, max_length=1000, description="spline: [u, f] points in normalised units from [0, 0] to [1, 1]",
        json_schema_extra=notes(allowed="[u, f]: fractions of the angle and of the lift, from [0, 0] to [1, 1], u "
                                f"increasing; f, f', f'', f''' within {MAX_NORMALISED:g} on [0, 1]",
                                absent='required for law "spline"'))
    ends: Literal["dwell", "natural"] | None = Field(
        None, description="spline, table: end conditions",
        json_schema_extra=notes(allowed="dwell: zero velocity and acceleration at both ends; natural: free",
                                absent='"dwell"'))
    file: str | None = Field(None, max_length=1000, description="table: a CSV of angle (degrees from the segment's "
                             "start), displacement above the segment's low end",
                             json_schema_extra=notes(allowed="relative to the template; at most 10000 rows and 2 MB; "
                                                     "a first line of names and lines starting with # are passed "
                                                     "over", absent='required for law "table" (or data)'))
    data: list[tuple[float, float]] | None = Field(
        None, min_length=4, max_length=MAX_TABLE_ROWS, description="table: [angle, value] rows (degrees, lift's unit)")
    continuity: int | None = Field(None, ge=2, le=4, description="table: the fitted spline's continuity inside the "
                                                                 "segment (2: acceleration, 3: jerk, 4)",
                                   json_schema_extra=notes(absent="3"))
    fit_tolerance: float | None = Field(None, gt=0, le=MAX_LENGTH_MM, description="table: how far a row may lie from "
                                        "the fitted spline",
                                        json_schema_extra=unit("mm, or degrees of arm swing", absent="0.01"))
    load: float | None = Field(None, ge=-1e6, le=1e6, description="an external force pressing the follower onto the "
                               "cam over this segment, constant (added to follower.load; the alternative to "
                               "follower.load_table)",
                               json_schema_extra=unit("N", allowed="not with follower.load_table"))

    @model_validator(mode="before")
    @classmethod
    def _read_file(cls, data: Any) -> Any:
        """A table law's ``file`` read into its ``data`` (a path relative to the current folder; :func:`load_spec`
        makes a template's relative to the template)."""
        if isinstance(data, Mapping) and isinstance(data.get("file"), str) and data.get("data") is None:
            return {**data, "data": read_table(Path(data["file"]))}
        return data

    @model_validator(mode="after")
    def _fits_type(self) -> "SegmentTable":
        params = {k for k in LAW_PARAMS_ALL if getattr(self, k) is not None}
        if self.type == "dwell":
            extra = sorted(({"lift", "law"} | params) & self.model_fields_set)
            if extra:
                raise ValueError(f"{extra[0]}: a dwell takes only 'angle'")
            return self
        if self.lift is None:
            raise ValueError(f"lift: required for a {self.type} (mm, > 0)")
        if self.law is None:
            raise ValueError(f"law: required for a {self.type}; one of {', '.join(LAW_NAMES)}")
        if self.file is not None and self.law != "table":
            raise ValueError(f"file: only for law 'table' (got law '{self.law}')")
        allowed = set(LAW_PARAMS[self.law])
        for key in sorted(params - allowed):
            takes = ", ".join(LAW_PARAMS[self.law]) or "none"
            raise ValueError(f"{key}: not a parameter of law '{self.law}' (its parameters: {takes})")
        if self.law == "polynomial" and self.conditions is None:
            raise ValueError("conditions: required for law 'polynomial' ([[u, order, value], ...])")
        if self.law == "spline" and self.points is None:
            raise ValueError("points: required for law 'spline' ([[u, f], ...] from [0, 0] to [1, 1])")
        if self.law == "table" and self.data is None:
            raise ValueError("file: required for law 'table' (a CSV of angle, value rows), or give data")
        return self

    def law_params(self) -> dict[str, Any]:
        """The law parameters given for this segment."""
        return {k: getattr(self, k) for k in LAW_PARAMS.get(self.law or "", ()) if getattr(self, k) is not None}


class HubTable(Model):
    """Hub features: a keyed bore, a boss with a set screw (printed part only), bolt-circle holes, engraving."""

    keyway: bool = Field(False, description="cut a DIN 6885-1 keyway for the bore",
                         json_schema_extra=notes(allowed="cam.bore over 6 up to 110 mm; output.kerf below the key's "
                                                 "width"))
    boss_diameter: float = length("printed hub boss diameter, 0 for none", 0.0, zero=True,
                                  allowed="> cam.bore, with boss_height; not on a grooved cam")
    boss_height: float = length("printed hub boss height above the cam", 0.0, zero=True, le=1000.0,
                                allowed="with boss_diameter")
    set_screw: float = length("radial set-screw hole diameter through the boss, 0 for none", 0.0, zero=True,
                              allowed="< boss_height")
    bolt_circle: float = length("mounting-hole circle diameter", 0.0, zero=True,
                                allowed=f"the holes stay inside the cam and keep {MIN_WEB_MM:g} mm of material "
                                        "between any two (the bore, its keyway, the bolt holes), as drawn and as "
                                        "printed")
    bolt_holes: int = Field(0, ge=0, le=36, description="number of mounting holes",
                            json_schema_extra=notes(allowed="the first on +X; with bolt_circle and "
                                                    "bolt_hole_diameter"))
    bolt_hole_diameter: float = length("mounting-hole diameter", 0.0, zero=True)
    engrave: bool = Field(False, description="add an ENGRAVE layer: name, rotation arrow, theta = 0 mark")

    @model_validator(mode="after")
    def _consistent(self) -> "HubTable":
        if (self.boss_diameter > 0) != (self.boss_height > 0):
            raise ValueError("boss_height: give both boss_diameter and boss_height (mm), or neither")
        if self.set_screw > 0 and not (self.boss_height > 0 and self.set_screw < self.boss_height):
            raise ValueError(f"set_screw: needs a boss taller than the screw ({self.set_screw:g} mm)")
        if self.bolt_holes > 0 and not (self.bolt_circle > 0 and self.bolt_hole_diameter > 0):
            raise ValueError("bolt_circle: bolt holes need bolt_circle and bolt_hole_diameter (mm)")
        return self


class OutputTable(CutOutputTable):
    """What to write and how accurately: the shared keys (formats, DXF flavour and version), the outline's
    tolerance, the laser's kerf and the printer's clearance, and how the outline's curves are written."""

    curves: Literal["polylines", "biarcs"] = Field("polylines", description="how curved stretches are written")


class CamSpec(TemplateSpec):
    """A whole cam template, validated: the base of every cam kind's spec, which its package holds
    (``camgen/kinds/<kind>/table.py``), naming its own ``[cam]`` table and the followers it drives;
    ``CamSpec.from_toml`` and :func:`validate_spec` give the spec of the kind a template names (by the registry,
    :func:`camgen.kinds.kind_for`).

    Made by :func:`validate_spec` or :func:`load_spec` from a template (every key, its unit, range and default:
    the template reference); frozen. A kind's spec built with its constructor is validated the same way.

    Parameters
    ----------
    name : str
        The part's name, used for its files: letters, digits, ``.``, ``_``, ``-``.
    cam : table
        The cam body, its kind's ``[cam]`` table (built from :mod:`camgen.tables`): its size, bore, rotation, sizing
        limits and speed.
    follower : AnyFollower
        The follower: its type, geometry, mass, spring and loads, the table of its ``type`` among those the kind
        drives (:mod:`camgen.tables.followers`).
    motion : list of SegmentTable
        The segments in order from theta = 0, their angles adding up to 360 degrees.
    hub : HubTable, optional
        Keyway, boss, set screw, bolt holes, engraving.
    output : OutputTable, optional
        Formats, tolerance, kerf, clearance and the files' flavours.

    Raises
    ------
    pydantic.ValidationError
        A kind's spec built with its constructor, from a template that fails validation (:func:`validate_spec` turns
        the first problem into a one-line :class:`~camgen.core.errors.SpecError` instead).
    """

    name: str = name_field("part")
    if TYPE_CHECKING:
        cam: CamBody                                # what every kind's table gives, for the shared checks
    else:
        cam: Any                                    # a kind's spec names its own [cam] table
    follower: AnyFollower
    motion: list[SegmentTable] = Field(min_length=1, description="segments in order from theta = 0")
    hub: HubTable = HubTable()
    output: OutputTable = OutputTable()

    product: ClassVar[str] = "camgen"
    noun: ClassVar[str] = "a cam"

    @classmethod
    def validate_raw(cls, raw: Mapping[str, Any], folder: Path | None = None) -> TemplateSpec:
        """The spec of the kind ``raw`` describes (:func:`validate_spec`: another kind's for a table of its own),
        each table law's ``file`` read from ``folder`` (None: the current folder)."""
        return validate_spec(raw if folder is None else _tables_beside(dict(raw), folder))

    @model_validator(mode="after")
    def _whole(self) -> "CamSpec":
        total = sum(seg.angle for seg in self.motion)
        if abs(total - 360.0) > 1e-9:
            raise ValueError(f"motion: segment angles add up to {total:.6g} degrees; they must add up to 360")
        prime = self.prime_radius
        if isinstance(self.follower, Offset) and not abs(self.follower.offset) < prime:
            raise ValueError(f"follower.offset: |offset| must be < the prime radius {prime:.6g} mm "
                             f"(base_radius + roller_radius; got {self.follower.offset:.6g} mm)")
        self.kind_rules()
        hub = self.hub
        if hub.keyway and not 6 < self.cam.bore <= 110:
            raise ValueError(f"hub.keyway: DIN 6885-1 keys need a bore over 6 up to 110 mm (cam.bore is "
                             f"{self.cam.bore:g} mm)")
        if hub.keyway and self.output.kerf >= (key := key_for(self.cam.bore)[0]):
            raise ValueError(f"output.kerf: must be < {key:g} mm with hub.keyway, the width of the keyway of a "
                             f"{self.cam.bore:g} mm bore, which a wider kerf burns away (got {self.output.kerf:g})")
        if hub.bolt_holes and (why := web_refusal(self.cam.bore, hub.keyway, hub.bolt_circle, hub.bolt_holes,
                                                  hub.bolt_hole_diameter, self.output.clearance)) is not None:
            raise why
        if hub.boss_diameter and hub.boss_diameter <= self.cam.bore:
            raise ValueError(f"hub.boss_diameter: must be larger than the bore ({self.cam.bore:g} mm)")
        if self.follower.oscillating:
            for i, seg in enumerate(self.motion):
                if seg.lift is not None and seg.lift >= 90:
                    raise ValueError(f"motion[{i}].lift: an arm swing must be < 90 degrees (got {seg.lift:.6g})")
        if self.cam.rpm_range is not None:
            lo, hi = self.cam.rpm_range
            if not 0 < lo < hi <= 100_000:
                raise ValueError(f"cam.rpm_range: give [lowest, highest] with 0 < lowest < highest <= 100000 rpm "
                                 f"(got [{lo:g}, {hi:g}])")
            for needed, value in (("cam.rpm", self.cam.rpm), ("follower.mass", self.follower.mass)):
                if value is None:
                    raise ValueError(f"cam.rpm_range: needs {needed} (the report's forces are at cam.rpm, with the "
                                     "follower's mass)")
        loaded = [i for i, seg in enumerate(self.motion) if seg.load is not None]
        if loaded and self.follower.load_table is not None:
            raise ValueError(f"motion[{loaded[0]}].load: give loads per segment or follower.load_table, not both")
        return self

    def kind_rules(self) -> None:
        """The rules of this kind that its tables cannot check alone (a rule across two tables, or one of
        geometry): a ``ValueError("field: why")`` for the first broken. Called by the spec's validation after the
        motion's and the offset's checks and before the hub's; none here, a kind's spec says its own."""

    def mount(self) -> Mount:
        """How the cam carries its follower (:mod:`camgen.rig`): a disc's, turning in ``cam.rotation``'s sense; a kind
        whose cam is not a disc turning about its centre says its own."""
        return disc_mount(self.follower, self.cam.rotation)

    def follower_at(self, base_radius: Any, roller_radius: float) -> Any:
        """The follower on this cam of base radius ``base_radius`` (mm) under a roller of ``roller_radius`` (mm; 0 for
        a knife edge or a flat face), for :func:`camgen.flat.build_cam`: on its :meth:`mount`."""
        return self.mount().at(base_radius, roller_radius)

    @property
    def base_circle(self) -> float | Literal["auto"] | None:
        """``cam.base_radius`` as given (mm, or ``"auto"``); None for a cam without a base circle (a barrel): here,
        a flat cam's spec says its own."""
        return None

    def rest_height(self, roller_radius: float) -> float:
        """For a cam without a base circle (:attr:`base_circle` None), what its cam is built on instead (mm): a
        barrel's developed plate's height under a roller of ``roller_radius`` mm. A kind without one says its own."""
        raise SpecError("give the cam's base radius (cam.base_radius)", "cam.base_radius")

    @property
    def kind(self) -> str:
        """The cam's kind, ``cam.kind`` (the registry's key, :data:`camgen.kinds.KINDS`)."""
        return self.cam.kind

    @property
    def prime_radius(self) -> float:
        """Base radius plus the roller's (mm): the circle the roller's centre rides at rest (inf while "auto", and
        for a cam without a base circle, a barrel)."""
        rb = self.base_circle
        return (rb if isinstance(rb, float) else math.inf) + self.follower.contact_radius


class FlatSpec(CamSpec):
    """The spec of a cam cut from a flat plate (every kind but the barrel: a disc, a plate, a grooved cam and a
    conjugate pair; :mod:`camgen.flat` designs and sizes them): its base circle is its table's."""

    if TYPE_CHECKING:
        cam: FlatCamBody

    @property
    def base_circle(self) -> float | Literal["auto"]:
        return self.cam.base_radius


def cam_specs() -> dict[str, type[CamSpec]]:
    """Every kind chosen by ``cam.kind``'s spec by the kind's name, in the registry's order (each imported)."""
    return {name: kind.spec for name, kind in KINDS.items() if kind.table_key == CAM_TABLE}


def validate_spec(raw: Mapping[str, Any]) -> TemplateSpec:
    """The spec of the kind the raw template ``raw`` describes (:func:`camgen.kinds.kind_for`): a :class:`CamSpec`
    of the kind its ``cam.kind`` names, or the spec of the kind whose own table it has (a Geneva drive's for a
    ``[geneva]`` table); its ``output.formats`` checked against those the kind writes.

    Parameters
    ----------
    raw : mapping
        The template as TOML reads it: ``{"name": ..., "cam": {...}, "follower": {...}, "motion": [...]}``.

    Returns
    -------
    TemplateSpec
        The validated, frozen spec of the kind (a :class:`CamSpec` for a ``[cam]`` table).

    Raises
    ------
    SpecError
        The first problem, in one line naming the key, what is allowed and what was given
        (``motion[0].lift: must be > 0 and <= 10000 mm (got -1)``); a format the kind does not write
        (``output.formats: a barrel cam has no flat part to write as an exact STEP solid ...``).
    """
    kind = kind_for(raw)
    try:
        spec = validate(kind.spec, raw)
    except SpecError as exc:
        raise _owned(exc, kind) from None
    refused = [fmt for fmt in spec.output.formats if fmt not in kind.formats]
    if refused:
        raise SpecError(kind.format_refusal(refused[0]), "output.formats")
    return spec


def _owned(exc: SpecError, kind: Kind[Any, Any]) -> SpecError:
    """``exc`` with the kinds whose table has its key named, where it refuses a key of ``kind``'s table that another
    kind takes (``cam.pitch_radius: not a key of a disc cam (a key of cam.kind = "barrel"); it takes: ...``)."""
    table, _, key = (exc.field or "").partition(".")
    if table != kind.table_key or not key.isidentifier() or not exc.detail.startswith("not a key of"):
        return exc
    cams = [f'"{name}"' for name, other in KINDS.items() if other.table_key == CAM_TABLE and key in table_keys(other)]
    where = [("" if table == CAM_TABLE else f"[{CAM_TABLE}] with ") + "cam.kind = " + _either(cams)] if cams else []
    where += [f"[{other.table_key}], {other.title}" for other in KINDS.values()
              if other.table_key not in (CAM_TABLE, table) and key in table_keys(other)]
    if not where:
        return exc
    head, sep, rest = exc.detail.partition(";")
    head = head.split(" (did you mean")[0]
    return SpecError(f"{head} (a key of {' or '.join(where)}){sep}{rest}", exc.field)


def _either(names: list[str]) -> str:
    """``"a"``, ``"a" or "b"``, ``"a", "b" or "c"``."""
    return " or ".join((", ".join(names[:-1]), names[-1])) if len(names) > 1 else names[0]


def load_spec(path: str | Path, overrides: Iterable[str] = ()) -> TemplateSpec:
    """Read a TOML cam (or Geneva) template (and its ``base``), merge ``key=value`` overrides, validate.

    Parameters
    ----------
    path : str or Path
        The template file. Relative paths inside it (its ``base``, a table law's ``file``) are relative to it.
    overrides : iterable of str
        ``"key=value"`` strings, as ``--set`` takes them (``"motion.0.lift=25"``, values read as TOML), merged
        into the template before validation.

    Returns
    -------
    TemplateSpec
        The validated spec (see :func:`validate_spec`).

    Raises
    ------
    SpecError
        The file cannot be read, is a template of another command, or fails validation (one line naming the key).
    """
    raw = read_template(path, overrides)
    check_kind(raw, "camgen")
    return validate_spec(_tables_beside(raw, Path(path).parent))


def _tables_beside(raw: dict[str, Any], folder: Path) -> dict[str, Any]:
    """``raw`` with each table law's relative ``file`` read from ``folder`` (the template's) into its ``data``;
    ``file`` stays as the user wrote it (the report names it so, wherever the template lies); the files its kind
    names made to lie beside it (:meth:`camgen.kinds.base.Kind.beside`: a machine's mounts)."""
    raw = kind_for(raw).beside(raw, folder)
    follower = raw.get("follower")
    if isinstance(follower, dict) and isinstance(follower.get("load_table"), str):
        try:
            raw = {**raw, "follower": {**follower, "load_table": read_table(folder / follower["load_table"])}}
        except ValueError as exc:
            raise SpecError(str(exc).removeprefix("file: "), "follower.load_table") from None
    motion = raw.get("motion")
    if not isinstance(motion, list):
        return raw
    segments = []
    for i, seg in enumerate(motion):
        if isinstance(seg, dict) and isinstance(seg.get("file"), str) and seg.get("data") is None:
            try:
                seg = {**seg, "data": read_table(folder / seg["file"])}
            except ValueError as exc:
                raise SpecError(str(exc).removeprefix("file: "), f"motion[{i}].file") from None
        segments.append(seg)
    return {**raw, "motion": segments}
