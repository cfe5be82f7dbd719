"""``linkgen bench``: linkage positions against a plain closed form and pylinkage, measured in the same run,
and the linkages' hard cases.

Every figure is measured here, on this machine, in this run; nothing is asserted about time.
Results go to ``RESULTS.md`` and ``results.json``.
"""
from __future__ import annotations

import math
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from camgen.core import bench as core_bench
from camgen.core.bench import call_seconds, process_seconds, ratio_markdown, ratio_row, timed
from linkgen.kinematics import dyads, equivalents
from linkgen.kinematics.fourbar import FourBar
from linkgen.kinematics.inertia import LinkMass, moving_links
from linkgen.kinematics.kinetostatics import Loads, kinetostatics
from linkgen.kinematics.linkage import Linkage
from linkgen.kinematics.slidercrank import SliderCrank
from linkgen.kinematics.structure import Input, Structure, make_structure

#: Jansen's "holy numbers" (mm): a, l the crank centre to the fixed pivot B (left and down), m the crank, the rest
#: the legs' bars and triangles (strandbeest.com)
HOLY = {"a": 38.0, "b": 41.5, "c": 39.3, "d": 40.1, "e": 55.8, "f": 39.4, "g": 36.7, "h": 65.7, "i": 49.0,
        "j": 50.0, "k": 61.9, "l": 7.8, "m": 15.0}
#: Jansen's joints in solve order: (joint, first known joint, its distance, second, its distance, pick), ``pick``
#: choosing the intersection: the upper ('y+'), lower ('y-') or left ('x-') one
JANSEN_DYADS = (("C", "A", "j", "B", "b", "y+"), ("D", "A", "k", "B", "c", "y-"), ("E", "B", "d", "C", "e", "x-"),
                ("F", "E", "f", "D", "g", "x-"), ("G", "D", "i", "F", "h", "y-"))


def linkage_speed(repeats: int) -> list[dict]:
    """Rocker-pin positions of the reference crank-rocker at 360 and 100 000 crank angles: ours, a plain numpy
    closed form (arccos), and pylinkage (plain steps, and its numba-compiled steps), with their accuracy."""
    fb = FourBar(180, 80, 200, 150)
    rows = []
    for n in (360, 100_000):
        t = 2 * math.pi / n * np.arange(1, n + 1)
        exact, ours = timed(partial(_rocker_pins, fb, t), repeats)
        naive, seconds = timed(partial(plain_positions, t), repeats)
        rows += [{"method": "linkgen closed form (stable at toggles)", "angles": n, "seconds": ours,
                  "max_error_mm": 0.0},
                 {"method": "plain numpy closed form (arccos)", "angles": n, "seconds": seconds,
                  "max_error_mm": float(np.abs(naive - exact).max())}]
        rows += _pylinkage(n, exact, repeats)
    return rows


#: the bundled crank-rocker (templates/crank-rocker.toml), written out by the bench to time the commands
CRANK_ROCKER = """name = "crank-rocker"
[linkage]
type = "four-bar"
ground = 180.0
crank = 80.0
coupler = 200.0
rocker = 150.0
[parts]
width = 14.0
thickness = 4.0
pin_diameter = 4.0
clearance = 0.2
kerf = 0.15
sheet = [600.0, 400.0]
pins = true
"""


def _rocker_pins(fb: FourBar, t: np.ndarray) -> np.ndarray:
    """The rocker pin B (n, 2) mm of ``fb`` at crank angles ``t`` (rad), by linkgen's closed form."""
    return fb.positions(t).b


def plain_positions(t: np.ndarray) -> np.ndarray:
    """The reference crank-rocker's rocker pin at crank angles ``t`` by the plain numpy closed form (arccos, one
    branch, no care at toggles): the yardstick of :func:`speed_ratios`."""
    ax, ay = 80 * np.cos(t), 80 * np.sin(t)
    dx, dy = 180 - ax, -ay
    z = np.hypot(dx, dy)
    alpha = np.arccos(np.clip((200**2 + z**2 - 150**2) / (2 * 200 * z), -1, 1))
    th3 = np.arctan2(dy, dx) + alpha
    return np.column_stack([ax + 200 * np.cos(th3), ay + 200 * np.sin(th3)])


