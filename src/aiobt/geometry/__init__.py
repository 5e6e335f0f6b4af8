"""Planar geometry written once for the library, the services, viewers and pictures:
poses, velocities, the angle wrap, paths."""

from .path import FloatArray, PlanarPath, integrate_arc, to_robot_frame
from .pose import STOP, Pose2D, Velocity, XYYaw, turn_rate, wrap_angle

__all__ = [
    "STOP",
    "FloatArray",
    "PlanarPath",
    "Pose2D",
    "Velocity",
    "XYYaw",
    "integrate_arc",
    "to_robot_frame",
    "turn_rate",
    "wrap_angle",
]
