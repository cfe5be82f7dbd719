"""Issue 30's bad input, each class refused in one line naming its field (exit 2, nothing written) or handled as a
Unix tool handles it: a keyway burnt away by the kerf, laws of huge values, a path the file system cannot hold, a
FIFO where a file is read, a family's progress and its size, a closed standard output, holes that merge when
opened by the clearance (and a part in two bodies), a family's [sheet] checked before building, a misspelt
value, a resumed family's count and a list given as one value.
"""
from __future__ import annotations

import io
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.errors import DesignError, ExportError, SpecError
from linkgen.cli import main as linkgen
from tests.conftest import RDRD, ROOT, template
from tests.support.refusals import assert_refused

TEMPLATES = ROOT / "templates"
RDRD_FILE = TEMPLATES / "rdrd.toml"


def refused(program, args: list[str], message: str, out: Path | None) -> None:
    """``program args`` exits 2 with one line on stderr starting ``error: message``; nothing at ``out``."""
    result = CliRunner().invoke(program, args)
    assert result.exit_code == 2, (result.exit_code, result.output, result.exception)
    assert result.stderr.startswith(f"error: {message}") and result.stderr.count("\n") == 1, result.stderr
    assert out is None or not out.exists()


def run(args: list[str], **kwargs) -> subprocess.CompletedProcess:
    """``python -m args`` as a process of its own (this clone's code), with a time limit that a hang would meet."""
    return subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True, timeout=120,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, cwd=ROOT, **kwargs)


# ------------------------------------------------------------------------------ a kerf that burns a keyway away

@pytest.mark.parametrize("name", ["rdrd", "grooved", "conjugate"])
def test_a_kerf_wider_than_the_key_is_refused_naming_output_kerf(name, tmp_path):
    """DIN 6885-1 gives a 7 mm bore a 2 mm key: a 5 mm kerf made keyed_bore take the root of a negative number."""
    assert_refused(TEMPLATES / f"{name}.toml", {"cam.bore": 7, "hub.keyway": True, "output.kerf": 5},
                   "output.kerf: must be < 2 mm with hub.keyway", tmp_path)


def test_a_kits_keyway_is_held_to_the_same_rule(tmp_path):
    assert_refused(TEMPLATES / "kit-rdrd.toml", {"cam.bore": 7, "hub.keyway": True, "output.kerf": 2, "kit.shaft": 5,
                                                 "kit.bearing": "625"}, "output.kerf: must be < 2 mm", tmp_path)


def test_a_kerf_just_under_the_key_is_cut_and_keyed_bore_refuses_the_rest():
    from camgen.core.features import key_for, keyed_bore

    width = key_for(7.0)[0]
    assert width == 2.0
    contour = keyed_bore(7.0, -(width - 1e-6) / 2)          # the kerf a hair under the key's width
    assert contour.area > 0
    with pytest.raises(DesignError, match=r"^output\.kerf: a kerf of 2 mm closes the 2 mm keyway"):
        keyed_bore(7.0, -1.0)
    with pytest.raises(DesignError, match="closes"):
        keyed_bore(7.0, -2.5)                              # was: math domain error


# ------------------------------------------------------------------------------------------ laws of huge values

POLY = {"motion.0.law": "polynomial", "motion.0.conditions": [[0, 0, 0], [1, 0, 1], [0, 1, 0], [1, 1, 0]]}
SPLINE = {"motion.0.law": "spline", "motion.0.points": [[0, 0], [0.5, 0.5], [1, 1]]}


