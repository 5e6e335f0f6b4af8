"""The two action executes with a fake robot, clock and goal handle (no bus)."""

from __future__ import annotations

import asyncio
from typing import Any

import numpy as np
import pytest

from aiobt.core.clock import ManualClock
from aiobt.costmap import CostGrid, GridGeometry
from aiobt.msgs import PoseStamped
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, ComputeRoute
from aiobt_services.route.actions import RouteActions
from aiobt_services.route.operations import CollisionMonitor, OperationsManager
from aiobt_services.route.planning import RouteParams, RoutePlanner
from aiobt_services.route.scorers import DistanceScorer, EdgeScorer
from aiobt_services.route.tracker import TrackerParams

from .helpers import square


class Handle:
    """The goal handle: feedback kept; :meth:`preempt` queues a newer goal."""

    def __init__(self) -> None:
        self.feedback: list[Any] = []
        self.newer: list[Any] = []

    def publish_feedback(self, feedback: Any) -> None:
        self.feedback.append(feedback)

    def preempt(self, goal: Any) -> None:
        self.newer.append(goal)

    @property
    def preempt_requested(self) -> bool:
        return bool(self.newer)

    def take_new_goal(self) -> Any:
        newest = self.newer[-1] if self.newer else None
        self.newer.clear()
        return newest


class Robot:
    """A robot at ``at``; the test moves it."""

    def __init__(self, x: float, y: float, yaw: float = 0.0) -> None:
        self.at: tuple[float, float] | None = (x, y)
        self.yaw = yaw

    def __call__(self) -> tuple[float, float, float]:
        if self.at is None:
            raise LookupError("no pose")
        return (*self.at, self.yaw)


def make(robot: Robot, grid: CostGrid | None = None, graph: bool = True) -> RouteActions:
    costmap = lambda: grid  # noqa: E731
    planner = RoutePlanner(square() if graph else None, EdgeScorer([DistanceScorer()]),
                           RouteParams(path_density=0.5), costmap)  # fmt: skip
    ops = OperationsManager([CollisionMonitor(costmap, rate=10.0)] if grid is not None else [])
    return RouteActions(planner, ops, TrackerParams(), robot, ManualClock())


def pose(x: float, y: float, frame: str = "map") -> PoseStamped:
    msg = PoseStamped.model_validate({"header": {"frame_id": frame}, "pose": {}})
    msg.pose.position.x, msg.pose.position.y = x, y
    return msg


async def test_compute_route_by_ids_returns_route_and_dense_path() -> None:
    actions = make(Robot(0, 0))
    goal = ComputeRoute.Goal(start_id=1, goal_id=3)
    result = await actions.compute_route(goal, Handle())
    assert result.error_code == 0, result.error_msg
    assert [n.nodeid for n in result.route.nodes][::2] == [1, 3]
    assert len(result.route.edges) == 2
    assert result.route.route_cost == pytest.approx(8.0)
    assert len(result.path.poses) == 17
    assert result.path.header.frame_id == "map"
    assert (result.path.poses[-1].x, result.path.poses[-1].y) == (4.0, 4.0)


async def test_compute_route_from_the_robot_pose_to_a_goal_pose() -> None:
    goal = ComputeRoute.Goal(use_poses=True, goal=pose(4.2, 4.1))
    result = await make(Robot(-0.1, -0.1)).compute_route(goal, Handle())
    assert result.error_code == 0, result.error_msg
    assert result.route.nodes[0].nodeid == 1
    assert result.route.nodes[-1].nodeid == 3
    assert len(result.route.edges) == 2
    along = await make(Robot(0.1, 0.1)).compute_route(goal, Handle())  # already along edge 1
    assert len(along.route.edges) == 1
    assert along.route.nodes[0].nodeid in (2, 4)


@pytest.mark.parametrize(
    ("goal", "robot", "graph", "code", "text"),
    [
        (ComputeRoute.Goal(start_id=1, goal_id=3), Robot(0, 0), False, 402, "no route graph"),
        (
            ComputeRoute.Goal(use_poses=True, goal=pose(1, 1, "odom")),
            Robot(0, 0),
            True,
            401,
            "frame 'odom'",
        ),
        (ComputeRoute.Goal(use_poses=True, goal=pose(1, 1)), Robot(0, 0), True, 0, ""),
        (ComputeRoute.Goal(start_id=1, goal_id=77), Robot(0, 0), True, 400, "goal_id 77"),
    ],
)
async def test_failures_carry_nav2_codes(
    goal: Any, robot: Robot, graph: bool, code: int, text: str
) -> None:
    result = await make(robot, graph=graph).compute_route(goal, Handle())
    assert result.error_code == code
    assert text in result.error_msg


