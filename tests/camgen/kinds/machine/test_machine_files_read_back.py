"""Every file of the bundled machines read back by the programs people use (issue 35): each template with a
``[machine]`` table and each of the machine kind's starters, built once with every format a machine writes, and
every file it wrote opened by a real reader that is asked for numbers the report (or another file of the same part)
also gives:

* DXF: ezdxf's audit finds nothing to fix; LibreCAD prints each drawing at scale 1 the size ezdxf measures (to two
  pixels at 50 dpi); a frame plate's outline is the report's plate to its tolerance.
* STL: admesh finds no open, degenerate or flipped facet, pymeshlab a closed two-manifold that does not cross
  itself, the two the same volume; each is as thick as its part (the report's plate, spacer, cam or bar), a cam's
  volume the one its own report gives.
* 3MF: PrusaSlicer reads each part's file closed, of its STL's volume and its part's thickness, and slices each to
  G-code a part's height tall; it slices the assembly's made parts, every one of them, and not the bought ones.
* STEP: FreeCAD (one process for every machine) finds one valid solid per piece of the report's assembly, each
  standing at its bounds and height to 0.01 mm, of its 3MF object's volume (the 3MF's chords against the STEP's arcs).
* HTML: headless Chromium opens every page (the machine's and each mount's) without a console message; Play runs the
  machine's animation; its Animate link names the GIF written beside it.
* PNG, SVG, GIF: each opens as an image or parses as SVG; a cut SVG is its DXF's drawing in mm; the GIF has the
  default frames and size, its frames moving.
* CSV and JSON: the timing table's samples, outputs and extremes are the report's; the kit's lines are the frame's
  bill of materials and its bought lines the assembly's bought pieces; each mount's report lists its own files as
  the machine's report does.

The builds go through :mod:`tests.support.builds` (each machine built once a run, shared by xdist's workers).
"""
from __future__ import annotations

import csv
import json
import math
import os
import re
import shutil
import subprocess
import tomllib
import uuid
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from camgen.kinds.machine.assembly import BOUGHT_GROUP
from camgen.kinds.machine.kind import MACHINE_FORMATS, STARTERS
from tests.conftest import ROOT
from tests.project.test_page_browser import CHROMIUM, DRIVER, browser  # noqa: F401  (the fixture, shared)

pytestmark = pytest.mark.slow

TEMPLATES = ROOT / "templates"
#: the bundled machines: every template with a [machine] table
BUNDLED = tuple(p.stem for p in sorted(TEMPLATES.glob("*.toml"))
                if "machine" in tomllib.loads(p.read_text(encoding="utf-8")))
#: the machine kind's starters, each built as ``camgen new KIND`` writes it, named ``starter-KIND``
#: the bundled machines standing in a frame (they have a kit)
FRAMED = tuple(n for n in BUNDLED if tomllib.loads((TEMPLATES / f"{n}.toml").read_text(encoding="utf-8"))["machine"]
               .get("frame", "none") != "none")
STARTED = tuple(f"starter-{kind}" for kind in STARTERS)
MACHINES = (*BUNDLED, *STARTED)
#: every format a machine writes (its timing table comes with json)
FORMATS = json.dumps(sorted(MACHINE_FORMATS))
CORE = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"
#: PrusaSlicer's default layer height after the first (mm)
LAYER = 0.3


@dataclass(frozen=True)
class Built:
    """A machine's build: the folder its files are in and its report."""

    name: str
    folder: Path
    report: dict

    def files(self, ending: str) -> dict[str, Path]:
        """The files the report lists whose names end with ``ending``, by their report keys."""
        return {k: self.folder / v for k, v in self.report["files"].items() if v.endswith(ending)}

    def mount(self, mount: str) -> dict:
        """The report of one of the machine's mounts (a cam or a linkage), from its own JSON file."""
        return json.loads((self.folder / self.report["files"][f"{mount}.json"]).read_text())


