"""The following server's failures, as Nav2's (``opennav_docking_core``'s exceptions
the following server throws, and the ``FollowObject`` result codes they map to)."""

from __future__ import annotations

from aiobt.msgs.remote_actions import FollowObjectError


class FollowingError(Exception):
    """A failure with Nav2's ``reason`` (a :class:`FollowObjectError` name) and a
    message naming what and where."""

    reason = "UNKNOWN"

    def __init__(self, message: str, reason: str | None = None) -> None:
        super().__init__(message)
        if reason is not None:
            if reason not in FollowObjectError.__members__:
                raise ValueError(f"following error: unknown reason {reason!r}")
            self.reason = reason
        self.message = message

    @property
    def code(self) -> int:
        return int(FollowObjectError[self.reason])


class FailedToDetect(FollowingError):
    """No fresh detection of the object (Nav2's ``FailedToDetectDock``): retried."""

    reason = "FAILED_TO_DETECT_OBJECT"


class FailedToControl(FollowingError):
    """No usable command, or the search timed out (Nav2's ``FailedToControl``)."""

    reason = "FAILED_TO_CONTROL"


class TransformError(FollowingError):
    """A pose that cannot be put in the fixed frame (Nav2's ``TF_ERROR``)."""

    reason = "TF_ERROR"