async def test_no_robot_pose_is_a_tf_error() -> None:
    robot = Robot(0, 0)
    robot.at = None
    result = await make(robot).compute_route(ComputeRoute.Goal(use_poses=True, goal=pose(4, 4)),
                                             Handle())  # fmt: skip
    assert result.error_code == 401
    assert "no robot pose" in result.error_msg


async def drive_along(actions: RouteActions, robot: Robot, goal: Any, handle: Handle,
                      block: Any = None) -> Any:  # fmt: skip
    """Run the tracking goal; the robot follows the newest feedback path, 0.1 m a tick;
    ``block(at)`` is called after each tick."""
    clock = actions.clock
    assert isinstance(clock, ManualClock)
    task = asyncio.ensure_future(actions.compute_and_track_route(goal, handle))
    for _ in range(2000):
        await clock.forward(0.02, step=0.02)
        if task.done():
            return task.result()
        path = handle.feedback[-1].path.poses
        xy = np.array([(p.x, p.y) for p in path])
        here = np.asarray(robot()[:2])
        nearest = int(np.argmin(np.hypot(*(xy - here).T)))
        target = xy[min(nearest + 1, len(xy) - 1)]
        step = target - here
        dist = float(np.hypot(*step))
        moved = here + step * min(1.0, 0.1 / dist) if dist > 0 else here
        robot.at = (float(moved[0]), float(moved[1]))
        if block is not None:
            block(robot.at)
    task.cancel()
    raise AssertionError("the route was not completed")


async def test_track_route_to_its_end_with_feedback() -> None:
    robot = Robot(0.0, 0.0)
    actions = make(robot)
    handle = Handle()
    goal = ComputeAndTrackRoute.Goal(start_id=1, goal_id=3)
    result = await drive_along(actions, robot, goal, handle)
    assert result.error_code == 0
    assert result.execution_duration > 0.0
    first, last = handle.feedback[0], handle.feedback[-1]
    assert first.rerouted
    assert first.next_node_id == 1
    passed = [f.last_node_id for f in handle.feedback if not f.rerouted]
    assert passed[0] == 1
    assert passed[-1] == 3
    assert len(set(passed)) == 3
    assert last.next_node_id == 0
    assert last.current_edge_id == 0


async def test_a_blocked_edge_ahead_reroutes_the_other_way_round() -> None:
    robot = Robot(0.0, 0.0)
    costs = np.zeros((100, 100), dtype=np.uint8)
    grid = CostGrid(GridGeometry(100, 100, 0.1, -1.0, -1.0), costs)
    actions = make(robot, grid)
    handle = Handle()
    goal = ComputeAndTrackRoute.Goal(start_id=1, goal_id=3)
    first_route = await actions.compute_route(ComputeRoute.Goal(start_id=1, goal_id=3), Handle())
    first_edge = first_route.route.edges[0].edgeid  # 10 (1->2) or 14 (1->4)
    blocked_xy = (2.0, 0.0) if first_edge == 10 else (0.0, 2.0)

    def block(at: tuple[float, float]) -> None:
        col, row = int((blocked_xy[0] + 1.0) / 0.1), int((blocked_xy[1] + 1.0) / 0.1)
        costs[row - 2 : row + 3, col - 2 : col + 3] = 254  # a box on the first edge

    result = await drive_along(actions, robot, goal, handle, block)
    assert result.error_code == 0, result.error_msg
    rerouted = [f for f in handle.feedback if f.rerouted]
    assert len(rerouted) == 2  # the start and one reroute
    edges_after = [e.edgeid for e in rerouted[1].route.edges]
    assert first_edge not in edges_after
    assert edges_after[-1] in (12, 16)
    assert robot.at is not None
    assert np.hypot(robot.at[0] - 4, robot.at[1] - 4) < 1.0


async def test_a_newer_goal_takes_the_tracking_over() -> None:
    robot = Robot(0.0, 0.0)
    actions = make(robot)
    handle = Handle()
    sent: list[Any] = []

    def preempt_on_the_way(at: tuple[float, float]) -> None:
        if np.hypot(*at) > 1.0 and not sent:  # once, 1 m along the first route
            sent.append(ComputeAndTrackRoute.Goal(use_poses=True, goal=pose(4.0, 0.0)))
            handle.preempt(sent[0])

    goal = ComputeAndTrackRoute.Goal(start_id=1, goal_id=3)
    result = await drive_along(actions, robot, goal, handle, preempt_on_the_way)
    assert result.error_code == 0, result.error_msg
    planned = [f.route for f in handle.feedback if f.rerouted]
    # the newer goal's route ends at node 2 (its start node pruned when the robot is
    # already on the way from it, as Nav2's goal intent extractor does)
    assert planned[0].nodes[0].nodeid == 1
    assert [r.nodes[-1].nodeid for r in planned] == [3, 2]
    assert robot.at is not None
    assert np.hypot(robot.at[0] - 4.0, robot.at[1]) < 1.0  # it ended at node 2 (4, 0)
