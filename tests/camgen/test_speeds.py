"""Cams over a range of speeds and loads per motion segment: the inertia's share of the torque against single-speed
builds, the contact's minimum crossing zero at the lift-off speed, a segment's load by hand."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from camgen.api import design_cam
from camgen.dynamics import spec_loading
from camgen.forces import cycle_mean, torque
from camgen.spec import load_spec
from camgen.speed import Speed
from tests.support.refusals import assert_refused
from tests.camgen.test_forces import LOADED, RDRD, ROOT, _design  # the loaded rdrd of the forces tests


def _with_loads(folder: Path, loads: dict[int, float]) -> Path:
    """rdrd.toml with ``load = value`` in the motion tables named by index (--set takes no list indices)."""
    parts = RDRD.read_text().split("[[motion]]")
    for i, value in loads.items():
        parts[i + 1] = parts[i + 1].replace("\n", f"\nload = {value!r}\n", 1)
    path = folder / "loaded.toml"
    path.write_text("[[motion]]".join(parts))
    return path


def test_a_load_per_segment_by_hand(tmp_path):
    """8 N over the rise (0-120 degrees), -2 N over the return (180-300), none on the dwells. At 60 degrees (mid-rise
    of the cycloid: s = 10 mm, s' = 2 h / beta = 60 / pi mm/rad, s'' = 0) the torque is (preload 5 + rate 0.5 * 10 +
    load 3 + 8) * 60 / pi / 1000 N*m; on the dwell at 150 degrees (s = 20 mm, at rest) the contact force is 5 + 10 + 3
    = 18 N. Over a turn only the segments' loads do net work: 8 N over the 20 mm rise and -2 N back down the 20 mm
    return, 160 + 40 = 200 N*mm, so the mean torque is 200 / 2 pi / 1000 N*m."""
    design = _design(_with_loads(tmp_path, {0: 8.0, 2: -2.0}))
    ld = spec_loading(design.spec.follower, design.cam.follower, motion=design.spec.motion,
                      program=design.cam.program)
    omega = 300 * 2 * math.pi / 60
    at = np.radians([60.0, 150.0, 240.0, 330.0])
    m = design.cam.program.evaluate(at)
    assert ld.segments(at) == pytest.approx([8.0, 0.0, -2.0, 0.0], abs=0)
    assert torque(ld, omega, m, at)[0] == pytest.approx((5 + 0.5 * 10 + 3 + 8) * 60 / math.pi / 1000, rel=1e-12)
    assert ld.force(m, omega, at)[1] == pytest.approx(18.0, rel=1e-12)
    mean = cycle_mean(design.cam, lambda t, mm: torque(ld, omega, mm, t))
    assert mean == pytest.approx(200 / (2 * math.pi) / 1000, rel=1e-9)
    theta = np.linspace(0.0, 2 * math.pi, 400001)
    t = torque(ld, omega, design.cam.program.evaluate(theta), theta)
    forces, contact = design.speed.forces, design.speed.contact
    assert forces.torque_max == pytest.approx(t.max(), rel=1e-9)
    assert forces.torque_rms == pytest.approx(math.sqrt(np.mean(t[:-1] ** 2)), rel=1e-6)
    assert contact.segment_loads == (8.0, 0.0, -2.0, 0.0)


def test_a_segments_load_at_its_bounds_and_with_a_table_refused(tmp_path):
    """-1e6 N (the bound) on the first dwell pulls the follower off there; 1e-12 beyond is refused by name, and so is
    a load per segment beside a load table."""
    design = _design(_with_loads(tmp_path, {1: -1e6}))
    assert design.speed.contact.holds is False
    assert 120.0 - 1e-9 <= design.speed.contact.force_min_at_deg <= 180.0 + 1e-9
    assert_refused(_with_loads(tmp_path, {0: 1e6 * (1 + 1e-12)}), {}, "motion[0].load: must be", tmp_path)
    assert_refused(_with_loads(tmp_path, {1: 2.0}), {"follower.load_table": [[0, 1], [180, 2]]},
                   "motion[1].load: give loads per segment or follower.load_table, not both", tmp_path)


RANGE = (*LOADED, "cam.rpm_range=[100, 1500]", "cam.rpm_steps=8")


def test_each_speed_is_a_single_speed_build():
    """Every row of the speeds table is what a build at that one cam.rpm reports, to 1e-9."""
    rows = _design(sets=RANGE).speed.speeds.rows
    assert [r.rpm for r in rows[:2]] == [100.0, 300.0] and rows[-1].rpm == 1500.0
    for row in (rows[0], rows[3], rows[-1]):
        single = _design(sets=(*LOADED, f"cam.rpm={row.rpm!r}")).speed
        forces, contact = single.forces, single.contact
        for key in ("torque_max", "torque_min", "torque_rms", "power_max", "contact_force_max"):
            assert getattr(row, key) == pytest.approx(getattr(forces, key), rel=1e-9, abs=1e-12)
        assert row.contact_force_min == pytest.approx(contact.force_min, rel=1e-9, abs=1e-12)
        assert row.holds is contact.holds
        assert row.pressure_max == pytest.approx(forces.stress.pressure_max, rel=1e-9)


def test_the_inertia_scales_with_the_speed_squared():
    """At every cam angle the torque is T_static + (rpm / rpm0)^2 T_inertia (T_static at rest, T_inertia at rpm0
    less it), so the mean of T^2 is a quadratic in k = (rpm / rpm0)^2: the RMS of three rows of the table give the
    rest's to 1e-9."""
    design = _design(sets=RANGE)
    ld = spec_loading(design.spec.follower, design.cam.follower)
    theta = np.linspace(0.0, 2 * math.pi, 3601)
    m = design.cam.program.evaluate(theta)
    still = torque(ld, 0.0, m, theta)
    inertia = torque(ld, 300 * math.pi / 30, m, theta) - still
    for rpm in (100.0, 471.3, 1500.0):
        t = torque(ld, rpm * math.pi / 30, m, theta)
        assert t == pytest.approx(still + (rpm / 300) ** 2 * inertia, rel=1e-9, abs=1e-12)
    rows = design.speed.speeds.rows
    k = np.array([(r.rpm / 300) ** 2 for r in rows])
    ms = np.array([r.torque_rms ** 2 for r in rows])
    quadratic = np.polyfit(k[[0, 3, -1]], ms[[0, 3, -1]], 2)
    assert np.polyval(quadratic, k) == pytest.approx(ms, rel=1e-9)


