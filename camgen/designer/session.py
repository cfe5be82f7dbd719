"""One browser tab's design: the template's text and its history, each edit validated and designed by the
project's own code (:mod:`camgen.api` for cams, :mod:`linkgen.api` for linkages), files read and written only
inside the folder the server was started in. No server library here: a message in, an answer out."""
from __future__ import annotations

import base64
import copy
import io
import itertools
import json
import math
import tempfile
import threading
import tomllib
import zipfile
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, cast

from camgen.core.errors import CamgenError, SpecError
from camgen.designer import form, views
from camgen.core.toml_text import dumps

#: the largest template file the designer opens (bytes)
MAX_TEMPLATE = 1 << 20
#: the most edits undo goes back through
MAX_HISTORY = 500
#: the most template files listed of the folder
MAX_LISTED = 500
#: an animation's options where the tab leaves them out: the ``animate`` commands' defaults
ANIMATION_DEFAULTS = {"frames": 72, "size": "640x480", "fps": 24.0, "format": "gif"}
#: the most fields one edit changes together
MAX_CHANGES = 100


class Abandoned(Exception):
    """The server stopped waiting for this answer (past its time limit): nothing is changed."""


def _program(raw: Mapping[str, Any]) -> str:
    """``"linkgen"`` for a linkage template (a ``[linkage]`` table), ``"camgen"`` for the rest."""
    return "linkgen" if "linkage" in raw else "camgen"


def _api(program: str) -> Any:
    if program == "linkgen":
        from linkgen import api as linkage_api

        return linkage_api
    from camgen import api as cam_api

    return cam_api


def inside(root: Path, name: Any, suffix: str = ".toml", field: str = "path") -> Path:
    """The file ``name`` (relative to ``root``) once resolved, refused in one line naming ``field`` where it is not
    a ``suffix`` file inside ``root`` (an absolute path, ``..``, a link leading out)."""
    if not isinstance(name, str) or not name or "\x00" in name:
        raise SpecError("give a file name inside the folder the designer was started in", field)
    path = (root / name).resolve()
    if not path.is_relative_to(root) or Path(name).is_absolute():
        raise SpecError(f"{name!r} lies outside the folder the designer was started in ({root})", field)
    if path.suffix != suffix:
        raise SpecError(f"give a {suffix} file (got {name!r})", field)
    return path


def _parse(text: str, entry: Mapping[str, Any] | None) -> Any:
    """A value typed in a field: JSON (``45``, ``[1, 2]``, ``true``, ``null``) where it reads as JSON, the text
    itself for a string field or where it does not; an empty field is None (the default)."""
    if text.strip() == "":
        return None
    kinds = (entry or {}).get("type")
    kinds = kinds if isinstance(kinds, list) else [kinds]
    if kinds == ["string"]:
        return text
    try:
        return json.loads(text)
    except ValueError:
        return text


def _set(raw: dict[str, Any], path: str, value: Any) -> None:
    """Set the field ``path`` (``motion[0].lift``, ``linkage.joints.G``) of ``raw`` to ``value`` (None removes
    it); a path that names no table of the template is refused in one line."""
    parts: list[str | int] = []
    for piece in path.split("."):
        name, _, rest = piece.partition("[")
        if name:
            parts.append(name)
        for index in filter(None, rest.replace("]", "").split("[")) if rest else ():
            if not index.isdigit():
                raise SpecError("not a field of this template", path)
            parts.append(int(index))
    if not parts:
        raise SpecError("not a field of this template", path or "path")
    here: Any = raw
    for key, after in itertools.pairwise(parts):
        if isinstance(key, int):
            if not isinstance(here, list) or key >= len(here):
                raise SpecError("not a field of this template", path)
            here = here[key]
        else:
            if not isinstance(here, dict):
                raise SpecError("not a field of this template", path)
            here = here.setdefault(key, [] if isinstance(after, int) else {})
    last = parts[-1]
    if isinstance(last, int) or not isinstance(here, dict):
        raise SpecError("not a field of this template", path)
    if value is None:
        here.pop(last, None)
    else:
        here[last] = value


