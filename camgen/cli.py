"""The ``camgen`` command: load -> validate -> build -> write. Errors: one line on stderr, exit code 2."""
from __future__ import annotations

import json
from pathlib import Path

import click

from camgen.core.cli import (Commands, add_bench, add_examples, add_family, add_new, echo_written, one_design,
                             output_option, set_option, template_options)


@click.group(cls=Commands, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="camgen")
def main() -> None:
    """camgen: disc, plate, grooved, barrel and conjugate cams from motion requirements, and Geneva drives, to DXF,
    STL, plots and a report."""


@main.command()
@template_options("motion.0.lift=25")
@click.option("--construction", is_flag=True,
              help="Also draw the cam's graphical construction as the course teaches it (a disc cam): "
                   "<name>-construction.png and .svg, the displacement diagram over the prime circle's perimeter "
                   "(a flat face's base circle) and the follower inverted at each station (every 15 degrees and "
                   "each segment's start), numbered.")
@one_design
def build(template: Path, output: Path | None, overrides: tuple[str, ...], construction: bool) -> None:
    """Build the cam described by TEMPLATE (a TOML file)."""
    from camgen.profile import design_cam
    from camgen.outputs import write_cam
    from camgen.report import design_lines
    from camgen.spec import load_spec

    spec = load_spec(template, overrides)
    design = design_cam(spec)
    directory = output if output is not None else Path("out") / spec.name
    extra = ()
    if construction:
        from camgen.construction.figure import construction_files

        extra = construction_files(design)
    report = write_cam(design, directory, extra)
    lines = _summary(report)
    if lines is not None:
        for line in lines:
            click.echo(line)
        echo_written(report["files"], directory, report["warnings"])
        return
    click.echo(_checks_line(design))
    click.echo(f"outline: {report['outline_vertices']} vertices ({report['outline_arcs']} exact arcs), "
               f"max error {report['outline_max_error_mm']:.2e} mm (tolerance {report['tolerance_mm']:g} mm)")
    for line in design_lines(report):
        click.echo(line)
    if "flanks" in report:
        from camgen.grooved.outputs import groove_summary

        click.echo(groove_summary(report))
    echo_written(report["files"], directory, report["warnings"])


def _checks_line(design: object) -> str:
    """The console's first line: the peak pressure angle and the smallest convex radius (deg, mm). A flat face has
    no pitch curve apart from its profile, so only the cam's radius is given; a translating flat face is pushed
    square to its face, so its pressure angle is said to be 0 by definition rather than printed as a peak."""
    a, name = design.analysis, design.spec.name
    flat = design.cam.follower.flat
    where = f"at {a.pitch_rho_min_at_deg:.2f} deg"
    radius = (f"min convex radius {a.profile_rho_min_mm:.3f} mm (cam) {where}" if flat else
              f"min convex radius {a.profile_rho_min_mm:.3f} mm (cam), {a.pitch_rho_min_mm:.3f} mm (pitch) {where}")
    if flat and not design.spec.follower.oscillating:
        return f"{name}: pressure angle 0 by definition (the flat face is pushed square to its face); {radius}"
    return (f"{name}: pressure angle max {a.pressure_angle_max_deg:.2f} deg at {a.pressure_angle_max_at_deg:.2f} deg; "
            f"{radius}")


def _summary(report: dict) -> list[str] | None:
    """The key figures of a Geneva drive's, a barrel cam's or a conjugate pair's report to print; None for the other
    cams."""
    if "geneva" in report:
        from camgen.geneva.report import summary_lines

        return summary_lines(report)
    if report["cam"].get("kind") == "conjugate":
        from camgen.conjugate.outputs import summary_lines as pair_lines

        return pair_lines(report)
    if report["cam"].get("kind") == "barrel":
        from camgen.barrel.outputs import summary_lines as barrel_lines

        return barrel_lines(report)
    return None


