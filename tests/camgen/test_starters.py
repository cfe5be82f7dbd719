"""`camgen new` and `linkgen new`: every kind's starter template builds as it is, with no warning; its comments
are the models' own descriptions; an existing file is never overwritten; bad kinds and names are refused."""
from __future__ import annotations

import math
import re
import tomllib

import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen
from camgen.core.starter import table_models
from camgen.starters import starters
from camgen.spec import validate_spec
from camgen.kinds.disc.table import DiscTable
from camgen.core.errors import SpecError
from linkgen.cli import main as linkgen
from linkgen.mechanisms import MECHANISMS
from linkgen.starters import STARTERS as LINKAGE_STARTERS
from tests.conftest import ROOT

#: every cam kind's starter, with its kind
CAM_STARTERS = starters()


def _run(program, args):
    result = CliRunner().invoke(program, [str(a) for a in args])
    return result.exit_code, result.output


@pytest.mark.parametrize("kind", sorted(CAM_STARTERS))
def test_every_cam_starter_builds_without_a_warning(tmp_path, kind):
    path = tmp_path / f"my-{kind}.toml"
    assert _run(camgen, ["new", kind, "-o", path]) == (0, f"wrote {path}\n")
    code, output = _run(camgen, ["build", path, "-o", tmp_path / "out"])
    assert code == 0, output
    assert "warning" not in output, output
    assert (tmp_path / "out" / f"my-{kind}.json").exists()


@pytest.mark.parametrize("kind", sorted(LINKAGE_STARTERS))
def test_every_linkage_starter_analyses_and_builds(tmp_path, kind):
    path = tmp_path / f"{kind}.toml"
    assert _run(linkgen, ["new", kind, "-o", path])[0] == 0
    code, output = _run(linkgen, ["analyze", path, "-o", tmp_path / "a"])
    assert code == 0 and "warning" not in output, output
    if kind != "whitworth":                 # its parts cannot be stacked (docs/guides/parts-and-allowances.md)
        code, output = _run(linkgen, ["build", path, "-o", tmp_path / "b"])
        assert code == 0, output


def test_every_kind_has_a_starter():
    assert set(MECHANISMS) <= set(LINKAGE_STARTERS)
    extra = set(LINKAGE_STARTERS) - set(MECHANISMS)             # named examples of a type (the eight-bar)
    assert extra == {"eight-bar", "geared-fivebar"}
    assert all(LINKAGE_STARTERS[k][1][0][1]["type"] in MECHANISMS for k in extra)
    assert {"translating-roller", "knife-edge", "translating-flat", "oscillating-roller", "oscillating-flat",
            "plate", "grooved", "barrel", "conjugate", "geneva", "machine", "walking-toy"} == set(CAM_STARTERS)


def test_comments_are_the_models_descriptions(tmp_path):
    path = tmp_path / "c.toml"
    _run(camgen, ["new", "translating-roller", "-o", path])
    lines = path.read_text().splitlines()
    info = DiscTable.model_fields["base_radius"]
    line = next(x for x in lines if x.startswith("base_radius"))
    assert line.split("# ", 1)[1] == f"mm: {info.description}"
    assert 'name = "c"' in lines


def test_no_file_is_overwritten_and_bad_names_are_refused(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "plate.toml").write_text("mine\n")
    assert _run(camgen, ["new", "plate"]) == (2, "error: --output: plate.toml exists; give another file\n")
    assert (tmp_path / "plate.toml").read_text() == "mine\n"
    code, output = _run(camgen, ["new", "cylinder"])
    assert code == 2 and output.startswith("error: KIND: unknown value 'cylinder'; one of translating-roller")
    assert _run(linkgen, ["new", "four-bar", "-o", "a b.toml"]) == (
        2, "error: --output: 'a b' cannot name a template: letters, digits, '.', '_' and '-'\n")
    assert _run(linkgen, ["new", "four-bar", "-o", "no/such/x.toml"]) == (2, "error: --output: no folder no/such\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plate.toml"]
    code, output = _run(linkgen, ["new"])
    assert code == 0 and len(output.splitlines()) == len(LINKAGE_STARTERS)


