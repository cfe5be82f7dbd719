"""A nest's search leaves out the rotations that cannot win (camgen.core.nesting._least_used): the layouts are the
ones the search of every rotation finds, part for part, and the bound is a true lower bound of what each rotation
keeps."""
from __future__ import annotations

import numpy as np
import pytest

from camgen.core import nesting
from camgen.core.nesting import SheetRules, nest, rotations_of
from tests.core.test_nesting import _mixed

CASES = [((200.0, 150.0), 2.5, 90.0, 9), ((120.0, 300.0), 1.0, 45.0, 7), ((400.0, 100.0), 4.0, 30.0, 12),
         ((90.0, 90.0), 2.0, 90.0, 10)]


@pytest.mark.parametrize(("size", "gap", "step", "count"), CASES)
def test_a_pruned_nest_is_the_nest_of_every_rotation(monkeypatch, size, gap, step, count):
    """Parts of three shapes (concave, holed, round-ended) at quarter, eighth and twelfth turns, on one sheet or
    several: the same parts at the same rotations and shifts, on the same sheets, as when no rotation is left out,
    with fewer footprints asked for."""
    parts = _mixed(count)
    rules = SheetRules(size, gap, rotations_of(step, False), "sheet")
    searched: list[int] = []
    made = nesting._Footprints.get

    def counted(self, i, flat, k, grid):
        searched.append(k)
        return made(self, i, flat, k, grid)

    monkeypatch.setattr(nesting._Footprints, "get", counted)
    pruned = nest(parts, rules)
    fewer = len(searched)
    searched.clear()
    monkeypatch.setattr(nesting, "_least_used", lambda bounds, ends: 0.0)      # every rotation searched
    full = nest(parts, rules)
    assert pruned == full
    assert fewer < len(searched)                     # some rotation was left out unmade (1 % to 15 % here)


def test_the_bound_is_at_most_what_any_free_position_keeps():
    """For a half-filled sheet, every free position of every rotation keeps a layout rectangle (rounded as the
    search rounds it) no smaller than the rotation's bound; on an empty sheet the bound is the part's box."""
    parts = _mixed(6)
    rules = SheetRules((200.0, 150.0), 2.0, rotations_of(30, False), "sheet")
    cell = max(nesting.MIN_CELL_MM, np.sqrt(200.0 * 150.0 / nesting.MAX_CELLS))
    grid = nesting._Grid(rules, cell)
    flats = [nesting._Flat.of(p, rules) for p in parts]
    for flat in flats[:3]:                                   # three parts placed in the corner, one above another
        k, shift = nesting._best_spot(grid, flat, "down", nesting._Footprints(0), 0) or (0, None)
        assert shift is not None
        nesting._occupy(grid, nesting._shift(flat.polygon(k), shift), flat.grow)
    window = grid.shape
    overlap = nesting._Overlap(grid, window)
    for flat in flats[3:]:
        for k, b in enumerate(flat.bounds.tolist()):
            _, mask = flat.footprint(k, grid)
            free = np.argwhere(overlap.free(mask))
            assert len(free)
            right = free[:, 1] * grid.cell + (b[2] - b[0])
            top = free[:, 0] * grid.cell + (b[3] - b[1])
            used = np.round(np.maximum(right, grid.ends[0]) * np.maximum(top, grid.ends[1]), 6)
            assert used.min() >= nesting._least_used(b, grid.ends)
    empty = nesting._Grid(rules, cell)
    assert nesting._least_used([0.0, 0.0, 30.0, 20.0], empty.ends) == 600.0
