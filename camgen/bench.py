"""``camgen bench``: speed against error, peers measured in the same run, throughput, memory, hard cases.

Every figure is measured here, on this machine, in this run; nothing is asserted about time.
Results go to ``RESULTS.md`` (tables a user can read), ``results.json`` and plots.
"""
from __future__ import annotations

import functools
import math
import subprocess
import sys
import tempfile
import time
import tomllib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from camgen.flat import build_cam
from camgen.core import bench as core_bench
from camgen.core.bench import call_seconds, process_seconds, ratio_markdown, ratio_row, timed
from camgen.convergence_study import contour_error, convergence
from camgen.spec import validate_spec
from camgen.core.spec import apply_overrides

#: the standard cams: the reference rise-dwell-return-dwell with one law family each
STANDARD = {"cycloidal": "cycloidal", "harmonic": "harmonic", "polynomial": "polynomial-345",
            "modified-sine": "modified-sine"}
#: the reference cam as a template (the bundled templates/rdrd.toml with cycloidal laws); the bench writes it
#: out to time ``camgen build`` as a whole process, so it needs no checkout
BASE_TOML = """name = "bench"
cam = {base_radius = 40.0, thickness = 8.0, bore = 10.0}
follower = {type = "translating-roller", roller_radius = 10.0, offset = 5.0}
motion = [{type = "rise", law = "cycloidal", lift = 20.0, angle = 120.0}, {type = "dwell", angle = 60.0},
          {type = "return", law = "cycloidal", lift = 20.0, angle = 120.0}, {type = "dwell", angle = 60.0}]
"""
BASE = tomllib.loads(BASE_TOML)
#: the reference cam's output tolerance (mm), the default
BASE_SPEC_TOLERANCE = 0.01


def _template(law: str, **changes: Any):
    """The standard cam with ``law``; a change to None removes that key."""
    raw = apply_overrides(BASE, [("motion.0.law", law), ("motion.2.law", law),
                                 *((k, v) for k, v in changes.items() if v is not None)])
    for key in (k for k, v in changes.items() if v is None):
        table, field = key.rsplit(".", 1)
        raw[table].pop(field, None)
    return validate_spec(raw)


def outline_speed(tolerances: list[float], repeats: int) -> list[dict]:
    rows = []
    for family, law in STANDARD.items():
        cam = build_cam(_template(law))
        for curves in ("polylines", "biarcs"):
            for r in convergence(cam, tolerances, curves, repeats):
                rows.append({"cam": family, "method": f"camgen {curves}", "tolerance_mm": r.tolerance_mm,
                             "entities": r.entities, "max_error_mm": r.max_error_mm, "seconds": r.seconds})
    return rows


def naive_peer(resolutions: list[int], repeats: int) -> list[dict]:
    """Uniform samples of the pitch curve, offset inwards with shapely's buffer (what a quick script does)."""
    import shapely

    from camgen.core.shapes import Contour

    cam = build_cam(_template("cycloidal"))
    rows = []
    for n in resolutions:
        def run(n: int = n) -> Any:
            pitch = cam.pitch(np.linspace(0, 2 * math.pi, n, endpoint=False)).point
            return shapely.Polygon(pitch).buffer(-cam.contact_radius, quad_segs=8)

        poly, seconds = timed(run, repeats)
        ring = np.asarray(poly.exterior.coords)[:-1]
        rows.append({"cam": "cycloidal", "method": f"naive: {n} pitch samples + shapely buffer",
                     "tolerance_mm": None, "entities": len(ring),
                     "max_error_mm": contour_error(cam, Contour(ring), 1e-3), "seconds": seconds})
    return rows


