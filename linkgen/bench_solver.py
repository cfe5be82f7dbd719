"""``linkgen bench``'s general-solver rows: the fused solver against pylinkage's numba-compiled steps and a plain
numpy closed form, on the bundled Jansen leg, Klann linkage and Watt I six-bar, measured in the same run.

Each linkage is the bundled template itself (``templates/jansen.toml`` and so on), so the bench's leg is the one
users build. Every figure is measured here: the two sides of a ratio alternate, each side's time is the least of
its repeats (the machine is shared: the least is the run least disturbed), and the ratio is pylinkage's least over
ours (above 1: ours is faster). Accuracy is against a 50-digit (mpmath) solution of the same construction at 100
of the angles. Peak memory is each call's rise of the process's peak resident set (``VmHWM`` after resetting it
through ``/proc/self/clear_refs``) in a fresh process, so that numba's own allocations count as well as numpy's.
"""
from __future__ import annotations

import json
import math
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from camgen.core.bench import child_env
from linkgen.kinematics import compiled, fused
from linkgen.kinematics.linkage import FEASIBILITY_TOL

#: the bundled linkages of the solver rows: (bench name, template, the point whose accuracy is reported)
LINKAGES = (("jansen", "jansen", "G"), ("klann", "klann", "F"), ("watt six-bar", "watt1", "P"))


def bundled(template: str) -> Any:
    """The bundled template's linkage (:class:`~linkgen.kinematics.linkage.Linkage`)."""
    import linkgen
    from camgen.core import examples

    return linkgen.design_linkage(linkgen.load_spec(examples.folder() / f"{template}.toml")).kinematics.linkage


def angles(linkage: Any, n: int) -> np.ndarray:
    """n crank angles (rad) a turn apart / n, from the revolution's start."""
    return linkage.revolution + 2.0 * math.pi / n * np.arange(n)


def reference(linkage: Any, t: np.ndarray, digits: int = 50) -> dict[str, np.ndarray]:
    """Every moving point at crank angles ``t`` to ``digits`` digits (mpmath), by the fused program's construction
    (the crank turned, each RRR joint where the circles about its pins meet on its branch, a body's other points
    carried rigidly), on the branches the linkage takes there; independent of numpy's arithmetic."""
    import mpmath

    prog = linkage.program
    signs = [np.broadcast_to(g, t.shape) for g in linkage.signs(np.atleast_2d(linkage.unwrap(t)))]
    mp = mpmath.mp.clone() if hasattr(mpmath.mp, "clone") else mpmath.mp
    mp.dps = digits
    drawn = {k: mp.mpc(v.real, v.imag) for k, v in prog.drawn.items()}
    out: dict[str, list[complex]] = {name: [] for name, holder, _ in prog.points if holder is not None}
    from linkgen.kinematics.fused import CrankOp

    def at(frame: dict[str, tuple[Any, Any, Any]], body: str | None, name: str) -> Any:
        if body is None:
            return drawn[name]
        p, q, pd = frame[body]
        return p + q * (drawn[name] - pd)

    for i, theta in enumerate(t):
        frame: dict[str, tuple[Any, Any, Any]] = {}      # body -> (P, rotation q, pd): world(x) = P + q (x - pd)
        for op in prog.ops:
            if isinstance(op, CrankOp):
                delta = mp.mpf(float(theta)) - mp.mpf(op.drawn)
                turn = mp.expjpi(delta / mp.pi)
                q = turn
                frame[op.body] = (at(frame, None, op.pivot), q, drawn[op.pivot])
                continue
            p1, p2 = at(frame, op.refs[0], op.pins[0]), at(frame, op.refs[1], op.pins[1])
            jd = drawn[op.joint]
            r1, r2 = abs(jd - drawn[op.pins[0]]), abs(jd - drawn[op.pins[1]])
            d = p2 - p1
            dist = abs(d)
            along = (dist**2 + r1**2 - r2**2) / (2 * dist)
            height = mp.sqrt(max(r1**2 - along**2, 0)) * float(signs[op.step][i])
            j = p1 + (along + 1j * height) * d / dist
            for body, p, pd in ((op.bodies[0], p1, drawn[op.pins[0]]), (op.bodies[1], p2, drawn[op.pins[1]])):
                frame[body] = (p, (j - p) / (jd - pd), pd)
        for name in out:
            out[name].append(complex(at(frame, prog.holders[name], name)))
    return {name: np.array([[z.real, z.imag] for z in zs]) for name, zs in out.items()}


