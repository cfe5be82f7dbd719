"""The machine's template: a ``[machine]`` table (the main shaft and its speed), ``[[shafts]]``, ``[[gears]]``,
``[[cams]]``, ``[[linkages]]`` and ``[[couplings]]``, validated into a frozen :class:`MachineSpec`.

Each cam is a cam template in its own terms (``template``: an inline table, or the path of a cam template file,
relative to the machine template's folder: :mod:`camgen.kinds.machine.mounts`) mounted on a shaft at a ``phase``
and a ``layer``; each linkage a linkgen template likewise. The machine names every sub-template
``<machine>-<mount>`` (its files' names) and sets each cam's ``cam.rpm`` to its shaft's speed. Every
cross-reference is checked here, one :class:`SpecError` naming the field: a shaft, cam, linkage or link that does
not exist, two cams on one shaft at one layer, a gear pair whose shafts lie at another distance than its pitch
circles need, a coupling loop (a shaft driven twice, or round a ring of gears).
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from functools import cached_property
from typing import Annotated, Any, ClassVar, Literal

from pydantic import ConfigDict, Field, field_validator, model_validator

from camgen.core.errors import SpecError
from camgen.core.kit import BearingChoice
from camgen.core.spec import (MAX_ALLOWANCE_MM, MAX_LENGTH_MM, NAME_PATTERN, Model, OutputTable, TemplateSpec,
                              check_kind, length, name_field, notes, read_template, unit)
from camgen.kinds.machine.barrel_parts import check_coupling as check_barrel
from camgen.kinds.machine.conjugate_parts import check_layers
from camgen.kinds.machine.indexing import check_genevas
from camgen.kinds.machine.keeptime import KeepTime
from camgen.kinds.machine.ratchet_mount import RatchetMount, check_ratchets
from camgen.kinds.machine.slider_coupling import STEMS
from camgen.kinds.machine.slider_coupling import check as check_slider
from camgen.kinds.machine.slider_coupling import check_arm

#: the most shafts, gear pairs, cams, linkages or couplings a machine may have
MAX_MOUNTS = 20
#: the largest frame margin and plate thickness (mm)
FRAME_MARGIN_MAX_MM, FRAME_THICKNESS_MAX_MM = 200.0, 50.0
#: the most layers a shaft may stack its cams in
MAX_LAYER = 50
#: how far apart (mm) a gear pair's shafts may lie from the sum of its pitch radii
GEAR_DISTANCE_TOL_MM = 0.01
#: the four-bar's links a coupling may name, and the one a follower arm can be (its input)
FOUR_BAR_LINKS = ("ground", "crank", "coupler", "rocker")
#: the follower types whose arm can be a linkage's input link
ARMS = ("oscillating-roller", "oscillating-flat")
#: the most main shaft angles the machine's figures may draw it at
MAX_FIGURE_ANGLES = 12

MountName = Field(pattern=NAME_PATTERN, description="its name: letters, digits, '.', '_', '-' (its files' names "
                  "are <machine>-<name>)")


def _template_field(description: str, allowed: str) -> Any:
    """A mount's ``template`` field: an inline template or the path of a template file (relative to the machine
    template's folder)."""
    return Field(description=f"{description} (relative to the machine template's folder; its own table laws' files "
                 "relative to it)",
                 json_schema_extra=notes(allowed=allowed))


