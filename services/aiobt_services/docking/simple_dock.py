"""What Nav2's ``SimpleChargingDock`` and ``SimpleNonChargingDock`` share: a dock found
by an external detection (``use_external_detection_pose``: the ``detected_dock_pose``
topic, filtered) or taken blind from the database, docked when the robot is within
``docking_threshold`` of the dock pose.

The detector is started and stopped around each docking (``detector_service_name``,
``detector_service_timeout``, ``subscribe_toggle``: :mod:`.detector`). With
``use_stall_detection`` docked is the wheels stalled against the dock (``joint_states``:
:mod:`.stall`), not ``docking_threshold``.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import PoseFilter, StampedPose3D
from aiobt.geometry.quaternion import quat_from_rpy
from aiobt.transport.keys import Keys

from .detection import dock_pose
from .detector import DetectorControl
from .plugins import DockWiring
from .stall import is_stalled

log = logging.getLogger("aiobt_services.docking.simple_dock")


@dataclass(slots=True, frozen=True)
class SimpleDockParams:
    """Nav2's parameters of both plugins, with its defaults."""

    use_external_detection_pose: bool = False
    external_detection_timeout: float = 1.0
    external_detection_translation_x: float = -0.20
    external_detection_translation_y: float = 0.0
    external_detection_rotation_yaw: float = 0.0
    external_detection_rotation_pitch: float = 1.57
    external_detection_rotation_roll: float = -1.57
    filter_coef: float = 0.1
    use_stall_detection: bool = False
    stall_joint_names: tuple[str, ...] = ()
    stall_velocity_threshold: float = 1.0
    stall_effort_threshold: float = 1.0
    docking_threshold: float = 0.05
    staging_x_offset: float = -0.7
    staging_yaw_offset: float = 0.0
    dock_direction: str = "forward"
    rotate_to_dock: bool = False
    detector_service_name: str = ""
    detector_service_timeout: float = 5.0
    subscribe_toggle: bool = False

    def __post_init__(self) -> None:
        if not (math.isfinite(self.filter_coef) and 0.0 <= self.filter_coef <= 1.0):
            raise ValueError(f"filter_coef must be within [0, 1], got {self.filter_coef}")
        if self.dock_direction.lower() not in ("forward", "backward"):
            raise ValueError("Dock direction is not valid. Valid options are: forward or backward")
        if self.rotate_to_dock and self.dock_direction.lower() != "backward":
            raise ValueError("Parameter rotate_to_dock is enabled but dock direction is not "
                             "backward. Please set dock direction to backward.")  # fmt: skip
        if self.use_stall_detection and not self.stall_joint_names:
            raise ValueError("stall_joint_names cannot be empty! (use_stall_detection is true; "
                             "e.g. [wheel_left_joint, wheel_right_joint])")  # fmt: skip
        if self.detector_service_name:
            try:
                Keys("robot").service(self.detector_service_name.strip("/"))
            except ValueError as exc:
                raise ValueError(f"detector_service_name: {exc}") from None
        if not (math.isfinite(self.detector_service_timeout) and self.detector_service_timeout > 0):
            raise ValueError(f"detector_service_timeout must be > 0, got "
                             f"{self.detector_service_timeout}")  # fmt: skip


class SimpleDock:
    """The two plugins' common part (``is_charger`` and the charging methods are each
    one's)."""

    is_charger = True

    def __init__(self, name: str, params: SimpleDockParams, wiring: DockWiring) -> None:
        self.name = name
        self.params = params
        self.wiring = wiring
        self.backward = params.dock_direction.lower() == "backward"
        self.rotate_to_dock = params.rotate_to_dock
        self.filter = PoseFilter(params.filter_coef, params.external_detection_timeout)
        p = params
        self.rotation = quat_from_rpy(p.external_detection_rotation_roll,
                                      p.external_detection_rotation_pitch,
                                      p.external_detection_rotation_yaw)  # fmt: skip
        self.dock: tuple[Pose2D, str] | None = None  # the tracked dock pose and its frame
        if p.use_stall_detection:
            wiring.joint_states()  # subscribed from the start, as Nav2's
        self.detector = DetectorControl(wiring, service=p.detector_service_name,
                                        timeout=p.detector_service_timeout,
                                        subscribe_toggle=p.subscribe_toggle,
                                        detects=p.use_external_detection_pose)  # fmt: skip

    def staging_pose(self, dock: Pose2D, frame: str) -> Pose2D:
        if not self.params.use_external_detection_pose:
            self.dock = (dock, frame)
        offset = self.params.staging_x_offset
        staging = Pose2D(dock.x + math.cos(dock.yaw) * offset, dock.y + math.sin(dock.yaw) * offset,
                         dock.yaw + self.params.staging_yaw_offset)  # fmt: skip
        self.wiring.show("staging_pose", staging, frame)
        return staging

    def refined_pose(self, estimate: Pose2D, frame: str, dock_id: str) -> Pose2D | None:
        if not self.params.use_external_detection_pose:
            self.dock = (estimate, frame)
            self.wiring.show("dock_pose", estimate, frame)
            return estimate
        seen = self.detector.latest()
        if seen is None:
            log.warning("Waiting for first detected_dock_pose; none received yet")
            return None
        age = self.wiring.clock.now() - seen.stamp
        if age > self.params.external_detection_timeout:
            log.warning("Lost detection or did not detect: timeout exceeded (is %.2f seconds "
                        "old)", age)  # fmt: skip
            return None
        return self._refine(seen, frame)

    def _refine(self, seen: StampedPose3D, frame: str) -> Pose2D | None:
        try:
            seen = self.wiring.frames.lift(seen)  # a camera's frame: up tf_static, in 3D
            placed = self.wiring.frames.transform(Pose2D(), seen.frame, frame, seen.stamp)
        except LookupError as exc:
            log.warning("Failed to transform detected dock pose: %s", exc)
            return None
        filtered = self.filter.update(seen.moved(placed, frame))
        self.wiring.show("filtered_dock_pose", Pose2D(filtered.x, filtered.y), frame)
        p = self.params
        pose = dock_pose(filtered, self.rotation, (p.external_detection_translation_x,
                                                   p.external_detection_translation_y))  # fmt: skip
        self.dock = (pose, frame)
        self.wiring.show("dock_pose", pose, frame)
        return pose

    def is_docked(self) -> bool:
        p = self.params
        if p.use_stall_detection:
            return is_stalled(self.wiring.joint_states(), p.stall_joint_names,
                              p.stall_velocity_threshold, p.stall_effort_threshold)  # fmt: skip
        if self.dock is None:
            return False
        pose, frame = self.dock
        try:
            robot = self.wiring.frames.robot(frame)
        except LookupError:
            return False
        return math.hypot(robot.x - pose.x, robot.y - pose.y) < self.params.docking_threshold

    async def start_detection(self) -> bool:
        return await self.detector.start()

    async def stop_detection(self) -> bool:
        return await self.detector.stop()