def plain_positions(linkage: Any, t: np.ndarray) -> dict[str, np.ndarray]:
    """The yardstick: every moving point by the plain numpy closed form a user would write (float (n, 2) arrays,
    each joint by arctan2 and arccos of the law of cosines, no chunks, no care at toggles)."""
    from linkgen.kinematics.fused import CrankOp

    prog = linkage.program
    signs = list(linkage.base_signs)
    drawn = {k: np.array([v.real, v.imag]) for k, v in prog.drawn.items()}
    frame: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}    # body -> (P, turn angle, pd)

    def at(body: str | None, name: str) -> np.ndarray:
        if body is None:
            return np.broadcast_to(drawn[name], (len(t), 2))
        p, phi, pd = frame[body]
        v = drawn[name] - pd
        c, s = np.cos(phi), np.sin(phi)
        return p + np.column_stack([c * v[0] - s * v[1], s * v[0] + c * v[1]])

    for op in prog.ops:
        if isinstance(op, CrankOp):
            phi = t - op.drawn
            frame[op.body] = (at(None, op.pivot), phi, drawn[op.pivot])
            continue
        p1, p2 = at(op.refs[0], op.pins[0]), at(op.refs[1], op.pins[1])
        d = p2 - p1
        dist = np.hypot(d[:, 0], d[:, 1])
        base = np.arctan2(d[:, 1], d[:, 0])
        gamma = np.arccos(np.clip((op.r1**2 + dist**2 - op.r2**2) / (2 * op.r1 * dist), -1, 1))
        th1 = base + signs[op.step] * gamma
        j = p1 + op.r1 * np.column_stack([np.cos(th1), np.sin(th1)])
        for body, p, pin in ((op.bodies[0], p1, op.pins[0]), (op.bodies[1], p2, op.pins[1])):
            v = drawn[op.joint] - drawn[pin]
            now = j - p
            frame[body] = (p, np.arctan2(now[:, 1], now[:, 0]) - math.atan2(v[1], v[0]), drawn[pin])
    return {name: at(holder, name) for name, holder, _ in prog.points if holder is not None}


def pylinkage_model(linkage: Any, t: np.ndarray) -> tuple[Any, list[str]]:
    """The same linkage in pylinkage (a crank, an RRR dyad per joint, a fixed dyad per further point of a body),
    drawn at the pose before ``t[0]`` and stepping by ``t[1] - t[0]``, so that its poses are ours at ``t``; and
    its joints' names in its order. Its crank turns at unit speed for the velocities and accelerations (rad per
    unit time, as ours are per unit crank speed)."""
    import pylinkage as pl

    from linkgen.kinematics.fused import CrankOp

    prog = linkage.program
    step = float(t[1] - t[0])
    start = linkage.positions(np.array([t[0] - step]), strict=False).points
    xy = {name: (float(v[0, 0]), float(v[0, 1])) for name, v in start.items()}
    joints: dict[str, Any] = {}
    placed: dict[str, tuple[str, str]] = {}             # body -> two of its joints already in pylinkage

    def joint(body: str | None, name: str) -> Any:
        """The pylinkage joint of ``name`` on ``body``: a ground point, or a point carried by two of its body's
        joints (a fixed dyad: distance and angle from the line between them)."""
        if name in joints:
            return joints[name]
        if body is None:
            joints[name] = pl.Ground(*xy[name], name=name)
            return joints[name]
        a, b = placed[body]
        da, db = np.subtract(xy[b], xy[a]), np.subtract(xy[name], xy[a])
        angle = math.atan2(db[1], db[0]) - math.atan2(da[1], da[0])
        joints[name] = pl.FixedDyad(joints[a], joints[b], float(np.hypot(*db)), angle, name=name)
        return joints[name]

    for op in prog.ops:
        if isinstance(op, CrankOp):
            pivot = joint(None, op.pivot)
            pin = next(p for p in linkage.structure.bodies[op.body] if p != op.pivot)
            r = math.dist(xy[op.pivot], xy[pin])
            angle = math.atan2(xy[pin][1] - xy[op.pivot][1], xy[pin][0] - xy[op.pivot][0])
            joints[pin] = crank = pl.Crank(pivot, r, angular_velocity=step, initial_angle=angle, name=pin)
            placed[op.body] = (op.pivot, pin)
            continue
        p1, p2 = joint(op.refs[0], op.pins[0]), joint(op.refs[1], op.pins[1])
        joints[op.joint] = pl.RRRDyad(p1, p2, op.r1, op.r2, x=xy[op.joint][0], y=xy[op.joint][1], name=op.joint)
        placed[op.bodies[0]], placed[op.bodies[1]] = (op.pins[0], op.joint), (op.pins[1], op.joint)
    for name, holder, _ in prog.points:
        joint(holder, name)
    model = pl.Linkage(list(joints.values()))
    model.set_input_velocity(crank, 1.0, 0.0)
    return model, list(joints)