@pytest.mark.parametrize("change, message", [
    ({**POLY, "motion.0.conditions": [[0, 0, 0], [1, 0, 1], [0, 1, 1e200], [1, 1, 0]]},
     "motion[0].conditions: the law's displacement reaches 1.48e+199; it must stay within 1e+12"),
    ({**POLY, "motion.0.conditions": [[0, 0, 0], [1, 0, 1], [0, 1, 1.7e308], [1, 1, 0]]},
     "motion[0].conditions: the law's displacement overflows"),
    ({**SPLINE, "motion.0.points": [[0, 0], [0.5, 1e200], [1, 1]]},
     "motion[0].points: the law's displacement reaches 1e+200"),
    ({**SPLINE, "motion.0.points": [[0, 0], [1e-100, 0.5], [2e-100, 0.6], [1, 1]]},
     "motion[0].points: the law's displacement reaches"),
    ({**SPLINE, "motion.0.points": [[0, 0], [1e-300, 0.5], [2e-300, 0.6], [1, 1]]},
     "motion[0].points: no spline through these points: the closest lie 1e-300 apart"),
])
def test_laws_of_huge_values_are_refused_naming_their_data(change, message, tmp_path):
    """Each was a FloatingPointError from the peak search (or scipy's ValueError)."""
    assert_refused(RDRD_FILE, change, message, tmp_path)


def test_the_bound_is_at_1e12_and_ordinary_laws_are_far_inside():
    from camgen.laws import LAW_NAMES, TABLE_LAWS, from_conditions, make_law, spline_law
    from camgen.laws.base import MAX_NORMALISED, bounded

    u = np.linspace(0.0, 1.0, 100_001)
    for name in TABLE_LAWS:
        law = make_law(name) if name != "modified-uniform" else make_law(name, form="blended")
        assert bounded(law, "law", "") is law
        assert np.abs(law.derivatives(u)).max() < 1e-6 * MAX_NORMALISED
    assert "polynomial" in LAW_NAMES
    # f''' of the polynomial with f'(0) = v: 6 v at u = 0 among others; v = 1e11 passes, 1e12 is refused
    grown = [[0, 0, 0], [1, 0, 1], [0, 1, 1e11], [1, 1, 0]]
    assert from_conditions(grown).degree == 3
    with pytest.raises(SpecError, match=r"^conditions: the law's (velocity|acceleration|jerk|displacement) reaches"):
        from_conditions([[0, 0, 0], [1, 0, 1], [0, 1, 1e12], [1, 1, 0]])
    with pytest.raises(SpecError, match=r"^points: the law's jerk reaches"):
        spline_law([[0, 0], [0.5, 1e10], [1, 1]])


@pytest.mark.parametrize("seed", range(6))
def test_the_coefficient_bounds_are_bounds(seed):
    """What decides the fast path: the polynomial's and the spline's coefficient bounds are never below the
    magnitudes sampled on 20 001 points (independently: the laws' own evaluation)."""
    from camgen.laws import from_conditions, spline_law

    rng = np.random.default_rng(seed)
    u = np.linspace(0.0, 1.0, 20_001)
    inner = np.sort(rng.uniform(0.05, 0.95, 4))
    spline = spline_law([[0, 0], *zip(inner, np.sort(rng.uniform(-0.5, 1.5, 4)), strict=True), [1, 1]],
                        ends=str(rng.choice(["dwell", "natural"])))
    conds = [[0, 0, 0], [1, 0, 1], *[[0, k, rng.normal()] for k in (1, 2)], [0.5, 0, rng.uniform(0, 1)],
             [1, 1, rng.normal()]]
    for law in (spline, from_conditions(conds)):
        sampled = np.abs(law.derivatives(u)).max(axis=1)
        assert np.all(law.magnitude_bounds() >= sampled * (1 - 1e-12)), (law, law.magnitude_bounds(), sampled)


# ------------------------------------------------------------------------- a path the file system cannot hold

