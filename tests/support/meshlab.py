"""pymeshlab's reading of a mesh file, as the tests take it: skipped, saying so, where pymeshlab is not installed."""
from __future__ import annotations

from pathlib import Path

import pytest


def meshlab(path: Path) -> dict:
    """What pymeshlab finds in the mesh file ``path``: whether it is a two-manifold, its boundary edges, its faces
    that cross another (the self-intersection filter's selection) and its volume (mm^3; NaN where not closed)."""
    pymeshlab = pytest.importorskip("pymeshlab", reason="pymeshlab is not installed (PyPI; .ci/run installs it)")
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(path))
    topo = ms.get_topological_measures()
    ms.compute_selection_by_self_intersections_per_face()
    return {"manifold": topo["is_mesh_two_manifold"], "boundary_edges": topo["boundary_edges"],
            "self_intersecting": ms.current_mesh().selected_face_number(),
            "volume": ms.get_geometric_measures().get("mesh_volume", float("nan"))}