@main.command()
@click.argument("template", type=click.Path(exists=True, dir_okay=False, path_type=Path), required=False)
@click.option("--factors", is_flag=True, help="Print the cam-factor table instead (no template needed).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@set_option("cam.max_pressure_angle=25")
@one_design
def size(template: Path | None, factors: bool, as_json: bool, overrides: tuple[str, ...]) -> None:
    """Smallest base radius for TEMPLATE, or (--factors) the cam factors f with Rp = f h / beta."""
    from camgen.core.errors import SpecError
    from camgen.geneva.spec import GenevaSpec
    from camgen.sizing import FACTOR_ANGLES, factor_table
    from camgen.spec import load_spec

    if factors:
        table = factor_table()
        if as_json:
            click.echo(json.dumps(table, indent=2))
            return
        click.echo(f"{'law':<18}" + "".join(f"{a:>8}" for a in FACTOR_ANGLES) + "   (max pressure angle, degrees)")
        for law, row in table.items():
            click.echo(f"{law:<18}" + "".join(f"{row[str(a)]:>8.3f}" for a in FACTOR_ANGLES))
        click.echo("prime radius = f x lift / segment angle (radians); modified-uniform in its drafted form")
        return
    if template is None:
        raise SpecError("give a TEMPLATE, or --factors for the cam-factor table", "size")
    spec = load_spec(template, overrides)
    if isinstance(spec, GenevaSpec):
        raise SpecError("a Geneva drive has no base radius to size; `camgen build` it", "template")
    if spec.cam.kind == "barrel":
        raise SpecError("a barrel cam has no base radius to size: its pitch_radius is the designer's choice (the "
                        "report gives the pressure angle at it)", "template")
    alone = None
    if spec.cam.kind == "grooved":
        from camgen.grooved.design import size_grooved

        s = size_grooved(spec)
    elif spec.cam.kind == "conjugate":
        from camgen.conjugate.design import size_conjugate

        alone = size_conjugate(spec)
        s = max(alone, key=lambda one: one.base_radius_mm)
    else:
        from camgen.flat import size_disc, size_plate

        s = (size_plate if spec.cam.kind == "plate" else size_disc)(spec)
    result = {"base_radius_mm": s.base_radius_mm, "decided_by": s.decided_by,
              "pressure_radius_mm": s.pressure_radius_mm, "curvature_radius_mm": s.curvature_radius_mm,
              "max_pressure_angle_deg": s.max_pressure_angle_deg, "min_rho_margin_mm": s.min_rho_margin_mm}
    if alone is not None:
        result["each_cam_base_radius_mm"] = [one.base_radius_mm for one in alone]
    if as_json:
        click.echo(json.dumps(result, indent=2))
        return
    click.echo(f"smallest base radius {s.base_radius_mm:.4f} mm, decided by the {s.decided_by} "
               f"(pressure angle <= {s.max_pressure_angle_deg:g} deg needs {s.pressure_radius_mm:.4f} mm; "
               f"convex radius > {s.min_rho_margin_mm:g} mm needs {s.curvature_radius_mm:.4f} mm)")
    if alone is not None:
        click.echo(f"each cam alone: cam 1 needs {alone[0].base_radius_mm:.4f} mm (cam.base_radius), cam 2 "
                   f"{alone[1].base_radius_mm:.4f} mm (cam.second_base_radius); a pair of equal cams, the larger")


@main.command()
@output_option("Output folder (default: out/<name>/, out/coupon/).", default=None)
@set_option("coupon.diameter=8")
@one_design
def coupon(output: Path | None, overrides: tuple[str, ...]) -> None:
    """Write a fit-test coupon: holes at a range of clearances round one pin, labelled, and the pin."""
    from camgen.core.coupon import coupon_spec, design_coupon, write_coupon

    spec = coupon_spec(None, overrides)
    directory = output if output is not None else Path("out") / spec.name
    report = write_coupon(design_coupon(spec), directory)
    holes, allow = report["holes"], report["allowances"]
    click.echo(f"{spec.name}: {len(holes)} holes for a {report['nominal_mm']:g} mm pin, clearances {holes[0]['label']} "
               f"to {holes[-1]['label']} mm; cut holes drawn at nominal + clearance - kerf {allow['kerf_mm']:g} mm, "
               f"printed at nominal + clearance + {allow['clearance_mm']:g} mm")
    echo_written(report["files"], directory, report["warnings"])


add_family(main, "camgen.spec:validate_spec", "camgen.outputs:build_member",
           "Build every member of the family a TEMPLATE's [sweep] table describes; "
           "re-running resumes.", nestable="camgen.spec:sheet_refusal")


add_new(main, "camgen.starters:starter", "camgen.starters:STARTERS", "camgen")
add_examples(main, "camgen")


add_bench(main, "camgen.bench:run_bench", Path("out/bench"),
          "Measure speed against error, peers, throughput, memory and the hard cases on this machine.")


@main.command()
@click.option("--json", "as_json", is_flag=True, help="Print the table as JSON.")
@one_design
def laws(as_json: bool) -> None:
    """Compare the motion laws for lift h = 1 over beta = 1 rad: peak velocity, acceleration, jerk."""
    from camgen.laws.table import law_table

    rows = law_table()
    if as_json:
        click.echo(json.dumps(rows, indent=2))
        return
    click.echo(f"{'law':<18}{'Cv':>10}{'Ca':>10}{'Cj':>10}   infinite between dwells")
    for row in rows:
        inf = ", ".join({"v": "velocity", "a": "acceleration", "j": "jerk"}[k] for k in row["infinite"]) or "-"
        click.echo(f"{row['law']:<18}{row['cv']:>10.4f}{row['ca']:>10.4f}{row['cj']:>10.4f}   {inf}")
    click.echo("Cv, Ca, Cj: peak |s'|, |s''|, |s'''| inside the segment for h = beta = 1 "
               "(modified-uniform: cycloidal blends over 0.25 of beta)")