def test_a_part_sharing_the_printable_pins_files_is_refused(tmp_path):
    """A slider named "pin" makes a block part "pin": its STL would be the printable pin's."""

    text = (ROOT / "templates" / "toggle-press.toml").read_text()
    path = tmp_path / "press.toml"
    path.write_text(text.replace("[linkage.sliders.ram]", "[linkage.sliders.pin]"))
    code, output = _run(linkgen, ["build", path, "-o", tmp_path / "o", "--set", "parts.pins=true"])
    assert (code, output) == (2, "error: parts.pins: a part named 'pin' would share its files with the printable "
                                 "pin; rename its link or slider\n")
    assert not (tmp_path / "o").exists()


# --- per-kind comments (issue 30): every comment names only keys its kind takes, and the rules it states hold ---

#: the tables a comment may name as ``table.key``
TABLES = ("cam", "follower", "motion", "hub", "output", "geneva", "kit", "linkage", "parts")
#: a value to try a key with that a starter's comment names but does not set, where the model has no default
SAMPLES = {"max_pressure_angle": 30.0, "second_base_radius": 40.0, "thickness": 8.0, "base_radius": 40.0,
           "offset": 2.0, "spring_rate": 0.5, "preload": 5.0, "travel": 200.0}


def _comments(text: str) -> list[tuple[str, str | None, str]]:
    """``(table, key, comment)`` for every comment of a starter: a key's (its continuation lines joined), a table
    heading's note or the header (key None; the header's table is "")."""
    out: list[tuple[str, str | None, str]] = []
    table = ""
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("[") and not line.startswith(" "):
            table = stripped.strip("[]")
        elif line.startswith(" ") and stripped.startswith("#"):
            t, k, c = out[-1]
            out[-1] = (t, k, f"{c} {stripped[2:]}")        # a key's comment going on
        elif stripped.startswith("#"):
            out.append((table, None, stripped[2:]))
        elif " # " in line:
            code, comment = line.split(" # ", 1)
            out.append((table, code.split("=")[0].strip(), comment))
    return out


def _mentions(text: str, models: dict) -> set[tuple[str, str]]:
    """The keys a starter's comments name, as ``(table, key)``: written ``table.key``; an identifier with an
    underscore that is a key of some table (of the comment's own table first); a plain word that is another key of
    the comment's own table (``< thickness`` in a ``[cam]`` comment)."""
    owners: dict[str, list[str]] = {}
    for table, model in models.items():
        for key in getattr(model, "model_fields", {}):
            owners.setdefault(key, []).append(table)
    found = set()
    for table, key, comment in _comments(text):
        top = table.split(".")[0]
        for t, k in re.findall(rf"\b({'|'.join(TABLES)})\.([a-z_]+)\b", comment):
            found.add((t, k))
        for word in re.findall(r"\b[a-z][a-z0-9]*(?:_[a-z0-9]+)*\b", comment):
            if word == key or word not in owners:
                continue
            if top in owners[word]:
                found.add((top, word))
            elif "_" in word:
                found.add((owners[word][0], word))
    return found


def _sets(raw: dict, table: str, key: str) -> bool:
    entries = raw.get(table)
    return any(key in e for e in entries) if isinstance(entries, list) else key in (entries or {})


def _models(kind: str) -> dict:
    """The template models of the kind whose starter ``kind`` is, by table."""
    return table_models(CAM_STARTERS[kind][0].spec)


def _cam_takes(kind: str, text: str, table: str, key: str) -> bool:
    """Whether the starter ``text`` takes ``table.key``: it sets it, or it validates with it added (its default, or a
    sample value)."""
    raw = tomllib.loads(text)
    if _sets(raw, table, key):
        return True
    model = _models(kind).get(table)
    field = model.model_fields.get(key) if model is not None else None
    if field is None:
        return False
    value = SAMPLES.get(key, field.default)
    if value is None or repr(value) == "PydanticUndefined":
        raise AssertionError(f"give SAMPLES a value to try {table}.{key} with")
    target = raw.setdefault(table, {})
    for entry in target if isinstance(target, list) else [target]:
        entry[key] = value
    try:
        validate_spec(raw)
    except ValueError:
        return False
    return True