def _rounds(funcs: dict[str, Callable[[], Any]], repeats: int) -> dict[str, list[float]]:
    """Each function's wall times over ``repeats`` rounds, the functions taking turns in each round (so that every
    side sees the same machine), after one untimed round."""
    times: dict[str, list[float]] = {k: [] for k in funcs}
    for round_ in range(repeats + 1):
        for k, f in funcs.items():
            start = time.perf_counter()
            f()
            if round_:
                times[k].append(time.perf_counter() - start)
    return times


def _least(funcs: dict[str, Callable[[], Any]], repeats: int) -> dict[str, float]:
    """Each function's least wall time over ``repeats`` rounds taken in turn (see :func:`_rounds`)."""
    return {k: min(v) for k, v in _rounds(funcs, repeats).items()}


def _spread(theirs: list[float], ours: list[float]) -> tuple[float, float, float]:
    """The least, median and largest of the rounds' ratios theirs / ours (each round's pair measured in turn)."""
    ratios = sorted(a / b for a, b in zip(theirs, ours, strict=True))
    return ratios[0], float(np.median(ratios)), ratios[-1]


def solver_rows(sizes: tuple[int, ...] = (10_000, 100_000, 1_000_000), repeats: int = 5) -> list[dict]:
    """Per linkage and size: the least times of our positions (:meth:`Linkage.positions`: every joint, as
    pylinkage gives), our full solve (``solve(derivatives=False)``: rotations, margins and transmission angles too),
    the plain numpy closed form and pylinkage's ``step_fast``; with velocities and accelerations our positions
    (``derivatives=True``: every joint's), our full ``solve()`` and pylinkage's ``step_fast_with_kinematics``;
    their ratios to pylinkage, rates (angles per second) and the accuracy at 100 angles against 50 digits."""
    try:
        import pylinkage  # noqa: F401
        have = True
    except ImportError:
        have = False
    return [_row(name, bundled(template), point, n, repeats, have) for name, template, point in LINKAGES
            for n in sizes]


def _kernels(linkage: Any, t: np.ndarray, threads: int) -> Callable[[], Any]:
    """The fused kernels' positions of ``linkage`` at angles ``t`` (near its drawn turn) on ``threads`` threads."""
    prog, x, signs = linkage.program, t[None, :], list(linkage.base_signs)
    return lambda: fused.run(prog, x, np.ones(1), signs, False, False, FEASIBILITY_TOL, workers=threads)


