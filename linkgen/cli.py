"""The ``linkgen`` command: load the spec -> design -> bundle -> write, and print. Errors: one line, exit code 2."""
from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import click

from camgen.core.cli import (Commands, Family, Starters, add_bench, add_examples, add_family, add_new,
                             animation_options, echo_written, figures_option, fixed, one_design, output_option,
                             set_option, template_argument, template_options, user_errors, write_animation_file)


@click.group(cls=Commands, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="camgen")
def main() -> None:
    """linkgen: four-bars, slider-cranks and friends, right up to the dead centres."""


@main.command()
@template_argument()
@click.option("--angle", type=float, default=None,
              help="Input angle in degrees (the rocker's when linkage.input = 'rocker'): adds the positions there.")
@click.option("--method", type=click.Choice(["closed", "newton"]), default="closed", show_default=True,
              help="newton also prints the Newton-Raphson iteration table (needs --angle).")
@click.option("--newton", "newton", metavar="THETA3,THETA4", default=None,
              help="Newton-Raphson from this start: coupler and rocker angles in degrees, e.g. 30,100; prints the "
                   "iteration table (a four-bar driven by its crank; needs --angle).")
@click.option("--tolerance", type=float, default=None, metavar="MM",
              help="Newton-Raphson stops at the first estimate whose residual norm (loop closure) is at most this "
                   "many mm (with --newton or --method newton; default 1e-12 of the longest link).")
@click.option("--json", "as_json", is_flag=True, help="Print the report as JSON.")
@output_option("Folder for the report and plots (default: out/<name>/).", default=None)
@set_option("linkage.crank=60")
@figures_option
@one_design
def analyze(template: Path, angle: float | None, method: str, newton: str | None, tolerance: float | None,
            as_json: bool, output: Path | None, overrides: tuple[str, ...]) -> None:
    """Analyze the linkage described by TEMPLATE (a TOML file)."""
    from camgen.core.errors import SpecError
    from linkgen.linkage_design import design_linkage
    from linkgen.outputs import write_linkage
    from linkgen.spec import load_spec

    spec = load_spec(template, overrides)
    if method == "newton" and angle is None:
        raise SpecError("the Newton-Raphson table needs an input angle: add --angle DEG", "--method")
    asked = _newton_asked(newton, tolerance, method, angle, spec.linkage)
    try:
        design = design_linkage(spec, angle, "closed" if asked else method)
    except SpecError as exc:
        if exc.field == "angle":                        # the kinematics' name for what --angle gave
            raise SpecError(exc.detail, "--angle") from None
        raise
    if asked and angle is not None:
        design = _with_newton(design, angle, _start(newton), tolerance)
    directory = output if output is not None else Path("out") / spec.name
    files = write_linkage(design, directory)
    if as_json:
        click.echo(json.dumps({**design.report, "files": files}, indent=2))
        return
    _print_text(design.report)
    echo_written(files, directory)


def _newton_asked(newton: str | None, tolerance: float | None, method: str, angle: float | None,
                  table: Any) -> bool:
    """Whether --newton or --tolerance asks for a Newton-Raphson table of our own; refuses (one line naming the
    option) what cannot be one: no --angle, a malformed start, a tolerance that is not a number of mm > 0, a
    --tolerance with no table asked for, a linkage that is not a crank-driven four-bar."""
    from camgen.core.errors import SpecError

    option = "--newton" if newton is not None else "--tolerance"
    if newton is None and tolerance is None:
        return False
    if newton is not None:
        _start(newton)
    if tolerance is not None and not (math.isfinite(tolerance) and tolerance > 0):
        raise SpecError(f"must be a finite number of mm > 0 (got {tolerance:g})", "--tolerance")
    if newton is None and method != "newton":
        raise SpecError("is the Newton-Raphson table's: add --newton THETA3,THETA4 (or --method newton)", "--tolerance")
    if angle is None:
        raise SpecError("the Newton-Raphson table needs an input angle: add --angle DEG", option)
    if table.type != "four-bar":
        raise SpecError(f"the Newton-Raphson table is for linkage.type 'four-bar' (this is {table.type!r})", option)
    if table.input != "crank":
        raise SpecError("the Newton-Raphson table is for a four-bar driven by its crank (linkage.input = 'crank')",
                        option)
    return True


