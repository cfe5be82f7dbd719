"""The effort that holds a linkage's loads (``[[loads]]``): virtual work against a free-body solution and against
finite differences of the positions, its refined extremes, the mechanical advantage, and bad loads refused."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from linkgen.cli import main as linkgen
from linkgen.linkage_design import design_linkage
from linkgen.kinematics.fourbar import FourBar
from linkgen.spec import validate_spec

FOURBAR = {"name": "fb", "linkage": {"type": "four-bar", "ground": 100.0, "crank": 30.0, "coupler": 90.0,
                                     "rocker": 70.0, "point_distance": 40.0, "point_angle": 30.0}}
FORCE = (12.0, -50.0)           # N at the coupler point P
TORQUE = 2.0                    # N*m counter-clockwise on the rocker


def _design(loads: list[dict], raw: dict = FOURBAR) -> object:
    return design_linkage(validate_spec({**raw, "loads": loads}))


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def free_body_torque(theta: np.ndarray) -> np.ndarray:
    """The crank torque (N*m) holding FORCE at P and TORQUE on the rocker, from each link's static equilibrium with
    the dedicated closed-form poses: unknowns R_A (crank on coupler), R_B (coupler on rocker) and T, five equations
    (the coupler's forces and moment, the rocker's and the crank's moments about their pivots)."""
    fb = FourBar(100.0, 30.0, 90.0, 70.0, point_distance=40.0, point_angle=math.radians(30.0))
    p = fb.positions(theta, "open")
    o2, o4 = np.zeros(2), np.array([100.0, 0.0])
    out = []
    for a, b, pt in zip(p.a, p.b, p.point, strict=True):
        f = np.array(FORCE)
        rows = np.zeros((5, 5))
        rhs = np.zeros(5)
        # unknowns: RAx RAy RBx RBy T (N, N*mm)
        rows[0, [0, 2]] = 1.0, -1.0                     # coupler, x: R_A - R_B + F = 0
        rows[1, [1, 3]] = 1.0, -1.0
        rhs[0:2] = -f
        ab, ap = b - a, pt - a                            # coupler moment about A: AB x (-R_B) + AP x F = 0
        rows[2, 2:4] = ab[1], -ab[0]
        rhs[2] = -(ap[0] * f[1] - ap[1] * f[0])
        ob = b - o4                                       # rocker moment about O4: O4B x R_B + M = 0
        rows[3, 2:4] = -ob[1], ob[0]
        rhs[3] = -1000.0 * TORQUE
        oa = a - o2                                       # crank moment about O2: O2A x (-R_A) + T = 0
        rows[4, 0:2] = oa[1], -oa[0]
        rows[4, 4] = 1.0
        out.append(np.linalg.solve(rows, rhs)[4] / 1000.0)
    return np.array(out)


LOADS = [{"point": "P", "force": list(FORCE)}, {"link": "rocker", "torque": TORQUE}]


def test_virtual_work_equals_the_free_body_solution():
    st = _design(LOADS).statics
    theta = st.inputs[::4]
    want = free_body_torque(theta)
    got = st.effort_at(theta)
    assert np.all(np.abs(got - want) <= 1e-9 * np.max(np.abs(want)))
    assert np.ptp(want) > 1.0                             # a real, varying torque


def test_effort_is_minus_the_derivative_of_the_loads_potential():
    """T = -dV/dtheta with V = -F . r_P - M phi_rocker: central differences of the closed-form positions."""
    fb = FourBar(100.0, 30.0, 90.0, 70.0, point_distance=40.0, point_angle=math.radians(30.0))
    st = _design(LOADS).statics
    theta, h = np.linspace(0.1, 6.2, 37), 1e-4

    def potential(t: np.ndarray) -> np.ndarray:
        p = fb.positions(t, "open")
        rocker = np.arctan2(p.b[:, 1], p.b[:, 0] - 100.0)
        return -(p.point @ np.array(FORCE)) - 1000.0 * TORQUE * np.unwrap(rocker)

    grad = (-potential(theta + 2 * h) + 8 * potential(theta + h) - 8 * potential(theta - h)
            + potential(theta - 2 * h)) / (12 * h)
    assert np.max(np.abs(st.effort_at(theta) - grad / 1000.0)) < 1e-8


def test_a_constant_load_does_no_work_over_a_turn():
    st = _design(LOADS).statics
    x = np.linspace(0.0, 2 * math.pi, 20001)
    e = st.effort_at(x)
    assert abs(np.trapezoid(e, x)) < 1e-6 * np.max(np.abs(e))


def test_extremes_are_refined_and_reported():
    design = _design(LOADS)
    r, st = design.report["statics"], design.statics
    dense = np.linspace(0.0, 2 * math.pi, 200001)
    e = st.effort_at(dense)
    assert r["max_N_m"] >= e.max() - 1e-12 and r["max_N_m"] - e.max() < 1e-9
    assert r["min_N_m"] <= e.min() + 1e-12 and e.min() - r["min_N_m"] < 1e-9
    assert abs(r["max_at_input_deg"] - math.degrees(dense[np.argmax(e)])) < 0.01
    assert r["rms_N_m"] == pytest.approx(math.sqrt(np.trapezoid(e ** 2, dense) / (2 * math.pi)), rel=1e-4)
    assert r["peak_power_W"] == pytest.approx(max(abs(r["max_N_m"]), abs(r["min_N_m"])) * 2 * math.pi, rel=1e-12)


def test_mechanical_advantage_of_one_force():
    """One force F at B: MA = |F| * crank / |T| with T = F . dB/dtheta (central differences of the closed form)."""
    design = _design([{"point": "B", "force": [0.0, 10.0]}])
    st, r = design.statics, design.report["statics"]
    fb = FourBar(100.0, 30.0, 90.0, 70.0)
    x, h = np.linspace(0.05, 6.2, 41), 1e-5
    db = (fb.positions(x + h, "open").b - fb.positions(x - h, "open").b) / (2 * h)
    want = 10.0 * 30.0 / np.abs(db @ np.array([0.0, 10.0]))
    assert np.max(np.abs(st.advantage(st.effort_at(x)) / want - 1)) < 1e-7
    dense = np.linspace(0.0, 2 * math.pi, 100001)
    ma = st.advantage(st.effort_at(dense))
    assert r["lever_mm"] == 30.0
    assert r["mechanical_advantage_min"] == pytest.approx(np.min(ma), rel=1e-6)
    assert r["mechanical_advantage_min"] <= np.min(ma) + 1e-12


def test_a_slider_force_on_a_slider_crank():
    """A force -F along the slide on a slider-crank: T = F * dx/dtheta (x the slider's travel)."""
    raw = {"name": "sc", "linkage": {"type": "slider-crank", "crank": 25.0, "rod": 80.0}}
    st = _design([{"point": "B", "force": [-100.0, 0.0]}], raw).statics
    theta = np.linspace(0.0, 2 * math.pi, 91)
    r, rod = 25.0, 80.0
    x = r * np.cos(theta) + np.sqrt(rod ** 2 - (r * np.sin(theta)) ** 2)
    dx = -r * np.sin(theta) - r ** 2 * np.sin(theta) * np.cos(theta) / np.sqrt(rod ** 2 - (r * np.sin(theta)) ** 2)
    assert x[0] == pytest.approx(105.0)
    assert np.max(np.abs(st.effort_at(theta) - 100.0 * dx / 1000.0)) < 1e-12


def test_a_general_linkage_takes_loads_by_its_joints_names(tmp_path):
    result = CliRunner().invoke(linkgen, ["analyze", "templates/jansen.toml", "-o", str(tmp_path / "o"), "--json",
                                          "--figures", "--set", 'loads=[{point="G", force=[0, 100]}]'])
    assert result.exit_code == 0, result.output
    r = json.loads(result.output)["statics"]
    assert r["max_N_m"] > 0 > r["min_N_m"] and r["mechanical_advantage_min"] > 0
    assert (tmp_path / "o" / "jansen-effort.svg").exists()


@pytest.mark.parametrize("loads, words", [
    ('[{point="Q", force=[0, 1]}]', "loads[0].point: no joint 'Q'; joints: O2, O4, A, B"),
    ('[{link="frame", torque=1}]', "loads[0].link: no moving link 'frame'; links: crank, coupler, rocker"),
    ('[{point="B", torque=1}]', "loads[0]: give point and force"),
    ('[{point="B", force=[0, 1e9]}]', "loads[0].force: must be at most 1e+07 in size (got 0, 1e+09)"),
])
def test_bad_loads_are_refused_by_name(tmp_path, loads, words):
    result = CliRunner().invoke(linkgen, ["analyze", "templates/crank-rocker.toml", "-o", str(tmp_path / "o"),
                                          "--set", f"loads={loads}"])
    assert result.exit_code == 2, result.output
    assert result.output.startswith(f"error: {words}") and result.output.count("\n") == 1, result.output
    assert not (tmp_path / "o").exists()


def test_no_loads_no_statics():
    design = design_linkage(validate_spec(FOURBAR))
    assert "statics" not in design.report and design.statics is None
