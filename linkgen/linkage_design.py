"""A linkage design from a spec: its kinematics, its report and, when asked, its parts. No I/O.

The report (what ``linkgen analyze`` prints) is in mm and degrees: the common keys here,
then the mechanism's own section (:meth:`linkgen.mechanisms.Mechanism.report`).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from camgen.core.errors import SpecError
from camgen.core.routing import add_routing
from linkgen.dynamics.masses import Stack
from linkgen.dynamics.run import Dynamics, flywheel_build
from linkgen.dynamics.report import dynamics_report
from linkgen.effort import Statics, statics_of, statics_report
from linkgen.kit import LinkageKit, base_plate, linkage_kit
from linkgen.mechanisms import Mechanism, MechanismTable
from linkgen.mechanisms.common import Figure
from linkgen.parts import LinkageBuild, build_parts
from linkgen.slack import Slack, slack_of
from linkgen.spec import LinkageSpec

CONVENTIONS = ("input pivot at the origin, output pivot on +X; angles counter-clockwise from the ground line (+X) "
               "in degrees; lengths in mm; speeds per second at the template's rpm")


@dataclass(frozen=True)
class LinkageDesign:
    """Everything known about one linkage before anything is written (made by :func:`design_linkage`): its spec, its
    mechanism, the kinematics object the mechanism built, the report, and with parts asked for their build.

    Attributes
    ----------
    spec : LinkageSpec
        The validated template (``design.spec.linkage`` is its ``[linkage]`` table).
    mechanism : Mechanism
        The mechanism registered for ``linkage.type`` (:data:`linkgen.mechanisms.MECHANISMS`).
    kinematics : object
        What the mechanism built: a :class:`~linkgen.kinematics.fourbar.FourBar`, a
        :class:`~linkgen.kinematics.slidercrank.SliderCrank`, a :class:`~linkgen.kinematics.linkage.Linkage`, ...;
        its positions at any input angles.
    report : dict
        The report, as the JSON file holds it (``report["transmission_min_deg"]``, ``report["dead_centres"]``, ...).
    build : LinkageBuild or None
        The parts, the cut sheet and the assembly drawing, when parts were asked for (``linkgen build``).
    angle : float or None
        The input angle (degrees; mm for a slide input) the report's positions are at, and the pose figure shows.
    statics : Statics or None
        The effort holding the template's loads (``[[loads]]``), when it has any.
    kit : LinkageKit or None
        The kit of a ``[kit]`` table, when parts are made (its build is :attr:`build`: the base plate is the
        ground).
    dynamics : Dynamics or None
        The dynamics of a ``[dynamics]`` table (:mod:`linkgen.dynamics`): masses, joint forces, driving effort,
        shaking, flywheel, counterweight and the holes' and pins' loads.
    slack : Slack or None
        The band of its motion under its joints' play and its links' tolerances, with a ``[slack]`` table.
    """

    spec: LinkageSpec
    mechanism: Mechanism
    kinematics: Any
    report: dict[str, Any]
    build: LinkageBuild | None = None
    angle: float | None = None
    statics: Statics | None = None
    kit: LinkageKit | None = None
    dynamics: Dynamics | None = None
    slack: Slack | None = None

    def figures(self) -> tuple[Figure, ...]:
        """The mechanism's figures of this linkage, each drawn only when called; with an angle, the pose there (for
        the mechanisms linkgen can draw as a general linkage)."""
        figures = self.mechanism.figures(self.spec.name, self.spec.linkage, self.kinematics)
        if self.statics is not None:
            statics = self.statics

            def effort() -> Any:
                from linkgen import plots

                return plots.effort_figure(self.spec.name, statics)

            figures = (*figures, ("effort", effort))
        if self.dynamics is not None:
            from linkgen.dynamics.plots import dynamics_figures

            figures = (*figures, *dynamics_figures(self.spec.name, self.dynamics))
        if self.slack is not None:
            slack = self.slack

            def blur() -> Any:
                from linkgen.slack.figure import slack_figure

                return slack_figure(self.spec.name, slack)

            figures = (*figures, ("slack", blur))
        posed = None if self.angle is None else pose_of(self.kinematics, self.spec.linkage, self.angle)
        if posed is None:
            return figures

        def draw() -> Any:
            from linkgen import plots

            return plots.linkage_pose_figure(self.spec.name, *posed)

        return (*figures, ("pose", draw))

    def family_row(self) -> dict[str, Any]:
        """What a family's summary adds for this linkage: the mechanism's columns and thumbnail, and with
        ``[dynamics]`` its peaks."""
        from linkgen.dynamics.report import family_columns

        return {**self.mechanism.family_row(self.spec.linkage, self.kinematics, self.report),
                **family_columns(self.report)}

    def page(self, report: dict[str, Any] | None = None) -> Any:
        """The linkage's interactive page (:func:`linkgen.page.linkage_page`) showing the figures of ``report`` (the
        design's own by default); None for a kind linkgen cannot draw as a general linkage (see :func:`pose_of`).
        It is drawn from the design's angle, else 0, else the middle of a range the input reaches."""
        from linkgen.page import linkage_page

        extra = None if self.dynamics is None else self.dynamics_plots
        if self.slack is not None:                    # drawn as the slack's band was (from the same pose)
            from linkgen.slack.figure import with_slack

            return with_slack(linkage_page(self.spec.name, self.slack.band.analysis,
                                           self.report if report is None else report, extra), self.slack)
        posed = drawn_pose(self.kinematics, self.spec.linkage, self.angle)
        if posed is None:
            return None
        return linkage_page(self.spec.name, posed[0], self.report if report is None else report, extra)

    def dynamics_plots(self, values: np.ndarray) -> tuple[Any, ...]:
        """The page's plots of the dynamics at the page's input values (rad or mm): the driving effort and power,
        and the joints' forces."""
        from linkgen.dynamics.plots import page_plots

        return () if self.dynamics is None else page_plots(self.dynamics, values)

    def _repr_html_(self) -> str | None:
        """Jupyter shows the linkage's interactive page inline, as its html file holds it (without the files)."""
        from camgen.core.page import page_frame

        page = self.page()
        return None if page is None else page_frame(page)

    def _repr_svg_(self) -> str | None:
        """Jupyter shows the linkage at one pose with its path (strokes 0.5 mm wide), where the mechanism draws it."""
        drawing = self.mechanism.sketch(self.spec.linkage, self.kinematics)
        if drawing is None:
            return None
        from camgen.core.writers.svg import svg_document

        return svg_document(drawing, stroke_width=0.5)


