"""Round trips and validation of the wire models (no Zenoh)."""

from __future__ import annotations

import math
from typing import get_args, get_origin

import numpy as np
import numpy.typing as npt
import pytest
from pydantic import ValidationError

import aiobt.msgs as msgs
import aiobt.msgs.nav as nav
from aiobt.geometry import wrap_angle
from aiobt.msgs import MessageError, Msg, PoseStamped, decode

SAMPLES: list[Msg] = [
    msgs.Header(stamp=1.5, frame_id="map"),
    msgs.Point(x=1, y=-2, z=0.5),
    msgs.Quaternion.from_yaw(1.0),
    msgs.Pose.from_xy_yaw(1, 2, -0.5),
    PoseStamped.from_xy_yaw(3, 4, 0.25, stamp=2.0),
    msgs.Twist.planar(0.5, -0.2),
    msgs.JointState(
        name=["wheel_left_joint", "wheel_right_joint"], velocity=[1.0, -1.0], effort=[0.5, 0.25]
    ),
    msgs.Odometry(pose=msgs.Pose.from_xy_yaw(1, 1), twist=msgs.Twist.planar(0.1, 0.0)),
    msgs.LaserScan(
        angle_min=-1.0,
        angle_max=1.0,
        angle_increment=0.5,
        range_min=0.1,
        range_max=5.0,
        ranges=[1.0, 2.0, 5.5, 0.3, 4.0],
    ),
    msgs.OccupancyGrid.from_array(np.array([[0, 100, -1], [50, 0, 0]]), 0.05),
    msgs.Path(poses=[PoseStamped.from_xy_yaw(0, 0), PoseStamped.from_xy_yaw(1, 0)]),
    msgs.Goals(goals=[PoseStamped.from_xy_yaw(1, 2)]),
    msgs.BatteryState(voltage=12.0, percentage=0.5, power_supply_status=2),
    msgs.GoalStatus(goal_id="abc", status=msgs.GoalState.EXECUTING, stamp=1.0),
    msgs.Clock(clock=12.5),
    msgs.ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(1, 2), planner_id="GridBased"),
    msgs.ComputePathToPose.Result(path=msgs.Path(), planning_time=0.1, error_code=208),
    msgs.ComputePathThroughPoses.Goal(goals=msgs.Goals(goals=[PoseStamped.from_xy_yaw(1, 2)])),
    msgs.SmoothPath.Goal(path=msgs.Path(), smoother_id="simple_smoother"),
    msgs.SmoothPath.Result(was_completed=True, smoothing_duration=0.2),
    msgs.FollowPath.Goal(
        path=msgs.Path(), controller_id="FollowPath", goal_checker_id="g", progress_checker_id="p"
    ),
    msgs.FollowPath.Feedback(distance_to_goal=1.0, speed=0.3),
    msgs.FollowPath.Result(error_code=104, error_msg="patience exceeded"),
    msgs.Spin.Goal(target_yaw=1.57),
    msgs.Spin.Feedback(angular_distance_traveled=0.3),
    msgs.BackUp.Goal(target=msgs.Point(x=-0.15), speed=0.025),
    msgs.DriveOnHeading.Goal(target=msgs.Point(x=0.3), speed=0.1),
    msgs.Wait.Goal(time=1.0),
    msgs.Wait.Feedback(time_left=0.5),
    msgs.Wait.Result(total_elapsed_time=1.0),
    msgs.AssistedTeleop.Goal(time_allowance=5.0),
    msgs.NavigateToPose.Goal(pose=PoseStamped.from_xy_yaw(1, 2)),
    msgs.NavigateToPose.Feedback(distance_remaining=2.0, number_of_recoveries=1),
    msgs.NavigateThroughPoses.Goal(poses=msgs.Goals(goals=[PoseStamped.from_xy_yaw(1, 2)])),
    msgs.NavigateThroughPoses.Feedback(number_of_poses_remaining=3),
    msgs.ComputeCoveragePath.Goal(polygons=[[msgs.Point(x=0), msgs.Point(x=1), msgs.Point(y=1)]]),
    msgs.ComputeCoveragePath.Result(error_code=802),
    msgs.ClearEntireCostmap.Request(plugins=["obstacle_layer"]),
    msgs.ClearCostmapExceptRegion.Request(reset_distance=2.0),
    msgs.ClearCostmapAroundRobot.Request(reset_distance=1.0),
    msgs.ClearCostmapAroundPose.Request(pose=PoseStamped.from_xy_yaw(1, 1), reset_distance=0.5),
    msgs.ClearCostmapResponse(success=True),
    msgs.IsPathValid.Request(path=msgs.Path()),
    msgs.IsPathValid.Response(is_valid=False, invalid_pose_indices=[3, 4]),
]


