"""Motion laws: textbook coefficients, end values, analytic vs numeric derivatives, the general polynomial."""
from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.polynomial import Polynomial

from camgen.core.errors import SpecError
from camgen.laws import BlendedUniform, DraftedUniform, Parabolic, from_conditions, make_law
from camgen.laws.table import law_table

PI = math.pi

ALL_LAWS = [
    make_law("uniform"), make_law("harmonic"), make_law("cycloidal"), make_law("polynomial-345"),
    make_law("polynomial-4567"), Parabolic(1.0), Parabolic(0.4), Parabolic(3.0),
    BlendedUniform(0.25, "cycloidal"), BlendedUniform(0.1, "parabolic"), BlendedUniform(0.5, "cycloidal"),
    DraftedUniform(math.sqrt(3)), DraftedUniform(2.5), DraftedUniform(12.0),
    from_conditions([(0, 0, 0), (0, 1, 0), (0, 2, 0), (0, 3, 0), (0.5, 0, 0.5), (1, 0, 1), (1, 1, 0), (1, 2, 0),
                     (1, 3, 0)]),
    make_law("modified-trapezoid"), make_law("modified-sine"), make_law("double-harmonic"),
    make_law("spline", points=[[0, 0], [0.3, 0.1], [0.5, 0.5], [0.7, 0.95], [1, 1]]),
]


def _table() -> dict[str, dict]:
    return {row["law"]: row for row in law_table()}


@pytest.mark.parametrize("name, cv, ca, cj", [
    ("cycloidal", 2.0, 2 * PI, 4 * PI**2),
    ("harmonic", PI / 2, PI**2 / 2, PI**3 / 2),
    ("polynomial-345", 1.875, 10 / math.sqrt(3), 60.0),
    ("polynomial-4567", 35 / 16, None, 52.5),
    ("parabolic", 2.0, 4.0, None),
    ("uniform", 1.0, None, None),
])
def test_law_table_textbook_values(name, cv, ca, cj):
    row = _table()[name]
    assert row["cv"] == pytest.approx(cv, rel=1e-12)
    if ca is not None:
        assert row["ca"] == pytest.approx(ca, rel=1e-12)
    if cj is not None:
        assert row["cj"] == pytest.approx(cj, rel=1e-12)


def test_law_table_4567_acceleration_matches_roots_of_jerk():
    """Independent check: the peak of |f''| is at a root of f''' (numpy's polynomial roots)."""
    f = Polynomial([0, 0, 0, 0, 35, -84, 70, -20])
    roots = f.deriv(3).roots()
    roots = roots[(abs(roots.imag) < 1e-12) & (roots.real > 0) & (roots.real < 1)].real
    assert _table()["polynomial-4567"]["ca"] == pytest.approx(max(abs(f.deriv(2)(roots))), rel=1e-12)


def test_law_table_infinite_flags():
    table = _table()
    assert table["uniform"]["infinite"] == ["a", "j"]
    assert table["parabolic"]["infinite"] == ["j"]
    assert table["harmonic"]["infinite"] == ["j"]
    for name in ("cycloidal", "polynomial-345", "polynomial-4567", "modified-uniform"):
        assert table[name]["infinite"] == [], name
    assert all(math.isfinite(row[k]) for row in table.values() for k in ("cv", "ca", "cj"))


@pytest.mark.parametrize("law", ALL_LAWS, ids=lambda law: repr(law)[:40])
def test_end_values(law):
    f = law.derivatives(np.array([0.0, 1.0]))
    assert f[0, 0] == pytest.approx(0.0, abs=1e-13)
    assert f[0, 1] == pytest.approx(1.0, abs=1e-13)


@pytest.mark.parametrize("law", ALL_LAWS, ids=lambda law: repr(law)[:40])
def test_analytic_derivatives_match_numeric(law):
    """Central differences of f, f', f'' inside each smooth piece match f', f'', f'''."""
    h = 1e-6
    for a, b in law.smooth_intervals():
        u = np.linspace(a, b, 41)[1:-1]
        if len(u) == 0 or b - a < 4 * h:
            continue
        d = law.derivatives(u)
        numeric = (law.derivatives(u + h) - law.derivatives(u - h)) / (2 * h)
        for k in range(3):
            scale = max(1.0, float(np.abs(d[k + 1]).max()))
            assert np.abs(numeric[k] - d[k + 1]).max() < 1e-6 * scale * max(1.0, float(np.abs(d).max())), k


