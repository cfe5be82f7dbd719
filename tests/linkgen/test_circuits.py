"""Limits and swings by circuit (issue 30, item 1 and "also asked"): the course's Exercise 3.1 (ground 100,
crank 125, coupler 75, rocker 88, 125 or 163 mm) worked here by the law of cosines, both assemblies, the
rocker-driven view, and random linkages against their own poses sampled along each circuit.

The derivation, independent of :mod:`linkgen.kinematics.circuits`:

* the crank stops where coupler and rocker are in line: |A O4| = L3 + L4 (extended) or |L3 - L4| (folded), so in
  the triangle O2-A-O4 cos theta2 = (L1^2 + L2^2 - |A O4|^2) / (2 L1 L2);
* the rocker stops where crank and coupler are in line: |O2 B| = L2 + L3 or |L2 - L3|, so in the triangle O2-B-O4
  the angle at O4 is psi, cos psi = (L1^2 + L4^2 - |O2 B|^2) / (2 L1 L4), theta4 = 180 -+ psi, and the angle at
  O2 is phi, cos phi = (L1^2 + |O2 B|^2 - L4^2) / (2 L1 |O2 B|) (the crank at phi, or phi + 180 folded with
  L3 > L2);
* which of the two arcs between its limits a link sweeps follows from whether it can point along the ground line:
  the rocker at theta4 = 0 puts B at L1 + L4 from O2, at 180 at |L1 - L4|; reachable when that distance lies in
  [|L2 - L3|, L2 + L3].
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from linkgen.cli import main
from linkgen.kinematics.circuits import TWO_PI, circuits
from linkgen.kinematics.fourbar import FourBar

L1, L2, L3 = 100.0, 125.0, 75.0


def cos_rule(a: float, b: float, opposite: float) -> float:
    """The angle (degrees) between sides a and b of a triangle whose third side is ``opposite``."""
    return math.degrees(math.acos((a * a + b * b - opposite * opposite) / (2 * a * b)))


def reachable(l4: float, theta4: float) -> bool:
    """Whether the rocker can point at ``theta4`` degrees (0 or 180): |O2 B| within crank and coupler's reach."""
    o2b = L1 + l4 if theta4 == 0 else abs(L1 - l4)
    return abs(L2 - L3) <= o2b <= L2 + L3


def analyze(tmp_path, l4: float, *args: str, **linkage: str) -> dict:
    tmp_path.mkdir(exist_ok=True)
    path = tmp_path / "t.toml"
    extra = "".join(f'{k} = "{v}"\n' for k, v in linkage.items())
    path.write_text(f'name = "ex31"\n[linkage]\ntype = "four-bar"\nground = {L1}\ncrank = {L2}\ncoupler = {L3}\n'
                    f"rocker = {l4}\n{extra}")
    result = CliRunner().invoke(main, ["analyze", str(path), "-o", str(tmp_path / "out"), *args])
    assert result.exit_code == 0, result.output
    return json.loads(result.output) if "--json" in args else {"text": result.output}


def arc(start: float, end: float) -> float:
    """The counter-clockwise arc (degrees) from ``start`` to ``end``."""
    return (end - start) % 360.0


def limits_of(entry: dict) -> list[tuple[float, float]]:
    return sorted((x["crank_deg"], x["rocker_deg"]) for x in entry["limits"])