@pytest.mark.parametrize("kind", sorted(CAM_STARTERS))
def test_a_cam_starters_comments_name_only_keys_its_kind_takes(kind):
    from camgen.starters import starter

    text = starter(kind, "x")
    mentions = _mentions(text, {"": None, **_models(kind)})
    assert mentions, text
    refused = sorted(f"{t}.{k}" for t, k in mentions if not _cam_takes(kind, text, t, k))
    assert refused == [], text


@pytest.mark.parametrize("kind", sorted(LINKAGE_STARTERS))
def test_a_linkage_starters_comments_name_only_keys_its_type_takes(kind):
    from linkgen.spec import PartsTable
    from linkgen.starters import starter

    text = starter(kind, "x")
    raw = tomllib.loads(text)
    models = {"linkage": MECHANISMS[raw["linkage"]["type"]].table, "parts": PartsTable}
    refused = sorted(f"{t}.{k}" for t, k in _mentions(text, models)
                     if not (_sets(raw, t, k) or k in getattr(models.get(t), "model_fields", {})))
    assert refused == [], text


def test_the_generic_comment_that_named_another_kinds_key_is_gone():
    """The barrel's groove depth was commented "< thickness", a key a barrel refuses; its comment now says the
    barrel's own rule, and every kind has rules of its own."""
    from camgen.starters import starter
    from linkgen.starters import RULES as LINKAGE_RULES

    line = next(x for x in starter("barrel", "x").splitlines() if x.startswith("groove_depth"))
    assert "thickness" not in line and "pitch_radius" in line
    assert _cam_takes("barrel", starter("barrel", "x"), "cam", "thickness") is False    # the test would have caught it
    assert all(s.rules for _, s in CAM_STARTERS.values()) and set(LINKAGE_RULES) == set(LINKAGE_STARTERS)
    lifts = {kind: next(x for x in starter(kind, "x").splitlines() if x.startswith("lift")).split("# ")[1]
             for kind in ("translating-roller", "oscillating-roller", "oscillating-flat", "barrel")}
    assert lifts["oscillating-roller"].startswith("degrees") and lifts["oscillating-flat"].startswith("degrees")
    assert lifts["translating-roller"].startswith("mm") and lifts["barrel"].startswith("mm")


def _cam_raw(kind: str, **changes: dict) -> dict:
    from camgen.starters import starter

    raw = tomllib.loads(starter(kind, "x"))
    for table, keys in changes.items():
        raw[table].update(keys)
    return raw


def _refused(raw: dict, field: str) -> bool:
    """Whether ``raw`` is refused naming ``field``, by validation or when its cam (its follower) is built."""
    from camgen.flat import build_cam
    from camgen.core.errors import SpecError

    try:
        spec = validate_spec(raw)
        if "geneva" not in raw:
            build_cam(spec)
    except SpecError as exc:
        return str(exc).startswith(field)
    return False