def _template(name: str, root: Path) -> Path:
    """The template of machine ``name``: a bundled one, or a starter written once into the builds' cache (its path
    the same for every worker, so that the build is shared)."""
    if name in BUNDLED:
        return TEMPLATES / f"{name}.toml"
    from camgen.starters import starter

    path = root / "starters" / f"{name}.toml"
    if not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
        part = path.with_name(f".{uuid.uuid4().hex}.toml")
        part.write_text(starter(name.removeprefix("starter-"), name), encoding="utf-8")
        os.replace(part, path)
    return path


def _built(bundled_builds, name: str) -> Built:
    path = _template(name, bundled_builds.root)
    folder = bundled_builds.folder(path, "camgen", ["build", str(path), "--set", f"output.formats={FORMATS}"])
    return Built(name, folder, json.loads((folder / f"{name}.json").read_text()))


@pytest.fixture(params=MACHINES)
def machine(request, bundled_builds) -> Built:
    return _built(bundled_builds, request.param)


@pytest.fixture(scope="module")
def every_machine(bundled_builds) -> dict[str, Built]:
    return {name: _built(bundled_builds, name) for name in MACHINES}


def test_the_machines_are_found():
    """The four bundled machines and the two starters (a test that finds none would pass on nothing)."""
    assert set(BUNDLED) >= {"automaton", "keep-time", "pick-and-place", "walking-toy"}
    assert set(STARTED) == {"starter-machine", "starter-walking-toy"}
    assert set(FRAMED) >= {"automaton", "walking-toy"}


def test_the_report_lists_every_file_written_and_each_mount_its_own(machine):
    """The machine's ``files`` are the folder's files; each mount's own report lists the machine's files of that
    mount, named as the machine's report names them; a file of every type a machine writes is there."""
    folder, files = machine.folder, machine.report["files"]
    assert set(files.values()) == {p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()}
    mounts = [k.removesuffix(".json") for k in files if k.endswith(".json")]
    assert sorted(mounts) == sorted(_mount_names(machine.report))
    for mount in mounts:
        own = {f"{mount}.{k}": v for k, v in machine.mount(mount)["files"].items()}
        assert own == {k: v for k, v in files.items() if k.startswith(f"{mount}.")}, mount
    endings = {Path(v).suffix for v in files.values()}
    assert endings == {".dxf", ".svg", ".stl", ".3mf", ".step", ".json", ".png", ".html", ".gif", ".csv"}
    for key in ("json", "html", "gif", "timing_csv", "timing_png", "timing_svg", "machine_png", "machine_svg",
                "assembly_3mf", "assembly_step"):
        assert key in files, key


def _mount_names(report: dict) -> list[str]:
    """The names of a machine's cams and linkages (each has a report of its own), from its report."""
    return [*report["cams"], *report["linkages"], *report.get("cranked", {}), *report.get("slid", {})]


# ---------------------------------------------------------------------------------------------------------- DXF

def test_every_dxf_reads_clean_and_librecad_prints_it_at_its_size(machine, tmp_path):
    import ezdxf
    from ezdxf import bbox

    from tests.support.librecad import printed_extents

    dxfs = machine.files(".dxf")
    assert dxfs
    extents = {}
    for key, path in dxfs.items():
        doc = ezdxf.readfile(path)
        auditor = doc.audit()
        assert not auditor.has_errors and not auditor.fixes, (path.name, auditor.errors, auditor.fixes)
        assert doc.units == ezdxf.units.MM, path.name
        extents[key] = bbox.extents(doc.modelspace())
    page = max(max(e.size.x, e.size.y) for e in extents.values()) + 40.0
    printed = printed_extents(list(dxfs.values()), tmp_path, page)
    for key, path in dxfs.items():
        width, height = printed[path]
        # two pixels at 50 dpi: LibreCAD's line width and the rasteriser's rounding
        assert width == pytest.approx(extents[key].size.x, abs=1.02), path.name
        assert height == pytest.approx(extents[key].size.y, abs=1.02), path.name
    pieces = {p["name"]: p for p in machine.report["assembly"]["pieces"]}
    for plate in machine.report.get("frame", {}).get("plates", []):
        doc = ezdxf.readfile(dxfs[f"{plate}_dxf"])
        outline = bbox.extents(doc.modelspace().query("*[layer=='OUTLINE']"))
        x0, y0, x1, y1 = pieces[plate]["bounds_mm"]
        assert [outline.extmin.x, outline.extmin.y, outline.extmax.x, outline.extmax.y] == pytest.approx(
            [x0, y0, x1, y1], abs=0.01), plate


