"""``sensor_msgs/JointState``: a base's wheel joints (what Nav2's docking plugins read
for stall detection on ``joint_states``)."""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field, model_validator

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import Header


class JointState(Msg):
    """Per joint named in ``name``: ``position`` (rad), ``velocity`` (rad/s), ``effort``
    (N m); each list empty or as long as ``name``, as ROS has it."""

    __bt_type_name__: ClassVar[str] = "sensor_msgs::msg::JointState"

    header: Header = Field(default_factory=Header)
    name: list[str] = Field(default_factory=list)
    position: list[float] = Field(default_factory=list)
    velocity: list[float] = Field(default_factory=list)
    effort: list[float] = Field(default_factory=list)

    @model_validator(mode="after")
    def _lengths(self) -> JointState:
        for field in ("position", "velocity", "effort"):
            values = getattr(self, field)
            if values and len(values) != len(self.name):
                raise ValueError(f"{field} has {len(values)} values for {len(self.name)} joints")
        return self

    def of(self, field: str, joint: str) -> float | None:
        """``field``'s value for ``joint`` (None: not named, or the field is empty)."""
        values: list[float] = getattr(self, field)
        if joint not in self.name or not values:
            return None
        return values[self.name.index(joint)]
