"""ValidatePath and IsPathValid (Nav2): is a path still free of obstacles?"""

from __future__ import annotations

import math
from typing import Any

from aiobt.core.node import NodeKind
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import IsPathValid as IsPathValidSrv
from aiobt.msgs import Msg, Path
from aiobt.nav.remote import service_ports
from aiobt.nav.services.base import BtService

POSES = "vector<geometry_msgs::msg::PoseStamped>"
_CHECKS = (
    input_port("path", Path, description="The global path to check for validity."),
    input_port("max_cost", int, 254, "The maximum allowable cost for the path to be valid."),
    input_port("consider_unknown_as_obstacle", bool, False, "Unknown cost (255) is an obstacle."),
    input_port("layer_name", str, "", "Costmap layer to check; empty: the full costmap."),
    input_port("footprint", str, "", "Custom footprint; empty: the robot's footprint."),
)
_COLLISIONS = output_port("collision_poses", POSES, description="Poses in collision.")


class ValidatePath(BtService):
    """``<ValidatePath path="{remaining_path}"/>``: asks the planner's costmap.

    - SUCCESS: the path is valid (``collision_poses`` empty);
    - FAILURE: a pose costs more than ``max_cost``; ``collision_poses`` lists them
      (only the first unless ``stop_at_first_collision`` is false), or the service
      did not answer within ``server_timeout``.
    ``max_lookahead_distance`` >= 0 checks only that length of path from its start.
    The planner checks the full costmap with the robot's footprint: a
    ``layer_name`` or ``footprint`` is refused with a clear error.
    """

    SERVICE = IsPathValidSrv.service_name
    RESPONSE = IsPathValidSrv.Response
    PORTS = service_ports(
        SERVICE,
        *_CHECKS,
        input_port("stop_at_first_collision", bool, True, "Stop at the first collision."),
        input_port("max_lookahead_distance", float, -1.0, "Path length to check (m); < 0: all."),
        _COLLISIONS,
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._path = Path()

    def make_request(self) -> Msg:
        for unsupported in ("layer_name", "footprint"):
            if self.get_input(unsupported, ""):
                raise ValueError(
                    f"[{unsupported}]: the planner's is_path_valid checks the full "
                    "costmap with the robot's footprint; leave it empty"
                )
        self._path = _ahead(self.get_input_or_blackboard("path"), self._lookahead())
        return IsPathValidSrv.Request(
            path=self._path,
            max_cost=min(self.get_input("max_cost"), 255),
            consider_unknown_as_obstacle=self.get_input("consider_unknown_as_obstacle"),
        )

    def _lookahead(self) -> float:
        value = self.get_input("max_lookahead_distance", -1.0)
        return float(value)

    def _first_only(self) -> bool:
        return bool(self.get_input("stop_at_first_collision", True))

    def on_completion(self, response: Any) -> Status:
        indices = [i for i in response.invalid_pose_indices if 0 <= i < len(self._path.poses)]
        if response.is_valid:
            self.set_output("collision_poses", [])
            return SUCCESS
        if self._first_only():
            indices = indices[:1]
        self.log.warning("%s: path validation failed. Invalid pose indices: %s", self.path, indices)
        self.set_output("collision_poses", [self._path.poses[i] for i in indices])
        return FAILURE


class IsPathValid(ValidatePath):
    """``<IsPathValid path="{path}"/>``: Nav2's condition form (jazzy and older trees):
    SUCCESS if the path is valid, else FAILURE; RUNNING only while the planner answers."""

    KIND = NodeKind.CONDITION
    PORTS = service_ports(
        IsPathValidSrv.service_name,
        *_CHECKS,
        input_port("check_full_path", bool, False, "Check every pose, not only up to the first."),
        _COLLISIONS,
    )

    def _lookahead(self) -> float:
        return -1.0

    def _first_only(self) -> bool:
        return not self.get_input("check_full_path", False)


def _ahead(path: Path, distance: float) -> Path:
    """The first ``distance`` metres of ``path`` (all of it if ``distance`` < 0)."""
    if distance < 0 or not path.poses:
        return path
    travelled, last = 0.0, path.poses[0]
    for index, pose in enumerate(path.poses[1:], start=1):
        travelled += math.hypot(pose.x - last.x, pose.y - last.y)
        if travelled > distance:
            return path.model_copy(update={"poses": path.poses[:index]})
        last = pose
    return path
