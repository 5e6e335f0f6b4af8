"""Server-side goals: the handle ``execute`` gets, goal records (running or waiting), results."""

from __future__ import annotations

import asyncio
from collections import OrderedDict
from collections.abc import Callable
from typing import Generic, TypeVar

import zenoh

from aiobt.msgs import ActionResult, Msg
from aiobt.transport import _z
from aiobt.transport.actions.protocol import ACCEPTED, REJECTED
from aiobt.transport.bridge import JSON

G = TypeVar("G", bound=Msg)
R = TypeVar("R", bound=ActionResult)
F = TypeVar("F", bound=Msg)
_KEEP_RESULTS = 128


class GoalRecord:
    """An accepted goal: its open send_goal query (the goal's stream) and its fate."""

    __slots__ = (
        "acknowledged",
        "cancel_requested",
        "done",
        "goal_id",
        "preempted_by",
        "query",
        "waiters",
    )

    def __init__(self, goal_id: str, query: zenoh.Query) -> None:
        self.goal_id = goal_id
        self.query = query
        self.preempted_by = ""
        self.cancel_requested = False
        self.acknowledged = False
        self.done = False
        self.waiters: list[zenoh.Query] = []

    def acknowledge(self) -> None:
        """Reply ``accepted`` once; a goal whose result went first needs none (implied)."""
        if not self.acknowledged and not self.done:
            self.acknowledged = True
            self.query.reply(self.query.key_expr, b"", attachment=ACCEPTED)

    def reject(self, reason: str) -> None:
        """Refuse the goal with ``reason`` (only before its acceptance went out)."""
        if not self.acknowledged and not self.done:
            self.done = True
            self.query.reply(self.query.key_expr, reason.encode(), attachment=REJECTED)
            _z.drop(self.query)

    def reply(self, payload: bytes, tag: bytes) -> None:
        """A reply on the goal's stream (feedback), after the acceptance."""
        if not self.done:
            self.acknowledge()
            self.query.reply(self.query.key_expr, payload, encoding=JSON, attachment=tag)

    def finish(self, tag: bytes, payload: bytes) -> None:
        """Send the result on the goal's stream and to result queries, then end them."""
        if self.done:
            return
        self.done = True
        self.query.reply(self.query.key_expr, payload, encoding=JSON, attachment=tag)
        _z.drop(self.query)
        for waiter in self.waiters:
            waiter.reply(waiter.key_expr, payload, encoding=JSON, attachment=tag)
            _z.drop(waiter)
        self.waiters.clear()


class WaitingGoals:
    """Accepted goals waiting for the running goal to stop: cancelable. (The runner keeps
    at most one, Nav2's pending slot: a newer goal takes the others out first.)"""

    __slots__ = ("_records",)

    def __init__(self) -> None:
        self._records: dict[str, GoalRecord] = {}

    def add(self, record: GoalRecord) -> None:
        self._records[record.goal_id] = record

    def discard(self, record: GoalRecord) -> None:
        if self._records.get(record.goal_id) is record:
            del self._records[record.goal_id]

    def get(self, goal_id: str) -> GoalRecord | None:
        return self._records.get(goal_id)

    def take(self, goal_id: str) -> list[GoalRecord]:
        """Remove and return the waiting goal ``goal_id``, or all of them for ``""``."""
        if not goal_id:
            taken = list(self._records.values())
            self._records.clear()
            return taken
        record = self._records.pop(goal_id, None)
        return [record] if record is not None else []


class ResultStore:
    """The last results by goal id, so a client can fetch one by query."""

    __slots__ = ("_results",)

    def __init__(self) -> None:
        self._results: OrderedDict[str, tuple[bytes, bytes]] = OrderedDict()

    def store(self, goal_id: str, tag: bytes, payload: bytes) -> None:
        self._results[goal_id] = (tag, payload)
        while len(self._results) > _KEEP_RESULTS:
            self._results.popitem(last=False)

    def get(self, goal_id: str) -> tuple[bytes, bytes] | None:
        return self._results.get(goal_id)


class RecentIds:
    """Goal ids seen lately (bounded): to refuse a duplicate, or a goal canceled before
    it arrived. One writer each."""

    __slots__ = ("_ids",)

    def __init__(self) -> None:
        self._ids: OrderedDict[str, None] = OrderedDict()

    def add(self, goal_id: str) -> bool:
        """False if ``goal_id`` was seen already."""
        if goal_id in self._ids:
            return False
        self._ids[goal_id] = None
        if len(self._ids) > 4 * _KEEP_RESULTS:
            self._ids.popitem(last=False)
        return True

    def __contains__(self, goal_id: object) -> bool:
        return goal_id in self._ids


class GoalHandle(Generic[G, R, F]):
    """What ``execute`` gets: the goal, feedback publishing, and (replace) newer goals."""

    def __init__(self, publish: Callable[[str, F], None], record: GoalRecord, goal: G) -> None:
        self.goal_id = record.goal_id
        self.goal = goal
        self.record = record
        self._publish = publish
        self._queue: asyncio.Queue[G] | None = None  # made when first needed (replace only)

    @property
    def _new_goals(self) -> asyncio.Queue[G]:
        if self._queue is None:
            self._queue = asyncio.Queue()
        return self._queue

    def publish_feedback(self, feedback: F) -> None:
        self._publish(self.goal_id, feedback)

    @property
    def preempt_requested(self) -> bool:
        """A newer goal waits to take this execution over (Nav2's ``is_preempt_requested``);
        :meth:`take_new_goal` takes it."""
        return self._queue is not None and not self._queue.empty()

    def take_new_goal(self) -> G | None:
        """The newest goal that took this execution over since the last call, if any."""
        newest: G | None = None
        while self._queue is not None and not self._queue.empty():
            newest = self._new_goals.get_nowait()
        return newest

    async def wait_new_goal(self) -> G:
        """Wait for a newer goal to take this execution over (replace policy)."""
        newest = await self._new_goals.get()
        return self.take_new_goal() or newest

    def _switch(self, record: GoalRecord, goal: G) -> None:
        self.record = record
        self.goal_id = record.goal_id
        self.goal = goal
        self._new_goals.put_nowait(goal)
