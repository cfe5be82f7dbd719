"""Shared fixtures: the issue's reference template as a raw mapping; the Hypothesis profiles."""
from __future__ import annotations

import copy
import os
from datetime import timedelta
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

ROOT = Path(__file__).resolve().parent.parent

# One BLAS thread a process: the run's xdist workers already fill the cores, and OpenBLAS' own threads spinning
# beside the other worker made small dense solves (SLSQP's, a least-squares fit) up to 100 times slower on a busy
# 2-core machine (a 25-variable SLSQP 1.3 s against 0.013 s). Set here, before pytest-xdist starts its workers, so
# that they and the commands the tests start inherit it before they import numpy; a user's own setting is kept.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

# --------------------------------------------------------------------------------------------------- Hypothesis
#: Hypothesis' own deadline for one example (a call or two of a command, in seconds)
DEADLINE_SECONDS = 10
_COMMON = {
    "database": None, "deadline": timedelta(seconds=DEADLINE_SECONDS), "print_blob": True,
    "suppress_health_check": [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much,
                              HealthCheck.function_scoped_fixture]}
#: the profiles, by the name ``HYPOTHESIS_PROFILE`` picks: ``ci`` (the default, what the README's test command and
#: ``.ci/run`` run: 50 cases a unit, derandomized, so that a run is repeatable and the suite stays within ten
#: minutes on two cores), ``quick`` (20 cases a unit, derandomized, for a quick local run) and ``thorough`` (1000
#: cases a unit, random, for a hunt)
PROFILES = {"ci": {"max_examples": 50, "derandomize": True},
            "quick": {"max_examples": 20, "derandomize": True},
            "thorough": {"max_examples": 1000}}
for _name, _sizes in PROFILES.items():
    settings.register_profile(_name, **_sizes, **_COMMON)
PROFILE_NAME = os.environ.get("HYPOTHESIS_PROFILE", "ci")
if PROFILE_NAME not in PROFILES:
    raise pytest.UsageError(f"HYPOTHESIS_PROFILE: one of {', '.join(PROFILES)} (got {PROFILE_NAME!r})")
settings.load_profile(PROFILE_NAME)

RDRD = {
    "name": "rdrd",
    "cam": {"base_radius": 40.0, "thickness": 8.0, "bore": 10.0, "rotation": "ccw"},
    "follower": {"type": "translating-roller", "roller_radius": 10.0, "offset": 5.0},
    "motion": [
        {"type": "rise", "law": "cycloidal", "lift": 20.0, "angle": 120.0},
        {"type": "dwell", "angle": 60.0},
        {"type": "return", "law": "harmonic", "lift": 20.0, "angle": 120.0},
        {"type": "dwell", "angle": 60.0},
    ],
    "output": {"tolerance": 0.01},
}


@pytest.fixture
def raw() -> dict:
    """A fresh deep copy of the rdrd template mapping."""
    return copy.deepcopy(RDRD)


def template(overrides: dict | None = None, **changes):
    """A validated template: rdrd with dotted-key ``overrides`` applied."""
    from camgen.spec import validate_spec
    from camgen.core.spec import apply_overrides

    return validate_spec(apply_overrides(RDRD, list((overrides or {}).items())))


@pytest.fixture(scope="session")
def bundled_builds(tmp_path_factory: pytest.TempPathFactory):
    """The folders of bundled templates' commands, each run once per test run (:mod:`tests.support.builds`); read
    them, never write into them."""
    from tests.support.builds import Builds, shared_root

    return Builds(shared_root(tmp_path_factory.getbasetemp()))


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Run the tests marked ``slow`` first, the rest in their collected order: with ``-n auto`` the workers take
    the longest checks while many short ones remain, so both end at about the same time."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)


@pytest.fixture(scope="session")
def plain_install(tmp_path_factory: pytest.TempPathFactory):
    """A plain install of the checkout with every bundled example run in it (:mod:`tests.support.plain_install`),
    made once a run for the checks of the xdist group ``plain-install``; read it, never write into it."""
    from tests.support.plain_install import example_runs

    return example_runs(tmp_path_factory.mktemp("plain-install"))


@pytest.fixture(scope="session")
def shared_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A cache folder (an ``XDG_CACHE_HOME``) shared by the run's workers, outside the checkout and the user's own
    cache, with the closed atlas of Fourier path synthesis in its ``linkgen`` folder: built by the first worker to
    ask (the others wait on a lock file, then read it), where the quick benches and the published problems each
    built their own (about 3.6 CPU s one). Read it, never write into it."""
    import fcntl

    from linkgen.synthesis import atlas
    from tests.support.builds import run_base

    root = run_base(tmp_path_factory.getbasetemp()) / "shared-cache"
    root.mkdir(parents=True, exist_ok=True)
    with (root / ".atlas.lock").open("w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        atlas.load("closed", root / "linkgen")
    return root


#: the xdist group of the checks that read the quick benches' one run
BENCHES = "quick-benches"


@pytest.fixture(scope="session")
def quick_benches(tmp_path_factory: pytest.TempPathFactory, shared_cache: Path) -> dict[str, Path]:
    """``camgen bench --quick`` and ``linkgen bench --quick`` run once a run by the installed console scripts, from
    a folder outside the checkout (the linkage atlas read from :func:`shared_cache`, not the user's cache):
    {"camgen": its output folder, "linkgen": its}. For the checks of the xdist group :data:`BENCHES`; read them,
    never write into them."""
    import shutil
    import subprocess
    import sys

    folder = tmp_path_factory.mktemp("quick-benches")
    assert not folder.is_relative_to(ROOT)
    out = {"camgen": folder / "camgen", "linkgen": folder / "linkgen"}
    env = {**os.environ, "XDG_CACHE_HOME": str(shared_cache)}
    env.pop("PYTHONPATH", None)
    for program, target in out.items():
        script = shutil.which(program, path=str(Path(sys.executable).parent)) or shutil.which(program)
        assert script, f"the {program} console script is not installed: pip install '.[test]'"
        result = subprocess.run([script, "bench", "--quick", "-o", str(target)], cwd=folder, env=env,
                                capture_output=True, text=True, timeout=1200)
        assert result.returncode == 0, f"{program} bench --quick: exit {result.returncode}\n{result.stderr}"
    return out
