"""FollowPath failures with Nav2's numeric error codes (``aiobt.msgs.FollowPathError``)."""

from __future__ import annotations

from aiobt.msgs import FollowPathError


class ControllerError(Exception):
    """A failure of the control loop, carrying its Nav2 code and a clear message."""

    def __init__(self, code: FollowPathError, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message

    def __repr__(self) -> str:
        return f"ControllerError({self.code.name}, {self.message!r})"


def no_valid_control(message: str) -> ControllerError:
    return ControllerError(FollowPathError.NO_VALID_CONTROL, message)
