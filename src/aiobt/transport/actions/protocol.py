"""The action wire protocol (docs/architecture.md, the wire contract), shared by server
and client.

The client makes the goal id and sends the goal as the payload of a query on
``goal?id={id}``. The server's replies to that one query form the goal's stream,
each tagged by its attachment:

- ``accepted`` (empty payload), or ``rejected`` (payload: the reason), first;
- ``feedback`` (payload: the Feedback model), any number;
- ``result:{GoalState}`` (payload: the Result model), last; then the stream ends.

A goal done within execute's first step gets its result as the only reply: a
result or feedback before ``accepted`` implies the acceptance.

An error reply means the goal payload was refused (it names the field). A
stream that ends without a result means the server went away. Status,
feedback and result are also published on ``status/{id}``, ``feedback/{id}``
and ``result/{id}`` for observers, and ``result/{id}`` answers queries.
"""

from __future__ import annotations

import os
import re
from enum import IntEnum
from typing import Literal

from pydantic import Field

from aiobt.msgs import ActionResult, GoalState, Msg

ACCEPTED = b"accepted"
REJECTED = b"rejected"
FEEDBACK = b"feedback"
RESULT_PREFIX = b"result:"
_GOAL_ID = re.compile(r"^[A-Za-z0-9_.-]{1,64}$")
Preemption = Literal["abort", "replace"]


class ActionError(RuntimeError):
    """Base of the action client's failures."""


class ServerUnavailable(ActionError):
    """No action server answered send_goal within ``server_timeout``."""


class GoalRejected(ActionError):
    """The server refused the goal; ``reason`` says why (e.g. the bad field)."""

    def __init__(self, server: str, goal_id: str, reason: str) -> None:
        super().__init__(f"action {server}: goal {goal_id} rejected: {reason}")
        self.reason = reason


class GoalLost(ActionError):
    """The goal ended without a result: the server died, hung, or shut down."""


class CancelRequest(Msg):
    goal_id: str = Field(default="", description="empty: cancel every goal of the server")


class CancelResponse(Msg):
    goals_canceling: list[str] = Field(default_factory=list)


def new_goal_id() -> str:
    return os.urandom(16).hex()  # 32 hex chars, as a uuid4 hex, at a fraction of its cost


def valid_goal_id(goal_id: str) -> bool:
    return bool(_GOAL_ID.match(goal_id))


_RESULT_TAGS = {state: RESULT_PREFIX + str(int(state)).encode() for state in GoalState}
_STATES_BY_TAG = {tag: state for state, tag in _RESULT_TAGS.items()}


def result_tag(state: GoalState) -> bytes:
    return _RESULT_TAGS[state]


def parse_result_tag(tag: bytes) -> GoalState | None:
    """The state of a ``result:{state}`` tag; None for any other tag."""
    return _STATES_BY_TAG.get(tag)


def unknown_error_code(table: type[IntEnum]) -> int:
    """The table's UNKNOWN code (or its first non-zero one): for crashes in execute."""
    if "UNKNOWN" in table.__members__:
        return int(table["UNKNOWN"])
    return next((int(member) for member in table if int(member) != 0), 1)


def terminal_state(result: ActionResult) -> GoalState:
    return GoalState.SUCCEEDED if result.error_code == 0 else GoalState.ABORTED
