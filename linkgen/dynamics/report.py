"""The report's ``dynamics`` section, its warnings, and a family's columns: in user units (N, N*m, W, J, kg, mm,
MPa; input angles in degrees, a slide's travel in mm).

Peaks are found on the poses and refined between their neighbours (a finer grid, a few rounds, every peak at once)
to 1e-9 of the motion's range; "at" is the input value there. A joint's "direction" is its force's, at the peak, in
the drawing's frame (degrees counter-clockwise from +X), on the second link named from the first.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from linkgen.dynamics.forward_report import motor_columns, motor_report, motor_warnings
from linkgen.dynamics.run import TOGGLE_CUT, Dynamics
from linkgen.dynamics.strength import HoleLoad, hole_force
from linkgen.kinematics.kinetostatics import Kinetostatics

#: rounds of the peaks' refinement, and the grid of each
ROUNDS, GRID = 12, 21

Quantity = Callable[[Kinetostatics], np.ndarray]


def _peaks(dyn: Dynamics, quantities: list[Quantity]) -> list[tuple[float, float]]:
    """Each quantity's largest value over the motion, refined (all at once: one kinetostatics a round over every
    quantity's bracket): (input value, value) each; a quantity that is not finite somewhere keeps its samples."""
    x = dyn.result.inputs
    values = [q(dyn.result) for q in quantities]
    best: list[tuple[float, float]] = []
    brackets = []
    for v in values:
        finite = np.where(np.isfinite(v), v, -np.inf)
        i = int(np.argmax(finite))
        best.append((float(x[i]), float(v[i])))
        brackets.append((float(x[max(i - 1, 0)]), float(x[min(i + 1, len(x) - 1)])))
    live = [k for k, v in enumerate(values) if np.isfinite(v).all() and brackets[k][1] > brackets[k][0]]
    width = float(x[-1] - x[0]) if len(x) > 1 else 1.0
    for _ in range(ROUNDS):
        if not live:
            break
        grids = [np.linspace(*brackets[k], GRID) for k in live]
        k_all = dyn.at(np.concatenate(grids))
        done = []
        for j, k in enumerate(live):
            got = quantities[k](k_all)[j * GRID:(j + 1) * GRID]
            got = np.where(np.isfinite(got), got, -np.inf)
            m = int(np.argmax(got))
            if got[m] > best[k][1]:
                best[k] = (float(grids[j][m]), float(got[m]))
            step = grids[j][1] - grids[j][0]
            brackets[k] = (max(grids[j][m] - step, float(x[0])), min(grids[j][m] + step, float(x[-1])))
            if step <= 1e-9 * width:
                done.append(k)
        live = [k for k in live if k not in done]
    return best


def _num(x: float) -> float | None:
    return round(float(x), 9) if math.isfinite(x) else None


def _effort(k: Kinetostatics) -> np.ndarray:
    return k.effort


def _negative_effort(k: Kinetostatics) -> np.ndarray:
    return -k.effort


def _power(k: Kinetostatics) -> np.ndarray:
    return np.abs(k.power)


def _shaking_force(k: Kinetostatics) -> np.ndarray:
    return np.hypot(*k.shaking_force.T)


def _shaking_moment(k: Kinetostatics) -> np.ndarray:
    return np.abs(k.shaking_moment)


def _pair_force(i: int, k: Kinetostatics) -> np.ndarray:
    return np.hypot(*k.pairs[i].force.T)


def _hole_force(h: HoleLoad, k: Kinetostatics) -> np.ndarray:
    return np.hypot(*hole_force(k, h.part, h.joint, h.kind).T)


