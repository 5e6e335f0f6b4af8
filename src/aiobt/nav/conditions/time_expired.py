"""Nav2's timer conditions on the tree's clock: TimeExpired, PathExpiringTimer."""

from __future__ import annotations

from typing import Any

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.core.status import IDLE
from aiobt.msgs import Path


def _period(node: ConditionNode) -> float:
    seconds: float = node.get_input("seconds")
    if seconds < 0.0:
        raise node.logic_error(f"seconds must be >= 0, not {seconds!r}")
    return seconds


class TimeExpired(ConditionNode):
    """``<TimeExpired seconds="1.0"/>`` (Nav2).

    - ticked while IDLE: starts the timer, FAILURE;
    - afterwards: FAILURE until ``seconds`` have passed, then SUCCESS and the
      timer restarts.

    Nav2's behaviour, matched here: the timer starts over whenever the parent
    resets the node to IDLE, so under a parent that resets finished children
    every tick (a Sequence that fails, a reactive parent with a RUNNING
    sibling) it never expires.
    """

    __slots__ = ("_start",)
    PORTS = (input_port("seconds", float, 1.0, "The time passed to return success (s)."),)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._start = 0.0

    def check(self) -> bool:
        now = self.clock.now()
        if self._status is IDLE:
            self._start = now
            return False
        if now - self._start < _period(self):
            return False
        self._start = now
        return True


class PathExpiringTimer(ConditionNode):
    """``<PathExpiringTimer seconds="15" path="{path}"/>`` (Nav2).

    - the very first tick starts the timer and returns FAILURE;
    - a new ``path`` (another object that also compares unequal) restarts the
      timer;
    - FAILURE until ``seconds`` have passed, then SUCCESS and the timer
      restarts.

    Unlike TimeExpired, the timer survives resets by the parent.
    """

    __slots__ = ("_path", "_start", "_started")
    PORTS = (
        input_port("seconds", float, 1.0, "Time to check if expired."),
        input_port(
            "path",
            Path,  # nav_msgs::msg::Path
            description="Check if path has been updated to enable timer reset.",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._start = 0.0
        self._started = False
        self._path: Any = None

    def check(self) -> bool:
        now = self.clock.now()
        path = self.get_input("path", None)
        if not self._started:
            self._started = True
            self._path, self._start = path, now
            return False
        if _is_new_path(path, self._path):
            self._path, self._start = path, now
        if now - self._start < _period(self):
            return False
        self._start = now
        return True


def _is_new_path(path: Any, previous: Any) -> bool:
    """A different path object that also differs in value (Nav2 compares both)."""
    if path is None or path is previous:
        return False
    return previous is None or bool(path != previous)
