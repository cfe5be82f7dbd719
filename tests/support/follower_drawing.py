"""What each follower type draws on a cam's page and in its cam figure, as plain numbers, for
tests/camgen/test_follower_drawing.py.

``python tests/support/follower_drawing.py`` (with ``PYTHONPATH`` at the checkout to record from) writes
tests/data/follower_drawing.json: for each starter below, the page's still outlines (the frame's: guide, pivot, the
centre mark) and its movers (every :data:`STEP`-th frame), and the cam figure's follower lines (colour ``C2``). It
was recorded from main before the followers drew themselves, so the test holds today's drawing to that one.
"""
from __future__ import annotations

import json
import sys
import tomllib
from typing import Any

import numpy as np
from tests.conftest import ROOT

#: one starter a follower type (and the plate's and the grooved cam's, which draw theirs through the same page)
STARTERS = ("translating-roller", "knife-edge", "translating-flat", "oscillating-roller", "oscillating-flat", "plate",
            "grooved")
#: every how many frames of the page's movers are recorded
STEP = 4
DATA = ROOT / "tests" / "data" / "follower_drawing.json"


def drawing(name: str) -> dict[str, Any]:
    """The page's and the cam figure's follower drawing of the starter ``name``."""
    import matplotlib

    matplotlib.use("Agg")
    from camgen import page, plots
    from camgen.kinds import kind_of
    from camgen.spec import validate_spec
    from camgen.starters import starter

    spec = validate_spec(tomllib.loads(starter(name, name)))
    kind = kind_of(spec.kind)
    design = kind.design(spec)
    _, report = kind.bundle(design)
    from camgen.kinds.grooved.page import grooved_page

    shown = (grooved_page if spec.kind == "grooved" else page.cam_page)(design, report)
    frame = next(b for b in shown.scene.bodies if b.name == "frame")
    out: dict[str, Any] = {
        "still": [{"style": o.style, "closed": o.closed, "points": np.asarray(o.points, float).tolist()}
                  for o in frame.outlines],
        "movers": [{"name": m.name, "style": m.style, "radius": m.radius,
                    "points": np.asarray(m.points, float)[::STEP].tolist()} for m in shown.scene.movers],
    }
    if spec.kind != "grooved":
        import matplotlib.pyplot as plt

        fig = plots.cam_figure(design)
        lines = [line for line in fig.axes[0].get_lines() if line.get_color() == "C2"]
        out["figure"] = [{"label": line.get_label() if not line.get_label().startswith("_") else "",
                          "marker": line.get_marker(), "points": np.asarray(line.get_xydata(), float).tolist()}
                         for line in lines]
        plt.close(fig)
    return out


def record() -> None:
    """Write :data:`DATA` from the checkout on ``sys.path`` (its ``camgen``)."""
    DATA.write_text(json.dumps({name: drawing(name) for name in STARTERS}, indent=None, separators=(",", ":")))


if __name__ == "__main__":
    record()
    sys.exit(0)