# ---------------------------------------------------------------------------------------------------------- STL

def _thickness(machine: Built, key: str) -> float:
    """The thickness (mm) the report gives the part of the mesh file ``key`` (``frame_stl``, ``spacer_0_3mf``,
    ``head.stl``, ``arm-bars.coupler_3mf``)."""
    frame = machine.report.get("frame")
    if "." not in key:                                          # the frame's or a follower's part
        stem = key.rsplit("_", 1)[0]
        follower = [p for p in machine.report["followers"] if p["name"].replace("-", "_") == stem]
        if follower:
            return follower[0]["thickness_mm"]
        if stem in frame["plates"]:
            return frame["thickness_mm"]
        return frame["spacers"][int(stem.removeprefix("spacer_"))]["height_mm"]
    mount, _, part = key.partition(".")
    if mount == "gears":                                        # a gear pair's gear: the pair's face width and hub
        name = part.rsplit("_", 1)[0]
        (gear,) = [g for g in machine.report["gears"] if name in (f"{g['name']}-driver", f"{g['name']}-driven")]
        return gear["thickness_mm"] + gear["hub_height_mm"]
    report = machine.mount(mount)
    if part in ("stl", "3mf"):                                  # a cam: one part, its own files
        return report["cam"]["thickness_mm"]
    name = part.rsplit("_", 1)[0]
    (found,) = [p for p in report["parts"] if p["name"] == name]
    return found["thickness_mm"]


def _admesh(path: Path) -> dict[str, float]:
    program = shutil.which("admesh")
    if program is None:
        pytest.skip("admesh is not installed (Debian package; .ci/run installs it)")
    text = subprocess.run([program, "-e", str(path)], capture_output=True, text=True, timeout=120).stdout
    stats = {key: float(re.search(rf"{key}\s*:\s*(\d+)", text).group(1))
             for key in ("Total disconnected facets", "Degenerate facets", "Facets reversed", "Backwards edges",
                         "Normals fixed", "Edges fixed", "Facets removed", "Facets added")}
    low, high = (float(v) for v in re.search(r"Min Z =\s*([-\d.]+), Max Z =\s*([-\d.]+)", text).groups())
    return {**stats, "volume": float(re.search(r"Volume\s*:\s*([-\d.]+)", text).group(1)), "height": high - low}


def test_every_stl_is_closed_for_admesh_and_pymeshlab_and_as_thick_as_its_part(machine):
    from tests.support.meshlab import meshlab as measure

    stls = machine.files(".stl")
    assert stls
    for key, path in stls.items():
        admesh, meshlab = _admesh(path), measure(path)
        assert all(v == 0 for k, v in admesh.items() if k not in ("volume", "height")), (path.name, admesh)
        assert meshlab["manifold"] and meshlab["boundary_edges"] == 0, path.name
        assert meshlab["self_intersecting"] == 0, path.name
        assert meshlab["volume"] > 0 and admesh["volume"] == pytest.approx(meshlab["volume"], rel=1e-5), path.name
        assert admesh["height"] == pytest.approx(_thickness(machine, key), abs=1e-5), path.name
        mount, _, rest = key.partition(".")
        if rest == "stl":                                       # a cam: its report's own mesh check
            assert meshlab["volume"] == pytest.approx(machine.mount(mount)["mesh"]["volume_mm3"], rel=1e-6), key


