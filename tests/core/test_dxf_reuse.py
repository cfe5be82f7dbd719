"""The DXF writer reuses one document per DXF version and writes the fixed sections once (camgen.core.writers.dxf):
every file is byte for byte what a new ezdxf document holding the same drawing writes, in every version, flavour
and text mode, file after file in one process, after a refused drawing and after one ezdxf fails part-way; what is
written passes ezdxf's audit."""
from __future__ import annotations

import io
import threading

import ezdxf
import numpy as np
import pytest

from camgen.core.errors import ExportError
from camgen.core.parts import Drawing
from camgen.core.shapes import Circle, Contour, Polyline, Text
from camgen.core.writers import DXF_FLAVOURS, DXF_VERSIONS, TEXT_MODES, WriteOptions
from camgen.core.writers.dxf import _sorted_classes, dxf_document, write_dxf
from camgen.api import design_cam
from tests.conftest import template


def _mixed() -> Drawing:
    """Every kind of shape on several layers, new layers appearing between entities (their handles interleave)."""
    square = Contour(np.array([[0.0, 0.0], [40.0, 0.0], [40.0, 30.0], [0.0, 30.0]]), np.array([0.0, 0.4, 0.0, -0.3]))
    line = Polyline(np.array([[1.0, 2.0], [5.0, 2.0], [9.0, 6.0]]), np.array([0.0, 0.5]))
    return Drawing((("OUTLINE", square), ("HOLES", Circle((20.0, 15.0), 4.0)), ("ENGRAVE", line),
                    ("ENGRAVE", Text("cam 7", (3.0, 20.0), 3.5, 15.0)), ("HOLES", Circle((8.0, 8.0), 1.5)),
                    ("DC1-limit", line), ("OUTLINE-2", square)), 0.01)


@pytest.fixture(scope="module")
def drawings() -> list[Drawing]:
    cam = design_cam(template())
    plate = design_cam(template({"motion.0.lift": 12.0, "motion.2.lift": 12.0, "follower.roller_radius": 6.0}))
    return [Drawing.of_part(cam.cut), _mixed(), Drawing.of_part(plate.cut), Drawing((), 0.01)]


def _reference(drawing: Drawing, options: WriteOptions) -> bytes:
    """What a new ezdxf document holding the drawing writes (the writer before it reused documents)."""
    shown = drawing.with_outlined_text() if options.text == "outline" else drawing
    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        doc = dxf_document(shown, options.dxf_version, options.dxf_flavour)
        stream = io.StringIO()
        doc.write(stream)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
    return _sorted_classes(stream.getvalue()).encode(doc.output_encoding, errors="replace")


@pytest.mark.parametrize("version", DXF_VERSIONS)
def test_every_file_is_what_a_new_document_writes(tmp_path, drawings, version):
    path = tmp_path / "x.dxf"
    # each drawing twice, in every flavour and text mode, one after another: each file starts from a clean state
    for flavour in DXF_FLAVOURS:
        for text in TEXT_MODES:
            for drawing in [*drawings, *drawings[::-1]]:
                options = WriteOptions(version, flavour, text)
                write_dxf(drawing, path, options)
                assert path.read_bytes() == _reference(drawing, options), (flavour, text)
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors


@pytest.mark.parametrize("bad", [Circle((0.0, 0.0), float("nan")), Circle((0.0, 0.0), 0.0),
                                 Text("x", (float("inf"), 0.0), 2.0),
                                 Contour(np.array([[0.0, 0.0], [1.0, np.nan], [0.0, 1.0]]))])
def test_a_non_finite_drawing_is_refused_and_the_next_file_is_right(tmp_path, drawings, bad):
    path = tmp_path / "bad.dxf"
    broken = Drawing((*drawings[1].items, ("BROKEN", bad)), 0.01)
    with pytest.raises(ExportError, match="layer BROKEN"):
        write_dxf(broken, path)
    assert not path.exists()
    write_dxf(drawings[1], path)
    assert path.read_bytes() == _reference(drawings[1], WriteOptions())


@pytest.mark.parametrize("version", ["R2010", "R12"])
def test_a_drawing_failing_part_way_leaves_the_document_as_new(tmp_path, drawings, version):
    """A layer name ezdxf refuses (``<`` is not allowed in DXF table names) passes our check and fails in ezdxf
    after the drawing's other layers and entities were added: the writer's cleanup takes them out again."""
    from ezdxf.lldxf.const import DXFValueError

    from camgen.core.writers import dxf

    options = WriteOptions(version)
    path = tmp_path / "ok.dxf"
    write_dxf(drawings[1], path, options)                  # the version's reused document exists
    plate = dxf._PLATES[version]
    added = []
    real = plate.doc.layers.add

    def spy(name: str, *args: object, **kwargs: object) -> object:
        added.append((name, len(plate.doc.modelspace())))
        return real(name, *args, **kwargs)

    plate.doc.layers.add = spy
    broken = Drawing((*drawings[1].items, ("bad<name>", Circle((1.0, 1.0), 1.0))), 0.01)
    try:
        with pytest.raises(DXFValueError):
            write_dxf(broken, tmp_path / "bad.dxf", options)
    finally:
        del plate.doc.layers.add
    assert added[-1] == ("bad<name>", len(drawings[1].items))  # refused after every other entity was added
    assert not (tmp_path / "bad.dxf").exists()
    assert dxf._PLATES[version] is plate and len(plate.doc.modelspace()) == 0   # cleaned up, not thrown away
    for drawing in drawings:
        write_dxf(drawing, path, options)
        assert path.read_bytes() == _reference(drawing, options)
    assert dxf._PLATES[version] is plate


def test_threads_each_write_their_own_files(tmp_path, drawings):
    """A Dask worker runs members in threads: they share each version's one document, one file at a time behind
    the writer's lock, and each gets the bytes a new document writes."""
    expected = [_reference(d, WriteOptions()) for d in drawings]
    got: dict[int, list[bytes]] = {}

    def run(k: int) -> None:
        out = []
        for _ in range(3):
            for i, drawing in enumerate(drawings):
                path = tmp_path / f"t{k}-{i}.dxf"
                write_dxf(drawing, path)
                out.append(path.read_bytes())
        got[k] = out

    threads = [threading.Thread(target=run, args=(k,)) for k in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(got[k] == expected * 3 for k in range(3))
