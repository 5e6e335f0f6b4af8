"""A ``tracked_frame`` goal: the object as a TF frame on ``{ns}/tf``, walked up its
chain to a frame the server knows, and followed as a detection is (Nav2's
``getFramePose``)."""

from __future__ import annotations

import math

import pytest

from aiobt.geometry import Pose2D
from aiobt.msgs import TFMessage
from aiobt.msgs.remote_actions import FollowObjectError
from aiobt_services.following.follow import FollowingState
from aiobt_services.following.params import FollowingParams
from aiobt_services.following.tf_frames import FrameDetections, TransformTree

from .kinematic import Kinematic, transform
from .test_follow import FAST, walking


def tree_with(*links: tuple[str, str, Pose2D, float]) -> TransformTree:
    tree = TransformTree(lambda frame: frame in ("odom", "map", "base_link"))
    tree.add(TFMessage(transforms=[transform(*link) for link in links]))
    return tree


def test_a_chain_is_composed_up_to_a_known_frame_with_its_oldest_stamp() -> None:
    tree = tree_with(("odom", "cart_base", Pose2D(1.0, 2.0, math.pi / 2), 5.0),
                     ("cart_base", "cart", Pose2D(1.0, 0.0, 0.0), 4.5))  # fmt: skip
    found = tree.pose_of("cart")
    assert found.frame == "odom"
    assert (found.pose.x, found.pose.y) == pytest.approx((1.0, 3.0))
    assert found.pose.yaw == pytest.approx(math.pi / 2)
    assert found.stamp == 4.5


def test_the_newest_transform_of_a_frame_counts() -> None:
    tree = tree_with(("map", "cart", Pose2D(1.0, 0.0, 0.0), 1.0))
    tree.add(TFMessage(transforms=[transform("base_link", "cart", Pose2D(2.0, 0.0, 0.0), 2.0)]))
    assert tree.pose_of("cart").frame == "base_link"


@pytest.mark.parametrize(
    ("links", "problem"),
    [
        ((), "no transform to frame 'cart' on tf"),
        ((("cart_base", "cart", Pose2D(), 1.0),), "frame 'cart_base' (a parent of 'cart')"),
        ((("cart", "cart_base", Pose2D(), 1.0), ("cart_base", "cart", Pose2D(), 1.0)),
         "a loop"),
    ],
)  # fmt: skip
def test_a_chain_that_leads_nowhere_names_the_missing_link(
    links: tuple[tuple[str, str, Pose2D, float], ...], problem: str
) -> None:
    tree = tree_with(*links)
    with pytest.raises(LookupError, match=problem.replace("(", r"\(").replace(")", r"\)")):
        tree.pose_of("cart")
    detections = FrameDetections(tree, "cart", "robot/tf")
    assert detections.latest() is None
    assert problem.split(" (")[0] in detections.topic


async def test_a_walking_object_followed_by_its_frame_on_tf() -> None:
    world = Kinematic(walking, FollowingParams(controller=FAST))
    result = await world.follow(tracked_frame="person", pose_topic="ignored", max_duration=20.0)
    assert result.error_code == 0, result.error_msg
    gap = walking(world.time).x - world.robot.x
    assert 1.0 <= gap <= 1.0 + 0.15 + 0.1
    assert world.opened == ["tf:person"]  # the frame, not the pose topic (Nav2's order)
    assert FollowingState.CONTROLLING in world.states


async def test_a_frame_never_published_fails_to_detect_naming_it() -> None:
    world = Kinematic(walking, FollowingParams())
    result = await world.follow(tracked_frame="cart")
    assert result.error_code == FollowObjectError.FAILED_TO_DETECT_OBJECT
    assert "tracked_frame 'cart': no transform to frame 'cart' on tf" in result.error_msg


@pytest.mark.parametrize("frame", ["base_link", "odom", "map"])
async def test_the_robots_own_frames_are_refused(frame: str) -> None:
    world = Kinematic(walking, FollowingParams())
    result = await world.follow(tracked_frame=frame)
    assert result.error_code == FollowObjectError.TF_ERROR
    assert f"tracked_frame '{frame}' is one of the robot's own frames" in result.error_msg
    assert world.time == 0.0
