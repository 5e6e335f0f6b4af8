"""Shared pytest configuration.

aiobt's test plugin (fixtures ``manual_clock``, ``stubs``, ``bt_factory``) is
loaded through its ``pytest11`` entry point (``aiobt.testing.plugin``), the
same way it reaches users' test suites.

Hypothesis runs without its per-example deadline: a deadline is a timed
assertion, and on two loaded cores an example that takes 200 ms is not a bug
(each test is still bounded by pytest-timeout).

SIGTERM stops the run as Ctrl-C does (``KeyboardInterrupt``), so fixtures' teardown
still stops the processes the tests started; Python's default SIGTERM would end
pytest without it (they would then only get their parent-death signal).
"""

import signal
from collections.abc import AsyncIterator

import pytest
from hypothesis import settings

from aiobt.testing.bus import open_local_bus
from aiobt.transport import Bus

settings.register_profile("aiobt", deadline=None)
settings.load_profile("aiobt")


def _sigterm_interrupts() -> None:
    signal.signal(signal.SIGTERM, signal.default_int_handler)


def pytest_configure() -> None:
    _sigterm_interrupts()


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup() -> None:
    _sigterm_interrupts()  # again: a closed event loop that had a SIGTERM handler left SIG_DFL


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_teardown() -> None:
    _sigterm_interrupts()


@pytest.fixture
async def local_bus() -> AsyncIterator[Bus]:
    """An in-process bus (no router): see :func:`aiobt.testing.bus.open_local_bus`."""
    async with open_local_bus() as bus:
        yield bus