def _start(newton: str | None) -> tuple[float, float] | None:
    """The start THETA3,THETA4 (degrees) of --newton, or None; a malformed pair refused in one line."""
    from camgen.core.errors import SpecError

    if newton is None:
        return None
    parts = newton.split(",")
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        values = ()
    if len(values) != 2 or not all(math.isfinite(v) for v in values):
        raise SpecError(f"must be two finite angles in degrees, the coupler's and the rocker's, as THETA3,THETA4 "
                        f"(e.g. 30,100; got {newton!r})", "--newton")
    return values[0], values[1]


def _with_newton(design: Any, angle: float, start: tuple[float, float] | None, tolerance: float | None) -> Any:
    """The design with its report's Newton-Raphson table from ``start`` to ``tolerance``: where the iteration
    fails (a singular Jacobian, a stall, no convergence), one line naming the option."""
    from dataclasses import replace

    from camgen.core.errors import SolverError, SpecError
    from linkgen.mechanisms.fourbar import newton_table

    option = "--newton" if start is not None else "--tolerance"
    try:
        table = newton_table(design.kinematics, angle, design.spec.linkage.assembly, start, tolerance)
    except SolverError as exc:
        raise SpecError(str(exc), option) from None
    except SpecError as exc:
        raise SpecError(exc.detail, "--tolerance" if exc.field == "tolerance" else option) from None
    return replace(design, report={**design.report, "newton": table})


@main.command()
@template_options("parts.kerf=0.2")
@one_design
def build(template: Path, output: Path | None, overrides: tuple[str, ...]) -> None:
    """Make the parts of the linkage in TEMPLATE: cut sheet, assembly drawing, meshes and the report."""
    from linkgen.linkage_design import design_linkage
    from linkgen.outputs import write_linkage
    from linkgen.spec import load_spec

    spec = load_spec(template, overrides)
    design = design_linkage(spec, parts=True)
    directory = output if output is not None else Path("out") / spec.name
    files = write_linkage(design, directory)
    built = design.build
    if built is not None:                               # parts=True: made, or refused without a [parts] table
        click.echo(f"{spec.name}: {len(built.parts)} parts; layers from the bottom: {', '.join(built.layer_names)}")
    if "routing" in design.report:
        from camgen.core.routing import tool_warning

        warning = tool_warning(design.report["routing"])
        if warning is not None:
            click.echo(f"warning: {warning}")
    echo_written(files, directory)


@main.command()
@template_argument()
@output_option("Folder for the candidates' templates, reports (and figures), summary.json and summary.csv "
               "(default: out/<name>/).", default=None)
@click.option("--jobs", type=click.IntRange(1, 256), default=1, show_default=True,
              help="Local processes a path search spreads its independent searches over.")
@click.option("--scheduler", metavar="ADDRESS", default=None,
              help="Run a path search's independent searches on the Dask cluster at ADDRESS (e.g. tcp://host:8786).")
@click.option("--figures/--no-figures", default=False, show_default=True,
              help="Also draw each candidate's figure as PNG and SVG (off by default, as for linkgen build).")
@set_option("task.seed=2")
@user_errors
def synthesize(template: Path, output: Path | None, jobs: int, scheduler: str | None, figures: bool,
               overrides: tuple[str, ...]) -> None:
    """Find linkages that do what TEMPLATE's [task] asks, best first, each written as a template with its report."""
    from linkgen.synthesis import load_task, write_synthesis
    from linkgen.synthesis import synthesize as find

    spec = load_task(template, overrides)
    result = find(spec, jobs, scheduler)
    directory = output if output is not None else Path("out") / spec.name
    names = write_synthesis(result, directory, figures)
    _print_synthesis(result.summary())
    each = "a template, report and figure" if figures else "a template and report"
    click.echo(f"wrote {len(names)} files to {directory} (summary.json, summary.csv; {each} a candidate)")