@pytest.mark.parametrize("message", SAMPLES, ids=lambda m: type(m).__name__)
def test_round_trip_through_json(message: Msg) -> None:
    again = decode(type(message), message.to_json())
    assert again == message
    assert again.to_json() == message.to_json()


def test_short_goal_form_is_a_pose_in_map() -> None:
    goal = decode(PoseStamped, b'{"x": 1.5, "y": -2.0, "yaw": 0.5}')
    assert goal.header.frame_id == "map"
    assert (goal.x, goal.y) == (1.5, -2.0)
    assert goal.yaw == pytest.approx(0.5)
    odom = PoseStamped.model_validate({"x": 1, "y": 2, "frame_id": "odom"})
    assert odom.header.frame_id == "odom"
    assert odom.yaw == 0.0


@pytest.mark.parametrize(
    ("payload", "field"),
    [
        (b'{"x": 1, "y": NaN}', "y"),
        (b'{"x": 1, "y": 2, "yaw": Infinity}', "yaw"),
        (b'{"x": 1, "y": 2, "yam": 0}', "yam"),
        (b'{"pose": {"position": {"x": -Infinity}}}', "pose.position.x"),
        (b'{"pose": {"orientation": {"x": 0, "y": 0, "z": 0, "w": 0}}}', "pose.orientation"),
        (b'{"header": {"stamp": -1}, "pose": {}}', "header.stamp"),
        (b"[1, 2", "<payload>"),
    ],
)
def test_bad_goals_are_refused_naming_the_field(payload: bytes, field: str) -> None:
    with pytest.raises(MessageError) as caught:
        decode(PoseStamped, payload, key="robot/goal_pose")
    assert caught.value.field == field
    assert "robot/goal_pose" in str(caught.value)
    assert f"'{field}'" in str(caught.value)


@pytest.mark.parametrize(
    ("payload", "field", "reason"),
    [
        (b'{"y": 2, "yaw": 0.5}', "x", "Field required"),
        (b'{"yaw": 0.5}', "x", "Field required (and 1 more error(s))"),
        (b'{"y": 2}', "x", "Field required"),
        (b'{"x": 1, "yaw": 0.5}', "y", "Field required"),
        (b'{"y": 2, "frame_id": "odom"}', "x", "Field required"),
        (b'{"frame_id": "odom", "stamp": 1}', "x", "Field required (and 1 more error(s))"),
    ],
)
def test_a_short_goal_missing_a_coordinate_names_it(
    payload: bytes, field: str, reason: str
) -> None:
    with pytest.raises(MessageError) as caught:
        decode(PoseStamped, payload, key="robot/goal_pose")
    assert (caught.value.field, caught.value.reason) == (field, reason)
    with pytest.raises(MessageError) as caught:  # inside a list of goals: the index too
        decode(msgs.Goals, b"[" + payload + b"]", key="robot/goals")
    assert caught.value.field == f"goals.0.{field}"


@pytest.mark.parametrize(
    ("payload", "field", "reason"),
    [  # long forms (a "header" or "pose" key) keep pydantic's own errors
        (b'{"pose": {}, "y": 2}', "y", "Extra inputs are not permitted"),
        (b'{"header": {}, "yaw": 1}', "yaw", "Extra inputs are not permitted"),
        (b'{"header": {"frame_id": 1}}', "header.frame_id", "Input should be a valid string"),
        (b'{"pose": {"position": {"x": "a"}}}', "pose.position.x", None),
        (
            b'{"x": 1, "y": 2, "pose": {}}',
            "x",
            "Extra inputs are not permitted (and 1 more error(s))",
        ),
    ],
)
def test_long_form_errors_are_pydantics_own(payload: bytes, field: str, reason: str | None) -> None:
    with pytest.raises(MessageError) as caught:
        decode(PoseStamped, payload)
    assert caught.value.field == field
    if reason is not None:
        assert caught.value.reason == reason


