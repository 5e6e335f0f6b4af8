"""The action server's goal check: id, payload, the user's ``accept``, duplicates.

A goal that fails is answered here (an error reply naming the field, or a
rejection with the reason) and its query ends; a good one goes on to the server.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Generic, TypeVar

import zenoh

from aiobt.msgs import MessageError, Msg, decoder
from aiobt.transport import _z
from aiobt.transport.actions import protocol as p
from aiobt.transport.actions.goals import RecentIds
from aiobt.transport.bridge import LoopBridge, PayloadTooLarge
from aiobt.transport.services import query_payload

G = TypeVar("G", bound=Msg)


class GoalIntake(Generic[G]):
    """Checks goal queries (in Zenoh's thread unless ``accept`` is user code)."""

    def __init__(
        self,
        goal_key: str,
        model: type[G],
        bridge: LoopBridge,
        accept: Callable[[G], str | None] | None,
    ) -> None:
        self.accept = accept
        self._goal_key = goal_key
        self._decode = decoder(model, key=goal_key)
        self._bridge = bridge
        self._recent_ids = RecentIds()

    def check(self, query: zenoh.Query) -> tuple[str, G] | None:
        """The goal id and goal, or None once the query has been answered with an error
        or a rejection."""
        goal_id = query.parameters.get("id") or ""
        try:
            goal = self._decode_goal(goal_id, query)
        except (MessageError, PayloadTooLarge, ValueError) as exc:
            query.reply_err(f"bad goal: {exc}")
            _z.drop(query)
            return None
        reason = self.accept(goal) if self.accept else None
        if reason is None and not self._recent_ids.add(goal_id):
            reason = f"duplicate goal id {goal_id}"
        if reason is not None:
            query.reply(query.key_expr, reason.encode(), attachment=p.REJECTED)
            _z.drop(query)
            return None
        return goal_id, goal

    def _decode_goal(self, goal_id: str, query: zenoh.Query) -> G:
        if not p.valid_goal_id(goal_id):
            raise ValueError(f"goal id {goal_id!r} must be 1-64 of [A-Za-z0-9_.-]")
        payload = query_payload(query)
        self._bridge.check_size(self._goal_key, payload)
        return self._decode(payload)
