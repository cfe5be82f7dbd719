"""barrel-oscillating.toml at 1e-4 mm (1.1 million triangles): the STL read back is one closed outward solid of the
exact volume (tests/camgen/kinds/barrel/test_barrel_tolerances.py)."""
from __future__ import annotations

from tests.camgen.kinds.barrel.test_barrel_tolerances import assert_exact_solid


def test_a_barrel_with_an_arm_at_1e_4_mm_is_a_closed_solid_of_its_exact_volume(tmp_path):
    assert_exact_solid(tmp_path, "barrel-oscillating", 1e-4)