def _print_synthesis(summary: dict[str, Any]) -> None:
    """One line a candidate: its template, its error and its lengths; then how the search went."""
    search = summary["search"]
    count = len(summary["candidates"])
    click.echo(f"{summary['name']}: {summary['kind']}, {count} candidate{'s' if count != 1 else ''} in "
               f"{search['seconds']:.3g} s on {search['ran_on']}")
    for row in summary["candidates"]:
        figures = [f"{label} {row[key]:.6g}" for key, label in (
            ("error_mm2", "error mm^2"), ("structural_error_percent", "structural error %"),
            ("transmission_worst_deg", "worst transmission angle deg")) if key in row]
        lengths = ", ".join(f"{k} {row[k]:.6g}" for k in ("ground", "crank", "coupler", "rocker", "rod", "offset")
                            if k in row)
        click.echo(f"  {row['rank']}. {row['template']}: {'; '.join(figures)}; {lengths} mm")
    for line in search.get("bound", []):
        click.echo(f"note: {line}")


def _family() -> Family:
    from linkgen.outputs import build_member
    from linkgen.spec import validate_spec

    return Family(validate_spec, build_member)


def _starters() -> Starters:
    from linkgen.starters import STARTERS, starter

    return Starters({name: what for name, (what, _) in STARTERS.items()}, starter)


def _bench() -> Callable[[Path, bool], dict[str, Any]]:
    from linkgen.bench import run_bench

    return run_bench


add_family(main, _family, "Analyze (and, with [parts], make) every member of the family a TEMPLATE's [sweep] table "
                          "describes; re-running resumes.")
add_bench(main, _bench, Path("out/linkgen-bench"),
          "Measure linkage positions against a plain closed form and pylinkage, and rerun the hard cases.")
add_new(main, _starters, "linkgen")
add_examples(main, "linkgen")


def _print_general(r: dict[str, Any]) -> None:
    """The general linkage's part of the text report: mobility, solve order, toggles, dyads, outputs."""
    out = click.echo
    unit = "deg" if "input_range_deg" in r else "mm"
    order = ", ".join(s["step"] if s["step"] == "input" else
                      f"{s['step']}({s['link']} from {s['from']})" if s["step"] in ("gear", "rack") else
                      f"{s['step']}({'+'.join(s.get('links', []))} at "
                      f"{s.get('joint', ', '.join(s.get('joints', [])))})" for s in r["solve_order"])
    out(f"mobility {r['mobility']}; solved as: {order}")
    if unit == "mm":
        out(f"input reaches {r['input_range_mm']} mm")
    for t in r["toggles"]:
        out(f"  {t['kind']:<13} at input {t[f'input_{unit}']:.6f} {unit}: {'-'.join(t['links'])} in line at "
            f"{t['joint']}")
    circuit = r.get("circuit")
    if circuit:
        pieces = "; then ".join(f"{p[f'input_{unit}'][0]:.6f} to {p[f'input_{unit}'][1]:.6f} {unit} {p['branches']}"
                                for p in circuit["pieces"])
        out(f"circuit of the drawing{'' if circuit['closed'] else ' (open)'}: {pieces}")
        if circuit[f"separate_{unit}"]:
            apart = ", ".join(f"[{a:.6f}, {b:.6f}]" for a, b in circuit[f"separate_{unit}"])
            out(f"  the input's range is split into separate circuits: {apart} {unit} is never reached from the "
                "drawing")
    for d in r["dyads"]:
        if "conditioning_min" in d:             # a class-III group
            out(f"  group {d['kind']} {'-'.join(d['links'])} at {d['joint']}: conditioning {d['conditioning_min']:.4g} "
                f"to {d['conditioning_max']:.4g} (0 at a toggle)")
            continue
        out(f"  dyad {d['kind']} {'-'.join(d['links'])} at {d['joint']}: transmission {d['transmission_min_deg']:.3f} "
            f"to {d['transmission_max_deg']:.3f} deg")
    for name, o in r["outputs"].items():
        if "swing_deg" in o:
            ratio = "" if o.get("time_ratio") is None else f", time ratio {o['time_ratio']:.6g}"
            between = "" if "swing_between_deg" not in o else \
                " ({:.6g} to {:.6g} deg from the drawing)".format(*o["swing_between_deg"])
            out(f"  {name}: swings {o['swing_deg']:.6g} deg{between}{ratio}")
        elif o.get("turns_fully"):
            out(f"  {name}: turns fully")
        elif "stroke_mm" in o:
            ratio = "" if o.get("time_ratio") is None else f", time ratio {o['time_ratio']:.6g}"
            out(f"  {name}: stroke {o['stroke_mm']:.6g} mm{ratio}")
    for name, t in r.get("tracers", {}).items():
        (x0, x1), (y0, y1) = t["x_mm"], t["y_mm"]
        out(f"  tracer {name}: x {fixed(x0)} to {fixed(x1)} mm ({fixed(x1 - x0)} wide), y {fixed(y0)} to {fixed(y1)} "
            f"mm ({fixed(y1 - y0)} high)")


