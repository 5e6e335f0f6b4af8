"""The follow_object execute: following at the desired distance, the search, and
every failure with Nav2's code and a message naming what."""

from __future__ import annotations

import math

import pytest

from aiobt.geometry import STOP, Pose2D
from aiobt.geometry.smooth import SmoothControlParams
from aiobt.msgs.remote_actions import FollowObjectError
from aiobt_services.following.follow import FollowingState
from aiobt_services.following.params import FollowingParams

from .kinematic import Kinematic

FAST = SmoothControlParams(v_linear_max=0.5, v_angular_max=1.0)


def walking(t: float) -> Pose2D:
    """An object starting 2 m ahead, walking along +x at 0.3 m/s."""
    return Pose2D(2.0 + 0.3 * t, 0.0, 0.0)


async def test_it_keeps_the_desired_distance_behind_a_walking_object() -> None:
    world = Kinematic(walking, FollowingParams(controller=FAST))
    result = await world.follow(pose_topic="dynamic_pose", max_duration=20.0)
    assert result.error_code == 0
    assert result.total_elapsed_time == pytest.approx(20.0, abs=0.1)
    gap = walking(world.time).x - world.robot.x
    assert 1.0 <= gap <= 1.0 + 0.15 + 0.1  # stops within linear_tolerance, then catches up
    assert FollowingState.CONTROLLING in world.states
    assert world.commands[-1] == STOP  # the goal's end stops the robot
    assert world.opened == ["dynamic_pose"]


async def test_a_still_object_is_reached_and_static_object_timeout_ends_the_goal() -> None:
    world = Kinematic(lambda t: Pose2D(3.0, 1.0, 0.0), FollowingParams(static_object_timeout=2.0))
    result = await world.follow(pose_topic="dynamic_pose")
    assert result.error_code == 0
    assert world.robot.distance_to(Pose2D(3.0, 1.0)) == pytest.approx(1.0, abs=0.15)
    assert world.states[-1] == FollowingState.STOPPING


async def test_an_object_never_seen_fails_naming_its_topic() -> None:
    world = Kinematic(lambda t: None, FollowingParams())
    result = await world.follow(pose_topic="people/alice")
    assert result.error_code == FollowObjectError.FAILED_TO_DETECT_OBJECT
    assert "robot/people/alice" in result.error_msg
    assert "within 2 s (detection_timeout)" in result.error_msg
    assert result.num_retries == 4  # Nav2: max_retries 3, failed on the fourth
    assert world.commands[-1] == STOP


async def test_never_seen_while_searching_is_still_a_detection_failure() -> None:
    world = Kinematic(lambda t: None, FollowingParams(search_by_rotating=True))
    result = await world.follow(pose_topic="people/bob")
    assert result.error_code == FollowObjectError.FAILED_TO_DETECT_OBJECT
    assert "robot/people/bob" in result.error_msg
    assert "never seen" in result.error_msg
    assert FollowingState.RETRY in world.states


def hides_after(t: float, seconds: float) -> Pose2D | None:
    return walking(t) if not 5.0 <= t < 5.0 + seconds else None


async def test_a_hidden_object_is_searched_for_and_found_again() -> None:
    world = Kinematic(lambda t: hides_after(t, 3.0),
                      FollowingParams(search_by_rotating=True, controller=FAST))  # fmt: skip
    result = await world.follow(pose_topic="dynamic_pose", max_duration=25.0)
    assert result.error_code == 0
    assert result.num_retries == 1
    retry = world.states.index(FollowingState.RETRY)
    assert FollowingState.CONTROLLING in world.states[retry:]
    turns = [c.w for c in world.commands if c.v == 0.0 and c.w != 0.0]
    assert turns
    assert max(turns) > 0.5
    assert walking(world.time).x - world.robot.x == pytest.approx(1.1, abs=0.2)


async def test_without_search_a_lost_object_fails_after_the_retries() -> None:
    world = Kinematic(lambda t: hides_after(t, 100.0), FollowingParams(controller=FAST))
    result = await world.follow(pose_topic="dynamic_pose")
    assert result.error_code == FollowObjectError.FAILED_TO_DETECT_OBJECT
    assert "all retries have been used" in result.error_msg
    assert "lost the object on 'robot/dynamic_pose'" in result.error_msg
    assert world.time == pytest.approx(7.0, abs=0.3)  # 2 s after its last detection


async def test_lost_for_good_while_searching_fails_to_control() -> None:
    world = Kinematic(lambda t: hides_after(t, 100.0),
                      FollowingParams(search_by_rotating=True, controller=FAST))  # fmt: skip
    result = await world.follow(pose_topic="dynamic_pose")
    assert result.error_code == FollowObjectError.FAILED_TO_CONTROL
    assert result.error_msg == "Failed to rotate to object"


@pytest.mark.parametrize(
    ("goal", "code", "words"),
    [
        ({"pose_topic": ""}, FollowObjectError.FAILED_TO_DETECT_OBJECT, "No pose topic"),
        ({"tracked_frame": "base_link"}, FollowObjectError.TF_ERROR, "tracked_frame 'base_link'"),
        ({"pose_topic": "sim/target"}, FollowObjectError.FAILED_TO_DETECT_OBJECT, "truth"),
        ({"pose_topic": "a/*"}, FollowObjectError.FAILED_TO_DETECT_OBJECT, "'a/*'"),
    ],
)
async def test_bad_goals_fail_at_once_naming_what(
    goal: dict[str, str], code: int, words: str
) -> None:
    world = Kinematic(walking, FollowingParams())
    result = await world.follow(**goal)
    assert result.error_code == code
    assert words in result.error_msg
    assert world.time == 0.0
    assert world.commands == [STOP]


def test_the_search_turns_left_first() -> None:
    assert math.pi / 2 == FollowingParams().search_angle


async def test_a_detection_that_is_not_finite_is_never_driven_to() -> None:
    world = Kinematic(lambda t: Pose2D(math.nan, 0.0, 0.0), FollowingParams())
    result = await world.follow(pose_topic="dynamic_pose")
    assert result.error_code == FollowObjectError.FAILED_TO_DETECT_OBJECT
    assert "is not finite" in result.error_msg
    assert all(c.is_finite() for c in world.commands)
