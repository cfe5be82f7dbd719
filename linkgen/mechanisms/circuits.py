"""The four-bar report's circuits: every link's limits and swing on each circuit, in the course's words.

See :mod:`linkgen.kinematics.circuits` for what a circuit is. The report lists every circuit (a crank
that turns fully: one an assembly; a limited input: one a range of its angles, both assemblies on it)
and marks the one the linkage is drawn on: the one holding the pose the drawings start from (its
assembly a tenth into the input's first range, or at 30 degrees when the crank turns fully). Angles
in degrees in [0, 360) as in the rest of the report; a swing runs counter-clockwise from ``from_deg``
to ``to_deg``.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from linkgen.kinematics.circuits import Circuit, Limit, Swing, circuits, drawn, mirrored
from linkgen.kinematics.fourbar import ASSEMBLIES, Assembly, FourBar
from linkgen.mechanisms.common import deg

#: which links are in line at each kind of limit position
MEANING = {"extended": "crank and coupler in line, extended", "folded": "crank and coupler in line, folded",
           "toggle-extended": "coupler and rocker in line, extended",
           "toggle-folded": "coupler and rocker in line, folded",
           "fold": "all four links in line (a change point)"}
LABELS = {1: "open", -1: "crossed", 0: "both"}


def motion(swing: Swing) -> str:
    """How a link pivoted on the ground moves on a circuit, in the course's words: ``a crank that turns fully``,
    ``a rocker that oscillates`` or ``a rocker that oscillates through the ground line (at 0 degrees)`` (or 180)."""
    if swing.turns:
        return "a crank that turns fully"
    if swing.still:
        return f"does not move (stays at {deg(swing.start):g} degrees)"
    through = swing.through()
    if not through:
        return "a rocker that oscillates"
    at = " and ".join(f"{math.degrees(x):g}" for x in through)
    return f"a rocker that oscillates through the ground line (at {at} degrees)"


def coupler_motion(circuit: Circuit) -> str:
    """The coupler's motion relative to the ground on a circuit."""
    return {"turns": "turns fully", "oscillates": "oscillates, never a full turn",
            "translates": "translates, never turning (it stays parallel to itself)"}[circuit.coupler]


def _limit(limit: Limit) -> dict[str, Any]:
    return {"kind": limit.kind, "crank_deg": deg(limit.crank), "rocker_deg": deg(limit.rocker),
            "assembly": LABELS[limit.assembly], "meaning": MEANING[limit.kind]}


def _swing(swing: Swing) -> dict[str, Any]:
    entry: dict[str, Any] = {"motion": "crank" if swing.turns else "still" if swing.still else "rocker",
                             "description": motion(swing)}
    if swing.turns:
        return {**entry, "swing_deg": 360.0, "limits": []}
    if swing.still:
        return {**entry, "from_deg": deg(swing.start), "to_deg": deg(swing.start), "swing_deg": 0.0, "limits": []}
    return {**entry, "from_deg": deg(swing.start), "to_deg": deg(swing.end),
            "swing_deg": round(math.degrees(swing.arc), 9),
            "through_ground_line_deg": [round(math.degrees(x), 9) for x in swing.through()],
            "limits": [_limit(x) for x in swing.limits]}


def _entry(circuit: Circuit, is_drawn: bool) -> dict[str, Any]:
    span = circuit.input_range
    return {"drawn": is_drawn,
            "input_range_deg": None if span is None else [round(math.degrees(x), 9) for x in span],
            "assemblies": [LABELS[a] for a in circuit.assemblies] if span is None else ["open", "crossed"],
            "input_turns": circuit.turns or None,
            "crank": _swing(circuit.crank),
            "coupler": {"motion": circuit.coupler, "description": coupler_motion(circuit)},
            "rocker": _swing(circuit.rocker)}


def drawn_pose(fb: FourBar) -> float:
    """The crank angle (rad) the drawings start from (:func:`linkgen.mechanisms.fourbar.fourbar_sketch`'s)."""
    ranges = fb.input_ranges()
    if ranges is None:
        return math.radians(30)
    lo, hi = ranges[0]
    return lo + 0.1 * (hi - lo)


def circuits_report(fb: FourBar, assembly: Assembly, rocker_in: bool) -> dict[str, Any]:
    """The report's ``circuits`` (every circuit, the drawn one marked), ``motion`` (the drawn circuit's, in the
    course's words) and ``rocker_swing_deg`` (the rocker's swing there, None where it turns fully); with
    ``rocker_in`` the circuits are the rocker-driven linkage's (its input range the rocker's angles, its
    assemblies named as :meth:`FourBar.rocker_positions` names them)."""
    label = 1 if assembly == "open" else -1
    crank = drawn_pose(fb)
    if rocker_in:
        mirror = FourBar(fb.ground, fb.rocker, fb.coupler, fb.crank)
        found = circuits(mirror)
        at = _mirror_label(fb, crank, assembly)
        index = drawn(found, math.pi - at[0], at[1])
        found = tuple(mirrored(c) for c in found)
    else:
        found = circuits(fb)
        index = drawn(found, crank, label)
    shown = found[index]
    return {"circuits": [_entry(c, i == index) for i, c in enumerate(found)],
            "motion": {"crank": motion(shown.crank), "coupler": coupler_motion(shown), "rocker": motion(shown.rocker)},
            "rocker_swing_deg": None if shown.rocker.turns else round(math.degrees(shown.rocker.arc), 9)}


def split_warning(report: dict[str, Any], link: str) -> str | None:
    """The warning that an input's reach is split into separate circuits, or None."""
    spans = [c["input_range_deg"] for c in report["circuits"] if c["input_range_deg"] is not None]
    if len(spans) < 2:
        return None
    text = " and ".join(f"{lo:.4f} to {hi:.4f}" for lo, hi in spans)
    first = next(i for i, c in enumerate(report["circuits"]) if c["drawn"]) + 1
    return (f"the {link}'s reach is split into {len(spans)} separate circuits ({link} {text} degrees): the linkage "
            f"never passes from one to the other; it is drawn on circuit {first}")


def _mirror_label(fb: FourBar, theta2: float, assembly: Assembly) -> tuple[float, int]:
    """The rocker angle (rad) and the rocker-driven label (+1 open, -1 crossed, 0 both) of the crank-driven pose
    at ``theta2`` with ``assembly``."""
    pose = fb.positions([theta2], assembly)
    t4 = float(pose.theta4[0])
    labels = [s for s, name in zip((1, -1), ASSEMBLIES, strict=True)
              if np.linalg.norm(fb.rocker_positions([t4], name).a[0] - pose.a[0]) <= 1e-7 * fb.longest]
    return t4, labels[0] if len(labels) == 1 else 0