def test_the_least_contact_force_crosses_zero_at_the_liftoff_speed():
    """The lift-off speed is a row of the table where the least contact force is 0 (to 1e-9 of the spring's
    force): positive at every slower row, negative at every faster one, and 1e-9 either side of it the same."""
    design = _design(sets=RANGE)
    speeds = design.speed.speeds
    off = speeds.liftoff_rpm
    assert off == design.speed.contact.liftoff_rpm and 100 < off < 1500
    rows = speeds.rows
    assert len(rows) == 9 and sorted(r.rpm for r in rows) == [r.rpm for r in rows]
    at = next(r for r in rows if r.rpm == off)
    assert at.contact_force_min == pytest.approx(0.0, abs=1e-9 * 15)
    assert all(r.contact_force_min > 0 and r.holds for r in rows if r.rpm < off)
    assert all(r.contact_force_min < 0 and not r.holds for r in rows if r.rpm > off)
    ld = spec_loading(design.spec.follower, design.cam.follower)
    from camgen.dynamics import peak_at

    for rpm, sign in ((off * (1 - 1e-9), 1), (off * (1 + 1e-9), -1)):
        omega = rpm * math.pi / 30
        assert sign * -peak_at(design.cam, lambda t, mm, omega=omega: -ld.force(mm, omega, t)).value > 0