def test_an_output_name_longer_than_the_file_system_allows_is_one_line(tmp_path):
    long = tmp_path / ("a" * 300)
    for program, args in ((camgen, ["build", str(RDRD_FILE)]), (linkgen, ["analyze", str(TEMPLATES /
                                                                                        "crank-rocker.toml")]),
                          (camgen, ["family", str(TEMPLATES / "automaton-cams.toml")])):
        refused(program, [*args, "-o", str(long / "x")], "Invalid value for '-o' / '--output': cannot create output "
                "folder: a name of 300 bytes (aaaaaaaaaaaaaaaaaaaaaaaa...) is longer than the file system allows "
                "(255)", None)
    deep = tmp_path.joinpath(*["b" * 200] * 25)
    refused(camgen, ["build", str(RDRD_FILE), "-o", str(deep)], "Invalid value for '-o' / '--output': cannot "
            "create output folder: the path is", None)
    refused(camgen, ["new", "translating-roller", "-o", str(long / "x.toml")], "--output: cannot write x.toml: a "
            "name of 300 bytes", None)
    assert list(tmp_path.iterdir()) == []


def test_a_name_of_255_bytes_is_written(tmp_path):
    out = tmp_path / ("a" * 255)
    result = CliRunner().invoke(camgen, ["build", str(RDRD_FILE), "-o", str(out), "--set", "output.formats=['json']"])
    assert result.exit_code == 0, result.output
    assert (out / "rdrd.json").is_file()


# ----------------------------------------------------------------------------------------- FIFOs and devices

@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "pipe"
    os.mkfifo(path)
    return path


@pytest.mark.parametrize("where", ["template", "base", "load_table", "table_law"])
def test_a_fifo_is_refused_without_waiting_for_a_writer(where, fifo, tmp_path):
    """Each waited for ever in open() or read(): the programs run as processes, so a hang fails (timeout)."""
    args, message = {
        "template": (["camgen", "build", str(fifo)], f"error: template: {fifo} is a FIFO, not a regular file"),
        "base": (["linkgen", "analyze", str(tmp_path / "t.toml")], f"error: base: {fifo} is a FIFO, not a regular "
                 "file"),
        "load_table": (["camgen", "build", str(RDRD_FILE), "--set", f'follower.load_table="{fifo}"', "--set",
                        "cam.rpm=100", "--set", "follower.mass=1"],
                       f"error: follower.load_table: cannot read '{fifo}' (a FIFO, not a regular file)"),
        "table_law": (["camgen", "build", str(TEMPLATES / "table-law.toml"), "--set", f'motion.0.file="{fifo}"'],
                      f"error: motion[0].file: cannot read '{fifo}' (a FIFO, not a regular file)"),
    }[where]
    (tmp_path / "t.toml").write_text(f'base = "{fifo.name}"\nname = "x"\n')
    done = run([*args, "-o", str(tmp_path / "out")])
    assert done.returncode == 2 and done.stderr.startswith(message) and done.stderr.count("\n") == 1, done.stderr
    assert not (tmp_path / "out").exists()


def test_a_device_is_refused_and_a_large_file_by_its_size(tmp_path):
    from camgen.core.reading import NotRegularFile, read_regular

    with pytest.raises(NotRegularFile, match="a character device, not a regular file"):
        read_regular("/dev/zero", 10)
    with pytest.raises(IsADirectoryError):
        read_regular(tmp_path, 10)
    with pytest.raises(FileNotFoundError):
        read_regular(tmp_path / "none", 10)
    (tmp_path / "f").write_bytes(b"x" * 100)
    assert read_regular(tmp_path / "f", 10) == b"x" * 11            # one past the limit: the caller says so
    assert read_regular(tmp_path / "f", 1000) == b"x" * 100


# ---------------------------------------------------------------------------------- a family's progress, size

