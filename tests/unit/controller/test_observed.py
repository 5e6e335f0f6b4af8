"""The controller's local plan and local costmap as observers get them."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pytest

from aiobt.costmap import CostGrid, GridGeometry
from aiobt.costmap.local import LocalCostmap, LocalCostmapParams
from aiobt.geometry import Pose2D, Velocity
from aiobt.msgs import OccupancyGrid
from aiobt.robot.freshness import PoseAge
from aiobt.robot.rate import RateGate
from aiobt.robot.state import RobotState
from aiobt_services.controller.base import NO_TRAJECTORY
from aiobt_services.controller.observed import (
    OCCUPANCY_OF_COST,
    LocalView,
    costmap_msg,
    path_msg,
)
from aiobt_services.controller.session import (
    ControllerConfig,
    FollowPathSession,
    FollowRequest,
)

from .courses import curve, straight


def test_costs_translate_as_nav2_publishes_them() -> None:
    table = OCCUPANCY_OF_COST
    assert (table[0], table[1], table[252], table[253], table[254], table[255]) == (
        0, 1, 98, 99, 100, -1,
    )  # fmt: skip
    inflated = table[1:253]
    assert np.all(np.diff(inflated.astype(int)) >= 0), "not monotonic over the inflated costs"


def test_costmap_message_keeps_geometry_and_translated_cells() -> None:
    costs = np.zeros((4, 6), dtype=np.uint8)
    costs[1, 2], costs[3, 5], costs[0, 0] = 254, 255, 128
    msg = costmap_msg(CostGrid(GridGeometry(6, 4, 0.05, -1.5, 2.25), costs), stamp=3.5)
    assert (msg.info.width, msg.info.height, msg.info.resolution) == (6, 4, 0.05)
    assert (msg.info.origin.position.x, msg.info.origin.position.y) == (-1.5, 2.25)
    assert msg.header == msg.header.model_copy(update={"stamp": 3.5, "frame_id": "map"})
    assert (msg.array[1, 2], msg.array[3, 5], msg.array[0, 0], msg.array[2, 2]) == (
        100, -1, 1 + 97 * 127 // 251, 0,
    )  # fmt: skip
    assert OccupancyGrid.from_json(msg.to_json()) == msg


def test_path_message_holds_the_poses_in_their_frame_and_empty_clears() -> None:
    poses = np.array([[0.0, 0.0, 0.0], [0.5, 0.25, math.pi / 2]])
    msg = path_msg(poses, stamp=2.0, frame_id="odom")
    assert msg.header.frame_id == "odom"
    assert [(p.x, p.y) for p in msg.poses] == [(0.0, 0.0), (0.5, 0.25)]
    assert msg.poses[1].yaw == pytest.approx(math.pi / 2)
    assert all(p.header.frame_id == "odom" for p in msg.poses)
    assert path_msg(NO_TRAJECTORY, 2.0, "map").poses == []


def test_rate_gate_lets_one_through_per_period_and_after_a_clock_reset() -> None:
    gate = RateGate(0.5)
    assert [gate.due(t) for t in (0.0, 0.2, 0.49, 0.5, 0.9, 1.01)] == [
        True, False, False, True, False, True,
    ]  # fmt: skip
    assert gate.due(0.1), "a clock that went back must not block the gate"
    gate.reset()
    assert gate.due(0.15)
    with pytest.raises(ValueError, match="period must be finite and > 0 s, got 0"):
        RateGate(0.0)


@dataclass
class FakeSink:
    matched: bool = True
    messages: list[Any] = field(default_factory=list)

    def put(self, message: Any) -> None:
        self.messages.append(message)


def _view(plan: FakeSink, costmap: FakeSink) -> tuple[LocalView, list[int]]:
    calls: list[int] = []
    local = LocalCostmap(LocalCostmapParams(size=1.0, resolution=0.1))

    def costs() -> CostGrid:
        calls.append(1)
        return local.grid()

    return LocalView(plan, costmap, costs, costmap_period=0.5), calls


def test_view_publishes_plan_each_cycle_and_costmap_at_its_rate() -> None:
    plan, costmap = FakeSink(), FakeSink()
    view, _ = _view(plan, costmap)
    view.begin()
    trajectory = np.array([[0.0, 0.0, 0.0], [0.1, 0.0, 0.0]])
    for i in range(21):  # 1 s at 20 Hz
        view.cycle(trajectory, "map", i * 0.05)
    view.end("map", 1.05)
    assert len(plan.messages) == 22
    assert all(len(m.poses) == 2 for m in plan.messages[:-1])
    assert plan.messages[-1].poses == [], "the goal's end must clear the local plan"
    assert [m.header.stamp for m in costmap.messages] == [0.0, 0.5, 1.0]
    assert all(isinstance(m, OccupancyGrid) and m.info.width == 10 for m in costmap.messages)
    view.begin()  # the next goal shows the costmap at its first cycle
    view.cycle(trajectory, "map", 1.1)
    assert len(costmap.messages) == 4


def test_view_converts_nothing_nobody_listens_to() -> None:
    plan, costmap = FakeSink(matched=False), FakeSink(matched=False)
    view, calls = _view(plan, costmap)
    view.begin()
    view.cycle(np.zeros((3, 3)), "map", 0.0)
    view.end("map", 0.1)
    assert plan.messages == []
    assert costmap.messages == []
    assert calls == []


def _session(controller_id: str, path_name: str = "curve") -> FollowPathSession:
    path = curve() if path_name == "curve" else straight()
    return FollowPathSession(FollowRequest(path, controller_id), ControllerConfig(), 0.0, None)


@pytest.mark.parametrize("controller_id", ["FollowPath", "DWB"])
def test_a_moving_command_comes_with_the_trajectory_ahead_of_the_robot(
    controller_id: str,
) -> None:
    session = _session(controller_id)
    pose = Pose2D(0.5, 0.02, 0.0)
    step = session.step(0.0, {"map": RobotState(pose, Velocity(0.4, 0.0), 0.0)})
    trajectory = step.trajectory
    assert step.cmd.v > 0.0
    assert trajectory.shape[1] == 3
    assert len(trajectory) >= 2
    ahead = trajectory[-1, 0] - pose.x
    assert 0.2 < ahead < 1.5, trajectory  # reaches forward, within the look-ahead / sim_time
    assert np.all(np.diff(trajectory[:, 0]) > -1e-9), "the trajectory goes back"


def test_rpp_local_plan_is_the_path_up_to_the_carrot() -> None:
    session = _session("FollowPath", "straight")
    step = session.step(0.0, {"map": RobotState(Pose2D(1.0, 0.1, 0.0), Velocity(0.4, 0.0), 0.0)})
    trajectory = step.trajectory
    # lookahead = 0.4 m/s * 1.5 s = 0.6 m: the carrot on y = 0 at sqrt(0.6^2 - 0.1^2) ahead
    assert trajectory[-1, 0] == pytest.approx(1.0 + math.sqrt(0.6**2 - 0.1**2), abs=1e-6)
    assert np.allclose(trajectory[:, 1], 0.0)
    assert np.allclose(trajectory[:, 2], 0.0)
    assert trajectory[0, 0] == pytest.approx(1.0, abs=0.06)  # from the foot point


def test_dwb_local_plan_starts_at_the_robot_and_follows_the_chosen_arc() -> None:
    session = _session("DWB", "straight")
    pose = Pose2D(1.0, 0.0, 0.0)
    step = session.step(0.0, {"map": RobotState(pose, Velocity(0.4, 0.0), 0.0)})
    trajectory = step.trajectory
    assert tuple(trajectory[0]) == (1.0, 0.0, 0.0)
    assert len(trajectory) == 16  # the pose and DWB's 15 sim steps
    expected = step.cmd.v * 1.5
    assert math.hypot(*(trajectory[-1, :2] - trajectory[0, :2])) == pytest.approx(
        expected, rel=0.05
    )


def test_standing_still_has_no_trajectory() -> None:
    session = _session("FollowPath")
    waiting = session.step(0.0, {})  # no pose yet: the goal waits, the robot stands
    assert waiting.trajectory.shape == (0, 3)
    old = PoseAge(robot=5.0, silence=5.0, quiet=5.0)  # the robot went quiet 5 s ago
    stale = session.step(5.0, {"map": RobotState(Pose2D(0, 0, 0), Velocity(), 0.0, old)})
    assert stale.error is not None
    assert len(stale.trajectory) == 0
