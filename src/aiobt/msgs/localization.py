"""Localization messages (ROS ``geometry_msgs``/``nav2_msgs`` shapes): a pose with
its covariance (``amcl_pose``, ``initialpose``), the ``map`` -> ``odom``
transform (``tf``), and the particle cloud for viewers.

``PoseWithCovarianceStamped`` also takes a ``PoseStamped`` (long or short form,
``{"x": 1, "y": 2, "yaw": 0}``) and then carries Nav2's default initial
covariance (0.5 m, 0.5 m, pi/12 rad standard deviations), as RViz's "2D Pose
Estimate" does.
"""

from __future__ import annotations

import math
from typing import Any

from pydantic import Field, field_validator, model_validator

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import Header, Pose, PoseStamped, Quaternion, Vector3

# row-major 6x6 over (x, y, z, roll, pitch, yaw); amcl_node's initial covariance
DEFAULT_INITIAL_COVARIANCE: tuple[float, ...] = tuple(
    {0: 0.25, 7: 0.25, 35: (math.pi / 12.0) ** 2}.get(i, 0.0) for i in range(36)
)


class PoseWithCovariance(Msg):
    pose: Pose = Field(default_factory=Pose)
    covariance: list[float] = Field(default_factory=lambda: [0.0] * 36)

    @field_validator("covariance")
    @classmethod
    def _six_by_six(cls, value: list[float]) -> list[float]:
        if len(value) != 36:
            raise ValueError(f"covariance must have 36 entries (row-major 6x6), got {len(value)}")
        return value


class PoseWithCovarianceStamped(Msg):
    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    pose: PoseWithCovariance = Field(default_factory=PoseWithCovariance)

    @model_validator(mode="before")
    @classmethod
    def _from_pose_stamped(cls, data: Any) -> Any:
        """A PoseStamped (or its short form) gets the default initial covariance."""
        if not isinstance(data, dict):
            return data
        inner = data.get("pose")
        plain = isinstance(inner, dict) and "covariance" not in inner and "pose" not in inner
        if plain or "pose" not in data:
            stamped = PoseStamped.model_validate(data)
            return {
                "header": stamped.header,
                "pose": {"pose": stamped.pose, "covariance": list(DEFAULT_INITIAL_COVARIANCE)},
            }
        return data

    @classmethod
    def from_xy_yaw(
        cls, x: float, y: float, yaw: float, covariance: list[float] | None = None, *,
        frame_id: str = "map", stamp: float = 0.0,
    ) -> PoseWithCovarianceStamped:  # fmt: skip
        cov = list(DEFAULT_INITIAL_COVARIANCE) if covariance is None else covariance
        return cls(
            header=Header(stamp=stamp, frame_id=frame_id),
            pose=PoseWithCovariance(pose=Pose.from_xy_yaw(x, y, yaw), covariance=cov),
        )

    def as_pose_stamped(self) -> PoseStamped:
        """The pose without its covariance."""
        return PoseStamped(header=self.header, pose=self.pose.pose)

    @property
    def x(self) -> float:
        return self.pose.pose.position.x

    @property
    def y(self) -> float:
        return self.pose.pose.position.y

    @property
    def yaw(self) -> float:
        return self.pose.pose.orientation.yaw


class Transform(Msg):
    translation: Vector3 = Field(default_factory=Vector3)
    rotation: Quaternion = Field(default_factory=Quaternion)


class TransformStamped(Msg):
    """``child_frame_id`` in ``header.frame_id`` (e.g. ``odom`` in ``map``)."""

    header: Header = Field(default_factory=Header)
    child_frame_id: str = ""
    transform: Transform = Field(default_factory=Transform)

    @property
    def yaw(self) -> float:
        return self.transform.rotation.yaw


class TFMessage(Msg):
    transforms: list[TransformStamped] = Field(default_factory=list)


class Particle(Msg):
    pose: Pose = Field(default_factory=Pose)
    weight: float = 0.0


class ParticleCloud(Msg):
    """``nav2_msgs/ParticleCloud``: particles in ``header.frame_id`` (``map``)."""

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    particles: list[Particle] = Field(default_factory=list)
