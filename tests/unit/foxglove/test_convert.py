"""aiobt messages -> Foxglove messages, decoded back through the schemas Foxglove gets."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from foxglove import messages as fm
from mcap.records import Schema
from mcap_protobuf.decoder import DecoderFactory

from aiobt.foxglove import convert, inbound
from aiobt.msgs import (
    BtNode,
    BtTransition,
    BtTransitions,
    BtTree,
    Header,
    LaserScan,
    MessageError,
    OccupancyGrid,
    Odometry,
    Path,
    Pose,
    PoseStamped,
    Twist,
    Vector3,
)


def decoded(msg: Any) -> Any:
    """``msg`` as Foxglove decodes it: its protobuf bytes through its own schema."""
    schema = type(msg).get_schema()
    record = Schema(id=1, name=schema.name, encoding=schema.encoding, data=schema.data)
    decode = DecoderFactory().decoder_for("protobuf", record)
    assert decode is not None
    return decode(msg.encode())


def test_timestamp_splits_seconds() -> None:
    stamp = decoded(fm.Log(timestamp=convert.timestamp(12.25), message="x"))
    assert (stamp.timestamp.seconds, stamp.timestamp.nanos) == (12, 250_000_000)
    assert convert.timestamp(0.9999999999).nsec == 999_999_999  # never a full second


def test_grid_keeps_cells_row_major_with_row_zero_at_the_origin() -> None:
    cells = np.array([[0, 100, -1], [50, 0, 0]])
    origin = Pose.from_xy_yaw(-2.5, -1.0)
    grid = OccupancyGrid.from_array(cells, resolution=0.05, origin=origin, stamp=3.0)
    out = decoded(convert.grid(grid))
    assert out.frame_id == "map"
    assert out.column_count == 3
    assert out.row_stride == 3
    assert out.cell_stride == 1
    assert (out.cell_size.x, out.cell_size.y) == (pytest.approx(0.05), pytest.approx(0.05))
    assert (out.pose.position.x, out.pose.position.y) == (-2.5, -1.0)
    assert [f.name for f in out.fields] == ["occupancy"]
    assert np.frombuffer(out.data, dtype=np.int8).tolist() == [0, 100, -1, 50, 0, 0]
    assert out.timestamp.seconds == 3


def test_laser_scan_ends_at_the_last_ray() -> None:
    scan = LaserScan(
        header=Header(stamp=1.5, frame_id="base_scan"),
        angle_min=-math.pi / 2, angle_max=math.pi / 2, angle_increment=math.pi / 2,
        range_min=0.1, range_max=10.0, ranges=[1.0, 2.0, 3.0],
    )  # fmt: skip
    out = decoded(convert.laser_scan(scan))
    assert out.frame_id == "base_scan"
    assert out.start_angle == pytest.approx(-math.pi / 2)
    assert out.end_angle == pytest.approx(math.pi / 2)
    assert list(out.ranges) == [1.0, 2.0, 3.0]


def test_odometry_and_speed() -> None:
    odom = Odometry(
        header=Header(stamp=2.0, frame_id="odom"),
        pose=Pose.from_xy_yaw(1.0, 2.0, 0.5),
        twist=Twist(linear=Vector3(x=0.3, y=0.4), angular=Vector3(z=-0.2)),
    )
    out = decoded(convert.odometry(odom))
    assert (out.frame_id, out.body_frame_id) == ("odom", "base_link")
    assert (out.linear_velocity.x, out.angular_velocity.z) == (0.3, -0.2)
    assert convert.speed(odom) == {
        "stamp": 2.0, "linear": 0.3, "angular": -0.2, "speed": pytest.approx(0.5)
    }  # fmt: skip


def _compose(a: Pose, b: Pose) -> tuple[float, float, float]:
    c, s = math.cos(a.yaw), math.sin(a.yaw)
    x = a.position.x + c * b.position.x - s * b.position.y
    y = a.position.y + s * b.position.x + c * b.position.y
    return x, y, a.yaw + b.yaw


def test_map_to_odom_puts_the_odom_body_at_the_map_pose() -> None:
    in_map = PoseStamped.from_xy_yaw(2.0, 1.0, math.pi / 2)
    odom = Odometry(pose=Pose.from_xy_yaw(1.0, 0.5, 0.3))
    link = convert.map_to_odom(in_map, odom)
    assert _compose(link, odom.pose) == pytest.approx((2.0, 1.0, math.pi / 2))


def test_transforms_chain_map_odom_base_and_scan() -> None:
    in_map = PoseStamped.from_xy_yaw(2.0, 1.0)
    out = decoded(convert.transforms(in_map, None, "base_scan"))
    chain = [(t.parent_frame_id, t.child_frame_id) for t in out.transforms]
    assert chain == [("map", "odom"), ("odom", "base_link"), ("base_link", "base_scan")]
    assert out.transforms[1].translation.x == 2.0  # no odometry: odom is the map
    odom = Odometry(pose=Pose.from_xy_yaw(0.5, 0.0))
    with_odom = decoded(convert.transforms(in_map, odom, None))
    assert [t.translation.x for t in with_odom.transforms] == [1.5, 0.5]
    assert decoded(convert.transforms(None, None, "base_scan")).transforms == []


def test_footprint_is_a_ring_locked_to_the_base() -> None:
    out = decoded(convert.footprint(1.0, 0.22))
    [entity] = out.entities
    assert entity.frame_id == "base_link"
    assert entity.frame_locked
    [ring] = entity.lines
    radii = {round(math.hypot(p.x, p.y), 6) for p in ring.points}
    assert radii == {0.22}
    assert len(ring.points) == 32


def test_plan_and_goal_poses() -> None:
    path = Path(poses=[PoseStamped.from_xy_yaw(x, 0.0) for x in (0.0, 0.5, 1.0)])
    out = decoded(convert.poses_in_frame(path))
    assert out.frame_id == "map"
    assert [p.position.x for p in out.poses] == [0.0, 0.5, 1.0]
    goal = decoded(convert.pose_in_frame(PoseStamped.from_xy_yaw(1.0, 2.0, math.pi)))
    assert goal.pose.orientation.z == pytest.approx(1.0)


@pytest.mark.parametrize(
    "payload",
    [
        b'{"x": 1.5, "y": -0.5, "yaw": 0}',
        b'{"header": {"stamp": {"sec": 3, "nsec": 0}, "frame_id": ""},'
        b' "pose": {"position": {"x": 1.5, "y": -0.5, "z": 0}}}',
        b'{"frame_id": "map", "timestamp": {"sec": 1, "nsec": 0},'
        b' "pose": {"position": {"x": 1.5, "y": -0.5}}}',
    ],
    ids=["aiobt-short", "ros-pose-stamped", "foxglove-pose-in-frame"],
)
def test_goal_from_json_forms(payload: bytes) -> None:
    goal = inbound.goal_from_json(payload)
    assert goal.header.frame_id == "map"
    assert (goal.pose.position.x, goal.pose.position.y) == (1.5, -0.5)


def test_a_bad_goal_names_the_field() -> None:
    with pytest.raises(MessageError, match=r"pose\.position\.x"):
        inbound.goal_from_json(b'{"pose": {"position": {"x": "far"}}}')
    with pytest.raises(ValueError, match="not JSON"):
        inbound.goal_from_json(b"{nope")


def test_transition_logs_name_nodes_of_the_same_run() -> None:
    tree = BtTree(run=2, tree_id="Main", nodes=[
        BtNode(uid=1, path="Main/Seq", id="Sequence", name="Seq", kind="Control"),
    ])  # fmt: skip
    ticks = BtTransitions(run=2, stamp=4.0, transitions=[
        BtTransition(uid=1, previous="IDLE", status="RUNNING", stamp=4.0),
        BtTransition(uid=9, previous="RUNNING", status="FAILURE", stamp=4.0),
    ])  # fmt: skip
    lines = [decoded(line) for line in convert.transition_logs(ticks, tree)]
    assert [line.message for line in lines] == [
        "Main/Seq: IDLE -> RUNNING",
        "node 9: RUNNING -> FAILURE",
    ]
    assert lines[1].level == fm.LogLevel.Warning.value
    other_run = BtTransitions(run=3, transitions=ticks.transitions)
    assert decoded(convert.transition_logs(other_run, tree)[0]).message.startswith("node 1:")
