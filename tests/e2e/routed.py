"""The e2e stack with the route server (office graph), for a module's tests.

A module imports both fixtures (route_goals is named ``goals``); they replace
conftest's module stack and goal watcher:
``from .routed import _module_stack, route_goals  # noqa: F401``.
"""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterator

import pytest

from aiobt.msgs.remote_actions import ComputeRoute
from aiobt.testing.navwatch import ServerGoals
from aiobt.testing.stack import SERVICES, NavStack, StackConfig, running_stack
from aiobt.transport import Bus

from .conftest import SAFETY_CHAIN, SPEED
from .world import ACTIONS


@pytest.fixture(scope="module")
def _module_stack() -> Iterator[NavStack]:
    config = StackConfig(world="office", speed=SPEED, seed=7, services=(*SERVICES, "route"),
                         safety_chain=SAFETY_CHAIN,
                         extra={"route": ["--graph-filepath", "office", "--sim-time"]})  # fmt: skip
    with running_stack(config) as stack:
        yield stack


@pytest.fixture(name="goals")
async def route_goals(bus: Bus) -> AsyncIterator[ServerGoals]:
    """Every server's goals, the route server's included."""
    watcher = ServerGoals(bus, (*ACTIONS, ComputeRoute))
    try:
        yield watcher
    finally:
        watcher.close()