def dynamics_report(dyn: Dynamics, rpm: float) -> dict[str, Any]:
    """The ``dynamics`` section of the report (see the module's note)."""
    a, r = dyn.analysis, dyn.result
    crank = a.crank
    unit, effort_unit = ("deg", "N_m") if crank else ("mm", "N")
    at_key = f"at_input_{unit}"

    def shown(v: float) -> float:
        return a.shown(v)

    quantities: list[Quantity] = [_effort, _negative_effort, _power, _shaking_force, _shaking_moment]
    quantities += [partial(_pair_force, i) for i in range(len(r.pairs))]
    quantities += [partial(_hole_force, h) for h in dyn.holes]
    peaks = _peaks(dyn, quantities)
    (x_max, t_max), (x_min, t_min), (x_pow, p_pow), (x_sf, sf), (x_sm, sm) = peaks[:5]
    t_min = -t_min
    x = r.inputs
    finite = np.isfinite(r.effort)
    out: dict[str, Any] = {
        "conventions": "SI units (N, N*m, W, J, kg); masses' centres in mm in each link's own frame (origin at its "
                       "first joint, +x towards its second); forces in the drawing's frame; a joint's force is on "
                       "the second link named from the first",
        "speed": speed_section(dyn, rpm),
        "gravity_m_s2": [_num(v) for v in dyn.loads.gravity],
        "poses": len(x),
        "material": dyn.masses.material.name, "density_kg_m3": dyn.masses.density,
        "moving_mass_kg": _num(dyn.masses.total_mass),
        "masses": _masses(dyn),
        "effort": "torque on the crank, N*m counter-clockwise" if crank else "force on the input slide, N along "
                  "its guide",
        f"max_{effort_unit}": _num(t_max), f"max_{at_key}": shown(x_max),
        f"min_{effort_unit}": _num(t_min), f"min_{at_key}": shown(x_min),
        f"rms_{effort_unit}": _num(_rms(x, r.effort, dyn.turns)) if finite.all() else None,
        "power_peak_W": _num(p_pow), f"power_peak_{at_key}": shown(x_pow),
        "power_mean_W": _num(_mean(x, r.power, dyn.turns)) if finite.all() else None,
        "power_rms_W": _num(_rms(x, r.power, dyn.turns)) if finite.all() else None,
        "shaking_force_peak_N": _num(sf), f"shaking_force_peak_{at_key}": shown(x_sf),
        "shaking_moment_peak_N_m": _num(sm), f"shaking_moment_peak_{at_key}": shown(x_sm),
        "generalised_inertia_kg_m2" if crank else "generalised_inertia_kg": {
            "mean": _num(float(np.mean(dyn.inertia))), "min": _num(float(np.min(dyn.inertia))),
            "max": _num(float(np.max(dyn.inertia)))},
        "joints": [_joint(pf, peak, shown, at_key) for pf, peak in zip(r.pairs, peaks[5:5 + len(r.pairs)],
                                                                       strict=True)],
        "balance_residual": None if r.residual is None else _num(float(np.nanmax(r.residual))),
    }
    if dyn.profile is None:
        out[f"input_acceleration_{'rad_s2' if crank else 'mm_s2'}"] = dyn.table.input_acceleration
    if dyn.turns and dyn.fluctuation is not None:
        out["mean_effort_N_m"] = _num(dyn.fluctuation.mean_torque)
        out["energy_fluctuation_J"] = _num(dyn.fluctuation.energy)
    if dyn.flywheel is not None:
        out["flywheel"] = _flywheel(dyn)
    if dyn.counterweight is not None:
        cw = dyn.counterweight
        out["counterweight"] = {"mass_radius_kg_mm": _num(cw.mass_radius * 1e3),
                                "angle_from_crank_deg": _num(math.degrees(cw.angle) % 360.0),
                                "first_harmonic_forward_N": _num(cw.forward),
                                "first_harmonic_backward_N": _num(cw.backward),
                                "shaking_force_peak_N": _num(cw.peak_before),
                                "shaking_force_peak_after_N": _num(cw.peak_after)}
    holes, pins, warnings = _strength(dyn, peaks[5 + len(r.pairs):], shown, at_key)
    out["holes"] = holes
    out["pins"] = pins
    if dyn.toggles:
        ends = " and ".join(f"{shown(v):.6g}" for v in dyn.toggles)
        out[f"analysed_{unit}"] = [shown(float(x[0])), shown(float(x[-1]))]
        warnings.append(f"the input's range ends at a toggle ({ends} {'degrees' if crank else 'mm'}), where at "
                        "constant input speed the links' rates and their inertia's forces grow without bound: the "
                        f"forces are given from {100 * TOGGLE_CUT:g} % of the range inside it")
    warnings += _flywheel_warnings(dyn)
    if dyn.motion is not None and dyn.table.motor is not None:
        out["motor"] = motor_report(dyn.table.motor, dyn.motion, shown)
        warnings += motor_warnings(out["motor"])
    if not finite.all():
        bad = x[~finite]
        warnings.append(f"the driver cannot move the linkage near input {shown(float(bad[0])):.4g} "
                        f"{'degrees' if crank else 'mm'} (a dead centre): its effort and forces are unbounded there")
    out["warnings"] = warnings
    return out


