"""Headless Chromium driven by Selenium with Debian's chromedriver (``apt-get install
chromium chromium-driver``; ``.ci/run`` installs them). Tests that need it are skipped,
with the reason, where either is absent; nothing is downloaded."""

from __future__ import annotations

import os
import shutil
from collections.abc import Iterator
from typing import Any

import pytest

CHROMEDRIVER = "/usr/bin/chromedriver"


def _chromium() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture
def browser() -> Iterator[Any]:
    chromium = _chromium()
    if chromium is None or not os.access(CHROMEDRIVER, os.X_OK):
        pytest.skip(
            "needs Debian's chromium and chromium-driver (/usr/bin/chromedriver): "
            "apt-get install -y chromium chromium-driver"
        )
    webdriver = pytest.importorskip("selenium.webdriver")
    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for flag in (
        "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
        "--window-size=1400,1000", "--disable-extensions", "--no-first-run",
    ):  # fmt: skip
        options.add_argument(flag)
    service = webdriver.ChromeService(executable_path=CHROMEDRIVER)
    driver = webdriver.Chrome(options=options, service=service)
    try:
        yield driver
    finally:
        driver.quit()  # ends chromedriver and the browser it started
