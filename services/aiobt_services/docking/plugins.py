"""Dock plugins (Nav2's ``opennav_docking_core::ChargingDock``): one Protocol, the
registry of the plugin classes by their Nav2 name, and their parameters from
``PLUGIN.name=value`` strings."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Protocol

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D
from aiobt.msgs import BatteryState

from .detection import Detection
from .frames import RobotFrames


@dataclass(slots=True, frozen=True)
class DockWiring:
    """What a plugin reads: the robot's frames, robot time, the newest detection of
    the dock (``detected_dock_pose``) and battery state, and where it shows the poses
    it works with (``dock_pose``, ``filtered_dock_pose``, ``staging_pose``)."""

    frames: RobotFrames
    clock: Clock
    detection: Callable[[], Detection | None]
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


PluginFactory = Callable[[str, Mapping[str, str], DockWiring], ChargingDock]


def params_from(cls: type[Any], plugin: str, given: Mapping[str, str]) -> Any:
    """``cls`` (a dataclass of parameters) from strings; ValueError naming the
    parameter that is unknown or of the wrong type."""
    fields = {f.name: f for f in dataclasses.fields(cls)}
    values: dict[str, Any] = {}
    for key, text in given.items():
        if key not in fields:
            raise ValueError(f"{plugin}.{key}: no such parameter (known: {', '.join(fields)})")
        values[key] = _convert(f"{plugin}.{key}", fields[key].type, text)
    return cls(**values)


def _convert(name: str, kind: object, text: str) -> Any:
    if kind in (bool, "bool"):
        if text.lower() not in ("true", "false"):
            raise ValueError(f"{name}: expected true or false, got {text!r}")
        return text.lower() == "true"
    if kind in (float, "float"):
        try:
            return float(text)
        except ValueError:
            raise ValueError(f"{name}: expected a number, got {text!r}") from None
    return text
