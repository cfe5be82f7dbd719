"""The designer's bench rows (``camgen bench``): how long the server takes to answer one step of a drag, with no
synthesis running and while another tab's synthesis runs (in its child process, as the server runs it)."""
from __future__ import annotations

import shutil
import statistics
import time
from pathlib import Path

from camgen.core.examples import folder
from camgen.designer.session import Session

#: the joint dragged (Jansen's foot) and the steps of the drag (mm each, down and to the right)
JOINT, STEPS, STEP_MM = "G", 40, 0.25
#: the other tab's synthesis during the busy row: a path search long enough to outlast the drag (then cancelled)
BUSY_TASK = {"kind": "path", "points": [[0, 0], [10, 2], [20, 8], [28, 18], [32, 30]], "starts": 4,
             "generations": 2000}
#: the longest the busy row waits for that search to be under way (s)
START_SECONDS = 120.0


def _drag(session: Session) -> list[float]:
    """The times (s) of :data:`STEPS` drag steps of :data:`JOINT` of the session's design."""
    x, y = session.design.spec.linkage.joints[JOINT]
    times = []
    for k in range(1, STEPS + 1):
        start = time.perf_counter()
        answer = session.handle({"op": "drag", "joint": JOINT, "x": x + k * STEP_MM, "y": y - k * STEP_MM})
        times.append(time.perf_counter() - start)
        if answer["kind"] != "preview":
            raise RuntimeError(answer.get("message", "the drag was refused"))
    return times


def drag_row(out: Path, busy: bool = False) -> dict:
    """The median time (s) of a drag step of Jansen's leg (templates/jansen.toml) as the designer answers it:
    the template validated, the linkage analysed at its drawing and the preview scene made (positions, coupler
    curve, toggles, transmission angles); the answer's own sending is not included. ``busy``: while a path search
    runs as another tab's synthesis (:data:`BUSY_TASK`, in its child process), cancelled after."""
    from camgen.designer.child import ChildJob

    out.mkdir(parents=True, exist_ok=True)
    shutil.copy(folder() / "jansen.toml", out / "jansen.toml")
    session = Session(out.resolve())
    session.handle({"op": "open", "path": "jansen.toml"})
    job = None
    if busy:
        seen: list[dict] = []
        job = ChildJob({"task": BUSY_TASK}, seen.append)
        job.start()
        end = time.monotonic() + START_SECONDS
        while not any("generation" in str(m.get("stage", "")) for m in list(seen)):
            if time.monotonic() > end or not job.running():
                job.cancel()
                raise RuntimeError("the other tab's synthesis did not start")
            time.sleep(0.02)
    try:
        times = _drag(session)
    finally:
        if job is not None:
            job.cancel()
            job.join(START_SECONDS)
    during = ", a synthesis running in another tab" if busy else ""
    return {"what": f"designer: one drag step of Jansen's leg (median of {STEPS}{during}; max "
                    f"{max(times) * 1000:.1f} ms)", "seconds": statistics.median(times), "cams_per_second": None}
