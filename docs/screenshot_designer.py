"""Write docs/_static/designer.png: the designer (``camgen serve``) editing Jansen's leg, as headless Chromium shows
it. Run from the checkout's root, by hand, when the designer's look changes: ``python docs/screenshot_designer.py``
(needs the serve extra, selenium, Debian's chromium and chromium-driver)."""
from __future__ import annotations

import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.support.designer_server import designer  # noqa: E402


def main() -> None:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,900",
                "--force-device-scale-factor=1"):
        options.add_argument(arg)
    options.binary_location = shutil.which("chromium") or shutil.which("chromium-browser") or "chromium"
    driver = webdriver.Chrome(service=Service(shutil.which("chromedriver") or "chromedriver"), options=options)
    with tempfile.TemporaryDirectory() as tmp:
        shutil.copy(ROOT / "templates" / "jansen.toml", Path(tmp) / "jansen.toml")
        try:
            with designer(Path(tmp), "jansen.toml") as url:
                driver.get(url)
                end = time.monotonic() + 60
                while not driver.execute_script("return !!(window.designer && window.designer.state)"):
                    if time.monotonic() > end:
                        raise SystemExit("the designer did not answer")
                    time.sleep(0.1)
                driver.execute_script("window.designer.send({op: 'angle', value: 150})")
                time.sleep(2)
                driver.save_screenshot(str(ROOT / "docs" / "_static" / "designer.png"))
        finally:
            driver.quit()


if __name__ == "__main__":
    main()