def test_quaternions_read_back_equal_through_json() -> None:
    """Normalising is done once: a normalised quaternion is not nudged again on decode."""
    rng = np.random.default_rng(7)
    for values in rng.uniform(-1.0, 1.0, size=(500, 4)):
        values *= rng.uniform(0.995, 1.005) / np.linalg.norm(values)
        q = msgs.Quaternion(x=values[0], y=values[1], z=values[2], w=values[3])
        assert msgs.Quaternion.from_json(q.to_json()) == q
        pose = msgs.Pose(orientation=q)
        assert msgs.Pose.from_json(pose.to_json()) == pose


def test_near_unit_quaternion_is_normalised() -> None:
    q = msgs.Quaternion(z=0.707, w=0.707)
    assert math.hypot(q.z, q.w) == pytest.approx(1.0)
    assert q.yaw == pytest.approx(math.pi / 2)


@pytest.mark.parametrize("yaw", [-3.0, -1.0, 0.0, 0.5, 2.0, 3.1])
def test_yaw_helpers_invert_each_other(yaw: float) -> None:
    assert msgs.quaternion_to_yaw(*msgs.yaw_to_quaternion(yaw)) == pytest.approx(yaw)
    assert wrap_angle(yaw + 4 * math.pi) == pytest.approx(yaw)  # the one wrap, aiobt.geometry


def test_occupancy_grid_is_compact_and_numpy_inside() -> None:
    cells = np.zeros((200, 300), dtype=np.int8)
    cells[50:60, :] = 100
    grid = msgs.OccupancyGrid.from_array(cells, 0.05, origin=msgs.Pose.from_xy_yaw(-5, -5))
    assert len(grid.to_json()) < 2000  # 60k cells
    again = msgs.OccupancyGrid.from_json(grid.to_json())
    assert again.array.shape == (200, 300)
    assert np.array_equal(again.array, cells)
    assert (again.info.width, again.info.height) == (300, 200)


def test_occupancy_grid_cells_are_decoded_once_per_message(monkeypatch: pytest.MonkeyPatch) -> None:
    grid = msgs.OccupancyGrid.from_array(np.arange(-1, 99).reshape(10, 10), 0.1)
    payload = grid.to_json()
    decoded: list[int] = []
    real = nav._decode_cells

    def counting(data: bytes, meta: msgs.MapMetaData) -> npt.NDArray[np.int8]:
        decoded.append(meta.width)
        return real(data, meta)

    monkeypatch.setattr(nav, "_decode_cells", counting)
    again = msgs.OccupancyGrid.from_json(payload)
    assert decoded == [10]
    assert np.array_equal(again.array, grid.array)
    other = msgs.OccupancyGrid.from_array([[0, 100]], 0.1)  # a new grid: its own cells
    assert decoded == [10, 2]
    assert other.array.tolist() == [[0, 100]]


def test_occupancy_grid_accepts_a_plain_list_and_checks_it() -> None:
    info = {"resolution": 0.1, "width": 2, "height": 2}
    grid = msgs.validate(msgs.OccupancyGrid, {"info": info, "data": [0, 100, -1, 5]})
    assert grid.array.tolist() == [[0, 100], [-1, 5]]
    for data, reason in (([0, 101, 0, 0], r"not in \[-1, 100\]"), ([0, 1, 2], "holds 3 cells")):
        with pytest.raises(MessageError, match=reason) as caught:
            msgs.validate(msgs.OccupancyGrid, {"info": info, "data": data}, key="robot/map")
        assert caught.value.field == "data"


def test_occupancy_grid_refuses_a_zip_bomb_cheaply() -> None:
    import zlib

    bomb = zlib.compress(bytes(50_000_000))
    info = {"resolution": 0.1, "width": 10, "height": 10}
    with pytest.raises(MessageError, match="more than 100"):
        msgs.validate(msgs.OccupancyGrid, {"info": info, "data": bomb})


