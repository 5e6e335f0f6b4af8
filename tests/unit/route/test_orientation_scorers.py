"""The orientation scorers: Nav2's cases (nav2_route/test/test_edge_scorers.cpp), which
edges they score (START before END), and how they steer a search and a request."""

from __future__ import annotations

import asyncio
import math
from typing import Any

import pytest

from aiobt.core.clock import ManualClock
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, ComputeRoute
from aiobt_services.route.actions import RouteActions
from aiobt_services.route.errors import RouteError
from aiobt_services.route.graph import Graph
from aiobt_services.route.intent import ReroutingState
from aiobt_services.route.operations import OperationsManager, ReroutingService
from aiobt_services.route.orientation_scorers import (
    GoalOrientationScorer,
    StartPoseOrientationScorer,
)
from aiobt_services.route.planning import RouteParams, RoutePlanner
from aiobt_services.route.request import BY_IDS, EdgeType, RouteRequest
from aiobt_services.route.scorers import DistanceScorer, EdgeScorer, Scorer
from aiobt_services.route.search import find_route
from aiobt_services.route.tracker import TrackerParams

from .helpers import line, square

EAST = line(0.0, 1.0).edges[101]  # node 1 (0, 0) -> node 2 (1, 0)
WEST = line(1.0, 0.0).edges[101]  # (1, 0) -> (0, 0)
FACING_EAST = RouteRequest(True, start_yaw=0.0, goal_yaw=0.0)


@pytest.mark.parametrize(
    ("scorer", "edge_type"),
    [(StartPoseOrientationScorer, "START"), (GoalOrientationScorer, "END")],
)
def test_nav2s_threshold_and_weighted_cases(scorer: type[Scorer], edge_type: EdgeType) -> None:
    threshold = scorer(orientation_tolerance=1.57, use_orientation_threshold=True)  # type: ignore[call-arg]
    assert threshold.score(EAST, FACING_EAST, edge_type) == 0.0
    assert threshold.score(WEST, FACING_EAST, edge_type) is None  # pi off: closed
    weighted = scorer(orientation_tolerance=1.57, orientation_weight=100.0)  # type: ignore[call-arg]
    assert weighted.score(EAST, FACING_EAST, edge_type) == 0.0
    assert weighted.score(WEST, FACING_EAST, edge_type) == pytest.approx(100 * math.pi, abs=1e-3)
    with pytest.raises(RouteError) as caught:
        weighted.score(WEST, BY_IDS, edge_type)
    assert caught.value.reason == "INVALID_EDGE_SCORER_USE"
    assert caught.value.code == 407
    assert scorer.__name__ in caught.value.message


def test_defaults_and_only_their_own_edges() -> None:
    start, goal = StartPoseOrientationScorer(), GoalOrientationScorer()
    assert (start.orientation_tolerance, start.orientation_weight) == (math.pi / 2, 1.0)
    assert not start.use_orientation_threshold
    north = RouteRequest(True, start_yaw=math.pi / 2, goal_yaw=-math.pi / 2)
    assert start.score(EAST, north, "START") == pytest.approx(math.pi / 2)
    assert goal.score(EAST, north, "END") == pytest.approx(math.pi / 2)
    at_the_limit = StartPoseOrientationScorer(use_orientation_threshold=True)
    assert at_the_limit.score(EAST, north, "START") == pytest.approx(math.pi / 2)  # still costs
    not_start: tuple[EdgeType, ...] = ("NONE", "END")
    not_end: tuple[EdgeType, ...] = ("NONE", "START")
    assert all(start.score(WEST, north, other) == 0.0 for other in not_start)
    assert all(goal.score(WEST, north, other) == 0.0 for other in not_end)
    angled = RouteRequest(True, start_yaw=3.0, goal_yaw=-3.0)  # across the +-pi seam
    assert start.score(WEST, angled, "START") == pytest.approx(math.pi - 3.0)
    assert goal.score(WEST, angled, "END") == pytest.approx(math.pi - 3.0)


def ids(graph: Graph, a: int, b: int, scorer: EdgeScorer, request: RouteRequest) -> list[int]:
    start, goal = graph.node(a), graph.node(b)
    assert start is not None
    assert goal is not None
    return [e.edgeid for e in find_route(graph, start, goal, scorer, request=request).edges]


def test_the_start_heading_and_the_goal_heading_pick_the_way_round() -> None:
    graph = square()  # 1 (0,0) -> 3 (4,4): east then north (10, 12), or north then east (14, 16)
    start = EdgeScorer([DistanceScorer(), StartPoseOrientationScorer()])
    assert ids(graph, 1, 3, start, RouteRequest(True, start_yaw=0.0)) == [10, 12]
    assert ids(graph, 1, 3, start, RouteRequest(True, start_yaw=math.pi / 2)) == [14, 16]
    goal = EdgeScorer([DistanceScorer(), GoalOrientationScorer()])
    assert ids(graph, 1, 3, goal, RouteRequest(True, goal_yaw=math.pi / 2)) == [10, 12]
    assert ids(graph, 1, 3, goal, RouteRequest(True, goal_yaw=0.0)) == [14, 16]
    narrow = StartPoseOrientationScorer(use_orientation_threshold=True, orientation_tolerance=0.5)
    only = EdgeScorer([DistanceScorer(), narrow])
    with pytest.raises(RouteError, match="no route from node 1 to node 3"):
        ids(graph, 1, 3, only, RouteRequest(True, start_yaw=-math.pi / 4))  # facing neither
    with pytest.raises(RouteError) as caught:
        ids(graph, 1, 3, start, BY_IDS)
    assert caught.value.reason == "INVALID_EDGE_SCORER_USE"


