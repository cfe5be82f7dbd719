"""A Geneva drive is not mounted on a machine's shafts yet (issue 35): a mount naming one is refused in one line, and
nothing is written."""
from __future__ import annotations

from tests.conftest import ROOT
from tests.support.refusals import assert_refused


def test_a_geneva_drive_as_a_mount_is_refused_in_one_line(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(f"""
name = "indexer"

[machine]
main = "camshaft"
rpm = 30.0

[[shafts]]
name = "camshaft"
at = [0.0, 0.0]

[[cams]]
name = "index"
shaft = "camshaft"
template = "{ROOT / 'templates' / 'geneva4.toml'}"
""")
    assert_refused(path, {}, "cams[0].template: a cam template; a Geneva drive is not mounted on a machine's shafts "
                   "yet (make it with its own camgen build)", tmp_path)