class MachineTable(Model):
    """The machine's input: the main shaft and its speed."""

    model_config = ConfigDict(title="a machine")

    main: str = Field(description="the main shaft's name (one of [[shafts]]), the machine's input")
    rpm: float = Field(gt=0, le=10_000, description="the main shaft's speed", json_schema_extra=unit("rpm"))
    samples: int = Field(720, ge=36, le=36_000, description="shaft angles over one turn of the main shaft at which "
                         "every output, the timing diagram and the forces are evaluated")
    clash: Literal["error", "warn"] = Field("warn", description="what a clash of two moving parts (or of a part "
                                            "and a shaft or pin) over the turn is: an error (nothing written) or a "
                                            "warning in the report")
    clash_samples: int = Field(720, ge=36, le=3600, description="main shaft angles over one turn at which the clash "
                               "check places every part (a clash's first angle is then refined to 0.1 degree)")
    frame: Literal["none", "one", "two"] = Field("none", description="the frame plate carrying every shaft and "
                                                 "pivot: none, one plate under the parts, or two plates (under and "
                                                 "over the parts) held apart by spacers round the pivot pins")
    frame_margin: float = length("the frame plate's margin round every shaft and pivot (its outline: their rounded "
                                 "hull at this distance)", 12.0, le=FRAME_MARGIN_MAX_MM,
                                 allowed=">= the largest seat's radius + 2 mm of wall")
    frame_thickness: float = length("the frame plates' thickness", 6.0, le=FRAME_THICKNESS_MAX_MM)
    bearing: BearingChoice = Field("none", description="the ball bearing the frame seats every shaft in (its bore "
                                   "the shaft's diameter: the smallest cam.bore on it), or none: a plain hole the "
                                   "shaft runs in")
    assembly_angle: float = Field(0.0, ge=0, lt=360, description="the main shaft's angle at which the assembly "
                                  "(its 3MF and STEP files) places every part", json_schema_extra=unit("degrees"))
    figure_angles: tuple[Annotated[float, Field(ge=0, lt=360)], ...] = Field(
        (0.0, 90.0, 180.0, 270.0),
        description="main shaft angles at which the figures (<name>-machine.png and .svg, a panel each) draw the "
                    "whole machine and the report gives every part's pose",
        json_schema_extra=unit("degrees", allowed=f"each from 0 to under 360; 1 to {MAX_FIGURE_ANGLES} angles"))

    @field_validator("figure_angles")
    @classmethod
    def _few_angles(cls, angles: tuple[float, ...]) -> tuple[float, ...]:
        if not 1 <= len(angles) <= MAX_FIGURE_ANGLES:
            raise ValueError(f"give 1 to {MAX_FIGURE_ANGLES} angles (got {len(angles)})")
        return angles


class ShaftTable(Model):
    """A shaft: a fixed pivot on the frame."""

    name: str = Field(pattern=NAME_PATTERN, description="the shaft's name")
    at: tuple[float, float] = Field(description="the shaft's centre on the frame (x, y)",
                                    json_schema_extra=unit("mm", allowed=f"|x|, |y| <= {MAX_LENGTH_MM:g}"))

    @model_validator(mode="after")
    def _on_the_frame(self) -> ShaftTable:
        if any(abs(v) > MAX_LENGTH_MM for v in self.at):
            raise ValueError(f"at: each coordinate within +-{MAX_LENGTH_MM:g} mm (got {list(self.at)})")
        return self


class GearTable(Model):
    """A pair of external spur gears between two shafts: the driven shaft turns the other way, driver_teeth /
    driven_teeth times as fast."""

    driver: str = Field(description="the driving shaft's name")
    driven: str = Field(description="the driven shaft's name")
    driver_teeth: int = Field(ge=6, le=400, description="teeth of the driver's gear")
    driven_teeth: int = Field(ge=6, le=400, description="teeth of the driven gear")
    module: float = Field(gt=0, le=50, description="the gears' module: pitch diameter / teeth",
                          json_schema_extra=unit("mm", allowed="the shafts lie module (driver_teeth + driven_teeth) "
                                                 f"/ 2 apart (with shifts: the working centre distance), within "
                                                 f"{GEAR_DISTANCE_TOL_MM:g} mm"))
    name: str | None = Field(None, pattern=NAME_PATTERN, description="the pair's name: its gears' files are "
                             "<machine>-<name>-driver and -driven (.dxf cut, .stl printed)",
                             json_schema_extra=notes(absent="<driver>-<driven>"))
    pressure_angle: float = Field(20.0, ge=10.0, le=30.0, description="the pressure angle of the basic rack",
                                  json_schema_extra=unit("degrees"))
    backlash: float = Field(0.1, gt=0, le=50.0, description="play between the teeth along the working pitch "
                            "circles: each gear's teeth thinned by half of it",
                            json_schema_extra=unit("mm", allowed="<= pi module / 8"))
    driver_shift: float = Field(0.0, ge=-1.0, le=0.8, description="profile shift coefficient of the driver's gear "
                                "(thicker teeth, fewer without undercut)", json_schema_extra=unit("modules"))
    driven_shift: float = Field(0.0, ge=-1.0, le=0.8, description="profile shift coefficient of the driven gear",
                                json_schema_extra=unit("modules"))
    thickness: float = length("the gears' thickness (face width)", 6.0, le=FRAME_THICKNESS_MAX_MM)
    hub_diameter: float = Field(0.0, ge=0, le=MAX_LENGTH_MM, description="a printed hub round each gear's hole, "
                                "0 for none", json_schema_extra=unit("mm", allowed="> the shaft, within the root "
                                                                     "circle; with hub_height"))
    hub_height: float = Field(0.0, ge=0, le=FRAME_THICKNESS_MAX_MM, description="the hubs' height over the gears "
                              "(they fill the plane over the gears' in the clash check)",
                              json_schema_extra=unit("mm", allowed="with hub_diameter"))
    set_screw: float = Field(0.0, ge=0, le=20.0, description="a radial set-screw hole through each hub, 0 for none",
                             json_schema_extra=unit("mm", allowed="< hub_height"))
    layer: int | None = Field(None, ge=0, le=MAX_LAYER, description="the pair's plane along its shafts: plane "
                              "2 layer, as a cam's (a cam on either shaft at this layer is refused)",
                              json_schema_extra=notes(absent="the lowest plane from 0 up that no other part "
                                                      "sweeps into, nor crosses either shaft under"))


