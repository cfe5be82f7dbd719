"""A cam kind from a plugin: a toy "eccentric" kind (an eccentric circle disc under a translating roller), written
here into a temporary folder as a module and a ``*.dist-info/entry_points.txt`` (group ``camgen.kinds``), found by
the registry through that folder on PYTHONPATH alone: no file of the package changed. The console commands run as
a user runs them (the ``camgen`` console script, or ``python -m camgen``, in its own interpreter, from a folder
outside the checkout): ``new``, ``build`` (its DXF, STL, JSON and page checked against the eccentric's closed forms)
and ``size``; a plugin whose name is a built-in kind's is refused in one line. Nothing is written inside the
checkout."""
from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import ROOT

#: the toy kind: a module a plugin distribution would install
TOY = '''
"""An eccentric: a circle of radius R whose centre lies e from the shaft's axis, turning counter-clockwise under a
translating roller (radius Rr, its axis through the shaft's). Its pitch curve is the circle of radius rho = R + Rr
about the centre; with the centre at angle theta + 180 degrees from the follower's axis the roller's centre stands at
y = sqrt(rho^2 - e^2 sin^2 theta) - e cos theta, so the stroke is 2 e (from rho - e at theta = 0 to rho + e at 180)
and the pressure angle phi satisfies sin phi = e sin theta / rho: at most asin(e / rho)."""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from pydantic import Field, model_validator

from camgen.core.bundle import Bundle, item, tail
from camgen.core.page import FRAMES, Body, Mover, Outline, Page, Plot, Scene, key_figures, pose_motion
from camgen.core.parts import Drawing, Part
from camgen.core.shapes import Circle, Contour
from camgen.core.spec import CutOutputTable, Model, TemplateSpec, length, name_field, unit, validate
from camgen.kinds.base import KindBase, Operations, SizeReport, Starter
from camgen.sizing import Sizing


class EccentricTable(Model):
    """The ``[eccentric]`` table: the disc, its offset, the roller, the plate and the bore."""

    radius: float = length("the disc's radius R")
    eccentricity: float = length("distance e from the shaft's axis to the disc's centre", le=1000.0)
    roller_radius: float = length("the follower's roller radius", le=1000.0)
    thickness: float = length("plate thickness", le=1000.0)
    bore: float = length("bore diameter, 0 for none", 0.0, zero=True)
    max_pressure_angle: float = Field(30.0, ge=1, lt=90, description="pressure-angle limit",
                                      json_schema_extra=unit("degrees"))


class EccentricSpec(TemplateSpec):
    kind: ClassVar[str] = "eccentric"
    product: ClassVar[str] = "camgen"
    noun: ClassVar[str] = "an eccentric disc"
    name: str = name_field("eccentric")
    eccentric: EccentricTable
    output: CutOutputTable = CutOutputTable(formats=("dxf", "stl", "json", "html"))

    @classmethod
    def validate_raw(cls, raw: Mapping[str, Any], folder: Any = None) -> "EccentricSpec":
        return validate(cls, raw)

    @model_validator(mode="after")
    def _fits(self) -> "EccentricSpec":
        t = self.eccentric
        if not t.eccentricity + t.bore / 2 < t.radius:
            raise ValueError(f"eccentric.radius: must be > eccentricity + bore / 2 = "
                             f"{t.eccentricity + t.bore / 2:g} mm, so the bore lies inside the disc "
                             f"(got {t.radius:g})")
        return self


@dataclass(frozen=True)
class EccentricDesign:
    """The eccentric designed: its spec and its part (the disc as at theta = 0, the bore about the shaft)."""

    spec: EccentricSpec
    part: Part

    def lift(self, theta: np.ndarray) -> np.ndarray:
        t = self.spec.eccentric
        rho, e = t.radius + t.roller_radius, t.eccentricity
        return np.sqrt(rho ** 2 - (e * np.sin(theta)) ** 2) - e * np.cos(theta) - (rho - e)

    def pressure_angle_deg(self, theta: np.ndarray) -> np.ndarray:
        t = self.spec.eccentric
        return np.degrees(np.arcsin(t.eccentricity * np.sin(theta) / (t.radius + t.roller_radius)))


def design(spec: EccentricSpec) -> EccentricDesign:
    t = spec.eccentric
    centre = np.array([-t.eccentricity, 0.0])        # at theta = 0, opposite the follower: the roller at rest
    outline = Contour(np.array([centre + [t.radius, 0.0], centre - [t.radius, 0.0]]), np.array([1.0, 1.0]))
    holes = (Circle((0.0, 0.0), t.bore / 2),) if t.bore > 0 else ()
    return EccentricDesign(spec, Part(spec.name, outline, holes, t.thickness, spec.output.tolerance))


def report_of(d: EccentricDesign) -> dict[str, Any]:
    t = d.spec.eccentric
    theta = np.linspace(0.0, 2 * math.pi, 721)
    return {"eccentric": {"radius_mm": t.radius, "eccentricity_mm": t.eccentricity},
            "stroke_mm": float(np.ptp(d.lift(theta))),
            "pressure_angle_max_deg": float(np.max(np.abs(d.pressure_angle_deg(theta)))),
            "pressure_angle_limit_deg": t.max_pressure_angle, "warnings": []}


def page(d: EccentricDesign, report: dict[str, Any]) -> Page:
    t = d.spec.eccentric
    theta = np.radians(np.arange(FRAMES) * 360.0 / FRAMES)
    ring = d.part.outline.flatten(d.spec.output.tolerance)
    rest = t.radius + t.roller_radius - t.eccentricity
    centre = np.column_stack([np.zeros_like(theta), rest + d.lift(theta)])
    return Page(d.spec.name, f"{d.spec.name}: eccentric disc", f"e = {t.eccentricity:g} mm, R = {t.radius:g} mm",
                "cam angle", "deg", np.degrees(theta),
                Scene((Body("disc", (Outline(ring, "part"),), pose_motion(np.degrees(theta))),),
                      (Mover("roller", centre[:, None, :], "roller", t.roller_radius),)),
                (Plot("displacement s", "mm", (("s", d.lift(theta)),)),
                 Plot("pressure angle", "deg", (("pressure angle", d.pressure_angle_deg(theta)),))),
                key_figures(report, (("stroke", "stroke_mm", "mm"),
                                     ("largest pressure angle", "pressure_angle_max_deg", "deg"))))


def bundle(d: EccentricDesign) -> tuple[Bundle, dict[str, Any]]:
    from camgen.core.solids import extrude

    out, name = d.spec.output, d.spec.name
    report = report_of(d)
    items = [item(Drawing.of_part(d.part), [("dxf", "dxf", f"{name}.dxf")], out.formats),
             item(lambda: extrude(d.part), [("stl", "stl", f"{name}.stl")], out.formats),
             *tail(name, None, (), report, lambda: page(d, report), out.formats)]
    return Bundle.of(items, out.write_options), report


def size(spec: EccentricSpec) -> SizeReport:
    """The smallest radius R whose largest pressure angle, asin(e / (R + Rr)), stays within the limit."""
    t = spec.eccentric
    pressure = t.eccentricity / math.sin(math.radians(t.max_pressure_angle)) - t.roller_radius
    fit = t.eccentricity + t.bore / 2
    return SizeReport(Sizing(max(pressure, fit), "pressure angle" if pressure >= fit else "bore", pressure, 0.0,
                             t.max_pressure_angle, 0.0), notes=(f"the bore needs R > {fit:g} mm",))


class EccentricKind(KindBase[EccentricSpec, EccentricDesign]):
    name = "eccentric"
    title = "an eccentric disc"
    table_key = "eccentric"
    formats = frozenset({"dxf", "stl", "json", "html"})
    starters = {"eccentric": Starter("An eccentric disc under a translating roller: a stroke of twice e.",
                                     (("eccentric", {"radius": 30.0, "eccentricity": 10.0, "roller_radius": 8.0,
                                                     "thickness": 6.0, "bore": 8.0}),),
                                     {"eccentric.eccentricity": "mm: the stroke is twice this"})}

    @property
    def spec(self) -> type[EccentricSpec]:
        return EccentricSpec

    def operations(self) -> Operations[EccentricSpec, EccentricDesign]:
        return Operations(design, bundle, lambda d, report: [f"stroke {report['stroke_mm']:.4f} mm"],
                          lambda d, report: {"stroke_mm": report["stroke_mm"]}, size)


KIND = EccentricKind()
'''


