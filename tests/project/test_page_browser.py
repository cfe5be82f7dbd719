"""Each kind of interactive page in a real browser (headless Chromium driven by Selenium): it loads from the file
with no console error, moving the slider with the keyboard moves the mechanism and the plots' cursors and nothing
else, and a screenshot a person can look at is kept in out/pages/<name>.png.

Needs Debian's ``chromium`` and ``chromium-driver`` (``.ci/run`` installs them); skipped, saying so, without them.
"""
from __future__ import annotations

import io
import shutil

import numpy as np
import pytest

from tests.conftest import ROOT
from tests.camgen.test_page import build

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
pytestmark = pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="headless browser test: Debian's chromium and "
                                "chromium-driver are not installed (apt-get install chromium chromium-driver; "
                                ".ci/run installs them)")

SHOTS = ROOT / "out" / "pages"
#: (program, command, template, degrees the slider is moved by): every kind of page
PAGES = [("camgen", "build", "rdrd", 90), ("camgen", "build", "oscillating", 90), ("camgen", "build", "flat-face", 90),
         ("camgen", "build", "plate", 90), ("camgen", "build", "grooved", 90), ("camgen", "build", "barrel", 90),
         ("camgen", "build", "geneva4", 180), ("camgen", "build", "conjugate-arm", 90),
         ("linkgen", "analyze", "crank-rocker", 90),
         ("linkgen", "analyze", "slider-crank", 90), ("linkgen", "analyze", "jansen", 90)]


@pytest.fixture(scope="module")
def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1300,1000",
                "--force-device-scale-factor=1"):
        options.add_argument(arg)
    options.binary_location = CHROMIUM
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(DRIVER), options=options)
    yield driver
    driver.quit()


def _pixels(png: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)


def _changed(before: bytes, after: bytes) -> float:
    """The fraction of pixels that differ between two screenshots of one element."""
    a, b = _pixels(before), _pixels(after)
    assert a.shape == b.shape
    return float((np.abs(a - b).sum(axis=2) > 30).mean())


@pytest.mark.parametrize(("program", "command", "name", "turn"), PAGES, ids=[p[2] for p in PAGES])
def test_the_page_runs_in_chromium(browser, tmp_path, program, command, name, turn):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    page = tmp_path / f"{name}.html"
    page.write_text(build(tmp_path, program, command, name, 'output.formats=["json", "html"]')[0], encoding="utf-8")
    browser.get(page.as_uri())
    assert browser.execute_script("return window.camgenPage && window.camgenPage.frames") == 360
    errors = [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")]
    assert errors == []
    scene = browser.find_element(By.CSS_SELECTOR, "svg.scene")
    plot = browser.find_element(By.CSS_SELECTOR, "svg.plot")
    facts = browser.find_element(By.CSS_SELECTOR, "table.figures")
    assert scene.size["width"] > 300 and scene.size["height"] > 100
    before = (scene.screenshot_as_png, plot.screenshot_as_png, facts.screenshot_as_png)
    slider = browser.find_element(By.ID, "frame")
    slider.send_keys(Keys.ARROW_RIGHT * turn)                   # as a person moves it: one degree a key
    assert slider.get_attribute("value") == str(turn)
    shown = browser.find_element(By.ID, "shown").text
    start = float(browser.execute_script("return JSON.parse(document.getElementById('page-data').textContent)"
                                         ".inputs[0]"))
    assert float(shown.split()[0]) == pytest.approx(start + turn, abs=1e-6)
    after = (scene.screenshot_as_png, plot.screenshot_as_png, facts.screenshot_as_png)
    moved = _changed(before[0], after[0])
    assert moved > 0.002, f"the mechanism did not move ({moved:.4%} of its pixels changed)"
    assert _changed(before[1], after[1]) > 0.0005                 # the plot's cursor followed
    assert _changed(before[2], after[2]) == 0.0                   # the figures stand still
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == []
    SHOTS.mkdir(parents=True, exist_ok=True)
    browser.execute_script("window.scrollTo(0, 0)")
    browser.save_screenshot(str(SHOTS / f"{name}.png"))


def test_play_runs_the_mechanism(browser, tmp_path):
    """Play advances the frames by itself; pause stops them."""
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    page = tmp_path / "rdrd.html"
    page.write_text(build(tmp_path, "camgen", "build", "rdrd", 'output.formats=["json", "html"]')[0], encoding="utf-8")
    browser.get(page.as_uri())
    play = browser.find_element(By.ID, "play")
    slider = browser.find_element(By.ID, "frame")
    play.click()
    assert play.text == "Pause"
    WebDriverWait(browser, 20).until(lambda d: int(slider.get_attribute("value")) >= 10)
    play.click()
    assert play.text == "Play"
    stopped = slider.get_attribute("value")
    browser.execute_async_script("setTimeout(arguments[0], 300)")       # a few frames' time
    assert slider.get_attribute("value") == stopped


def test_the_family_page_sorts_its_table(browser, tmp_path):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    path = tmp_path / "fam.toml"
    path.write_text(f'base = "{(ROOT / "templates" / "crank-rocker.toml").as_posix()}"\nname = "bars"\n[output]\n'
                    'formats = ["json", "html"]\n[sweep]\n"linkage.crank" = [60, 80, 40]\n')
    from click.testing import CliRunner

    from linkgen.cli import main

    result = CliRunner().invoke(main, ["family", str(path), "-o", str(tmp_path / "f")])
    assert result.exit_code == 0, result.output
    browser.get((tmp_path / "f" / "overview.html").as_uri())
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == []
    assert len(browser.find_elements(By.CSS_SELECTOR, "svg.scene")) == 3

    def first_column() -> list[str]:
        return [r.find_elements(By.TAG_NAME, "td")[1].text for r in browser.find_elements(
            By.CSS_SELECTOR, "table.members tbody tr")]

    assert first_column() == ["40", "60", "80"]                        # sorted by the swept value, as numbers
    head = browser.find_elements(By.CSS_SELECTOR, "table.members th")[1]
    head.click()
    assert first_column() == ["40", "60", "80"]
    head.click()
    assert first_column() == ["80", "60", "40"]
    cards = browser.find_elements(By.CSS_SELECTOR, "svg.scene")
    before = [c.screenshot_as_png for c in cards]
    browser.find_element(By.ID, "frame").send_keys(Keys.ARROW_RIGHT * 90)
    assert all(_changed(b, c.screenshot_as_png) > 0.002 for b, c in zip(before, cards, strict=True))
    SHOTS.mkdir(parents=True, exist_ok=True)
    browser.execute_script("window.scrollTo(0, 0)")
    browser.save_screenshot(str(SHOTS / "family.png"))