@pytest.mark.parametrize("law", ALL_LAWS, ids=lambda law: repr(law)[:40])
def test_displacement_and_velocity_are_continuous(law):
    """f and f' never jump inside any law but uniform's ends (velocity jumps only against dwells)."""
    for u, order, _ in law.jumps():
        assert order >= 1
        if 0 < u < 1:
            assert order >= 2, f"velocity jumps inside {law} at u={u}"


def test_parabolic_acceleration_ratio():
    law = Parabolic(2.5)
    u1 = law.breakpoints[0]
    a1, a2 = law.derivatives(np.array([u1 / 2]))[2, 0], -law.derivatives(np.array([(1 + u1) / 2]))[2, 0]
    assert a1 / a2 == pytest.approx(2.5, rel=1e-13)
    assert law.peaks()[0] == pytest.approx(2.0, rel=1e-12)


def test_blended_uniform_cruise_velocity():
    for b in (0.1, 0.25, 0.5):
        for kind in ("cycloidal", "parabolic"):
            law = BlendedUniform(b, kind)
            assert law.derivatives(np.array([0.5]))[1, 0] == pytest.approx(1 / (1 - b), rel=1e-13)
    assert BlendedUniform(0.25, "parabolic").infinite() == ["j"]
    assert BlendedUniform(0.25, "cycloidal").infinite() == []


@pytest.mark.parametrize("k", [math.sqrt(3), 2.0, 4.0, 20.0])
def test_drafted_uniform_arcs_have_radius_of_the_lift(k):
    """In the drafting diagram (x = k u, y = f, units of the lift) the ends are arcs of radius 1."""
    law = DraftedUniform(k)
    u = np.linspace(0, law.u1, 50)
    f = law.derivatives(u)
    x, y = k * u, f[0]
    assert np.allclose(x**2 + (y - 1) ** 2, 1.0, atol=1e-12)          # circle about (0, 1)
    xe, ye = k * (1 - u), law.derivatives(1 - u)[0]
    assert np.allclose(xe**2 + ye**2 - 2 * xe * k + k * k, 1.0, atol=1e-12)  # circle about (k, 0)
    left, right = law.derivatives(np.array([np.nextafter(law.u1, 0), law.u1])).T
    assert left[1] == pytest.approx(right[1], rel=1e-12)           # tangent line
    assert law.infinite() == ["j"]


def test_drafted_uniform_needs_room():
    with pytest.raises(SpecError, match="sqrt"):
        DraftedUniform(1.7)


def test_general_polynomial_reproduces_345_and_4567():
    c345 = [(0, 0, 0), (0, 1, 0), (0, 2, 0), (1, 0, 1), (1, 1, 0), (1, 2, 0)]
    c4567 = [*c345, (0, 3, 0), (1, 3, 0)]
    u = np.linspace(0, 1, 501)
    for conds, name in ((c345, "polynomial-345"), (c4567, "polynomial-4567")):
        general, fixed = from_conditions(conds).derivatives(u), make_law(name).derivatives(u)
        assert np.abs(general - fixed).max() < 1e-11 * np.abs(fixed).max()


@pytest.mark.parametrize("m", [7, 9, 12])
def test_general_polynomial_high_degree(m):
    """Degree 2m+1 with m derivatives zero at both ends equals the regularised incomplete beta I_u(m+1, m+1)."""
    conds = [(0, k, 0) for k in range(m + 1)] + [(1, 0, 1)] + [(1, k, 0) for k in range(1, m + 1)]
    law = from_conditions(conds)
    assert law.degree == 2 * m + 1
    u = np.linspace(0, 1, 2001)
    exact = u ** (m + 1) * sum(math.comb(m + k, k) * (1 - u) ** k for k in range(m + 1))
    assert np.abs(law.derivatives(u)[0] - exact).max() < 1e-12