# ---------------------------------------------------------------------------------------------------------- 3MF

def _prusa(*args: str) -> str:
    program = shutil.which("prusa-slicer")
    if program is None:
        pytest.skip("prusa-slicer is not installed (Debian package; .ci/run installs it)")
    done = subprocess.run([program, *args], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return done.stdout


def _info(paths: list[Path]) -> dict[str, list[dict[str, float]]]:
    """PrusaSlicer's ``--info`` of each of ``paths`` (one call): by file name, each object's numbers in order."""
    out: dict[str, list[dict[str, float]]] = {}
    sections = re.split(r"^\[(.+)\]$", _prusa("--info", *(str(p) for p in paths)), flags=re.M)
    for name, body in zip(sections[1::2], sections[2::2], strict=True):
        values = dict(re.findall(r"^(\w+) =\s*(\S+)$", body, re.M))
        out.setdefault(name, []).append({k: (1.0 if v == "yes" else 0.0 if v == "no" else float(v))
                                         for k, v in values.items()})
    return out


def _layers(gcode: str) -> tuple[set[str], float]:
    """The objects a G-code file prints (PrusaSlicer's labels) and the height of its last layer (mm)."""
    objects = set(re.findall(r"^; printing object (.+) id:\d+ copy \d+$", gcode, re.M))
    return objects, max(float(z) for z in re.findall(r"^;Z:([\d.]+)$", gcode, re.M))


def _stl_volume(path: Path) -> float:
    import trimesh

    return float(trimesh.load(path).volume)


def test_prusaslicer_reads_every_part_closed_and_slices_it_a_part_tall(machine, tmp_path):
    """Each part's 3MF: closed, one shell, its STL's volume, its part's thickness; sliced (every file in one call)
    to G-code that prints that one object, its last layer within half a layer of the part's thickness."""
    parts = {k: p for k, p in machine.files(".3mf").items() if k != "assembly_3mf"}
    assert parts
    info = _info(list(parts.values()))
    for key, path in parts.items():
        (found,) = info[path.name]
        thick = _thickness(machine, key)
        assert found["manifold"] == 1.0 and found["number_of_parts"] == 1.0, path.name
        assert found["size_z"] == pytest.approx(thick, abs=1e-5), path.name
        assert found["volume"] == pytest.approx(_stl_volume(path.with_suffix(".stl")), rel=1e-5), path.name
    _prusa("--export-gcode", "--gcode-label-objects", "--output", str(tmp_path), *(str(p) for p in parts.values()))
    for key, path in parts.items():
        objects, top = _layers((tmp_path / f"{path.stem}.gcode").read_text())
        assert objects == {path.stem}, path.name
        assert abs(top - _thickness(machine, key)) <= LAYER / 2 + 1e-9, (path.name, top)


def _objects(path: Path) -> tuple[dict[str, np.ndarray], dict[str, str | None]]:
    """Each object of a 3MF by name: its vertices (n, 3) mm and triangles (m, 3); and each build item's
    ``printable`` attribute by the name of its object."""
    with zipfile.ZipFile(path) as package:
        root = ET.fromstring(package.read("3D/3dmodel.model"))
    meshes, names = {}, {}
    for obj in root.iter(f"{CORE}object"):
        vertices = np.array([[float(v.get(k)) for k in "xyz"] for v in obj.iter(f"{CORE}vertex")])
        faces = np.array([[int(t.get(k)) for k in ("v1", "v2", "v3")] for t in obj.iter(f"{CORE}triangle")])
        meshes[obj.get("name")] = (vertices, faces)
        names[obj.get("id")] = obj.get("name")
    printable = {names[item.get("objectid")]: item.get("printable") for item in root.iter(f"{CORE}item")}
    return meshes, printable


def _volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """A closed mesh's volume (mm^3): the signed tetrahedra from the origin, summed."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def test_prusaslicer_slices_the_assembly_without_its_bought_parts(machine, tmp_path):
    """The assembly 3MF: one object per made piece of the report and one of the bought ones, marked not printable;
    PrusaSlicer reads every object closed and slices the made pieces, all of them, and nothing bought. With a frame,
    the bought pieces are the kit's bought lines, piece for piece."""
    pieces = machine.report["assembly"]["pieces"]
    made = {p["name"] for p in pieces if not p["bought"]}
    bought = [p["name"] for p in pieces if p["bought"]]
    path = machine.files(".3mf")["assembly_3mf"]
    meshes, printable = _objects(path)
    assert set(meshes) == made | ({BOUGHT_GROUP} if bought else set())
    assert {k: v for k, v in printable.items() if v is not None} == ({BOUGHT_GROUP: "0"} if bought else {})
    found = _info([path])[path.name]
    assert len(found) == len(meshes) and all(f["manifold"] == 1.0 for f in found)
    _prusa("--export-gcode", "--gcode-label-objects", "--dont-arrange", "--output", str(tmp_path / "a.gcode"),
           str(path))
    objects, _ = _layers((tmp_path / "a.gcode").read_text())
    assert objects == made
    frame = machine.report.get("frame")
    if frame is not None:
        assert sorted(_kit_pieces(frame["bom"])) == sorted(bought)


def _kit_pieces(bom: list[dict]) -> list[str]:
    """The assembly's name of each thing the kit buys: a shaft's (``shaft X``: ``shafts.X``), a bearing's (in the
    seat of a shaft), a pivot pin's (a bolt or a pin, named in its line), a roller's axle or a ratchet's arm's
    pawl's pin (a bolt, named in its line)."""
    out = []
    for line in bom:
        if line["source"] != "buy":
            continue
        assert line["quantity"] == 1, line
        if line["item"].startswith("shaft "):
            out.append("shafts." + line["item"].removeprefix("shaft "))
        elif line["item"].startswith("bearing "):
            seat = re.search(r"seat of (\S+)$", line["size"]).group(1)
            out.append(f"{line['item']} of {seat}")
        else:
            out.append(re.search(r"(?:pivot pin|roller axle|arm's pawl pin) "
                                 r"(pins\.\d+|cams\.\S+\.axle|ratchets\.\S+\.pin)", line["size"]).group(1))
    return out


@pytest.mark.parametrize("name", FRAMED)
def test_each_shaft_in_the_assembly_is_the_rod_the_kit_buys(bundled_builds, name):
    """With a frame: each shaft of the assembly is as thick as the kit's rod (to 0.01 mm: the clash check's circle
    is a polygon of chords) and as long, to the whole mm the kit rounds it up to."""
    built = _built(bundled_builds, name)
    frame = built.report["frame"]
    pieces = {p["name"]: p for p in built.report["assembly"]["pieces"]}
    shafts = [line for line in frame["bom"] if line["item"].startswith("shaft ")]
    assert shafts
    for line in shafts:
        diameter, length = (float(v) for v in re.fullmatch(r"([\d.]+) mm ground rod \(h6\), ([\d.]+) mm long",
                                                            line["size"]).groups())
        piece = pieces["shafts." + line["item"].removeprefix("shaft ")]
        x0, y0, x1, y1 = piece["bounds_mm"]
        assert math.ceil(piece["thickness_mm"] - 1e-9) == length, line["item"]
        assert [x1 - x0, y1 - y0] == pytest.approx([diameter, diameter], abs=0.01), line["item"]


def _box(name: str, x: float, printable: bool):
    """A 10 mm cube at ``x`` (mm) on the bed, its faces outward, as a mesh of the project's 3MF writer."""
    from camgen.core.solids import Mesh

    corners = np.array([[i, j, k] for k in (0, 1) for j in (0, 1) for i in (0, 1)], dtype=float) * 10.0
    faces = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7],
                      [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])
    return Mesh(corners + np.array([x, 0.0, 0.0]), faces, name, printable)


