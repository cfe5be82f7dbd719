"""The scripting API: importable from camgen and linkgen, cheap to import, objects that render in Jupyter."""
from __future__ import annotations

import ast
import importlib
import importlib.util
import json
import subprocess
import sys
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

import camgen
import linkgen
from tests.conftest import ROOT, template


def test_public_names_resolve():
    for name in camgen.__all__:
        assert getattr(camgen, name) is not None
    for name in linkgen.__all__:
        assert getattr(linkgen, name) is not None


def test_import_stays_light():
    code = "import sys, camgen, linkgen; print(sorted(m for m in ('ezdxf', 'trimesh', 'matplotlib', 'scipy') " \
           "if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_objects_render_themselves_as_svg():
    design = camgen.design_cam(template())
    linkages = [linkgen.design_linkage(linkgen.validate_spec({"name": "fb", "linkage": {"type": "four-bar", **table}}))
                for table in ({"ground": 180, "crank": 80, "coupler": 200, "rocker": 150, "point_distance": 100,
                               "point_angle": 28.6479}, {"ground": 100, "crank": 70, "coupler": 60, "rocker": 80})]
    for obj in (design, design.part, camgen.Drawing.of_part(design.part), *linkages):
        root = ET.fromstring(obj._repr_svg_())
        assert root.tag.endswith("svg") and root.get("width").endswith("mm")
        assert root.findall(".//{http://www.w3.org/2000/svg}path")


def test_a_family_in_ten_lines(tmp_path):
    """docs/tutorials/scripting.md: a family made in a few lines of Python."""
    rows = []
    for lift in (10, 20, 30):
        spec = camgen.load_spec(ROOT / "templates" / "rdrd.toml", [f"motion.0.lift={lift}", f"motion.2.lift={lift}",
                                                            f"name='cam-{lift}'", "output.formats=['dxf']"])
        design = camgen.design_cam(spec)
        camgen.write_cam(design, tmp_path / spec.name)
        rows.append((lift, design.analysis.pressure_angle_max_deg))
    assert [r[0] for r in rows] == [10, 20, 30] and rows[0][1] < rows[2][1]
    assert all((tmp_path / f"cam-{lift}" / f"cam-{lift}.dxf").exists() for lift in (10, 20, 30))


# ---------------------------------------------------------------------- the typed API (issue 31, item 4)


def _close(ours, theirs, where="report"):
    """Whether two JSON values agree: numbers within 1e-9 relative (1e-9 absolute near 0), everything else equal."""
    if isinstance(ours, dict):
        assert isinstance(theirs, dict) and list(ours) == list(theirs), where
        for key in ours:
            _close(ours[key], theirs[key], f"{where}.{key}")
    elif isinstance(ours, list):
        assert isinstance(theirs, list) and len(ours) == len(theirs), where
        for i, (a, b) in enumerate(zip(ours, theirs, strict=True)):
            _close(a, b, f"{where}[{i}]")
    elif isinstance(ours, float) or isinstance(theirs, float):
        assert ours == pytest.approx(theirs, rel=1e-9, abs=1e-9), where
    else:
        assert ours == theirs, where


