"""barrel.toml (0.87 million triangles) and barrel-rib.toml at 1e-4 mm: the STL read back is one closed outward solid
of the exact volume (tests/camgen/kinds/barrel/test_barrel_tolerances.py; barrel-conical.toml and
barrel-oscillating.toml in tests/camgen/kinds/barrel/test_barrel_fine_conical.py and
tests/camgen/kinds/barrel/test_barrel_fine_oscillating.py, to keep each file within a minute)."""
from __future__ import annotations

import pytest

from tests.camgen.kinds.barrel.test_barrel_tolerances import assert_exact_solid


@pytest.mark.parametrize("name", ["barrel", "barrel-rib"])
def test_a_groove_or_a_rib_at_1e_4_mm_is_a_closed_solid_of_its_exact_volume(tmp_path, name):
    assert_exact_solid(tmp_path, name, 1e-4)
