"""What a command loads: ``import camgen``, ``camgen laws`` and a DXF-only build load neither matplotlib nor trimesh,
a cam's DXF, STL and JSON build nothing of the Geneva drive, the cut sheets, the pages or the kits, and no build
loads trimesh (the STL and 3MF are written and the mesh checked with numpy; here they are checked against
trimesh's, byte for byte). Each command runs in a fresh interpreter, whose ``sys.modules`` is read. And how a
command that makes one design treats the garbage collector (paused while it runs, frozen at the exit)."""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from tests.conftest import ROOT

HEAVY = ("matplotlib", "trimesh")


def _modules(code: str) -> set[str]:
    """The modules loaded once ``code`` has run in a fresh interpreter (in the checkout)."""
    probe = code + "\nimport sys, json\nprint('loaded:', json.dumps(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True, text=True, check=True)
    line = next(line for line in out.stdout.splitlines() if line.startswith("loaded: "))
    return set(json.loads(line.removeprefix("loaded: ")))


def _loaded(code: str) -> set[str]:
    """The top-level modules loaded once ``code`` has run in a fresh interpreter (in the checkout)."""
    return {m.split(".")[0] for m in _modules(code)}


def _command(program: str, *args: str) -> str:
    """Code that runs ``program`` (camgen or linkgen) with ``args`` in the interpreter, as the command would."""
    return (f"import sys\nfrom {program}.cli import main\nsys.argv = {[program, *args]!r}\n"
            "try:\n    main()\nexcept SystemExit as exc:\n    assert not exc.code, exc.code")


def test_import_camgen_loads_no_heavy_library():
    assert not _loaded("import camgen, linkgen") & {*HEAVY, "ezdxf", "scipy", "shapely", "pydantic"}


def test_camgen_laws_loads_no_heavy_library():
    assert not _loaded(_command("camgen", "laws")) & {*HEAVY, "ezdxf", "scipy", "shapely", "manifold3d"}


def test_a_dxf_only_build_loads_neither_matplotlib_nor_trimesh(tmp_path):
    loaded = _loaded(_command("camgen", "build", str(ROOT / "templates" / "rdrd.toml"), "-o", str(tmp_path),
                              "--set", 'output.formats=["dxf"]'))
    assert (tmp_path / "rdrd.dxf").is_file() and not (tmp_path / "rdrd.stl").exists()
    assert "ezdxf" in loaded and not loaded & set(HEAVY)


#: what a cam's build of DXF, STL and JSON does not use: cut sheets, pages, kits, figures, the speed's dynamics and
#: forces (no cam.rpm), a flat face's envelope, the second mesh library (each package with everything below it)
NOT_FOR_A_CAM = ("camgen.core.nesting", "camgen.core.page", "camgen.page", "camgen.kit",
                 "camgen.plots", "camgen.core.figures", "camgen.dynamics", "camgen.forces", "camgen.flat_envelope",
                 "matplotlib", "trimesh", "scipy")


def test_a_cam_s_dxf_stl_json_build_loads_only_what_those_files_need(tmp_path):
    modules = _modules(_command("camgen", "build", str(ROOT / "templates" / "rdrd.toml"), "-o", str(tmp_path),
                                "--set", 'output.formats=["dxf","stl","json"]'))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rdrd.dxf", "rdrd.json", "rdrd.stl"]
    assert not {m for m in modules for name in NOT_FOR_A_CAM if m == name or m.startswith(name + ".")}
    assert {"camgen.profile", "camgen.core.writers.dxf", "camgen.core.writers.stl", "ezdxf"} <= modules
    # of every other kind (the Geneva drive's models included) only what the registry holds: its declaration
    from camgen.kinds import BUILT_IN

    others = {f"camgen.kinds.{kind.name}" for kind in BUILT_IN if kind.name != "disc"}
    loaded = {m for m in modules for pkg in others if m == pkg or m.startswith(pkg + ".")}
    declared = {f"{pkg}{part}" for pkg in others for part in ("", ".kind", ".starters")}
    assert {"camgen.kinds.geneva", "camgen.kinds.geneva.kind"} <= loaded <= declared


def test_a_geneva_drive_still_builds_with_its_modules_loaded_on_demand(tmp_path):
    """The Geneva drive's spec, design and files load only for a ``[geneva]`` template: its build, and a family
    member's row, still find them."""
    modules = _modules(_command("camgen", "build", str(ROOT / "templates" / "geneva4.toml"), "-o", str(tmp_path),
                                "--set", 'output.formats=["dxf","json"]'))
    report = json.loads((tmp_path / "geneva4.json").read_text())
    assert "geneva" in report and (tmp_path / "geneva4-sheet.dxf").is_file()
    assert {"camgen.kinds.geneva.table", "camgen.kinds.geneva.design", "camgen.core.nesting"} <= modules


