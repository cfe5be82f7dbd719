"""``camgen animate`` of a machine: every mechanism over one turn of the main shaft; one GIF of the asked frames and
size, the same bytes twice; a frame count its page's 360 frames cannot give refused in one line."""
from __future__ import annotations

from camgen.cli import main
from tests.conftest import ROOT
from tests.support.kind_animation import assert_animated

MACHINE = ROOT / "templates" / "automaton.toml"


def test_machine_gif(tmp_path):
    assert_animated(MACHINE, tmp_path)


def test_frames_not_dividing_360_refused(tmp_path):
    from click.testing import CliRunner

    result = CliRunner().invoke(main, ["animate", str(MACHINE), "-o", str(tmp_path / "out"), "--frames", "7"])
    assert result.exit_code == 2
    assert result.output.startswith("error: --frames: a machine's animation shows its page's 360 frames: give one "
                                    "of 2, 3, 4, 5, 6, 8, 9, 10, 12") and result.output.count("\n") == 1
    assert not (tmp_path / "out").exists()
