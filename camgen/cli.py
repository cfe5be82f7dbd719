"""The ``camgen`` command: load -> validate -> build -> write. Errors: one line on stderr, exit code 2."""
from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import click

from camgen.core.cli import (Commands, Family, Starters, add_bench, add_examples, add_family, add_new,
                             animation_options, echo_written, one_design, output_option, set_option, template_options,
                             user_errors, write_animation_file)


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
    from camgen import api

    spec = api.load(template, overrides)
    design = api.design(spec)
    directory = output if output is not None else Path("out") / spec.name
    extra = api.construction(design) if construction else ()
    report = api.write(design, directory, extra=extra).report
    for line in api.summary(design, report):
        click.echo(line)
    echo_written(report["files"], directory, report["warnings"])


@main.command()
@click.argument("template", type=click.Path(exists=True, dir_okay=False, path_type=Path), required=False)
@click.option("--factors", is_flag=True, help="Print the cam-factor table instead (no template needed).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@set_option("cam.max_pressure_angle=25")
@one_design
def size(template: Path | None, factors: bool, as_json: bool, overrides: tuple[str, ...]) -> None:
    """Smallest base radius for TEMPLATE, or (--factors) the cam factors f with Rp = f h / beta."""
    from camgen import api
    from camgen.core.errors import SpecError
    from camgen.sizing import FACTOR_ANGLES, factor_table

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
    sized = api.size(api.load(template, overrides))
    s = sized.sizing
    result = {"base_radius_mm": s.base_radius_mm, "decided_by": s.decided_by,
              "pressure_radius_mm": s.pressure_radius_mm, "curvature_radius_mm": s.curvature_radius_mm,
              "max_pressure_angle_deg": s.max_pressure_angle_deg, "min_rho_margin_mm": s.min_rho_margin_mm,
              **sized.figures}
    if as_json:
        click.echo(json.dumps(result, indent=2))
        return
    click.echo(f"smallest base radius {s.base_radius_mm:.4f} mm, decided by the {s.decided_by} "
               f"(pressure angle <= {s.max_pressure_angle_deg:g} deg needs {s.pressure_radius_mm:.4f} mm; "
               f"convex radius > {s.min_rho_margin_mm:g} mm needs {s.curvature_radius_mm:.4f} mm)")
    for note in sized.notes:
        click.echo(note)


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


def _family() -> Family:
    from camgen import api

    return Family(api.validate, api.build_member, api.sheet_refusal, api.thumbnail_bore)


def _starters() -> Starters:
    from camgen.starters import starter, starters

    return Starters({name: s.what for name, (_, s) in starters().items()}, starter)


def _bench() -> Callable[[Path, bool], dict[str, Any]]:
    from camgen.bench import run_bench

    return run_bench


add_family(main, _family, "Build every member of the family a TEMPLATE's [sweep] table describes; re-running resumes.")
add_new(main, _starters, "camgen")
add_examples(main, "camgen")
add_bench(main, _bench, Path("out/bench"),
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


@main.command()
@click.argument("template", type=click.Path(exists=True, dir_okay=False, path_type=Path), required=False)
@click.option("--port", type=int, default=None, help="Port on 127.0.0.1 (default: a free one).")
@click.option("--no-browser", is_flag=True, help="Do not open the page in the browser (scripts, tests).")
@user_errors
def serve(template: Path | None, port: int | None, no_browser: bool) -> None:
    """Edit cams and linkages in the browser: serve the designer on 127.0.0.1 for the templates in this folder,
    opening TEMPLATE (a cam's or a linkage's) in each tab, until Ctrl-C."""
    from camgen.designer.serve import serve as run

    def started(url: str) -> None:
        click.echo(f"designer at {url} (folder {Path.cwd()}); Ctrl-C stops it", err=False)
        if not no_browser:
            import webbrowser

            webbrowser.open(url)

    run(Path.cwd(), template, port, started)


@main.command()
@animation_options
@one_design
def animate(template: Path, output: Path | None, overrides: tuple[str, ...], options: Any) -> None:
    """Write one full cycle of the cam, Geneva drive or machine in TEMPLATE, its follower riding it, as an animation."""
    from camgen import api
    from camgen.kinds import spec_kind

    spec = api.load(template, overrides)
    frames = spec_kind(spec).animation(api.design(spec), options.frames, options.size)
    directory = output if output is not None else Path("out") / spec.name
    click.echo(f"wrote {write_animation_file(frames, options, directory, spec.name)}")
