"""The following server's parameters: Nav2's ``following_server`` names and defaults
(``opennav_following/src/parameter_handler.cpp`` and the docking ``controller.*``)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

from aiobt.geometry.smooth import RotateParams, SmoothControlParams

# The control law aims this far short of the desired distance, so that it never
# reaches the end of its spiral before the robot is at the desired distance
# (Nav2's ``backward_projection``).
BACKWARD_PROJECTION = 0.25
POSITIVE = ("controller_frequency", "detection_timeout", "rotate_to_object_timeout")


@dataclass(slots=True, frozen=True)
class FollowingParams:
    controller_frequency: float = 50.0  # Hz
    detection_timeout: float = 2.0  # s a detection stays good
    rotate_to_object_timeout: float = 10.0  # s of searching before FAILED_TO_CONTROL
    static_object_timeout: float = -1.0  # s at the object before success; <= 0: never
    linear_tolerance: float = 0.15  # m from the pose at the desired distance
    angular_tolerance: float = 0.15  # rad
    max_retries: int = 3
    base_frame: str = "base_link"
    fixed_frame: str = "odom"
    desired_distance: float = 1.0  # m from the object
    skip_orientation: bool = True  # aim at the object, ignore its detected heading
    search_by_rotating: bool = False  # search by turning, else wait on the last heading
    search_angle: float = math.pi / 2  # rad either side of the heading when lost
    transform_tolerance: float = 0.1  # s between a detection and the robot pose used
    odom_topic: str = "odom"
    odom_duration: float = 0.3  # Nav2's OdomSmoother window; its search turns from the raw rate
    filter_coef: float = 0.1
    controller: SmoothControlParams = field(default_factory=SmoothControlParams)
    rotate: RotateParams = field(default_factory=RotateParams)

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                continue
            if f.name in POSITIVE and not value > 0.0:
                raise ValueError(f"{f.name} must be > 0, got {value}")
            if f.name != "static_object_timeout" and not (math.isfinite(value) and value >= 0):
                raise ValueError(f"{f.name} must be >= 0, got {value}")
        if not 0.0 <= self.filter_coef <= 1.0:
            raise ValueError(f"filter_coef must be within [0, 1], got {self.filter_coef}")

    @property
    def period(self) -> float:
        return 1.0 / self.controller_frequency