def mechanism_peer(repeats: int) -> dict:
    """The ``mechanism`` package's cam profile (knife edge, its own sampling) against our exact surface."""
    try:
        from mechanism import Cam
    except ImportError:
        return {"method": "mechanism", "status": "not installed (pip install '.[bench]')"}
    cam = build_cam(_template("cycloidal", **{"follower.type": "knife-edge", "follower.roller_radius": None,
                                              "follower.offset": 0.0}))

    def run() -> np.ndarray:
        peer = Cam(motion=[("Rise", 20, 120), ("Dwell", 60), ("Fall", 20, 120), ("Dwell", 60)], degrees=True,
                   omega=1.0)
        x, y = peer._get_motion_type("cycloidal").get_profile(40, peer.thetas_r)
        return np.column_stack([x, y])

    try:
        pts, seconds = timed(run, repeats)
    except Exception as exc:  # a peer's own failure is a result to report
        return {"method": "mechanism", "status": f"failed: {exc}"}
    # measured like ours: the polyline through its points (vertices and chord midpoints) against our exact
    # surface; its frame conventions differ from ours, so in the best of the eight axis symmetries
    from camgen.core.shapes import Contour

    best = math.inf
    for swap in (False, True):
        for sx in (1, -1):
            for sy in (1, -1):
                p = (pts[:, ::-1] if swap else pts) * [sx, sy]
                best = min(best, contour_error(cam, Contour(p), 1e-3))
    return {"method": "mechanism", "status": "measured", "cam": "cycloidal (knife edge)", "entities": len(pts),
            "max_error_mm": best, "seconds": seconds}


def family_rows(count: int, out: Path, jobs: tuple[int, ...] = (1, 2), dask_workers: int = 0) -> list[dict]:
    """A family of ``count`` reference cams (lifts 5 to 30 mm), DXF and STL, built into ``out`` on each number of
    ``jobs`` (and on a local Dask cluster of ``dask_workers`` workers, if any, see :func:`_dask_family_row`): wall
    seconds, cams per second and CPU seconds (this process and its workers: on a shared machine the wall time
    follows the other sessions' load and the disk, the CPU time far less). Alone: ``python -c "from pathlib import
    Path; from camgen.bench import family_rows; print(family_rows(200, Path('f'), dask_workers=2))"``.
    """
    import resource

    from camgen.core.family import members, run_family
    from camgen.api import build_member

    def cpu() -> float:
        return sum(u.ru_utime + u.ru_stime for u in (resource.getrusage(resource.RUSAGE_SELF),
                                                   resource.getrusage(resource.RUSAGE_CHILDREN)))

    raw = apply_overrides(BASE, [("output.formats", ["dxf", "stl"])])
    lifts = list(np.round(np.linspace(5, 30, count), 6))
    items = members(raw, {"zip": {"motion.0.lift": lifts, "motion.2.lift": lifts}})
    rows = []
    for n in jobs:
        start, used = time.perf_counter(), cpu()
        run_family(items, out / f"family-{n}", build_member, n, progress=False)
        seconds = time.perf_counter() - start
        rows.append({"what": f"family of {count} cams, DXF + STL, {n} job(s)", "seconds": seconds,
                     "cams_per_second": count / seconds, "cpu_seconds": cpu() - used})
    if dask_workers:
        rows += _dask_family_row(items, out, dask_workers, cpu)
    return rows


def _dask_family_row(items: list, out: Path, workers: int, cpu: Callable[[], float]) -> list[dict]:
    """The family on a local Dask cluster of ``workers`` worker processes (one thread each, on loopback), twice on
    the same workers: first on fresh workers (each imports the builder's modules and warms its caches on its first
    member), then again into another folder (workers as a long-lived cluster keeps them). Each run is timed from
    the scheduler's address given (the cluster started untimed) to the last member's row; CPU seconds of both runs
    once the cluster has closed (a worker's time counts when it ends)."""
    from dask.distributed import LocalCluster

    from camgen.api import build_member
    from camgen.core.family import run_family

    used, rows = cpu(), []
    with LocalCluster(n_workers=workers, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                      processes=True) as cluster:
        for state, folder in (("fresh", "family-dask"), ("warm", "family-dask-warm")):
            start = time.perf_counter()
            run_family(items, out / folder, build_member, progress=False, scheduler=cluster.scheduler_address)
            seconds = time.perf_counter() - start
            rows.append({"what": f"family of {len(items)} cams, DXF + STL, a local Dask cluster of {workers} "
                                 f"{state} workers", "seconds": seconds, "cams_per_second": len(items) / seconds})
    rows[-1]["cpu_seconds"] = cpu() - used
    return rows