def test_the_slicing_check_sees_a_printable_part_printed(tmp_path):
    """The check of the assembly above, on two cubes: PrusaSlicer prints the one marked printable and not the other;
    written without the mark, both (as the bought parts were printed before they were marked)."""
    from camgen.core.writers.threemf import threemf_bytes

    for printable, printed in ((False, {"made"}), (True, {"made", "bought"})):
        path = tmp_path / f"cubes-{printable}.3mf"
        path.write_bytes(threemf_bytes((_box("made", 0.0, True), _box("bought", 30.0, printable))))
        gcode = tmp_path / f"cubes-{printable}.gcode"
        _prusa("--export-gcode", "--gcode-label-objects", "--dont-arrange", "--output", str(gcode), str(path))
        objects, top = _layers(gcode.read_text())
        assert objects == printed
        assert abs(top - 10.0) <= LAYER / 2 + 1e-9


# ---------------------------------------------------------------------------------------------------------- STEP

def test_freecad_reads_every_assembly_each_part_in_its_place(every_machine):
    """Every machine's STEP file in one FreeCAD process: a valid solid per piece of the report's assembly, in its
    order, its bounding box the piece's plan bounds and height to 0.01 mm, and its volume its 3MF object's (the
    bought ones together the bought object's) to 0.5 % (the 3MF's chords of the STEP's arcs)."""
    from tests.support.freecad import freecad_solids

    steps = {name: built.files(".step")["assembly_step"] for name, built in every_machine.items()}
    found = freecad_solids(list(steps.values()))
    for name, built in every_machine.items():
        solids, pieces = found[str(steps[name])], built.report["assembly"]["pieces"]
        assert len(solids) == len(pieces), name
        meshes, _ = _objects(built.files(".3mf")["assembly_3mf"])
        bought = 0.0
        for solid, piece in zip(solids, pieces, strict=True):
            x0, y0, x1, y1 = piece["bounds_mm"]
            z = piece["z_mm"]
            assert solid["valid"], (name, piece["name"])
            assert solid["box"] == pytest.approx([x0, y0, z, x1, y1, z + piece["thickness_mm"]], abs=0.01), \
                (name, piece["name"])
            if piece["bought"]:
                bought += solid["volume"]
            else:
                assert solid["volume"] == pytest.approx(_volume(*meshes[piece["name"]]), rel=5e-3), \
                    (name, piece["name"])
        if bought:
            assert bought == pytest.approx(_volume(*meshes[BOUGHT_GROUP]), rel=5e-3), name


