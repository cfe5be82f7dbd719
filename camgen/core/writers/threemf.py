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
    ids = _ids((mesh,), 3)
    namespaces = f' xmlns="{_CORE}"' + "".join(f' xmlns:{k}="{v}"' for k, v in _NAMESPACES.items())
    return _model(_object(1, mesh, ids[0]), ids[1], _item(1, mesh, ids[2], namespaces))


def assembly_xml(meshes: tuple[Mesh, ...]) -> str:
    """The 3MF model of several meshes (an assembly, each in its place): one object and one build item each, named
    after its mesh; UUIDs derived from the meshes' bytes."""
    ids = iter(_ids(meshes, 2 * len(meshes) + 1))
    objects, items = [], []
    for number, mesh in enumerate(meshes, 1):
        objects.append(_object(number, mesh, next(ids)))
        items.append(_item(number, mesh, next(ids)))
    return _model("".join(objects), next(ids), "".join(items))


def _ids(meshes: tuple[Mesh, ...], count: int) -> list[uuid.UUID]:
    """``count`` UUIDs derived from the meshes' bytes (the same meshes, the same UUIDs)."""
    digest = hashlib.sha256(b"".join(m.vertices.tobytes() + m.faces.tobytes() for m in meshes)).hexdigest()
    return [uuid.uuid5(uuid.NAMESPACE_URL, f"camgen:{digest}:{k}") for k in range(count)]


def _object(number: int, mesh: Mesh, object_id: uuid.UUID) -> str:
    """The object ``number`` of a model: ``mesh``'s vertices (at full precision) and triangles, named after it."""
    vertices = ('<vertex x="{}" y="{}" z="{}" />' * len(mesh.vertices)).format(*mesh.vertices.flatten())
    triangles = ('<triangle v1="{}" v2="{}" v3="{}" />' * len(mesh.faces)).format(*mesh.faces.flatten())
    return (f'<object id="{number}" name="{_attribute(mesh.name)}" type="model" p:UUID="{object_id}"><mesh><vertices>'
            f'{vertices}</vertices><triangles>{triangles}</triangles></mesh></object>')


def _item(number: int, mesh: Mesh, item_id: uuid.UUID, namespaces: str = "") -> str:
    """The build item placing object ``number`` (``mesh``'s) where it is drawn (the identity transform); a mesh
    that is not ``printable`` marked ``printable="0"`` (PrusaSlicer's attribute, which it and the slicers derived
    from it read: the object is shown, not sliced)."""
    printable = "" if mesh.printable else ' printable="0"'
    return (f'<item{namespaces} objectid="{number}" transform="1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0" '
            f'p:UUID="{item_id}" partnumber="{_attribute(mesh.name)}"{printable}/>')


def _model(objects: str, build_id: uuid.UUID, items: str) -> str:
    """The model document of the ``objects`` and the build of the ``items``."""
    namespaces = "".join(f' xmlns:{k}="{_NAMESPACES[k]}"' for k in sorted(_NAMESPACES))
    return (f'{_DECLARATION}<model xmlns="{_CORE}"{namespaces} unit="millimeter"><resources>{objects}</resources>'
            f'<build p:UUID="{build_id}">{items}</build></model>')


def threemf_bytes(mesh: Mesh | tuple[Mesh, ...]) -> bytes:
    """``mesh`` as a 3MF package (see the module docstring); a tuple of meshes as one package of them all.

    Parameters
    ----------
    mesh : Mesh or tuple of Mesh
        One mesh, or several (each an object of the package, named after its mesh); mm.

    Returns
    -------
    bytes
        The package's bytes (a zip file, its model in millimetres), the same for the same meshes.
    """
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
