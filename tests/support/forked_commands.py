"""Run console-script command lines as an installed package's users do, each in its own process, without paying for
a fresh interpreter and the dependencies' imports each time.

``python forked_commands.py RESULTS.json [JOBS] < LINES`` (run by the interpreter of the environment under test,
from the folder the commands run in): each line of standard input is one command line, ``PROGRAM ARG ...``, where
PROGRAM is a console script of that environment (``camgen``, ``linkgen``). The parent imports the third-party
packages the programs depend on (each package's top-level import, and the few of their submodules every build loads:
pydantic's models, scipy's integration, interpolation, optimisation and spatial modules), then forks one child per
line. The child loads PROGRAM's entry point from the environment's installed metadata (so the package's own modules
are imported afresh in every child, as in a new process) and calls it with the line's arguments, its standard output
and error going to a file of its own. The lines start in order, one after the other, or with JOBS (default 1) up to
that many children at a time, the next line starting when one ends.

RESULTS.json gets one record per line, in order: ``{"line": ..., "code": exit code, "seconds": its wall time,
"output": what it printed}`` (the seconds to see which line a slow run spends its time on; never asserted).
The script's own exit code is 0 when it ran every line, whatever their exit codes (the caller asserts on them).

This file is run as a script by another interpreter: it imports nothing of the checkout.
"""
from __future__ import annotations

import importlib
import importlib.metadata
import json
import os
import sys
import time
from pathlib import Path

#: the programs' dependencies, imported once in the parent (third-party modules only; see the module's docstring)
PRELOADED = ("numpy", "scipy", "shapely", "trimesh", "manifold3d", "ezdxf", "matplotlib", "pydantic", "click",
             # every template's validation loads pydantic's models, the cams' and linkages' analyses these scipy
             # modules: about 0.1 CPU s a child (a fifth of a small build's), 12 s over the examples' 120 lines
             "pydantic.main", "pydantic.fields", "pydantic.json_schema", "scipy.integrate", "scipy.interpolate",
             "scipy.optimize", "scipy.spatial")


def _child(program: str, args: list[str], log: Path) -> int:
    """In the forked child: run ``program args`` with its output into ``log``; its exit code."""
    fd = os.open(log, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    os.dup2(fd, 1)
    os.dup2(fd, 2)
    sys.argv = [program, *args]
    code = 1
    try:
        [entry] = [e for e in importlib.metadata.entry_points(group="console_scripts") if e.name == program]
        entry.load()()
        code = 0
    except SystemExit as stop:                         # click's standalone mode ends with sys.exit(code)
        code = stop.code if isinstance(stop.code, int) else 1
    except BaseException:                              # a traceback is a failure the caller shows
        import traceback

        traceback.print_exc()
        code = 1
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
    return code


def run_lines(lines: list[str], logs: Path, jobs: int = 1) -> list[dict[str, object]]:
    """Each command line run in a forked child, started in order, at most ``jobs`` children at a time (the next line
    starts when a child ends); a record for each, in the lines' order (see the module's docstring)."""
    logs.mkdir(parents=True, exist_ok=True)
    records: list[dict[str, object]] = [{} for _ in lines]
    running: dict[int, tuple[int, float]] = {}          # pid: (the line's number, its start)
    todo = list(enumerate(lines))[::-1]
    while todo or running:
        while todo and len(running) < jobs:
            number, line = todo.pop()
            program, *args = line.split()
            sys.stdout.flush()
            sys.stderr.flush()
            start = time.perf_counter()
            pid = os.fork()
            if pid == 0:                                # the child: never returns into the loop
                os._exit(_child(program, args, logs / f"{number:03d}.log"))
            running[pid] = (number, start)
        pid, status = os.wait()
        number, start = running.pop(pid)
        records[number] = {"line": lines[number], "code": os.waitstatus_to_exitcode(status),
                           "seconds": round(time.perf_counter() - start, 3),
                           "output": (logs / f"{number:03d}.log").read_text(encoding="utf-8", errors="replace")}
    return records


def main() -> None:
    for name in PRELOADED:
        importlib.import_module(name)
    results = Path(sys.argv[1])
    jobs = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    lines = [line for line in sys.stdin.read().splitlines() if line.strip()]
    records = run_lines(lines, results.with_suffix(".logs"), jobs)
    results.write_text(json.dumps(records, indent=1), encoding="utf-8")


if __name__ == "__main__":
    main()