def _print_statics(st: dict[str, Any]) -> None:
    """The effort holding the loads: its extremes, RMS, peak power and least mechanical advantage."""
    unit, label = ("N_m", "N*m") if "max_N_m" in st else ("N", "N")
    where = "input_deg" if "max_at_input_deg" in st else "input_mm"
    if f"max_{unit}" not in st:
        return
    click.echo(f"input effort to hold the loads: {st[f'min_{unit}']:.4g} to {st[f'max_{unit}']:.4g} {label} "
               f"(at {st[f'min_at_{where}']:.4g} and {st[f'max_at_{where}']:.4g} {where[6:]}), "
               f"RMS {st[f'rms_{unit}']:.4g} {label}"
               + (f", peak power {st['peak_power_W']:.4g} W" if "peak_power_W" in st else ""))
    if "mechanical_advantage_min" in st:
        click.echo(f"least mechanical advantage {st['mechanical_advantage_min']:.4g} (lever {st['lever_mm']:.4g} mm) "
                   f"at {st[f'mechanical_advantage_min_at_{where}']:.4g} {where[6:]}")


def _print_dynamics(d: dict[str, Any]) -> None:
    """The dynamics in a few lines: the moving mass, the driving effort and power, the most loaded joint, the
    shaking, the flywheel and counterweight, and the most used hole."""
    out = click.echo
    crank = "max_N_m" in d
    unit, label, where = ("N_m", "N*m", "deg") if crank else ("N", "N", "mm")
    from linkgen.dynamics.report import speed_words

    speed = speed_words(d["speed"])
    out(f"dynamics at {speed}: moving links {1000 * d['moving_mass_kg']:.4g} g ({d['material']}); driving "
        f"{'torque' if crank else 'force'} {d[f'min_{unit}']:.4g} to {d[f'max_{unit}']:.4g} {label} (at "
        f"{d[f'min_at_input_{where}']:.4g} and {d[f'max_at_input_{where}']:.4g} {where}), peak power "
        f"{d['power_peak_W']:.4g} W")
    joints = [j for j in d["joints"] if j["peak_N"] is not None]
    if joints:
        j = max(joints, key=lambda j: j["peak_N"])
        out(f"  most loaded joint {j['joint']} ({'-'.join(j['between'])}): {j['peak_N']:.4g} N at "
            f"{j[f'at_input_{where}']:.4g} {where}; shaking force up to {d['shaking_force_peak_N']:.4g} N, moment "
            f"{d['shaking_moment_peak_N_m']:.4g} N*m")
    if "energy_fluctuation_J" in d:
        out(f"  energy fluctuation {d['energy_fluctuation_J']:.4g} J over a turn")
    f = d.get("flywheel")
    if f is not None:
        made = f" ({f['plates']} x {f['shape']} {f['diameter_mm']:.4g} mm, {1000 * f['mass_kg']:.4g} g)" \
            if "diameter_mm" in f else ""
        out(f"  flywheel for Cs {f['coefficient']:g}: {f['flywheel_kg_m2']:.4g} kg*m^2 beyond the linkage's own "
            f"{f['linkage_own_kg_m2']:.4g}{made}")
    c = d.get("counterweight")
    if c is not None:
        out(f"  counterweight {c['mass_radius_kg_mm']:.4g} kg*mm at {c['angle_from_crank_deg']:.4g} deg from the "
            f"crank: shaking force peak {c['shaking_force_peak_N']:.4g} -> {c['shaking_force_peak_after_N']:.4g} N")
    used = [h for h in d["holes"] if h.get("utilisation") is not None]
    if used:
        h = max(used, key=lambda h: h["utilisation"])
        out(f"  most used hole: {h['part']} at {h['joint']}, {h['bearing_MPa']:.3g} MPa of {h['allowable_MPa']:.3g} "
            f"({100 * h['utilisation']:.3g} %)")
    if "motor" in d:
        from linkgen.dynamics.forward_report import motor_lines

        for line in motor_lines(d["motor"]):
            out(line)


