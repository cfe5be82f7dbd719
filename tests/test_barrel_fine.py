"""barrel.toml and barrel-conical.toml at 1e-4 mm (some 0.87 million triangles each): the STL read back is one closed
outward solid of the exact volume (tests/test_barrel_tolerances.py; the other two templates in
tests/test_barrel_fine_oscillating.py, to keep each file under a minute)."""
from __future__ import annotations

import pytest

from tests.test_barrel_tolerances import assert_exact_solid


@pytest.mark.parametrize("name", ["barrel", "barrel-conical"])
def test_a_barrel_at_1e_4_mm_is_a_closed_solid_of_its_exact_volume(tmp_path, name):
    assert_exact_solid(tmp_path, name, 1e-4)
