"""Each ``[cam]`` kind owns its table and its spec (``camgen/kinds/<kind>/table.py``), and validation is dispatched by
the registry alone: ``camgen.spec`` and ``camgen.tables`` name no kind, a template loads no other kind's table, the
spec of each kind says how its cam carries its follower (the plate's and the barrel's roller against values worked
out by hand from their templates), and the conjugate pair's rule across its tables (the second roller's keys by the
follower's type) is its spec's, with its message."""
from __future__ import annotations

import ast
import json
import math
import subprocess
import sys
import tomllib

import pytest

from camgen.core.errors import SpecError
from camgen.flat import build_cam
from camgen.followers.plate import PlateRoller
from camgen.kinds import KINDS
from camgen.kinds.base import CAM_TABLE
from camgen.spec import CamSpec, cam_specs, load_spec, validate_spec
from tests.conftest import ROOT

#: the kinds chosen by ``cam.kind``, as the registry holds them
CAM_KINDS = [name for name, kind in KINDS.items() if kind.table_key == CAM_TABLE]


def _names_imported(path) -> set[str]:
    """Every module a source file imports, at any depth (``from a.b import c`` gives ``a.b``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module:
            found.add(node.module)
    return found


def test_each_cam_kind_s_table_and_spec_are_in_its_own_package():
    assert CAM_KINDS == ["disc", "plate", "grooved", "barrel", "conjugate"]
    specs = cam_specs()
    assert list(specs) == CAM_KINDS
    for name, spec in specs.items():
        table = spec.model_fields["cam"].annotation
        assert spec.__module__ == table.__module__ == f"camgen.kinds.{name}.table", name
        assert issubclass(spec, CamSpec) and spec is KINDS[name].spec
        assert table.model_fields["kind"].annotation.__args__ == (name,)       # Literal["<name>"]
        assert table.model_config["extra"] == "forbid" and table.model_config["title"] == KINDS[name].title


@pytest.mark.parametrize("module", ["camgen/spec.py", "camgen/tables/__init__.py", "camgen/tables/followers.py",
                                    "camgen/tables/rows.py", "camgen/flat.py", "camgen/profile.py",
                                    "camgen/outputs.py"])
def test_the_shared_modules_name_no_kind(module):
    """No shared module imports a kind's package (the registry, ``camgen.kinds``, and what every kind declares,
    ``camgen.kinds.base``, are not kinds), nor names a kind's table or spec."""
    imported = _names_imported(ROOT / module)
    kinds = {m for m in imported if m.startswith("camgen.kinds.") and m != "camgen.kinds.base"}
    assert not kinds, kinds
    tree = ast.parse((ROOT / module).read_text(encoding="utf-8"))
    used = ({n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
            | {a.name for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) for a in n.names})
    named = {f"{name.capitalize()}{what}" for name in CAM_KINDS for what in ("Table", "Spec")} & used
    assert not named, named


def test_the_flow_contract_ignores_no_import():
    """The layers hold as written: the contract lists no import it lets through."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    flow = next(c for c in config["tool"]["importlinter"]["contracts"] if c["id"] == "flow")
    assert "camgen.kinds : camgen.spec" in flow["layers"] and not flow.get("ignore_imports")


@pytest.mark.parametrize("template, kind", [("rdrd", "disc"), ("plate", "plate"), ("grooved", "grooved"),
                                            ("barrel", "barrel"), ("conjugate", "conjugate")])
def test_a_template_loads_its_own_kind_s_table_and_no_other(template, kind):
    """Validation asks the registry for the kind and validates with that kind's spec alone: no other kind's table
    module is imported (each in a fresh interpreter)."""
    path = str(ROOT / "templates" / f"{template}.toml")
    code = (f"import sys, json\nfrom camgen.spec import load_spec\nspec = load_spec({path!r})\n"
            "print(json.dumps([type(spec).__module__, sorted(m for m in sys.modules "
            "if m.startswith('camgen.kinds.') and m.endswith('.table'))]))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True)
    module, tables = json.loads(out.stdout.splitlines()[-1])
    assert module == f"camgen.kinds.{kind}.table" and tables == [module]


def test_a_plate_cam_s_roller_rides_over_the_sliding_plate():
    """templates/plate.toml: base_radius 20 mm (the plate's height), roller 8 mm, travel 200 mm."""
    cam = build_cam(load_spec(ROOT / "templates" / "plate.toml"))
    assert cam.follower == PlateRoller(20.0, 8.0, 200.0) and cam.base_radius == 20.0


def test_a_barrel_s_roller_rides_on_its_developed_pitch_cylinder():
    """templates/barrel.toml: length 50 mm, a rise of 20 mm from 0, so the roller's centre rests at z0 = (50 - 20) / 2
    = 15 mm; the developed plate is 2 pi 30 mm long and its height under the 5 mm roller z0 - 5 = 10 mm. A barrel has
    no base circle: the cam is built on that height instead."""
    spec = load_spec(ROOT / "templates" / "barrel.toml")
    cam = build_cam(spec)
    assert spec.base_circle is None and math.isinf(spec.prime_radius)
    assert cam.base_radius == pytest.approx(10.0, abs=1e-12) == spec.rest_height(5.0)
    assert isinstance(cam.follower, PlateRoller)
    assert (cam.follower.base_height, cam.follower.roller_radius) == pytest.approx((10.0, 5.0), abs=1e-12)
    assert cam.follower.travel == pytest.approx(2 * math.pi * 30.0, rel=1e-15)


@pytest.mark.parametrize("template, key, value, owner", [
    ("conjugate", "arm_angle", 80.0, "an oscillating-roller"),
    ("conjugate", "second_arm_length", 90.0, "an oscillating-roller"),
    ("conjugate-arm", "yoke_span", 130.0, "a translating-roller"),
])
def test_the_second_roller_s_keys_are_the_follower_type_s(template, key, value, owner):
    """A key of the second roller that the follower's type does not take is refused by the conjugate spec's own
    rules, in one line naming it and the type it is for."""
    raw = tomllib.loads((ROOT / "templates" / f"{template}.toml").read_text(encoding="utf-8"))
    raw["cam"][key] = value
    with pytest.raises(SpecError) as refused:
        validate_spec(raw)
    assert str(refused.value) == f"cam.{key}: only for a conjugate cam with {owner} follower"


def test_a_kind_s_rule_is_checked_where_it_was_before_the_shared_hub_checks():
    """The kind's rules run inside the shared validation, after the motion's and before the hub's, as before the
    tables moved: a conjugate template with a yoke's arm_angle and a keyway on a 5 mm bore is refused for the
    arm_angle (a separate after-validator of the kind's spec would run after the hub's and name the keyway)."""
    raw = tomllib.loads((ROOT / "templates" / "conjugate.toml").read_text(encoding="utf-8"))
    raw["cam"].update(arm_angle=80.0, bore=5.0)
    raw["hub"] = {"keyway": True}
    with pytest.raises(SpecError) as refused:
        validate_spec(raw)
    assert str(refused.value) == "cam.arm_angle: only for a conjugate cam with an oscillating-roller follower"
    del raw["cam"]["arm_angle"]
    with pytest.raises(SpecError, match=r"^hub\.keyway: DIN 6885-1 keys need a bore over 6 up to 110 mm"):
        validate_spec(raw)
