"""The bumper: contacts of the robot body turned into pressed/released events."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any

from aiobt.geometry import Pose2D, wrap_angle

TOUCH = 0.001  # m: a contact point this close (or penetrating) counts as a touch


@dataclass(slots=True, frozen=True)
class ContactEvent:
    """Contact with ``other`` ("wall" or an obstacle id) began (pressed) or ended."""

    time: float
    pressed: bool
    other: str
    x: float
    y: float
    angle: float  # direction of the contact seen from the robot, rad, 0 = ahead


class Bumper:
    """Tracks which bodies touch the robot; reports only changes."""

    __slots__ = ("_touching",)

    def __init__(self) -> None:
        self._touching: dict[str, ContactEvent] = {}

    @property
    def touching(self) -> list[str]:
        return sorted(self._touching)

    def forget(self, name: str) -> None:
        self._touching.pop(name, None)

    def update(
        self,
        points: Iterable[Sequence[Any]],
        name_of: Callable[[int], str | None],
        pose: Pose2D,
        time: float,
    ) -> list[ContactEvent]:
        """``points`` as ``getContactPoints(bodyA=robot)`` returns them."""
        current: dict[str, ContactEvent] = {}
        for point in points:
            name = name_of(point[2])
            if name is None or name in current or point[8] > TOUCH:
                continue
            x, y = point[5][0], point[5][1]
            angle = wrap_angle(math.atan2(y - pose.y, x - pose.x) - pose.yaw)
            current[name] = ContactEvent(time, True, name, x, y, angle)
        events = [e for name, e in current.items() if name not in self._touching]
        events += [
            ContactEvent(time, False, name, e.x, e.y, e.angle)
            for name, e in self._touching.items()
            if name not in current
        ]
        self._touching = current
        return events