class CamMount(Model):
    """A cam on a shaft: a cam template, its phase and its layer."""

    name: str = MountName
    shaft: str = Field(description="the shaft it turns with (one of [[shafts]])")
    layer: int = Field(0, ge=0, le=MAX_LAYER, description="its plane along the shaft, 0 nearest the frame; two "
                       "cams on one shaft take different layers")
    phase: float = Field(0.0, ge=0, lt=360, description="the shaft's angle (turned from the machine's start) at "
                         "which the cam's program starts: its motion over the turn is its program shifted by this",
                         json_schema_extra=unit("degrees"))
    template: str | dict[str, Any] = _template_field("the cam: a cam template in its own terms ([cam], [follower], "
                                                     "[[motion]] as an inline table) or a cam template file's path",
                                                     "a cam of any kind, not a Geneva drive or a machine; its "
                                                     "cam.rpm is the shaft's")


class GenevaMount(Model):
    """A Geneva drive between two shafts: its driver (crank and locking disc) on ``driver``, its wheel on ``wheel``;
    the wheel shaft indexes (:mod:`camgen.kinds.machine.indexing`)."""

    name: str = MountName
    driver: str = Field(description="the shaft its driver turns with (one of [[shafts]], driven)")
    wheel: str = Field(description="the shaft its wheel turns (one of [[shafts]]; no gear pair or other Geneva "
                       "drive turns it), its centre_distance from the driver's")
    phase: float = Field(180.0, ge=-180, le=180, description="the driver's pin angle at the machine's start, from "
                         "the line from the driver's shaft to the wheel's, in the driver's sense of rotation "
                         "(counter-clockwise for a driver turning so, else clockwise): 0 mid-index, 180 mid-dwell",
                         json_schema_extra=unit("degrees"))
    layer: int | None = Field(None, ge=0, le=MAX_LAYER, description="the drive's planes along its shafts: its crank "
                              "on plane 2 layer, its locking disc and wheel on the plane over it (the clash check's; "
                              "see camgen.kinds.machine.geneva_bodies)",
                              json_schema_extra=notes(absent="the lowest two planes from 0 up that no other part "
                                                      "sweeps into, nor crosses either shaft under"))
    template: str | dict[str, Any] = _template_field("the drive: a Geneva template ([geneva]) as an inline table or "
                                                     "a Geneva template file's path",
                                                     "its geneva.rpm is the driver shaft's")