def test_a_family_hands_its_workers_small_batches_and_shows_a_bar_on_a_terminal(monkeypatch, tmp_path):
    """A family of a thousand members on two jobs: batches of at most 8 (a family's eighth a worker held the bar
    still for minutes); the bar is drawn on stderr when it is a terminal, and not otherwise."""
    import camgen.core.family as family

    asked = []

    class Pool:
        def __init__(self, max_workers, initializer):
            pass

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            return False

        def map(self, func, batches):
            batches = list(batches)
            asked.append(max(len(b) for b in batches))
            return ([{"name": m.name, "status": "ok"} for _, m, _ in batch] for batch in batches)

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    items = [family.Member(f"m{i:04d}", (), {}) for i in range(1000)]
    monkeypatch.setattr(family, "ProcessPoolExecutor", Pool)
    for stderr, drawn in ((Terminal(), True), (io.StringIO(), False)):
        monkeypatch.setattr(sys, "stderr", stderr)
        rows = family.run_family(items, tmp_path, builder=None, jobs=2)
        assert len(rows) == 1000 and ("1000/1000" in stderr.getvalue()) == drawn, stderr.getvalue()
    assert asked == [family.PROGRESS_CHUNK] * 2 and family.PROGRESS_CHUNK == 8


def test_a_family_larger_than_the_bound_is_refused_stating_it(tmp_path):
    path = tmp_path / "f.toml"
    path.write_text(f'base = "{RDRD_FILE}"\n[sweep]\n"follower.offset" = {{start = 0, stop = 1, step = 0.01}}\n'
                    '"cam.bore" = {start = 1, stop = 100, step = 1}\n')
    refused(camgen, ["family", str(path), "-o", str(tmp_path / "out")], "sweep: the sweep makes 10100 members, more "
            "than 10000", tmp_path / "out")


# ------------------------------------------------------------------------------------------ a closed stdout

@pytest.mark.parametrize("args", [
    ["camgen", "build", "templates/rdrd.toml", "--set", "output.formats=['json']"],
    ["camgen", "size", "--factors"],
    ["camgen", "--help"],
    ["camgen", "new"],
    ["linkgen", "analyze", "templates/crank-rocker.toml", "--set", "output.formats=['json']"],
])
def test_a_closed_standard_output_ends_quietly_with_141(args, tmp_path):
    """``| head`` that has stopped reading: a write meets a closed pipe (deterministically: its reading end is closed
    before the program starts). No message, status 141 (128 + SIGPIPE, as a tool that signal ends); was 'error:
    Broken pipe' and 2."""
    out = ["-o", str(tmp_path / "o")] if args[1] in ("build", "analyze") else []
    read, write = os.pipe()
    os.close(read)
    try:
        done = subprocess.run([sys.executable, "-m", *args, *out], stdout=write, stderr=subprocess.PIPE, text=True,
                              timeout=120, env={**os.environ, "PYTHONPATH": str(ROOT)}, cwd=ROOT)
    finally:
        os.close(write)
    assert (done.returncode, done.stderr) == (141, "")


def test_an_error_keeps_its_status_and_line_when_stdout_is_closed(tmp_path):
    read, write = os.pipe()
    os.close(read)
    try:
        done = subprocess.run([sys.executable, "-m", "camgen", "build", "templates/rdrd.toml", "-o",
                               str(tmp_path / "o"), "--set", "cam.bore=-1"], stdout=write, stderr=subprocess.PIPE,
                              text=True, timeout=120, env={**os.environ, "PYTHONPATH": str(ROOT)}, cwd=ROOT)
    finally:
        os.close(write)
    assert done.returncode == 2 and done.stderr == "error: cam.bore: must be >= 0 and <= 10000 mm (got -1)\n"


# ------------------------------------------------------------------ holes opened by the clearance, two bodies

RING = {"hub.bolt_holes": 12, "hub.bolt_circle": 24, "hub.bolt_hole_diameter": 4}


