"""The speed, contact and force records (camgen.speed) and the report's keys made from them: the keys, their order
and their units are the user-facing contract (the JSON report), each key holds its record's figure, the records are
frozen. The figures themselves are checked against independent computations in test_dynamics, test_forces and
test_speeds."""
from __future__ import annotations

import dataclasses
import math

import pytest

from camgen.kinds.conjugate.design import design_conjugate
from camgen.kinds.grooved.design import design_grooved
from camgen.api import design_cam
from camgen.report import cam_report
from camgen.spec import load_spec
from camgen.speed import (KNIFE_NOTE, Forces, GravityHold, HeldContact, KnifeEdge, LoadRange, SpeedRow, SpeedTable,
                          Stress, Unanalysed)
from tests.conftest import ROOT

TEMPLATES = ROOT / "templates"

RATES = ["rpm", "omega_rad_s", "velocity_max_mm_s", "velocity_max_at_deg", "acceleration_max_mm_s2",
         "acceleration_max_at_deg", "jerk_max_mm_s3", "jerk_max_at_deg", "parabolic_acceleration_ratios", "contact"]
HELD = ["mode", "spring_rate_n_mm", "preload_n", "load_n", "weight_n", "margin_n", "force_min_n", "force_min_at_deg",
        "holds", "preload_needed_n", "rate_needed_n_mm", "rate_needed_at_deg", "liftoff_rpm"]
TORQUES = ["torque_max_N_m", "torque_max_at_deg", "torque_min_N_m", "torque_min_at_deg", "torque_rms_N_m",
           "power_max_W", "contact_force_max_N", "contact_force_max_at_deg"]
STRESS = ["cam_material", "follower_material", "length_mm", "e_star_MPa", "pressure_max_MPa", "pressure_max_at_deg",
          "half_width_mm", "allowable_MPa", "holds"]
ROW = ["rpm", "torque_max_N_m", "torque_min_N_m", "torque_rms_N_m", "power_max_W", "contact_force_max_N"]
DRIVE = ["carried_by", "side_changes"]


def _disc(template: str, *sets: str):
    return design_cam(load_spec(TEMPLATES / template, sets))


def test_a_sprung_followers_report_keys_and_figures():
    """speeds.toml (a spring, a load, materials and a speed range): the report's ``speed`` is its record's, key by
    key in the order the report has always had, each key holding the record's figure of that name."""
    design = _disc("speeds.toml")
    speed = design.speed
    report = cam_report(design)["speed"]
    assert report == speed.as_report()
    assert list(report) == [*RATES, "forces", "speeds"]
    assert list(report["contact"]) == HELD
    assert list(report["forces"]) == [*TORQUES, "stress"] and list(report["forces"]["stress"]) == STRESS
    assert list(report["speeds"]) == ["rpm_range", "liftoff_rpm", "rows", "margin_N", "allowable_MPa"]
    assert all(list(row) == [*ROW, "contact_force_min_N", "contact_force_min_at_deg", "holds", "pressure_max_MPa"]
               for row in report["speeds"]["rows"])
    contact, forces, table = speed.contact, speed.forces, speed.speeds
    assert isinstance(contact, HeldContact) and isinstance(forces, Forces) and isinstance(table, SpeedTable)
    assert isinstance(forces.stress, Stress) and forces.hertz is forces.stress
    pairs = [
        (report["rpm"], speed.rpm), (report["omega_rad_s"], speed.omega),
        (report["velocity_max_mm_s"], speed.velocity_max), (report["acceleration_max_mm_s2"], speed.acceleration_max),
        (report["jerk_max_mm_s3"], speed.jerk_max), (report["jerk_max_at_deg"], speed.jerk_max_at_deg),
        (report["contact"]["spring_rate_n_mm"], contact.spring_rate), (report["contact"]["load_n"], contact.load),
        (report["contact"]["force_min_n"], contact.force_min), (report["contact"]["liftoff_rpm"], contact.liftoff_rpm),
        (report["contact"]["preload_needed_n"], contact.preload_needed),
        (report["contact"]["rate_needed_n_mm"], contact.rate_needed),
        (report["forces"]["torque_max_N_m"], forces.torque_max),
        (report["forces"]["torque_min_N_m"], forces.torque_min),
        (report["forces"]["torque_min_at_deg"], forces.torque_min_at_deg),
        (report["forces"]["torque_rms_N_m"], forces.torque_rms), (report["forces"]["power_max_W"], forces.power_max),
        (report["forces"]["contact_force_max_N"], forces.contact_force_max),
        (report["forces"]["stress"]["pressure_max_MPa"], forces.stress.pressure_max),
        (report["forces"]["stress"]["half_width_mm"], forces.stress.half_width),
        (report["forces"]["stress"]["e_star_MPa"], forces.stress.e_star),
        (report["speeds"]["liftoff_rpm"], table.liftoff_rpm), (report["speeds"]["margin_N"], table.margin),
        (report["speeds"]["allowable_MPa"], table.allowable),
        (report["speeds"]["rows"][-1]["torque_max_N_m"], table.rows[-1].torque_max),
        (report["speeds"]["rows"][-1]["contact_force_min_N"], table.rows[-1].contact_force_min),
        (report["speeds"]["rows"][0]["pressure_max_MPa"], table.rows[0].pressure_max),
    ]
    assert all(got == want for got, want in pairs)
    # the lift-off speed found at cam.rpm is the table's, and lies inside its range (a row of its own)
    assert table.liftoff_rpm == contact.liftoff_rpm and table.rpm_range[0] < table.liftoff_rpm < table.rpm_range[1]
    assert table.liftoff_rpm in [row.rpm for row in table.rows]


