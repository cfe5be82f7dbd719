"""The ``[slack]`` table: how loose a linkage's joints are and how far its links' lengths may be off, and how the
band they give is checked (see :mod:`linkgen.slack`)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

from pydantic import Field, field_validator
from pydantic.json_schema import JsonDict

from camgen.core.parts import Allowances
from camgen.core.spec import Model, unit

if TYPE_CHECKING:
    from linkgen.spec import PartsTable

#: the largest length tolerance and measured clearance a template may give (mm)
MAX_SLACK_MM = 5.0
#: the most Monte Carlo samples a template may ask for (each is a solve of the whole motion)
MAX_SAMPLES = 10_000


def _unit(name: str, absent: str = "") -> JsonDict:
    """:func:`camgen.core.spec.unit`, typed as pydantic's ``json_schema_extra`` takes it."""
    extra: JsonDict = {**unit(name, absent=absent)}
    return extra


class SlackTable(Model):
    """``[slack]``: the play of every pin in its holes (from the ``[parts]`` table: its pin diameter, clearance and
    kerf, or a measured clearance) and the tolerance of every link's lengths give a worst-case band round each
    tracer's path and each output's angle or travel; Monte Carlo samples check it."""

    length_tolerance: float = Field(0.05, ge=0, le=MAX_SLACK_MM, description="each link's lengths lie within +- "
                                    "this: a bar's hole distance, a plate's distances from its first hole, a slot's "
                                    "line across its guide", json_schema_extra=_unit("mm"))
    links: dict[str, float] = Field(default_factory=dict, description="a link's own length tolerance, by the link's "
                                    "name: [slack.links] crank = 0.02 (ground for the frame)",
                                    json_schema_extra=_unit("mm"))
    process: Literal["cut", "printed"] = Field("cut", description="how the holes are made: cut (the cut file's "
                                               "holes, opened by the kerf the laser burns) or printed (the printed "
                                               "parts' holes)")
    clearance: float | None = Field(None, ge=0, le=MAX_SLACK_MM, description="the clearance the holes really have, "
                                    "hole less pin diameter, as measured (a fit-test coupon); less than the pin's "
                                    "diameter", json_schema_extra=_unit("mm", "as [parts] makes them: parts.clearance"))
    monte_carlo: int = Field(200, ge=0, le=MAX_SAMPLES, description="Monte Carlo samples checking the band, each a "
                             "linkage with its pins and lengths drawn at random within their slack (0: none)")
    seed: int = Field(1, ge=0, description="seed of the Monte Carlo samples: the same seed gives the "
                      "same samples")

    @field_validator("links")
    @classmethod
    def _links(cls, links: dict[str, float]) -> dict[str, float]:
        for name, value in links.items():
            if isinstance(value, bool) or not 0 <= value <= MAX_SLACK_MM:
                raise ValueError(f"{name}: must be >= 0 and <= {MAX_SLACK_MM:g} mm (got {value!r})")
        if len(links) > 100:
            raise ValueError("at most 100 links")
        return links

    def play(self, parts: PartsTable | None) -> Play:
        """The holes as made and the pins' play in them, from ``parts``; a ValueError naming the field (for the
        template's one-line error) without parts, or where the clearance is not less than the pin."""
        if parts is None:
            raise ValueError("slack: the joints' play comes from the [parts] table's pin_diameter, clearance and "
                             "kerf: add a [parts] table")
        return play_of(self, parts)


@dataclass(frozen=True)
class Play:
    """The pins' fit in their holes (mm): the process, the pin's diameter, the hole as its file draws it and as
    made, and whether the hole was measured (``slack.clearance``) rather than derived from ``[parts]``."""

    process: str
    pin: float
    drawn: float
    made: float
    measured: bool

    @property
    def radial(self) -> float:
        """The play r = (hole - pin) / 2: how far a pin's centre may sit from its hole's (mm)."""
        return (self.made - self.pin) / 2


def play_of(table: SlackTable, parts: PartsTable) -> Play:
    """The holes ``parts`` makes by ``table.process`` and the pins' play in them (mm).

    A hole is pin + clearance (nominal); the parts layer's allowances (:class:`camgen.core.parts.Allowances`, as
    :func:`linkgen.parts.build_parts` applies them) draw it nominal - kerf in the cut file, which the laser burns
    open by its kerf, and nominal in the printed part: both come out nominal, so the process names the file whose
    hole is meant, and a measured ``slack.clearance`` says what a machine really makes."""
    allowances = Allowances(kerf=parts.kerf, clearance=0.0, kerf_field="parts.kerf")
    nominal = parts.pin_diameter + parts.clearance
    if table.process == "cut":
        drawn = allowances.cut_diameter(nominal)
        made = drawn + parts.kerf
    else:
        drawn = allowances.printed_diameter(nominal)
        made = drawn
    if table.clearance is not None:
        made = parts.pin_diameter + table.clearance
    field = "slack.clearance" if table.clearance is not None else "parts.clearance"
    clearance = made - parts.pin_diameter
    if not clearance < parts.pin_diameter:
        raise ValueError(f"{field}: with [slack], must be >= 0 and < the pin's diameter ({parts.pin_diameter:g} mm): "
                         f"a pin in a hole more than twice its size is no joint (got {clearance:g})")
    return Play(table.process, parts.pin_diameter, drawn, made, table.clearance is not None)
