"""Four-bar rates at and near change points (Grashof class III: the linkage folds flat and its two assemblies
cross), against a 50-digit mpmath reference and against exact values.

The reference is independent of the code's: the pose from the triangle A-B-O4 in 50 digits (its loop
closure checked to 45), then the textbook implicit differentiation of the loop closure
(omega3 = L2 sin(t4 - t2) / (L3 sin(t3 - t4)), ...), whose 0/0 at the fold 50 digits resolve. Measured
worst error over every pose below: 5e-14 relative (|error| / (1 + |value|)); asserted: 1e-11.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from camgen.core.errors import SpecError
from linkgen.kinematics.fourbar import FourBar

OFFSETS = (1e-12, 1e-10, 1e-8, 1e-6, 1e-4)
TOL = 1e-11
PARALLELOGRAM = FourBar(128, 10, 128, 10)
KITE = FourBar(114, 114, 178, 178)             # ground = crank, coupler = rocker: folds with A on O4
LINKAGES = {
    "parallelogram": PARALLELOGRAM,             # its crossed branch is the anti-parallelogram
    "kite": KITE,
    "kite-crank-coupler": FourBar(178, 114, 114, 178),   # ground = rocker, crank = coupler: folds at 0 and 180
    "kite-crank-rocker": FourBar(114, 178, 178, 114),
    "general": FourBar(100, 40, 90, 50),         # S + L = P + Q, neither: folds at 180 only
}


def _random_class_three(n: int, seed: int = 19) -> list[FourBar]:
    """Integer lengths with S + L = P + Q in a random loop order (every one folds at 0, 180 or both)."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        s, p, q = sorted(int(x) for x in rng.integers(5, 200, 3))
        try:
            out.append(FourBar(*(float(x) for x in rng.permutation([s, p, q, p + q - s]))))
        except SpecError:                         # flat: the longest as long as the other three
            continue
    return out


def reference(fb: FourBar, theta2: float, label: int, fold: float | None = None) -> tuple[float, ...]:
    """(omega3, omega4, alpha3, alpha4) per unit crank speed on the branch whose B lies on side ``label`` of
    A -> O4 at crank angle ``theta2`` (the double, exactly), or just beyond the change point ``fold``
    (1e-30 rad past it, in 120 digits, so that the 0/0 still leaves 30 digits)."""
    with mpmath.workdps(50 if fold is None else 120):
        l1, l2, l3, l4 = (mpmath.mpf(x) for x in (fb.ground, fb.crank, fb.coupler, fb.rocker))
        t = mpmath.mpf(theta2) if fold is None else (mpmath.pi if fold else 0) + mpmath.mpf("1e-30")
        ax, ay = l2 * mpmath.cos(t), l2 * mpmath.sin(t)
        z2 = (l1 - ax) ** 2 + ay**2
        area = mpmath.sqrt(max(0, ((l3 + l4) ** 2 - z2) * (z2 - (l3 - l4) ** 2)))
        t3 = mpmath.atan2(-ay, l1 - ax) + mpmath.atan2(label * area, l3**2 - l4**2 + z2)
        bx, by = ax + l3 * mpmath.cos(t3), ay + l3 * mpmath.sin(t3)
        t4 = mpmath.atan2(by, bx - l1)
        assert abs(mpmath.hypot(bx - l1, by) - l4) < mpmath.mpf("1e-45") * l4          # the loop closes
        det = l3 * l4 * mpmath.sin(t3 - t4)
        w3 = l2 * l4 * mpmath.sin(t4 - t) / det
        w4 = l2 * l3 * mpmath.sin(t3 - t) / det
        r1 = l2 * mpmath.cos(t) + l3 * mpmath.cos(t3) * w3**2 - l4 * mpmath.cos(t4) * w4**2
        r2 = l2 * mpmath.sin(t) + l3 * mpmath.sin(t3) * w3**2 - l4 * mpmath.sin(t4) * w4**2
        a3 = -l4 * (mpmath.cos(t4) * r1 + mpmath.sin(t4) * r2) / det
        a4 = -l3 * (mpmath.sin(t3) * r2 + mpmath.cos(t3) * r1) / det
        return tuple(float(v) for v in (w3, w4, a3, a4))


