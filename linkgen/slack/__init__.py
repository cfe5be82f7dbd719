"""How a linkage's slack blurs its motion (``[slack]``): the worst-case band round every tracer's path and every
output's angle or travel that its pins' play in their holes and its links' length tolerances allow, where it
binds, and a Monte Carlo check of the band (see docs/guides/slack.md).

:func:`slack_of` makes a :class:`Slack` from the ``[slack]`` table, the ``[parts]`` table (the holes) and the
linkage's general-linkage analysis (a dedicated mechanism's general drawing,
:func:`linkgen.linkage_design.pose_of`); :mod:`linkgen.slack.report` gives the report's section,
:mod:`linkgen.slack.figure` the figure and the page's band. The first-order response itself is
:mod:`linkgen.kinematics.sensitivity`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from linkgen.slack.table import Play, SlackTable

if TYPE_CHECKING:
    from linkgen.mechanisms.general import Analysis
    from linkgen.slack.band import SlackBand
    from linkgen.slack.montecarlo import MonteCarlo
    from linkgen.spec import PartsTable

__all__ = ["Play", "Slack", "SlackTable", "slack_of"]


@dataclass(frozen=True)
class Slack:
    """A linkage's band under its slack and its Monte Carlo check (None with ``monte_carlo = 0``), with the
    ``[slack]`` table they were made from."""

    table: SlackTable
    band: SlackBand
    monte_carlo: MonteCarlo | None

    def report(self) -> dict[str, Any]:
        """The report's ``slack`` section (mm and degrees)."""
        from linkgen.slack.report import slack_report

        return slack_report(self.band, self.table, self.monte_carlo)


def slack_of(table: SlackTable, parts: PartsTable | None, analysis: Analysis) -> Slack:
    """The band of the linkage ``analysis`` draws under the slack of ``table`` with the holes of ``parts``, and its
    Monte Carlo check.

    Raises
    ------
    SpecError
        Naming the field: no ``[parts]`` table, a clearance not less than the pin, a link the linkage has not, a
        linkage of more than one input or with redundant constraints.
    """
    from camgen.core.errors import SpecError
    from linkgen.slack.band import slack_band
    from linkgen.slack.montecarlo import monte_carlo

    try:
        play = table.play(parts)
    except ValueError as exc:
        field, _, detail = str(exc).partition(": ")
        raise SpecError(detail, field) from None
    band = slack_band(table, play, analysis)
    mc = monte_carlo(band, table.monte_carlo, table.seed) if table.monte_carlo else None
    return Slack(table, band, mc)
