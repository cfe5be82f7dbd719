"""The kind registry is the only dispatch: every kind designs, bundles, summarises and sizes through it (each the kind's
own functions, checked against independent figures), a Geneva drive joins by its own table, a template with two
kinds' tables is refused in one line, and a kind written in this file, registered without any file of the package
changed, is built, sized, started and refused through the command line in-process."""
from __future__ import annotations

import json
import math
import tomllib
from dataclasses import dataclass
from typing import Any, ClassVar, Literal

import numpy as np
import pytest
from click.testing import CliRunner
from pydantic import model_validator

import camgen.kinds
from camgen import api
from camgen.cli import main
from camgen.core.errors import SpecError
from camgen.core.registry import registry
from camgen.core.spec import Model, length, name_field
from camgen.kinds import KINDS, kind_for, spec_kind
from camgen.kinds.base import KindBase, Operations, SizeReport, Starter
from camgen.spec import OutputTable
from tests.conftest import ROOT

#: a bundled template of each kind
TEMPLATES = {"disc": "rdrd.toml", "plate": "plate.toml", "grooved": "grooved.toml", "barrel": "barrel.toml",
             "conjugate": "conjugate.toml", "geneva": "geneva4.toml", "machine": "automaton.toml"}


def _raw(name: str, **changes: Any) -> dict[str, Any]:
    raw = tomllib.loads((ROOT / "templates" / name).read_text())
    for dotted, value in changes.items():
        table, key = dotted.split(".")
        raw.setdefault(table, {})[key] = value
    return raw


def _run(args: list[Any]) -> tuple[int, str]:
    result = CliRunner().invoke(main, [str(a) for a in args])
    return result.exit_code, result.output


def test_every_kind_is_registered_once_and_chosen_by_its_template():
    assert list(KINDS) == ["disc", "plate", "grooved", "barrel", "conjugate", "geneva", "machine"]
    assert set(TEMPLATES) == set(KINDS)
    for name, template in TEMPLATES.items():
        raw = _raw(template)
        kind = kind_for(raw)
        assert kind is KINDS[name] and kind.name == name
        spec = api.load(ROOT / "templates" / template)
        assert isinstance(spec, kind.spec) and spec_kind(spec) is kind
    with pytest.raises(SpecError, match=r"^cam\.kind: 'disc' already names a cam kind$"):
        registry([KINDS["disc"]], lambda k: (k.name,), "cam.kind", "a cam kind", base=KINDS)


def _own(name: str, spec: Any) -> tuple[Any, Any, Any]:
    """The kind's own design, bundle and summary functions, named here independently of the registry."""
    from camgen.report import cam_summary

    if name in ("disc", "plate"):
        from camgen.flat import design_flat
        from camgen.outputs import cam_bundle
        from camgen.rig import disc_mount, plate_mount

        mount = (disc_mount(spec.follower, spec.cam.rotation) if name == "disc"
                 else plate_mount(spec.follower, spec.cam.travel))
        return lambda s: design_flat(s, mount), cam_bundle, cam_summary
    if name == "grooved":
        from camgen.kinds.grooved.design import design_grooved
        from camgen.kinds.grooved.outputs import groove_summary, grooved_bundle

        return design_grooved, grooved_bundle, lambda d, r: [*cam_summary(d, r), groove_summary(r)]
    if name == "barrel":
        from camgen.kinds.barrel.design import design_barrel
        from camgen.kinds.barrel.outputs import barrel_bundle, summary_lines

        return design_barrel, barrel_bundle, lambda d, r: summary_lines(r)
    if name == "conjugate":
        from camgen.kinds.conjugate.design import design_conjugate
        from camgen.kinds.conjugate.outputs import conjugate_bundle, summary_lines

        return design_conjugate, conjugate_bundle, lambda d, r: summary_lines(r)
    if name == "machine":
        from camgen.kinds.machine.design import design_machine
        from camgen.kinds.machine.outputs import machine_bundle
        from camgen.kinds.machine.report import summary_lines as machine_lines

        return design_machine, machine_bundle, lambda d, r: machine_lines(r)
    from camgen.kinds.geneva.design import design_geneva
    from camgen.kinds.geneva.outputs import geneva_bundle
    from camgen.kinds.geneva.report import summary_lines

    return design_geneva, geneva_bundle, lambda d, r: summary_lines(r)


