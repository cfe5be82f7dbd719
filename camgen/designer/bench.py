"""The designer's bench row (``camgen bench``): how long the server takes to answer one step of a drag."""
from __future__ import annotations

import shutil
import statistics
import time
from pathlib import Path

from camgen.core.examples import folder
from camgen.designer.session import Session

#: the joint dragged (Jansen's foot) and the steps of the drag (mm each, down and to the right)
JOINT, STEPS, STEP_MM = "G", 40, 0.25


def drag_row(out: Path) -> dict:
    """The median time (s) of a drag step of Jansen's leg (templates/jansen.toml) as the designer answers it:
    the template validated, the linkage designed at its drawing and the scene made (positions, coupler curve,
    transmission angles); the answer's own sending is not included."""
    out.mkdir(parents=True, exist_ok=True)
    shutil.copy(folder() / "jansen.toml", out / "jansen.toml")
    session = Session(out.resolve())
    session.handle({"op": "open", "path": "jansen.toml"})
    x, y = session.design.spec.linkage.joints[JOINT]
    times = []
    for k in range(1, STEPS + 1):
        start = time.perf_counter()
        answer = session.handle({"op": "drag", "joint": JOINT, "x": x + k * STEP_MM, "y": y - k * STEP_MM})
        times.append(time.perf_counter() - start)
        if answer["kind"] != "preview":
            raise RuntimeError(answer.get("message", "the drag was refused"))
    return {"what": f"designer: one drag step of Jansen's leg (median of {STEPS})",
            "seconds": statistics.median(times), "cams_per_second": None}
