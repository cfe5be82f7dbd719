"""Burmester motion generation: four and five positions made by known four-bars give back their pivots, every dyad
found meets the positions by an independent check (its moving pivot carried with the coupler stays on a circle about
its ground pivot), the candidates move through the positions without defects, and bad tasks are refused in one line
with nothing written."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
from click.testing import CliRunner

from linkgen.synthesis import synthesize, validate_task
from linkgen.synthesis.burmester import burmester_points, four_position_dyads, poses
from linkgen.synthesis.defects import defects
from tests.synthesis.test_synthesis import refused_in_one_line

#: known four-bars placed in the task's frame: crank pivot O2 (mm), ground direction (rad), ground, crank, coupler,
#: rocker (mm), coupler point (along A->B, square to it; mm), branch (+1 open, -1 crossed), crank angles (degrees)
KNOWN = [
    (complex(10, -5), 0.3, 80.0, 30.0, 70.0, 60.0, (25.0, 30.0), 1, (10, 60, 130, 200, 280)),
    (complex(-20, 15), -0.8, 100.0, 25.0, 90.0, 70.0, (-15.0, 40.0), -1, (0, 50, 95, 170, 250)),
]


def known(case):
    """The pivots, pins at each crank angle and the coupler's poses [x, y, angle degrees] of a known four-bar,
    solved here by the intersection of the coupler and rocker circles."""
    o2, turn, r1, r2, r3, r4, (cx, cy), branch, angles = case
    o4 = o2 + r1 * np.exp(1j * turn)
    th = np.radians(angles)
    a = o2 + r2 * np.exp(1j * (turn + th))
    d = o4 - a
    z = np.abs(d)
    along = (r3**2 - r4**2 + z**2) / (2 * z)
    b = a + (along + 1j * branch * np.sqrt(r3**2 - along**2)) * d / z
    u = (b - a) / r3
    p = a + (cx + 1j * cy) * u
    phi = np.degrees(np.unwrap(np.angle(u)))
    return o2, o4, a, b, np.column_stack([p.real, p.imag, phi])


def carried(positions, circle):
    """The moving pivot ``circle`` (drawn at the first position) carried with the coupler to every position."""
    p, alpha = poses(positions)
    return p[:, None] + (circle - p[0])[None, :] * np.exp(1j * alpha)[:, None]


def on_circles(positions, centre, circle):
    """How far (mm) each dyad's moving pivot strays from its circle about the ground pivot over the positions."""
    r = np.abs(carried(positions, circle) - centre[None, :])
    return np.max(r, axis=0) - np.min(r, axis=0)


@pytest.mark.parametrize("case", KNOWN)
def test_four_positions_give_back_the_pivots_on_the_curves(case):
    """The curves at the known crank's (rocker's) turn from position 1 to 2 pass through O2 and A_1 (O4 and B_1)."""
    o2, o4, a, b, pos = known(case)
    p, alpha = poses(pos[:4])
    for ground, pin in ((o2, a), (o4, b)):
        turn = np.angle((pin[1] - ground) / (pin[0] - ground)) % (2 * math.pi)
        d = four_position_dyads(p, alpha, np.array([turn]))
        k = np.nanargmin(np.abs(d.centre - ground))
        assert abs(d.centre[k] - ground) < 1e-8 and abs(d.circle[k] - pin[0]) < 1e-8
        assert np.allclose(np.exp(1j * d.betas[k]), (pin[1:4] - ground) / (pin[0] - ground), atol=1e-10)


@pytest.mark.parametrize("case", KNOWN)
def test_every_sampled_dyad_meets_the_four_positions(case):
    """Sampled round the curve, each dyad found (within 1000 mm) keeps its moving pivot on one circle about its
    ground pivot at all four positions, to 1e-9 of its size; and both branches give dyads."""
    *_, pos = known(case)
    p, alpha = poses(pos[:4])
    d = four_position_dyads(p, alpha, np.linspace(0, 2 * math.pi, 720, endpoint=False))
    ok = np.isfinite(d.centre) & (np.abs(d.centre) < 1000) & (np.abs(d.circle) < 1000)
    assert np.count_nonzero(ok) > 200 and set(d.branch[ok]) == {-1.0, 1.0}
    size = np.abs(d.circle[ok] - d.centre[ok]) + np.abs(d.circle[ok] - p[0])
    assert np.all(on_circles(pos[:4], d.centre[ok], d.circle[ok]) <= 1e-9 * size)


@pytest.mark.parametrize("case", KNOWN)
def test_five_positions_give_back_the_pivots_among_the_burmester_points(case):
    o2, o4, a, b, pos = known(case)
    p, alpha = poses(pos)
    d = burmester_points(p, alpha)
    assert 2 <= len(d.centre) <= 4 and len(d.centre) % 2 == 0
    for ground, pin in ((o2, a), (o4, b)):
        k = np.argmin(np.abs(d.centre - ground))
        assert abs(d.centre[k] - ground) < 1e-8 and abs(d.circle[k] - pin[0]) < 1e-8
    size = np.abs(d.circle - d.centre) + np.abs(d.circle - p[0])
    assert np.all(on_circles(pos, d.centre, d.circle) <= 1e-9 * size)