def test_rocker_88_triple_rocker_sweeps_both_links_through_the_ground_line(tmp_path):
    """S + L = 75 + 125 > 100 + 88: non-Grashof, one circuit holding both assemblies. The crank stops at
    +-92.16 degrees (|A O4| = 163, extended) and swings 184.33 degrees through 0; crank and coupler fold
    (|O2 B| = 50) at crank +-61.60 with the rocker at 180 -+ 29.99: the rocker can point along 0 (B 188 from O2)
    but not along 180 (12 < 50), so it swings 300.03 degrees through 0. Before: no swing, one limit an assembly."""
    r = analyze(tmp_path, 88.0, "--json")
    (c,) = r["circuits"]
    toggle = cos_rule(L1, L2, L3 + 88)
    assert c["drawn"] and c["assemblies"] == ["open", "crossed"]
    assert c["input_range_deg"] == pytest.approx([-toggle, toggle], abs=1e-9)
    assert c["crank"]["swing_deg"] == pytest.approx(2 * toggle, abs=1e-9)
    assert c["crank"]["from_deg"] == pytest.approx(360 - toggle, abs=1e-9)
    assert c["crank"]["through_ground_line_deg"] == [0.0]
    assert [x["kind"] for x in c["crank"]["limits"]] == ["toggle-extended"] * 2
    at_o4 = cos_rule(L1, L3 + 88, L2)              # in O2-A-O4 with |A O4| = 163; B on A O4, so the rocker points at A
    assert limits_of(c["crank"]) == [pytest.approx((toggle, 180 - at_o4), abs=1e-9),
                                     pytest.approx((360 - toggle, 180 + at_o4), abs=1e-9)]
    psi, phi = cos_rule(L1, 88, L2 - L3), cos_rule(L1, L2 - L3, 88)
    assert limits_of(c["rocker"]) == [pytest.approx((phi, 180 - psi), abs=1e-9),
                                      pytest.approx((360 - phi, 180 + psi), abs=1e-9)]
    assert sorted(x["assembly"] for x in c["rocker"]["limits"]) == ["crossed", "open"]   # one on each
    assert reachable(88, 0) and not reachable(88, 180)
    assert c["rocker"]["swing_deg"] == pytest.approx(360 - 2 * psi, abs=1e-9)
    assert arc(c["rocker"]["from_deg"], c["rocker"]["to_deg"]) == pytest.approx(360 - 2 * psi, abs=1e-9)
    assert c["rocker"]["through_ground_line_deg"] == [0.0] and r["rocker_swing_deg"] == c["rocker"]["swing_deg"]
    words = "a rocker that oscillates through the ground line (at 0 degrees)"
    assert r["motion"] == {"crank": words, "coupler": "oscillates, never a full turn", "rocker": words}


def test_rocker_125_double_rocker_has_two_circuits_and_swings_on_the_drawn_one(tmp_path):
    """S + L = 75 + 125 < 100 + 125: Grashof with the coupler shortest, a double rocker; the crank reaches
    [22.33, 125.10] (folded |A O4| = 50 and extended 200) or its mirror image, two circuits. The drawn one is the
    first: the rocker, which can point along neither 0 (225 > 200) nor 180 (25 < 50), stays above the ground line
    there and swings between 180 - psi(200) = 54.90 and 180 - psi(50) = 157.67 degrees: 102.77, not the 147.43
    that the extended limit of one circuit and the folded limit of the other made before."""
    r = analyze(tmp_path, 125.0, "--json")
    lo, hi = cos_rule(L1, L2, 125 - L3), cos_rule(L1, L2, 125 + L3)
    first, second = r["circuits"]
    assert first["drawn"] and not second["drawn"]
    assert first["input_range_deg"] == pytest.approx([lo, hi], abs=1e-9)
    assert second["input_range_deg"] == pytest.approx([360 - hi, 360 - lo], abs=1e-9)
    assert first["crank"]["swing_deg"] == pytest.approx(hi - lo, abs=1e-9)
    assert [x["kind"] for x in first["crank"]["limits"]] == ["toggle-folded", "toggle-extended"]
    assert not reachable(125, 0) and not reachable(125, 180)
    up_ext, up_fold = 180 - cos_rule(L1, 125, L2 + L3), 180 - cos_rule(L1, 125, L2 - L3)
    rocker = first["rocker"]
    assert (rocker["from_deg"], rocker["to_deg"]) == (pytest.approx(up_ext, abs=1e-9), pytest.approx(up_fold, abs=1e-9))
    assert rocker["swing_deg"] == r["rocker_swing_deg"] == pytest.approx(up_fold - up_ext, abs=1e-9)
    assert r["rocker_swing_deg"] != pytest.approx(147.431, abs=0.01)
    assert [(x["kind"], x["assembly"]) for x in rocker["limits"]] == [("extended", "open"), ("folded", "crossed")]
    assert rocker["limits"][0]["crank_deg"] == pytest.approx(cos_rule(L1, L2 + L3, 125), abs=1e-9)
    assert rocker["limits"][1]["crank_deg"] == pytest.approx(cos_rule(L1, L2 - L3, 125), abs=1e-9)   # L2 > L3
    # the other circuit is this one's mirror image in the ground line
    mirror = sorted(((-c) % 360, (-x) % 360) for c, x in limits_of(rocker))
    assert limits_of(second["rocker"]) == [pytest.approx(m, abs=1e-9) for m in mirror]
    assert r["motion"] == {"crank": "a rocker that oscillates", "coupler": "turns fully",
                           "rocker": "a rocker that oscillates"}
    assert any("split into 2 separate circuits" in w and "never passes from one to the other" in w
               for w in r["warnings"])