def _print_slack(sl: dict[str, Any]) -> None:
    """The slack's band: the pins' play, each tracer's and output's widest band and where, the Monte Carlo check."""
    unit = "deg" if "analysed_deg" in sl else "mm"
    click.echo(f"slack: pins {sl['pin_diameter_mm']:g} mm in holes of {sl['hole_made_mm']:.4g} mm ({sl['process']}), "
               f"play {sl['play_mm']:.4g} mm; lengths within +-{sl['length_tolerance_mm']:g} mm")
    for name, t in sl["tracers"].items():
        click.echo(f"  tracer {name}: band up to {t['width_max_mm']:.4g} mm wide at input {t[f'at_input_{unit}']:.6g} "
                   f"{unit} ({t['x_mm']:.4g}, {t['y_mm']:.4g} mm), {t['width_mean_mm']:.4g} mm on average")
    for name, o in sl["outputs"].items():
        key = "deg" if "band_max_deg" in o else "mm"
        change = o.get("swing_change_deg", o.get("stroke_change_mm"))
        click.echo(f"  {name}: within +-{o[f'band_max_{key}']:.4g} {key} (most at input {o[f'at_input_{unit}']:.6g} "
                   f"{unit}); its {'swing' if key == 'deg' else 'stroke'} by up to {change:.4g} {key}")
    mc = sl.get("monte_carlo")
    if mc is not None:
        reach = max(mc["reach"].values(), default=0.0)
        click.echo(f"  Monte Carlo: {mc['assembled']} of {mc['count']} samples (seed {mc['seed']}), "
                   f"{mc['compared_poses']} poses, reach {100 * reach:.3g} % of the band; {mc['outside']} poses "
                   "outside it")


def _print_text(r: dict[str, Any]) -> None:
    out = click.echo
    out(f"{r['name']}: {r['type']}, lengths {r['lengths_mm']}")
    if "grashof_class" in r:
        form = f" ({r['form']})" if r.get("form") else ""
        out(f"Grashof class {r['grashof_class']}: {r['inversion']}{form}")
    if "input_range_deg" in r:
        rng = r["input_range_deg"]
        out("input turns fully" if rng is None else f"input reaches {rng} degrees")
    if "transmission_min_deg" in r:
        out(f"transmission angle {r['transmission_min_deg']:.3f} to {r['transmission_max_deg']:.3f} degrees "
            f"(at crank {r['transmission_min_at_crank_deg']:.3f} and {r['transmission_max_at_crank_deg']:.3f})")
    for d in r.get("dead_centres", []):
        where = (f"rocker {d['rocker_deg']:.4f} deg" if "rocker_deg" in d else f"slider {d['slider_mm']:.4f} mm")
        out(f"  {d['kind']:<16} crank {d['crank_deg']:9.4f} deg  {where}  {d.get('meaning', '')}")
    for key, label in (("time_ratio", "time ratio"), ("rocker_swing_deg", "rocker swing (deg)"),
                       ("stroke_mm", "stroke (mm)"), ("approximation_error_max_mm", "approximation error (mm)")):
        if r.get(key) is not None:
            out(f"{label}: {r[key]:.6g}")
    if "circuits" in r:
        _print_circuits(r)
    if "straightness" in r:
        s = r["straightness"]
        out(f"straight stroke {s['stroke_mm']:.6g} mm within {s['error_mm']:.4g} mm "
            f"({100 * s['error_ratio']:.3f} %), input {s['input_from_deg']:.2f} to {s['input_to_deg']:.2f} deg")
    if "solve_order" in r:
        _print_general(r)
    if "contact_ratio" in r:
        _print_gears(r)
    if "engagement_angle_deg" in r:
        _print_ratchet(r)
    if "count" in r:
        _print_counter(r)
    if r.get("classification", {}).get("classes"):
        out(f"class: {', '.join(r['classification']['classes'])} (the rules: the report's classification)")
    positions = r.get("positions")
    if r["type"] in ("oldham", "trammel", "rapson"):
        _print_coupling(r)
        positions = None
    if r["type"] == "gear-train":
        _print_train(r)
        positions = None
    if positions and "lever_deg" in positions:
        out(f"at lever {positions['lever_deg']:.4f} deg: wheel {positions['wheel_deg']:.4f} deg, "
            f"{positions['teeth_passed']} teeth passed")
    elif positions and "pinion_deg" in positions:
        where = (f"rack {positions['rack_mm']:.6f} mm, {positions['rack_speed_mm_s']:.6g} mm/s" if "rack_mm" in
                 positions else f"gear {positions['gear_deg']:.6f} deg, {positions['gear_speed_deg_s']:.6g} deg/s")
        out(f"at pinion {positions['pinion_deg']:.4f} deg ({positions['pinion_speed_deg_s']:.6g} deg/s): {where}")
    elif positions and "joints" in positions:
        for joint, p in positions["joints"].items():
            out(f"  {joint:>6}: x {p['x_mm']:12.6f} mm  y {p['y_mm']:12.6f} mm  "
                f"|v| {math.hypot(*p['v_mm_s']):.6g} mm/s  |a| {math.hypot(*p['a_mm_s2']):.6g} mm/s^2")
    elif positions:
        if "slider_mm" in positions:
            out(f"at crank {positions['crank_deg']:.4f} deg: slider {positions['slider_mm']:.6f} mm, "
                f"v {positions['velocity_mm_s']:.6g} mm/s, a {positions['acceleration_mm_s2']:.6g} mm/s^2")
        else:
            for assembly, p in positions.items():
                out(f"{assembly:>8}: coupler {p['coupler_deg']:.6f} deg, rocker {p['rocker_deg']:.6f} deg, "
                    f"transmission {p['transmission_deg']:.6f} deg")
    if "statics" in r:
        _print_statics(r["statics"])
    if "dynamics" in r:
        _print_dynamics(r["dynamics"])
    if "slack" in r:
        _print_slack(r["slack"])
    for warning in (r.get("warnings", []) + r.get("statics", {}).get("warnings", [])
                    + r.get("dynamics", {}).get("warnings", []) + r.get("slack", {}).get("warnings", [])):
        out(f"warning: {warning}")
    if "newton" in r:
        _print_newton(r["newton"], max(v for v in r["lengths_mm"].values() if isinstance(v, float)))