#: the tables a template may hold that make it something other than one design, and what to run instead
NOT_ONE_DESIGN = {"sweep": "a family: build it with `camgen family` or `linkgen family`",
                  "task": "a synthesis task: run it with `linkgen synthesize`",
                  "base": "a template built on another (base = ...): open the template it names, or copy its keys in"}
#: the keys whose values name a file the template reads (a law's table, a load table)
FILE_KEYS = ("file", "load_table")


def _one_design(raw: dict[str, Any], root: Path) -> dict[str, Any]:
    """``raw`` with each file it reads named by its full path in ``root`` (a copy: the template keeps its own
    names); refused, in one line, where the designer cannot edit it as one design or it names a file to read
    outside ``root``."""
    raw = copy.deepcopy(raw)
    for table, what in NOT_ONE_DESIGN.items():
        if table in raw:
            raise SpecError(f"the designer edits one design; this template is {what}", table)
    todo: list[tuple[str, Any]] = [("", raw)]
    while todo:
        path, here = todo.pop()
        items: list[tuple[str | int, Any]] = (list(here.items()) if isinstance(here, Mapping)
                                              else list(enumerate(here)) if isinstance(here, list) else [])
        for key, value in items:
            where = form.join(path, key)
            if key in FILE_KEYS and isinstance(value, str):
                here[key] = str(inside(root, value, Path(value).suffix, where))
            elif isinstance(value, (Mapping, list)):
                todo.append((where, value))
    return raw


def _named(text: str, paths: list[str]) -> list[str]:
    """The form's fields that ``text`` (a warning or an error) names, longest first so that ``motion[1].lift``
    is not also ``motion[1]``."""
    found: list[str] = []
    for p in sorted(paths, key=len, reverse=True):
        if p in text and not any(p in f for f in found):
            found.append(p)
    return found


