"""Where a machine's parts meet, as the frame tests check it independently of the clash check's planes: heights
from the assembly (each piece's z and thickness), outlines from the kinematics."""
from __future__ import annotations

import numpy as np
import shapely


def spans(design, bodies) -> dict[str, tuple[float, float]]:
    """Each body's bottom and top (mm) as the assembly of ``design`` stands it."""
    from camgen.kinds.machine import assembly

    pieces = {p.part.name: p for p in assembly.pieces(design)}
    return {b.name: (pieces[b.name].z, pieces[b.name].z + pieces[b.name].part.thickness) for b in bodies}


def joint_free(a, b, joints, phi: np.ndarray) -> np.ndarray:
    """Where (bool (n,)) the placed outlines of bodies ``a`` and ``b`` overlap (by more than 1e-6 mm^2) outside the
    discs of the joints between them."""
    from camgen.kinds.machine.clash import outlines

    common = shapely.intersection(outlines(a, phi), outlines(b, phi))
    for joint in joints:
        if {joint.a, joint.b} == {a.name, b.name}:
            common = shapely.difference(common, shapely.buffer(shapely.points(joint.centre(phi)), joint.radius))
    return shapely.area(common) > 1e-6


def assert_meet_only_at_joints(bodies, joints, span: dict[str, tuple[float, float]], phi: np.ndarray) -> int:
    """Assert that two of ``bodies`` whose heights (``span``) overlap meet only inside a joint's disc at the angles
    ``phi``; the number of such pairs checked."""
    checked = 0
    for i, a in enumerate(bodies):
        for b in bodies[i + 1:]:
            (a0, a1), (b0, b1) = span[a.name], span[b.name]
            if a0 < b1 - 1e-9 and b0 < a1 - 1e-9:
                met = joint_free(a, b, joints, phi)
                assert not met.any(), (a.name, b.name, np.degrees(phi[met][:3]))
                checked += 1
    return checked


def freecad_boxes(design, step) -> dict[str, list[float]]:
    """FreeCAD's reading of the assembly STEP file ``step`` of ``design``: one valid solid a piece (in the pieces'
    order) of the piece's volume (to 0.5 %), each piece's bounding box (x0, y0, z0, x1, y1, z1 mm) by its name."""
    import json

    import pytest

    from camgen.kinds.machine.assembly import pieces
    from tests.support.freecad import freecad_check

    done = freecad_check("step", step, [])
    found = json.loads(done.stdout.strip().splitlines()[-1])["solids"]
    want = pieces(design)
    assert len(found) == len(want)
    box = {}
    for solid, piece in zip(found, want, strict=True):
        assert solid["valid"], piece.part.name
        assert solid["volume"] == pytest.approx(piece.part.area * piece.part.thickness, rel=5e-3), piece.part.name
        box[piece.part.name] = solid["box"]
    return box