def test_a_one_design_command_pauses_the_collector_and_restores_it(tmp_path, monkeypatch):
    """In the running interpreter (as tests call the commands): the collector is off while the design is made
    and back on afterwards, also after a refusal. In a command's own interpreter, what is alive at its exit is
    frozen (out of the shutdown's collections) before the exit handlers registered earlier run."""
    import gc

    from click.testing import CliRunner

    import camgen.api
    from camgen.cli import main
    from camgen.core.errors import DesignError

    real, seen = camgen.api.design, []

    def recording(spec, *args, **kwargs):              # what the collector was doing while the design was made
        seen.append(gc.isenabled())
        if spec.cam.thickness == 7.0:
            raise DesignError("cam.thickness: refused by the test")
        return real(spec, *args, **kwargs)

    monkeypatch.setattr(camgen.api, "design", recording)
    build = ["build", str(ROOT / "templates" / "rdrd.toml"), "-o", str(tmp_path), "--set"]
    assert gc.isenabled()
    ok = CliRunner().invoke(main, [*build, 'output.formats=["json"]'])
    assert ok.exit_code == 0 and seen == [False] and gc.isenabled()
    refused = CliRunner().invoke(main, [*build, "motion.0.angle=-30"])
    assert refused.exit_code == 2 and refused.output.startswith("error: motion[0].angle") and gc.isenabled()
    failed = CliRunner().invoke(main, [*build, "cam.thickness=7"])
    assert failed.exit_code == 2 and failed.output.startswith("error: cam.thickness: refused by the test")
    assert seen == [False, False] and gc.isenabled()
    probe = ("import atexit, gc\natexit.register(lambda: print('frozen at exit:', gc.get_freeze_count()))\n"
             + _command("camgen", "laws"))
    out = subprocess.run([sys.executable, "-c", probe], cwd=ROOT, capture_output=True, text=True, check=True)
    frozen = int(out.stdout.splitlines()[-1].removeprefix("frozen at exit: "))
    assert frozen > 10_000


@pytest.mark.parametrize("template", ["rdrd.toml", "geneva4.toml"])
def test_a_default_build_loads_no_mesh_library(tmp_path, template):
    """Every default output, STL and 3MF included, without trimesh (nor lxml and networkx, which it wrote 3MF
    with)."""
    loaded = _loaded(_command("camgen", "build", str(ROOT / "templates" / template), "-o", str(tmp_path)))
    assert list(tmp_path.glob("*.stl")) and list(tmp_path.glob("*.3mf"))
    assert not loaded & {"trimesh", "lxml", "networkx", "scipy"}


def test_linkgen_build_loads_no_mesh_library(tmp_path):
    loaded = _loaded(_command("linkgen", "build", str(ROOT / "templates" / "crank-rocker.toml"), "-o",
                              str(tmp_path)))
    assert list(tmp_path.glob("*.stl")) and not loaded & {"trimesh", "lxml", "networkx"}


# ---- the mesh files and their check, against trimesh's ----

def _meshes() -> list:
    import camgen
    from camgen.core.solids import extrude, stack

    parts = [camgen.design_cam(camgen.load_spec(ROOT / "templates" / f"{name}.toml")).printed
             for name in ("rdrd", "plate", "grooved", "flat-face", "oscillating")]
    return [extrude(part) for part in parts] + [stack(parts[:2], "stacked")]


@pytest.fixture(scope="module")
def meshes() -> list:
    return _meshes()


def _trimesh_3mf(mesh) -> bytes:
    """The 3MF package as the project wrote it with trimesh until it wrote its own: trimesh's export, repacked with
    fixed dates and UUIDs made from the mesh."""
    import hashlib
    import io
    import itertools
    import re
    import uuid
    import zipfile

    import trimesh

    from camgen.core.solids import trimesh_of

    scene = trimesh.Scene()
    scene.add_geometry(trimesh_of(mesh), geom_name=mesh.name, node_name=mesh.name)
    raw = zipfile.ZipFile(io.BytesIO(scene.export(file_type="3mf")))
    digest = hashlib.sha256(mesh.vertices.tobytes() + mesh.faces.tobytes()).hexdigest()
    count = itertools.count()

    def fixed(_: re.Match) -> str:
        return f'UUID="{uuid.uuid5(uuid.NAMESPACE_URL, f"camgen:{digest}:{next(count)}")}"'

    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as package:
        for name in sorted(raw.namelist()):
            data = raw.read(name)
            if name.endswith(".model"):
                data = re.sub(r'UUID="[0-9a-fA-F-]+"', fixed, data.decode("utf-8")).encode("utf-8")
            package.writestr(zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0)), data,
                             compress_type=zipfile.ZIP_DEFLATED)
    return out.getvalue()


