"""ValidatePath and IsPathValid (Nav2): is a path still free of obstacles?"""

from __future__ import annotations

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
    The planner checks as Nav2's planner server does: from the pose closest to
    the robot, ``max_lookahead_distance`` m along the path from there (all if
    < 0), on ``layer_name``'s own costs (static_layer, obstacle_layer; "" the
    full costmap), with the ``footprint`` polygon if given (else the round robot).
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
        self._path = self.get_input_or_blackboard("path")
        return IsPathValidSrv.Request(
            path=self._path,
            max_cost=min(self.get_input("max_cost"), 255),
            consider_unknown_as_obstacle=self.get_input("consider_unknown_as_obstacle"),
            layer_name=self.get_input("layer_name", "") or "",
            footprint=self.get_input("footprint", "") or "",
            stop_at_first_collision=self._first_only(),
            max_lookahead_distance=self._lookahead(),
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
        if not response.success:
            self.log.warning("%s: the path could not be validated: %s", self.path,
                             response.message or "the service gave no reason")  # fmt: skip
            self.set_output("collision_poses", [])
            return FAILURE
        if self._first_only():  # the service stops there too; a server that did not, cut
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