def test_the_speeds_figure_and_console_draw_the_table(tmp_path):
    """A build with cam.rpm_range writes <name>-speeds.png/.svg (two files more) whose curves are the table's
    columns, and its console line names the range, the lift-off speed and the allowable."""
    from click.testing import CliRunner

    from camgen.cli import main
    from camgen.plots import speeds_figure

    design = _design(sets=RANGE)
    rows = design.speed.speeds.rows
    axes = speeds_figure(design).axes
    assert list(axes[0].get_lines()[0].get_ydata()) == [r.torque_max for r in rows]
    assert list(axes[1].get_lines()[1].get_ydata()) == [r.contact_force_min for r in rows]
    pressure = next(a for a in axes if a.get_ylabel().startswith("Hertz"))
    assert list(pressure.get_lines()[0].get_ydata()) == [r.pressure_max for r in rows]
    args = ["build", str(RDRD), "-o", str(tmp_path / "out"), "--figures"]
    for s in RANGE:
        args += ["--set", s]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    assert (tmp_path / "out" / "rdrd-speeds.png").exists() and (tmp_path / "out" / "rdrd-speeds.svg").exists()
    speeds = design.speed.speeds
    line = next(x for x in result.output.splitlines() if x.startswith("over 100 to 1500 rpm"))
    assert f"lift-off {speeds.liftoff_rpm:.4g} rpm" in line and "allowable" in line
    plain = CliRunner().invoke(main, ["build", str(RDRD), "-o", str(tmp_path / "plain"), "--figures"])
    assert plain.exit_code == 0, plain.output
    assert len(list((tmp_path / "out").iterdir())) == len(list((tmp_path / "plain").iterdir())) + 2
    off = design.speed.speeds.liftoff_rpm
    assert ("over 100 to 1500 rpm (9 speeds)" in result.output and f"(lift-off {off:.4g} rpm)" in result.output
            and "over the allowable 30 MPa from" in result.output), result.output


@pytest.mark.parametrize("change, message", [
    ({"cam.rpm_range": [1500, 100]}, "cam.rpm_range: give [lowest, highest] with 0 < lowest < highest <= 100000"),
    ({"cam.rpm_range": [0, 100]}, "cam.rpm_range: give [lowest, highest]"),
    ({"cam.rpm_range": [100, 100_000 * (1 + 1e-12)]}, "cam.rpm_range: give [lowest, highest]"),
    ({"cam.rpm_range": [100, 200], "follower.mass": 0.2}, "cam.rpm_range: needs cam.rpm"),
    ({"cam.rpm_range": [100, 200], "cam.rpm": 300}, "cam.rpm_range: needs follower.mass"),
    ({"cam.rpm_range": [100, 200], "cam.rpm_steps": 1}, "cam.rpm_steps: must be"),
])
def test_bad_speed_ranges_are_refused(tmp_path, change, message):
    assert_refused(RDRD, change, message, tmp_path)


def test_the_range_at_its_bounds():
    """The widest range, 1e-12 rpm up to 100 000 rpm, in two speeds: both ends are rows, nothing NaN."""
    rows = _design(sets=(*LOADED, "cam.rpm_range=[1e-12, 100000]", "cam.rpm_steps=2")).speed.speeds.rows
    assert [r.rpm for r in rows][::len(rows) - 1] == [1e-12, 100000.0]
    assert all(math.isfinite(v) for r in rows for v in vars(r).values() if isinstance(v, float))