def test_rocker_163_triple_rocker_sweeps_through_180(tmp_path):
    """S + L = 75 + 163 > 100 + 125: non-Grashof; the crank reaches [44.34, 315.66] (folded |A O4| = 88),
    271.33 degrees through 180. Crank and coupler only extend (|O2 B| = 200; 50 + 100 < 163 cannot fold): the
    rocker stops at 180 -+ 96.04; it can point along 180 (63 from O2) but not 0 (263 > 200): 192.08 degrees."""
    r = analyze(tmp_path, 163.0, "--json")
    (c,) = r["circuits"]
    lo = cos_rule(L1, L2, 163 - L3)
    assert c["crank"]["swing_deg"] == pytest.approx(360 - 2 * lo, abs=1e-9)
    assert c["crank"]["through_ground_line_deg"] == [180.0]
    psi, phi = cos_rule(L1, 163, L2 + L3), cos_rule(L1, L2 + L3, 163)
    assert limits_of(c["rocker"]) == [pytest.approx((phi, 180 - psi), abs=1e-9),
                                      pytest.approx((360 - phi, 180 + psi), abs=1e-9)]
    assert reachable(163, 180) and not reachable(163, 0)
    assert c["rocker"]["swing_deg"] == pytest.approx(2 * psi, abs=1e-9)
    assert (c["rocker"]["from_deg"], c["rocker"]["to_deg"]) == (pytest.approx(180 - psi, abs=1e-9),
                                                                pytest.approx(180 + psi, abs=1e-9))
    words = "a rocker that oscillates through the ground line (at 180 degrees)"
    assert r["motion"]["crank"] == r["motion"]["rocker"] == words


@pytest.mark.parametrize("l4", [88.0, 125.0, 163.0])
def test_the_console_summary_says_each_links_motion_and_limits(tmp_path, l4):
    text = analyze(tmp_path, l4)["text"]
    assert "motion on the drawn circuit: crank: a rocker that oscillates" in text
    assert ("circuit 1 of 2 (drawn)" if l4 == 125 else "circuit 1 of 1 (drawn)") in text
    assert "counter-clockwise from" in text and "limits: toggle-" in text
    assert ("through the ground line" in text) == (l4 != 125)


@pytest.mark.parametrize("l4", [88.0, 125.0, 163.0])
def test_the_other_assembly_is_drawn_on_the_same_circuit_and_the_rocker_driven_view_agrees(tmp_path, l4):
    """A limited crank's circuit holds both assemblies: drawn crossed, the report is the same circuit's. Driven by
    the rocker the circuits are the same poses, seen from the rocker: the same limits and swings."""
    base = analyze(tmp_path / "a", l4, "--json")
    crossed = analyze(tmp_path / "b", l4, "--json", assembly="crossed")
    assert crossed["circuits"] == base["circuits"]
    driven = analyze(tmp_path / "c", l4, "--json", input="rocker")
    ours = next(c for c in base["circuits"] if c["drawn"])
    same = [c for c in driven["circuits"] if np.allclose(limits_of(c["rocker"]), limits_of(ours["rocker"]))]
    assert len(same) == 1
    for link in ("crank", "rocker"):
        assert same[0][link]["swing_deg"] == pytest.approx(ours[link]["swing_deg"], abs=1e-9)
        assert np.allclose(limits_of(same[0][link]), limits_of(ours[link]), atol=1e-9, rtol=0)


def test_a_crank_rockers_two_assemblies_are_two_circuits_mirrored(tmp_path):
    """The bundled crank-rocker (180, 80, 200, 150): each assembly a circuit, the crank turning fully, the rocker
    between the extended and folded limits (law of cosines, as tests/linkgen/test_fourbar.py has them), the crossed
    assembly the mirror image; the swing as it was reported before."""
    fb = FourBar(180, 80, 200, 150)
    found = circuits(fb)
    assert [c.assemblies for c in found] == [(1,), (-1,)]
    ext = cos_rule(180, 280, 150)
    fold = cos_rule(180, 120, 150) + 180
    open_, crossed = found
    assert open_.crank.turns and not open_.rocker.turns and open_.coupler == "oscillates"
    assert sorted(math.degrees(x.crank) % 360 for x in open_.rocker.limits) == pytest.approx([ext, fold], abs=1e-9)
    swing = cos_rule(180, 150, 280) - cos_rule(180, 150, 120)     # the angles at O4, extended and folded
    assert math.degrees(open_.rocker.arc) == math.degrees(crossed.rocker.arc) == pytest.approx(swing, abs=1e-9)
    assert math.degrees(crossed.rocker.start) == pytest.approx(-math.degrees(open_.rocker.end), abs=1e-9)


