"""A machine's mounts name their templates by path (issue 35): read from the machine template's folder, not the
current one, so a machine builds from wherever it is called; a mount's own table law's file is read from its
template's folder in turn. Refusals stay one line naming the mount's ``template``."""
from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
from click.testing import CliRunner

from camgen import api
from camgen.cli import main as camgen
from tests.conftest import ROOT
from tests.support.refusals import assert_refused

MACHINE = """name = "paths"

[machine]
main = "camshaft"
rpm = 20.0

[[shafts]]
name = "camshaft"
at = [0.0, 0.0]

[output]
formats = ["dxf", "json"]

[[cams]]
name = "lever"
shaft = "camshaft"
template = "parts/lever.toml"

[[linkages]]
name = "bars"
template = "bars.toml"

[[couplings]]
cam = "lever"
linkage = "bars"
rest = 60.0
"""

LEVER = """name = "lever"

[cam]
base_radius = 40.0
thickness = 6.0
bore = 8.0

[follower]
type = "oscillating-roller"
roller_radius = 8.0
pivot_distance = 110.0
arm_length = 90.0
mass = 0.1
spring_rate = 0.5
preload = 8.0

[[motion]]
type = "rise"
law = "table"
file = "laws/rise.csv"
lift = 15.0
angle = 150.0

[[motion]]
type = "dwell"
angle = 60.0

[[motion]]
type = "return"
law = "cycloidal"
lift = 15.0
angle = 90.0

[[motion]]
type = "dwell"
angle = 60.0
"""

BARS = """name = "bars"

[linkage]
type = "four-bar"
ground = 80.0
crank = 30.0
coupler = 90.0
rocker = 60.0
"""


def _machine(root) -> object:
    """The machine's folder under ``root``: machine.toml, bars.toml, parts/lever.toml and parts/laws/rise.csv."""
    folder = root / "machines"
    (folder / "parts" / "laws").mkdir(parents=True)
    (folder / "machine.toml").write_text(MACHINE)
    (folder / "bars.toml").write_text(BARS)
    (folder / "parts" / "lever.toml").write_text(LEVER)
    shutil.copy(ROOT / "templates" / "table-law.csv", folder / "parts" / "laws" / "rise.csv")
    return folder


def test_a_mount_path_is_read_from_the_machine_templates_folder(tmp_path, monkeypatch):
    """Built from another folder (where none of the files lie): the mounts are found beside the machine, the cam's
    table law beside the cam's template; the follower's swing is that table's."""
    folder = _machine(tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    result = CliRunner().invoke(camgen, ["build", "../machines/machine.toml", "-o", "out"])
    assert result.exit_code == 0, result.output
    assert (elsewhere / "out" / "paths.json").exists()
    assert (elsewhere / "out" / "paths-lever.dxf").exists()
    design = api.design(api.load("../machines/machine.toml"))
    lever = design.cam("lever").design
    assert lever.spec.name == "paths-lever" and design.linkages[0].design.spec.linkage.crank == 30.0
    rows = np.loadtxt(folder / "parts" / "laws" / "rise.csv", delimiter=",", skiprows=2)
    program = lever.cam.program
    for angle, lift in rows[::6]:
        assert abs(float(program.evaluate(np.radians([angle]))[0][0]) - lift) <= 0.005 + 1e-9


def test_the_same_machine_from_its_own_folder_and_by_an_absolute_path(tmp_path, monkeypatch):
    folder = _machine(tmp_path)
    monkeypatch.chdir(folder)
    here = api.design(api.load("machine.toml"))
    monkeypatch.chdir(tmp_path)
    (folder / "machine.toml").write_text(MACHINE.replace('"bars.toml"', f'"{(folder / "bars.toml").as_posix()}"'))
    absolute = api.design(api.load(folder / "machine.toml"))
    assert np.array_equal(here.linkages[0].theta4, absolute.linkages[0].theta4)


def test_a_mount_path_missing_beside_the_machine_is_refused_naming_its_mount(tmp_path, monkeypatch):
    """A file that lies in the current folder but not beside the machine is not taken: one line naming
    cams[0].template, exit 2, nothing written."""
    folder = _machine(tmp_path)
    (folder / "parts" / "lever.toml").unlink()
    monkeypatch.chdir(tmp_path)
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "lever.toml").write_text(LEVER)
    assert_refused(folder / "machine.toml", {}, "cams[0].template: ", tmp_path)


def test_a_geneva_template_path_is_read_from_the_machine_templates_folder(tmp_path, monkeypatch):
    """``genevas`` is a mount table too (:data:`camgen.kinds.machine.mounts.MOUNT_TABLES`): its ``template`` path is
    read beside the machine, not from the current folder (it was not, and the build failed naming it)."""
    from tests.camgen.kinds.machine.test_geneva_mount import MACHINE as GENEVA

    folder = tmp_path / "machines"
    folder.mkdir()
    shutil.copy(ROOT / "templates" / "geneva4.toml", folder / "drive.toml")
    (folder / "machine.toml").write_text(GENEVA.replace(f'"{ROOT / "templates" / "geneva4.toml"}"', '"drive.toml"'))
    assert 'template = "drive.toml"' in (folder / "machine.toml").read_text()
    monkeypatch.chdir(tmp_path)
    design = api.design(api.load("machines/machine.toml"))
    assert design.indexed[0].law.slots == 4
    assert design.spec.genevas[0].template == str(Path("machines") / "drive.toml")