def test_a_clearance_that_opens_bolt_holes_into_each_other_is_refused_with_the_largest_that_keeps_the_web(tmp_path):
    """12 holes of 4 mm on a 24 mm circle: adjacent centres 24 sin(15 deg) = 6.2117 mm apart, 2.2117 mm of material;
    a clearance c opens them by c, so 1 mm of web stays up to c = 1.2117 mm. Was: the hub fell out of the STL."""
    web = 24 * math.sin(math.pi / 12) - 4
    largest = web - 1.0
    assert_refused(RDRD_FILE, {**RING, "output.clearance": 5}, f"output.clearance: must be at most {largest:.4g} mm "
                   "with these holes (got 5): it opens two bolt holes into each other, and holes must keep 1 mm",
                   tmp_path)
    assert_refused(RDRD_FILE, {**RING, "output.clearance": largest + 0.01}, "output.clearance: must be at most",
                   tmp_path)
    result = CliRunner().invoke(camgen, ["build", str(RDRD_FILE), "-o", str(tmp_path / "ok"),
                                         *(a for k, v in {**RING, "output.clearance": largest - 0.01}.items()
                                           for a in ("--set", f"{k}={v}"))])
    assert result.exit_code == 0, result.output
    assert json.loads((tmp_path / "ok" / "rdrd.json").read_text())["mesh"]["bodies"] == 1


@pytest.mark.parametrize("change, message", [
    ({"hub.bolt_holes": 36, "hub.bolt_circle": 30, "hub.bolt_hole_diameter": 5},
     "hub.bolt_circle: two bolt holes overlap (36 holes of 5 mm on a 30 mm circle, bore 10 mm)"),
    ({"hub.bolt_holes": 4, "hub.bolt_circle": 16, "hub.bolt_hole_diameter": 5},
     "hub.bolt_circle: a bolt hole and the bore are only 0.5 mm apart"),       # 8 - 2.5 - 5
    ({"hub.bolt_holes": 4, "hub.bolt_circle": 30, "hub.bolt_hole_diameter": 3, "cam.bore": 20, "hub.keyway": True},
     "hub.bolt_circle: a bolt hole and the bore are only 0.7 mm apart"),      # 15 - 1.5 - (10 + 2.8)
])
def test_holes_as_drawn_keep_a_web_of_1_mm(change, message, tmp_path):
    assert_refused(RDRD_FILE, change, message, tmp_path)


@pytest.mark.parametrize("seed", range(8))
def test_the_web_is_the_distance_shapely_measures_between_the_holes(seed):
    """hub_web against shapely's distances between the holes as drawn (finely flattened; 0 where they meet) and
    largest_clearance against the web measured so at that clearance (1 mm)."""
    import shapely

    from camgen.core.features import MIN_WEB_MM, bolt_holes, hub_web, keyed_bore, largest_clearance

    rng = np.random.default_rng(seed)
    keyway = bool(seed % 2)
    bore = float(rng.uniform(8, 30)) if seed % 4 else 0.0
    keyway = keyway and bore > 0
    count = int(rng.integers(2, 13))
    circle = float(rng.uniform(bore + 4, bore + 40))
    hole = float(rng.uniform(1, 6))

    def measured(grow: float) -> float:
        """The least distance between the holes (polygons within 1e-5 mm of their circles) as shapely measures it:
        each bolt hole to its neighbour and to the bore, the only pairs that can be nearest."""
        ring = [shapely.Point(h.centre).buffer(h.radius, quad_segs=512) for h in bolt_holes(circle, count, hole,
                                                                                              grow)]
        pairs = [(a, b) for a, b in zip(ring, ring[1:] + ring[:1], strict=True)]
        if bore:
            middle = (shapely.Polygon(keyed_bore(bore, grow).flatten(1e-6)) if keyway else
                      shapely.Point(0, 0).buffer(bore / 2 + grow, quad_segs=512))
            pairs += [(a, middle) for a in ring]
        return min(a.distance(b) for a, b in pairs)

    for grow in (0.0, 0.4, 1.3):
        web = hub_web(bore, keyway, circle, count, hole, grow)[0]
        assert abs(max(web, 0.0) - measured(grow)) < 3e-5, (seed, grow, web, measured(grow))
    largest = largest_clearance(bore, keyway, circle, count, hole)
    if largest > 0:
        assert abs(measured(largest / 2) - MIN_WEB_MM) < 3e-5
    else:
        assert hub_web(bore, keyway, circle, count, hole)[0] < MIN_WEB_MM


