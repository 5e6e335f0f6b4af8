"""The docking server's controller (Nav2's ``opennav_docking::Controller``): the
graceful control law toward a pose in the robot's frame, and the turn in place.

Collision checking of the projected trajectory (``controller.use_collision_detection``,
Nav2's default true) is not available here: the server keeps no local costmap; the
flag must be false (see README).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from aiobt.geometry import Pose2D, Velocity

from .control_law import ControlLawParams, SmoothControlLaw


@dataclass(slots=True, frozen=True)
class ControllerParams:
    law: ControlLawParams = field(default_factory=ControlLawParams)
    use_collision_detection: bool = False

    def __post_init__(self) -> None:
        if self.use_collision_detection:
            raise ValueError("controller.use_collision_detection: the docking server here keeps "
                             "no costmap to check against; set it false")  # fmt: skip


class DockController:
    def __init__(self, params: ControllerParams) -> None:
        self.params = params
        self.law = SmoothControlLaw(params.law)

    def command(self, target: Pose2D, backward: bool) -> Velocity:
        """Toward ``target``, given in the robot's frame."""
        return self.law.velocity(target, None, backward)

    def rotate(self, angle_to_go: float, angular_now: float, dt: float) -> Velocity:
        return Velocity(0.0, self.law.rotate_to_heading(angle_to_go, angular_now, dt))
