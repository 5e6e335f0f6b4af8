"""Shared pytest configuration.

aiobt's test plugin (fixtures ``manual_clock``, ``stubs``, ``bt_factory``) is
loaded through its ``pytest11`` entry point (``aiobt.testing.plugin``), the
same way it reaches users' test suites.
"""

from collections.abc import AsyncIterator

import pytest

from aiobt.testing.bus import open_local_bus
from aiobt.transport import Bus


@pytest.fixture
async def local_bus() -> AsyncIterator[Bus]:
    """An in-process bus (no router): see :func:`aiobt.testing.bus.open_local_bus`."""
    async with open_local_bus() as bus:
        yield bus