def _print_gears(r: dict[str, Any]) -> None:
    """A gear pair's working figures, and each member's circles, tip thickness and undercut limit."""
    out = click.echo
    out(f"{r['kind']} pair: centre distance {r['centre_distance_mm']:.6g} mm, working pressure angle "
        f"{r['working_pressure_angle_deg']:.6g} deg, contact ratio {r['contact_ratio']:.6g}, speed ratio "
        f"{r['speed_ratio']:.6g}, backlash {r['backlash_mm']:.4g} mm ({r['normal_backlash_mm']:.4g} mm normal)")
    for name, g in r["gears"].items():
        if "base_radius_mm" not in g:
            out(f"  {name:<6} {g['teeth']} teeth, {g['length_mm']:.6g} mm long, teeth thinned by "
                f"{g['thinning_mm']:.4g} mm")
            continue
        fewest = (f", fewest teeth without undercut {g['fewest_teeth_without_undercut']:.4g}"
                  if "fewest_teeth_without_undercut" in g else "")
        out(f"  {name:<6} {g['teeth']} teeth, shift {g['shift']:g}: radii base {g['base_radius_mm']:.6g}, tip "
            f"{g['tip_radius_mm']:.6g}, root {g['root_radius_mm']:.6g} mm; tip thickness "
            f"{g['tip_thickness_mm']:.4g} mm{fewest}")


def _print_ratchet(r: dict[str, Any]) -> None:
    """A ratchet's holding check and its index per stroke."""
    w, lever = r["wheel"], r["lever"]
    click.echo(f"wheel {w['teeth']} teeth, pitch {w['pitch_deg']:.6g} deg, tip radius {w['tip_radius_mm']:.6g} mm, "
               f"root {w['root_radius_mm']:.6g} mm, faces leaning {w['face_angle_deg']:g} deg")
    click.echo(f"pawl holds: engagement angle {r['engagement_angle_deg']:.6g} deg >= friction angle "
               f"{r['friction_angle_deg']:.6g} deg (margin {r['holding_margin_deg']:.4g})")
    click.echo(f"lever swing {lever['swing_deg']:g} deg indexes {lever['teeth_per_stroke']} teeth "
               f"({lever['index_deg']:.6g} deg) a stroke, {lever['lost_motion_deg']:.6g} deg lost; wheel "
               f"{r['wheel_rpm']:.6g} rpm")


