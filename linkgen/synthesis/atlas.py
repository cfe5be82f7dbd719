"""The atlas of normalised four-bar coupler curves: the first guesses of Fourier-descriptor path synthesis.

An entry is a Grashof crank-rocker in its own frame (crank pivot at the origin, rocker pivot on +x,
crank 1, the ``open`` assembly: B left of the line from A to O4) with its coupler point (cx, cy)
in the coupler's frame (see :mod:`linkgen.synthesis.geometry`), and the normalised elliptic
Fourier descriptors (:mod:`linkgen.synthesis.fourier`) of what it traces:

* ``closed``: the whole coupler curve over a turn of the crank (SAMPLES crank angles);
* ``arcs``: arcs of the first ARC_LINKAGES entries' curves, the crank from each of ARC_STARTS
  start angles through each of ARC_SPANS, each retraced into a closed curve.

The linkages are drawn from one fixed seed (SEED): ground, coupler and rocker log-uniform in
[LENGTH_MIN, LENGTH_MAX] crank lengths, kept where the crank is the shortest link of a Grashof chain
clear of a change point (S + L < P + Q by GRASHOF_MARGIN), the worst transmission angle over the
turn is at least MIN_TRANSMISSION_DEG and the curve does not cross itself (checked on every
CROSS_STEP-th sample); the coupler point uniform in cx in [-1, 2] and cy in [-1.5, 1.5] coupler
lengths. Built once and kept as one ``.npz`` file a kind in the user's cache folder
(:func:`cache_folder`), it is read back in well under a second.
"""
from __future__ import annotations

import math
import os
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from linkgen.synthesis import fourier
from linkgen.synthesis.geometry import place, worst_transmission

#: the atlas file's format: a change of any constant below gives a new file name
VERSION = 1
SEED = 36
#: entries of the closed atlas, and the harmonics kept of each
ENTRIES, HARMONICS = 40_000, 12
#: crank angles a closed curve is sampled at (uniform over the turn), and an arc
SAMPLES, ARC_SAMPLES = 180, 48
#: the arcs atlas: of the first ARC_LINKAGES linkages, arcs from ARC_STARTS start angles through each span (rad)
ARC_LINKAGES, ARC_STARTS = 2000, 12
ARC_SPANS = (math.pi / 2, 5 * math.pi / 6, 7 * math.pi / 6, 3 * math.pi / 2)
LENGTH_MIN, LENGTH_MAX = 1.05, 6.0
GRASHOF_MARGIN = 0.02
MIN_TRANSMISSION_DEG = 15.0
CROSS_STEP = 3
KINDS = ("closed", "arcs")


@dataclass(frozen=True)
class Atlas:
    """One kind of atlas: ``linkages`` (N, 5) ground, coupler, rocker, cx, cy (crank lengths; crank 1, open
    assembly); ``arcs`` (N, 2) the crank's start and span (rad; the whole turn for a closed atlas);
    ``curves`` the normalised descriptors of what each traces (coefficients (N, H, 4))."""

    kind: str
    linkages: np.ndarray
    arcs: np.ndarray
    curves: fourier.Normalised

    def __len__(self) -> int:
        return len(self.linkages)


def cache_folder() -> Path:
    """The user's cache folder for linkgen, where platformdirs would put it: ``$XDG_CACHE_HOME/linkgen``
    (``~/.cache/linkgen`` without it), ``%LOCALAPPDATA%/linkgen/Cache`` on Windows, ``~/Library/Caches/linkgen`` on
    macOS."""
    if sys.platform == "win32" and os.environ.get("LOCALAPPDATA"):
        return Path(os.environ["LOCALAPPDATA"]) / "linkgen" / "Cache"
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Caches" / "linkgen"
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "linkgen"


def file_name(kind: str) -> str:
    """The atlas file of ``kind`` in the cache folder: its version, size and seed in the name."""
    size = ENTRIES if kind == "closed" else ARC_LINKAGES * ARC_STARTS * len(ARC_SPANS)
    return f"fourbar-{kind}-v{VERSION}-{size}-h{HARMONICS}-s{SEED}.npz"


def _linkages(rng: np.random.Generator, count: int) -> np.ndarray:
    """``count`` draws (count, 5) of ground, coupler, rocker, cx, cy before the checks."""
    lengths = np.exp(rng.uniform(math.log(LENGTH_MIN), math.log(LENGTH_MAX), (count, 3)))
    cx = lengths[:, 1] * rng.uniform(-1.0, 2.0, count)
    cy = lengths[:, 1] * rng.uniform(-1.5, 1.5, count)
    return np.column_stack([lengths, cx, cy])