def _row(name: str, linkage: Any, point: str, n: int, repeats: int, have: bool) -> dict:
    """One row of :func:`solver_rows`: ``linkage`` at n angles, ``have`` whether pylinkage is installed."""
    t = angles(linkage, n)
    probe = np.arange(0, n, max(1, n // 100))
    try:
        ref = reference(linkage, t[probe])[point]
    except ImportError:
        ref = None
    funcs: dict[str, Callable[[], Any]] = {
        "ours positions": lambda: linkage.positions(t),
        "ours solve": lambda: linkage.solve(t, derivatives=False),
        "plain numpy": lambda: plain_positions(linkage, t),
        "ours positions with rates": lambda: linkage.positions(t, derivatives=True),
        "ours with rates": lambda: linkage.solve(t)}
    if compiled.available():           # the optional compiled kernel (numba), compiled before it is timed
        linkage.positions(t[:10], engine="numba")
        funcs["ours compiled positions"] = lambda: linkage.positions(t, engine="numba")
        funcs["ours compiled with rates"] = lambda: linkage.positions(t, derivatives=True, engine="numba")
    for threads in (1, 2):             # the fused kernels alone on one thread and on two: what the threads win
        funcs[f"fused kernels {threads} thread{'s' if threads > 1 else ''}"] = _kernels(linkage, t, threads)
    if have:
        model, order = pylinkage_model(linkage, t)
        funcs["pylinkage step_fast"] = lambda: model.step_fast(iterations=n)
        funcs["pylinkage with rates"] = lambda: model.step_fast_with_kinematics(iterations=n)
    times = _rounds(funcs, repeats)
    best = {k: min(v) for k, v in times.items()}
    row: dict[str, Any] = {"linkage": name, "angles": n, "point": point, **{f"{k} s": v for k, v in best.items()}}
    if ref is not None:
        row["ours error mm"] = float(np.abs(linkage.positions(t[probe]).points[point] - ref).max())
        if "ours compiled positions" in funcs:
            got = linkage.positions(t[probe], engine="numba").points[point]
            row["ours compiled error mm"] = float(np.abs(got - ref).max())
        row["plain numpy error mm"] = float(np.abs(plain_positions(linkage, t[probe])[point] - ref).max())
        if have:
            model, order = pylinkage_model(linkage, t)
            theirs = np.asarray(model.step_fast(iterations=n))[probe, order.index(point), :]
            row["pylinkage error mm"] = float(np.abs(theirs - ref).max())
    if have:
        row["positions speed-up"] = best["pylinkage step_fast"] / best["ours positions"]
        row["solve speed-up"] = best["pylinkage step_fast"] / best["ours solve"]
        row["rates speed-up"] = best["pylinkage with rates"] / best["ours positions with rates"]
        row["solve with rates speed-up"] = best["pylinkage with rates"] / best["ours with rates"]
        row["positions speed-up rounds"] = _spread(times["pylinkage step_fast"], times["ours positions"])
        if "ours compiled positions" in best:
            row["compiled positions speed-up"] = best["pylinkage step_fast"] / best["ours compiled positions"]
            row["compiled positions speed-up rounds"] = _spread(times["pylinkage step_fast"],
                                                                times["ours compiled positions"])
            row["compiled rates speed-up"] = best["pylinkage with rates"] / best["ours compiled with rates"]
            row["compiled rates speed-up rounds"] = _spread(times["pylinkage with rates"],
                                                            times["ours compiled with rates"])
        row["rates speed-up rounds"] = _spread(times["pylinkage with rates"], times["ours positions with rates"])
    row["two threads / one"] = best["fused kernels 1 thread"] / best["fused kernels 2 threads"]
    row["plain numpy / ours positions"] = best["plain numpy"] / best["ours positions"]
    return row


#: what :func:`memory_rows` measures in a fresh process each: the call and its label
_MEMORY_CALLS = {
    "ours positions": "linkage.positions(t)",
    "ours compiled positions": "linkage.positions(t, engine='numba')",
    "ours compiled with rates": "linkage.positions(t, derivatives=True, engine='numba')",
    "ours solve": "linkage.solve(t, derivatives=False)",
    "ours positions with rates": "linkage.positions(t, derivatives=True)",
    "ours with rates": "linkage.solve(t)",
    "pylinkage step_fast": "model.step_fast(iterations=n)",
    "pylinkage with rates": "model.step_fast_with_kinematics(iterations=n)",
}


def peak_rise(template: str, n: int, what: str) -> float | None:
    """The rise (MiB) of a fresh process's peak resident set over its resident set just before one call of
    ``what`` at n angles (the results kept until the peak is read); None where it cannot be measured."""
    code = f"""
import json, math, numpy as np
from linkgen import bench_solver as b
linkage = b.bundled({template!r})
n = {n}
t = b.angles(linkage, n)
model = None
if {what!r}.startswith("pylinkage"):
    model, _ = b.pylinkage_model(linkage, t)
    model.step_fast(iterations=10)
    model.step_fast_with_kinematics(iterations=10)
linkage.positions(t[:100]); linkage.solve(t[:100])
if {what!r}.startswith("ours compiled"):
    linkage.positions(t[:100], derivatives=True, engine="numba")

def status(key):
    for line in open("/proc/self/status"):
        if line.startswith(key):
            return int(line.split()[1]) / 1024
with open("/proc/self/clear_refs", "w") as f:
    f.write("5")
before = status("VmRSS:")
kept = {_MEMORY_CALLS[what]}
print(json.dumps(status("VmHWM:") - before))
"""
    try:
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=child_env(),
                              timeout=600, cwd=Path(__file__).resolve().parents[1])
        return float(json.loads(done.stdout.strip().splitlines()[-1])) if done.returncode == 0 else None
    except (OSError, ValueError, IndexError, subprocess.TimeoutExpired):
        return None


def memory_rows(n: int = 1_000_000) -> list[dict]:
    """Peak memory of each call at n angles on each bundled linkage, each in a fresh process (see
    :func:`peak_rise`)."""
    rows = []
    for name, template, _ in LINKAGES:
        rows.append({"linkage": name, "angles": n,
                     **{f"{what} MiB": peak_rise(template, n, what) for what in _MEMORY_CALLS}})
    return rows


def markdown(rows: list[dict], memory: list[dict]) -> list[str]:
    """The solver rows as Markdown tables."""
    lines = ["## The general solver against pylinkage (numba) and a plain numpy closed form", "",
             "Each linkage is the bundled template. Least of the repeats, the sides taking turns in the same run; "
             "speed-up = pylinkage's least time / ours (above 1: ours faster), and the least, median and largest "
             "of the rounds' own ratios; two threads / one: the fused kernels' least time on one thread over "
             "theirs on two (what the second core wins); errors of the reported point against "
             "a 50-digit solution at 100 of the angles.", "",
             "Positions: every joint's (what pylinkage's step_fast gives); solve: the whole Solution (rotations, "
             "margins, transmission angles, slack too). With rates: every joint's velocity and acceleration besides "
             "(step_fast_with_kinematics), and solve() with the bodies' rates. Compiled: the optional numba "
             "kernel (positions(engine=\"numba\"), pip install 'camgen[fast]'); numpy's is the default.", "",
             "| linkage | angles | ours positions | ours solve | plain numpy | pylinkage step_fast | speed-up "
             "positions / solve | ours positions with rates | ours solve with rates | pylinkage with rates | "
             "speed-up with rates (positions / solve) | rounds' speed-ups min / median / max, positions; with rates | "
             "two threads / one | ours compiled positions | compiled speed-up (rounds min / median / max) | "
             "ours compiled with rates | compiled speed-up with rates (rounds) | "
             "error ours / compiled / pylinkage / plain (mm) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]

    def ms(row: dict, key: str) -> str:
        v = row.get(f"{key} s")
        return "-" if v is None else f"{v * 1e3:.3g} ms ({row['angles'] / v / 1e6:.3g} M/s)"

    def ratio(row: dict, key: str) -> str:
        v = row.get(key)
        return "-" if v is None else f"{v:.2f}x"

    def rounds(row: dict, key: str) -> str:
        v = row.get(key)
        return "-" if v is None else " / ".join(f"{r:.2f}" for r in v)

    def err(row: dict, key: str) -> str:
        v = row.get(key)
        return "-" if v is None else f"{v:.1e}"

    for r in rows:
        lines.append(f"| {r['linkage']} | {r['angles']} | {ms(r, 'ours positions')} | {ms(r, 'ours solve')} | "
                     f"{ms(r, 'plain numpy')} | {ms(r, 'pylinkage step_fast')} | {ratio(r, 'positions speed-up')} / "
                     f"{ratio(r, 'solve speed-up')} | {ms(r, 'ours positions with rates')} | "
                     f"{ms(r, 'ours with rates')} | {ms(r, 'pylinkage with rates')} | {ratio(r, 'rates speed-up')} / "
                     f"{ratio(r, 'solve with rates speed-up')} | {rounds(r, 'positions speed-up rounds')}; "
                     f"{rounds(r, 'rates speed-up rounds')} | {ratio(r, 'two threads / one')} | "
                     f"{ms(r, 'ours compiled positions')} | {ratio(r, 'compiled positions speed-up')} "
                     f"({rounds(r, 'compiled positions speed-up rounds')}) | {ms(r, 'ours compiled with rates')} | "
                     f"{ratio(r, 'compiled rates speed-up')} ({rounds(r, 'compiled rates speed-up rounds')}) | "
                     f"{err(r, 'ours error mm')} / {err(r, 'ours compiled error mm')} / "
                     f"{err(r, 'pylinkage error mm')} / {err(r, 'plain numpy error mm')} |")
    if memory:
        lines += ["", "Peak memory of one call (MiB: the rise of a fresh process's peak resident set, numba's "
                  "allocations included):", "",
                  "| linkage | angles | " + " | ".join(_MEMORY_CALLS) + " |",
                  "|---|---|" + "---|" * len(_MEMORY_CALLS)]
        for r in memory:
            cells = ["-" if r.get(f"{w} MiB") is None else f"{r[f'{w} MiB']:.0f}" for w in _MEMORY_CALLS]
            lines.append(f"| {r['linkage']} | {r['angles']} | " + " | ".join(cells) + " |")
    return lines
