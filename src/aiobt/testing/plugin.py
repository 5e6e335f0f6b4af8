"""pytest plugin: a manual clock and a factory with stub leaves.

Enable it with ``pytest_plugins = ["aiobt.testing.plugin"]`` in a conftest (or
through the ``pytest11`` entry point ``aiobt = "aiobt.testing.plugin"``).

Fixtures:

- ``manual_clock`` — a :class:`~aiobt.core.clock.ManualClock` at t=0;
- ``stubs`` — a fresh :class:`~aiobt.testing.stubs.Stubs` (scripts, counters, log);
- ``bt_factory`` — a :class:`~aiobt.factory.BehaviorTreeFactory` with the
  built-ins and ``stubs``' StubAction/StubCondition/StubAsyncAction registered.
"""

from __future__ import annotations

import pytest

from aiobt.core.clock import ManualClock
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs


@pytest.fixture
def manual_clock() -> ManualClock:
    return ManualClock()


@pytest.fixture
def stubs() -> Stubs:
    return Stubs()


@pytest.fixture
def bt_factory(stubs: Stubs) -> BehaviorTreeFactory:
    return stubs.factory()