def test_stl_and_3mf_are_trimesh_s_bytes(meshes):
    from camgen.core.solids import trimesh_of
    from camgen.core.writers.stl import stl_bytes
    from camgen.core.writers.threemf import threemf_bytes

    for mesh in meshes:
        assert stl_bytes(mesh) == trimesh_of(mesh).export(file_type="stl"), mesh.name
        assert threemf_bytes(mesh) == _trimesh_3mf(mesh), mesh.name


def test_mesh_check_agrees_with_trimesh(meshes):
    """Closed, consistently wound, the same volume to the last bit, distinct vertices: as trimesh finds them."""
    from camgen.core.solids import check_mesh, trimesh_of

    for mesh in meshes:
        ours, tm = check_mesh(mesh), trimesh_of(mesh)
        assert (ours.watertight, ours.winding_consistent) == (tm.is_watertight, tm.is_winding_consistent) == (True,
                                                                                                               True)
        assert ours.volume_mm3 == float(tm.volume) and ours.triangles == len(tm.faces) and ours.ok


def test_mesh_check_finds_a_hole_a_flipped_triangle_and_an_inside_out_solid(meshes):
    from camgen.core.solids import Mesh, check_mesh

    mesh = meshes[0]
    holed = check_mesh(Mesh(mesh.vertices, mesh.faces[1:], mesh.name))
    assert not holed.watertight and not holed.ok
    flipped = mesh.faces.copy()
    flipped[0] = flipped[0, ::-1]
    turned = check_mesh(Mesh(mesh.vertices, flipped, mesh.name))
    assert turned.watertight and not turned.winding_consistent and not turned.ok
    inside_out = check_mesh(Mesh(mesh.vertices, mesh.faces[:, ::-1], mesh.name))
    assert inside_out.winding_consistent and inside_out.volume_mm3 < 0 and not inside_out.ok
    merged = mesh.vertices.copy()
    merged[1] = merged[0] * (1 + 1e-9)                                  # one point in single precision
    assert not check_mesh(Mesh(merged, mesh.faces, mesh.name)).distinct_in_float32


def test_stl_reads_back(meshes):
    """The STL's triangles are the mesh's in single precision, with unit normals along their cross products."""
    from camgen.core.writers.stl import stl_bytes

    mesh = meshes[1]
    data = stl_bytes(mesh)
    count = int(np.frombuffer(data[80:84], "<u4")[0])
    facets = np.frombuffer(data[84:], dtype=[("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")])
    assert count == len(mesh.faces) == len(facets)
    assert np.array_equal(facets["v"], mesh.vertices[mesh.faces].astype(np.float32))
    corners = facets["v"].astype(float)
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    cross /= np.linalg.norm(cross, axis=1)[:, None]
    assert np.allclose(facets["n"], cross, atol=1e-5)


#: scipy's subpackages a linkage's or a machine's build needs none of, unless its template asks for a motion from
#: rest, a speed profile or a slider's guide (about 0.35 s of the command's start: special functions, optimisers,
#: splines, integrators and what they import)
SCIPY_HEAVY = ("scipy.integrate", "scipy.interpolate", "scipy.optimize", "scipy.special")


@pytest.mark.parametrize(("program", "name"), [("linkgen", "crank-rocker"), ("linkgen", "eightbar-triad"),
                                               ("camgen", "automaton")])
def test_a_linkage_or_machine_build_loads_no_scipy_subpackage_it_does_not_use(tmp_path, program, name):
    modules = _modules(_command(program, "build", str(ROOT / "templates" / f"{name}.toml"), "-o", str(tmp_path)))
    assert (tmp_path / f"{name}.json").is_file()
    assert not {m for m in modules for pkg in SCIPY_HEAVY if m == pkg or m.startswith(pkg + ".")}


def test_a_motion_from_rest_still_finds_scipy_s_integrator(tmp_path):
    """The dynamics' spline and integrator are imported where a motion is worked out: a template that asks for one
    (jansen-motor.toml) still builds, and loads them."""
    modules = _modules(_command("linkgen", "build", str(ROOT / "templates" / "jansen-motor.toml"), "-o",
                                str(tmp_path)))
    assert (tmp_path / "jansen-motor.json").is_file() and {"scipy.integrate", "scipy.interpolate"} <= modules
