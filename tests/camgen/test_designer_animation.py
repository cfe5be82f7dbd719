"""The designer's animate button: the current design's GIF, the bytes ``linkgen animate`` / ``camgen animate``
write of the saved template (so its frame count and size are the asked ones), offered as a download; its options
refused in the commands' lines."""
from __future__ import annotations

import base64
import io
import time

import pytest

from tests.support.designer_server import designer
from tests.camgen.test_designer import _ask, _folder, _snapshot, _tab
from tests.project.test_designer_browser import _run, _save, _settled
from tests.project.test_page_browser import CHROMIUM, DRIVER, browser  # noqa: F401  (the fixture, shared)

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")


def _gif(data):
    from PIL import Image

    image = Image.open(io.BytesIO(data))
    return image.n_frames, image.size


@pytest.mark.parametrize(("name", "program"), [("crank-rocker", "linkgen"), ("rdrd", "camgen"), ("grooved", "camgen")])
def test_the_animation_is_the_commands_gif_of_the_design(tmp_path, name, program):
    folder = _folder(tmp_path, name)
    with designer(folder, f"{name}.toml") as url, _tab(url) as (ws, _, _):
        got = _ask(ws, {"op": "animate", "frames": 12, "size": "320x240"})
        assert got["kind"] == "animation" and got["name"] == f"{state_name(folder, name)}-animation.gif"
        data = base64.b64decode(got["data"])
        assert _gif(data) == (12, (320, 240))
        done = _run(folder, program, "animate", f"{name}.toml", "--frames", "12", "--size", "320x240", "-o", "cli")
        assert done.returncode == 0, done.stderr
        assert data == (folder / "cli" / got["name"]).read_bytes()
        before = _snapshot(folder)
        refused = _ask(ws, {"op": "animate", "frames": 1000})
        assert refused["message"] == "error: --frames: must be a whole number of frames from 2 to 720 (got 1000)"
        refused = _ask(ws, {"op": "animate", "size": "33x20"})
        assert refused["message"].startswith("error: --size: must be WIDTHxHEIGHT in pixels, each an even number")
        assert _ask(ws, {"op": "animate", "frames": "many"})["field"] == "animate"
        assert _snapshot(folder) == before


def state_name(folder, name):
    import tomllib

    return tomllib.loads((folder / f"{name}.toml").read_text())["name"]


@pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="headless browser test: chromium and chromium-driver")
def test_the_animate_button_downloads_the_gif_of_the_design_shown(browser, tmp_path):  # noqa: F811
    from selenium.webdriver.common.by import By

    folder = _folder(tmp_path, "crank-rocker")
    downloads = tmp_path / "downloads"
    downloads.mkdir()
    with designer(folder, "crank-rocker.toml") as url:
        browser.get(url)
        _settled(browser)
        browser.execute_cdp_cmd("Page.setDownloadBehavior", {"behavior": "allow", "downloadPath": str(downloads)})
        box = browser.find_element(By.CSS_SELECTOR, '[data-path="linkage.crank"]')
        box.clear()
        box.send_keys("85\n")                               # the design shown, not the file: an edit first
        _settled(browser)
        for key, text in (("anim-frames", "10"), ("anim-size", "240x160")):
            field = browser.find_element(By.ID, key)
            field.clear()
            field.send_keys(text)
        browser.find_element(By.ID, "animate").click()
        _settled(browser)
        name = f"{state_name(folder, 'crank-rocker')}-animation.gif"
        end = time.monotonic() + 60
        while not (downloads / name).exists() and time.monotonic() < end:
            time.sleep(0.1)
        data = (downloads / name).read_bytes()
        assert _gif(data) == (10, (240, 160))
        _save(browser, "edited.toml")
        import tomllib

        assert tomllib.loads((folder / "edited.toml").read_text())["linkage"]["crank"] == 85
        done = _run(folder, "linkgen", "animate", "edited.toml", "--frames", "10", "--size", "240x160", "-o", "cli")
        assert done.returncode == 0, done.stderr
        assert data == (folder / "cli" / name).read_bytes()
