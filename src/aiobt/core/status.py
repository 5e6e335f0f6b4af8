"""Node status, with BehaviorTree.CPP's numeric values (used in .btlog files)."""

from __future__ import annotations

from enum import Enum


class Status(Enum):
    """The status a node reports to its parent.

    - IDLE: not started, or reset by its parent.
    - RUNNING: needs more ticks.
    - SUCCESS / FAILURE: finished; stays so until the parent resets it.
    - SKIPPED: a pre-condition skipped it; the node itself stays IDLE.
    """

    IDLE = 0
    RUNNING = 1
    SUCCESS = 2
    FAILURE = 3
    SKIPPED = 4

    @property
    def is_completed(self) -> bool:
        return self is Status.SUCCESS or self is Status.FAILURE

    @property
    def is_active(self) -> bool:
        return self is not Status.IDLE and self is not Status.SKIPPED

    @classmethod
    def of(cls, value: Status | bool | None) -> Status:
        """A leaf's return value as a Status: None and True succeed, False fails."""
        if value is None or value is True:
            return cls.SUCCESS
        if value is False:
            return cls.FAILURE
        if isinstance(value, Status):
            return value
        raise TypeError(f"a node must return a Status, a bool or None, not {value!r}")


IDLE = Status.IDLE
RUNNING = Status.RUNNING
SUCCESS = Status.SUCCESS
FAILURE = Status.FAILURE
SKIPPED = Status.SKIPPED
