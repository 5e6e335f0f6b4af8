"""Dock plugins (Nav2's ``opennav_docking_core::ChargingDock``): the Protocol and what
a plugin is given (the registry of plugin types is ``options.PLUGIN_TYPES``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import StampedPose3D
from aiobt.msgs import BatteryState

from .frames import RobotFrames


@dataclass(slots=True, frozen=True)
class DockWiring:
    """What a plugin reads: the robot's frames, robot time, the newest detection of
    the dock (``detected_dock_pose``) and battery state, and where it shows the poses
    it works with (``dock_pose``, ``filtered_dock_pose``, ``staging_pose``)."""

    frames: RobotFrames
    clock: Clock
    detection: Callable[[], StampedPose3D | None]
    battery: Callable[[], BatteryState | None]
    show: Callable[[str, Pose2D, str], None]


class ChargingDock(Protocol):
    """A dock type (Nav2's ChargingDock; a non-charging dock says ``is_charger``
    False). Poses are planar, in the frame given."""

    name: str
    is_charger: bool
    backward: bool  # dock_direction: backward
    rotate_to_dock: bool

    def staging_pose(self, dock: Pose2D, frame: str) -> Pose2D: ...

    def refined_pose(self, estimate: Pose2D, frame: str, dock_id: str) -> Pose2D | None:
        """The dock's pose in ``frame`` now (None: not detected)."""
        ...

    def is_docked(self) -> bool: ...

    def is_charging(self) -> bool: ...

    def disable_charging(self) -> bool: ...

    def has_stopped_charging(self) -> bool: ...

    def start_detection(self) -> bool: ...

    def stop_detection(self) -> bool: ...


PluginFactory = Callable[[str, Any, DockWiring], ChargingDock]  # (name, its params, wiring)
