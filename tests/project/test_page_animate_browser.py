"""The animate control of each product's page in headless Chromium (the page tests' browser,
:mod:`tests.project.test_page_browser`): with ``gif`` in ``output.formats`` the page's Animate link points to the GIF
written beside it, the browser loads it (640 x 480, ``animate``'s default size), and its bytes are those ``camgen
animate`` / ``linkgen animate`` write with their default options; without it the control is disabled and says how
to make one."""
from __future__ import annotations

from pathlib import Path
from urllib.parse import unquote, urlparse

import pytest
from click.testing import CliRunner

from camgen.cli import main as camgen_main
from linkgen.cli import main as linkgen_main
from tests.conftest import ROOT
from tests.project.test_page_browser import CHROMIUM, DRIVER, browser  # noqa: F401  (the fixture, shared)

pytestmark = pytest.mark.skipif(not (CHROMIUM and DRIVER), reason="headless browser test: Debian's chromium and "
                                "chromium-driver are not installed")

#: (program, its build command, template): a cam, a Geneva drive, a linkage, a machine
PAGES = [(camgen_main, "build", "rdrd"), (camgen_main, "build", "geneva4"), (linkgen_main, "analyze", "crank-rocker"),
         (camgen_main, "build", "automaton")]


def _run(main, *args: str) -> None:
    result = CliRunner().invoke(main, list(args))
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize(("main", "command", "name"), PAGES, ids=[p[2] for p in PAGES])
def test_the_animate_link_offers_the_commands_gif(browser, tmp_path, main, command, name):  # noqa: F811
    from selenium.webdriver.common.by import By

    template = str(ROOT / "templates" / f"{name}.toml")
    _run(main, command, template, "-o", str(tmp_path / "built"), "--set", 'output.formats=["json", "html", "gif"]')
    _run(main, "animate", template, "-o", str(tmp_path / "animated"))
    browser.get((tmp_path / "built" / f"{name}.html").as_uri())
    link = browser.find_element(By.ID, "animate")
    assert link.tag_name == "a" and link.text == "Animate" and link.is_displayed()
    assert link.get_attribute("download") == f"{name}-animation.gif"
    found = Path(unquote(urlparse(link.get_property("href")).path))
    assert found == tmp_path / "built" / f"{name}-animation.gif"
    size = browser.execute_async_script(
        "const done = arguments[1], img = new Image();"
        "img.onload = () => done([img.naturalWidth, img.naturalHeight]); img.onerror = () => done(null);"
        "img.src = arguments[0];", link.get_property("href"))
    assert size == [640, 480]
    assert found.read_bytes() == (tmp_path / "animated" / f"{name}-animation.gif").read_bytes()
    errors = [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")]
    assert errors == []


def test_without_the_gif_the_control_says_how(browser, tmp_path):  # noqa: F811
    from selenium.webdriver.common.by import By

    _run(camgen_main, "build", str(ROOT / "templates" / "plate.toml"), "-o", str(tmp_path), "--set",
         'output.formats=["json", "html"]')
    browser.get((tmp_path / "plate.html").as_uri())
    control = browser.find_element(By.ID, "animate")
    assert control.tag_name == "button" and not control.is_enabled()
    how = browser.find_element(By.CSS_SELECTOR, ".animate-how").text
    assert 'add "gif" to output.formats' in how and "camgen animate" in how
    assert not list(tmp_path.glob("*.gif"))
