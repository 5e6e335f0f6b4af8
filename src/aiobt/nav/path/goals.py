"""Nav2's goal-list utilities: GetNextFewGoals, AppendGoalPoseToGoals, ExtractRouteNodesAsGoals."""

from __future__ import annotations

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import Goals, PoseStamped, Route
from aiobt.msgs.geometry import Point, Pose


class GetNextFewGoals(SyncActionNode):
    """``<GetNextFewGoals num_goals="3" input_goals="{goals}" output_goals="{next}"/>``
    (Nav2): SUCCESS, writing the first ``num_goals`` goals; FAILURE with no goals."""

    __slots__ = ()
    PORTS = (
        input_port("num_goals", int, description="How many of the goals to take."),
        input_port("input_goals", Goals, description="Input goals list."),
        output_port("output_goals", Goals, description="The output pruned goals list."),
    )

    def on_tick(self) -> Status:
        goals: Goals = self.get_input("input_goals")
        count: int = self.get_input("num_goals")
        if count < 0:
            raise self.logic_error(f"num_goals must be >= 0, not {count}")
        if not goals.goals:
            return FAILURE
        kept = Goals.model_construct(header=goals.header, goals=goals.goals[:count])
        self.set_output("output_goals", kept)
        return SUCCESS


class AppendGoalPoseToGoals(SyncActionNode):
    """``<AppendGoalPoseToGoals goal_pose="{goal}" input_goals="{goals}"
    output_goals="{goals}"/>`` (Nav2): SUCCESS, writing the goals with ``goal_pose``
    appended (an unset ``input_goals`` is an empty list)."""

    __slots__ = ()
    PORTS = (
        input_port("goal_pose", PoseStamped, description="Goal pose to append."),
        input_port("input_goals", Goals, description="Input goals vector to append to."),
        output_port("output_goals", Goals, description="Output goals vector appended to."),
    )

    def on_tick(self) -> Status:
        goal: PoseStamped = self.get_input("goal_pose")
        goals: Goals = self.get_input("input_goals", Goals())
        appended = Goals.model_construct(header=goals.header, goals=[*goals.goals, goal])
        self.set_output("output_goals", appended)
        return SUCCESS


class ExtractRouteNodesAsGoals(SyncActionNode):
    """``<ExtractRouteNodesAsGoals route="{route}" goals="{goals}"/>`` (Nav2): SUCCESS,
    writing one goal per route node (its position, the route's header); FAILURE for a
    route without nodes."""

    __slots__ = ()
    PORTS = (
        input_port("route", Route, description="Route to convert its `nodes` into Goals."),
        output_port("goals", Goals, description="Goals comprising the route's `nodes`."),
    )

    def on_tick(self) -> Status:
        route: Route = self.get_input("route")
        if not route.nodes:
            return FAILURE
        goals = [
            PoseStamped(
                header=route.header,
                pose=Pose(position=Point(x=node.position.x, y=node.position.y)),
            )
            for node in route.nodes
        ]
        self.set_output("goals", Goals(header=route.header, goals=goals))
        return SUCCESS