def computed(fb: FourBar, theta2: float, assembly: str) -> np.ndarray:
    pose = fb.positions([theta2], assembly)
    return np.array([x[0] for x in fb.velocities(pose, 1.0) + fb.accelerations(pose, 1.0)])


def _poses_near_folds(fb: FourBar):
    for fold in fb.change_points():
        for offset in OFFSETS:
            for theta2 in (fold + offset, fold - offset):
                if math.hypot(*fb._z(np.array(theta2))) <= 1e-10 * fb.longest:
                    continue                      # the kite's crank pin on the rocker pivot: refused
                for label, assembly in ((1, "open"), (-1, "crossed")):
                    yield theta2, label, assembly


@pytest.mark.parametrize("fb", list(LINKAGES.values()) + _random_class_three(12),
                         ids=list(LINKAGES) + [f"random-{i}" for i in range(12)])
def test_rates_near_a_change_point_match_50_digits(fb):
    assert fb.grashof.grashof_class == "III" and fb.change_points()
    worst = 0.0
    for theta2, label, assembly in _poses_near_folds(fb):
        got, ref = computed(fb, theta2, assembly), np.array(reference(fb, theta2, label))
        assert np.isfinite(got).all()
        worst = max(worst, float((np.abs(got - ref) / (1 + np.abs(ref))).max()))
    assert worst < TOL


@pytest.mark.parametrize("fb", list(LINKAGES.values()) + _random_class_three(6, seed=7),
                         ids=list(LINKAGES) + [f"random-{i}" for i in range(6)])
def test_rates_at_a_change_point_are_the_branch_limit(fb):
    """At the fold itself the label names the branch beyond it (as FourBar.sweep counts it)."""
    for fold in fb.change_points():
        if math.hypot(*fb._z(np.array(fold))) <= 1e-10 * fb.longest:
            with pytest.raises(SpecError, match=r"angle: .*undetermined"):
                fb.positions([fold])
            continue
        for label, assembly in ((1, "open"), (-1, "crossed")):
            got, ref = computed(fb, fold, assembly), np.array(reference(fb, fold, label, fold=fold))
            assert np.abs(got - ref).max() < TOL * (1 + np.abs(ref).max())


def test_poses_near_a_change_point_are_exact():
    """The positions too: near a fold z has lost half the digits the triangle's area needs (1e-9 rad off at
    1e-8 rad from the parallelogram's fold before); now 1e-15."""
    for fb in list(LINKAGES.values()) + _random_class_three(6):
        for theta2, label, assembly in _poses_near_folds(fb):
            pose = fb.positions([theta2], assembly)
            with mpmath.workdps(50):
                l1, l2, l3, l4 = (mpmath.mpf(x) for x in (fb.ground, fb.crank, fb.coupler, fb.rocker))
                t = mpmath.mpf(theta2)
                ax, ay = l2 * mpmath.cos(t), l2 * mpmath.sin(t)
                z2 = (l1 - ax) ** 2 + ay**2
                area = mpmath.sqrt(((l3 + l4) ** 2 - z2) * (z2 - (l3 - l4) ** 2))
                t3 = float(mpmath.atan2(-ay, l1 - ax) + mpmath.atan2(label * area, l3**2 - l4**2 + z2))
            assert abs(math.remainder(pose.theta3[0] - t3, 2 * math.pi)) < 1e-14


