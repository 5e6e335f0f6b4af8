"""Does anybody watch an action server's status, feedback or results?

Wildcard publishers on ``status/*``, ``feedback/*`` and ``result/*`` that are
never put to: their matching status says whether a subscriber exists. Matching
listeners keep one flag per kind current, so unobserved goals cost no puts and
a "yes" costs a dict lookup; a "no" is checked with Zenoh (the listener's news
of a new subscriber can come after that subscriber's first message is due).
Statuses are stamped with the time of the change on the server's (robot) clock.
Statuses and results are put reliably (congestion control BLOCK, as the server's
replies are): a monitor must not lose a goal's end to a moment of congestion,
and there are a handful per goal. Feedback, a stream, may drop.
"""

from __future__ import annotations

from typing import Any, Literal

import zenoh

from aiobt.core.clock import Clock
from aiobt.msgs import GoalState, GoalStatus
from aiobt.transport import _z
from aiobt.transport.bridge import JSON, callback
from aiobt.transport.keys import ActionKeys

Kind = Literal["status", "feedback", "result"]
RELIABLE = zenoh.CongestionControl.BLOCK


class Observers:
    """``observers("status")``: whether a subscriber matches that kind of key right now."""

    __slots__ = ("_clock", "_entities", "_flags", "_keys", "_publishers", "_session")

    def __init__(self, session: zenoh.Session, keys: ActionKeys, clock: Clock) -> None:
        self._session = session
        self._keys = keys
        self._clock = clock
        keys_by_kind: dict[Kind, str] = {
            "status": keys.any_status,
            "feedback": keys.any_feedback,
            "result": keys.any_result,
        }
        self._flags: dict[Kind, bool] = dict.fromkeys(keys_by_kind, False)
        self._publishers: dict[Kind, zenoh.Publisher] = {}
        self._entities: list[Any] = []
        for kind, key in keys_by_kind.items():
            publisher = session.declare_publisher(key)
            self._publishers[kind] = publisher
            self._entities.append(publisher)
            self._entities.append(publisher.declare_matching_listener(self._listener(kind)))
            self._refresh(kind)  # after the listener: no change can slip in between

    def _listener(self, kind: Kind) -> zenoh.handlers.Callback[zenoh.MatchingStatus]:
        def on_change(_status: zenoh.MatchingStatus) -> None:
            self._refresh(kind)  # Zenoh thread: re-read, so the flag ends on the truth

        return callback(on_change)

    def _refresh(self, kind: Kind) -> bool:
        matching = self._flags[kind] = _z.matching(self._publishers[kind].matching_status)
        return matching

    def __call__(self, kind: Kind) -> bool:
        """A "no" is read again from Zenoh: the matching listener's news of a new
        subscriber may trail the subscriber's declaration (seen on the in-process bus:
        a watcher declared before the goal was sent missed its first statuses)."""
        return self._flags[kind] or self._refresh(kind)

    def put_status(self, goal_id: str, state: GoalState, reason: str = "") -> None:
        """Put the goal's new status, stamped now, if anybody watches statuses."""
        if not self("status"):
            return
        stamp = max(0.0, self._clock.now())
        status = GoalStatus(goal_id=goal_id, status=state, stamp=stamp, reason=reason)
        self.put(self._keys.status(goal_id), status.to_json())

    def put(self, key: str, payload: str | bytes, attachment: bytes | None = None) -> None:
        """Put a status or a result on ``key``, reliably."""
        self._session.put(
            key, payload, encoding=JSON, congestion_control=RELIABLE, attachment=attachment
        )

    def close(self) -> None:
        for entity in reversed(self._entities):
            _z.undeclare(entity)
        self._entities.clear()