def _print_counter(r: dict[str, Any]) -> None:
    """A counter's transfer: the tens wheel's step, its window and the count."""
    t, c = r["transfer"], r["count"]
    start, end = t["units_window_deg"]
    click.echo(f"tens wheel {t['slots']} slots: one step of {t['step_deg']:.6g} deg every {c['strokes_per_turn']} "
               f"strokes, turning while the units wheel goes {start:.6g} to {end:.6g} deg of its turn (strokes "
               f"{', '.join(str(s) for s in t['strokes_turning_tens'])}); after {c['strokes']} strokes it reads "
               f"{c['tens_index'][-1]} {c['units_index'][-1]}")


def _print_coupling(r: dict[str, Any]) -> None:
    """A coupling's or double slider's figures (Oldham, trammel, Rapson) and its pose at the asked input."""
    out, p = click.echo, r.get("positions")
    if r["type"] == "oldham":
        c = r["disc_centre_circle"]
        out(f"hub 2 turns with hub 1 (speed ratio {r['speed_ratio']:g}); the disc's centre runs on the circle "
            f"centre {c['centre_mm']} mm, radius {c['radius_mm']:.6g} mm, twice a turn; each tongue slides "
            f"{r['slot_stroke_mm']:.6g} mm, at most {r['sliding_speed_max_mm_s']:.6g} mm/s")
        if p:
            out(f"at hub 1 {p['hub1_deg']:.4f} deg: hub 2 {p['hub2_deg']:.4f} deg, disc centre {p['disc_centre_mm']} "
                f"mm, slides {p['slides_mm']} mm")
    elif r["type"] == "trammel":
        e = r["ellipse"]
        out(f"the tracer's ellipse: semi-axes {e['semi_axis_x_mm']:.6g} mm (X) and {e['semi_axis_y_mm']:.6g} mm (Y); "
            f"each block strokes {r['block_stroke_mm']:.6g} mm")
        if p:
            out(f"at input {p['input_deg']:.4f} deg: blocks {p['block_a_mm']:.6f} and {p['block_b_mm']:.6f} mm, "
                f"tracer {p['tracer_mm']} mm")
    else:
        out(f"crosshead travel {r['input_range_mm']} mm; leverage {r['leverage_amidships_mm']:.6g} mm amidships, "
            f"{r['leverage_hard_over_mm']:.6g} mm hard over (x {r['leverage_gain_hard_over']:.6g})")
        if p:
            out(f"at crosshead {p['crosshead_mm']:.6f} mm: tiller {p['tiller_deg']:.6f} deg, "
                f"{p['tiller_rate_deg_s']:.6g} deg/s, leverage {p['leverage_mm']:.6g} mm")


def _print_train(r: dict[str, Any]) -> None:
    """A gear train's ratio, its gears' speeds and, at the asked input, their angles."""
    out, p = click.echo, r.get("positions")
    out(f"{r['kind']} train, module {r['module_mm']:g} mm: ratio {r['ratio']:.9g} (output speed per input speed)")
    if "planetary" in r:
        pl = r["planetary"]
        out(f"  {pl['fixed']} fixed, {pl['input']} driven, {pl['output']} the output; {pl['planets']} planets on a "
            f"carrier of {pl['carrier_radius_mm']:.6g} mm")
    for g in r["gears"]:
        angle = f", at {p['gears'][g['name']]['angle_deg']:.4f} deg" if p else ""
        out(f"  {g['name']:<8} {g['teeth']:>4} teeth, {g['rpm']:.6g} rpm{angle}")