def drawn_pose(kinematics: Any, table: Any, angle: float | None) -> tuple[Any, float] | None:
    """The general-linkage analysis and input value (:func:`pose_of`) a linkage is drawn from: at ``angle`` (when
    given), else 0, else the middle of a range the input reaches; None for a kind linkgen cannot draw so."""
    for value in _drawable(kinematics, angle):
        try:
            return pose_of(kinematics, table, value)
        except SpecError:                  # out of reach there: try the next
            continue
    return None


def _drawable(kinematics: Any, angle: float | None) -> list[float]:
    """Input angles (degrees) to draw a linkage at: ``angle`` (when given), 0, and the middle of each range of crank
    angles its four-bar reaches (one that does not turn fully)."""
    fourbar = getattr(kinematics, "linkage", kinematics)
    ranges = fourbar.input_ranges() if hasattr(fourbar, "input_ranges") else None
    return [a for a in (angle, 0.0) if a is not None] + [math.degrees((lo + hi) / 2) for lo, hi in ranges or ()]


def lengths(table: Any) -> dict[str, Any]:
    """The table's lengths: every number field in mm, in the table's order (a table that draws its links gives
    them itself: ``lengths_mm()``)."""
    if hasattr(table, "lengths_mm"):
        return table.lengths_mm()
    return {k: v for k, v in table.model_dump().items()
            if (type(table).model_fields[k].json_schema_extra or {}).get("unit") == "mm" and isinstance(v, float)}


def _refuse_geared(spec: LinkageSpec, kinematics: Any) -> None:
    """Refuse ``[slack]`` and ``[dynamics]`` for a linkage with gears or racks: their closures and joint forces do
    not take the higher pairs yet."""
    from linkgen.mechanisms.general import Analysis

    if not isinstance(kinematics, Analysis) or not kinematics.linkage.structure.pairs:
        return
    for key in ("slack", "dynamics"):
        if getattr(spec, key) is not None:
            raise SpecError(f"a linkage with gears or racks takes no [{key}] yet (the tooth forces of its higher pairs "
                            "are not modelled); leave it out", key)