def speed_section(dyn: Dynamics, rpm: float) -> dict[str, Any]:
    """The speed the dynamics ran at: ``used`` (constant, profile or motor) and its least, mean (over time: a turn,
    or the travel, over the time it takes) and largest, in rpm or mm/s; the constant's own key (``rpm`` or
    ``speed_mm_s``), or a profile's row count."""
    p = dyn.profile
    unit, scale = ("rpm", 60.0 / (2.0 * math.pi)) if dyn.crank else ("mm_s", 1e3)
    if p is None:
        value = rpm if dyn.crank else dyn.table.speed
        out: dict[str, Any] = {"used": "constant", "rpm" if dyn.crank else "speed_mm_s": value}
        out.update({f"{k}_{unit}": value for k in ("min", "mean", "max")})
        return out
    out = {"used": p.kind, f"min_{unit}": _num(p.slowest * scale), f"mean_{unit}": _num(p.mean * scale),
           f"max_{unit}": _num(p.fastest * scale)}
    if isinstance(dyn.table.speed_profile, tuple):
        out["rows"] = len(dyn.table.speed_profile)
    return out


def speed_words(speed: dict[str, Any]) -> str:
    """The report's ``speed`` section in a few words: ``60 rpm``, or ``40 to 80 rpm (profile, mean 57.7)``."""
    unit = "rpm" if "mean_rpm" in speed else "mm_s"
    shown = "rpm" if unit == "rpm" else "mm/s"
    if speed.get("used", "constant") == "constant":
        return f"{speed['rpm' if unit == 'rpm' else 'speed_mm_s']:g} {shown}"
    return f"{speed[f'min_{unit}']:.4g} to {speed[f'max_{unit}']:.4g} {shown} ({speed['used']}, mean " \
           f"{speed[f'mean_{unit}']:.4g})"


def _flywheel_warnings(dyn: Dynamics) -> list[str]:
    """What keeps the flywheel sized from being made: a plate larger than the sheet, or one that cannot give the
    inertia needed within the largest plate (:data:`camgen.core.spec.MAX_LENGTH_MM` across)."""
    f = dyn.flywheel
    if f is None or f.radius is None or f.inertia is None:
        return []
    out = []
    if f.inertia < f.needed * (1 - 1e-6):
        out.append(f"the flywheel: the largest plate ({2 * f.radius:.6g} mm across) gives {f.inertia:.3g} of the "
                   f"{f.needed:.3g} kg*m^2 needed; stack more plates (dynamics.flywheel.plates) or choose a denser "
                   "material")
    elif not f.fits:
        out.append(f"the flywheel: {f.plates} plate(s) {2 * f.radius:.6g} mm across do not fit the sheet; linkgen "
                   "build refuses it: stack more plates (dynamics.flywheel.plates), or choose the rim shape or a "
                   "denser material")
    return out


def _masses(dyn: Dynamics) -> dict[str, Any]:
    out = {}
    for name, m in dyn.masses.links.items():
        entry: dict[str, Any] = {"mass_kg": _num(m.total.mass), "centre_mm": [_num(v) for v in m.total.centre],
                                 "inertia_kg_mm2": _num(m.total.inertia)}
        if m.part is not None:
            entry["part_kg"] = _num(m.part.mass)
        if m.hardware:
            entry["hardware"] = [{"what": what, "mass_kg": _num(h.mass)} for what, h in m.hardware]
        if m.given:
            entry["given"] = list(m.given)
        out[name] = entry
    return out


def _mean(x: np.ndarray, y: np.ndarray, turns: bool) -> float:
    """The mean over the motion: over a turn the poses' mean (they are uniform without the end), else by
    trapezoids."""
    if turns or len(x) < 2:
        return float(np.mean(y))
    return float(np.trapezoid(y, x) / (x[-1] - x[0]))


def _rms(x: np.ndarray, y: np.ndarray, turns: bool) -> float:
    return math.sqrt(_mean(x, y**2, turns))


def _joint(pf: Any, peak: tuple[float, float], shown: Callable[[float], float], at_key: str) -> dict[str, Any]:
    x, value = peak
    magnitude = np.hypot(*pf.force.T)
    i = int(np.argmax(np.where(np.isfinite(magnitude), magnitude, -np.inf)))
    pair = pf.pair
    entry: dict[str, Any] = {"joint": pair.slider or pair.point, "kind": pair.kind, "between": [pair.by, pair.on],
                             "peak_N": _num(value), at_key: shown(x),
                             "direction_deg": _num(math.degrees(math.atan2(pf.force[i, 1], pf.force[i, 0])) % 360.0)
                             if math.isfinite(magnitude[i]) else None,
                             "rms_N": _num(math.sqrt(float(np.mean(magnitude**2))))}
    if pf.couple is not None:
        couple = np.abs(pf.couple)
        entry["couple_peak_N_m"] = _num(float(np.max(couple)))
    return entry


