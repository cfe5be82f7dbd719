"""camgen.core.records.unchecked: the frozen dataclasses a design makes without their __init__ hold what
their own constructor gives them."""
import dataclasses

import pytest

from camgen.analysis import CamAnalysis
from camgen.bench import _template
from camgen.core.parts import Allowances, Part
from camgen.core.records import unchecked
from camgen.design import CamDesign, design_cam
from camgen.program import Jump, Segment


def test_defaults_filled_and_equal_to_the_constructor():
    made = unchecked(Allowances, kerf=0.2, clearance=0.3)
    assert made == Allowances(0.2, 0.3)
    assert made.kerf_field == "kerf" and made.elephant_foot == 0.0
    jump = unchecked(Jump, at_deg=120.0, order=3, jump=-85.9, inside=False)
    assert jump == Jump(at_deg=120.0, order=3, jump=-85.9, inside=False)


def test_missing_and_unknown_fields_refused():
    with pytest.raises(TypeError, match="at_deg"):
        unchecked(Jump, order=3, jump=1.0, inside=False)
    with pytest.raises(TypeError, match="atdeg"):
        unchecked(Jump, atdeg=1.0, order=3, jump=1.0, inside=False)


@pytest.mark.parametrize("law", ["cycloidal", "harmonic", "modified-trapezoid"])
def test_a_design_holds_exactly_the_fields_its_classes_declare(law):
    design = design_cam(_template(law))
    objects = [design, design.analysis, design.allowances, design.part, design.cut, design.printed,
               *design.jumps, *design.cam.program.segments]
    for obj in objects:
        names = [f.name for f in dataclasses.fields(obj)]
        assert {k: v for k, v in obj.__dict__.items() if k in names}.keys() == set(names), type(obj)
        # the constructor accepts those values (no field left to a default the fast path missed)
        again = type(obj)(**{name: getattr(obj, name) for name in names})
        assert [getattr(again, n) is getattr(obj, n) for n in names] == [True] * len(names), type(obj)
    assert isinstance(design, CamDesign) and isinstance(design.analysis, CamAnalysis)
    assert isinstance(design.part, Part) and all(isinstance(s, Segment) for s in design.cam.program.segments)


def test_class_variables_are_no_fields():
    from dataclasses import dataclass
    from typing import ClassVar

    @dataclass(frozen=True)
    class Held:
        KIND: ClassVar[str] = "held"
        value: float
        unit: str = "mm"

    made = unchecked(Held, value=2.5)
    assert made == Held(2.5) and made.KIND == "held"
