"""The local costmap adapter over the costmap library, frame shifts, and wire conversion."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.costmap import INSCRIBED, LETHAL, NO_INFORMATION
from aiobt.costmap.checker import CostQuery
from aiobt.costmap.local import FrameShift, LocalCostmap, frame_transform
from aiobt.geometry import Pose2D
from aiobt.msgs import FollowPath, FollowPathError, LaserScan, Path, PoseStamped
from aiobt_services.controller.errors import ControllerError
from aiobt_services.controller.service import path_of, request_of, result_of


def _scan_with_wall_ahead(distance: float) -> LaserScan:
    ranges = [13.0] * 360  # no return
    for i in range(170, 191):  # +-10 degrees around angle 0
        ranges[i] = distance / math.cos((i - 180) * 2 * math.pi / 360)
    return LaserScan(
        angle_min=-math.pi,
        angle_max=math.pi,
        angle_increment=2 * math.pi / 360,
        range_min=0.05,
        range_max=12.0,
        ranges=ranges,
    )


def test_scan_marks_obstacle_inflates_it_and_clearing_removes_it():
    costmap = LocalCostmap()
    assert isinstance(costmap, CostQuery)
    robot = Pose2D(1.0, 1.0, math.pi / 2)  # facing +y: the wall lands at y = 2.0
    costmap.add_scan(_scan_with_wall_ahead(1.0), robot)
    probe = np.array([[1.0, 2.02], [1.0, 1.85], [1.0, 1.3], [1.0, 5.0]])
    on_wall, near, free, outside = costmap.costs_at(probe).tolist()
    assert on_wall == LETHAL
    assert near >= INSCRIBED  # within the 0.22 m robot radius of the wall
    assert free == 0
    assert outside == NO_INFORMATION  # beyond the 5 m window
    costmap.clear_around(robot, 0.5)
    assert costmap.costs_at(probe[:1]).tolist() == [LETHAL]  # 1 m away: kept
    costmap.clear_entirely()
    assert costmap.costs_at(probe[:2]).tolist() == [0, 0]


def test_frame_shift_moves_odom_queries_into_map():
    costmap = LocalCostmap()
    costmap.add_scan(_scan_with_wall_ahead(1.0), Pose2D(0.0, 0.0, 0.0))  # wall at map x = 1
    same_robot_in_odom = Pose2D(5.0, -2.0, math.pi / 2)
    shift = FrameShift(costmap, frame_transform(Pose2D(0.0, 0.0, 0.0), same_robot_in_odom))
    # 1 m ahead of the robot in odom is (5, -1): the wall
    assert shift.costs_at(np.array([[5.0, -1.0 + 0.02]])).tolist() == [LETHAL]
    inflated = int(252 * math.exp(-3.0 * (0.5 - 0.22)))  # 0.5 m from the wall
    assert shift.costs_at(np.array([[5.0, -1.5]])).tolist() == [inflated]
    assert shift.costs_at(np.array([[5.0, -1.9]])).tolist() == [0]


def test_wire_goal_converts_and_errors_map_to_nav2_codes():
    poses = [PoseStamped.from_xy_yaw(float(x), 0.0, 0.0) for x in range(3)]
    goal = FollowPath.Goal(path=Path(poses=poses), controller_id="DWB")
    request = request_of(goal)
    assert request.controller_id == "DWB"
    assert request.path.frame_id == "map"
    assert request.path.xy.tolist() == [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]
    assert len(path_of(Path())) == 0
    for code in FollowPathError:
        if code is FollowPathError.NONE:
            continue
        result = result_of(ControllerError(code, "why"))
        assert result.error_code == FollowPathError[code.name] == code.value
        assert result.error_msg == "why"
    assert result_of(None).error_code == 0


@pytest.mark.parametrize("frame", ["map", "odom"])
def test_known_frames_are_map_and_odom(frame):
    path = path_of(Path.model_validate({"header": {"frame_id": frame}, "poses": []}))
    assert path.frame_id == frame