# ---------------------------------------------------------------------------------------------------------- HTML

@pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="headless browser test: Debian's chromium and "
                    "chromium-driver are not installed (apt-get install chromium chromium-driver)")
def test_every_page_opens_in_chromium_and_the_machine_plays(machine, browser):  # noqa: F811
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    pages = machine.files(".html")
    assert set(pages) == {"html"} | {f"{m}.html" for m in _mount_names(machine.report)}
    for page in pages.values():
        browser.get(page.as_uri())
        assert browser.execute_script("return window.camgenPage && window.camgenPage.frames") == 360, page.name
        assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == [], page.name
    browser.get(pages["html"].as_uri())
    animate = browser.find_element(By.ID, "animate")
    assert animate.get_attribute("download") == machine.report["files"]["gif"]
    poses = """return Array.from(document.querySelectorAll("svg.scene [data-body]"),
                                 function(g){return g.getAttribute("transform");});"""
    still = browser.execute_script(poses)
    slider = browser.find_element(By.ID, "frame")
    assert slider.get_attribute("value") == "0"
    browser.find_element(By.ID, "play").click()
    WebDriverWait(browser, 20).until(lambda b: int(slider.get_attribute("value")) >= 30)
    browser.find_element(By.ID, "play").click()
    frame = int(slider.get_attribute("value"))
    assert browser.find_element(By.ID, "shown").text == f"{frame} deg"
    moved = browser.execute_script(poses)
    assert len(moved) == len(still) and moved != still
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == []


