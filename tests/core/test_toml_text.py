"""The one TOML writer (camgen.core.toml_text): every bundled template and every starter reads back to its values,
numbers in full, numpy scalars as plain numbers, a non-finite number refused."""
from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from camgen.core.toml_text import dumps, toml_value
from tests.conftest import ROOT


def test_every_bundled_template_reads_back_to_its_values():
    for path in sorted((ROOT / "templates").glob("*.toml")):
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
        assert tomllib.loads(dumps(raw, f"from {path.name}")) == raw, path.name


def test_numbers_are_written_in_full_and_numpy_scalars_as_plain_numbers():
    x = math.pi * 1e-7
    raw = {"name": "n", "cam": {"base_radius": np.float64(x), "teeth": np.int64(12), "flag": np.bool_(True),
                                 "list": [np.float32(0.5), 1, 2.0], "inline": [{"a b": 1.0}]}}
    text = dumps(raw)
    back = tomllib.loads(text)
    assert back["cam"]["base_radius"] == x and type(back["cam"]["base_radius"]) is float
    assert back["cam"]["teeth"] == 12 and back["cam"]["flag"] is True
    assert back["cam"]["list"] == [0.5, 1, 2.0]
    assert back["cam"]["inline"] == [{"a b": 1.0}]
    assert "np." not in text


def test_the_comment_comes_first_and_the_text_ends_in_one_newline():
    text = dumps({"name": "x", "linkage": {"joints": {"O-A": [0.0, 1.0]}}}, "first\nsecond")
    assert text.startswith("# first\n# second\nname = \"x\"\n\n[linkage]\n\n[linkage.joints]\nO-A = [0.0, 1.0]\n")
    assert text.endswith("]\n") and not text.endswith("\n\n")


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan, np.float64("nan")])
def test_a_number_that_is_not_finite_is_refused(bad):
    with pytest.raises(ValueError, match="finite"):
        toml_value(bad)
    with pytest.raises(ValueError, match="finite"):
        dumps({"cam": {"lift": [1.0, bad]}})


def test_a_value_with_no_toml_form_is_refused():
    with pytest.raises(TypeError, match="no TOML form for object"):
        toml_value(object())
