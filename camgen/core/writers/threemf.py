"""The project's one 3MF writer (millimetres, 3MF's default unit), written directly (no mesh or XML library loaded
on a build): a package of the model, its relationship and content types, with fixed entry dates and UUIDs made from
the mesh, so the same mesh gives the same bytes."""
from __future__ import annotations

import hashlib
import io
import uuid
import zipfile
from pathlib import Path
from typing import Any

from camgen.core.solids import Mesh

_CORE = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
_NAMESPACES = {"m": "http://schemas.microsoft.com/3dmanufacturing/material/2015/02",
               "p": "http://schemas.microsoft.com/3dmanufacturing/production/2015/06",
               "b": "http://schemas.microsoft.com/3dmanufacturing/beamlattice/2017/02",
               "s": "http://schemas.microsoft.com/3dmanufacturing/slice/2015/07",
               "sc": "http://schemas.microsoft.com/3dmanufacturing/securecontent/2019/04"}
_DECLARATION = "<?xml version='1.0' encoding='utf-8'?>\n"
_RELS = (_DECLARATION + '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
         '<Relationship Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel" '
         'Target="/3D/3dmodel.model" Id="rel0"/></Relationships>')
_TYPES = (_DECLARATION + '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">' + "".join(
    f'<Default Extension="{ext}" ContentType="{kind}"/>' for ext, kind in (
        ("jpeg", "image/jpeg"), ("jpg", "image/jpeg"),
        ("model", "application/vnd.ms-package.3dmanufacturing-3dmodel+xml"), ("png", "image/png"),
        ("rels", "application/vnd.openxmlformats-package.relationships+xml"),
        ("texture", "application/vnd.ms-package.3dmanufacturing-3dmodeltexture"))) + "</Types>")


def _attribute(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def model_xml(mesh: Mesh) -> str:
    """The 3MF model of ``mesh``: one object named after it, its vertices (as written, at full precision) and
    triangles, built once in place; its UUIDs derived from the mesh's bytes."""
    digest = hashlib.sha256(mesh.vertices.tobytes() + mesh.faces.tobytes()).hexdigest()
    ids = [uuid.uuid5(uuid.NAMESPACE_URL, f"camgen:{digest}:{k}") for k in range(3)]
    name = _attribute(mesh.name)
    sorted_ns = "".join(f' xmlns:{k}="{_NAMESPACES[k]}"' for k in sorted(_NAMESPACES))
    item_ns = "".join(f' xmlns:{k}="{v}"' for k, v in _NAMESPACES.items())
    vertices = ('<vertex x="{}" y="{}" z="{}" />' * len(mesh.vertices)).format(*mesh.vertices.flatten())
    triangles = ('<triangle v1="{}" v2="{}" v3="{}" />' * len(mesh.faces)).format(*mesh.faces.flatten())
    return (f'{_DECLARATION}<model xmlns="{_CORE}"{sorted_ns} unit="millimeter"><resources>'
            f'<object id="1" name="{name}" type="model" p:UUID="{ids[0]}"><mesh><vertices>{vertices}</vertices>'
            f'<triangles>{triangles}</triangles></mesh></object></resources><build p:UUID="{ids[1]}">'
            f'<item xmlns="{_CORE}"{item_ns} objectid="1" transform="1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0" '
            f'p:UUID="{ids[2]}" partnumber="{name}"/></build></model>')


def assembly_xml(meshes: tuple[Mesh, ...]) -> str:
    """The 3MF model of several meshes (an assembly, each in its place): one object and one build item each, named
    after its mesh; UUIDs derived from the meshes' bytes."""
    digest = hashlib.sha256(b"".join(m.vertices.tobytes() + m.faces.tobytes() for m in meshes)).hexdigest()
    ids = iter(uuid.uuid5(uuid.NAMESPACE_URL, f"camgen:{digest}:{k}") for k in range(2 * len(meshes) + 1))
    sorted_ns = "".join(f' xmlns:{k}="{_NAMESPACES[k]}"' for k in sorted(_NAMESPACES))
    objects, items = [], []
    for number, mesh in enumerate(meshes, 1):
        name = _attribute(mesh.name)
        vertices = ('<vertex x="{}" y="{}" z="{}" />' * len(mesh.vertices)).format(*mesh.vertices.flatten())
        triangles = ('<triangle v1="{}" v2="{}" v3="{}" />' * len(mesh.faces)).format(*mesh.faces.flatten())
        objects.append(f'<object id="{number}" name="{name}" type="model" p:UUID="{next(ids)}"><mesh><vertices>'
                       f'{vertices}</vertices><triangles>{triangles}</triangles></mesh></object>')
        items.append(f'<item objectid="{number}" transform="1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0" '
                     f'p:UUID="{next(ids)}" partnumber="{name}"/>')
    return (f'{_DECLARATION}<model xmlns="{_CORE}"{sorted_ns} unit="millimeter"><resources>{"".join(objects)}'
            f'</resources><build p:UUID="{next(ids)}">{"".join(items)}</build></model>')


def threemf_bytes(mesh: Mesh | tuple[Mesh, ...]) -> bytes:
    """``mesh`` as a 3MF package (see the module docstring); a tuple of meshes as one package of them all."""
    out = io.BytesIO()
    model = assembly_xml(mesh) if isinstance(mesh, tuple) else model_xml(mesh)
    entries = {"3D/3dmodel.model": model, "[Content_Types].xml": _TYPES, "_rels/.rels": _RELS}
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as package:
        for name in sorted(entries):
            package.writestr(zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0)), entries[name].encode("utf-8"),
                             compress_type=zipfile.ZIP_DEFLATED)
    return out.getvalue()


def write_3mf(mesh: Mesh | tuple[Mesh, ...], path: Path, options: Any = None) -> None:
    path.write_bytes(threemf_bytes(mesh))


WRITERS = {"3mf": write_3mf}
