"""Nav2's ';'-separated port strings, both ways."""

from __future__ import annotations

import pytest

import aiobt.msgs as msgs
from aiobt.msgs import MessageError, PoseStamped


def test_pose_stamped_nav2_nine_fields() -> None:
    pose = msgs.pose_stamped_from_string("1500000000;odom;1.0;2.0;0.0;0.0;0.0;0.0;1.0")
    assert pose.header.stamp == pytest.approx(1.5)
    assert pose.header.frame_id == "odom"
    assert (pose.x, pose.y, pose.yaw) == (1.0, 2.0, 0.0)


@pytest.mark.parametrize(
    "pose",
    [
        PoseStamped.from_xy_yaw(1.25, -3.5, 2.0, stamp=3.0),
        PoseStamped.from_xy_yaw(0, 0, -1.0, frame_id="odom"),
    ],
)
def test_pose_stamped_round_trip(pose: PoseStamped) -> None:
    text = msgs.pose_stamped_to_string(pose)
    assert len(text.split(";")) == 9
    again = msgs.pose_stamped_from_string(text)
    assert again.header == pose.header
    assert again.pose.position == pose.pose.position
    assert again.yaw == pytest.approx(pose.yaw)


def test_pose_stamped_short_forms() -> None:
    seven = msgs.pose_stamped_from_string("1;2;0;0;0;0.7071068;0.7071068")
    assert seven.header.frame_id == "map"
    assert seven.yaw == pytest.approx(1.5707963)
    three = msgs.pose_stamped_from_string("1; 2; 0.5")
    assert (three.x, three.y) == (1, 2)
    assert three.yaw == pytest.approx(0.5)


@pytest.mark.parametrize(
    ("text", "field"),
    [
        ("1;2", "<string>"),
        ("0;map;1;abc;0;0;0;0;1", "pose.position.y"),
        ("x;map;1;2;0;0;0;0;1", "header.stamp"),
        ("0;map;1;2;0;0;0;0;0", "pose.orientation"),
        ("1;nan;0", "y"),
    ],
)
def test_bad_pose_strings_name_the_field(text: str, field: str) -> None:
    with pytest.raises(MessageError) as caught:
        msgs.pose_stamped_from_string(text)
    assert caught.value.field == field


def test_point_and_quaternion() -> None:
    assert msgs.point_from_string("1;2;3") == msgs.Point(x=1, y=2, z=3)
    assert msgs.point_to_string(msgs.Point(x=1, y=2, z=3)) == "1.0;2.0;3.0"
    q = msgs.quaternion_from_string("0;0;0;1")
    assert msgs.quaternion_from_string(msgs.quaternion_to_string(q)) == q
    with pytest.raises(MessageError):
        msgs.point_from_string("1;2")


def test_path_and_goals_round_trip() -> None:
    poses = [PoseStamped.from_xy_yaw(i, -i, 0.1 * i) for i in range(3)]
    path = msgs.Path(header=msgs.Header(stamp=2.0, frame_id="map"), poses=poses)
    again = msgs.path_from_string(msgs.path_to_string(path))
    assert again.header == path.header
    assert [(p.x, p.y) for p in again.poses] == [(p.x, p.y) for p in poses]
    goals = msgs.goals_from_string(msgs.goals_to_string(msgs.Goals(goals=poses)))
    assert [p.yaw for p in goals.goals] == pytest.approx([p.yaw for p in poses])
    assert msgs.path_from_string("0;map").poses == []
    with pytest.raises(MessageError):
        msgs.path_from_string("0;map;1;2")
    with pytest.raises(MessageError):
        msgs.goals_from_string("1;2;3")


def test_a_negative_stamp_is_a_message_error_naming_the_stamp() -> None:
    with pytest.raises(MessageError) as caught:
        msgs.path_from_string("-5;map")
    assert (caught.value.model, caught.value.field) == ("Path", "header.stamp")
    with pytest.raises(MessageError) as caught:
        msgs.pose_stamped_from_string("-5;map;1;2;0;0;0;0;1")
    assert (caught.value.model, caught.value.field) == ("PoseStamped", "header.stamp")
