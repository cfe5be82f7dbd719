"""The ``gif`` output format: off by default, written beside the page as ``<name>-animation.gif`` with the bytes
``animate`` writes by default and listed as ``gif`` in the report's files; a design ``animate`` refuses is refused
in one line when the format is asked of it, nothing written."""
from __future__ import annotations

import json

from click.testing import CliRunner

from camgen.cli import main as camgen_main
from camgen.core.writers import DEFAULT_FORMATS, FORMATS
from linkgen.cli import main as linkgen_main
from tests.conftest import ROOT
from tests.support.refusals import assert_refused_sets


def test_gif_is_a_format_off_by_default():
    assert "gif" in FORMATS and "gif" not in DEFAULT_FORMATS


def test_build_writes_the_default_animation(tmp_path):
    template = str(ROOT / "templates" / "plate.toml")
    built = CliRunner().invoke(camgen_main, ["build", template, "-o", str(tmp_path / "b"), "--set",
                                             'output.formats=["json", "gif"]'])
    assert built.exit_code == 0, built.output
    plain = CliRunner().invoke(camgen_main, ["build", template, "-o", str(tmp_path / "c"), "--set",
                                             'output.formats=["json"]'])
    assert plain.exit_code == 0, plain.output
    animated = CliRunner().invoke(camgen_main, ["animate", template, "-o", str(tmp_path / "a")])
    assert animated.exit_code == 0, animated.output
    name = "plate-animation.gif"
    assert (tmp_path / "b" / name).read_bytes() == (tmp_path / "a" / name).read_bytes()
    assert json.loads((tmp_path / "b" / "plate.json").read_text())["files"]["gif"] == name
    assert not list((tmp_path / "c").glob("*.gif"))


def test_gif_of_a_linkage_animate_refuses(tmp_path):
    assert_refused_sets(ROOT / "templates" / "counter.toml", ['output.formats=["json", "gif"]'],
                        "linkage.type: linkgen animates", tmp_path, linkgen_main, "analyze")