class LinkageMount(Model):
    """A linkage of the machine: a linkgen template, driven by a coupling (a follower's arm as its crank) or, with
    ``shaft``, by a crank on a shaft (its input crank turning with the shaft, its pivot on the shaft's centre)."""

    name: str = MountName
    template: str | dict[str, Any] = _template_field("the linkage: a linkgen template ([linkage], [parts]) as an "
                                                     "inline table, or a linkgen template file's path",
                                                     "driven by a coupling: a four-bar driven by its crank; driven "
                                                     "by a shaft: a type = \"linkage\" template whose one input is "
                                                     "a crank turning fully about a ground joint")
    shaft: str | None = Field(None, description="the shaft that turns its input crank (one of [[shafts]]): the "
                              "linkage's drawing is moved so that its crank's pivot lies on the shaft's centre; none: "
                              "a [[couplings]] entry drives it")
    phase: float = Field(0.0, ge=0, lt=360, description="with shaft: how far (counter-clockwise) its crank stands "
                         "ahead of its drawing at the machine's start; two mounts of one leg at 0 and 180 move in "
                         "antiphase", json_schema_extra=unit("degrees"))
    layer: int = Field(0, ge=0, le=MAX_LAYER, description="with shaft: its plane along the shaft; its parts fill "
                       "planes 2 layer + their own layers (a cam's layer k is plane 2k)")
    side: Literal["front", "back"] = Field("front", description="with shaft: the frame's side it stands on: front "
                                           "(planes counted up from the frame, as the cams') or back (the same "
                                           "planes behind the frame, its shaft passing through the frame)")


class Coupling(Model):
    """A cam's follower driving a linkage: the follower's arm is the linkage's input link, its pivot the linkage's
    input pivot, and the linkage's input angle is ``rest`` + the follower's swing."""

    cam: str = Field(description="the cam whose follower drives (one of [[cams]]): an oscillating follower (its "
                     "arm a four-bar's crank) or a translating one (its stem a general linkage's input slider)")
    linkage: str = Field(description="the linkage it drives (one of [[linkages]])")
    link: str = Field("crank", description="the linkage's link the follower's arm is: its input link (a "
                      "translating follower: the name of its input slider, whose guide is drawn along +Y)")
    rest: float = Field(ge=-360, le=360, description="the linkage's input angle (from its ground line, "
                        "counter-clockwise) with the follower at rest (swing 0); a translating follower: the "
                        "slider's travel (mm from its drawing) at lift 0, its travel then rest + the lift",
                        json_schema_extra=unit("degrees", allowed="a translating follower's: mm, within "
                                               "its slider's reach"))
    output: str | None = Field(None, description="a translating follower's linkage: the link output_torque acts on "
                               "(one of its links; a four-bar's is its rocker)")
    output_torque: float = Field(0.0, ge=-1e4, le=1e4, description="an external torque on the linkage's output "
                                 "link (counter-clockwise positive), which the machine holds and works against: "
                                 "reflected onto the follower and the camshaft", json_schema_extra=unit("N*m"))
    keep_time: KeepTime | None = Field(None, description="the cam that makes the linkage keep time: targets its "
                                       "tracer reaches at given shaft angles, or its rocker's program; the machine "
                                       "designs the cam's motion and phase and this rest from it (give neither)")


#: the formats a machine writes (its cams' and linkages' files of these formats, its timing diagram, its report)
MachineFormat = Literal["dxf", "cut-svg", "stl", "3mf", "json", "png", "svg", "html", "step", "gif"]


class MachineOutputTable(OutputTable):
    """A machine's ``[output]``: which of its cams' and linkages' files, its timing diagram, its figures at
    chosen angles, its page and its report to write (no STEP file of the whole machine yet)."""

    formats: tuple[MachineFormat, ...] = Field(
        ("dxf", "cut-svg", "stl", "3mf", "json"), min_length=1, description="files to write: each cam's and "
        "linkage's of these formats (html: each one's own page), the timing diagram and the machine at "
        "machine.figure_angles as png and svg (and the timing's CSV with json), the report as json, the machine's "
        "page as html; step the assembly's solids (with the step extra)")
    folders: bool = Field(False, description="write each cam's and linkage's files in a sub-folder of its own, "
                          "<out>/<mount>/ (the machine's own files stay in <out>)")
    kerf: float = Field(0.0, ge=0, le=MAX_ALLOWANCE_MM, description="laser kerf of the frame's cut files: its "
                        "outline grows and its holes shrink by half of it", json_schema_extra=unit("mm"))
    clearance: float = Field(0.0, ge=0, le=MAX_ALLOWANCE_MM, description="printing clearance of the frame's and "
                             "spacers' printed files: their holes grow by this in diameter",
                             json_schema_extra=unit("mm"))