def positions_ratio(repeats: int) -> dict:
    """The four-bar positions row of :func:`speed_ratios` alone (``repeats`` alternated pairs): the bundled
    crank-rocker's rocker pins at 100 000 crank angles (``FourBar.positions(t).b``; the rest of each pose is derived
    only when read) against :func:`plain_positions`, e.g.
    ``python -c "from linkgen.bench import positions_ratio; print(positions_ratio(20))"``."""
    fb = FourBar(180, 80, 200, 150)
    t = 2 * math.pi / 100_000 * np.arange(1, 100_001)
    return ratio_row("four-bar positions, 100 000 crank angles", "plain numpy closed form (arccos)",
                     lambda: call_seconds(lambda: fb.positions(t).b, 3),
                     lambda: call_seconds(lambda: plain_positions(t), 3), repeats, goal="<= 1.0x")


def jansen_masses(structure: Structure) -> dict[str, LinkMass]:
    """Masses for Jansen's leg's moving links as 3 mm plywood bars 8 mm wide along their joints' lines (kg, mm,
    kg*mm^2: 680 kg/m^3; each centre the middle of its joints; a slender bar's m L^2 / 12 over its longest side):
    what :func:`kinetostatics_ratio` times the forces of (their values do not change the work)."""
    out = {}
    for body in moving_links(structure):
        pts = np.array([structure.points[p] for p in structure.bodies[body]], dtype=float)
        sides = [float(np.hypot(*(pts[i] - pts[j]))) for i in range(len(pts)) for j in range(i)]
        mass = 680e-9 * 3.0 * 8.0 * sum(sides)
        centre = pts.mean(axis=0)
        out[body] = LinkMass(mass, (float(centre[0]), float(centre[1])), mass * max(sides) ** 2 / 12)
    return out


def kinetostatics_ratio(repeats: int, n: int = 3600) -> dict:
    """Jansen's leg at 60 rpm under gravity at ``n`` crank angles: its kinetostatics (positions, rates and every
    joint's force and the driving torque by Newton-Euler, :func:`linkgen.kinematics.kinetostatics.kinetostatics`)
    against its kinematics alone (positions, velocities and accelerations), alternated ``repeats`` times; the
    forces' share alone (given the kinematics) is in ``forces_seconds``."""
    leg = Linkage.of(jansen(0.0))
    masses, loads = jansen_masses(leg.structure), Loads((0.0, -9.80665))
    t = 2 * math.pi / n * np.arange(n)
    speed = 2 * math.pi
    sol = leg.solve(t)
    count = f"{n:,}".replace(",", " ")
    row = ratio_row(f"kinetostatics of Jansen's leg, {count} crank angles",
                    "its kinematics (positions, velocities, accelerations)",
                    lambda: call_seconds(lambda: kinetostatics(leg, leg.solve(t), masses, speed, 0.0, loads), 3),
                    lambda: call_seconds(lambda: leg.solve(t), 3), repeats, warm=2, goal="<= 3x")
    _, forces = timed(lambda: kinetostatics(leg, sol, masses, speed, 0.0, loads), max(3, repeats))
    return {**row, "forces_seconds": forces}


