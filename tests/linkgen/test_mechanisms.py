"""The mechanism registry is the one place a linkage type is known: every registered mechanism validates, builds,
reports and (where it has parts) makes its parts, and a new mechanism registered through the registry runs through
design and bundle with no other edit."""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import pytest

from camgen.core.errors import SpecError
from camgen.core.spec import Model
from linkgen.linkage_design import LinkageDesign, analyze, design_linkage
from linkgen.mechanisms import MECHANISMS, MODULES, Mechanism, registry
from linkgen.mechanisms.common import length, rpm
from linkgen.outputs import linkage_bundle, write_linkage
from linkgen.parts import Layout, LinkPart, Placement, Stock
from linkgen.spec import validate_spec

#: a sound [linkage] table of every registered type (a new mechanism adds its own here)
EXAMPLES = {
    "four-bar": {"ground": 180.0, "crank": 80.0, "coupler": 200.0, "rocker": 150.0, "point_distance": 60.0},
    "slider-crank": {"crank": 40.0, "rod": 150.0, "offset": 10.0},
    "scotch-yoke": {"crank": 40.0},
    "whitworth": {"crank": 100.0, "ground": 40.0, "arm": 60.0, "rod": 200.0},
    "crank-shaper": {"crank": 50.0, "ground": 150.0, "lever": 300.0},
    **{kind: {"size": 20.0} for kind in ("chebyshev", "hoekens", "roberts", "watt")},
    "linkage": {"ground": ["O2", "O4"], "input": {"link": "crank", "pivot": "O2"}, "tracers": ["P"],
                "joints": {"O2": [0.0, 0.0], "O4": [180.0, 0.0], "A": [40.0, 69.2820323], "B": [240.0, 130.0],
                           "P": [150.0, 150.0]},
                "links": {"crank": ["O2", "A"], "coupler": ["A", "B", "P"], "rocker": ["O4", "B"]}},
    "gear-pair": {"module": 2.0, "pinion": {"teeth": 14, "shift": 0.2}, "gear": {"teeth": 25}},
    "ratchet": {"teeth": 20, "tip_diameter": 80.0, "depth": 6.0, "pawl": {"length": 30.0},
                "lever": {"swing": 72.0, "length": 80.0}},
    "oldham": {"offset": 20.0},
    "trammel": {"rod": 80.0, "point": 30.0},
    "rapson": {"distance": 100.0},          # its input is the crosshead's height: 60 mm is inside its 70 mm travel
    "gear-train": {"module": 2.0, "teeth": [18, 24]},
    "counter": {"teeth": 10, "tip_diameter": 100.0, "depth": 8.0, "pawl": {"length": 32.0},
                "lever": {"swing": 72.0, "length": 95.0}, "transfer": {"slots": 10, "centre_distance": 97.0}},
}
#: the types whose mechanism makes parts (all but Whitworth, whose crank sweeps over its slotted link's pivot)
WITH_PARTS = set(EXAMPLES) - {"whitworth"}
PARTS = {"width": 10.0, "thickness": 3.0, "pin_diameter": 3.0, "sheet": [1000.0, 1000.0]}


def _raw(kind: str, **more: Any) -> dict[str, Any]:
    return {"name": f"m-{kind}", "linkage": {"type": kind, **EXAMPLES.get(kind, {})}, **more}


def test_the_registry_lists_every_type_once_in_module_order():
    assert list(MECHANISMS) == ["four-bar", "slider-crank", "scotch-yoke", "whitworth", "crank-shaper", "chebyshev",
                                "hoekens", "roberts", "watt", "linkage", "gear-pair", "ratchet", "oldham",
                                "trammel", "rapson", "gear-train", "counter"]
    assert set(EXAMPLES) == set(MECHANISMS)
    assert [m for module in MODULES for m in module.REGISTER] == list(dict.fromkeys(MECHANISMS.values()))
    for kind, mechanism in MECHANISMS.items():
        assert kind in mechanism.types
        assert kind in mechanism.table.model_fields["type"].annotation.__args__
    with pytest.raises(TypeError):
        MECHANISMS["five-bar"] = MECHANISMS["four-bar"]                      # read-only
    with pytest.raises(SpecError, match="'four-bar' already names a mechanism"):
        registry(MECHANISMS["four-bar"], base=MECHANISMS)


def test_a_typo_in_the_type_lists_the_registered_types():
    with pytest.raises(SpecError) as err:
        validate_spec({"name": "x", "linkage": {"type": "hoeken", "size": 20.0}})
    assert str(err.value) == ("linkage.type: unknown value 'hoeken' (did you mean 'hoekens'?); one of "
                              + ", ".join(MECHANISMS))


@pytest.mark.parametrize("kind", list(MECHANISMS))
def test_every_mechanism_validates_builds_reports_and_draws(kind):
    spec = validate_spec(_raw(kind))
    assert spec.mechanism is MECHANISMS[kind] and type(spec.linkage) is MECHANISMS[kind].table
    design = design_linkage(spec, angle=60.0)   # inside every input range here
    report = design.report
    assert list(report)[:5] == ["name", "type", "conventions", "lengths_mm", "rpm"]
    assert report["type"] == kind and report["lengths_mm"] and "positions" in report
    assert analyze(spec, 60.0) == report
    assert design.figures() and all(callable(draw) for _, draw in design.figures())
    json.dumps(report, allow_nan=False)
    svg = design._repr_svg_()
    assert svg is None or svg.startswith("<?xml")