def test_an_edge_from_start_to_goal_is_a_start_edge() -> None:
    graph = line(0.0, 1.0)
    goal = EdgeScorer([GoalOrientationScorer(use_orientation_threshold=True)])
    backwards = RouteRequest(True, start_yaw=0.0, goal_yaw=math.pi)
    assert ids(graph, 1, 2, goal, backwards) == [101]  # START, so the goal scorer lets it be


def planner(scorer: Scorer) -> RoutePlanner:
    return RoutePlanner(square(), EdgeScorer([DistanceScorer(), scorer]), RouteParams(),
                        lambda: None)  # fmt: skip


def test_a_reroute_scores_from_the_robot_s_heading_where_it_rerouted() -> None:
    request = RouteRequest(True, start=(0.0, 0.0), goal=(4.0, 4.0), start_yaw=0.0)
    route, _ = planner(StartPoseOrientationScorer()).plan(request, ReroutingState())
    assert [e.edgeid for e in route.edges] == [10, 12]
    rerouting = ReroutingState(start_id=1, start_pose=(0.0, 0.0), start_yaw=math.pi / 2)
    route, _ = planner(StartPoseOrientationScorer()).plan(request, rerouting)
    assert [e.edgeid for e in route.edges] == [14, 16]


class Robot:
    def __init__(self, yaw: float) -> None:
        self.yaw = yaw
        self.at = (-0.1, -0.1)

    def __call__(self) -> tuple[float, float, float]:
        return (*self.at, self.yaw)


async def test_compute_route_takes_the_robot_s_heading_and_the_goal_s() -> None:
    def actions(scorer: Scorer, yaw: float) -> RouteActions:
        return RouteActions(planner(scorer), OperationsManager([]), TrackerParams(), Robot(yaw),
                            ManualClock())  # fmt: skip

    goal = ComputeRoute.Goal.model_validate(
        {"use_poses": True, "goal": {"x": 4.2, "y": 4.1, "yaw": 0.0}}
    )
    north = await actions(StartPoseOrientationScorer(), math.pi / 2).compute_route(goal, None)
    assert north.error_code == 0, north.error_msg
    assert [e.edgeid for e in north.route.edges] == [14, 16]
    east = await actions(StartPoseOrientationScorer(), 0.0).compute_route(goal, None)
    assert [e.edgeid for e in east.route.edges] == [10, 12]
    by_goal = await actions(GoalOrientationScorer(), math.pi / 2).compute_route(goal, None)
    assert [e.edgeid for e in by_goal.route.edges] == [14, 16]  # arriving heading east
    facing_north = ComputeRoute.Goal.model_validate(
        {"use_poses": True, "goal": {"x": 4.2, "y": 4.1, "yaw": math.pi / 2}}
    )
    by_goal = await actions(GoalOrientationScorer(), 0.0).compute_route(facing_north, None)
    assert [e.edgeid for e in by_goal.route.edges] == [10, 12]  # arriving heading north
    given = goal.model_copy(update={"use_start": True})
    given.start = ComputeRoute.Goal.model_validate({"start": {"x": 0, "y": 0, "yaw": 1.5}}).start
    from_start = await actions(StartPoseOrientationScorer(), 0.0).compute_route(given, None)
    assert [e.edgeid for e in from_start.route.edges] == [14, 16]  # the start pose's heading
    by_ids = await actions(GoalOrientationScorer(), 0.0).compute_route(
        ComputeRoute.Goal(start_id=1, goal_id=3), None
    )
    assert by_ids.error_code == ComputeRoute.ErrorCode.INVALID_EDGE_SCORER_USE
    assert "GoalOrientationScorer needs a goal pose" in by_ids.error_msg


class Handle:
    def __init__(self) -> None:
        self.feedback: list[Any] = []
        self.preempt_requested = False

    def publish_feedback(self, feedback: Any) -> None:
        self.feedback.append(feedback)

    def take_new_goal(self) -> None:
        return None


async def test_a_reroute_while_tracking_takes_the_robot_s_heading_then() -> None:
    robot, clock, rerouting = Robot(0.0), ManualClock(), ReroutingService()
    robot.at = (0.0, 0.0)
    actions = RouteActions(planner(StartPoseOrientationScorer()), OperationsManager([rerouting]),
                           TrackerParams(), robot, clock)  # fmt: skip
    goal = ComputeAndTrackRoute.Goal.model_validate({"use_poses": True, "goal": {"x": 4, "y": 4}})
    handle = Handle()
    task = asyncio.ensure_future(actions.compute_and_track_route(goal, handle))
    await clock.forward(0.1, step=0.02)
    assert [e.edgeid for e in handle.feedback[0].route.edges] == [10, 12]  # facing east
    robot.yaw, rerouting.requested = math.pi / 2, True  # turned north, at node 1 still
    await clock.forward(0.1, step=0.02)
    task.cancel()
    rerouted = [f for f in handle.feedback if f.rerouted]
    assert len(rerouted) == 2
    assert [e.edgeid for e in rerouted[1].route.edges] == [14, 16]
