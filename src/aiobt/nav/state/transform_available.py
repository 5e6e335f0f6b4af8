"""TransformAvailable (Nav2): are two frames connected yet?"""

from __future__ import annotations

import logging
from typing import Any

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.core.status import IDLE
from aiobt.nav.frames import frames_of
from aiobt.nav.robot_state import ODOM, POSE, RobotStateNode

log = logging.getLogger("aiobt.nav.transform_available")


class TransformAvailable(RobotStateNode, ConditionNode):
    """``<TransformAvailable parent="map" child="base_link"/>`` (Nav2).

    SUCCESS once both frames are known from the robot's data (``map`` and the
    base frame from ``{ns}/pose``, ``odom`` and the base frame from
    ``{ns}/odom``); from then on always SUCCESS, as Nav2. FAILURE before.
    Empty frames are an error.
    """

    READS = (POSE, ODOM)
    PORTS = (
        input_port("child", str, "", "Child frame for transform."),
        input_port("parent", str, "", "Parent frame for transform."),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._found = False

    def check(self) -> bool:
        child: str = self.get_input("child")
        parent: str = self.get_input("parent")
        if self._status is IDLE and (not child or not parent):
            raise self.logic_error(f"child frame ({child!r}) or parent frame ({parent!r}) empty")
        if self._found:
            return True
        frames = frames_of(self.robot)
        self._found = child in frames and parent in frames
        if not self._found:
            log.debug("%s: transform %s -> %s not available yet", self.path, parent, child)
        return self._found