def test_a_clearance_that_opens_a_hole_through_the_outline_is_refused_at_twice_its_gap(tmp_path):
    """Three 6 mm holes on a 72 mm circle come within g mm of the outline; a clearance c opens each by c / 2, so
    it breaks through at c = 2 g (was: a notch in the printed cam, said nothing)."""
    holes = {"hub.bolt_holes": 3, "hub.bolt_circle": 72, "hub.bolt_hole_diameter": 6}
    result = CliRunner().invoke(camgen, ["build", str(RDRD_FILE), "-o", str(tmp_path / "o"), "--set",
                                         "output.clearance=5", *(a for k, v in holes.items()
                                                                 for a in ("--set", f"{k}={v}"))])
    assert result.exit_code == 2 and not (tmp_path / "o").exists()
    line = result.stderr
    assert line.startswith("error: output.clearance: must be < ") and "opens a hole through the cam's outline" in line
    bound = float(line.split("must be < ")[1].split(" mm")[0])
    gap = float(line.split("comes within ")[1].split(" mm")[0])
    assert abs(bound - 2 * gap) < 2e-3 * bound
    for c, made in ((bound * 0.99, True), (bound * 1.01, False)):
        spec = template({**holes, "output.clearance": c})
        if made:
            from camgen.api import design_cam

            design_cam(spec)
        else:
            with pytest.raises(DesignError, match=r"^output\.clearance: must be < "):
                from camgen.api import design_cam

                design_cam(spec)


#: eight 6 mm holes on a 70 mm circle on templates/conjugate.toml (base circles 40 mm; the engraving left off, it
#: would not fit): the holes at 90 and 135 degrees lie where both cams' outlines are their base circles
CONJUGATE_HOLES = {"hub.bolt_holes": 8, "hub.bolt_circle": 70, "hub.bolt_hole_diameter": 6, "hub.engrave": False}


@pytest.mark.parametrize("second_base, refused", [(40.0, 1), (39.0, 2)])
def test_a_clearance_that_opens_a_hole_through_either_conjugate_cam_is_refused(tmp_path, second_base, refused):
    """Each cam of a conjugate pair gets the disc cam's check, by the same function: a hole reaching 35 + 3 = 38 mm
    from the centre comes within g = R - 38 mm of a base circle of R mm (2 mm on the first cam's 40, 1 mm on a
    second cam's 39), and a clearance c opens it by c / 2: refused, naming output.clearance and that cam, from
    c = 2 g (was: built, a notch in the printed cam, the mesh still watertight)."""
    gap = second_base - 38.0 if refused == 2 else 2.0
    change = {**CONJUGATE_HOLES, "cam.second_base_radius": second_base}
    conjugate = TEMPLATES / "conjugate.toml"
    assert_refused(conjugate, {**change, "output.clearance": 2 * gap + 0.1}, "output.clearance: must be < ", tmp_path)
    result = CliRunner().invoke(camgen, ["build", str(conjugate), "-o", str(tmp_path / "o"),
                                         *(a for k, v in {**change, "output.clearance": 2 * gap + 0.1}.items()
                                           for a in ("--set", f"{k}={json.dumps(v)}"))])
    assert f"it opens a hole through cam {refused}'s outline" in result.stderr
    bound = float(result.stderr.split("must be < ")[1].split(" mm")[0])
    assert bound == pytest.approx(2 * gap, abs=0.02)                 # the outline and the hole as chords within 0.01
    from camgen.api import design_cam
    from camgen.spec import load_spec

    def pair(clearance: float):
        sets = {**change, "output.clearance": clearance}
        return design_cam(load_spec(conjugate, [f"{k}={json.dumps(v)}" for k, v in sets.items()]))

    assert len(pair(2 * gap - 0.05).cams) == 2
    with pytest.raises(DesignError, match=rf"^output\.clearance: .* through cam {refused}'s outline"):
        pair(2 * gap + 0.05)