def _flywheel(dyn: Dynamics) -> dict[str, Any]:
    f = dyn.flywheel
    assert f is not None
    out: dict[str, Any] = {"coefficient": f.coefficient, "energy_fluctuation_J": _num(f.energy),
                           "inertia_needed_kg_m2": _num(f.total), "linkage_own_kg_m2": _num(f.own),
                           "flywheel_kg_m2": _num(f.needed), "shape": f.shape, "plates": f.plates}
    if f.radius is not None:
        out.update({"diameter_mm": _num(2 * f.radius), "mass_kg": _num(f.mass or 0.0),
                    "inertia_as_made_kg_m2": _num(f.inertia or 0.0), "fits_sheet": f.fits})
    return out


def _strength(dyn: Dynamics, peaks: list[tuple[float, float]], shown: Callable[[float], float],
              at_key: str) -> tuple[list[dict[str, Any]], list[dict[str, Any]], list[str]]:
    """Each hole's peak force, bearing pressure and its allowable; each pin's shear stress at its most loaded hole;
    a warning for each that exceeds its allowable."""
    holes: list[dict[str, Any]] = []
    pins: dict[str, dict[str, Any]] = {}
    warnings: list[str] = []
    unit = "degrees" if dyn.crank else "mm"
    name = dyn.masses.material.name
    for h, (x, force) in zip(dyn.holes, peaks, strict=True):
        entry: dict[str, Any] = {"part": h.part, "joint": h.joint, "kind": h.kind, "peak_N": _num(force),
                                 at_key: shown(x)}
        pressure = h.pressure(force)
        if pressure is not None:
            entry.update({"bearing_MPa": _num(pressure), "allowable_MPa": _num(h.allowable_bearing),
                          "utilisation": _num(pressure / h.allowable_bearing)})
            if pressure > h.allowable_bearing:
                warnings.append(f"{h.kind} of {h.part} at {h.joint}: bearing pressure {pressure:.3g} MPa at "
                                f"{shown(x):.4g} {unit} exceeds the allowable {h.allowable_bearing:.3g} MPa "
                                f"({'given' if dyn.table.allowable_bearing else name})")
        holes.append(entry)
        shear = h.shear(force)
        if shear is not None and (h.joint not in pins or shear > pins[h.joint]["shear_MPa"]):
            pins[h.joint] = {"joint": h.joint, "shear_MPa": _num(shear), "allowable_MPa": _num(h.allowable_shear),
                             "utilisation": _num(shear / h.allowable_shear), at_key: shown(x)}
    for pin in pins.values():
        if pin["utilisation"] is not None and pin["utilisation"] > 1:
            warnings.append(f"pin at {pin['joint']}: shear stress {pin['shear_MPa']:.3g} MPa at {pin[at_key]:.4g} "
                            f"{unit} exceeds the allowable {pin['allowable_MPa']:.3g} MPa")
    return holes, list(pins.values()), warnings


def family_columns(report: dict[str, Any]) -> dict[str, Any]:
    """A family member's dynamics columns: the driving effort's and the shaking force's peaks, the largest joint
    force, the flywheel's inertia, the most used hole."""
    d = report.get("dynamics")
    if not isinstance(d, dict):
        return {}
    unit = "N_m" if "max_N_m" in d else "N"
    efforts = [abs(v) for v in (d.get(f"max_{unit}"), d.get(f"min_{unit}")) if v is not None]
    joints = [j["peak_N"] for j in d.get("joints", []) if j.get("peak_N") is not None]
    used = [h["utilisation"] for h in d.get("holes", []) if h.get("utilisation") is not None]
    out = {f"effort_peak_{unit}": max(efforts) if efforts else None,
           "shaking_force_peak_N": d.get("shaking_force_peak_N"), "joint_force_peak_N": max(joints) if joints else None,
           "power_peak_W": d.get("power_peak_W")}
    if "flywheel" in d:
        out["flywheel_kg_m2"] = d["flywheel"]["flywheel_kg_m2"]
    if used:
        out["bearing_utilisation_max"] = max(used)
    if "motor" in d:
        out.update(motor_columns(d["motor"]))
    return out
