"""camgen.core.records.once: a value computed once and kept."""
import dataclasses

from camgen.core.records import once


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
