"""What the transport logged, for its tests."""

from __future__ import annotations

import pytest


def assert_one_bad_message_warning(caplog: pytest.LogCaptureFixture, *named: str) -> None:
    """One "dropped bad message" line was logged, naming each of ``named``."""
    warnings = [r.getMessage() for r in caplog.records if "dropped bad message" in r.getMessage()]
    assert len(warnings) == 1
    for part in named:
        assert part in warnings[0]
