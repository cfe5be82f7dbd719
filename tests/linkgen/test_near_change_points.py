"""The four-bar type near a change point (issue 30, item 3, checked for ``type = "four-bar"``): lengths within 1e-6
to 1e-12 of the longest link of S + L = P + Q, on both sides (Grashof and not), every pose the report and the
drawings give lies on the drawing's branch, against a circle intersection worked here in 40 digits, and no change
point is reported that the lengths do not have.

The branch: lengths within :data:`CHANGE_POINT_TOL` of a change point are one (Grashof class III, by the project's
rule), and the drawing's branch passes through its fold, its label swapping there as :meth:`FourBar.sweep` says;
farther off they are solved as given, on one label throughout (the assemblies pass each other without touching,
or the crank stops short of the gap at a toggle).
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from camgen.core.errors import SpecError
from linkgen.kinematics.fourbar import FourBar
from linkgen.kinematics.grashof import CHANGE_POINT_TOL
from linkgen.mechanisms.fourbar import FourBarTable, fourbar_report, input_span

OFFSETS = (1e-6, 1e-8, 1e-9, 1e-11, 1e-12)


def circle_b(fb: FourBar, theta2: float, label: int) -> tuple[float, float, bool]:
    """B at crank angle ``theta2`` (the double, exactly) on side ``label`` of A -> O4: the intersection of the
    circles of radius L3 about A and L4 about O4, in 40 digits; and whether they meet (in the gap they do not,
    and the foot of the chord, on A O4, is given)."""
    with mpmath.workdps(40):
        l1, l2, l3, l4 = (mpmath.mpf(x) for x in (fb.ground, fb.crank, fb.coupler, fb.rocker))
        t = mpmath.mpf(theta2)
        ax, ay = l2 * mpmath.cos(t), l2 * mpmath.sin(t)
        dx, dy = l1 - ax, -ay
        z2 = dx * dx + dy * dy
        along = (l3 * l3 - l4 * l4 + z2) / (2 * z2)          # the chord's foot: A + along D
        h2 = l3 * l3 / z2 - along * along                      # (half the chord / z)^2
        h = mpmath.sqrt(h2) if h2 > 0 else mpmath.mpf(0)
        return float(ax + along * dx - label * h * dy), float(ay + along * dy + label * h * dx), h2 >= 0


def near_change_points(seed: int = 31, n: int = 36) -> list[tuple[FourBar, float]]:
    """Random four-bars with integer lengths at a change point (random loop order), one length moved by
    +-offset times the longest link: (the linkage, its signed offset)."""
    rng = np.random.default_rng(seed)
    out: list[tuple[FourBar, float]] = []
    while len(out) < n:
        s, p, q = sorted(int(x) for x in rng.integers(5, 200, 3))
        lengths = [float(x) for x in rng.permutation([s, p, q, p + q - s])]
        offset = float(OFFSETS[len(out) % len(OFFSETS)] * (1 if len(out) % 2 else -1))
        lengths[int(rng.integers(4))] += offset * max(lengths)
        try:
            fb = FourBar(*lengths)
        except SpecError:                               # flat, or A on O4 at the fold: refused, not this test's
            continue
        if any(math.hypot(*fb._z(np.array(c))) <= 1e-10 * fb.longest for c in (0.0, math.pi)):
            continue                                    # a deltoid's crank pin on its pivot: undetermined there
        out.append((fb, offset))
    return out


CASES = near_change_points()


def expected_labels(fb: FourBar, theta2: np.ndarray, sign: int) -> np.ndarray:
    """The drawing's branch's label at each crank angle of a sweep from the first: swapped at each change point
    crossed (at 0 or pi modulo 2 pi), an angle that rounds onto one counted just past it, as FourBar.sweep says:
    the half turn an angle lies in is floor(theta2 / pi), and fold k pi lies at the start of half turns k + 2 j."""
    half = np.floor(theta2 / math.pi)
    flips = np.zeros(theta2.size, dtype=int)
    for fold in fb.change_points():
        passed = np.floor((half - round(fold / math.pi)) / 2)          # such folds at or below each angle
        flips += (passed - passed[0]).astype(int)
    return sign * np.where(flips % 2 == 0, 1, -1)


@pytest.mark.parametrize("fb, offset", CASES, ids=[f"{o:+.0e}-{f.grashof.grashof_class}" for f, o in CASES])
def test_every_drawn_pose_near_a_change_point_is_on_the_drawings_branch(fb, offset):
    near = abs(fb.grashof.margin) <= CHANGE_POINT_TOL * fb.longest
    assert bool(fb.change_points()) == near                     # none that the lengths do not have
    ends = [x for r in fb.input_ranges() or () for x in r]
    lo, hi = input_span(fb)
    theta2 = np.linspace(lo, hi, 361)
    for assembly, sign in (("open", 1), ("crossed", -1)):
        poses = fb.sweep(theta2, assembly)                      # what the drawings and the parts' layout show
        labels = expected_labels(fb, theta2, sign)
        assert (poses.assembly == labels).all()
        for k, t in enumerate(theta2):
            if any(abs(t - e) < 1e-6 for e in ends):
                continue                                        # at a toggle B moves as sqrt of the angle
            bx, by, meets = circle_b(fb, float(t), int(labels[k]))
            assert meets or near                                # the gap is crossed only at a change point
            error = math.hypot(bx - poses.b[k, 0], by - poses.b[k, 1])
            assert error < 1e-7 * fb.longest, (t, error)
            other = circle_b(fb, float(t), -int(labels[k]))
            apart = math.hypot(other[0] - bx, other[1] - by)
            assert apart < 1e-6 * fb.longest or math.hypot(other[0] - poses.b[k, 0],
                                                            other[1] - poses.b[k, 1]) > 0.5 * apart


@pytest.mark.parametrize("fb, offset", CASES[:10], ids=[f"{o:+.0e}" for _, o in CASES[:10]])
def test_the_reports_positions_and_change_points_near_a_change_point(fb, offset):
    """The report's positions at an angle a third into the reach, for both assemblies as named; its change
    points only at lengths the project counts as one."""
    lo, hi = input_span(fb)
    angle = math.degrees(lo + (hi - lo) / 3)
    table = FourBarTable(type="four-bar", ground=fb.ground, crank=fb.crank, coupler=fb.coupler, rocker=fb.rocker)
    report = fourbar_report(table, fb, angle, "closed")
    near = abs(fb.grashof.margin) <= CHANGE_POINT_TOL * fb.longest
    assert bool(report["change_points_crank_deg"]) == near
    assert (report["grashof_class"] == "III") == near
    for assembly, sign in (("open", 1), ("crossed", -1)):
        bx, by, _ = circle_b(fb, math.radians(angle), sign)
        assert report["positions"][assembly]["rocker_pin_mm"] == pytest.approx([bx, by], abs=1e-7 * fb.longest)