def _plugin(folder: Path, module: str, entry: str) -> Path:
    """``folder`` holding the module ``module`` (the toy kind) and the metadata of a distribution declaring the
    entry point ``entry`` (``name = module:KIND``) in the group ``camgen.kinds``."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{module}.py").write_text(TOY)
    info = folder / f"{module}-1.0.dist-info"
    info.mkdir(exist_ok=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {module}\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(f"[camgen.kinds]\n{entry}\n")
    return folder


#: the installed console script, which imports the package first found on the path (the checkout's, below)
SCRIPT = shutil.which("camgen")


def _camgen(cwd: Path, site: Path, *args: str, script: bool = False) -> subprocess.CompletedProcess:
    """``python -m camgen ARGS`` (with ``script``: the ``camgen`` console script) in its own interpreter, run from
    ``cwd`` with ``site`` and the checkout (which the installed package stands for) first on its path."""
    if script and SCRIPT is None:
        pytest.skip("no camgen console script installed")
    path = os.pathsep.join([str(site), str(ROOT), os.environ.get("PYTHONPATH", "")])
    command = [SCRIPT] if script else [sys.executable, "-m", "camgen"]
    return subprocess.run([*command, *args], cwd=cwd, capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": path}, timeout=300)


def _checkout_files() -> set[str]:
    """Every file under the checkout that git does not ignore (tracked or not): what a test must leave alone."""
    listed = subprocess.run(["git", "ls-files", "--others", "--cached", "--exclude-standard"], cwd=ROOT,
                            capture_output=True, text=True, check=True)
    return set(listed.stdout.splitlines())


@pytest.fixture()
def toy(tmp_path: Path) -> tuple[Path, Path]:
    """A plugin folder with the toy kind and a working folder, both outside the checkout."""
    work = tmp_path / "work"
    work.mkdir()
    assert ROOT not in work.parents
    return _plugin(tmp_path / "site", "toy_eccentric", "eccentric = toy_eccentric:KIND"), work


def test_a_plugin_kind_is_made_built_and_sized_by_the_console_commands(toy):
    site, work = toy
    before = _checkout_files()
    new = _camgen(work, site, "new", "eccentric", "-o", "ecc.toml", script=True)
    assert new.returncode == 0, new.stderr
    text = (work / "ecc.toml").read_text()
    assert "[eccentric]" in text and "the stroke is twice this" in text

    built = _camgen(work, site, "build", "ecc.toml", "-o", "out")
    assert built.returncode == 0, built.stderr
    assert sorted(p.name for p in (work / "out").iterdir()) == ["ecc.dxf", "ecc.html", "ecc.json", "ecc.stl"]
    # the closed forms: R = 30, e = 10, Rr = 8, so rho = 38, a stroke of 2 e and a pressure angle of asin(e / rho)
    report = json.loads((work / "out" / "ecc.json").read_text())
    assert report["stroke_mm"] == pytest.approx(20.0, abs=1e-9)
    assert report["pressure_angle_max_deg"] == pytest.approx(math.degrees(math.asin(10 / 38)), abs=1e-3)
    assert set(report["files"].values()) == {"ecc.dxf", "ecc.html", "ecc.json", "ecc.stl"}
    assert "stroke 20.0000 mm" in built.stdout

    import ezdxf

    entities = list(ezdxf.readfile(work / "out" / "ecc.dxf").modelspace())
    (outline,) = [e for e in entities if e.dxf.layer == "OUTLINE"]
    (a, *_, ba), (b, *_, bb) = outline.get_points("xyseb")
    assert (ba, bb) == (1.0, 1.0)                          # two half circles: the disc, exactly
    assert ((a + b) / 2, abs(b - a) / 2) == (pytest.approx(-10.0), pytest.approx(30.0))
    (bore,) = [e for e in entities if e.dxf.layer == "HOLES"]
    assert bore.dxftype() == "CIRCLE" and bore.dxf.radius == pytest.approx(4.0) and bore.dxf.center.x == 0.0

    import trimesh

    mesh = trimesh.load(work / "out" / "ecc.stl")
    exact = math.pi * (30.0 ** 2 - 4.0 ** 2) * 6.0          # the disc less the bore, 6 mm thick
    assert mesh.is_watertight and mesh.volume == pytest.approx(exact, rel=2e-3)
    assert mesh.bounds.ravel().tolist() == pytest.approx([-40.0, -30.0, 0.0, 20.0, 30.0, 6.0], abs=0.02)

    page = (work / "out" / "ecc.html").read_text()
    assert "ecc: eccentric disc" in page and "stroke" in page and "largest pressure angle" in page

    sized = _camgen(work, site, "size", "ecc.toml", "--json", script=True)
    assert sized.returncode == 0, sized.stderr
    s = json.loads(sized.stdout)
    # asin(e / (R + Rr)) = 30 degrees: R = e / sin 30 - Rr = 12 mm, less than the bore needs (e + 4 = 14)
    assert s["pressure_radius_mm"] == pytest.approx(12.0, abs=1e-12)
    assert (s["base_radius_mm"], s["decided_by"]) == (pytest.approx(14.0), "bore")
    assert _checkout_files() == before


def test_a_plugin_kind_refuses_what_its_kind_does_not_take(toy):
    site, work = toy
    _camgen(work, site, "new", "eccentric", "-o", "ecc.toml")
    step = _camgen(work, site, "build", "ecc.toml", "-o", "out", "--set", 'output.formats=["step"]')
    assert step.returncode == 2 and step.stderr.splitlines() == [
        "error: output.formats: an eccentric disc writes no 'step' file; give formats of dxf, html, json, stl"]
    inside = _camgen(work, site, "build", "ecc.toml", "-o", "out", "--set", "eccentric.radius=12")
    assert inside.returncode == 2 and inside.stderr.startswith("error: eccentric.radius: must be > ")
    assert len(inside.stderr.splitlines()) == 1 and not (work / "out").exists()


def test_a_plugin_kind_named_as_a_built_in_one_is_refused_in_one_line(tmp_path):
    site = _plugin(tmp_path / "site", "toy_disc", "disc = toy_disc:KIND")
    work = tmp_path / "work"
    work.mkdir()
    (work / "c.toml").write_text((ROOT / "templates" / "rdrd.toml").read_text())
    result = _camgen(work, site, "build", "c.toml", "-o", "out")
    assert result.returncode == 2 and len(result.stderr.splitlines()) == 1, result.stderr
    assert result.stderr.startswith("error: camgen.kinds: the plugin kind 'disc' (toy_disc:KIND) is named as a "
                                    "built-in kind")
    assert not (work / "out").exists()


def test_without_plugins_the_registry_holds_the_built_in_kinds_only():
    """The registry in this interpreter (no plugin on its path) is the seven built-in kinds, in order."""
    from camgen.kinds import KINDS

    assert list(KINDS) == ["disc", "plate", "grooved", "barrel", "conjugate", "geneva", "machine"]

