"""PathLongerOnApproach (Nav2): act when a new path near the goal is much longer."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status
from aiobt.msgs import Path
from aiobt.nav.path_math import PathGeometry


class PathLongerOnApproach(DecoratorNode):
    """``<PathLongerOnApproach path="{path}" prox_len="3.0" length_factor="2.0">child``
    (Nav2).

    Ticks the child only when the new ``path`` is an update of the previous
    one (same goal position, different number of poses), the previous path
    was shorter than ``prox_len`` (the robot is near the goal) and the new one
    is more than ``length_factor`` times longer; then it returns the child's
    status (a finished child is reset). Otherwise SUCCESS. A new goal (the
    paths end at different poses) is not an update: the check starts over.
    """

    __slots__ = ("_first", "_old")
    PORTS = (
        input_port(
            "path",
            Path,
            description="Path created by action server. Takes in a blackboard variable, e.g. "
            '"{path}".',
        ),
        input_port(
            "prox_len",
            float,
            3.0,
            "Proximity length (m) for the path to be longer on approach.",
        ),
        input_port(
            "length_factor",
            float,
            2.0,
            "Length multiplication factor to check if the path is significantly longer.",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._old = Path()
        self._first = True

    def execute_sync(self) -> Status:
        new: Path = self.get_input("path")
        old = self._old
        if not self._first and (
            not old.poses or not new.poses or old.poses[-1].pose != new.poses[-1].pose
        ):
            self._first = True
        self._set_status(RUNNING)
        if not self._first and _updated(new, old) and self._longer(new, old):
            status = self.tick_child()
            if status is RUNNING or status is SKIPPED:
                return status
            self._old = new
            self.reset_child()
            return status if status in (SUCCESS, FAILURE) else FAILURE
        self._old = new
        self._first = False
        return SUCCESS

    def _longer(self, new: Path, old: Path) -> bool:
        old_length = PathGeometry(old.poses).length()
        proximity: float = self.get_input("prox_len")
        factor: float = self.get_input("length_factor")
        return old_length < proximity and PathGeometry(new.poses).length() > factor * old_length


def _updated(new: Path, old: Path) -> bool:
    """Nav2's isPathUpdated: same goal position, another number of poses."""
    return (
        bool(old.poses)
        and bool(new.poses)
        and len(new.poses) != len(old.poses)
        and old.poses[-1].pose.position == new.poses[-1].pose.position
    )