@pytest.mark.parametrize("name", list(TEMPLATES))
def test_every_kind_designs_bundles_and_summarises_through_the_registry(tmp_path, name):
    spec = api.load(ROOT / "templates" / TEMPLATES[name], ['output.formats=["dxf","json"]'])
    design_of, bundle_of, summary_of = _own(name, spec)
    design = api.design(spec)
    assert type(design) is type(design_of(spec))
    written = api.write(design, tmp_path)
    report = written.report
    assert report["files"] == bundle_of(design)[0].files
    assert written.files == {key: tmp_path / name for key, name in report["files"].items()}
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(report["files"].values())
    assert json.loads((tmp_path / report["files"]["json"]).read_text()) == json.loads(json.dumps(report))
    assert api.summary(design, report) == summary_of(design, report)
    assert api.summary(design, report)[0].startswith(spec.name)


def _radii(ring: list[list[float]]) -> np.ndarray:
    return np.hypot(*np.array(ring).T)


def test_a_disc_cam_s_family_row_is_its_outline_and_the_overview_draws_its_bore(tmp_path):
    """rdrd: base radius 40, roller 10, offset 5, lift 20 mm. The profile is the base circle in the low dwell and,
    in the high dwell, the circle the roller's centre rides (sqrt(e^2 + (sqrt(Rp^2 - e^2) + h)^2) from the centre)
    less the roller; the thumbnail's chords (0.2 mm) lie inside by at most that."""
    row = api.build_member(_raw("rdrd.toml", **{"output.formats": ["dxf", "json"]}), tmp_path)
    radii = _radii(row["thumbnail"])
    top = math.hypot(5.0, math.sqrt(50.0 ** 2 - 5.0 ** 2) + 20.0) - 10.0
    assert 40.0 - 0.2 - 1e-3 <= radii.min() <= 40.0 + 1e-3
    assert top - 0.2 - 1e-3 <= radii.max() <= top + 1e-3
    assert row["files"] == "rdrd.dxf rdrd.json" and "thumbnail_bore" not in row      # row.json: the member's files
    barrel = api.build_member(_raw("barrel.toml", **{"output.formats": ["json"]}), tmp_path / "b")
    assert barrel["thumbnail"] and "thumbnail_bore" not in barrel
    # the bore the overview draws in each thumbnail, by the kind: a flat cam's cam.bore as its template gives it
    # (rdrd 10, grooved 8, conjugate 12 mm; a plate has none), none in a barrel drawn unrolled (its template's bore
    # is 10 mm) nor in a Geneva wheel, nor a machine (no outline of its own)
    bores = {name: api.thumbnail_bore(api.load(ROOT / "templates" / template)) for name, template in TEMPLATES.items()}
    assert bores == {"disc": 10.0, "plate": 0.0, "grooved": 8.0, "barrel": 0.0, "conjugate": 12.0, "geneva": 0.0,
                     "machine": 0.0}


def test_sizing_through_the_registry_meets_the_limit_it_names():
    """The size `camgen size` reports for the disc is the base radius at which the pressure angle reaches its limit;
    the conjugate pair is sized cam by cam, at the larger; a barrel cam and a Geneva drive say why they have none."""
    spec = api.load(ROOT / "templates" / "rdrd.toml")
    sized = api.size(spec)
    assert isinstance(sized, SizeReport) and sized.sizing.decided_by == "pressure angle" and sized.notes == ()
    at = api.design(api.validate(_raw("rdrd.toml", **{"cam.base_radius": sized.sizing.base_radius_mm})))
    assert at.analysis.pressure_angle_max_deg == pytest.approx(30.0, abs=1e-6)
    pair = api.size(api.load(ROOT / "templates" / "conjugate.toml"))
    each = pair.figures["each_cam_base_radius_mm"]
    assert pair.sizing.base_radius_mm == max(each) and len(each) == 2 and "each cam alone" in pair.notes[0]
    for template, why in (("barrel.toml", "a barrel cam has no base radius to size: its pitch_radius"),
                          ("geneva4.toml", "a Geneva drive has no base radius to size")):
        with pytest.raises(SpecError, match=f"^template: {why}"):
            api.size(api.load(ROOT / "templates" / template))