def sampled_worst_transmission(row) -> float:
    """The worst transmission angle (degrees) of a crank's four-bar over its whole turn, 36 000 crank angles."""
    r1, r2, r3, r4 = (row[k] for k in ("ground", "crank", "coupler", "rocker"))
    t = np.linspace(0, 2 * math.pi, 36000, endpoint=False)
    gamma = np.degrees(np.arccos((r3**2 + r4**2 - (r1**2 + r2**2 - 2 * r1 * r2 * np.cos(t))) / (2 * r3 * r4)))
    return float(np.min(np.minimum(gamma, 180 - gamma)))


@pytest.mark.parametrize("count", [4, 5])
def test_candidates_move_through_the_positions_without_defects(count):
    """Each candidate's pins, carried with the coupler, stay on their circles at every position (1e-9 mm); its crank
    turns fully through them in order on one branch, and its worst transmission angle over the turn, sampled here,
    is at least the 30 degrees asked (and what its row says, within the sampling)."""
    *_, pos = known(KNOWN[0])
    result = synthesize(validate_task({"name": "b", "task": {"kind": "burmester", "positions": pos[:count].tolist(),
                                                             "candidates": 3}}))
    assert result.candidates
    for c in result.candidates:
        row = c.row
        ground = np.array([complex(*xy) for xy in row["ground_pivots"]])
        pins = np.array([complex(*xy) for xy in row["moving_pivots"]])
        assert np.all(on_circles(pos[:count], ground, pins) < 1e-9)
        r = np.abs(carried(pos[:count], pins) - ground[None, :])
        assert np.allclose(r[0], [row["crank"], row["rocker"]], atol=1e-9)
        a, b = carried(pos[:count], pins).T
        theta = np.angle((a - ground[0]) / (ground[1] - ground[0]))
        branch = np.sign(((ground[1] - a) * np.conj(b - a)).imag)
        assert defects((row["ground"], row["crank"], row["coupler"], row["rocker"]), theta, branch, True) == []
        worst = sampled_worst_transmission(row)
        assert worst >= 30 - 1e-6 and abs(worst - row["transmission_worst_deg"]) < 1e-3


def test_the_region_keeps_only_its_dyads():
    """A box for the ground pivots and a range of the curve parameter: every candidate's pivots lie inside."""
    *_, pos = known(KNOWN[0])
    box = [[-150, -150], [150, 150]]
    result = synthesize(validate_task({"name": "b", "task": {
        "kind": "burmester", "positions": pos[:4].tolist(), "centre_region": box, "curve_range": [0, 180]}}))
    for c in result.candidates:
        assert all(-150 <= v <= 150 for xy in c.row["ground_pivots"] for v in xy)
        assert all(0 <= t[0] <= 180 for t in (c.row["free_choice"]["crank_turns_deg"],
                                               c.row["free_choice"]["rocker_turns_deg"]))


_POSE4 = [[18.1, 43.0, 68.2], [12.3, 63.1, 46.2], [-14.8, 50.3, 39.2], [-22.9, 14.9, 53.1]]


@pytest.mark.parametrize(("keys", "message"), [
    ({"positions": _POSE4[:3]}, "task.positions: needs 4 or 5 positions [x, y, angle] (got 3; 2 or 3: kind = "
                                "'motion')"),
    ({"positions": [*_POSE4, *_POSE4[:2]]}, "needs 4 or 5 positions [x, y, angle] (got 6"),
    ({"positions": [*_POSE4[:3], [18.1, 43.0, 428.2]]}, "task.positions: items 0 and 3 give the same pose"),
    ({"positions": [[0, 0, 10], [10, 0, 10], [20, 5, 10], [5, 30, 10]]}, "task.positions: the coupler must turn"),
    ({"positions": _POSE4, "centre_region": [[500, 500], [600, 600]]}, "task.centre_region: 0 of the"),
    ({"positions": _POSE4, "centre_region": [[5, 5], [0, 10]]}, "task.centre_region: give [[x_min, y_min]"),
    ({"positions": _POSE4, "curve_range": [90, 400]}, "task.curve_range: give [from, to] in degrees with 0 <= from"),
    ({"positions": _POSE4, "samples": 100000}, "task.samples"),
    ({"kind": "motion", "positions": _POSE4}, "task.positions: needs 2 or 3 positions [x, y, angle] (got 4; 4 or 5: "
                                              "kind = 'burmester')"),
])
def test_bad_burmester_tasks_are_one_line_exit_2_and_nothing_written(tmp_path, keys, message):
    refused_in_one_line(tmp_path, {"kind": "burmester", **keys}, message)


def test_a_written_candidate_builds(tmp_path):
    """The bundled four-position task's first candidate, written, is a template `linkgen build` takes; its figure
    (with the curves) is drawn when asked."""
    from linkgen.cli import main

    from tests.conftest import ROOT
    out = tmp_path / "s"
    result = CliRunner().invoke(main, ["synthesize", str(ROOT / "templates" / "synth-burmester.toml"), "-o", str(out),
                                       "--figures"])
    assert result.exit_code == 0, result.output
    assert (out / "synth-burmester-1-curve.png").stat().st_size > 0
    first = out / "synth-burmester-1.toml"
    assert tomllib.loads(first.read_text())["linkage"]["type"] == "linkage"
    built = CliRunner().invoke(main, ["build", str(first), "-o", str(tmp_path / "b")])
    assert built.exit_code == 0, built.output
