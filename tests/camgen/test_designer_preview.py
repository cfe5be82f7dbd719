"""A drag's preview (camgen/designer/quick.py) against the whole design: the positions are `linkgen analyze
--angle`'s on the template as dragged, saved, to 1e-9 mm, the paths, toggles and transmission at the angle are the full
scene's, and each dyad's extremes, taken at the samples, lie inside the refined ones within the bound the samples'
spacing and curvature give; the released drag answers the whole design again (refined)."""
from __future__ import annotations

import json
import math
import shutil
import tomllib

import numpy as np
import pytest

from tests.conftest import ROOT

#: the joint dragged of each template and by how much (mm)
DRAGS = {"jansen": ("G", 1.5, -2.0), "klann": (None, 1.0, 0.5), "eightbar-triad": (None, 0.5, 0.5),
         "toggle-press": (None, 0.5, -0.5), "shaper": (None, 0.5, 0.5)}


def _session(tmp_path, name):
    from camgen.designer.session import Session

    shutil.copy(ROOT / "templates" / f"{name}.toml", tmp_path / f"{name}.toml")
    session = Session(tmp_path.resolve())
    opened = session.handle({"op": "open", "path": f"{name}.toml"})
    assert opened["kind"] == "state" and opened["scene"] is not None and opened["scene"]["refined"] is True
    return session, opened["scene"]


def _moved(scene, name):
    joint, dx, dy = DRAGS[name]
    ground = set(scene["ground"])
    joint = joint or next(j for j in scene["drawn"] if j not in ground)
    x, y = scene["drawn"][joint]
    return {"op": "drag", "joint": joint, "x": x + dx, "y": y + dy}


def _sample_bound(values, inputs):
    """How far a sampled extreme of the smooth ``values`` (rad) over the even ``inputs`` may lie from the true one
    (rad): |g''| h^2 / 8 at the largest second difference, doubled for its own error."""
    g = np.asarray(values, dtype=float)
    h = float(inputs[1] - inputs[0])
    second = np.abs(np.diff(g, 2)) / h**2
    return 2.0 * float(np.nanmax(second)) * h**2 / 8.0


@pytest.mark.parametrize("name", sorted(DRAGS))
def test_a_drag_preview_equals_the_whole_design_but_for_the_refined_extremes(tmp_path, name):
    from click.testing import CliRunner

    from camgen.core.toml_text import dumps
    from camgen.designer import views
    from camgen.designer.session import _follow_checks
    from linkgen import api
    from linkgen.cli import main

    session, scene = _session(tmp_path, name)
    asked = _moved(scene, name)
    preview = session.handle(asked)
    assert preview["kind"] == "preview", preview
    quick = preview["scene"]
    assert quick["refined"] is False
    # the template as the drag left it, designed whole at the same angle (linkgen analyze --angle)
    raw = tomllib.loads((tmp_path / f"{name}.toml").read_text(encoding="utf-8"))
    raw["linkage"]["joints"][asked["joint"]] = [asked["x"], asked["y"]]
    _follow_checks(raw, asked["joint"])
    spec = api.validate(raw)
    angle = scene["drawn_angle"]
    analysed = api.design(spec, angle=angle)
    # the positions shown equal `linkgen analyze --angle` on the template as saved
    (tmp_path / "dragged.toml").write_text(dumps(raw), encoding="utf-8")
    done = CliRunner().invoke(main, ["analyze", str(tmp_path / "dragged.toml"), "--angle", repr(angle), "--json",
                                     "-o", str(tmp_path / "analysis")])
    assert done.exit_code == 0, done.output
    joints = json.loads(done.stdout)["positions"]["joints"]
    assert set(joints) == set(quick["joints"])
    for joint, shown in joints.items():
        assert quick["joints"][joint] == pytest.approx([shown["x_mm"], shown["y_mm"]], abs=1e-9), joint
    full = views.linkage_scene(analysed)
    assert full is not None
    assert {k: v for k, v in quick.items() if k not in ("dyads", "refined")} == {
        k: v for k, v in full.items() if k not in ("dyads", "refined")}
    # the extremes at the samples: inside the refined ones, by no more than the samples allow
    travel = analysed.kinematics.travel
    inputs = np.asarray(travel.inputs[0], dtype=float).reshape(-1)
    assert len(quick["dyads"]) == len(full["dyads"]) == len(travel.dyads)
    for sampled, refined, d in zip(quick["dyads"], full["dyads"], travel.dyads, strict=True):
        named = ("kind", "links", "joint")
        assert {k: sampled[k] for k in named} == {k: refined[k] for k in named}
        if "transmission_min_deg" not in refined:
            continue
        bound = math.degrees(_sample_bound(d.transmission, inputs)) + 1e-9
        assert refined["transmission_min_deg"] - 1e-9 <= sampled["transmission_min_deg"] <= (
            refined["transmission_min_deg"] + bound)
        assert refined["transmission_max_deg"] - bound <= sampled["transmission_max_deg"] <= (
            refined["transmission_max_deg"] + 1e-9)
    # released: the whole design, its extremes the report's
    released = session.handle({**asked, "final": True})
    assert released["kind"] == "state" and released["scene"]["refined"] is True
    assert released["scene"]["dyads"] == analysed.report["dyads"] == full["dyads"]
    assert released["scene"]["joints"] == full["joints"]


def test_a_drag_the_linkage_cannot_follow_is_refused_as_the_whole_design_refuses_it(tmp_path):
    session, scene = _session(tmp_path, "jansen")
    x, y = scene["drawn"]["O"]                           # the crank's pivot 30 mm away: the drawing does not close
    refused = session.handle({"op": "drag", "joint": "O", "x": x + 30.0, "y": y})
    released = session.handle({"op": "drag", "joint": "O", "x": x + 30.0, "y": y, "final": True})
    assert refused["kind"] == released["kind"] == "error"
    assert refused["message"] == released["message"]
    assert refused["message"].startswith("error: input: input 90 degrees is out of reach; the linkage reaches ")
    assert session.handle({"op": "undo"})["message"] == "error: history: nothing to undo"   # nothing committed