def test_a_geneva_drive_joins_by_its_own_table(tmp_path):
    """No ``cam.kind``: the ``[geneva]`` table chooses the drive; the wheel indexes 360 / slots degrees while the
    driver turns 180 - 360 / slots."""
    raw = _raw("geneva6.toml")
    assert "cam" not in raw and kind_for(raw) is KINDS["geneva"] and KINDS["geneva"].table_key == "geneva"
    slots = raw["geneva"]["slots"]
    code, output = _run(["build", ROOT / "templates" / "geneva6.toml", "-o", tmp_path, "--set",
                         'output.formats=["json"]'])
    assert code == 0, output
    report = json.loads((tmp_path / "geneva6.json").read_text())
    assert report["motion"]["index_deg"] == pytest.approx(360 / slots)
    assert report["motion"]["motion_deg"] == pytest.approx(180 - 360 / slots)
    from camgen.kinds.geneva.report import summary_lines

    assert output.splitlines()[:3] == summary_lines(report)


def test_a_template_with_a_cam_and_a_geneva_table_is_refused_in_one_line(tmp_path):
    both = _raw("geneva4.toml")
    both["cam"] = _raw("rdrd.toml")["cam"]
    path = tmp_path / "both.toml"
    path.write_text(_toml(both))
    code, output = _run(["build", path, "-o", tmp_path / "out"])
    assert (code, output) == (2, "error: template: give [cam] (a cam) or [geneva] (a Geneva drive), not both\n")
    assert not (tmp_path / "out").exists()


def test_a_template_with_three_kinds_tables_is_refused_naming_each(monkeypatch):
    from camgen.kinds.geneva.kind import GenevaKind

    class Ratchet(GenevaKind):
        name: str = "ratchet"
        title: str = "a ratchet"
        table_key: str = "ratchet"

    monkeypatch.setattr(camgen.kinds, "KINDS", registry([Ratchet()], lambda k: (k.name,), "cam.kind", "a cam kind",
                                                        base=KINDS))
    assert kind_for({"ratchet": {}}).name == "ratchet" and kind_for({"geneva": {}}).name == "geneva"
    with pytest.raises(SpecError) as refused:
        kind_for({"cam": {}, "geneva": {}, "ratchet": {}})
    assert str(refused.value) == ("template: give only one of [cam] (a cam), [geneva] (a Geneva drive), [ratchet] "
                                  "(a ratchet)")


def test_a_format_a_kind_does_not_write_is_refused_before_it_is_designed(monkeypatch):
    import camgen.kinds.barrel.design

    def never(spec: Any) -> None:
        raise AssertionError("designed")

    monkeypatch.setattr(camgen.kinds.barrel.design, "design_barrel", never)
    with pytest.raises(SpecError, match=r"^output\.formats: a barrel cam has no flat part to write as an exact STEP"):
        api.validate(_raw("barrel.toml", **{"output.formats": ["step", "stl"]}))
    assert "step" not in KINDS["barrel"].formats and "step" in KINDS["disc"].formats


def _toml(raw: dict[str, Any]) -> str:
    """``raw`` (tables of plain values, a list of tables) as TOML."""
    from camgen.core.starter import toml_value

    lines = [f"{k} = {toml_value(v)}" for k, v in raw.items() if not isinstance(v, (dict, list))]
    for key, value in raw.items():
        tables = [value] if isinstance(value, dict) else value if isinstance(value, list) else []
        for table in tables:
            lines += [f"[[{key}]]" if isinstance(value, list) else f"[{key}]",
                      *(f"{k} = {toml_value(v)}" for k, v in table.items())]
    return "\n".join(lines) + "\n"


# ---- a kind of the test's own: an eccentric disc under a translating flat face ----

