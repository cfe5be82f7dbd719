"""Every bundled template gives the files recorded in tests/data/golden.json, byte for byte.

A change that alters an output on purpose re-records them with ``python -m tests.golden``
and says so in its commit; any other difference is a regression. Figures drawn by
matplotlib are compared only by name (see :mod:`tests.golden`).
"""
from __future__ import annotations

import json

from tests.golden import GOLDEN, build_all


def test_bundled_templates_give_the_recorded_files(tmp_path):
    recorded = json.loads(GOLDEN.read_text())
    built = build_all(tmp_path)
    assert sorted(built) == sorted(recorded)
    for run_id, files in recorded.items():
        assert sorted(built[run_id]) == sorted(files), run_id
        for name, digest in files.items():
            if digest.endswith(" figure"):
                continue
            assert built[run_id][name] == digest, f"{run_id}: {name} differs from the recorded file"
