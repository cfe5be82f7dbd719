"""The designer in headless Chromium (the page tests' browser, :mod:`tests.project.test_page_browser`): a joint of
Jansen's leg dragged shows the positions ``linkgen analyze --angle`` gives of the saved template; a cam's lift edited
shows the profile and pressure angle ``camgen build`` gives; a bad value shows the command line's line at its field and
changes nothing; undo restores the file byte for byte; export downloads the command line's files."""
from __future__ import annotations

import io
import json
import os
import re
import shutil
import subprocess
import sys
import time
import zipfile

import pytest

from tests.conftest import ROOT
from tests.support.designer_server import designer
from tests.project.test_page_browser import CHROMIUM, DRIVER, browser  # noqa: F401  (the fixture, shared)

pytest.importorskip("starlette")
# slow: a designer server and Chromium per test (tests/conftest.py runs slow tests first; -m "not slow" skips them)
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="headless browser test: Debian's chromium and "
                                 "chromium-driver are not installed (apt-get install chromium chromium-driver)")]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}


def _run(folder, *args):
    done = subprocess.run([sys.executable, "-m", *args], cwd=folder, env=ENV, capture_output=True, text=True,
                          timeout=300)
    return done


def _settled(driver, timeout=60.0):
    """Wait until every message the page sent has its answer."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if driver.execute_script("const d = window.designer; return !!(d && d.state) && d.sent === d.answered"):
            return
        time.sleep(0.05)
    raise AssertionError(f"the designer did not answer: {driver.get_log('browser')}")


def _open(driver, url):
    driver.get(url)
    _settled(driver)


def _field(driver, path):
    from selenium.webdriver.common.by import By

    return driver.find_element(By.CSS_SELECTOR, f'[data-path="{path}"]')


def _type(driver, path, text):
    from selenium.webdriver.common.keys import Keys

    box = _field(driver, path)
    box.clear()
    box.send_keys(text + Keys.ENTER)
    _settled(driver)


def _save(driver, name):
    from selenium.webdriver.common.by import By

    box = driver.find_element(By.ID, "save-name")
    box.clear()
    box.send_keys(name)
    driver.find_element(By.ID, "save").click()
    _settled(driver)


def _positions(driver):
    return driver.execute_script("return window.designer.scene.joints"), {
        row.get_attribute("data-joint"): [float(c.text) for c in row.find_elements("css selector", "td")[1:]]
        for row in driver.find_elements("css selector", "#positions tr[data-joint]")}


def _analyzed(folder, name, angle):
    done = _run(folder, "linkgen", "analyze", name, "--angle", str(angle), "--json", "-o", "analysis")
    assert done.returncode == 0, done.stderr
    return {p: [j["x_mm"], j["y_mm"]] for p, j in json.loads(done.stdout)["positions"]["joints"].items()}


def test_dragging_a_joint_of_jansens_leg(browser, tmp_path):  # noqa: F811
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    original = (ROOT / "templates" / "jansen.toml").read_bytes()
    (tmp_path / "jansen.toml").write_bytes(original)
    with designer(tmp_path, "jansen.toml") as url:
        _open(browser, url)
        drawn = browser.execute_script("return window.designer.scene.drawn")
        scale = browser.execute_script("return window.designer.scale")        # px per mm while dragging
        foot = browser.find_element(By.CSS_SELECTOR, 'circle[data-joint="G"]')
        ActionChains(browser).move_to_element(foot).click_and_hold().move_by_offset(20, 10).move_by_offset(
            20, 15).release().perform()
        _settled(browser)
        assert browser.execute_script("return window.designer.state.can_undo")
        _save(browser, "moved.toml")
        saved = (tmp_path / "moved.toml").read_text(encoding="utf-8")
        import tomllib

        moved = tomllib.loads(saved)["linkage"]["joints"]["G"]
        # the foot moved by the pointer's 40 px right, 25 px down, at the drawing's scale (a pixel's rounding)
        assert moved[0] - drawn["G"][0] == pytest.approx(40 / scale, abs=1.5 / scale)
        assert moved[1] - drawn["G"][1] == pytest.approx(-25 / scale, abs=1.5 / scale)
        shown, table = _positions(browser)
        want = _analyzed(tmp_path, "moved.toml", 90)
        assert set(shown) == set(want) == set(table)
        for p, xy in want.items():
            assert shown[p] == pytest.approx(xy, abs=1e-9) and table[p] == pytest.approx(xy, abs=1e-9)
        assert shown["G"] != pytest.approx(drawn["G"], abs=1e-3)
        angle = browser.find_element(By.ID, "angle-value")            # the input turned to 150 degrees
        angle.clear()
        angle.send_keys("150\n")
        _settled(browser)
        shown, table = _positions(browser)
        want = _analyzed(tmp_path, "moved.toml", 150)
        for p, xy in want.items():
            assert shown[p] == pytest.approx(xy, abs=1e-9) and table[p] == pytest.approx(xy, abs=1e-9)
        paths = browser.execute_script("return window.designer.scene.paths.G.length")
        assert paths > 100                                              # the foot's coupler curve is drawn
        browser.find_element(By.ID, "undo").click()
        _settled(browser)
        _save(browser, "undone.toml")
        assert (tmp_path / "undone.toml").read_bytes() == original
        assert browser.execute_script("return window.designer.errors") == []
        assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []


def _page_parts(html):
    """The scene and plot SVGs and the figures of a page's document."""
    svgs = re.findall(r'<svg class="(?:scene|plot)".*?</svg>', html, re.S)
    data = json.loads(re.search(r'<script type="application/json" id="page-data">(.*?)</script>', html, re.S)[1])
    return svgs, data["figures"], data["scenes"]


