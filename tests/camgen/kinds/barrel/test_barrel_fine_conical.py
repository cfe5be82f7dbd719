"""barrel-conical.toml at 1e-4 mm (0.87 million triangles): the STL read back is one closed outward solid of the
exact volume (tests/camgen/kinds/barrel/test_barrel_tolerances.py)."""
from __future__ import annotations

from tests.camgen.kinds.barrel.test_barrel_tolerances import assert_exact_solid


def test_a_barrel_for_a_cone_at_1e_4_mm_is_a_closed_solid_of_its_exact_volume(tmp_path):
    assert_exact_solid(tmp_path, "barrel-conical", 1e-4)