def forward_ratio(repeats: int) -> dict:
    """Forward dynamics of Jansen's leg (its masses of :func:`jansen_masses`, upright under gravity, with the
    flywheel for a speed fluctuation of 0.05 at 60 rpm) driven by a motor's torque-speed line (0.005 N*m at rest,
    no load at 60 rpm) from rest for 10 turns: the equation of motion tabulated and integrated
    (:mod:`linkgen.dynamics.forward`), against the leg's kinematics at 3 600 crank angles, alternated ``repeats``
    times. The issue asks for it under a second (the row's own time)."""
    from linkgen.dynamics.forward import equation_of, simulate
    from linkgen.dynamics.motor import MAX_TIME, Motor, MotorTable
    from linkgen.kinematics.balance import fluctuation, flywheel_inertia
    from linkgen.kinematics.inertia import generalised_inertia

    leg = Linkage.of(jansen(0.0))
    masses, loads = jansen_masses(leg.structure), Loads((0.0, -9.80665))
    t = 2 * math.pi / 720 * np.arange(720)
    sol = leg.solve(t)
    energy = fluctuation(t, kinetostatics(leg, sol, masses, 2 * math.pi, 0.0, loads).effort).energy
    _, flywheel = flywheel_inertia(energy, 0.05, 2 * math.pi, float(generalised_inertia(leg.structure, sol,
                                                                                         masses)[0].mean()))
    motor = Motor.of(MotorTable(stall_torque=0.005, no_load_speed=60.0))
    fine = 2 * math.pi / 3600 * np.arange(3600)

    def run() -> None:
        motion = simulate(equation_of(leg, masses, loads, 0.0, flywheel, motor), MAX_TIME, turns=10, settle=False)
        if len(motion.turn_ends) != 10:
            raise RuntimeError(f"the bench's leg ran {len(motion.turn_ends)} turns, not 10 ({motion.outcome})")

    return ratio_row("forward dynamics of Jansen's leg, 10 turns from rest",
                     "its kinematics at 3 600 crank angles (positions, velocities, accelerations)",
                     lambda: call_seconds(run, 1), lambda: call_seconds(lambda: leg.solve(fine), 3), repeats,
                     warm=1, goal="< 1 s")


def speed_ratios(repeats: int, quick: bool = False) -> list[dict]:
    """Each of the issue's figures next to its yardstick measured alternately in this run (see
    :func:`camgen.core.bench.ratio_row`): four-bar positions at 100 000 crank angles against :func:`plain_positions`;
    Jansen's leg's kinetostatics at 3 600 against its kinematics (:func:`kinetostatics_ratio`), and its forward
    dynamics over 10 turns from rest (:func:`forward_ratio`); ``linkgen analyze``
    and ``linkgen build`` of the crank-rocker as whole processes (CPU seconds) against a process that only imports
    numpy and ezdxf (``quick``: ``linkgen build`` with its default outputs only)."""
    rows = [positions_ratio(repeats * 4), kinetostatics_ratio(repeats * 4), forward_ratio(repeats)]
    python = sys.executable
    reference = [python, "-c", "import numpy, ezdxf"]
    with tempfile.TemporaryDirectory() as tmp:
        template = Path(tmp) / "crank-rocker.toml"
        template.write_text(CRANK_ROCKER, encoding="utf-8")
        commands = (("analyze", "<= 3x", ""), ("build", "<= 3x", ""), ("build", "-", " --figures"))
        for command, goal, extra in commands[1:2] if quick else commands:
            args = [python, "-m", "linkgen", command, str(template), "-o", str(Path(tmp) / command), *extra.split()]
            what = "with its figures (--figures)" if extra else "every default output"
            rows.append(ratio_row(f"linkgen {command} crank-rocker, {what}",
                                  "python -c 'import numpy, ezdxf'", partial(process_seconds, args),
                                  lambda: process_seconds(reference), repeats, unit="cpu s", goal=goal))
    return rows


def _pylinkage(n: int, exact: np.ndarray, repeats: int) -> list[dict]:
    try:
        import pylinkage as pl
    except ImportError:
        return [{"method": "pylinkage", "angles": n, "seconds": None,
                 "status": "not installed (pip install '.[bench]')"}]
    try:
        import numba  # noqa: F401 - pylinkage compiles its fast steps with it where it installs
        fast_name = "pylinkage step_fast (numba)"
    except ImportError:
        fast_name = "pylinkage step_fast (numba not installed)"

    def linkage() -> Any:
        o2, o4 = pl.Ground(0, 0), pl.Ground(180, 0)
        crank = pl.Crank(o2, 80, angular_velocity=2 * math.pi / n, initial_angle=0.0)
        return pl.Linkage([o2, o4, crank, pl.RRRDyad(crank, o4, 200, 150, x=245, y=135)])

    rows = []
    for name, run in (("pylinkage step (plain Python)", lambda: np.array([c[3] for c in linkage().step(iterations=n)],
                                                                      dtype=float)),
                      (fast_name, lambda: linkage().step_fast(iterations=n)[:, 3, :])):
        start = time.perf_counter()
        run()
        first = time.perf_counter() - start
        result, seconds = timed(run, repeats)
        rows.append({"method": name, "angles": n, "seconds": seconds, "first_call_seconds": first,
                     "max_error_mm": float(np.abs(result - exact).max())})
    return rows


