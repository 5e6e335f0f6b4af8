"""Nav2's ';'-separated port strings, both ways."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import aiobt.msgs as msgs
from aiobt.core.convert import convert, to_text
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


@pytest.mark.parametrize(
    ("text", "frame", "stamp", "count"),
    [
        ("0;odom", "odom", 0.0, 0),
        ("2500000000;odom;0;map;1;2;0;0;0;0;1", "odom", 2.5, 1),  # Nav2's nav_msgs::msg::Goals
        ("0;map;1;2;0;0;0;0;1;0;map;3;4;0;0;0;0;1", "map", 0.0, 2),  # a vector of poses
    ],
)
def test_goals_read_nav2_goals_with_a_header_and_bare_pose_vectors(
    text: str, frame: str, stamp: float, count: int
) -> None:
    goals = msgs.goals_from_string(text)
    assert (goals.header.frame_id, goals.header.stamp, len(goals.goals)) == (frame, stamp, count)


def test_goals_keep_their_header_through_the_string() -> None:
    poses = [PoseStamped.from_xy_yaw(1, 2, 0.5, frame_id="odom", stamp=0.25)]
    goals = msgs.Goals(header=msgs.Header(stamp=1.5, frame_id="odom"), goals=poses)
    text = msgs.goals_to_string(goals)
    assert text.startswith("1500000000;odom;250000000;odom;")
    assert msgs.goals_from_string(text) == goals


@pytest.mark.parametrize("frame", ["map;odom", "odom ", " map", "a;"])
def test_a_frame_id_the_string_cannot_carry_is_refused_naming_it(frame: str) -> None:
    pose = PoseStamped.from_xy_yaw(1, 2, frame_id=frame)
    with pytest.raises(ValueError, match="frame_id") as caught:
        msgs.pose_stamped_to_string(pose)
    assert isinstance(caught.value, MessageError)
    assert (caught.value.model, caught.value.field) == ("PoseStamped", "header.frame_id")
    header = msgs.Header(frame_id=frame)
    with pytest.raises(MessageError) as caught:
        msgs.path_to_string(msgs.Path(header=header))
    assert (caught.value.model, caught.value.field) == ("Path", "header.frame_id")
    with pytest.raises(MessageError) as caught:  # a pose inside: its index is named
        msgs.path_to_string(msgs.Path(poses=[PoseStamped.from_xy_yaw(0, 0), pose]))
    assert (caught.value.model, caught.value.field) == ("Path", "poses.1.header.frame_id")
    with pytest.raises(MessageError) as caught:
        msgs.goals_to_string(msgs.Goals(goals=[pose]))
    assert (caught.value.model, caught.value.field) == ("Goals", "goals.0.header.frame_id")


@pytest.mark.parametrize("stamp", [0.3, 0.1, 7.1, 1.000000001, 12345.678901234, 1.7e9 + 0.25])
def test_stamps_of_whole_nanoseconds_read_back_exactly(stamp: float) -> None:
    pose = PoseStamped.from_xy_yaw(1, 2, 0.5, stamp=stamp)
    nanoseconds = msgs.pose_stamped_to_string(pose).split(";")[0]
    assert nanoseconds == f"{stamp:.9f}".replace(".", "").lstrip("0")
    assert msgs.pose_stamped_from_string(msgs.pose_stamped_to_string(pose)) == pose
    path = msgs.Path(header=msgs.Header(stamp=stamp, frame_id="map"), poses=[pose])
    assert msgs.path_from_string(msgs.path_to_string(path)) == path


# stamps a float holds to the nanosecond (< 2**23 s), and any stamp above that
STAMPS = st.one_of(
    st.integers(0, 8 * 10**15).map(lambda ns: ns / 1e9),
    st.floats(2.0**23, 4e9),
)


@given(
    stamp=STAMPS,
    xyz=st.tuples(*[st.floats(-1e6, 1e6, allow_nan=False)] * 3),
    quaternion=st.tuples(*[st.floats(-1.0, 1.0)] * 4).filter(
        lambda q: math.sqrt(sum(v * v for v in q)) > 0.5
    ),
)
@settings(max_examples=200, deadline=None)
def test_any_pose_reads_back_equal(
    stamp: float, xyz: tuple[float, float, float], quaternion: tuple[float, ...]
) -> None:
    norm = math.sqrt(sum(v * v for v in quaternion))
    qx, qy, qz, qw = (v / norm for v in quaternion)
    pose = PoseStamped.model_validate(
        {
            "header": {"stamp": stamp, "frame_id": "odom"},
            "pose": {
                "position": dict(zip("xyz", xyz, strict=True)),
                "orientation": {"x": qx, "y": qy, "z": qz, "w": qw},
            },
        }
    )
    text = msgs.pose_stamped_to_string(pose)
    assert msgs.pose_stamped_from_string(text) == pose
    assert convert(to_text(pose), PoseStamped) == pose  # as a port reads and writes it


def test_a_stamp_too_large_for_a_float_is_a_message_error() -> None:
    with pytest.raises(MessageError) as caught:
        msgs.pose_stamped_from_string("9" * 400 + ";map;1;2;0;0;0;0;1")
    assert caught.value.field == "header.stamp"
    with pytest.raises(MessageError) as caught:
        msgs.path_from_string("9" * 400 + ";map")
    assert caught.value.field == "header.stamp"


@pytest.mark.parametrize(
    ("model", "text"),
    [
        (msgs.Point, "1.5;-2.0;3.0"),
        (msgs.Quaternion, "0.0;0.0;0.6;0.8"),
        (PoseStamped, "1500000000;odom;1.0;2.0;0.0;0.0;0.0;0.6;0.8"),
        (msgs.Path, "0;map;1;map;1.0;2.0;0.0;0.0;0.0;0.0;1.0"),
        (msgs.Goals, "5;map;1;map;1.0;2.0;0.0;0.0;0.0;0.0;1.0"),
    ],
)
def test_ports_read_and_write_the_models_bt_strings(model: type[msgs.Msg], text: str) -> None:
    value = convert(text, model)
    assert isinstance(value, model)
    assert to_text(value) == text
    with pytest.raises(MessageError) as caught:
        convert("1;nan;" + text, model)
    assert caught.value.model == model.__name__
