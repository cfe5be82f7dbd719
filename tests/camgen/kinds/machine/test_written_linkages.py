"""A machine's linkages as it writes them (without the parts its arm, frame or stem are) are made once a design:
its files, its kit and its report's frame all read the same designs, and each linkage's cut sheet is nested again
once, not once for each of them."""
from __future__ import annotations

from camgen.kinds.machine import coupled_kit
from tests.conftest import ROOT


def test_each_linkage_is_nested_without_the_machines_parts_once_per_design(tmp_path, monkeypatch):
    """The walking toy (two Jansen legs on a frame: their ground links are its plates): writing it nests each leg's
    sheet once without its ground (six nestings before: the files, the kit and the report's bill each nested both
    legs again), and what the files and the kit read is what :func:`coupled_kit.machine_made` makes afresh."""
    from camgen import api
    from camgen.core import nesting

    design = api.design(api.load(ROOT / "templates" / "walking-toy.toml", ['output.formats=["json", "dxf"]']))
    nested = []
    real = nesting.nest
    monkeypatch.setattr(nesting, "nest", lambda parts, *a, **k: nested.append(len(parts)) or real(parts, *a, **k))
    written = api.write(design, tmp_path / "toy")
    assert nested == [7, 7]                     # each leg's seven parts to cut: its ground is the frame's plates
    linkages = design.written_linkages
    assert len(nested) == 2 and len(linkages) == 2
    afresh = coupled_kit.machine_made(design)
    for (m, made), (m2, again) in zip(linkages, afresh, strict=True):
        assert m is m2 and "ground" not in {p.name for p in made.build.cut}
        assert [p.name for p in made.build.cut] == [p.name for p in again.build.cut]
        assert [(q.part.name, q.sheet, q.rotation, q.shift) for q in made.build.nesting.placed] == \
            [(q.part.name, q.sheet, q.rotation, q.shift) for q in again.build.nesting.placed]
    kit = [line["item"] for line in written.report["frame"]["bom"]]
    assert [f"{m.name}-{p.name}" for m, made in afresh for p in made.build.cut] == \
        [item for item in kit if item.startswith(tuple(f"{m.name}-" for m, _ in afresh))]
