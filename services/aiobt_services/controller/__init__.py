"""Path following (Nav2's controller server): controllers, checkers, the FollowPath session.

The pure logic is importable without Zenoh; the service lives in ``.service``
and ``.main`` (``aiobt controller``).
"""

from aiobt.costmap.checker import CollisionChecker, CostQuery, GridCostmap
from aiobt.geometry import PlanarPath, Pose2D, Velocity, wrap_angle
from aiobt.robot.state import RobotState

from .base import ControlContext, Controller
from .checkers import SimpleGoalChecker, SimpleProgressChecker, default_checkers
from .dwb import DWBController, DWBParams
from .errors import ControllerError
from .rpp import RegulatedPurePursuit, RPPParams
from .session import ControllerConfig, FollowPathSession, FollowRequest, StepResult
from .tracking import TrackingFeedback, tracking_feedback
from .unicycle import Unicycle

__all__ = [
    "CollisionChecker",
    "ControlContext",
    "Controller",
    "ControllerConfig",
    "ControllerError",
    "CostQuery",
    "DWBController",
    "DWBParams",
    "FollowPathSession",
    "FollowRequest",
    "GridCostmap",
    "PlanarPath",
    "Pose2D",
    "RPPParams",
    "RegulatedPurePursuit",
    "RobotState",
    "SimpleGoalChecker",
    "SimpleProgressChecker",
    "StepResult",
    "TrackingFeedback",
    "Unicycle",
    "Velocity",
    "default_checkers",
    "tracking_feedback",
    "wrap_angle",
]