def design_linkage(spec: LinkageSpec, angle: float | None = None, method: str = "closed",
                   parts: bool = False) -> LinkageDesign:
    """The design of a validated linkage spec: kinematics, report and, when asked, parts; nothing written.

    With a ``[kit]`` table the ground is made the base plate first, so the build, the report's ``routing`` block
    and the kit are all of the parts as made.

    Parameters
    ----------
    spec : LinkageSpec
        A validated template (:func:`linkgen.spec.load_spec`).
    angle : float, optional
        The input's angle (degrees; mm for a slide input): adds every position there to the report.
    method : {"closed", "newton"}
        How the positions at ``angle`` are solved; ``"newton"`` adds the Newton-Raphson iteration table.
    parts : bool
        Also make the parts of the ``[parts]`` table (as ``linkgen build`` does).

    Returns
    -------
    LinkageDesign
        The design; ``design.report`` is the JSON report's content.

    Raises
    ------
    SpecError
        ``angle`` lies outside the input's reachable range (the message gives the range), or ``parts`` is asked
        for without a ``[parts]`` table.
    DesignError
        The parts cannot be made as asked.
    """
    if angle is not None and not math.isfinite(angle):
        raise SpecError(f"must be a finite number of degrees (got {angle})", "--angle")
    wanted = spec.parts if parts else None          # the [parts] table when parts are asked for
    if parts and wanted is None:
        raise SpecError("missing: give a [parts] table (width, thickness, pin_diameter, ...)", "parts")
    mechanism, table = spec.mechanism, spec.linkage
    if not isinstance(table, MechanismTable):
        raise TypeError(f"{type(table).__name__} is not a [linkage] table: it has no type and rpm")
    kinematics = mechanism.build(table)
    report: dict[str, Any] = {"name": spec.name, "type": table.type, "conventions": CONVENTIONS,
                              "lengths_mm": lengths(table), "rpm": table.rpm,
                              **mechanism.report(table, kinematics, angle, method)}
    report["classification"] = classification(kinematics, table, report)
    _refuse_geared(spec, kinematics)
    statics = dynamics = None
    if spec.loads:
        posed = pose_of(kinematics, table, 0.0)
        if posed is None:
            raise SpecError(f"a {table.type} of this kind cannot be drawn as a general linkage to take loads", "loads")
        statics = statics_of(spec.loads, posed[0])
        report["statics"] = statics_report(statics, table.rpm)
    slack = None
    if spec.slack is not None:
        drawn = drawn_pose(kinematics, table, angle)
        if drawn is None:
            raise SpecError(f"a {report['type']} of this kind cannot be drawn as a general linkage to take slack",
                            "slack")
        slack = slack_of(spec.slack, spec.parts, drawn[0])
        report["slack"] = slack.report()
    if wanted is None:
        if spec.dynamics is not None:
            stack = None if spec.parts is None else Stack.of_layout(_layout(spec, kinematics), spec.parts)
            dynamics, report["dynamics"] = _dynamics(spec, kinematics, statics, stack)
        return LinkageDesign(spec, mechanism, kinematics, report, None, angle, statics, None, dynamics, slack)
    layout = mechanism.layout(table, kinematics, wanted)
    mounts: tuple[tuple[float, float], ...] = ()
    if spec.kit is not None:
        layout, mounts = base_plate(layout, spec.kit)
    build = build_parts(layout, wanted, spec.output.elephant_foot)
    kit = None if spec.kit is None else linkage_kit(spec, layout, mounts, build)
    if spec.dynamics is not None:
        dynamics, report["dynamics"] = _dynamics(spec, kinematics, statics, Stack.of_build(build))
        if dynamics.flywheel is not None and kit is None:
            build = flywheel_build(build, dynamics)
    add_routing(report, build.cut, spec.output.tool_radius)
    return LinkageDesign(spec, mechanism, kinematics, report, build, angle, statics, kit, dynamics, slack)


def _layout(spec: LinkageSpec, kinematics: Any) -> Any:
    """The mechanism's layout of its ``[parts]`` (with a kit's base plate), as a build makes it: the layer order the
    dynamics' pins and spacers stack by; a :class:`SpecError` on ``dynamics`` for a mechanism that makes no parts."""
    assert spec.parts is not None
    try:
        layout = spec.mechanism.layout(spec.linkage, kinematics, spec.parts)
    except SpecError as exc:
        raise SpecError(f"{exc.detail}, so its masses cannot come from [parts]: give each link's mass, centre and "
                        "inertia in [dynamics.links.<link>] and leave [parts] out", "dynamics") from None
    return layout if spec.kit is None else base_plate(layout, spec.kit)[0]


