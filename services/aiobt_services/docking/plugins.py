"""Dock plugins (Nav2's ``opennav_docking_core::ChargingDock``): the Protocol and what
a plugin is given (the registry of plugin types is ``options.PLUGIN_TYPES``)."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Any, Protocol

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import StampedPose3D
from aiobt.msgs import BatteryState, JointState

from .frames import RobotFrames


def _always_subscribed(on: bool) -> None:
    return None


async def _no_services(name: str, timeout: float) -> str | None:  # noqa: ASYNC109
    return f"no service client to call '{name}'"


@dataclass(slots=True, frozen=True)
class DockWiring:
    """What a plugin reads: the robot's frames, robot time, the newest detection of
    the dock (``detected_dock_pose``; None while unsubscribed) and battery state, and
    where it shows the poses it works with (``dock_pose``, ``filtered_dock_pose``,
    ``staging_pose``); ``subscribe(True/False)`` opens and closes its subscription to
    the detections (``subscribe_toggle``), ``trigger(name, timeout)`` calls a
    ``std_srvs/Trigger`` service ``{ns}/srv/{name}``: None when it succeeded, else why
    not (``detector_service_name``); ``joint_states()`` the newest of the wheels (stall
    detection; subscribed at the first call)."""

    frames: RobotFrames
    clock: Clock
    detection: Callable[[], StampedPose3D | None]
    battery: Callable[[], BatteryState | None]
    show: Callable[[str, Pose2D, str], None]
    subscribe: Callable[[bool], None] = _always_subscribed
    trigger: Callable[[str, float], Awaitable[str | None]] = _no_services
    joint_states: Callable[[], JointState | None] = lambda: None


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

    async def start_detection(self) -> bool:
        """Nav2's startDetectionProcess: before the first refined pose of a docking."""
        ...

    async def stop_detection(self) -> bool:
        """Nav2's stopDetectionProcess: once the docking ends, however it ends."""
        ...


PluginFactory = Callable[[str, Any, DockWiring], ChargingDock]  # (name, its params, wiring)