def _pick(candidates: list, how: str) -> Any:
    axis, sign = (1 if how[0] == "y" else 0), (1 if how[1] == "+" else -1)
    return max(candidates, key=lambda p: sign * p[axis])


def jansen_points(theta: float) -> dict[str, tuple[float, float]]:
    """Jansen's leg drawn at crank angle ``theta`` (rad): crank centre O at the origin, fixed pivot B at (-a, -l),
    crank pin A, and the joints C to G (G the foot) by circle intersections, each on its usual side."""
    pts = {"O": (0.0, 0.0), "B": (-HOLY["a"], -HOLY["l"]),
           "A": (HOLY["m"] * math.cos(theta), HOLY["m"] * math.sin(theta))}
    for joint, p, rp, q, rq, how in JANSEN_DYADS:
        both = [dyads.circle_circle(np.array([pts[p]]), HOLY[rp], np.array([pts[q]]), HOLY[rq], sign)[0][0]
                for sign in (1.0, -1.0)]
        x, y = _pick(both, how)
        pts[joint] = (float(x), float(y))
    return pts


def jansen(theta: float = 0.0) -> Structure:
    """Jansen's leg as a general linkage drawn at ``theta``: crank O-A, bars A-C, A-D, B-D, E-F, the triangle
    B-C-E and the foot triangle D-F-G."""
    links = {"crank": ("O", "A"), "upper": ("A", "C"), "lower": ("A", "D"), "back": ("B", "D"),
             "top": ("B", "C", "E"), "thigh": ("E", "F"), "foot": ("D", "F", "G")}
    return make_structure(jansen_points(theta), links, ("O", "B"), (), (Input("crank", "crank", "O"),))


def jansen_reference(thetas: np.ndarray, signs: dict[str, int]) -> np.ndarray:
    """The foot G at crank angles ``thetas`` to 50 digits (mpmath), each joint on the side ``signs`` gives (+1:
    left of the line from its first known joint to its second)."""
    import mpmath

    mpmath.mp.dps = 50
    out = []
    for theta in thetas:
        t = mpmath.mpf(float(theta))
        pts = {"B": (-mpmath.mpf(HOLY["a"]), -mpmath.mpf(HOLY["l"])),
               "A": (HOLY["m"] * mpmath.cos(t), HOLY["m"] * mpmath.sin(t))}
        for joint, p, rp, q, rq, _ in JANSEN_DYADS:
            (x1, y1), (x2, y2) = pts[p], pts[q]
            r1, r2 = mpmath.mpf(HOLY[rp]), mpmath.mpf(HOLY[rq])
            d = mpmath.sqrt((x2 - x1) ** 2 + (y2 - y1) ** 2)
            along = (d * d + r1 * r1 - r2 * r2) / (2 * d)
            h = signs[joint] * mpmath.sqrt(r1 * r1 - along * along)
            ex, ey = (x2 - x1) / d, (y2 - y1) / d
            pts[joint] = (x1 + along * ex - h * ey, y1 + along * ey + h * ex)
        out.append([float(pts["G"][0]), float(pts["G"][1])])
    return np.array(out)