class EccentricTable(Model):
    """An eccentric: a circular disc turning about a shaft off its centre."""

    kind: Literal["eccentric"]
    radius: float = length("the disc's radius")
    eccentricity: float = length("the distance from the shaft's axis to the disc's centre")
    thickness: float = length("plate thickness", le=1000.0)
    bore: float = length("bore diameter, 0 for none", 0.0, zero=True)
    min_rho_margin: float = length("least radius of curvature of the profile", 0.0, zero=True)


class EccentricSpec(Model):
    kind: ClassVar[str] = "eccentric"
    name: str = name_field("part")
    cam: EccentricTable
    output: OutputTable = OutputTable()

    @model_validator(mode="after")
    def _wall(self) -> EccentricSpec:
        cam = self.cam
        if not cam.radius > cam.eccentricity + cam.bore / 2:
            raise ValueError(f"cam.radius: must be > eccentricity + bore / 2 = {cam.eccentricity + cam.bore / 2:g} "
                             f"mm, so the disc surrounds the bore (got {cam.radius:g})")
        return self


@dataclass(frozen=True)
class EccentricDesign:
    """The disc (centre at -e on Y: the face at rest on its nearest point) as cut, and the face's lift s = e (1 -
    cos theta) (mm) at each degree."""

    spec: EccentricSpec
    cut: Any
    lift_mm: np.ndarray

    @property
    def tolerance(self) -> float:
        return self.spec.output.tolerance


def _disc(radius: float, centre_y: float) -> Any:
    from camgen.core.shapes import Contour

    return Contour(np.array([[0.0, centre_y - radius], [0.0, centre_y + radius]]), np.array([1.0, 1.0]))


STARTERS = {"eccentric": Starter(
    "An eccentric under a flat face: simple harmonic motion.",
    (("cam", {"kind": "eccentric", "radius": 30.0, "eccentricity": 6.0, "thickness": 5.0, "bore": 8.0}),
     ("output", {"formats": ["dxf", "json"]})),
    {"cam.eccentricity": "mm: half the face's lift"})}


class EccentricKind(KindBase[EccentricSpec, EccentricDesign]):
    name = "eccentric"
    title = "an eccentric cam"
    followers = ("translating-flat",)
    formats = frozenset({"dxf", "cut-svg", "json"})

    @property
    def spec(self) -> type[EccentricSpec]:
        return EccentricSpec

    starters = STARTERS

    def operations(self) -> Operations[EccentricSpec, EccentricDesign]:
        return Operations(_design, _bundle, _summary, _row, _size)

    def thumbnail_bore(self, spec: EccentricSpec) -> float:
        return spec.cam.bore


def _design(spec: EccentricSpec) -> EccentricDesign:
    from camgen.core.parts import Part
    from camgen.core.shapes import Circle

    cam, kerf = spec.cam, spec.output.kerf
    holes = (Circle((0.0, 0.0), cam.bore / 2 - kerf / 2),) if cam.bore else ()
    cut = Part(spec.name, _disc(cam.radius + kerf / 2, -cam.eccentricity), holes, cam.thickness, spec.output.tolerance)
    theta = np.radians(np.arange(360.0))
    return EccentricDesign(spec, cut, cam.eccentricity * (1 - np.cos(theta)))


def _bundle(design: EccentricDesign) -> tuple[Any, dict[str, Any]]:
    from camgen.outputs import cam_files

    cam = design.spec.cam
    report = {"name": design.spec.name, "kind": "eccentric", "lift_max_mm": float(design.lift_mm.max()),
              "lift_at_90_deg_mm": float(design.lift_mm[90]), "radius_mm": cam.radius, "warnings": []}
    return cam_files(design.spec, design.cut, None, lambda kind: None, report, None, ()), report


def _summary(design: EccentricDesign, report: dict[str, Any]) -> list[str]:
    return [f"{report['name']}: an eccentric cam lifting a flat face {report['lift_max_mm']:.4f} mm"]


def _size(spec: EccentricSpec) -> SizeReport:
    """A flat face on a circle of radius R: its profile's radius of curvature is R everywhere, so the smallest disc
    that keeps it above min_rho_margin and round the bore; its base radius is R - e."""
    from camgen.sizing import Sizing

    cam = spec.cam
    bore = cam.eccentricity + cam.bore / 2
    radius = max(cam.min_rho_margin, bore)
    return SizeReport(Sizing(radius - cam.eccentricity, "curvature" if cam.min_rho_margin >= bore else "bore", 0.0,
                             cam.min_rho_margin - cam.eccentricity, 0.0, cam.min_rho_margin))


