"""camgen.core.records.record_maker: the frozen dataclasses a design makes without their __init__ hold what
their own constructor gives them; camgen.core.records.once: a value computed once and kept."""
import dataclasses

import pytest

from camgen.analysis import CamAnalysis
from camgen.bench import _template
from camgen.core.parts import Allowances, Part
from camgen.core.records import once, record_maker
from camgen.design import CamDesign, design_cam
from camgen.program import Jump, Segment


def test_defaults_filled_and_equal_to_the_constructor():
    made = record_maker(Allowances)(kerf=0.2, clearance=0.3)
    assert made == Allowances(0.2, 0.3)
    assert made.kerf_field == "kerf" and made.elephant_foot == 0.0
    jump = record_maker(Jump)(at_deg=120.0, order=3, jump=-85.9, inside=False)
    assert jump == Jump(at_deg=120.0, order=3, jump=-85.9, inside=False)


def test_missing_and_unknown_fields_refused():
    with pytest.raises(TypeError, match="at_deg"):
        record_maker(Jump)(order=3, jump=1.0, inside=False)
    with pytest.raises(TypeError, match="atdeg"):
        record_maker(Jump)(atdeg=1.0, order=3, jump=1.0, inside=False)


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

    made = record_maker(Held)(value=2.5)
    assert made == Held(2.5) and made.KIND == "held"


def test_once_computes_a_value_when_first_read_and_keeps_it():
    """A frozen dataclass's value made on first read, kept in its __dict__ under the property's name (the
    descriptor is not called again), each instance its own; the class gives the descriptor with the docstring."""
    calls = []

    @dataclasses.dataclass(frozen=True)
    class Box:
        side: float

        @once
        def area(self) -> float:
            """The square of the side."""
            calls.append(self.side)
            return self.side * self.side

    a, b = Box(3.0), Box(0.5)
    assert vars(a) == {"side": 3.0}
    assert a.area == 9.0 and a.area == 9.0 and vars(a) == {"side": 3.0, "area": 9.0}
    assert b.area == 0.25 and calls == [3.0, 0.5]
    assert isinstance(Box.area, once) and Box.area.__doc__ == "The square of the side."
    assert a == Box(3.0) and dataclasses.replace(a, side=2.0).area == 4.0 and calls == [3.0, 0.5, 2.0]


def test_a_record_maker_binds_the_fields_by_keyword_and_checks_nothing_else():
    """record_maker(cls) takes every field by keyword (those with a plain default optional, a default factory's
    field required), refuses a missing or unknown one by Python's own binding, names it, and sets the instance's
    __dict__ to the fields in their order, whatever the fields are called (its own names are prefixed)."""
    @dataclasses.dataclass(frozen=True)
    class Odd:
        out: float
        cls: str = "c"
        scope: tuple = dataclasses.field(default_factory=tuple)
        last: int = 7

    make = record_maker(Odd)
    assert record_maker(Odd) is make and make.__name__ == "Odd"
    made = make(scope=(1,), out=2.5)
    assert made == Odd(2.5, "c", (1,), 7) and list(vars(made)) == ["out", "cls", "scope", "last"]
    assert make(out=1.0, cls="k", scope=(), last=3) == Odd(1.0, "k", (), 3)
    with pytest.raises(TypeError, match="scope"):
        make(out=1.0)
    with pytest.raises(TypeError, match="colour"):
        make(out=1.0, scope=(), colour="red")
    with pytest.raises(TypeError):
        make(1.0, scope=())                         # by keyword only