def general_speed(repeats: int, n: int = 100_000) -> list[dict]:
    """The general solver against the dedicated four-bar closed form, and Jansen's leg against pylinkage, at ``n``
    crank angles, with the accuracy of each against a 50-digit reference (Jansen) or the closed form (four-bar)."""
    t = 2 * math.pi / n * np.arange(1, n + 1)
    fb = FourBar(180, 80, 200, 150)
    general = Linkage.of(equivalents.fourbar(fb, 0.0))
    exact, dedicated = timed(lambda: fb.positions(t).b, repeats)
    ours, seconds = timed(lambda: general.solve(t, derivatives=False).points["B"], repeats)
    rows = [{"linkage": "four-bar", "method": "linkgen dedicated closed form", "angles": n, "seconds": dedicated,
             "max_error_mm": 0.0},
            {"linkage": "four-bar", "method": "linkgen general solver (positions)", "angles": n, "seconds": seconds,
             "max_error_mm": float(np.abs(ours - exact).max())}]
    leg = Linkage.of(jansen(0.0))
    pts = leg.structure.points
    signs = {j: int(np.sign(dyads.cross(np.subtract(pts[q], pts[p]), np.subtract(pts[j], pts[p]))))
             for j, p, _, q, _, _ in JANSEN_DYADS}
    probe = np.arange(0, n, max(1, n // 100))
    try:
        reference = jansen_reference(t[probe], signs)
    except ImportError:                       # mpmath is the bench's and the tests' extra: compare with ours then
        reference = leg.solve(t[probe], derivatives=False).points["G"]
    foot, seconds = timed(lambda: leg.solve(t, derivatives=False).points["G"], repeats)
    _, with_rates = timed(lambda: leg.solve(t), repeats)
    rows += [{"linkage": "jansen", "method": "linkgen general solver (positions)", "angles": n, "seconds": seconds,
              "max_error_mm": float(np.abs(foot[probe] - reference).max())},
             {"linkage": "jansen", "method": "linkgen general solver (positions, velocities, accelerations)",
              "angles": n, "seconds": with_rates, "max_error_mm": None}]
    rows += _pylinkage_jansen(t, probe, reference, repeats)
    return rows


def _pylinkage_jansen(t: np.ndarray, probe: np.ndarray, reference: np.ndarray, repeats: int) -> list[dict]:
    """pylinkage's fastest path (its numba-compiled steps) on the same leg, drawn at the same first angle."""
    row = {"linkage": "jansen", "angles": len(t)}
    try:
        import pylinkage as pl
    except ImportError:
        return [{**row, "method": "pylinkage", "seconds": None, "status": "not installed (pip install '.[bench]')"}]
    start = jansen_points(float(t[0]))

    def linkage() -> Any:
        o, b = pl.Ground(0, 0, name="O"), pl.Ground(*start["B"], name="B")
        # its first pose is one step after the start: start a step early so that its poses are ours
        step = float(t[1] - t[0])
        crank = pl.Crank(o, HOLY["m"], angular_velocity=step, initial_angle=float(t[0]) - step, name="A")
        joints = {"O": o, "B": b, "A": crank}
        for joint, p, rp, q, rq, _ in JANSEN_DYADS:
            joints[joint] = pl.RRRDyad(joints[p], joints[q], HOLY[rp], HOLY[rq], x=start[joint][0],
                                       y=start[joint][1], name=joint)
        return pl.Linkage(list(joints.values())), list(joints).index("G")

    mech, foot = linkage()

    def run() -> np.ndarray:
        return np.asarray(mech.step_fast(iterations=len(t))[:, foot, :], dtype=float)

    begin = time.perf_counter()
    run()
    first_seconds = time.perf_counter() - begin
    mech, foot = linkage()
    result, seconds = timed(run, repeats)
    err = float(np.abs(result[probe] - reference).max())
    return [{**row, "method": "pylinkage step_fast (numba)", "seconds": seconds, "first_call_seconds": first_seconds,
             "max_error_mm": err}]


def hard_cases() -> list[dict]:
    """Each hard case with what happened: a sound value, or a clean refusal (never NaN or garbage)."""
    return core_bench.hard_cases(_cases())


def _cases() -> Iterator[tuple[str, Callable[[], str]]]:
    fb = FourBar(100, 70, 60, 80)
    ranges = fb.input_ranges()
    if ranges is None:                                  # a rocker: its crank has a toggle
        raise ValueError("the hard case's four-bar turns fully: it has no toggle")
    _, hi = ranges[0]
    for offset in (0.0, 1e-12):
        def toggle(offset: float = offset) -> str:
            p = fb.positions([hi - offset])
            closes = abs(np.linalg.norm(p.b[0] - p.a[0]) - 60) < 1e-9
            return f"{'ok' if closes and np.isfinite(p.theta4).all() else 'WRONG'}: transmission " \
                   f"{math.degrees(p.gamma[0]):.6f} deg"

        yield f"four-bar {offset:g} rad inside its toggle", toggle
    yield "four-bar 1e-6 rad beyond its toggle", lambda: str(fb.positions([hi + 1e-6]).theta3)
    par = FourBar(100, 40, 100, 40)
    yield "parallelogram through its change points", lambda: "ok" if np.abs(np.sin(par.sweep(
        np.radians(np.linspace(10, 730, 1441)), "open").theta3)).max() < 1e-12 else "WRONG"
    sc = SliderCrank(50.0, 50.0 + 1e-9)
    yield "slider-crank with rod = crank + 1e-9", lambda: "ok" if np.isfinite(sc.motion(
        np.linspace(0, 2 * math.pi, 721), 1.0).a).all() else "WRONG"


def run_bench(out: str | Path, quick: bool = False) -> dict:
    """Run everything; write RESULTS.md and results.json into ``out``; return the results."""
    repeats = 1 if quick else 5
    from linkgen.bench_solver import memory_rows, solver_rows
    from linkgen.synthesis.bench import published_rows, synthesis_rows

    return core_bench.finish(Path(out), {"quick": quick, "speed": speed_ratios(1 if quick else 5, quick),
                                         "linkages": linkage_speed(repeats),
                                         "general": general_speed(repeats, 10_000 if quick else 100_000),
                                         "solver": solver_rows((10_000,) if quick else (10_000, 100_000, 1_000_000),
                                                               1 if quick else 5),
                                         "solver_memory": [] if quick else memory_rows(),
                                         "synthesis": synthesis_rows(quick),
                                         "published": published_rows(quick=quick),
                                         "hard_cases": hard_cases()}, _markdown)


def _markdown(r: dict) -> list[str]:
    lines = ["# linkgen bench", "", f"Python {r['python']}; {'quick run' if r['quick'] else 'full run'}; "
             "median of repeats.", "",
             "## Speed against yardsticks measured in the same run", "",
             "Each row alternates with its reference; the ratio is the median of the pairs' ratios, with the least "
             "and the largest. Whole processes are timed in CPU seconds (user + system).", "",
             *ratio_markdown(r.get("speed", [])), "",
             *[f"The {row['what']}: the forces alone, given the kinematics, take {row['forces_seconds'] * 1e3:.3g} "
               "ms." for row in r.get("speed", []) if "forces_seconds" in row], "",
             "## Linkage positions (rocker pin of the reference crank-rocker)", "",
             "| method | angles | seconds | max error (mm) | status |", "|---|---|---|---|---|"]
    for row in r["linkages"]:
        sec = "-" if row.get("seconds") is None else f"{row['seconds']:.5f}"
        err = "-" if row.get("max_error_mm") is None else f"{row['max_error_mm']:.1e}"
        status = row.get("status", "measured")
        lines.append(f"| {row['method']} | {row.get('angles') or '-'} | {sec} | {err} | {status} |")
    lines += ["", "## Any linkage: the general solver", "",
              "| linkage | method | angles | seconds | max error (mm) | status |", "|---|---|---|---|---|---|"]
    for row in r.get("general", []):
        sec = "-" if row.get("seconds") is None else f"{row['seconds']:.5f}"
        err = "-" if row.get("max_error_mm") is None else f"{row['max_error_mm']:.1e}"
        lines.append(f"| {row['linkage']} | {row['method']} | {row['angles']} | {sec} | {err} | "
                     f"{row.get('status', 'measured')} |")
    lines += ["", "Jansen's leg (the holy numbers): errors of the foot against a 50-digit (mpmath) solution at 100 of "
              "the angles; the four-bar's against linkgen's dedicated closed form."]
    from linkgen.bench_solver import markdown as solver_markdown
    from linkgen.synthesis.bench import markdown as synthesis_markdown
    from linkgen.synthesis.bench import published_markdown

    lines += ["", *solver_markdown(r.get("solver", []), r.get("solver_memory", []))]

    lines += ["", "## Synthesis (`linkgen synthesize`)", "", *synthesis_markdown(r.get("synthesis", []))]
    lines += ["", "## Published path problems: each paper's linkage beside ours", "",
              *published_markdown(r.get("published", []), r.get("synthesis", []))]
    return [*lines, "", "Errors of linkage positions are against linkgen's closed form (which the tests check "
                    "against 50-digit references); pylinkage's first call includes its compilation: "
                    + "; ".join(f"{row['method']} at {row['angles']}: {row['first_call_seconds']:.3f} s"
                                for row in r["linkages"] if "first_call_seconds" in row) + "."]
