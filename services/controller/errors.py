"""FollowPath failures with Nav2's numeric error codes (nav2_msgs/FollowPath)."""

from __future__ import annotations

from enum import IntEnum


class FollowPathCode(IntEnum):
    NONE = 0
    UNKNOWN = 100
    INVALID_CONTROLLER = 101
    TF_ERROR = 102
    INVALID_PATH = 103
    PATIENCE_EXCEEDED = 104
    FAILED_TO_MAKE_PROGRESS = 105
    NO_VALID_CONTROL = 106
    CONTROLLER_TIMED_OUT = 107


class ControllerError(Exception):
    """A failure of the control loop, carrying its Nav2 code and a clear message."""

    def __init__(self, code: FollowPathCode, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message

    def __repr__(self) -> str:
        return f"ControllerError({self.code.name}, {self.message!r})"


def invalid_path(message: str) -> ControllerError:
    return ControllerError(FollowPathCode.INVALID_PATH, message)


def no_valid_control(message: str) -> ControllerError:
    return ControllerError(FollowPathCode.NO_VALID_CONTROL, message)
