"""The report's ``dynamics.motor`` section of the motion from rest (:mod:`linkgen.dynamics.forward`), its warnings,
its console lines and a family's columns: speeds in rpm, torques in N*m, times in s, energies in J, crank angles in
degrees in [0, 360).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from linkgen.dynamics.forward import MAX_TURNS, RUNAWAY_RPM, SETTLED, Motion

if TYPE_CHECKING:
    from linkgen.dynamics.motor import MotorTable

RPM = 60.0 / (2.0 * math.pi)


def _num(x: float) -> float:
    return round(float(x), 9)


def motor_report(table: MotorTable, motion: Motion, shown: Callable[[float], float]) -> dict[str, Any]:
    """The ``motor`` section for ``table``'s ``motion``; ``shown`` gives a crank angle (rad) in the report's
    degrees."""
    eq, m = motion.equation, motion.equation.motor
    out: dict[str, Any] = {
        "motor": "constant torque" if table.torque is not None else "torque-speed line",
        "crank_stall_torque_N_m": _num(m.stall), "gear_ratio": table.gear_ratio,
        "friction_N_m": table.friction, "viscous_N_m_at_1000_rpm": table.viscous,
        "added_inertia_kg_m2": _num(eq.added),
        "ended": motion.outcome, "simulated_s": _num(motion.end), "turns": len(motion.turn_ends),
        "steady_within": SETTLED,
    }
    if table.no_load_speed is not None:
        out["crank_no_load_rpm"] = _num(table.no_load_speed / table.gear_ratio)
    last = motion.last
    if last is not None:
        key = "steady" if motion.outcome == "steady" else "last_turn"
        out[key] = {"mean_rpm": _num(last.mean * RPM), "fastest_rpm": _num(last.fastest * RPM),
                    "slowest_rpm": _num(last.slowest * RPM), "fluctuation": _num(last.fluctuation),
                    "motor_torque_mean_N_m": _num(last.motor_torque),
                    "friction_torque_mean_N_m": _num(last.friction_torque), "power_mean_W": _num(last.power)}
        if motion.outcome == "steady":
            out["time_to_steady_s"] = None if last.settled is None else _num(last.settled)
    if motion.stall is not None:
        s = motion.stall
        out["stall"] = {"at_input_deg": shown(s.angle), "after_s": _num(s.time),
                        "then": "turns back" if s.turns_back else "stays"}
    motor, friction, loads, kinetic = motion.work
    out["work_J"] = {"motor": _num(motor), "friction": _num(friction), "loads": _num(loads),
                     "kinetic_at_end": _num(kinetic)}
    return out


def motor_warnings(d: dict[str, Any]) -> list[str]:
    """What the run says beyond its figures: a stall, a speed not yet steady, a runaway."""
    ended = d["ended"]
    if ended == "stall":
        s = d["stall"]
        return [f"the motor stalls at theta = {s['at_input_deg']:.4g} degrees after {s['after_s']:.4g} s (it "
                f"cannot pass the linkage's peak need there; the crank then {s['then']}): a stronger motor, a lower "
                "gear or a flywheel (dynamics.flywheel)"]
    if ended == "runaway":
        return [f"the crank speeds up without bound (a constant torque above the linkage's mean need and the "
                f"friction, or past {RUNAWAY_RPM:g} rpm): nothing holds the motor back; give it a no-load speed "
                "(dynamics.motor.no_load_speed) or viscous friction (dynamics.motor.viscous)"]
    if ended in ("time", "turns"):
        bound = (f"the simulated time {d['simulated_s']:.4g} s (dynamics.motor.time)" if ended == "time" else
                 f"{MAX_TURNS} turns")
        return [f"the speed is not steady within {bound}: the figures are of the last full turn"]
    return []


def motor_lines(d: dict[str, Any]) -> list[str]:
    """The console's lines of the ``motor`` section."""
    head = (f"  motor from rest ({d['motor']}, {d['crank_stall_torque_N_m']:.4g} N*m at the crank at rest): ")
    steady = d.get("steady")
    if steady is not None:
        settled = d.get("time_to_steady_s")
        when = f"steady after {settled:.4g} s" if settled is not None else "steady"
        return [head + f"{when} at {steady['mean_rpm']:.5g} rpm, fluctuation {steady['fluctuation']:.4g} "
                f"(max - min)/mean, mean torque {steady['motor_torque_mean_N_m']:.4g} N*m, "
                f"{steady['power_mean_W']:.4g} W"]
    if "stall" in d:
        s = d["stall"]
        return [head + f"stalls at theta = {s['at_input_deg']:.4g} degrees after {s['after_s']:.4g} s and "
                f"{s['then']}"]
    last = d.get("last_turn")
    if d["ended"] == "runaway":
        return [head + f"speeds up without bound ({d['turns']} turns in {d['simulated_s']:.4g} s"
                + (f", the last at {last['mean_rpm']:.5g} rpm)" if last is not None else ")")]
    tail = f"; last turn at {last['mean_rpm']:.5g} rpm" if last is not None else ""
    return [head + f"not steady after {d['simulated_s']:.4g} s ({d['turns']} turns){tail}"]


def motor_columns(d: dict[str, Any]) -> dict[str, Any]:
    """A family member's columns of the ``motor`` section: the steady speed, its fluctuation and the time to it, or
    where it stalls."""
    steady = d.get("steady") or {}
    stall = d.get("stall") or {}
    return {"motor_steady_rpm": steady.get("mean_rpm"), "motor_fluctuation": steady.get("fluctuation"),
            "motor_time_to_steady_s": d.get("time_to_steady_s"), "motor_stall_deg": stall.get("at_input_deg")}
