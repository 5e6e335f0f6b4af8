"""Does anybody watch an action server's status, feedback or results?

Wildcard publishers on ``status/*``, ``feedback/*`` and ``result/*`` that are
never put to: their matching status says whether a subscriber exists. Matching
listeners keep one flag per kind current, so unobserved goals cost no puts and
asking costs a dict lookup (not a call into Zenoh per goal).
"""

from __future__ import annotations

from typing import Any, Literal

import zenoh

from aiobt.transport import _z
from aiobt.transport.bridge import callback
from aiobt.transport.keys import ActionKeys

Kind = Literal["status", "feedback", "result"]


class Observers:
    """``observers("status")``: whether a subscriber matches that kind of key right now."""

    __slots__ = ("_entities", "_flags", "_publishers")

    def __init__(self, session: zenoh.Session, keys: ActionKeys) -> None:
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

    def _refresh(self, kind: Kind) -> None:
        self._flags[kind] = _z.matching(self._publishers[kind].matching_status)

    def __call__(self, kind: Kind) -> bool:
        return self._flags[kind]

    def close(self) -> None:
        for entity in reversed(self._entities):
            _z.undeclare(entity)
        self._entities.clear()