def traced(linkages: np.ndarray, theta2: np.ndarray) -> np.ndarray:
    """The coupler points (N, m, 2) of atlas ``linkages`` (N, 5) at crank angles ``theta2`` (m,) or (N, m)."""
    l1, l3, l4, cx, cy = (linkages[:, k, None] for k in range(5))
    at = place(0.0, 0.0, 0.0, l1, 1.0, l3, l4, cx, cy, 1.0, theta2)
    return np.stack([at.px, at.py], axis=-1)


def crossings(points: np.ndarray, closed: bool, step: int = 1) -> np.ndarray:
    """Whether each polygon (N, K, 2) (every ``step``-th vertex; ``closed``: its last side back to the first) has
    two sides that are not neighbours crossing each other (N,): each side's line strictly separating the other's
    ends, both ways. A closed polygon whose turning number is not +-1 crosses itself and is not checked further;
    for the rest the cross products of every side with every vertex are one batched matrix product."""
    p = points[:, ::step]
    k = p.shape[1]
    out = np.zeros(len(p), bool)
    checked = np.arange(len(p))
    if closed:                      # a simple closed polygon turns once: any other turning number has a crossing
        out = np.abs(turns(p)) != 1
        checked = np.flatnonzero(~out)
    i, j = np.triu_indices(k, 2)
    pair = np.zeros((k, k), bool)
    pair[i, j] = True
    pair[0, k - 1] = not closed
    if not closed:                  # the open polygon has no side from its last vertex back to its first
        pair[k - 1, :] = pair[:, k - 1] = False
    for lo in range(0, len(checked), 1024):
        c = checked[lo:lo + 1024]
        out[c] = np.any(_separated(p[c]) & np.swapaxes(_separated(p[c]), 1, 2) & pair, axis=(1, 2))
    return out


def _separated(p: np.ndarray) -> np.ndarray:
    """Whether the line of side e (p_e -> p_{e+1}, the last back to the first) strictly separates p_v and p_{v+1}:
    (N, K sides e, K sides v). The cross products (p_{e+1} - p_e) x (p_v - p_e) of every side with every vertex
    are [dx, -dy, dy x_e - dx y_e] . [y_v, x_v, 1]."""
    a, b = p, np.roll(p, -1, axis=1)
    d = b - a
    lhs = np.stack([d[..., 0], -d[..., 1], d[..., 1] * a[..., 0] - d[..., 0] * a[..., 1]], axis=-1)
    rhs = np.stack([p[..., 1], p[..., 0], np.ones(p.shape[:2])], axis=-1)
    s = lhs @ np.swapaxes(rhs, 1, 2)                                              # (N, K, K)
    return s * np.roll(s, -1, axis=2) < 0


def turns(p: np.ndarray) -> np.ndarray:
    """The turning numbers (N,) of closed polygons (N, K, 2): the sides' turns (each in (-pi, pi]) summed, in whole
    turns (counter-clockwise positive)."""
    side = np.roll(p, -1, axis=1) - p
    heading = np.arctan2(side[..., 1], side[..., 0])
    turn = np.mod(np.roll(heading, -1, axis=1) - heading + math.pi, 2.0 * math.pi) - math.pi
    return np.rint(turn.sum(axis=1) / (2.0 * math.pi)).astype(int)


def _closed(entries: int) -> tuple[np.ndarray, np.ndarray]:
    """The closed atlas's first ``entries`` linkages (entries, 5) and their closed curves (entries, SAMPLES, 2)."""
    rng = np.random.default_rng(SEED)
    theta2 = np.linspace(0.0, 2.0 * math.pi, SAMPLES, endpoint=False)
    kept: list[np.ndarray] = []
    curves: list[np.ndarray] = []
    count = 0
    while count < entries:
        draw = _linkages(rng, 8192)
        l1, l3, l4 = draw[:, 0], draw[:, 1], draw[:, 2]
        longest = np.max(draw[:, :3], axis=1)
        grashof = 1.0 + longest + GRASHOF_MARGIN < l1 + l3 + l4 + 1.0 - longest
        mu = np.degrees(worst_transmission(l1, 1.0, l3, l4, 0.0, 2.0 * math.pi))
        draw = draw[grashof & (mu >= MIN_TRANSMISSION_DEG)]
        pts = traced(draw, theta2)
        simple = ~crossings(pts, True, CROSS_STEP)
        kept.append(draw[simple])
        curves.append(pts[simple])
        count += int(simple.sum())
    return np.concatenate(kept)[:entries], np.concatenate(curves)[:entries]