def throughput(count: int, out: Path, quick: bool = False) -> list[dict]:
    """:func:`family_rows` on one and two jobs (and, unless ``quick``, a local Dask cluster of two workers), then
    ``camgen build`` of the reference cam as a whole process."""
    rows = family_rows(count, out, dask_workers=0 if quick else 2)
    template = out / "bench.toml"
    template.write_text(BASE_TOML, encoding="utf-8")
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "camgen", "build", str(template), "-o", str(out / "build")],
                   check=True, capture_output=True)
    rows.append({"what": "camgen build of the reference cam, whole process", "seconds": time.perf_counter() - start,
                 "cams_per_second": None})
    from camgen.designer.bench import drag_row

    rows.append(drag_row(out / "designer"))
    rows.append(drag_row(out / "designer-busy", busy=True))
    return rows


def _plain_surface(theta: np.ndarray) -> np.ndarray:
    """The reference cam's surface at cam angles ``theta`` (rad) as a quick numpy script makes it: the roller's
    centre in closed form (cycloidal rise 0-120 degrees and return 180-300 degrees, 20 mm, offset 5 mm, base radius
    40 mm, roller 10 mm, counter-clockwise cam), moved in by the roller radius along the normal. Returns (n, 2) mm."""
    rb, rr, e, h, beta = 40.0, 10.0, 5.0, 20.0, math.radians(120.0)
    d0 = math.sqrt((rb + rr) ** 2 - e**2)
    u = np.clip(theta / beta, 0.0, 1.0)                                     # the rise: 0 to 120 degrees
    w = np.clip((theta - math.pi) / beta, 0.0, 1.0)                         # the return: 180 to 300
    s = h * (u - np.sin(2 * math.pi * u) / (2 * math.pi)) - h * (w - np.sin(2 * math.pi * w) / (2 * math.pi))
    ds = h / beta * ((theta < beta) * (1 - np.cos(2 * math.pi * u))
                     - ((theta > math.pi) & (theta < math.pi + beta)) * (1 - np.cos(2 * math.pi * w)))
    y = d0 + s                                                              # the centre (e, y), fixed frame
    tx, ty = y, ds - e                                                      # its velocity in the cam's frame
    speed = np.hypot(tx, ty)
    px, py = e + rr * ty / speed, y - rr * tx / speed                       # the surface point, fixed frame
    c, sn = np.cos(theta), np.sin(theta)
    return np.column_stack([px * c + py * sn, py * c - px * sn])            # turned back by theta


def _plain_checked(n: int) -> tuple[np.ndarray, float]:
    """The plain surface at ``n`` equally spaced vertices (n, 2) and the largest distance (mm) between the surface
    midway (in cam angle) between two vertices and their chord's midpoint."""
    theta = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    points = _plain_surface(theta)
    chord = (points + np.roll(points, -1, axis=0)) / 2
    return points, float(np.linalg.norm(_plain_surface(theta + math.pi / n) - chord, axis=1).max())


def plain_chord_error(n: int) -> float:
    """:func:`_plain_checked`'s chord error (mm) at ``n`` vertices."""
    return _plain_checked(n)[1]


@functools.cache
def plain_vertices(tolerance: float) -> int:
    """The fewest equally spaced vertices whose chords all lie within ``tolerance`` mm of the plain surface (by
    :func:`plain_chord_error`), found by trying every count from 3 up: the yardstick's resolution is the one the
    tolerance needs, not a round figure above it. At most 10^6 vertices (a tolerance below about 1e-8 mm)."""
    n = 3
    while plain_chord_error(n) > tolerance:
        n += 1 if n < 4096 else n // 64
        if n > 1_000_000:
            raise ValueError(f"tolerance {tolerance} mm needs more than 10^6 vertices")
    return n


