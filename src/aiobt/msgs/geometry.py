"""Geometry messages (ROS ``std_msgs``/``geometry_msgs`` shapes) and yaw helpers.

Time stamps are float seconds on the robot clock. A ``PoseStamped`` may also be
given short, ``{"x": 1.0, "y": 2.0, "yaw": 0.5}`` (frame ``map`` unless a
``frame_id`` is given), as a user types it on the zenoh command line.

Point, Quaternion and PoseStamped read and write Nav2's ``;``-separated port
strings (registered with the port converters by :mod:`aiobt.msgs.strings`),
so they work as typed BT ports with XML literals.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar, Self

from pydantic import Field, model_validator

from aiobt.msgs._base import Msg
from aiobt.msgs._wire import identity_on_canonical, in_place_check

_QUATERNION_NORM_TOLERANCE = 0.01
# a norm this close to 1 is float rounding of an already normalised quaternion:
# dividing again would nudge it by an ulp on every decode (no exact round trips)
_NORMALISED = 1e-12


def yaw_to_quaternion(yaw: float) -> tuple[float, float, float, float]:
    """``(x, y, z, w)`` of a rotation by ``yaw`` radians about z."""
    half = 0.5 * yaw
    return 0.0, 0.0, math.sin(half), math.cos(half)


def pose_fields(x: float, y: float, yaw: float) -> dict[str, dict[str, float]]:
    """A :class:`Pose`'s fields as plain data, for building a message validated from one
    nested dict (one call into pydantic's core instead of one per nested model: about
    half the CPU for the robot's 50 Hz poses and the planner's paths)."""
    qx, qy, qz, qw = yaw_to_quaternion(yaw)
    return {
        "position": {"x": x, "y": y, "z": 0.0},
        "orientation": {"x": qx, "y": qy, "z": qz, "w": qw},
    }


def quaternion_to_yaw(x: float, y: float, z: float, w: float) -> float:
    """Yaw (rotation about z, radians in [-pi, pi]) of a quaternion."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


class Header(Msg):
    stamp: float = Field(default=0.0, ge=0.0, description="seconds on the robot clock")
    frame_id: str = ""


class Point(Msg):
    __bt_type_name__: ClassVar[str] = "geometry_msgs::msg::Point"

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0


class Vector3(Msg):
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0


class Quaternion(Msg):
    """A unit quaternion; inputs within 1 % of unit length are normalised, others refused."""

    __bt_type_name__: ClassVar[str] = "geometry_msgs::msg::Quaternion"

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    w: float = 1.0

    @model_validator(mode="after")
    @in_place_check  # wire_validator may run it after pydantic (see aiobt.msgs._wire)
    def _unit_length(self) -> Self:
        norm = math.sqrt(self.x**2 + self.y**2 + self.z**2 + self.w**2)
        if abs(norm - 1.0) > _QUATERNION_NORM_TOLERANCE:
            raise ValueError(f"quaternion must have unit length, got norm {norm:.6g}")
        if abs(norm - 1.0) > _NORMALISED:
            self.__dict__.update(x=self.x / norm, y=self.y / norm, z=self.z / norm, w=self.w / norm)
        return self

    @classmethod
    def from_yaw(cls, yaw: float) -> Self:
        x, y, z, w = yaw_to_quaternion(yaw)
        return cls(x=x, y=y, z=z, w=w)

    @property
    def yaw(self) -> float:
        return quaternion_to_yaw(self.x, self.y, self.z, self.w)


class Pose(Msg):
    position: Point = Field(default_factory=Point)
    orientation: Quaternion = Field(default_factory=Quaternion)

    @classmethod
    def from_xy_yaw(cls, x: float, y: float, yaw: float = 0.0) -> Self:
        return cls(position=Point(x=x, y=y), orientation=Quaternion.from_yaw(yaw))

    @property
    def yaw(self) -> float:
        return self.orientation.yaw


class _ShortPose(Msg):
    """The short goal form; validated first so errors name ``x``, ``y`` or ``yaw``."""

    x: float
    y: float
    yaw: float = 0.0
    frame_id: str = "map"
    stamp: float = Field(default=0.0, ge=0.0)


_SHORT_KEYS = frozenset(_ShortPose.model_fields)


def _is_short_form(data: dict[Any, Any]) -> bool:
    """A dict with ``x`` and no ``pose``, or any short-form key and neither ``header`` nor
    ``pose``: the long form refuses all of these keys, so only short-form errors change
    (they name a missing ``x``/``y`` instead of an "extra" key)."""
    if "pose" in data:
        return False
    return "x" in data or ("header" not in data and not _SHORT_KEYS.isdisjoint(data))


class PoseStamped(Msg):
    __bt_type_name__: ClassVar[str] = "geometry_msgs::msg::PoseStamped"

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    pose: Pose = Field(default_factory=Pose)

    @model_validator(mode="before")
    @classmethod
    @identity_on_canonical  # a long form has no short-form key (extra fields are refused)
    def _short_form(cls, data: Any) -> Any:
        if isinstance(data, dict) and _is_short_form(data):
            short = _ShortPose.model_validate(data)
            return {
                "header": {"stamp": short.stamp, "frame_id": short.frame_id},
                "pose": Pose.from_xy_yaw(short.x, short.y, short.yaw),
            }
        return data

    @classmethod
    def from_xy_yaw(
        cls, x: float, y: float, yaw: float = 0.0, frame_id: str = "map", stamp: float = 0.0
    ) -> Self:
        return cls(header=Header(stamp=stamp, frame_id=frame_id), pose=Pose.from_xy_yaw(x, y, yaw))

    @property
    def x(self) -> float:
        return self.pose.position.x

    @property
    def y(self) -> float:
        return self.pose.position.y

    @property
    def yaw(self) -> float:
        return self.pose.orientation.yaw


class Twist(Msg):
    linear: Vector3 = Field(default_factory=Vector3)
    angular: Vector3 = Field(default_factory=Vector3)

    @classmethod
    def planar(cls, vx: float, wz: float, vy: float = 0.0) -> Self:
        """A base command: forward ``vx`` m/s, sideways ``vy`` m/s, turn ``wz`` rad/s."""
        return cls(linear=Vector3(x=vx, y=vy), angular=Vector3(z=wz))
