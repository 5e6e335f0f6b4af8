"""Fixtures of the transport integration tests (the router and ``bus`` come from
``tests/integration/conftest.py``)."""

from __future__ import annotations

from collections.abc import AsyncIterator

import pytest

from aiobt.transport import Bus, BusSettings, open_bus


@pytest.fixture
async def client_bus(bus_settings: BusSettings) -> AsyncIterator[Bus]:
    """A second session on the same router (the client side of a test)."""
    async with open_bus(bus_settings) as opened:
        yield opened