def test_a_part_in_two_bodies_is_not_written():
    """Past the spec (model_copy skips validation): a 3 mm clearance opens the ring of holes into each other and
    the hub falls out; the mesh check counts two bodies, so the STL is refused, never reported watertight."""
    from camgen.core.solids import bodies, check_mesh, extrude
    from camgen.api import write_cam
    from camgen.api import design_cam

    spec = template(RING)
    wide = spec.model_copy(update={"output": spec.output.model_copy(update={"clearance": 3.0})})
    design = design_cam(wide)
    check = check_mesh(extrude(design.printed))
    assert check.watertight and check.bodies == 2 and not check.ok
    assert check_mesh(extrude(design_cam(spec).printed)).bodies == 1
    with pytest.raises(ExportError, match="bodies=2"):
        write_cam(design, Path("/nonexistent/never-written"))
    assert bodies(np.zeros((0, 3), dtype=int), 5) == 0


@pytest.mark.parametrize("seed", range(5))
def test_bodies_counts_what_networkx_counts(seed):
    import networkx as nx

    from camgen.core.solids import bodies

    rng = np.random.default_rng(seed)
    n = int(rng.integers(10, 400))
    faces = rng.integers(0, n, (int(rng.integers(1, 300)), 3))
    graph = nx.Graph()
    graph.add_edges_from(np.vstack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]).tolist())
    assert bodies(faces, n) == nx.number_connected_components(graph)


# --------------------------------------------------------------------------- a family's [sheet], before building

def _sheet_family(tmp_path: Path, base: str, extra: str = "") -> Path:
    path = tmp_path / "f.toml"
    path.write_text(f'base = "{TEMPLATES / base}"\nname = "f"\n{extra}[sheet]\nsize = [600, 400]\n[sweep]\n'
                    '"output.tolerance" = [0.01, 0.02]\n')
    return path


@pytest.mark.parametrize("base, message", [
    ("geneva4.toml", "sheet: member f-tolerance0.01: a Geneva drive's wheel, lock and crank are nested on its own "
                     "<name>-sheet.dxf; a family's [sheet] nests disc, plate and grooved cams"),
    ("conjugate.toml", "sheet: member f-tolerance0.01: a conjugate pair's two cams are nested on its own"),
    ("barrel.toml", "sheet: member f-tolerance0.01: a barrel cam is printed: its DXF is a developed template"),
])
def test_a_sheet_of_members_that_write_no_one_part_is_refused_before_building(base, message, tmp_path):
    refused(camgen, ["family", str(_sheet_family(tmp_path, base)), "-o", str(tmp_path / "out")], message,
            tmp_path / "out")


def test_a_sheet_of_members_without_dxf_is_refused_before_building(tmp_path):
    path = _sheet_family(tmp_path, "rdrd.toml", '[output]\nformats = ["json"]\n')
    refused(camgen, ["family", str(path), "-o", str(tmp_path / "out")], 'sheet: member f-tolerance0.01: it writes no '
            'cut file to nest: add "dxf" to output.formats', tmp_path / "out")


def test_a_linkage_familys_sheet_is_refused_before_building(tmp_path):
    path = tmp_path / "f.toml"
    path.write_text(f'base = "{TEMPLATES / "crank-rocker.toml"}"\n[sheet]\n[sweep]\n"linkage.crank" = [70, 80]\n')
    refused(linkgen, ["family", str(path), "-o", str(tmp_path / "out")], "sheet: these members nest their parts on "
            "sheets of their own (parts.sheet)", tmp_path / "out")


# ------------------------------------------------------------------------------------------- a misspelt value