def test_the_rules_the_cam_starters_state_hold():
    """Each starter's stated rule is where validation draws the line, just inside it and just past it: a barrel's
    groove floor outside the roller (pitch_radius - groove_depth / 2 > roller_radius + running_clearance / 2, the
    bore being smaller), an arm that puts the roller on the prime circle (|pivot_distance - arm_length| < base_radius
    + roller_radius), an oscillating flat face's pivot far enough that its contact stays on the arm's side of it
    (base_radius / cos(the largest swing)), an offset inside the prime circle, a grooved cam's groove shallower than
    its plate, a Geneva wheel of 3 to 36 slots."""
    eps = 1e-6
    # barrel: Rm 30, Rr 5, c 0.2, bore 10: depth < 2 (30 - 5.1) = 49.8 mm (the roller, not the bore, decides)
    limit = 2 * (30.0 - (5.0 + 0.2 / 2))
    assert not _refused(_cam_raw("barrel", cam={"groove_depth": limit - eps}), "cam.groove_depth")
    assert _refused(_cam_raw("barrel", cam={"groove_depth": limit + eps}), "cam.groove_depth")
    # the bore as printed decides when it reaches further than the roller: bore 20, clearance 0.2 -> depth <
    # 2 (30 - 10.1) = 39.8 (refused naming the bore, which the same message says a shallower groove would clear)
    bored = 2 * (30.0 - (20.0 / 2 + 0.2 / 2))
    assert not _refused(_cam_raw("barrel", cam={"bore": 20.0, "groove_depth": bored - eps}), "cam")
    assert _refused(_cam_raw("barrel", cam={"bore": 20.0, "groove_depth": bored + eps}), "cam.bore")
    with pytest.raises(SpecError, match=r"or cam\.groove_depth < 39\.8 mm"):
        validate_spec(_cam_raw("barrel", cam={"bore": 20.0, "groove_depth": bored + eps}))
    # oscillating roller: pivot 110, Rb 40, Rr 8: |110 - L| < 48 < 110 + L, so L > 62
    assert not _refused(_cam_raw("oscillating-roller", follower={"arm_length": 62.0 + eps}), "follower")
    assert _refused(_cam_raw("oscillating-roller", follower={"arm_length": 62.0 - eps}), "follower.arm_length")
    # oscillating flat face: pivot_distance > base_radius / cos(the largest swing), the starter's 15 degrees
    flat = {"base_radius": 50.0}
    least = 50.0 / math.cos(math.radians(15.0))
    assert _refused(_cam_raw("oscillating-flat", cam=flat, follower={"pivot_distance": least - eps}),
                    "follower.pivot_distance")
    assert not _refused(_cam_raw("oscillating-flat", cam=flat, follower={"pivot_distance": least + eps}),
                        "follower.pivot_distance")
    # an offset inside the prime circle (40 + 10) and, for a knife edge, inside the base circle
    assert _refused(_cam_raw("translating-roller", follower={"offset": 50.0}), "follower.offset")
    assert not _refused(_cam_raw("translating-roller", follower={"offset": 45.0}), "follower.offset")
    assert _refused(_cam_raw("knife-edge", follower={"offset": 40.0}), "follower.offset")
    # a grooved cam's groove is a pocket: shallower than the plate (12 mm)
    assert _refused(_cam_raw("grooved", cam={"groove_depth": 12.0}), "cam.groove_depth")
    assert not _refused(_cam_raw("grooved", cam={"groove_depth": 11.0}), "cam.groove_depth")
    # a Geneva wheel of 3 to 36 slots
    for slots, refused in ((2, True), (3, False), (36, False), (37, True)):
        raw = _cam_raw("geneva", geneva={"slots": slots, "centre_distance": 200.0, "driver_bore": 0.0,
                                         "wheel_bore": 0.0})
        assert _refused(raw, "geneva.slots") is refused, slots


def test_the_rules_the_linkage_starters_state_hold():
    """The four-bar's Grashof rule (its crank turns fully while shortest + longest < the others: 45 + 150 < 135 +
    105), the slider-crank's (its parts need rod >= crank + |offset|), the crank-shaper's lever swing
    2 asin(crank / ground) and time ratio (180 + swing) / (180 - swing), Chebyshev's proportions in units of size:
    all read back from the analysis."""
    from linkgen.linkage_design import design_linkage
    from linkgen.spec import validate_spec as validate_linkage
    from linkgen.starters import starter

    def design(kind: str, **keys):
        raw = tomllib.loads(starter(kind, "x"))
        raw["linkage"].update(keys)
        return design_linkage(validate_linkage(raw))

    assert design("four-bar").report["grashof_class"] == "I"
    assert design("four-bar", crank=115.0).report["grashof_class"] == "II"    # 115 + 150 > 135 + 105
    shaper = design("crank-shaper").report
    swing = 2 * math.degrees(math.asin(50.0 / 150.0))
    assert shaper["lever_swing_deg"] == pytest.approx(swing, abs=1e-9)
    assert shaper["time_ratio"] == pytest.approx((180 + swing) / (180 - swing), rel=1e-12)
    proportions = design("chebyshev", size=10.0).report["proportions"]
    assert [proportions[k] for k in ("ground", "crank", "coupler", "rocker")] == pytest.approx([20, 25, 10, 25])
    from camgen.core.errors import SpecError

    raw = tomllib.loads(starter("slider-crank", "x"))
    raw["linkage"].update(rod=69.9)                            # < crank 50 + |offset| 20
    spec = validate_linkage(raw)
    assert design_linkage(spec).report["input_range_deg"] is not None   # the crank stops short of a turn
    with pytest.raises(SpecError, match=r"rod >= crank \+ \|offset\|"):
        design_linkage(spec, parts=True)
    raw["linkage"].update(rod=70.0)
    assert design_linkage(validate_linkage(raw), parts=True).build is not None