@pytest.mark.parametrize("theta2", [1e-12, 1e-8, 1e-5, 0.3, math.pi - 1e-9, math.pi, math.pi + 1e-7])
def test_parallelogram_turns_its_rocker_with_the_crank(theta2):
    """Along the parallelogram branch the coupler translates: omega4 = omega2, omega3 = 0, no accelerations
    (the issue: 5e16 at 1e-8 rad, alpha4 = -0.28 at 1e-5). Which label is the parallelogram swaps at each fold."""
    assembly = "open" if 0 <= theta2 < math.pi else "crossed"
    w3, w4, a3, a4 = computed(PARALLELOGRAM, theta2, assembly)
    assert abs(w4 - 1) < 1e-15 and abs(w3) < 1e-15 and abs(a3) < 1e-15 and abs(a4) < 1e-15
    assert PARALLELOGRAM.mechanical_advantage(PARALLELOGRAM.positions([theta2], assembly))[0] == pytest.approx(1)


def test_parallelogram_swept_through_its_fold_keeps_its_rates():
    """FourBar.sweep through theta2 = 0 (the issue: omega4 = 0 and alpha4 = -inf there)."""
    t = np.concatenate([-np.array(OFFSETS), [0.0], OFFSETS])
    t.sort()
    pose = PARALLELOGRAM.sweep(t, "crossed")     # below 0 the parallelogram is the crossed label
    w3, w4 = PARALLELOGRAM.velocities(pose, 2.0)
    a3, a4 = PARALLELOGRAM.accelerations(pose, 2.0, 0.5)
    assert np.abs(w4 - 2.0).max() < 1e-14 and np.abs(w3).max() < 1e-14
    assert np.abs(a4 - 0.5).max() < 1e-14 and np.abs(a3).max() < 1e-14
    # round about, through 180, 360 (which rounds onto a fold) and 540 degrees
    t = np.concatenate([np.linspace(0.1, 10.0, 991), [math.pi, 2 * math.pi, 3 * math.pi]])
    t.sort()
    w3, w4 = PARALLELOGRAM.velocities(PARALLELOGRAM.sweep(t, "open"), 1.0)
    assert np.abs(w4 - 1).max() < 1e-14 and np.abs(w3).max() < 1e-14


def test_kite_coupler_rate_as_the_crank_pin_nears_the_rocker_pivot():
    """Kite ground = crank = a, coupler = rocker = b: B lies on the bisector of A O4, B = rho e^(i t/2) with
    rho -> a + b or a - b, so omega3 -> (rho / 2 - a) / (rho - a) = (b - a) / 2b = 16/89 or (a + b) / 2b = 73/89
    (the issue: -0.140 at 1e-8 rad)."""
    for theta2 in (1e-8, -1e-8, 1e-7):
        rates = {a: computed(KITE, theta2, a)[0] for a in ("open", "crossed")}
        assert sorted(rates.values()) == [pytest.approx(16 / 89, abs=1e-7), pytest.approx(73 / 89, abs=1e-7)]
    assert computed(KITE, 1e-8, "open")[0] == pytest.approx(16 / 89, abs=1e-9)


@pytest.mark.parametrize("fb", [FourBar(100, 70, 60, 80), FourBar(100, 60, 40, 90), FourBar(100, 80, 50, 60)],
                         ids=["triple-rocker", "double-rocker", "triple-rocker-2"])
def test_a_real_toggle_stays_unbounded(fb):
    """Where the crank input stops (coupler and rocker in line, not a change point) the rates are unbounded:
    +-inf with the sign of the limit from inside the reach, never a finite number and never NaN."""
    for lo, hi in fb.input_ranges():
        for end, inside in ((lo, lo + 1e-7), (hi, hi - 1e-7)):
            for assembly in ("open", "crossed"):
                pose = fb.positions([end, inside], assembly)
                for rate in fb.rates(pose):
                    assert np.isinf(rate[0]) and np.sign(rate[0]) == np.sign(rate[1])
                w3, w4 = fb.velocities(pose, 0.0)
                a3, a4 = fb.accelerations(pose, 0.0, 1.0)
                assert not np.isnan(np.concatenate([w3, w4, a3, a4])).any()
                assert fb.mechanical_advantage(pose)[0] == 0.0
