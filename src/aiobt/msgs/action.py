"""What every action shares: the definition base, result base, goal status, cancel."""

from __future__ import annotations

from enum import IntEnum
from typing import ClassVar, Generic, TypeVar, cast

from pydantic import Field

from aiobt.msgs._base import Msg


class ActionResult(Msg):
    """Base of every result: Nav2's numeric ``error_code`` (0 = success) and a message."""

    error_code: int = Field(default=0, ge=0, le=65535)
    error_msg: str = ""


class Empty(Msg):
    """A message without fields (the feedback of actions that send none)."""


GoalT = TypeVar("GoalT", bound=Msg)
ResultT = TypeVar("ResultT", bound=ActionResult)
FeedbackT = TypeVar("FeedbackT", bound=Msg)


class ActionDef(Generic[GoalT, ResultT, FeedbackT]):
    """An action type: a class holding ``Goal``, ``Result`` and ``Feedback`` models.

    Subclasses set ``name`` (Nav2's default server name, e.g.
    ``compute_path_to_pose``) and ``ErrorCode`` (the Nav2 error table).
    """

    name: ClassVar[str]
    ErrorCode: ClassVar[type[IntEnum]]

    @classmethod
    def goal_type(cls) -> type[GoalT]:
        return cast("type[GoalT]", _lookup(cls, "Goal"))

    @classmethod
    def result_type(cls) -> type[ResultT]:
        return cast("type[ResultT]", _lookup(cls, "Result"))

    @classmethod
    def feedback_type(cls) -> type[FeedbackT]:
        return cast("type[FeedbackT]", _lookup(cls, "Feedback"))


def _lookup(cls: type, attribute: str) -> type:
    for klass in cls.__mro__:
        if attribute in vars(klass):
            return cast(type, vars(klass)[attribute])
    raise TypeError(f"action type {cls.__name__} defines no {attribute}")


class GoalState(IntEnum):
    """``action_msgs/GoalStatus`` codes."""

    UNKNOWN = 0
    ACCEPTED = 1
    EXECUTING = 2
    CANCELING = 3
    SUCCEEDED = 4
    CANCELED = 5
    ABORTED = 6

    @property
    def is_terminal(self) -> bool:
        return self in (GoalState.SUCCEEDED, GoalState.CANCELED, GoalState.ABORTED)


class GoalStatus(Msg):
    """The status of one goal, published for observers under the goal's id."""

    goal_id: str
    status: GoalState
    stamp: float = Field(default=0.0, ge=0.0)
    reason: str = ""