def _print_circuits(r: dict[str, Any]) -> None:
    """The four-bar's circuits: the input angles each holds, and how each link moves on it, with its limits."""
    out = click.echo
    m = r["motion"]
    out(f"motion on the drawn circuit: crank: {m['crank']}; coupler: {m['coupler']}; rocker: {m['rocker']}")
    count = len(r["circuits"])
    for k, c in enumerate(r["circuits"], 1):
        span = c["input_range_deg"]
        holds = (f"{r['input']} {span[0]:.4f} to {span[1]:.4f} deg" if span is not None
                 else f"{r['input']} turns fully" + (f" (repeats after {c['input_turns']} turns)"
                                                     if c["input_turns"] == 2 else ""))
        out(f"circuit {k} of {count}{' (drawn)' if c['drawn'] else ''}: {holds}, "
            f"{' and '.join(c['assemblies'])} assembl{'ies' if len(c['assemblies']) > 1 else 'y'}")
        for link in ("crank", "coupler", "rocker"):
            s = c[link]
            line = f"  {link + ':':<9}{s['description']}"
            if s.get("limits"):
                limits = ", ".join(f"{x['kind']} at crank {x['crank_deg']:.4f} deg ({x['assembly']})"
                                   for x in s["limits"])
                line += (f"; {s['swing_deg']:.4f} deg counter-clockwise from {s['from_deg']:.4f} to "
                         f"{s['to_deg']:.4f} deg; limits: {limits}")
            out(line)


def _print_newton(n: dict[str, Any], longest: float) -> None:
    """The Newton-Raphson table: iteration, theta3 and theta4 (degrees, to the digits the tolerance resolves:
    the angle that moves the longest link's end by the tolerance, and one more) and the residual norm (mm)."""
    digits = min(12, max(4, math.ceil(-math.log10(math.degrees(n["tolerance_mm"] / longest))) + 1))
    width = digits + 6
    click.echo(f"Newton-Raphson ({n['start']}), stopping at a residual of {n['tolerance_mm']:.3g} mm:")
    click.echo(f"{'it':>3} {'theta3 (deg)':>{width}} {'theta4 (deg)':>{width}} {'residual (mm)':>13}")
    for s in n["iterations"]:
        click.echo(f"{s['iteration']:>3} {s['coupler_deg']:>{width}.{digits}f} {s['rocker_deg']:>{width}.{digits}f} "
                   f"{s['residual_mm']:>13.3e}")
    click.echo(f"{n['stopped']}: the {n['assembly']} assembly, {n['agrees_with_closed_form_deg']:.2g} degrees from "
               "its closed form")


@main.command()
@animation_options
@one_design
def animate(template: Path, output: Path | None, overrides: tuple[str, ...], options: Any) -> None:
    """Write one full cycle of the linkage in TEMPLATE as an animation, its tracers' paths drawn."""
    from linkgen.animation import design_frames
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import load_spec

    spec = load_spec(template, overrides)
    frames = design_frames(design_linkage(spec), options.frames, options.size)
    directory = output if output is not None else Path("out") / spec.name
    click.echo(f"wrote {write_animation_file(frames, options, directory, spec.name)}")


@main.command("import")
@click.argument("sketch", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="The template to write (default: <sketch's name>.toml here); an existing file is never "
                   "overwritten.")
@one_design
def import_sketch(sketch: Path, output: Path | None) -> None:
    """Read the linkage drawn in SKETCH (a DXF) into a type = "linkage" template: circles are joints, lines and
    polylines links, layer "ground" (or red) the frame, layer "input" the crank; says what it could not read."""
    import re

    from camgen.core.cli import _write_new
    from camgen.core.errors import SpecError
    from camgen.core.toml_text import dumps
    from linkgen.linkage_design import design_linkage
    from linkgen.sketch import read_sketch, sketch_template
    from linkgen.spec import validate_spec

    path = output if output is not None else Path(f"{sketch.stem}.toml")
    name = re.sub(r"[^A-Za-z0-9_-]+", "-", sketch.stem).strip("-")[:64] or "sketch"
    read = read_sketch(sketch)
    raw = sketch_template(read, name)
    try:
        design_linkage(validate_spec(raw))
    except SpecError as exc:
        raise SpecError(f"the linkage read does not build: {exc}", "sketch") from None
    for note in read.notes:
        click.echo(f"warning: {note}")
    _write_new(path, dumps(raw, f"Read from {sketch.name} by linkgen import.\nCheck it with:  linkgen analyze "
                              f"{path.name}").encode())
    links = raw["linkage"]["links"]
    click.echo(f"{name}: {len(raw['linkage']['joints'])} joints, {len(links)} moving links, ground "
               f"{', '.join(raw['linkage']['ground'])}, input {raw['linkage']['input']['link']}")
    click.echo(f"wrote {path}")