def plain_outline(tolerance: float) -> np.ndarray:
    """The yardstick of :func:`speed_ratios`: the reference cam's surface as a quick numpy script makes it
    (:func:`_plain_surface`) at the fewest equal steps of cam angle that meet ``tolerance`` mm
    (:func:`plain_vertices`, searched once and cached, untimed), and its chord check (the surface midway between
    vertices against their chords: design_cam checks its tolerance too). Returns the vertices (n, 2)."""
    points, error = _plain_checked(plain_vertices(tolerance))
    if error > tolerance:
        raise ArithmeticError(f"the plain outline misses {tolerance} mm by {error - tolerance:.1e} mm")
    return points


def program_template(segments: int):
    """The reference cam's program cut ``segments`` ways (a multiple of 4): rise, dwell, return, dwell repeated, each
    segment 360 / ``segments`` degrees, cycloidal, its lift 20 (4 / segments)^2 mm so that the follower's
    acceleration (and the pitch curve's curvature, clear of undercut) stays the reference cam's."""
    if segments % 4 or segments < 4:
        raise ValueError(f"segments: a multiple of 4, not {segments}")
    angle, lift = 360.0 / segments, 20.0 * (4 / segments) ** 2
    quarter = [{"type": "rise", "law": "cycloidal", "lift": lift, "angle": angle}, {"type": "dwell", "angle": angle},
               {"type": "return", "law": "cycloidal", "lift": lift, "angle": angle}, {"type": "dwell", "angle": angle}]
    return validate_spec({**BASE, "motion": quarter * (segments // 4)})


def segment_rows(repeats: int, counts: tuple[int, ...] = (4, 64, 256, 1024)) -> list[dict]:
    """design_cam of :func:`program_template` at each count of segments against :func:`plain_outline` (the
    reference cam at its tolerance), alternated in this run: the per-segment cost of cam design."""
    from camgen.api import design_cam

    tol = BASE_SPEC_TOLERANCE
    plain = f"the plain numpy outline ({plain_vertices(tol)} vertices)"
    rows = []
    for count in counts:
        spec = program_template(count)

        def design(spec: Any = spec) -> float:
            return call_seconds(lambda: design_cam(spec), 3)

        rows.append(ratio_row(f"design_cam of {count} segments (in-process)", plain, design,
                              lambda: call_seconds(lambda: plain_outline(tol), 5), repeats, warm=1,
                              goal="<= 5x at 256"))
    return rows


def speed_ratios(repeats: int, out: Path) -> list[dict]:
    """Each of the issue's figures next to its yardstick measured alternately in this run (see
    :func:`camgen.core.bench.ratio_row`): a cam designed in-process against :func:`plain_outline` at the same
    tolerance; ``camgen build`` and ``camgen laws`` as whole processes (CPU seconds) against a process that only
    imports numpy and ezdxf."""
    from camgen.analysis import analyze
    from camgen.api import design_cam

    spec = _template("cycloidal")
    tol = spec.output.tolerance
    plain = ("a plain numpy outline of the same cam at the same tolerance "
             f"({len(plain_outline(tol))} vertices)")
    cam = build_cam(spec)
    # in-process pairs are cheap (about 5 ms one): 40 of them a repeat, after 3 untimed, so that the VM's swings
    # (its speed moves by half between minutes) move the median ratio less than they move a single pair's
    pairs = 40 * repeats
    rows = [ratio_row("design_cam: checks and outline (in-process)", plain, lambda: call_seconds(
        lambda: design_cam(spec), 5), lambda: call_seconds(lambda: plain_outline(tol), 5), pairs, warm=3,
        goal="<= 3x, <= 1 ms"),
            ratio_row("of which the analysis (pressure angle, curvature peaks)", plain, lambda: call_seconds(
                lambda: analyze(cam), 5), lambda: call_seconds(lambda: plain_outline(tol), 5), pairs, warm=3)]
    template = out / "bench.toml"
    template.write_text(BASE_TOML, encoding="utf-8")
    python = sys.executable
    reference = [python, "-c", "import numpy, ezdxf"]
    label = "python -c 'import numpy, ezdxf'"
    commands = [("camgen build, every default output",
                 ["build", str(template), "-o", str(out / "all")], "<= 3x"),
                ("camgen build --figures (the defaults and the PNG and SVG figures)",
                 ["build", str(template), "-o", str(out / "figures"), "--figures"], "-"),
                ("camgen build, dxf stl json", ["build", str(template), "-o", str(out / "some"), "--set",
                                                'output.formats=["dxf","stl","json"]'], "<= 1.5x"),
                ("camgen laws", ["laws"], "<= 0.25 s")]
    for what, args, goal in commands:
        rows.append(ratio_row(what, label, functools.partial(process_seconds, [python, "-m", "camgen", *args]),
                              lambda: process_seconds(reference), repeats, unit="cpu s", goal=goal))
    return rows


def hard_cases() -> list[dict]:
    """Each hard case with what happened: a sound value, or a clean refusal (never NaN or garbage)."""
    return core_bench.hard_cases(_cases())


def _cases() -> Iterator[tuple[str, Callable[[], str]]]:
    import shapely

    from camgen.api import design_cam
    from camgen.laws import from_conditions

    def cam(changes: dict) -> str:
        d = design_cam(validate_spec(apply_overrides(BASE, list(changes.items()))))
        ring = d.outline.contour.flatten(0.01)
        sound = np.isfinite(ring).all() and shapely.Polygon(ring).is_valid and d.outline.max_error_mm <= 0.01
        return f"{'ok' if sound else 'WRONG'}: error {d.outline.max_error_mm:.2e} mm, pressure angle " \
               f"{d.analysis.pressure_angle_max_deg:.2f} deg"

    rho = design_cam(validate_spec(apply_overrides(BASE, [("follower.offset", 0.0)]))).analysis.pitch_rho_min_mm
    for side, sign in (("below", -1), ("above", 1)):
        yield (f"roller radius 1e-9 {side} the smallest convex radius",
               functools.partial(cam, {"follower.offset": 0.0, "follower.roller_radius": rho + sign * 1e-9,
                                       "cam.base_radius": 50.0 - rho - sign * 1e-9, "cam.bore": 0.0}))
    yield "rise over 1 degree", lambda: cam({"motion.0.angle": 1.0, "motion.1.angle": 179.0})
    yield "rise over 358.9999 degrees", lambda: cam({"motion.0.angle": 358.9999, "motion.1.angle": 0.5,
                                                     "motion.2.angle": 0.5, "motion.3.angle": 0.0001})
    yield "lift 10 x the base radius", lambda: cam({"motion.0.lift": 400.0, "motion.2.lift": 400.0})
    yield "offset 1e-9 inside the prime radius", lambda: cam({"follower.offset": 50 - 1e-9})
    for degree in (7, 11, 15, 19):
        m = (degree - 1) // 2

        def poly(m: int = m) -> str:
            conds = [(0, k, 0) for k in range(m + 1)] + [(1, 0, 1)] + [(1, k, 0) for k in range(1, m + 1)]
            u = np.linspace(0, 1, 1001)
            exact = u ** (m + 1) * sum(math.comb(m + k, k) * (1 - u) ** k for k in range(m + 1))
            err = float(np.abs(from_conditions(conds).derivatives(u)[0] - exact).max())
            return f"{'ok' if err < 1e-10 else 'WRONG'}: max deviation {err:.1e} from the closed form"

        yield f"polynomial law of degree {degree}", poly


def _plot(rows: list[dict], path: Path) -> None:
    from camgen.core.figures import figure
    from camgen.core.writers.figure import save

    fig = figure(10, 4.5)
    ax1, ax2 = fig.subplots(1, 2)
    for method in sorted({r["method"] for r in rows}):
        pts = sorted((r["entities"], r["max_error_mm"], r["seconds"]) for r in rows if r["method"] == method
                     and r["cam"] == "cycloidal")
        if not pts:
            continue
        e, err, sec = zip(*pts, strict=True)
        ax1.loglog(e, err, "o-", label=method, ms=3)
        ax2.loglog(sec, err, "o-", label=method, ms=3)
    ax1.set_xlabel("entities in the file")
    ax2.set_xlabel("seconds to build the outline")
    for ax in (ax1, ax2):
        ax.set_ylabel("measured max error (mm)")
        ax.grid(alpha=0.3, which="both")
    ax1.legend(fontsize=7)
    ax1.set_title("cycloidal cam: error against entities")
    ax2.set_title("error against time")
    save(fig, path, "png")


def run_bench(out: str | Path, quick: bool = False) -> dict:
    """Run everything; write RESULTS.md, results.json and speed-vs-error.png into ``out``; return the results."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    tolerances = [1e-1, 1e-2, 1e-3] if quick else [1e-1, 1e-2, 1e-3, 1e-4, 1e-5]
    repeats = 1 if quick else 5
    outlines = outline_speed(tolerances, repeats)
    outlines += naive_peer([90, 360] if quick else [90, 360, 1440, 5760, 23040], repeats)
    peer = mechanism_peer(repeats)
    with tempfile.TemporaryDirectory() as tmp:
        flow = throughput(10 if quick else 200, Path(tmp), quick)
        ratios = speed_ratios(1 if quick else 5, Path(tmp)) + segment_rows(1 if quick else 5)
    _plot(outlines, out / "speed-vs-error.png")
    return core_bench.finish(out, {"quick": quick, "speed": ratios, "outlines": outlines, "mechanism": peer,
                                   "throughput": flow, "hard_cases": hard_cases()}, _markdown)


def _markdown(r: dict) -> list[str]:
    lines = ["# camgen bench", "", f"Python {r['python']}; {'quick run' if r['quick'] else 'full run'}; "
             "median of repeats; errors measured against the exact cam surface.", "",
             "## Speed against yardsticks measured in the same run", "",
             "Each row alternates with its reference; the ratio is the median of the pairs' ratios, with the least "
             "and the largest. Whole processes are timed in CPU seconds (user + system), which a busy machine moves "
             "far less than wall time.", "", *ratio_markdown(r.get("speed", [])), "",
             "## Cam outlines: speed against error", "",
             "| cam | method | tolerance (mm) | entities | measured max error (mm) | seconds |",
             "|---|---|---|---|---|---|"]
    for row in r["outlines"]:
        tol = "-" if row["tolerance_mm"] is None else f"{row['tolerance_mm']:g}"
        lines.append(f"| {row['cam']} | {row['method']} | {tol} | {row['entities']} | {row['max_error_mm']:.2e} | "
                     f"{row['seconds']:.4f} |")
    m = r["mechanism"]
    lines += ["", "## Peer: the mechanism package", "",
              (f"cycloidal cam, knife edge: {m['entities']} points, max error {m['max_error_mm']:.2e} mm, "
               f"{m['seconds']:.4f} s" if m.get("status") == "measured" else f"mechanism: {m['status']}"), "",
              "## Throughput", "", "| what | seconds | cams per second | CPU seconds (workers included) |",
              "|---|---|---|---|"]
    for row in r["throughput"]:
        cps = "-" if row["cams_per_second"] is None else f"{row['cams_per_second']:.1f}"
        cpu = f"{row['cpu_seconds']:.2f}" if row.get("cpu_seconds") is not None else "-"
        lines.append(f"| {row['what']} | {row['seconds']:.2f} | {cps} | {cpu} |")
    return lines