def _shown_page(driver):
    import html

    frame = driver.execute_script("return document.querySelector('#page iframe').getAttribute('srcdoc')")
    return html.unescape(frame) if "&lt;" in frame else frame


def test_editing_a_cam_and_a_bad_value(browser, tmp_path):  # noqa: F811
    from selenium.webdriver.common.by import By

    original = (ROOT / "templates" / "rdrd.toml").read_bytes()
    (tmp_path / "rdrd.toml").write_bytes(original)
    with designer(tmp_path, "rdrd.toml") as url:
        _open(browser, url)
        before = _shown_page(browser)
        _type(browser, "motion[0].lift", "25")                # unbalanced until the return follows: an error
        assert "rises and returns must balance" in browser.find_element(
            By.CSS_SELECTOR, '.field-error[data-for="motion"]').text
        _type(browser, "motion[2].lift", "25")
        _save(browser, "lift25.toml")
        shown = _shown_page(browser)
        assert shown != before
        done = _run(tmp_path, "camgen", "build", "lift25.toml", "-o", "cli")
        assert done.returncode == 0, done.stderr
        svgs, figures, scenes = _page_parts((tmp_path / "cli" / "rdrd.html").read_text(encoding="utf-8"))
        got_svgs, got_figures, got_scenes = _page_parts(shown)
        assert got_svgs == svgs and got_scenes == scenes                   # the profile and the plots as built
        report = json.loads((tmp_path / "cli" / "rdrd.json").read_text(encoding="utf-8"))
        assert got_figures["pressure_angle_max_deg"] == pytest.approx(report["pressure_angle_max_deg"], abs=1e-9)
        assert got_figures == figures

        # a bad value: the command line's line at its field, nothing else changed
        cli = _run(tmp_path, "camgen", "build", "lift25.toml", "-o", "bad", "--set", "cam.base_radius=-5")
        assert cli.returncode == 2 and not (tmp_path / "bad").exists()
        text = browser.execute_script("return window.designer.state.text")
        _type(browser, "cam.base_radius", "-5")
        at = browser.find_element(By.CSS_SELECTOR, '.field-error[data-for="cam.base_radius"]')
        assert at.text == cli.stderr.strip()
        assert [e.text for e in browser.find_elements(By.CSS_SELECTOR, ".field-error") if e.text] == [at.text]
        assert _shown_page(browser) == shown
        assert browser.execute_script("return window.designer.state.text") == text
        assert _field(browser, "motion[0].lift").get_attribute("value") == "25"

        # export: the command line's files, as a download
        downloads = tmp_path / "downloads"
        downloads.mkdir()
        browser.execute_cdp_cmd("Page.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(downloads)})
        browser.find_element(By.ID, "export").click()
        _settled(browser)
        end = time.monotonic() + 60
        while not (downloads / "rdrd.zip").exists() and time.monotonic() < end:
            time.sleep(0.1)
        archive = zipfile.ZipFile(io.BytesIO((downloads / "rdrd.zip").read_bytes()))
        built = _run(tmp_path, "camgen", "build", "lift25.toml", "-o", "built")
        assert built.returncode == 0, built.stderr
        files = sorted(p.name for p in (tmp_path / "built").iterdir())
        assert sorted(archive.namelist()) == files and len(files) >= 4
        for name in files:
            assert archive.read(name) == (tmp_path / "built" / name).read_bytes(), name
        shutil.rmtree(downloads)
        assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []


def test_play_turns_the_input_and_pause_stops_it(browser, tmp_path):  # noqa: F811
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    shutil.copy(ROOT / "templates" / "jansen.toml", tmp_path / "jansen.toml")
    with designer(tmp_path, "jansen.toml") as url:
        _open(browser, url)
        start = browser.execute_script("return window.designer.scene.angle")
        play = browser.find_element(By.ID, "play")
        play.click()
        WebDriverWait(browser, 60).until(lambda d: d.execute_script("return window.designer.scene.angle") >= start + 10)
        play.click()
        assert play.text == "Play"
        _settled(browser)
        stopped = browser.execute_script("return window.designer.scene.angle")
        time.sleep(0.5)
        assert browser.execute_script("return window.designer.scene.angle") == stopped
        shown, _ = _positions(browser)
        for p, xy in _analyzed(tmp_path, "jansen.toml", stopped).items():        # the pose it stopped at
            assert shown[p] == pytest.approx(xy, abs=1e-9), p