def _command(program: str, *args: str) -> None:
    """Run ``program`` (camgen or linkgen) of this checkout with ``args``; it must succeed."""
    result = subprocess.run([sys.executable, "-m", program, *args], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def test_the_issue_s_idiom_writes_a_cam_as_the_command_does(tmp_path):
    spec = camgen.CamSpec.from_toml(ROOT / "templates" / "rdrd.toml").with_changes({"motion.0.lift": 25,
                                                                                    "motion.2.lift": 25})
    design = camgen.design(spec)
    written = camgen.write(design, tmp_path / "api", formats=["dxf", "stl", "json"])
    assert (spec.motion[0].lift, spec.motion[2].lift) == (25, 25) and "html" in spec.output.formats
    assert written.files == {"dxf": tmp_path / "api" / "rdrd.dxf", "stl": tmp_path / "api" / "rdrd.stl",
                             "json": tmp_path / "api" / "rdrd.json"}
    assert sorted(p.name for p in (tmp_path / "api").iterdir()) == ["rdrd.dxf", "rdrd.json", "rdrd.stl"]
    _command("camgen", "build", str(ROOT / "templates" / "rdrd.toml"), "-o", str(tmp_path / "cli"), "--set",
             "motion.0.lift=25", "--set", "motion.2.lift=25", "--set", 'output.formats=["dxf","stl","json"]')
    cli = json.loads((tmp_path / "cli" / "rdrd.json").read_text())
    _close(written.report, cli)
    _close(json.loads(written.files["json"].read_text()), cli)
    assert cli["lift_max_mm"] == pytest.approx(25, abs=1e-9)
    assert cli["pressure_angle_max_deg"] == pytest.approx(design.analysis.pressure_angle_max_deg, rel=1e-9)
    assert cli["files"] == {"dxf": "rdrd.dxf", "stl": "rdrd.stl",
                                                                             "json": "rdrd.json"}


def test_the_issue_s_idiom_writes_a_linkage_as_the_command_does(tmp_path):
    template = ROOT / "templates" / "crank-rocker.toml"
    spec = linkgen.LinkageSpec.from_toml(template).with_changes({"linkage.crank": 60})
    design = linkgen.design(spec, parts=True)
    written = linkgen.write(design, tmp_path / "api", formats=["json", "dxf"])
    assert spec.linkage.crank == 60 and design.build is not None
    assert written.files == {"sheet_dxf": tmp_path / "api" / "crank-rocker-sheet.dxf",
                             "assembly_dxf": tmp_path / "api" / "crank-rocker-assembly.dxf",
                             "json": tmp_path / "api" / "crank-rocker.json"}
    assert sorted(p.name for p in (tmp_path / "api").iterdir()) == sorted(p.name for p in written.files.values())
    _command("linkgen", "build", str(template), "-o", str(tmp_path / "cli"), "--set", "linkage.crank=60",
             "--set", 'output.formats=["json","dxf"]')
    cli = json.loads((tmp_path / "cli" / "crank-rocker.json").read_text())
    _close(written.report, cli)
    _close(json.loads(written.files["json"].read_text()), cli)
    assert cli["lengths_mm"]["crank"] == 60.0


def _type_checking_imports(package) -> dict[str, str]:
    """``{name: module}`` of the imports under ``if TYPE_CHECKING:`` in ``package``'s ``__init__.py`` (each written
    ``from module import name as name``, so that a type checker re-exports it)."""
    tree = ast.parse(Path(package.__file__).read_text())
    block = next(node for node in tree.body if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING")
    found = {}
    for node in block.body:
        assert isinstance(node, ast.ImportFrom), ast.unparse(node)
        for alias in node.names:
            assert alias.asname == alias.name, ast.unparse(node)
            found[alias.name] = node.module
    return found


@pytest.mark.parametrize("package", [camgen, linkgen], ids=["camgen", "linkgen"])
def test_every_public_name_is_its_type_checking_import(package):
    exports = package._EXPORTS
    assert _type_checking_imports(package) == exports
    assert [n for n in package.__all__ if n != "__version__"] == list(exports)
    for name, module in exports.items():
        assert getattr(package, name) is getattr(importlib.import_module(module), name), name
    assert dir(package) == sorted(package.__all__)
    with pytest.raises(AttributeError, match="has no attribute 'desing'"):
        _ = package.desing


def test_no_public_name_is_shadowed_by_a_submodule():
    """Importing every submodule binds each as an attribute of its package; none may take a public name's place
    (``camgen.design`` stays the function after ``camgen.kinds.geneva.design`` or any ``design`` module is imported)."""
    code = ("import importlib, pkgutil, camgen, linkgen\n"
            "for package in (camgen, linkgen):\n"
            "    for info in pkgutil.walk_packages(package.__path__, package.__name__ + '.'):\n"
            "        if not info.name.endswith('.__main__'):\n"
            "            importlib.import_module(info.name)\n"
            "    for name, module in package._EXPORTS.items():\n"
            "        assert getattr(package, name) is getattr(importlib.import_module(module), name), name\n"
            "assert callable(camgen.design) and callable(linkgen.design) and callable(camgen.write)\n"
            "print(len(camgen._EXPORTS) + len(linkgen._EXPORTS))")
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert int(result.stdout) == len(camgen._EXPORTS) + len(linkgen._EXPORTS)


def test_one_error_hierarchy_from_either_package():
    for name in ("CamgenError", "SpecError", "DesignError", "SolverError", "ExportError"):
        assert getattr(linkgen, name) is getattr(camgen, name)
    assert issubclass(camgen.SpecError, ValueError) and issubclass(camgen.SpecError, camgen.CamgenError)
    with pytest.raises(camgen.SpecError, match=r"^linkage\.crank: must be > 0"):
        linkgen.LinkageSpec.from_toml(ROOT / "templates" / "crank-rocker.toml").with_changes({"linkage.crank": -5})


def _model(name: str):
    """The spec class a test names: camgen's or linkgen's by its name, a mechanism's own by its linkage.type."""
    from linkgen.spec import spec_model

    if name in linkgen.MECHANISMS:
        return spec_model(linkgen.MECHANISMS[name])
    from camgen.kinds.barrel.table import BarrelSpec
    from camgen.kinds.disc.table import DiscSpec

    return {"CamSpec": camgen.CamSpec, "GenevaSpec": camgen.GenevaSpec, "LinkageSpec": linkgen.LinkageSpec,
            "DiscSpec": DiscSpec, "BarrelSpec": BarrelSpec}[name]


@pytest.mark.parametrize("cls, name, message", [
    ("CamSpec", "geneva4.toml", "template: a Geneva drive, not a cam"),
    ("GenevaSpec", "rdrd.toml", "template: a cam, not a Geneva drive"),
    ("CamSpec", "crank-rocker.toml", "template: this is a linkgen template: use `linkgen build` or `linkgen analyze`"),
    ("LinkageSpec", "rdrd.toml", "template: this is a camgen template: use `camgen build`"),
    ("slider-crank", "crank-rocker.toml", "template: a four-bar linkage, not a slider-crank linkage"),
    ("DiscSpec", "barrel.toml", "template: a barrel cam, not a disc cam"),
    ("BarrelSpec", "rdrd.toml", "template: a disc cam, not a barrel cam"),
])
def test_from_toml_refuses_another_kind_s_template_in_one_line(cls, name, message):
    model = _model(cls)
    with pytest.raises(camgen.SpecError) as caught:
        model.from_toml(ROOT / "templates" / name)
    assert str(caught.value) == message and caught.value.field == "template"
    with pytest.raises(camgen.SpecError) as caught:
        model.from_mapping(tomllib.loads((ROOT / "templates" / name).read_text()))
    assert str(caught.value) == message


def test_a_spec_of_its_own_class_is_the_one_the_product_loads():
    geneva = ROOT / "templates" / "geneva4.toml"
    assert camgen.GenevaSpec.from_toml(geneva) == camgen.load(geneva)
    rdrd = ROOT / "templates" / "rdrd.toml"
    assert camgen.CamSpec.from_mapping(tomllib.loads(rdrd.read_text())) == camgen.CamSpec.from_toml(rdrd)
    assert type(camgen.CamSpec.from_toml(ROOT / "templates" / "barrel.toml")).__name__ == "BarrelSpec"
    assert camgen.CamSpec.from_toml(rdrd, ["motion.0.lift=25"]) == \
        camgen.CamSpec.from_toml(rdrd).with_changes({"motion.0.lift": 25})


@pytest.mark.parametrize("path", sorted((ROOT / "templates").glob("*.toml")), ids=lambda p: p.stem)
def test_no_changes_give_the_same_spec(path):
    """A spec dumped and validated again is itself, for every bundled template (table laws' rows, defaults
    filled in by validators, a linkage's own table included)."""
    raw = tomllib.loads(path.read_text())
    if "sweep" in raw or "task" in raw:
        pytest.skip("a family or a synthesis task: no single spec")
    spec = (linkgen.LinkageSpec if "linkage" in raw else camgen.CamSpec if "cam" in raw else camgen.MachineSpec
            if "machine" in raw else camgen.GenevaSpec).from_toml(path)
    assert spec.with_changes({}) == spec and type(spec.with_changes({})) is type(spec)


def test_with_changes_names_the_key_it_cannot_set_or_the_value_it_refuses():
    spec = camgen.CamSpec.from_toml(ROOT / "templates" / "rdrd.toml")
    with pytest.raises(camgen.SpecError) as caught:
        spec.with_changes({"motion.9.lift": 25})
    assert str(caught.value) == "motion.9.lift: no item 9 in 'motion' (it has 4 items, indexed from 0)"
    with pytest.raises(camgen.SpecError, match=r"^motion\[0\]\.lift: must be > 0 and <= 10000 mm.* \(got -1\)$"):
        spec.with_changes({"motion.0.lift": -1})
    assert spec.motion[0].lift == 20                  # frozen: the spec changed is a new one


def test_a_linkage_s_type_changed_gives_that_type_s_spec():
    spec = linkgen.LinkageSpec.from_toml(ROOT / "templates" / "crank-rocker.toml")
    slider = spec.with_changes({"linkage": {"type": "slider-crank", "crank": 40, "rod": 120}})
    assert type(slider).mechanism is linkgen.MECHANISMS["slider-crank"] and slider.name == spec.name
    assert isinstance(slider, linkgen.LinkageSpec) and not isinstance(slider, type(spec))


def test_write_refuses_a_format_the_kind_does_not_write_and_writes_nothing(tmp_path):
    design = linkgen.design(linkgen.LinkageSpec.from_toml(ROOT / "templates" / "crank-rocker.toml"))
    with pytest.raises(camgen.SpecError, match=r"^output\.formats: 'step' writes the linkage's parts"):
        linkgen.write(design, tmp_path / "out", formats=["json", "step"])
    with pytest.raises(camgen.SpecError, match=r"^formats: give a list of formats, e\.g\. \['dxf'\]"):
        camgen.write(camgen.design(camgen.CamSpec.from_toml(ROOT / "templates" / "rdrd.toml")), tmp_path / "out",
                     formats="dxf")
    assert not (tmp_path / "out").exists()



def test_each_cam_kind_s_spec_is_named_as_its_table():
    from camgen.spec import cam_specs

    for kind, spec in cam_specs().items():
        table = spec.model_fields["cam"].annotation
        assert spec.noun == table.model_config["title"], kind
