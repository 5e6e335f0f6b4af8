"""FollowPath goal handling: bad requests, stale poses, patience, preemption, collisions."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.costmap import LETHAL
from aiobt.costmap.checker import CollisionChecker, GridCostmap
from aiobt.geometry import PlanarPath, Pose2D, Velocity
from aiobt.msgs import FollowPathError
from aiobt.robot.freshness import FRESH, PoseAge
from aiobt.robot.state import RobotState
from aiobt_services.controller.base import ControlContext
from aiobt_services.controller.dwb import DWBController
from aiobt_services.controller.errors import ControllerError
from aiobt_services.controller.rpp import RegulatedPurePursuit
from aiobt_services.controller.session import (
    ControllerConfig,
    FollowPathSession,
    FollowRequest,
)
from aiobt_services.controller.unicycle import Unicycle

from .courses import drive, polyline, straight


def _start(request: FollowRequest, config: ControllerConfig | None = None) -> FollowPathSession:
    return FollowPathSession(request, config or ControllerConfig(), 0.0, None)


def _state(pose: Pose2D, stamp: float = 0.0, age: PoseAge = FRESH) -> dict[str, RobotState]:
    return {"map": RobotState(pose, Velocity(), stamp, age)}


@pytest.mark.parametrize(
    ("request_", "code", "message"),
    [
        (
            FollowRequest(PlanarPath.from_poses("map", [])),
            FollowPathError.INVALID_PATH,
            "path is empty",
        ),
        (
            FollowRequest(PlanarPath.from_poses("map", [(1.0, 0.0, 0.0)])),
            FollowPathError.INVALID_PATH,
            "single pose",
        ),
        (
            FollowRequest(PlanarPath.from_poses("base_link", [(0, 0, 0), (1, 0, 0)])),
            FollowPathError.TF_ERROR,
            "path frame 'base_link' is unknown",
        ),
        (
            FollowRequest(PlanarPath.from_poses("map", [(0, 0, 0), (math.nan, 0, 0)])),
            FollowPathError.INVALID_PATH,
            "path pose 1 has a non-finite x",
        ),
        (
            FollowRequest(straight(), controller_id="MPPI"),
            FollowPathError.INVALID_CONTROLLER,
            "unknown controller id 'MPPI'; known: DWB, FollowPath",
        ),
        (
            FollowRequest(straight(), goal_checker_id="nope"),
            FollowPathError.INVALID_CONTROLLER,
            "unknown goal checker id 'nope'",
        ),
        (
            FollowRequest(straight(), progress_checker_id="nope"),
            FollowPathError.INVALID_CONTROLLER,
            "unknown progress checker id 'nope'",
        ),
    ],
    ids=["empty", "single", "frame", "nan", "controller", "goal_checker", "progress_checker"],
)
def test_bad_request_gets_code_and_message(request_, code, message):
    with pytest.raises(ControllerError) as caught:
        _start(request_)
    assert caught.value.code == code
    assert message in caught.value.message


def test_empty_ids_select_the_defaults():
    session = _start(FollowRequest(straight()))
    step = session.step(0.0, _state(Pose2D(0.0, 0.0, 0.0)))
    assert step.error is None
    assert step.cmd.v > 0.0


def test_stale_pose_stops_robot_with_tf_error():
    session = _start(FollowRequest(straight()))
    assert session.step(0.0, _state(Pose2D(0, 0, 0))).cmd.v > 0.0
    late = PoseAge(robot=1.5, silence=0.4, quiet=0.0)  # delivered late at a speed-up
    assert session.step(0.05, _state(Pose2D(0, 0, 0), age=late)).error is None
    behind = PoseAge(robot=0.6, silence=0.6, quiet=0.0)  # the pose stream stopped alone
    step = session.step(0.6, _state(Pose2D(0, 0, 0), age=behind))
    assert step.cmd == Velocity(0.0, 0.0)
    assert step.error is not None
    assert step.error.code == FollowPathError.TF_ERROR
    assert step.error.message == (
        "robot pose in frame 'map' is stale (0.60 s old in robot time, none newer for "
        "0.60 s of wall time, pose_timeout 0.50 s); stopping"
    )


def test_missing_pose_is_awaited_briefly_then_a_tf_error():
    session = _start(FollowRequest(straight()))
    waiting = session.step(0.5, {})
    assert waiting.error is None
    assert waiting.cmd == Velocity(0.0, 0.0)
    step = session.step(1.1, {})
    assert step.error is not None
    assert step.error.code == FollowPathError.TF_ERROR
    assert "no robot pose received in frame 'map'" in step.error.message


def test_robot_that_does_not_move_fails_to_make_progress():
    session = _start(FollowRequest(straight()))
    pose = Pose2D(0.0, 0.0, 0.0)
    now = 0.0
    while now < 10.0:
        assert session.step(now, _state(pose, now)).error is None
        now += 0.5
    step = session.step(10.5, _state(pose, 10.5))
    assert step.error is not None
    assert step.error.code == FollowPathError.FAILED_TO_MAKE_PROGRESS


def test_time_allowance_gives_controller_timed_out():
    config = ControllerConfig(time_allowance=2.0)
    run, _ = drive(straight(10.0), config=config)
    assert run.result is not None
    assert run.result.error is not None
    assert run.result.error.code == FollowPathError.CONTROLLER_TIMED_OUT
    assert run.time == pytest.approx(2.05, abs=0.06)


def _wall_at(x: float) -> CollisionChecker:
    grid = GridCostmap.empty(8.0, 4.0, 0.05, (-2.0, -2.0))
    grid.fill_box(x, -2.0, x + 0.2, 2.0, LETHAL)
    return CollisionChecker(grid)


def test_obstacle_ahead_stops_rpp_and_patience_runs_out():
    # Nav2's controller_server: failure_tolerance > 0 stops the robot, keeps
    # trying, and ends the goal PATIENCE_EXCEEDED once the tolerance has passed
    run, robot = drive(straight(4.0), collision=_wall_at(2.0))
    assert run.result is not None
    assert run.result.error is not None
    assert run.result.error.code == FollowPathError.PATIENCE_EXCEEDED
    assert "detected collision ahead" in run.result.error.message
    assert "no valid control for 0.3" in run.result.error.message
    assert 1.0 < robot.pose.x < 2.0
    stopped = [c for c in run.commands if c == (0.0, 0.0)]
    assert len(stopped) >= round(0.3 / 0.05)  # stood still for the whole tolerance
    assert run.commands[-1] == (0.0, 0.0)


def test_obstacle_ahead_without_patience_fails_no_valid_control_at_once():
    config = ControllerConfig(failure_tolerance=0.0)
    run, robot = drive(straight(4.0), collision=_wall_at(2.0), config=config)
    assert run.result is not None
    assert run.result.error is not None
    assert run.result.error.code == FollowPathError.NO_VALID_CONTROL
    assert "detected collision ahead" in run.result.error.message
    assert 1.0 < robot.pose.x < 2.0
    assert run.commands[-2] != (0.0, 0.0)  # the first refused cycle ends the goal
    assert run.commands[-1] == (0.0, 0.0)


def test_obstacle_ahead_makes_dwb_stop_short_then_fail_to_make_progress():
    # DWB keeps standing-still samples valid, so it halts at the wall and the
    # progress checker ends the goal, as Nav2's DWB does
    run, robot = drive(straight(4.0), controller_id="DWB", collision=_wall_at(2.0))
    assert run.result is not None
    assert run.result.error is not None
    assert run.result.error.code == FollowPathError.FAILED_TO_MAKE_PROGRESS
    assert 1.0 < robot.pose.x < 2.0
    assert run.commands[-1] == (0.0, 0.0)


def test_failure_within_patience_stops_then_resumes_when_cleared():
    checker = _wall_at(2.0)
    session = FollowPathSession(FollowRequest(straight(4.0)), ControllerConfig(), 0.0, checker)
    pose = Pose2D(1.7, 0.0, 0.0)
    step = session.step(0.0, {"map": RobotState(pose, Velocity(0.5, 0.0), 0.0)})
    assert step.error is None
    assert step.cmd == Velocity(0.0, 0.0)
    assert isinstance(checker.costmap, GridCostmap)
    checker.costmap.costs[:] = 0
    step = session.step(0.1, {"map": RobotState(pose, Velocity(0.0, 0.0), 0.1)})
    assert step.error is None
    assert step.cmd.v > 0.0


def test_replace_takes_new_path_without_stopping():
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0))
    session = FollowPathSession(FollowRequest(straight(4.0)), ControllerConfig(), 0.0, None)
    now = 0.0
    for _ in range(40):
        step = session.step(now, {"map": RobotState(robot.pose, robot.velocity, now)})
        robot.step(step.cmd, 0.05)
        now += 0.05
    x = robot.pose.x
    session.replace(FollowRequest(polyline([(x - 0.5, 0.0), (x + 1.0, 0.0), (x + 1.0, 2.0)])), now)
    step = session.step(now, {"map": RobotState(robot.pose, robot.velocity, now)})
    assert step.cmd.v > 0.3  # kept moving on the new path
    assert session.request.path.goal.y == 2.0


def test_replace_with_bad_path_raises_and_keeps_old_one():
    session = _start(FollowRequest(straight()))
    with pytest.raises(ControllerError):
        session.replace(FollowRequest(PlanarPath.from_poses("map", [])), 0.1)
    assert len(session.request.path) == len(straight())


def test_feedback_reports_signed_cross_track_and_remaining_length():
    session = _start(FollowRequest(straight(4.0)))
    step = session.step(0.0, _state(Pose2D(1.0, -0.2, 0.1)))
    fb = step.feedback
    assert fb is not None
    assert fb.cross_track_error == pytest.approx(-0.2)
    assert fb.heading_error == pytest.approx(0.1)
    assert fb.remaining_path_length == pytest.approx(3.0)
    assert fb.distance_to_goal == pytest.approx(float(np.hypot(3.0, 0.2)))


def test_tracking_feedback_does_not_jump_to_a_u_turns_return_leg():
    path = polyline(
        [(0.0, 0.0), (3.0, 0.0)]
        + [(3.0 + 0.2 * math.sin(a), 0.2 - 0.2 * math.cos(a)) for a in np.linspace(0, math.pi, 20)]
        + [(0.0, 0.4)]
    )
    session = _start(FollowRequest(path))
    step = session.step(0.0, _state(Pose2D(0.5, 0.25, 0.0)))  # 0.15 m from the return leg
    fb = step.feedback
    assert fb is not None
    assert fb.cross_track_error == pytest.approx(0.25, abs=1e-6)  # left of the outbound leg
    assert fb.current_path_index in (9, 10)  # the foot point is pose 10 itself
    assert fb.remaining_path_length == pytest.approx(path.length() - 0.5, abs=0.01)


@pytest.mark.parametrize(
    ("make", "name"), [(RegulatedPurePursuit, "RegulatedPurePursuit"), (DWBController, "DWB")]
)
def test_controllers_refuse_to_drive_without_a_plan_and_forget_it_on_reset(make, name):
    controller = make()
    ctx = ControlContext(0.05, 0.25, None)
    start = Pose2D(0.0, 0.0, 0.0)
    with pytest.raises(ControllerError, match=f"^{name} has no path to follow$") as caught:
        controller.compute_velocity(start, Velocity(0.0, 0.0), ctx)
    assert caught.value.code == FollowPathError.NO_VALID_CONTROL
    controller.set_plan(straight())
    assert controller.compute_velocity(start, Velocity(0.0, 0.0), ctx).v > 0.0  # drives off
    controller.reset()
    with pytest.raises(ControllerError, match="has no path"):
        controller.compute_velocity(start, Velocity(0.0, 0.0), ctx)