def test_the_contact_checks_each_keep_their_keys():
    """Gravity alone (rdrd with a mass): mode, lift-off speed and angle, holds; an oscillating roller free of any
    spring, load or weight: no mode and a note; a knife edge with materials: forces whose stress is a note."""
    gravity = _disc("rdrd.toml", "cam.rpm=300", "follower.mass=0.3").speed
    assert isinstance(gravity.contact, GravityHold) and gravity.contact.mode == "gravity"
    assert list(gravity.as_report()["contact"]) == ["mode", "liftoff_rpm", "liftoff_at_deg", "holds"]
    assert list(gravity.as_report()) == [*RATES, "forces"] and list(gravity.as_report()["forces"]) == TORQUES
    from tests.camgen.test_followers import OSC_ROLLER, spec

    free = design_cam(spec({**OSC_ROLLER, "cam.rpm": 60.0, "follower.mass": 0.2})).speed
    assert isinstance(free.contact, Unanalysed) and free.forces is None
    assert free.as_report()["contact"] == {"mode": None, "note": free.contact.note}
    assert [k for k in free.as_report() if k.startswith("velocity")] == ["velocity_max_deg_s", "velocity_max_at_deg"]
    knife = design_cam(spec({"follower.type": "knife-edge", "follower.roller_radius": None, "cam.rpm": 300.0,
                             "follower.mass": 0.3, "follower.spring_rate": 2.0, "cam.material": "pom"})).speed
    assert isinstance(knife.forces.stress, KnifeEdge) and knife.forces.hertz is None
    assert knife.as_report()["forces"]["stress"] == {"note": KNIFE_NOTE}


def test_a_load_table_and_segment_loads_in_the_report():
    """The load table's range and each segment's load as the report gives them (a list of one entry a segment)."""
    design = _disc("rdrd.toml", "cam.rpm=300", "follower.mass=0.2", "follower.spring_rate=0.5",
                   "follower.load_table=[[0, 1], [90, 4], [200, -2]]")
    contact = design.speed.contact
    assert contact.load_table == LoadRange(-2.0, 4.0, 3)
    assert contact.as_report()["load_table_n"] == {"min": -2.0, "max": 4.0, "rows": 3,
                                                   "interpolation": "linear, periodic over the turn"}
    loads = dataclasses.replace(contact, load_table=None, segment_loads=(8.0, 0.0, -2.0, 0.0))
    assert list(loads.as_report())[-1] == "segment_loads_n"
    assert loads.as_report()["segment_loads_n"] == [{"segment": 0, "load_n": 8.0}, {"segment": 1, "load_n": 0.0},
                                                    {"segment": 2, "load_n": -2.0}, {"segment": 3, "load_n": 0.0}]


def test_a_positive_drives_report_keys():
    """A grooved cam (no contact check: it drives both ways) and a conjugate pair (each cam's largest force, and each
    cam's stress under the larger): their forces' keys and the speeds table without a margin or a least force."""
    grooved = design_grooved(load_spec(TEMPLATES / "grooved-loaded.toml")).profile.speed
    report = grooved.as_report()
    assert grooved.contact is None and report["contact"] is None
    assert list(report["forces"]) == [*TORQUES, *DRIVE, "stress"]
    assert list(report["forces"]["stress"]) == [*STRESS, "on"]
    assert report["forces"]["carried_by"] == {"force_positive": grooved.forces.drive.force_positive,
                                              "force_negative": grooved.forces.drive.force_negative}
    assert report["forces"]["side_changes"] == [{"at_deg": c.at_deg, "to": c.to} for c in grooved.forces.drive.changes]
    assert list(report["speeds"]) == ["rpm_range", "liftoff_rpm", "rows", "allowable_MPa"]
    assert all(list(row) == [*ROW, "pressure_max_MPa"] for row in report["speeds"]["rows"])
    pair = design_conjugate(load_spec(TEMPLATES / "conjugate.toml", (
        "cam.rpm=200", "follower.mass=0.2", 'cam.material="pom"'))).cams[0].speed
    forces = pair.as_report()["forces"]
    pair_keys = [f"cam_{k}_contact_force_max_{end}" for k in (1, 2) for end in ("N", "at_deg")]
    assert list(forces) == [*TORQUES, *DRIVE, *pair_keys, "stress"]
    assert list(forces["stress"]) == [*STRESS, "on", "cams"] and len(forces["stress"]["cams"]) == 2
    assert [forces[key] for key in pair_keys] == [v for e in pair.forces.pair for v in (e.value, e.at_deg)]
    stress = pair.forces.stress
    assert stress.on in ("cam 1", "cam 2") and stress == dataclasses.replace(
        max(stress.cams, key=lambda c: c.pressure_max), cams=stress.cams)


def test_the_records_are_frozen():
    row = SpeedRow(100.0, 1.0, -1.0, 0.5, 10.0, 20.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        row.rpm = 200.0                                     # type: ignore[misc]
    assert row.as_report() == {"rpm": 100.0, "torque_max_N_m": 1.0, "torque_min_N_m": -1.0, "torque_rms_N_m": 0.5,
                               "power_max_W": 10.0, "contact_force_max_N": 20.0}
    held = dataclasses.replace(row, contact_force_min=-0.5, contact_force_min_at_deg=90.0, holds=False)
    assert list(held.as_report())[-3:] == ["contact_force_min_N", "contact_force_min_at_deg", "holds"]
    assert math.isclose(held.as_report()["contact_force_min_N"], -0.5)