def _sampled(fb: FourBar, circuit, n: int = 6001) -> tuple[np.ndarray, np.ndarray]:
    """Crank and rocker angles once round a circuit from the closed form: a range up on one assembly and back on
    the other (they meet at its ends), or a full turn on the circuit's assembly."""
    if circuit.input_range is None:
        t = np.linspace(0.0, TWO_PI, n)
        p = fb.positions(t, "open" if circuit.assemblies[0] > 0 else "crossed")
        return t, p.theta4
    t = np.linspace(*circuit.input_range, n)
    return np.concatenate([t, t[::-1]]), np.concatenate([fb.positions(t, "open").theta4,
                                                         fb.positions(t[::-1], "crossed").theta4])


def _inside(angles: np.ndarray, swing) -> np.ndarray:
    return np.remainder(angles - swing.start + 1e-9, TWO_PI) <= swing.arc + 2e-9


def _random_linkages(n: int, seed: int = 30) -> list[FourBar]:
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        lengths = rng.uniform(10, 200, 4)
        if 2 * lengths.max() < lengths.sum() and abs(FourBar(*lengths).grashof.margin) > 1e-3:
            out.append(FourBar(*lengths))
    return out


@pytest.mark.parametrize("fb", _random_linkages(60), ids=lambda f: f.grashof.inversion)
def test_every_pose_of_a_circuit_lies_in_its_swings_and_the_swings_are_reached(fb):
    """Random Grashof and non-Grashof linkages: every sampled pose of each circuit has its crank and rocker inside
    the reported arcs, the sampled poses come to within a sampling step of both ends (so neither arc is too
    wide), a link reported turning winds once round the circuit, and the limits close the loop."""
    found = circuits(fb)
    assert len(found) == 2 or (fb.grashof.grashof_class == "II" and len(found) == 1)
    for circuit in found:
        crank, rocker = _sampled(fb, circuit)
        for angles, swing in ((crank, circuit.crank), (rocker, circuit.rocker)):
            steps = np.remainder(np.diff(angles) + math.pi, TWO_PI) - math.pi
            if swing.turns:
                assert abs(abs(steps.sum()) - TWO_PI) < 1e-6     # the loop ends at a toggle, to rounding
                continue
            assert _inside(angles, swing).all()
            off = np.remainder(angles - swing.start, TWO_PI)
            assert off.min() < 2e-3 and off.max() > swing.arc - 2e-3
            for limit in swing.limits:
                assert abs(math.hypot(fb.crank * math.cos(limit.crank) - fb.ground - fb.rocker * math.cos(limit.rocker),
                                      fb.crank * math.sin(limit.crank) - fb.rocker * math.sin(limit.rocker))
                           - fb.coupler) < 1e-9 * fb.longest


def test_at_change_points_the_circuit_is_the_branch_through_the_fold():
    """Grashof class III. The parallelogram (128, 10, 128, 10): on its parallelogram branch (open just after 0,
    crossed past 180) the rocker turns with the crank and the coupler translates; on the other, the
    anti-parallelogram, the rocker turns too. The general change point (100, 40, 90, 50) folds at 180 only, so
    its branch comes back after two turns holding both assemblies: crank and coupler extend (|O2 B| = 130) with
    the rocker at 180 -+ 116.10 (cos = (100^2 + 50^2 - 130^2) / (2 100 50) = -0.44); they fold only at the fold
    itself (50 + 50 = 100: all four links in line, B at (50, 0)), which the rocker passes at 180 degrees, so it
    swings 232.21 degrees through 180. The rhombus's second branch keeps B on O2: the rocker does not move."""
    parallelogram, anti = circuits(FourBar(128, 10, 128, 10))
    assert parallelogram.rocker.turns and parallelogram.coupler == "translates"
    assert anti.rocker.turns and anti.coupler == "oscillates"
    (branch,) = circuits(FourBar(100, 40, 90, 50))
    assert branch.turns == 2 and branch.assemblies == (1, -1) and branch.folds == (math.pi,)
    psi = math.acos(-0.44)
    assert [x.kind for x in branch.rocker.limits] == ["extended", "extended"]
    assert branch.rocker.start == pytest.approx(math.pi - psi, abs=1e-12)
    assert branch.rocker.arc == pytest.approx(2 * psi, abs=1e-12) and branch.rocker.through() == (math.pi,)
    kite_mode = circuits(FourBar(20, 20, 20, 20))[1]
    assert kite_mode.rocker.still and math.degrees(kite_mode.rocker.start) == pytest.approx(180, abs=1e-7)
    assert np.abs(FourBar(20, 20, 20, 20).positions(np.radians([30, 100, 170]), "crossed").b).max() < 1e-12