def build(kind: str) -> Atlas:
    """Make the atlas of ``kind`` (``closed`` or ``arcs``; see the module): a few seconds on one core."""
    linkages, curves = _closed(ENTRIES if kind == "closed" else ARC_LINKAGES)
    if kind == "closed":
        centre, coeffs = fourier.coefficients(curves, HARMONICS)
        arcs = np.tile([0.0, 2.0 * math.pi], (len(linkages), 1))
        return Atlas(kind, linkages, arcs, fourier.normalise(centre, coeffs))
    base = linkages
    starts = np.arange(ARC_STARTS) * (2.0 * math.pi / ARC_STARTS)
    arcs = np.array([(s, w) for s in starts for w in ARC_SPANS])                  # (A, 2)
    u = np.linspace(0.0, 1.0, ARC_SAMPLES)
    theta2 = arcs[:, :1] + arcs[:, 1:] * u                                        # (A, m)
    which = np.repeat(np.arange(len(base)), len(arcs))
    pts = traced(base[which], np.tile(theta2, (len(base), 1)))
    centre, coeffs = fourier.coefficients(fourier.retrace(pts), HARMONICS)
    return Atlas(kind, base[which], np.tile(arcs, (len(base), 1)), fourier.normalise(centre, coeffs))


def _save(atlas: Atlas, path: Path) -> None:
    """Write ``atlas`` to ``path`` whole or not at all: into a ``.part`` file beside it, then renamed (the
    coefficients as float32: they only rank first guesses); the part file is removed if writing fails."""
    c = atlas.curves
    with tempfile.NamedTemporaryFile(dir=path.parent, prefix=path.name, suffix=".part", delete=False) as f:
        try:
            np.savez(f, linkages=atlas.linkages, arcs=atlas.arcs, coefficients=c.coefficients.astype(np.float32),
                     centre=c.centre, scale=c.scale, rotation=c.rotation, phase=c.phase, reversed=c.reversed)
        except OSError:
            f.close()
            os.unlink(f.name)
            raise
    os.replace(f.name, path)


def _read(kind: str, path: Path) -> Atlas | None:
    """The atlas kept at ``path``, or None where there is none or it cannot be read whole."""
    try:
        with np.load(path) as z:
            curves = fourier.Normalised(z["coefficients"].astype(float), z["centre"], z["scale"], z["rotation"],
                                        z["phase"], z["reversed"])
            return Atlas(kind, z["linkages"], z["arcs"], curves)
    except (OSError, ValueError, KeyError, EOFError):
        return None


def load(kind: str, folder: str | Path | None = None) -> tuple[Atlas, dict[str, Any]]:
    """The atlas of ``kind`` from ``folder`` (default :func:`cache_folder`), built and kept there the first time;
    and what happened (path, entries, bytes, whether built, seconds taken). A folder that cannot be made or
    written is refused in one line naming it (``task.atlas_folder``), with nothing left in it."""
    where = Path(folder) if folder is not None else cache_folder()
    path = where / file_name(kind)
    clock = time.perf_counter()
    atlas = _read(kind, path) if path.is_file() else None
    built = atlas is None
    if atlas is None:
        _writable(where, folder is None)
        atlas = build(kind)
        try:
            _save(atlas, path)
        except OSError as exc:
            raise _unwritable(where, exc, folder is None) from None
    return atlas, {"kind": kind, "path": str(path), "entries": len(atlas), "bytes": path.stat().st_size,
                   "built": built, "seconds": round(time.perf_counter() - clock, 3)}


def _writable(where: Path, default: bool) -> None:
    """Refuse a folder that cannot be made or written, before the build."""
    try:
        where.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=where):
            pass
    except OSError as exc:
        raise _unwritable(where, exc, default) from None


def _unwritable(where: Path, exc: OSError, default: bool) -> SpecError:
    why = exc.strerror or type(exc).__name__
    hint = ("it is the user's cache folder (XDG_CACHE_HOME): set task.atlas_folder to a folder you can write"
            if default else "give a folder you can write")
    return SpecError(f"cannot write the atlas folder {where} ({why}): {hint}", "task.atlas_folder")