# ------------------------------------------------------------------------------------------------- PNG, SVG, GIF

def test_every_figure_and_the_animation_read_back(machine):
    """Every PNG opens as an image and every SVG parses; a cut SVG is its DXF's drawing in mm (its view box the
    drawing's extents, ezdxf's flattened arcs within 0.01 mm, and the same margin all round); the GIF holds the
    default frames and size, and its frames move (the mechanism is not drawn still)."""
    import ezdxf
    from ezdxf import bbox
    from PIL import Image

    from camgen.core.animation import DEFAULT_FRAMES, DEFAULT_SIZE

    for path in machine.files(".png").values():
        with Image.open(path) as image:
            image.verify()
        with Image.open(path) as image:
            assert image.format == "PNG" and min(image.size) >= 100, path.name
    files = machine.report["files"]
    for key, path in machine.files(".svg").items():
        root = ET.parse(path).getroot()
        assert root.tag == "{http://www.w3.org/2000/svg}svg", path.name
        if not key.endswith("cut_svg"):
            continue
        width, height = (float(root.get(k).removesuffix("mm")) for k in ("width", "height"))
        box = [float(v) for v in root.get("viewBox").split()]
        assert box[2:] == pytest.approx([width, height], abs=1e-6), path.name
        dxf = machine.folder / files[key.removesuffix("cut_svg") + "dxf"]
        size = bbox.extents(ezdxf.readfile(dxf).modelspace()).size
        margin = (width - size.x) / 2
        assert 0 <= margin <= 10 and (height - size.y) / 2 == pytest.approx(margin, abs=0.01), path.name
    with Image.open(machine.folder / files["gif"]) as gif:
        assert gif.format == "GIF" and gif.size == DEFAULT_SIZE and gif.n_frames == DEFAULT_FRAMES
        frames = []
        for k in (0, DEFAULT_FRAMES // 4):
            gif.seek(k)
            frames.append(np.asarray(gif.convert("L"), dtype=np.int16))
    assert (np.abs(frames[0] - frames[1]) > 30).mean() > 1e-3


# ------------------------------------------------------------------------------------------------------ CSV, JSON

def test_the_timing_table_is_the_reports_timing(machine):
    """The timing CSV: a row per sample of the report's step over one turn, two columns per output (its value and
    its value over its range), each output's least and largest the report's, and its value still over each dwell."""
    _assert_timing_table(machine.report, machine.folder)


def test_a_ratchet_wheels_dwell_across_the_turns_end_is_still_but_for_its_index(tmp_path):
    """ratchet-counter at phase 0: the wheel's still run (the arm's back stroke and lost motion, from 150 degrees to
    55.5 past the turn's end) crosses the end of the turn, where its angle goes from one tooth (18 degrees, the
    index it gained over the turn) back to 0: the timing table's dwell holds it still, one whole index apart."""
    from click.testing import CliRunner

    from camgen.cli import main

    path = _template("ratchet-counter", ROOT / "templates")
    result = CliRunner().invoke(main, ["build", str(path), "-o", str(tmp_path), "--set", "cams.0.phase=0",
                                       "--set", 'output.formats=["json"]'])
    assert result.exit_code == 0, result.output
    report = json.loads((tmp_path / "ratchet-counter.json").read_text())
    wheel = next(o for o in report["timing"]["outputs"] if o["output"] == "ratchets.index")
    assert report["ratchets"]["index"]["advance_per_turn_deg"] == 18.0
    assert any(end > 360.0 for _, end in wheel["dwells_deg"])               # the run the old check refused
    _assert_timing_table(report, tmp_path)


def _assert_timing_table(report: dict, folder: Path) -> None:
    """The timing CSV in ``folder`` is ``report``'s timing (see the test above). A ratchet's wheel gains its index
    (``advance_per_turn_deg``) a turn: over a still run across the turn's end its angle past the end is that much
    less than before it."""
    timing = report["timing"]
    with (folder / report["files"]["timing_csv"]).open(newline="") as stream:
        rows = list(csv.DictReader(stream))
    assert len(rows) == timing["samples"] == round(360 / timing["step_deg"])
    shaft = np.array([float(r["shaft_deg"]) for r in rows])
    assert shaft == pytest.approx(np.arange(timing["samples"]) * timing["step_deg"], abs=1e-9)
    outputs = {o["output"]: o for o in timing["outputs"]}
    columns = [c for c in rows[0] if c != "shaft_deg"]
    units = {name: o["unit"] for name, o in outputs.items()}
    assert sorted(columns) == sorted([f"{n}_{u}" for n, u in units.items()] + [f"{n}_normalised" for n in units])
    for name, out in outputs.items():
        values = np.array([float(r[f"{name}_{out['unit']}"]) for r in rows])
        share = np.array([float(r[f"{name}_normalised"]) for r in rows])
        assert [values.min(), values.max()] == pytest.approx([out["min"], out["max"]], abs=1e-8), name
        span = out["max"] - out["min"]
        if span > 0:
            assert share == pytest.approx((values - out["min"]) / span, abs=1e-8), name
        ratchet = report.get("ratchets", {}).get(name.removeprefix("ratchets."), {})
        index = float(ratchet.get("advance_per_turn_deg", 0.0)) if name.startswith("ratchets.") else 0.0
        for start, end in out["dwells_deg"]:
            inside = ((shaft - start) % 360 <= (end - start) + 1e-9)
            unwrapped = values + np.where(shaft < start % 360, index, 0.0)      # past the turn's end: one index on
            assert np.ptp(unwrapped[inside]) <= 1e-6 * max(1.0, span), (name, start, end)


def test_the_kit_table_is_the_frames_bill_of_materials(machine):
    """The kit CSV (with a frame): its lines the report's bill of materials, quantities and all; what it makes is
    the frame's plates and spacers, the followers' parts, the gears, a line a cam plate (naming every cam) and a line
    for each part a linkage's own report lists as written (no crank a follower's arm is, no ground the frame is)."""
    frame = machine.report.get("frame")
    if frame is None:
        assert "kit_csv" not in machine.report["files"]
        return
    with (machine.folder / machine.report["files"]["kit_csv"]).open(newline="") as stream:
        rows = list(csv.DictReader(stream))
    assert [(r["part"], int(r["quantity"]), r["standard"], r["size"], r["process"]) for r in rows] == [
        (b["item"], b["quantity"], b["standard"], b["size"], b["source"]) for b in frame["bom"]]
    printed = [b["item"] for b in frame["bom"] if b["source"] != "buy"]
    files = machine.report["files"]
    cams = set(machine.report["cams"])
    plates = {b["item"] for b in frame["bom"] if b["size"].startswith(("cam plate of", "barrel cam of"))}
    assert {p.split(".")[0] for p in plates} == cams
    links = set()                          # each linkage's and Geneva's parts, as its own written report lists them
    for key in files:
        mechanism = key.removesuffix(".json")
        if key.endswith(".json") and mechanism not in cams:
            own = json.loads((machine.folder / files[key]).read_text())
            names = [p["name"] for p in own.get("parts", ())]
            links |= {f"{mechanism}-{n}" for n in names}
    assert set(printed) == (set(frame["plates"]) | {s["name"] for s in frame["spacers"]}
                            | {p["name"] for p in machine.report["followers"]} | plates | links
                            | {f"gear {g['name']}-{side}" for g in machine.report.get("gears", ())
                               for side in ("driver", "driven")})
    assert math.isfinite(frame["thickness_mm"])