def test_general_polynomial_interior_condition():
    law = from_conditions([(0, 0, 0), (0, 1, 0), (0.25, 0, 0.1), (1, 0, 1), (1, 1, 0)])
    assert law.derivatives(np.array([0.25]))[0, 0] == pytest.approx(0.1, abs=1e-14)
    assert law.degree == 4


@pytest.mark.parametrize("conds, words", [
    ([(0, 0, 0), (1, 0, 1), (0, 0, 0.5)], "contradict"),
    ([(0, 0, 0), (1, 0, 1), (1, 0, 1)], "independent conditions"),
    ([(0, 1, 0), (1, 1, 0), (0.5, 0, 0.3)], "f\\(0\\) = 0"),
    ([(0, 0, 0), (1.5, 0, 1)], "u must be in"),
    ([(0, 0, 0), (1, 0, float("nan"))], "finite"),
])
def test_general_polynomial_bad_conditions(conds, words):
    with pytest.raises(SpecError, match=words) as err:
        from_conditions(conds)
    assert str(err.value).startswith("conditions:")


@pytest.mark.parametrize("name, cv, ca, cj", [
    ("modified-trapezoid", 2.000, 4.888, 61.43),       # Norton, Design of Machinery, Table 8-3
    ("modified-sine", 1.760, 5.528, 69.47),
])
def test_published_coefficients_of_the_acceleration_laws(name, cv, ca, cj):
    row = _table()[name]
    assert row["cv"] == pytest.approx(cv, abs=6e-4)
    assert row["ca"] == pytest.approx(ca, abs=6e-4)
    assert row["cj"] == pytest.approx(cj, abs=6e-3)
    assert row["infinite"] == []


def test_modified_trapezoid_closed_form_peaks():
    """Its acceleration peak A follows from Cv = A (1/4 + 1/(2 pi)) = 2; its jerk peak is 4 pi A."""
    a = 2 / (0.25 + 1 / (2 * PI))
    law = make_law("modified-trapezoid")
    assert law.peaks()[1] == pytest.approx(a, rel=1e-12)
    assert law.peaks()[2] == pytest.approx(4 * PI * a, rel=1e-12)
    assert law.derivatives(np.array([0.5]))[1, 0] == pytest.approx(2.0, rel=1e-12)


def test_double_harmonic_has_no_acceleration_at_its_start_and_pi_squared_at_its_end():
    f = make_law("double-harmonic").derivatives(np.array([0.0, 1.0]))
    assert f[2] == pytest.approx([0.0, -PI**2], abs=1e-12)
    assert make_law("double-harmonic").infinite() == ["j"]


def test_spline_through_two_points_is_the_345_polynomial():
    """A quintic with zero velocity and acceleration at both ends through (0, 0) and (1, 1) is 3-4-5."""
    u = np.linspace(0, 1, 101)
    spline = make_law("spline", points=[[0, 0], [1, 1]]).derivatives(u)
    assert np.abs(spline - make_law("polynomial-345").derivatives(u)).max() < 1e-9


def test_spline_passes_through_its_points_smoothly_and_reports_overshoot():
    pts = [[0, 0], [0.3, 0.1], [0.5, 0.5], [0.7, 0.95], [1, 1]]
    law = make_law("spline", points=pts)
    assert law.derivatives(np.array([p[0] for p in pts]))[0] == pytest.approx([p[1] for p in pts], abs=1e-12)
    assert law.infinite() == []                         # zero velocity and acceleration at both ends
    assert law.overshoot() > 0.0                        # steep then flat: it bulges above the lift near the end
    assert make_law("spline", points=[[0, 0], [0.5, 0.5], [1, 1]]).overshoot() == 0.0
    free = make_law("spline", points=pts, ends="natural")
    assert abs(free.derivatives(np.array([0.0]))[1, 0]) > 0.1   # natural ends leave the velocity free


@pytest.mark.parametrize("points, words", [
    ([[0, 0]], "at least two"),
    ([[0, 0], [0.5, 0.2], [0.5, 0.6], [1, 1]], "increase strictly"),
    ([[0, 0], [1, 0.9]], "end at \\[1, 1\\]"),
])
def test_spline_bad_points(points, words):
    with pytest.raises(SpecError, match=words):
        make_law("spline", points=points)
