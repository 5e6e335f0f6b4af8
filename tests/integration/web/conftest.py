"""Headless Chromium for the browser tests (see aiobt.testing.browser); skipped, with the
reason, where Debian's chromium or chromium-driver is absent (``.ci/run`` installs them)."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

from aiobt.testing.browser import headless_chromium, missing_browser


@pytest.fixture
def browser() -> Iterator[Any]:
    reason = missing_browser()
    if reason is not None:
        pytest.skip(reason)
    with headless_chromium() as driver:
        yield driver
