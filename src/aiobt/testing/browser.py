"""Headless Chromium for tests and benches of the web view: Debian's ``chromium`` driven
by Debian's ``chromium-driver`` through Selenium (a dev dependency); nothing is downloaded.

    reason = missing_browser()          # None, or why a browser test cannot run here
    with headless_chromium() as driver:
        driver.get(url)
"""

from __future__ import annotations

import contextlib
import os
import shutil
from collections.abc import Iterator
from typing import Any

CHROMEDRIVER = "/usr/bin/chromedriver"
FLAGS = (
    "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
    "--window-size=1400,1000", "--disable-extensions", "--no-first-run",
)  # fmt: skip


def chromium_path() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser")


def missing_browser() -> str | None:
    """Why headless Chromium cannot run here (None when it can)."""
    if chromium_path() is None or not os.access(CHROMEDRIVER, os.X_OK):
        return (
            "needs Debian's chromium and chromium-driver (/usr/bin/chromedriver): "
            "apt-get install -y chromium chromium-driver"
        )
    try:
        import selenium  # noqa: F401  (inside: an optional dependency, asked for here)
    except ImportError:
        return "needs selenium (pip install -e '.[dev]')"
    return None


@contextlib.contextmanager
def headless_chromium() -> Iterator[Any]:
    """A Selenium driver of headless Chromium; quit (browser and chromedriver ended) on exit."""
    from selenium import webdriver  # inside: an optional dependency (the dev extras)

    options = webdriver.ChromeOptions()
    options.binary_location = chromium_path() or "chromium"
    for flag in FLAGS:
        options.add_argument(flag)
    driver = webdriver.Chrome(
        options=options, service=webdriver.ChromeService(executable_path=CHROMEDRIVER)
    )
    try:
        yield driver
    finally:
        driver.quit()


def page_value(driver: Any, script: str) -> Any:
    """The value of the JavaScript expression ``script`` in the page."""
    return driver.execute_script(f"return {script};")


def measured_rate(driver: Any, seconds: float = 3.0) -> tuple[float, float]:
    """Updates and pose updates per second the web view's page received over ``seconds``
    of wall time, counted in the page by its own clock (blocking: call in a thread when
    the view runs in the caller's event loop)."""
    script = (
        "const done = arguments[arguments.length - 1]; const s = window.aiobtState;"
        "const f0 = s.frames, p0 = s.poseUpdates, t0 = performance.now();"
        "setTimeout(() => done([s.frames - f0, s.poseUpdates - p0,"
        f" (performance.now() - t0) / 1000]), {seconds * 1000});"
    )
    driver.set_script_timeout(seconds + 30)
    frames, poses, elapsed = driver.execute_async_script(script)
    return frames / elapsed, poses / elapsed
