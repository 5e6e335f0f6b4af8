"""GoalReached (Nav2): is the robot within tolerance of the goal?"""

from __future__ import annotations

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.msgs import PoseStamped
from aiobt.nav.path_math import distance
from aiobt.nav.robot_state import RobotStateNode

GOAL_REACHED_TOL = 0.25  # m, Nav2's goal_reached_tol parameter default


class GoalReached(RobotStateNode, ConditionNode):
    """``<GoalReached goal="{goal}"/>`` (Nav2).

    SUCCESS when the robot, in the goal's frame, is within 0.25 m (Nav2's
    ``goal_reached_tol``) of ``goal``; FAILURE otherwise or without a pose.
    """

    PORTS = (
        input_port(
            "goal",
            PoseStamped,
            description='Destination to check. Takes in a blackboard variable, e.g. "{goal}".',
        ),
        input_port("robot_base_frame", str, description="Robot base frame."),
    )

    def check(self) -> bool:
        goal: PoseStamped = self.get_input("goal")
        robot = self.robot_pose(goal.header.frame_id)
        return robot is not None and distance(robot, goal) <= GOAL_REACHED_TOL
