"""Synthesis in the designer, in headless Chromium: targets clicked on the canvas land where the pointer was (mm at
the canvas' scale); a long synthesis shows its progress and is cancelled, after which the server still answers a
drag; a short one completes with the command line's candidates, and its first, opened, shows the positions
``linkgen analyze --angle`` gives of the candidate's template to 1e-9 mm."""
from __future__ import annotations

import json
import time
import tomllib

import pytest

from tests.conftest import ROOT
from tests.support.designer_server import designer
from tests.project.test_designer_browser import _analyzed, _open, _positions, _run, _save, _settled
from tests.project.test_page_browser import CHROMIUM, DRIVER, browser  # noqa: F401  (the fixture, shared)

pytest.importorskip("starlette")
# slow: a designer server and Chromium per test (tests/conftest.py runs slow tests first; -m "not slow" skips them)
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="headless browser test: Debian's chromium and "
                                 "chromium-driver are not installed (apt-get install chromium chromium-driver)")]
#: targets the tests click (mm): those of the path tests of tests/synthesis/test_synthesis_progress.py
TARGETS = [[0, 0], [10, 2], [20, 8], [28, 18], [32, 30]]


def _until(driver, script, timeout=120.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if driver.execute_script(script):
            return
        time.sleep(0.05)
    raise AssertionError(f"never true: {script}; {driver.get_log('browser')}")


def _click_targets(driver, targets):
    """Click each target (mm) on the synthesis canvas; return the points the page took (mm)."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    driver.find_element(By.CSS_SELECTOR, "#synthesis summary").click()
    canvas = driver.find_element(By.ID, "synth-canvas")
    driver.execute_script("arguments[0].scrollIntoView({block: 'center'})", canvas)
    view = driver.execute_script("const r = document.getElementById('synth-canvas').getBoundingClientRect();"
                                 "return [r.width, r.height]")
    x0, y1, scale = -50.0, 110.0, 2.4                          # the page's SYNTH_VIEW
    for x, y in targets:
        px, py = (x - x0) * scale, (y1 - y) * scale
        ActionChains(driver).move_to_element_with_offset(canvas, round(px - view[0] / 2),
                                                         round(py - view[1] / 2)).click().perform()
    taken = driver.execute_script("return window.designer.synth.points")
    assert len(taken) == len(targets)
    for (x, y), (tx, ty) in zip(targets, taken, strict=True):  # a pixel's rounding, and the page's 0.01 mm
        assert abs(tx - x) <= 1 / scale + 0.01 and abs(ty - y) <= 1 / scale + 0.01
    assert json.loads(driver.find_element(By.ID, "synth-points").get_attribute("value")) == taken
    return taken


def _keys(driver, keys):
    from selenium.webdriver.common.by import By

    box = driver.find_element(By.ID, "synth-keys")
    box.clear()
    box.send_keys(json.dumps(keys))


def test_a_synthesis_shows_progress_and_is_cancelled_and_a_drag_is_answered(browser, tmp_path):  # noqa: F811
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    (tmp_path / "jansen.toml").write_bytes((ROOT / "templates" / "jansen.toml").read_bytes())
    with designer(tmp_path, "jansen.toml") as url:
        _open(browser, url)
        _click_targets(browser, TARGETS)
        _keys(browser, {"starts": 4, "generations": 2000})
        browser.find_element(By.ID, "synth-run").click()
        _until(browser, "return document.getElementById('synth-progress').value > 0.001")
        stage = browser.find_element(By.ID, "synth-stage").text
        assert stage.startswith("search 1 of 4, generation ") and stage.endswith(" of 2000")
        assert browser.find_element(By.ID, "synth-run").get_attribute("disabled")
        browser.find_element(By.ID, "synth-cancel").click()
        _until(browser, "return window.designer.synthesis === 'synthesis-cancelled'", 60)
        assert browser.find_element(By.ID, "synth-stage").text.startswith("synthesis cancelled (")
        assert browser.execute_script("return document.getElementById('synth-progress').value") < 0.5
        assert not browser.find_element(By.ID, "synth-run").get_attribute("disabled")
        _settled(browser)
        # the server answers a drag of the leg's foot after the cancel
        before = browser.execute_script("return window.designer.scene.joints.G")
        foot = browser.find_element(By.CSS_SELECTOR, 'circle[data-joint="G"]')
        browser.execute_script("arguments[0].scrollIntoView({block: 'center'})", foot)
        ActionChains(browser).move_to_element(foot).click_and_hold().move_by_offset(20, 10).release().perform()
        _settled(browser)
        assert browser.execute_script("return window.designer.state.can_undo")
        assert browser.execute_script("return window.designer.scene.joints.G") != pytest.approx(before, abs=1e-3)


def test_a_short_synthesis_offers_the_commands_candidates_and_opens_the_first(browser, tmp_path):  # noqa: F811
    from selenium.webdriver.common.by import By

    with designer(tmp_path) as url:
        browser.get(url)
        _until(browser, "return window.designer.sent === window.designer.answered", 60)
        points = _click_targets(browser, TARGETS)
        keys = {"starts": 1, "generations": 40, "seed": 3, "candidates": 2}
        _keys(browser, keys)
        browser.find_element(By.ID, "synth-run").click()
        _until(browser, "return window.designer.synthesis === 'synthesized'", 300)
        shown = browser.execute_script("return window.designer.synth.candidates")
        # the same task through the command line: the same candidates, template for template
        task = {"name": "synthesis", "task": {"kind": "path", "points": points, **keys}}
        from camgen.core.toml_text import dumps

        (tmp_path / "task.toml").write_text(dumps(task), encoding="utf-8")
        done = _run(tmp_path, "linkgen", "synthesize", "task.toml", "-o", "out")
        assert done.returncode == 0, done.stderr
        summary = json.loads((tmp_path / "out" / "summary.json").read_text())
        assert [c["name"] for c in shown] == [r["template"][:-5] for r in summary["candidates"]]
        for c in shown:
            written = tomllib.loads((tmp_path / "out" / f"{c['name']}.toml").read_text(encoding="utf-8"))
            assert tomllib.loads(c["text"]) == written
        assert browser.find_elements(By.CSS_SELECTOR, "#synth-candidates tr[data-candidate]")
        browser.find_element(By.CSS_SELECTOR, f'button[data-candidate="{shown[0]["name"]}"]').click()
        _settled(browser)
        assert browser.execute_script("return window.designer.state.file") is None
        assert browser.find_element(By.ID, "save-name").get_attribute("value") == "synthesis-1.toml"
        angle = round(browser.execute_script("return window.designer.scene.drawn_angle") + 40.0, 6)
        box = browser.find_element(By.ID, "angle-value")
        box.clear()
        box.send_keys(f"{angle}\n")
        _settled(browser)
        joints, table = _positions(browser)
        want = _analyzed(tmp_path / "out", "synthesis-1.toml", angle)
        assert set(joints) == set(want) == set(table)
        for p, xy in want.items():
            assert joints[p] == pytest.approx(xy, abs=1e-9) and table[p] == pytest.approx(xy, abs=1e-9)
        _save(browser, "synthesis-1.toml")                 # saved as offered: the command line's template
        assert tomllib.loads((tmp_path / "synthesis-1.toml").read_text()) == tomllib.loads(
            (tmp_path / "out" / "synthesis-1.toml").read_text())
