"""What the navigator made of a goal put on ``{ns}/goal_pose``: driving to it, or refused.

The navigator sends a ``goal_pose`` goal to its own ``navigate_to_pose`` server,
so the goal gets an id the sender never sees. :class:`GoalAnswer` takes the
first goal ACCEPTED after the put as that goal (a goal sent by someone else in
the same instant could be mistaken for it), then waits for
either its tree to have ticked (``bt/snapshot`` of that goal with ticks) or its
end (a terminal status, with the navigator's reason).
"""

from __future__ import annotations

import asyncio
from dataclasses import dataclass
from typing import Any

from aiobt.msgs import BtSnapshot, GoalState, GoalStatus, NavigateToPose
from aiobt.transport import Bus, Subscription
from aiobt.transport.topics import declare_subscription


@dataclass(frozen=True, slots=True)
class Verdict:
    """``running``: the navigator drives to the goal; else it ended in ``state``
    (ABORTED: refused or failed at once, ``reason`` the navigator's message)."""

    running: bool
    state: GoalState = GoalState.EXECUTING
    reason: str = ""


class GoalAnswer:
    """The first goal the navigator starts after :meth:`expect`, and its fate so far."""

    def __init__(self) -> None:
        self.goal_id = ""
        self._expecting = False
        self._ticked: set[str] = set()
        self._ended: dict[str, GoalStatus] = {}
        self.changed = asyncio.Event()

    def expect(self) -> None:
        """The goal is about to be put: the next new goal id is taken as its."""
        self._expecting = True

    def on_status(self, status: GoalStatus) -> None:
        if self._expecting and not self.goal_id and status.status is GoalState.ACCEPTED:
            self.goal_id = status.goal_id
        if status.status.is_terminal:
            self._ended[status.goal_id] = status
        self.changed.set()

    def on_snapshot(self, snapshot: BtSnapshot) -> None:
        if snapshot.state == "navigating" and snapshot.ticks > 0:
            self._ticked.add(snapshot.goal_id)
            self.changed.set()

    def verdict(self) -> Verdict | None:
        """None while the goal is unknown or neither running nor ended."""
        if not self.goal_id:
            return None
        ended = self._ended.get(self.goal_id)
        if ended is not None:
            return Verdict(False, ended.status, ended.reason)
        if self.goal_id in self._ticked:
            return Verdict(True)
        return None


class GoalAnswerWatch:
    """A :class:`GoalAnswer` fed by the navigator's ``navigate_to_pose`` statuses and
    its ``bt/snapshot`` stream on ``bus`` (subscribe before the goal is put)."""

    def __init__(self, bus: Bus) -> None:
        self.answer = GoalAnswer()
        statuses = bus.keys.action(NavigateToPose.name).any_status
        self._subs: list[Subscription[Any]] = [
            declare_subscription(
                bus.session, bus.bridge, statuses, GoalStatus,
                callback_fn=self.answer.on_status, latched=False, queue_size=100,
            ),
            bus.subscribe("bt/snapshot", BtSnapshot, self.answer.on_snapshot, queue_size=10),
        ]  # fmt: skip

    async def wait(self, timeout: float) -> Verdict | None:  # noqa: ASYNC109
        """The verdict, or None if there is none within ``timeout`` s."""
        answer = self.answer
        try:
            async with asyncio.timeout(timeout):
                while (verdict := answer.verdict()) is None:
                    answer.changed.clear()
                    await answer.changed.wait()
        except TimeoutError:
            return None
        return verdict

    def close(self) -> None:
        for sub in self._subs:
            sub.close()