@dataclass
class Session:
    """One tab's design: ``texts`` the template's text after each edit (the first as the file holds it, so undo
    back to it restores the file byte for byte), ``at`` the one shown, ``angle`` the linkage's input shown.

    Parameters
    ----------
    root : Path
        The folder the server was started in: every file read or written lies inside it.
    """

    root: Path
    texts: list[str] = field(default_factory=list)
    at: int = -1
    file: str | None = None
    angle: float | None = None
    design: Any = None
    entries: dict[str, dict[str, Any]] = field(default_factory=dict)
    #: one message at a time: an answer abandoned past its time limit may still be running
    lock: threading.Lock = field(default_factory=threading.Lock, repr=False)
    #: the tab's synthesis' latest candidates: name -> template text (replaced whole as they come, never edited)
    candidates: dict[str, str] = field(default_factory=dict)

    # -- what the tab asks ------------------------------------------------------------------------------------------
    def handle(self, message: Any, abandoned: threading.Event | None = None) -> dict[str, Any]:
        """The answer to one message from the tab (a dict with ``op``), the session changed only where the answer
        is not an error (and not ``abandoned`` meanwhile): an error is ``{"kind": "error", "field": ..., "message":
        "error: <field>: <what is allowed>"}``, the line the command line prints."""
        with self.lock:
            return self._handle(message, abandoned)

    def _handle(self, message: Any, abandoned: threading.Event | None) -> dict[str, Any]:
        try:
            if not isinstance(message, dict) or not isinstance(message.get("op"), str):
                raise SpecError('give a JSON object with "op"', "message")
            op = OPS.get(message["op"])
            if op is None:
                raise SpecError(f"no such operation {message['op']!r}; one of {', '.join(sorted(OPS))}", "op")
            return op(self, message, abandoned or threading.Event())
        except CamgenError as exc:
            return self.error(exc)
        except OSError as exc:
            return {"kind": "error", "field": "path", "fields": ["path"], "message": f"error: {exc.strerror or exc}"}

    def error(self, exc: CamgenError) -> dict[str, Any]:
        """An error as the command line prints it, with the form fields it names."""
        where = exc.field if isinstance(exc, SpecError) else None
        text = str(exc)
        fields = [where] if where else _named(text, list(self.entries))
        return {"kind": "error", "field": where, "fields": fields, "message": f"error: {text}"}

    # -- operations -----------------------------------------------------------------------------------------------
    def open(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        path = inside(self.root, message.get("path"))
        if not path.is_file():
            raise SpecError(f"no template {message.get('path')!r} in {self.root}", "path")
        if path.stat().st_size > MAX_TEMPLATE:
            raise SpecError(f"a template of at most {MAX_TEMPLATE} bytes", "path")
        text = path.read_text(encoding="utf-8")
        raw = self._read(text)
        state = self._designed(raw, None, abandoned)
        self.texts, self.at, self.file = [text], 0, path.relative_to(self.root).as_posix()
        return self._commit(state)

    def candidate(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        """Open the candidate ``name`` of the tab's synthesis as the design: its template as ``linkgen synthesize``
        writes it, not yet saved (undo goes back to it, save writes it)."""
        name = message.get("name")
        text = self.candidates.get(name) if isinstance(name, str) else None
        if text is None:
            offered = ", ".join(self.candidates) or "none yet: run a synthesis"
            raise SpecError(f"no candidate {name!r} of this tab's synthesis (offered: {offered})", "candidate")
        state = self._designed(self._read(text), None, abandoned)
        self.texts, self.at, self.file = [text], 0, None
        return self._commit(state)

    def listing(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        names = sorted(p.relative_to(self.root).as_posix() for p in self.root.glob("*.toml") if p.is_file())
        return {"kind": "files", "files": names[:MAX_LISTED]}

    def set_field(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        """Set one field (``path``, ``text`` as typed) or several at once (``changes``: a list of them, what must
        change together: a rise's lift and the return's that balances it), as one step of the history."""
        raw = self._raw()
        changes = message.get("changes", [message])
        if not isinstance(changes, list) or not 0 < len(changes) <= MAX_CHANGES:
            raise SpecError(f"give 1 to {MAX_CHANGES} changes", "message")
        for change in changes:
            path, text = (change.get("path"), change.get("text")) if isinstance(change, dict) else (None, None)
            if not isinstance(path, str) or not isinstance(text, str):
                raise SpecError('give "path" and "text" (strings)', "message")
            value = _parse(text, self.entries.get(path))
            _set(raw, path, value)
            if _program(raw) == "linkgen" and path.startswith("linkage.joints.") and isinstance(value, list):
                _follow_checks(raw, path.removeprefix("linkage.joints."))
        return self._edit(raw, self.angle, abandoned)

    def drag(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        """Move a joint of the linkage's drawing to ``x``, ``y`` (mm), its length checks following; ``final``
        commits it (an undo step), else the answer only shows it (a drag under way)."""
        raw = self._raw()
        joint, x, y = message.get("joint"), message.get("x"), message.get("y")
        joints = raw.get("linkage", {}).get("joints")
        if not isinstance(joints, dict) or joint not in joints:
            raise SpecError(f"no joint {joint!r} in the drawing", "joint")
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in (x, y)):
            raise SpecError("give x and y as finite numbers of mm", "joint")
        joints[str(joint)] = [float(cast(float, x)), float(cast(float, y))]
        _follow_checks(raw, str(joint))
        angle = views.drawn_angle(self.design) if self.design is not None else None
        if message.get("final"):
            return self._edit(raw, angle, abandoned)
        scene = self._preview(raw, angle, abandoned)
        if scene is None:
            scene = self._designed(raw, angle, abandoned, full=False)["scene"]
        return {"kind": "preview", "scene": scene}

    def turn(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        value = message.get("value")
        if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
            raise SpecError("give the input's value as a finite number", "angle")
        state = self._designed(self._raw(), float(value), abandoned, full=False)
        self.angle, self.design = float(value), state["design"]
        return {"kind": "preview", "scene": state["scene"]}

    def undo(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        return self._step(-1, abandoned)

    def redo(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        return self._step(+1, abandoned)

    def save(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        """Write the template's text to ``path`` (a .toml file in the folder): what ``camgen build`` or ``linkgen``
        builds to the same files."""
        path = inside(self.root, message.get("path"))
        if not path.parent.is_dir():
            raise SpecError(f"no folder {path.parent.relative_to(self.root)} in {self.root}", "path")
        path.write_text(self._text(), encoding="utf-8")
        return {"kind": "saved", "path": path.relative_to(self.root).as_posix()}

    def export(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        """The files the command line's build writes of this design, as a zip (base64): ``camgen build``'s of a
        cam, ``linkgen build``'s of a linkage with a ``[parts]`` table (``linkgen analyze``'s without one)."""
        raw = self._raw()
        program = _program(raw)
        api = _api(program)
        spec = api.validate(_one_design(raw, self.root))
        if program == "linkgen":
            made = api.design(spec, parts=getattr(spec, "parts", None) is not None)
        else:
            made = api.design(spec)
        buffer = io.BytesIO()
        with tempfile.TemporaryDirectory(prefix="camgen-designer-") as tmp:
            folder = Path(tmp) / spec.name
            api.write(made, folder)
            with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
                for f in sorted(folder.rglob("*")):
                    if f.is_file():
                        archive.write(f, f.relative_to(folder).as_posix())
        if abandoned.is_set():
            raise Abandoned
        return {"kind": "export", "name": f"{spec.name}.zip", "data": base64.b64encode(buffer.getvalue()).decode()}

    def animate(self, message: Mapping[str, Any], abandoned: threading.Event) -> dict[str, Any]:
        """One full cycle of this design as ``linkgen animate`` or ``camgen animate`` writes it (``frames``,
        ``size`` as ``WxH`` pixels, ``fps``, ``format``: the commands' options and bounds, refused in their line),
        as a file to download (base64)."""
        from camgen.core.animation import animation_options
        from camgen.core.writers.animation import write_animation

        asked = {**ANIMATION_DEFAULTS, **message}
        frames, size, fps, fmt = (asked[k] for k in ("frames", "size", "fps", "format"))
        if not (isinstance(frames, int) and not isinstance(frames, bool) and isinstance(size, str)
                and isinstance(fps, (int, float)) and not isinstance(fps, bool) and isinstance(fmt, str)):
            raise SpecError("give frames (a whole number), size (WxH), fps (a number) and format (a name)", "animate")
        options = animation_options(frames, size, float(fps), fmt)
        raw = self._raw()
        program = _program(raw)
        spec = _api(program).validate(_one_design(raw, self.root))
        if program == "linkgen":
            from linkgen.animation import analysis_for_animation, linkage_frames
            from linkgen.linkage_design import design_linkage

            drawn = linkage_frames(analysis_for_animation(design_linkage(spec)), options.frames, options.size)
        else:
            from camgen.kinds import spec_kind

            drawn = spec_kind(spec).animation(_api(program).design(spec), options.frames, options.size)
        if abandoned.is_set():
            raise Abandoned
        name = f"{spec.name}-animation.{options.format}"
        with tempfile.TemporaryDirectory(prefix="camgen-designer-") as tmp:
            path = Path(tmp) / name
            write_animation(drawn, path, options.format, options.fps)
            data = path.read_bytes()
        return {"kind": "animation", "name": name, "format": options.format, "data": base64.b64encode(data).decode()}

    # -- the state ------------------------------------------------------------------------------------------------
    def _text(self) -> str:
        if self.at < 0:
            raise SpecError("open a template first", "path")
        return self.texts[self.at]

    def _raw(self) -> dict[str, Any]:
        """The shown template's raw tables, a fresh copy to edit."""
        return self._read(self._text())

    @staticmethod
    def _read(text: str) -> dict[str, Any]:
        try:
            return tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise SpecError(f"not TOML: {exc}", "template") from None

    def _designed(self, raw: dict[str, Any], angle: float | None, abandoned: threading.Event,
                  full: bool = True) -> dict[str, Any]:
        """Validate and design ``raw`` (at the input ``angle`` for a linkage, its drawing for None): the parts of
        an answer, nothing of the session changed."""
        program = _program(raw)
        api = _api(program)
        spec = api.validate(_one_design(raw, self.root))
        if program == "linkgen":
            first = api.design(spec) if angle is None else None
            at = views.drawn_angle(first) if first is not None else angle
            try:
                made = api.design(spec, angle=at)
            except SpecError as exc:
                raise SpecError(exc.detail, "angle") if exc.field == "angle" else exc from None
        else:
            made, at = api.design(spec), None
        if abandoned.is_set():
            raise Abandoned
        state: dict[str, Any] = {"design": made, "angle": at, "program": program, "raw": raw,
                                 "scene": views.linkage_scene(made) if program == "linkgen" else None}
        if full:
            entries = form.form(spec, raw)
            state["form"] = entries
            state["page"] = views.page(made)
        if abandoned.is_set():
            raise Abandoned
        return state

    def _preview(self, raw: dict[str, Any], angle: float | None, abandoned: threading.Event) -> dict[str, Any] | None:
        """A drag's scene of ``raw`` at ``angle`` from the linkage's analysis alone (:mod:`camgen.designer.quick`:
        the dyads' extremes at the samples); None where that does not apply (not a general linkage, no angle)."""
        from camgen.designer.quick import quick_scene

        if _program(raw) != "linkgen" or angle is None:
            return None
        scene = quick_scene(_api("linkgen").validate(_one_design(raw, self.root)), angle)
        if abandoned.is_set():
            raise Abandoned
        return scene

    def _edit(self, raw: dict[str, Any], angle: float | None, abandoned: threading.Event) -> dict[str, Any]:
        state = self._designed(raw, angle, abandoned)
        text = dumps(raw)
        if text != self._text():
            del self.texts[self.at + 1:]
            self.texts.append(text)
            del self.texts[:max(0, len(self.texts) - MAX_HISTORY)]
            self.at = len(self.texts) - 1
        return self._commit(state)

    def _step(self, by: int, abandoned: threading.Event) -> dict[str, Any]:
        at = self.at + by
        if not 0 <= at < len(self.texts):
            raise SpecError("nothing to " + ("undo" if by < 0 else "redo"), "history")
        state = self._designed(self._read(self.texts[at]), self.angle, abandoned)
        self.at = at
        return self._commit(state)

    def _commit(self, state: dict[str, Any]) -> dict[str, Any]:
        made = state["design"]
        self.design, self.angle = made, state["angle"]
        self.entries = {e["path"]: e for e in state["form"]}
        said = made.warnings if hasattr(made, "warnings") else made.report.get("warnings", ())
        warnings = [{"text": w, "fields": _named(w, list(self.entries))} for w in said]
        return {"kind": "state", "program": state["program"], "file": self.file, "text": self._text(),
                "form": state["form"], "page": state["page"], "scene": state["scene"], "warnings": warnings,
                "can_undo": self.at > 0, "can_redo": self.at < len(self.texts) - 1}


def _follow_checks(raw: dict[str, Any], joint: str) -> None:
    """Set each ``[linkage.lengths]`` check naming ``joint`` to the distance the drawing now shows (they are checks
    of the drawing: moving a joint changes the lengths it fixes)."""
    table = raw.get("linkage", {})
    joints, checks = table.get("joints", {}), table.get("lengths")
    if not isinstance(checks, dict):
        return
    for key in checks:
        a, _, b = str(key).partition("-")
        if joint in (a, b) and a in joints and b in joints:
            checks[key] = math.dist(joints[a], joints[b])


OPS: dict[str, Callable[[Session, Mapping[str, Any], threading.Event], dict[str, Any]]] = {
    "open": Session.open, "list": Session.listing, "set": Session.set_field, "drag": Session.drag,
    "angle": Session.turn, "undo": Session.undo, "redo": Session.redo, "save": Session.save,
    "export": Session.export, "candidate": Session.candidate, "animate": Session.animate}