def _row(design: EccentricDesign, report: dict[str, Any]) -> dict[str, Any]:
    return {"lift_max_mm": report["lift_max_mm"], "files": " ".join(sorted(report["files"].values())),
            "thumbnail": design.cut.outline.flatten(1.0).round(3).tolist()}


@pytest.fixture
def eccentric(monkeypatch):
    """The registry with the eccentric kind added (the package's own left as it was)."""
    kind = EccentricKind()
    monkeypatch.setattr(camgen.kinds, "KINDS", registry([kind], lambda k: (k.name,), "cam.kind", "a cam kind",
                                                        base=KINDS))
    return kind


def test_a_kind_written_here_is_built_sized_started_and_refused_through_the_command_line(tmp_path, eccentric):
    import ezdxf
    from ezdxf import bbox

    starter = tmp_path / "ecc.toml"
    assert _run(["new", "eccentric", "-o", starter]) == (0, f"wrote {starter}\n")
    assert "eccentric" in _run(["new"])[1]
    assert "# mm: half the face's lift" in starter.read_text()
    out = tmp_path / "out"
    code, output = _run(["build", starter, "-o", out, "--set", "output.kerf=0.2"])
    assert code == 0, output
    assert output == f"ecc: an eccentric cam lifting a flat face 12.0000 mm\nwrote {out / 'ecc.dxf'}\n" \
                     f"wrote {out / 'ecc.json'}\n"
    report = json.loads((out / "ecc.json").read_text())
    assert report["lift_at_90_deg_mm"] == pytest.approx(6.0, abs=1e-12)       # s(90) = e (1 - cos 90) = e
    box = bbox.extents(ezdxf.readfile(out / "ecc.dxf").modelspace())   # the disc as cut: R + kerf / 2 about (0, -e)
    assert np.allclose([*box.extmin][:2], [-30.1, -36.1], atol=1e-9)
    assert np.allclose([*box.extmax][:2], [30.1, 24.1], atol=1e-9)

    code, output = _run(["size", starter, "--set", "cam.min_rho_margin=40"])
    assert (code, output) == (0, "smallest base radius 34.0000 mm, decided by the curvature (pressure angle <= 0 "
                                 "deg needs 0.0000 mm; convex radius > 40 mm needs 34.0000 mm)\n")
    sized = json.loads(_run(["size", starter, "--json"])[1])
    assert sized["base_radius_mm"] == 4.0 and sized["decided_by"] == "bore"            # R = 6 + 8 / 2, less e

    for args, message in (
            (["--set", 'output.formats=["stl"]'],
             "output.formats: an eccentric cam writes no 'stl' file; give formats of cut-svg, dxf, json"),
            (["--construction"], "--construction: the graphical construction is drawn for a disc cam, not an "
                                 "eccentric cam"),
            (["--set", "cam.radius=9"], "cam.radius: must be > eccentricity + bore / 2 = 10 mm, so the disc "
                                        "surrounds the bore (got 9)"),
            (["--set", "cam.pitch_radius=9"], "cam.pitch_radius: unknown key")):
        code, output = _run(["build", starter, "-o", tmp_path / "refused", *args])
        assert code == 2 and output.startswith(f"error: {message}") and output.count("\n") == 1, output
    assert not (tmp_path / "refused").exists()


def test_a_kind_written_here_builds_a_family(tmp_path, eccentric):
    family = tmp_path / "ecc-family.toml"
    family.write_text('name = "ecc"\n[cam]\nkind = "eccentric"\nradius = 30.0\nthickness = 5.0\n'
                      '[output]\nformats = ["dxf", "json"]\n[sweep]\n"cam.eccentricity" = [4.0, 8.0]\n')
    code, output = _run(["family", family, "-o", tmp_path / "f"])
    assert code == 0, output
    rows = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert [(r["status"], r["lift_max_mm"]) for r in rows] == [("ok", 8.0), ("ok", 16.0)]
    assert "thumbnail_bore" not in rows[0]