def test_laser_scan_consistency() -> None:
    base = {"angle_min": 0, "angle_max": 1, "range_min": 0.1, "range_max": 5.0, "ranges": [1.0]}
    with pytest.raises(MessageError) as caught:
        msgs.validate(msgs.LaserScan, {**base, "angle_increment": 0.0})
    assert caught.value.field == "angle_increment"
    with pytest.raises(MessageError) as caught:
        msgs.validate(msgs.LaserScan, {**base, "angle_increment": 0.1, "range_max": 0.05})
    assert caught.value.field == "range_max"
    with pytest.raises(MessageError) as caught:
        msgs.validate(msgs.LaserScan, {**base, "angle_increment": 0.1, "ranges": [1.0, math.nan]})
    assert caught.value.field == "ranges.1"
    scan = msgs.validate(msgs.LaserScan, {**base, "angle_increment": 0.5, "ranges": [1, 2, 3]})
    assert scan.angles_array().tolist() == [0.0, 0.5, 1.0]
    backwards = {**base, "angle_min": 1.0, "angle_max": 0.0}
    with pytest.raises(MessageError) as caught:  # max below min with a positive step
        msgs.validate(msgs.LaserScan, {**backwards, "angle_increment": 0.5})
    assert caught.value.field == "angle_increment"
    clockwise = msgs.validate(msgs.LaserScan, {**backwards, "angle_increment": -0.5})
    assert clockwise.angles_array().tolist() == [1.0]


def test_out_of_range_values_are_refused() -> None:
    with pytest.raises(MessageError) as caught:
        msgs.validate(msgs.BatteryState, {"percentage": 1.5})
    assert caught.value.field == "percentage"
    with pytest.raises(MessageError) as caught:
        msgs.validate(msgs.BackUp.Goal, {"target": {"x": -0.1}, "speed": -1})
    assert caught.value.field == "speed"
    with pytest.raises(MessageError) as caught:
        msgs.validate(msgs.Wait.Goal, {"time": -2})
    assert caught.value.field == "time"


def test_goals_accept_a_bare_list() -> None:
    goals = msgs.decode(msgs.Goals, b'[{"x": 1, "y": 2}, {"x": 3, "y": 4, "yaw": 1}]')
    assert [(g.x, g.y) for g in goals.goals] == [(1, 2), (3, 4)]


ACTIONS = [
    value
    for value in vars(msgs).values()
    if isinstance(value, type) and issubclass(value, msgs.ActionDef) and value is not msgs.ActionDef
]


def test_every_action_declares_the_models_its_generic_parameters_name() -> None:
    """Each action spells its models twice (``ActionDef[G, R, F]`` types the bus API,
    ``Goal``/``Result``/``Feedback`` are what callers construct): they must agree."""
    assert len(ACTIONS) == 12
    for action in ACTIONS:
        [base] = [b for b in action.__orig_bases__ if get_origin(b) is msgs.ActionDef]  # type: ignore[attr-defined]
        declared = (action.goal_type(), action.result_type(), action.feedback_type())
        assert get_args(base) == declared, action.__name__
        aliases = tuple(vars(action)[name] for name in ("Goal", "Result", "Feedback"))
        assert declared == aliases, action.__name__
        assert issubclass(action.result_type(), msgs.ActionResult), action.__name__
    assert len({action.name for action in ACTIONS}) == len(ACTIONS)
    assert msgs.FollowPath.name == "follow_path"
    assert msgs.ClearEntireCostmap.service_name("global_costmap") == (
        "global_costmap/clear_entirely_global_costmap"
    )


def test_joint_state_lists_match_the_names() -> None:
    with pytest.raises(ValidationError, match="velocity has 2 values for 1 joints"):
        msgs.JointState(name=["wheel_left_joint"], velocity=[1.0, 2.0])
    state = msgs.JointState(name=["a", "b"], effort=[0.5, 1.5])
    assert (state.of("effort", "b"), state.of("velocity", "b"), state.of("effort", "c")) == (
        1.5, None, None)  # fmt: skip
