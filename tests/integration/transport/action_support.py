"""Helpers shared by the action-server integration tests."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import Any

from aiobt.transport import ClientGoal

WAIT = 5.0  # the bound of every wait in these tests


async def until(condition: Callable[[], object], timeout: float = WAIT) -> None:  # noqa: ASYNC109
    """Poll ``condition`` (state that Zenoh's threads change), bounded by ``timeout``."""
    async with asyncio.timeout(timeout):
        while not condition():  # noqa: ASYNC110 - no event to wait on: set in Zenoh's thread
            await asyncio.sleep(0.01)


def one_after_another(*goals: ClientGoal[Any, Any, Any]) -> list[str]:
    """The execute events of ``goals`` run one at a time, in this order."""
    return [f"{event} {goal.goal_id}" for goal in goals for event in ("start", "end")]