@pytest.mark.parametrize("template", ["grooved.toml", "barrel.toml"])
def test_a_grooves_speeds_are_single_speed_builds(template, tmp_path):
    """A grooved and a barrel cam over a range: each row is what a build at that one cam.rpm reports (torque, RMS,
    power, the largest normal force, the Hertz pressure on the wall carrying the force) to 1e-9; no lift-off (the
    groove drives both ways); <name>-speeds.png/.svg written."""
    from click.testing import CliRunner

    from camgen.cli import main

    path = ROOT / "templates" / template
    sets = ("cam.rpm=300", "follower.mass=0.2", "follower.load=-5", 'cam.material="pla"')

    def speed(extra: tuple[str, ...]) -> Speed:
        design = design_cam(load_spec(path, (*sets, *extra)))
        return getattr(design, "profile", design).speed

    speeds = speed(("cam.rpm_range=[100, 1000]", "cam.rpm_steps=4")).speeds
    assert speeds.liftoff_rpm is None and [r.rpm for r in speeds.rows] == [100.0, 400.0, 700.0, 1000.0]
    for row in speeds.rows[::3]:
        forces = speed((f"cam.rpm={row.rpm!r}",)).forces
        for key in ("torque_max", "torque_min", "torque_rms", "power_max", "contact_force_max"):
            assert getattr(row, key) == pytest.approx(getattr(forces, key), rel=1e-9, abs=1e-12)
        assert row.pressure_max == pytest.approx(forces.stress.pressure_max, rel=1e-9)
        assert row.holds is None and row.contact_force_min is None
    args = ["build", str(path), "-o", str(tmp_path / "out"), "--figures"]
    for s in (*sets, "cam.rpm_range=[100, 1000]", "cam.rpm_steps=4"):
        args += ["--set", s]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    name = path.stem
    assert (tmp_path / "out" / f"{name}-speeds.png").exists() and (tmp_path / "out" / f"{name}-speeds.svg").exists()


def test_a_conjugate_pairs_speeds_are_single_speed_builds():
    """A pair over a range: each row is a build at that one cam.rpm (torque figures, the larger of both cams' normal
    forces, both cams' larger Hertz pressure) to 1e-9; no lift-off."""
    from camgen.kinds.conjugate.design import design_conjugate

    path = ROOT / "templates" / "conjugate.toml"
    sets = ("cam.rpm=300", "follower.mass=0.2", "follower.load=-5", 'cam.material="pla"')
    speeds = design_conjugate(load_spec(path, (*sets, "cam.rpm_range=[100, 1000]", "cam.rpm_steps=3"))
                              ).cams[0].speed.speeds
    assert speeds.liftoff_rpm is None and [r.rpm for r in speeds.rows] == [100.0, 550.0, 1000.0]
    for row in speeds.rows[::2]:
        forces = design_conjugate(load_spec(path, (*sets, f"cam.rpm={row.rpm!r}"))).cams[0].speed.forces
        for key in ("torque_max", "torque_min", "torque_rms", "power_max"):
            assert getattr(row, key) == pytest.approx(getattr(forces, key), rel=1e-9, abs=1e-12)
        assert row.contact_force_max == pytest.approx(max(forces.pair[0].value,
                                                               forces.pair[1].value), rel=1e-9)
        assert row.pressure_max == pytest.approx(forces.stress.pressure_max, rel=1e-9)


def test_a_stacked_search_finds_each_peak_as_a_search_alone():
    """The speeds table's one search over the turn (camgen.dynamics.peaks_at / stacked_peaks) finds every row's
    peaks as a search of that quantity alone does, to 1e-12 of the value and 1e-9 degrees: the torque, its least,
    the contact force's least and -s'' at five speeds of the loaded rdrd, and against a dense brute force."""
    from camgen.dynamics import peak_at, peaks_at

    design = _design(RDRD, LOADED)
    cam = design.cam
    ld = spec_loading(design.spec.follower, cam.follower, motion=design.spec.motion, program=cam.program)
    funcs = []
    for rpm in (100.0, 400.0, 700.0, 1000.0, 1500.0):
        omega = rpm * 2 * math.pi / 60
        funcs += [lambda t, m, w=omega: torque(ld, w, m, t), lambda t, m, w=omega: -torque(ld, w, m, t),
                  lambda t, m, w=omega: -ld.force(m, w, t)]
    funcs.append(lambda t, m: -m[2])
    theta = np.linspace(0.0, 2 * math.pi, 200001)
    dense = cam.program.evaluate(theta)
    for stacked, func in zip(peaks_at(cam, *funcs), funcs, strict=True):
        alone = peak_at(cam, func)
        assert stacked.value == pytest.approx(alone.value, rel=1e-12, abs=1e-12)
        assert abs((stacked.at_deg - alone.at_deg + 180.0) % 360.0 - 180.0) < 1e-9
        assert stacked.value >= float(np.max(func(theta, dense))) - 1e-12 * max(abs(stacked.value), 1.0)