@pytest.mark.parametrize("program, base, key, value, message", [
    (camgen, "rdrd", "motion.0.law", "cycloid", "motion[0].law: unknown value 'cycloid' (did you mean 'cycloidal'?); "
     "one of uniform, modified-uniform, parabolic"),
    (camgen, "rdrd", "follower.type", "translating-rolle", "follower.type: unknown value 'translating-rolle' (did "
     "you mean 'translating-roller'?)"),
    (camgen, "rdrd", "cam.kind", "disk", "cam.kind: unknown value 'disk' (did you mean 'disc'?); one of disc, plate"),
    (camgen, "rdrd", "output.formats", ["dfx"], "output.formats[0]: unknown value 'dfx' (did you mean 'dxf'?)"),
    (camgen, "rdrd", "cam.rotation", "cc", "cam.rotation: unknown value 'cc' (did you mean 'ccw'?); one of ccw, cw"),
    (camgen, "rdrd", "cam.rotation", 5, "cam.rotation: must be one of ccw, cw (got 5)"),
    (camgen, "rdrd", "motion.0.law", "zzzz", "motion[0].law: unknown value 'zzzz'; one of uniform"),
    (linkgen, "crank-rocker", "linkage.assembly", "crosed", "linkage.assembly: unknown value 'crosed' (did you mean "
     "'crossed'?); one of open, crossed"),
    (linkgen, "crank-rocker", "output.dxf", "polylin", "output.dxf: unknown value 'polylin' (did you mean "
     "'polyline-bulge'?)"),
])
def test_a_misspelt_value_gets_the_closest_and_all_the_others(program, base, key, value, message, tmp_path):
    command = "build" if program is camgen else "analyze"
    refused(program, [command, str(TEMPLATES / f"{base}.toml"), "-o", str(tmp_path / "o"), "--set",
                      f"{key}={json.dumps(value)}"], message, tmp_path / "o")


def test_a_model_and_a_registry_say_it_alike():
    from camgen.core.options import choose, not_one_of

    with pytest.raises(SpecError) as caught:
        choose("cycloid", ("harmonic", "cycloidal"), "law")
    assert str(caught.value) == "law: " + not_one_of("cycloid", ("harmonic", "cycloidal"))
    with pytest.raises(SpecError) as caught:
        template({"motion.0.law": "cycloid"})
    from camgen.laws import LAW_NAMES

    assert str(caught.value) == "motion[0].law: " + not_one_of("cycloid", LAW_NAMES)


# --------------------------------------------------------------------------------- a list given as one value

@pytest.mark.parametrize("key, value, spelling", [
    ("output.formats", "dxf", "formats = [\"dxf\"] in the template, --set 'output.formats=[\"dxf\"]' on the command "
                              "line (got 'dxf')"),
    ("output.sheet", "600", "sheet = [600, 400] in the template, --set 'output.sheet=[600, 400]' on the command line"),
    ("motion.0.conditions", "5", "conditions = [...] in the template, --set 'motion[0].conditions=[...]'"),
])
def test_a_list_given_as_one_value_is_shown_how_to_write_it(key, value, spelling, tmp_path):
    refused(camgen, ["build", str(RDRD_FILE), "-o", str(tmp_path / "o"), "--set", f"{key}={value}"],
            f"{key.replace('.0.', '[0].')}: must be a list, e.g. {spelling}", tmp_path / "o")


def test_the_spelling_shown_works(tmp_path):
    result = CliRunner().invoke(camgen, ["build", str(RDRD_FILE), "-o", str(tmp_path / "o"), "--set",
                                         "output.formats=dxf"])
    shown = result.stderr.split("--set '")[1].split("'")[0]
    assert shown == 'output.formats=["dxf"]'
    result = CliRunner().invoke(camgen, ["build", str(RDRD_FILE), "-o", str(tmp_path / "o"), "--set", shown])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == ["rdrd.dxf"]
    assert RDRD["name"] == "rdrd"