class MachineSpec(TemplateSpec):
    """A whole machine template, validated (every key: the template reference); frozen.

    Parameters
    ----------
    name : str
        The machine's name, used for its files.
    machine : MachineTable
        The main shaft and its speed.
    shafts, gears, cams, linkages, couplings, genevas, ratchets : tuple
        The frame's shafts, the gear pairs between them, the cams on them, the linkages and what drives them, the
        Geneva drives between shafts and the ratchets the followers' arms index.
    output : OutputTable
        Which files to write (each cam's and linkage's own files are those of these formats its kind writes).
    """

    name: str = name_field("machine")
    machine: MachineTable
    shafts: tuple[ShaftTable, ...] = Field(min_length=1, max_length=MAX_MOUNTS, description="the shafts")
    gears: tuple[GearTable, ...] = Field((), max_length=MAX_MOUNTS, description="gear pairs between shafts")
    cams: tuple[CamMount, ...] = Field((), max_length=MAX_MOUNTS, description="the cams on the shafts (a machine "
                                       "has at least one cam, or a linkage driven by a shaft)")
    linkages: tuple[LinkageMount, ...] = Field((), max_length=MAX_MOUNTS, description="the linkages")
    genevas: tuple[GenevaMount, ...] = Field((), max_length=MAX_MOUNTS, description="Geneva drives between shafts")
    couplings: tuple[Coupling, ...] = Field((), max_length=MAX_MOUNTS, description="each follower driving a "
                                            "linkage")
    ratchets: tuple[RatchetMount, ...] = Field((), max_length=MAX_MOUNTS, description="ratchets, each indexed by "
                                               "a follower's arm")
    output: MachineOutputTable = MachineOutputTable()
    #: its kind's name (the registry's key), the command that builds it and how a message names it
    kind: ClassVar[str] = "machine"
    product: ClassVar[str] = "camgen"
    noun: ClassVar[str] = "a machine"

    @model_validator(mode="before")
    @classmethod
    def _keep_time(cls, data: Any) -> Any:
        """Each coupling's ``keep_time`` worked into its cam's motion and phase and its rest, before validation
        (:func:`camgen.kinds.machine.keeptime.expand`)."""
        from camgen.kinds.machine.keeptime import expand

        return expand(data, _template)

    @model_validator(mode="after")
    def _whole(self) -> MachineSpec:
        shafts = _unique([s.name for s in self.shafts], "shafts")
        cams = _unique([c.name for c in self.cams], "cams")
        _unique([m.name for m in self.linkages], "linkages")
        for i, m in enumerate(self.linkages):
            if m.name in cams:
                raise ValueError(f"linkages[{i}].name: {m.name!r} names cams[{cams.index(m.name)}] already (their "
                                 "files share the machine's folder: give each mount a name of its own)")
        if self.machine.main not in shafts:
            raise ValueError(f"machine.main: no shaft {self.machine.main!r}; shafts: {', '.join(shafts)}")
        self._check_gears(shafts)
        check_genevas(self, shafts)
        if not self.cams and not any(m.shaft for m in self.linkages):
            raise ValueError("cams: a machine has at least one cam, or a linkage driven by a shaft "
                             "(linkages[i].shaft)")
        for i, cam in enumerate(self.cams):
            self._check_shaft(f"cams[{i}].shaft", cam.shaft, shafts)
        check_layers(self.cams, self.cam_specs, MAX_LAYER)
        for i, m in enumerate(self.linkages):
            if m.shaft is not None:
                self._check_shaft(f"linkages[{i}].shaft", m.shaft, shafts)
            elif m.phase or m.layer or m.side != "front":
                key = "phase" if m.phase else "layer" if m.layer else "side"
                raise ValueError(f"linkages[{i}].{key}: a linkage driven by a coupling takes its phase and plane "
                                 "from its cam; give shaft, or leave it out")
        self.cam_specs, self.linkage_specs                  # noqa: B018 (each sub-template validated here)
        self._check_cranked()
        self._check_couplings()
        check_ratchets(self)
        return self

    def _check_shaft(self, where: str, shaft: str, shafts: list[str]) -> None:
        """Refuse a mount on a shaft that does not exist, is not driven, or turns part of a main turn."""
        if shaft not in shafts:
            raise ValueError(f"{where}: no shaft {shaft!r}; shafts: {', '.join(shafts)}")
        if shaft not in self.turns:
            raise ValueError(f"{where}: shaft {shaft} is not driven: no gear pair connects it to "
                             f"the main shaft {self.machine.main}")
        turns = abs(self.turns[shaft])
        if abs(turns - round(turns)) > 1e-9:
            raise ValueError(f"{where}: shaft {shaft} turns {turns:.6g} times a turn of the main "
                             f"shaft; a mount's shaft turns a whole number of times a main turn (so one main turn "
                             f"is the machine's cycle): make the slowest shaft the main one")

    def _check_cranked(self) -> None:
        """Refuse a linkage a shaft drives whose template has no single crank input about a ground joint."""
        for i, (m, lspec) in enumerate(zip(self.linkages, self.linkage_specs, strict=True)):
            if m.shaft is None:
                continue
            table = lspec.linkage
            inputs: tuple[Any, ...] = getattr(table, "inputs", ())
            if table.type != "linkage" or len(inputs) != 1 or inputs[0].slider is not None \
                    or inputs[0].relative_to != "ground" or inputs[0].pivot not in table.ground:
                raise ValueError(f"linkages[{i}].template: a shaft drives a type = \"linkage\" template whose one "
                                 f"input is a crank about a ground joint (input = {{ link, pivot }}); this is "
                                 + (f"a {table.type}" if table.type != "linkage" else "another input"))

    def _check_gears(self, shafts: list[str]) -> None:
        at = {s.name: s.at for s in self.shafts}
        driven: dict[str, int] = {}
        for i, g in enumerate(self.gears):
            for key in ("driver", "driven"):
                if getattr(g, key) not in at:
                    raise ValueError(f"gears[{i}].{key}: no shaft {getattr(g, key)!r}; shafts: {', '.join(shafts)}")
            if g.driven == self.machine.main or g.driven == g.driver:
                raise ValueError(f"gears[{i}].driven: a coupling loop: shaft {g.driven} is the "
                                 + ("main shaft, the machine's input" if g.driven == self.machine.main else
                                    "driver itself"))
            if g.driven in driven:
                raise ValueError(f"gears[{i}].driven: a coupling loop: shaft {g.driven} is driven by "
                                 f"gears[{driven[g.driven]}] already")
            driven[g.driven] = i
            from camgen.kinds.machine.machine_gears import pair_table

            need = pair_table(g, i).pair.centre_distance
            apart = math.dist(at[g.driver], at[g.driven])
            if abs(apart - need) > GEAR_DISTANCE_TOL_MM:
                how = "module x (driver_teeth + driven_teeth) / 2" + (", with their shifts" if g.driver_shift
                                                                       or g.driven_shift else "")
                raise ValueError(f"gears[{i}].module: the shafts {g.driver} and {g.driven} lie {apart:.6g} mm "
                                 f"apart; these gears need {need:.6g} mm ({how})")
        self._check_gear_names()
        for i, g in enumerate(self.gears):
            seen, shaft = [g.driven], g.driver
            while shaft in driven:
                if shaft in seen:
                    raise ValueError(f"gears[{i}]: a coupling loop: " + " -> ".join([*seen, shaft]))
                seen.append(shaft)
                shaft = self.gears[driven[shaft]].driver

    def _check_gear_names(self) -> None:
        """Refuse two gear pairs of one name, a pair named as a mount, and a pair at a cam's layer on its shafts."""
        from camgen.kinds.machine.machine_gears import gear_name

        names = _unique([gear_name(g) for g in self.gears], "gears")
        mounts = [c.name for c in self.cams] + [m.name for m in self.linkages]
        for i, (name, g) in enumerate(zip(names, self.gears, strict=True)):
            if name in mounts:
                raise ValueError(f"gears[{i}].name: {name!r} names a mount already; give the pair a name of its own")
            for cam in self.cams:
                if g.layer is not None and cam.layer == g.layer and cam.shaft in (g.driver, g.driven):
                    raise ValueError(f"gears[{i}].layer: cams.{cam.name} sits on shaft {cam.shaft} at layer "
                                     f"{cam.layer}; give another layer (0 to {MAX_LAYER}), or none: the lowest "
                                     "plane free of the other parts")

    def _check_couplings(self) -> None:
        cams = {c.name: i for i, c in enumerate(self.cams)}
        linkages = {m.name: i for i, m in enumerate(self.linkages)}
        driving: dict[str, int] = {}
        driven: dict[str, int] = {}
        for i, c in enumerate(self.couplings):
            if c.cam not in cams:
                raise ValueError(f"couplings[{i}].cam: no cam {c.cam!r}; cams: {', '.join(cams)}")
            if c.linkage not in linkages:
                raise ValueError(f"couplings[{i}].linkage: no linkage {c.linkage!r}; linkages: "
                                 f"{', '.join(linkages) or 'none'}")
            if c.cam in driving:
                raise ValueError(f"couplings[{i}].cam: cams.{c.cam}'s follower drives couplings[{driving[c.cam]}] "
                                 "already; one arm is one linkage's input link")
            if c.linkage in driven:
                raise ValueError(f"couplings[{i}].linkage: a coupling loop: linkages.{c.linkage} is driven by "
                                 f"couplings[{driven[c.linkage]}] already")
            shaft = self.linkages[linkages[c.linkage]].shaft
            if shaft is not None:
                raise ValueError(f"couplings[{i}].linkage: a coupling loop: linkages.{c.linkage} is driven by "
                                 f"shaft {shaft} already (its shaft)")
            driving[c.cam], driven[c.linkage] = i, i
            check_barrel(self.cam_specs[cams[c.cam]], i, c.cam)
            follower = self.cam_specs[cams[c.cam]].follower.type
            if follower in STEMS:
                check_slider(self, i, self.linkage_specs[linkages[c.linkage]])
                continue
            if follower not in ARMS:
                raise ValueError(f"couplings[{i}].cam: cams.{c.cam} has a {follower} follower; a follower drives a "
                                 f"linkage through its arm: give an oscillating-roller or oscillating-flat follower")
            table = self.linkage_specs[linkages[c.linkage]].linkage
            if table.type == "linkage":
                check_arm(self, i, self.linkage_specs[linkages[c.linkage]])
                continue
            if table.type != "four-bar":
                raise ValueError(f"couplings[{i}].linkage: linkages.{c.linkage} is a {table.type}; a follower's "
                                 "arm drives a four-bar's crank or a type = \"linkage\" template's")
            if c.link not in FOUR_BAR_LINKS:
                raise ValueError(f"couplings[{i}].link: linkages.{c.linkage} has no link {c.link!r}; its links: "
                                 f"{', '.join(FOUR_BAR_LINKS)}")
            if c.link != table.input or table.input != "crank":
                raise ValueError(f"couplings[{i}].link: the follower's arm is a four-bar's input link, its crank "
                                 f"(linkage.input = \"crank\"), not its {c.link}")
        for name, i in linkages.items():
            if name not in driven and self.linkages[i].shaft is None:
                raise ValueError(f"linkages[{i}]: linkages.{name} is driven by no coupling; give a [[couplings]] "
                                 "entry naming it, or its shaft")

    @cached_property
    def turns(self) -> dict[str, float]:
        """Each driven shaft's turns per turn of the main shaft, negative where it turns the other way (through an
        odd number of external gear pairs); shafts no gear pair reaches are left out."""
        out = {self.machine.main: 1.0}
        pending: list[Any] = [*self.gears, *self.genevas]
        while pending:
            ready = [g for g in pending if g.driver in out]
            if not ready:
                break
            for g in ready:
                if isinstance(g, GenevaMount):                  # its mean ratio: one index a driver turn
                    out[g.wheel] = -out[g.driver] / self.geneva_specs[self.genevas.index(g)].geneva.slots
                else:
                    out[g.driven] = -out[g.driver] * g.driver_teeth / g.driven_teeth
                pending.remove(g)
        return out

    @cached_property
    def geneva_specs(self) -> tuple[Any, ...]:
        """Each Geneva drive's validated spec, named ``<machine>-<mount>``, its ``geneva.rpm`` its driver shaft's
        (a shaft no gear reaches: the main shaft's)."""
        geared = self._gear_turns()
        out = []
        for i, mount in enumerate(self.genevas):
            raw = _template(mount.template, f"genevas[{i}].template")
            if "geneva" not in raw:
                raise SpecError("a Geneva template (with a [geneva] table)", f"genevas[{i}].template")
            rpm = self.machine.rpm * abs(geared.get(mount.driver, 1.0))
            out.append(self._turning(mount, raw, "geneva", rpm, f"genevas[{i}].template"))
        return tuple(out)

    def _turning(self, mount: Any, raw: dict[str, Any], table: str, rpm: float, where: str) -> Any:
        """A mount's cam or Geneva template ``raw`` validated, named ``<machine>-<mount>``, its ``<table>.rpm``
        its shaft's ``rpm`` (a :class:`SpecError` under ``where``)."""
        from camgen.kinds.machine.mounts import folder_of
        from camgen.spec import CamSpec

        raw = {**raw, "name": f"{self.name}-{mount.name}", table: {**raw[table], "rpm": rpm}}
        try:
            return CamSpec.validate_raw(raw, folder_of(mount.template))
        except SpecError as exc:
            raise exc.under(where) from None

    def _gear_turns(self) -> dict[str, float]:
        """Each shaft's turns per main turn through gear pairs alone (a Geneva's driver is never its wheel's)."""
        out = {self.machine.main: 1.0}
        for _ in self.gears:
            for g in self.gears:
                if g.driver in out:
                    out[g.driven] = -out[g.driver] * g.driver_teeth / g.driven_teeth
        return out

    @cached_property
    def cam_specs(self) -> tuple[Any, ...]:
        """Each cam's validated cam spec, named ``<machine>-<cam>`` and turning at its shaft's speed."""
        return tuple(self._cam_spec(f"cams[{i}].template", m) for i, m in enumerate(self.cams))

    def _cam_spec(self, where: str, mount: CamMount) -> Any:
        raw = _template(mount.template, where)
        if "geneva" in raw:
            raise SpecError("a cam template; a Geneva drive stands between two shafts: give it in [[genevas]] "
                            "(driver, wheel, template)", where)
        if "machine" in raw or "cam" not in raw:
            raise SpecError("a cam template (with a [cam] table); a machine's cams are cams", where)
        return self._turning(mount, raw, "cam", self.machine.rpm * abs(self.turns[mount.shaft]), where)

    @cached_property
    def linkage_specs(self) -> tuple[Any, ...]:
        """Each linkage's validated linkgen spec, named ``<machine>-<linkage>``."""
        from linkgen.spec import validate_spec

        out = []
        for i, mount in enumerate(self.linkages):
            where = f"linkages[{i}].template"
            raw = _template(mount.template, where, "linkgen")
            try:
                out.append(validate_spec({**raw, "name": f"{self.name}-{mount.name}"}))
            except SpecError as exc:
                raise exc.under(where) from None
        return tuple(out)


def _template(given: str | dict[str, Any], where: str, product: str = "camgen") -> dict[str, Any]:
    """The raw template a mount gives: its inline table, or the file it names read (its ``base`` merged)."""
    if isinstance(given, str):
        try:
            raw = read_template(given)
        except SpecError as exc:
            raise SpecError(exc.detail, where) from None
    else:
        raw = dict(given)
    try:
        check_kind(raw, product)
    except SpecError as exc:
        raise SpecError(exc.detail, where) from None
    return raw


def _unique(names: Sequence[str], table: str) -> list[str]:
    """``names`` where no two are the same, else a :class:`ValueError` naming the second."""
    seen: list[str] = []
    for i, name in enumerate(names):
        if name in seen:
            raise ValueError(f"{table}[{i}].name: {name!r} names {table}[{seen.index(name)}] already")
        seen.append(name)
    return seen