@pytest.mark.parametrize("kind", list(MECHANISMS))
def test_every_mechanism_with_parts_makes_them_and_the_others_refuse(kind):
    spec = validate_spec(_raw(kind, parts=PARTS))
    if kind not in WITH_PARTS:
        with pytest.raises(SpecError, match=f"linkage.type: no parts are made for {kind}: its crank sweeps"):
            design_linkage(spec, parts=True)
        return
    build = design_linkage(spec, parts=True).build
    assert build.layer_names[0] == "ground" and len(build.cut) == len(build.printed) == len(build.parts) >= 3
    assert build.report["assembly_layers"] == [f"DC{i + 1}-{k}" for i, (k, _) in enumerate(build.positions)]


@dataclass(frozen=True)
class Crank:
    """Kinematics of the dummy: a crank of ``length`` mm turning about the origin."""

    length: float

    def tip(self, theta: np.ndarray) -> np.ndarray:
        return self.length * np.column_stack([np.cos(theta), np.sin(theta)])


class CrankTable(Model):
    type: Literal["lone-crank"]
    crank: float = length("crank")
    rpm: float = rpm()


@dataclass(frozen=True)
class LoneCrank:
    """A mechanism known to no module of linkgen: a crank on a ground plate."""

    types: tuple[str, ...] = ("lone-crank",)
    table: type[Model] = CrankTable

    def build(self, table: CrankTable) -> Crank:
        return Crank(table.crank)

    def report(self, table: CrankTable, kinematics: Crank, angle: float | None, method: str) -> dict[str, Any]:
        out: dict[str, Any] = {"tip_speed_mm_s": kinematics.length * table.rpm * 2 * math.pi / 60}
        if angle is not None:
            out["positions"] = {"tip_mm": kinematics.tip(np.radians([angle]))[0].round(9).tolist()}
        return out

    def figures(self, name: str, table: CrankTable, kinematics: Crank) -> tuple:
        def draw() -> Any:
            from camgen.core.figures import figure

            fig = figure(3, 3)
            fig.add_subplot().plot(*kinematics.tip(np.linspace(0, 2 * math.pi, 73)).T)
            return fig

        return (("tip", draw),)

    def layout(self, table: CrankTable, kinematics: Crank, parts: Any) -> Layout:
        stock = Stock.of(parts)
        links = (LinkPart("ground", np.array([[0.0, 0.0]]), parts.width, stock, moving=False),
                 LinkPart("crank", np.array([[0.0, 0.0], [kinematics.length, 0.0]]), parts.width / 2, stock))
        theta = np.linspace(0, 2 * math.pi, 37)
        zero = np.zeros((len(theta), 2))
        sweep = Placement({"ground": np.zeros(len(theta)), "crank": theta}, {"ground": zero, "crank": zero},
                          {"O": (("ground", "crank"), zero)})
        at = Placement({"ground": np.zeros(1), "crank": np.zeros(1)}, {"ground": zero[:1], "crank": zero[:1]}, {})
        return Layout(links, sweep, (("start", 0.0),), (at,), (kinematics.tip(theta),))

    def family_row(self, table: CrankTable, kinematics: Crank, report: dict[str, Any]) -> dict[str, Any]:
        return {"thumbnail": kinematics.tip(np.linspace(0, 2 * math.pi, 13)).round(3).tolist(),
                "thumbnail_kind": "path"}

    def sketch(self, table: CrankTable, kinematics: Crank) -> None:
        return None


def test_a_new_mechanism_needs_only_registering(tmp_path):
    mine = registry(LoneCrank(), base=MECHANISMS)
    lone: Mechanism = mine["lone-crank"]
    raw = {"name": "lone", "linkage": {"type": "lone-crank", "crank": 30.0}, "parts": PARTS,
           "output": {"formats": ["json", "dxf", "cut-svg", "svg"]}}
    with pytest.raises(SpecError, match="unknown value 'lone-crank'"):
        validate_spec(raw)                                           # the shared registry is left as it was
    spec = validate_spec(raw, mine)
    assert spec.mechanism is lone
    design = design_linkage(spec, angle=90.0, parts=True)
    assert isinstance(design, LinkageDesign) and design._repr_svg_() is None
    assert linkage_bundle(design).files == {
        "sheet_dxf": "lone-sheet.dxf", "sheet_svg": "lone-sheet.svg", "assembly_dxf": "lone-assembly.dxf",
        "assembly_svg": "lone-assembly.svg", "tip_svg": "lone-tip.svg", "json": "lone.json"}
    files = write_linkage(design, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(files.values())
    report = json.loads((tmp_path / "lone.json").read_text())
    assert report["lengths_mm"] == {"crank": 30.0} and report["tip_speed_mm_s"] == pytest.approx(30 * 2 * math.pi)
    assert report["positions"]["tip_mm"] == pytest.approx([0.0, 30.0])
    assert report["layer_order"] == ["ground", "crank"] and report["assembly_layers"] == ["DC1-start"]
    assert [p["hole_distance_mm"] for p in report["parts"] if p["name"] == "crank"] == [30.0]
    assert report["files"] == files
    assert design.family_row()["thumbnail_kind"] == "path"
