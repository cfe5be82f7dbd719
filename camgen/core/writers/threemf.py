"""The project's one 3MF writer (via trimesh; millimetres, 3MF's default unit)."""
from __future__ import annotations

import hashlib
import itertools
import re
import uuid

from pathlib import Path
from typing import Any

from camgen.core.solids import Mesh, trimesh_of


def threemf_bytes(mesh: Mesh) -> bytes:
    """``mesh`` as a 3MF package whose object bears the mesh's name, repacked with fixed entry dates and UUIDs made
    from the mesh, so the same mesh gives the same bytes."""
    import io
    import zipfile

    import trimesh

    scene = trimesh.Scene()
    scene.add_geometry(trimesh_of(mesh), geom_name=mesh.name, node_name=mesh.name)
    raw = zipfile.ZipFile(io.BytesIO(scene.export(file_type="3mf")))
    digest = hashlib.sha256(mesh.vertices.tobytes() + mesh.faces.tobytes()).hexdigest()
    count = itertools.count()

    def fixed(_: re.Match) -> str:     # trimesh draws random object UUIDs: derive them from the mesh instead
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


def write_3mf(mesh: Mesh, path: Path, options: Any = None) -> None:
    path.write_bytes(threemf_bytes(mesh))


WRITERS = {"3mf": write_3mf}