def _dynamics(spec: LinkageSpec, kinematics: Any, statics: Statics | None,
              stack: Stack | None) -> tuple[Dynamics, dict[str, Any]]:
    """The dynamics of the ``[dynamics]`` table and the report's section of it, on the linkage drawn as a general
    one (from the first input angle it reaches of 0 and the middles of its ranges), with the loads of ``[[loads]]``
    and the pins and spacers of ``stack``."""
    from linkgen.dynamics.run import dynamics_of

    table: Any = spec.linkage
    forces, torques = ((), ()) if statics is None else (statics.forces, statics.torques)
    assert spec.dynamics is not None
    dynamics = dynamics_of(spec.dynamics, general_drawing(kinematics, table), spec.parts, table.rpm, forces,
                           torques, spec.kit, stack)
    return dynamics, dynamics_report(dynamics, table.rpm)


def general_drawing(kinematics: Any, table: Any) -> Any:
    """The general-linkage analysis the dynamics runs on (:func:`pose_of`, drawn at the first input angle it
    reaches of 0 and the middles of its ranges): its links and joints are what ``[dynamics]`` names; a
    :class:`SpecError` on ``dynamics`` for a kind it cannot draw."""
    posed = drawn_pose(kinematics, table, None)
    if posed is not None:
        return posed[0]
    why = ", driven by its rocker," if getattr(table, "input", "crank") != "crank" else ""
    raise SpecError(f"linkgen computes the dynamics of a linkage drawn as a general one, which this {table.type}"
                    f"{why} is not: drive it by its crank, or draw it as type = \"linkage\"", "dynamics")


def pose_of(kinematics: Any, table: Any, angle: float) -> tuple[Any, float] | None:
    """The general-linkage analysis and input value (rad, or mm for a slide) that show the linkage at input
    ``angle`` (degrees, or mm): the dedicated mechanisms drawn there as general linkages
    (:mod:`linkgen.kinematics.equivalents`); None for a kind it cannot draw (a rocker-driven four-bar, a
    mechanism registered from outside)."""
    from linkgen.kinematics import equivalents
    from linkgen.kinematics.fourbar import FourBar
    from linkgen.kinematics.quickreturn import CrankShaper, Whitworth
    from linkgen.kinematics.slidercrank import ScotchYoke, SliderCrank
    from linkgen.kinematics.straightline import StraightLine
    from linkgen.kinematics.structure import Structure
    from linkgen.mechanisms.general import Analysis, analysis_of

    if isinstance(kinematics, Analysis):
        return kinematics, (math.radians(angle) if kinematics.crank else angle)
    theta = math.radians(angle)
    if isinstance(kinematics, StraightLine):
        drawn, traced = equivalents.fourbar(kinematics.linkage, theta, kinematics.assembly), ("P",)
    elif isinstance(kinematics, FourBar) and getattr(table, "input", "crank") == "crank":
        drawn = equivalents.fourbar(kinematics, theta, table.assembly)
        traced = ("P",) if kinematics.point_distance > 0 else ("B",)
    else:
        make: dict[type, tuple[Callable[[Any, float], Structure], str]] = {
            SliderCrank: (equivalents.slider_crank, "B"), ScotchYoke: (equivalents.scotch_yoke, "Y"),
            CrankShaper: (equivalents.crank_shaper, "R"), Whitworth: (equivalents.whitworth, "D")}
        if type(kinematics) not in make:
            return None
        draw, point = make[type(kinematics)]
        drawn, traced = draw(kinematics, theta), (point,)
    analysis = analysis_of(drawn, traced)
    return analysis, float(analysis.linkage.drawn_inputs[0])


def classification(kinematics: Any, table: Any, report: dict[str, Any]) -> dict[str, Any]:
    """The course's class(es) of the mechanism by the motion it transforms (:mod:`linkgen.mechanisms.classify`):
    from its kinematics drawn as a general linkage where it can be, else from its own figures in ``report``."""
    from linkgen.mechanisms import classify

    try:
        posed = pose_of(kinematics, table, 0.0)
    except SpecError:                   # the input does not reach 0: classified from its own figures
        posed = None
    earned = classify.of_analysis(posed[0]) if posed is not None else classify.of_report(table.type, report)
    return classify.report(earned)


def analyze(spec: LinkageSpec, angle: float | None = None, method: str = "closed") -> dict[str, Any]:
    """The report of a validated linkage spec: :func:`design_linkage` without parts, its ``report``.

    Parameters
    ----------
    spec : LinkageSpec
        A validated template.
    angle : float, optional
        The input's angle (degrees): adds the positions there.
    method : {"closed", "newton"}
        How those positions are solved.

    Returns
    -------
    dict
        The report, as ``<name>.json`` holds it.

    Raises
    ------
    SpecError
        ``angle`` lies outside the input's reachable range (the message gives the range).
    """
    return design_linkage(spec, angle, method).report
