"""The robot's pose in ``map`` read when asked (:class:`aiobt.geometry.map_pose.MapPose`):
odometry composed with the correction localization sends, the pose stream only until
a correction comes."""

import asyncio
import math
from collections.abc import Iterator
from typing import Generic, TypeVar

import pytest

from aiobt.geometry.correction import correction_message
from aiobt.geometry.map_pose import MapPose
from aiobt.msgs import Odometry, PoseStamped, PoseWithCovarianceStamped, TFMessage
from aiobt_services.localization.node import LocalizationNode
from aiobt_services.localization.params import AmclParams

from .test_node import _grid, _odom, _scan

M = TypeVar("M")
TRUTH = (1.0, 3.0, 0.0)


class Ring(Generic[M]):
    """A :class:`~aiobt.transport.Latest` stand-in: the messages put, the last ``keep``."""

    def __init__(self, keep: int = 1) -> None:
        self.keep = keep
        self.kept: list[M] = []
        self.closed = False

    def put(self, message: M) -> None:
        assert not self.closed, "put into a closed ring"
        self.kept = [*self.kept, message][-self.keep :]

    def get(self) -> M | None:
        return self.kept[-1] if self.kept else None

    def newest_first(self) -> Iterator[M]:
        return reversed(self.kept)

    def close(self) -> None:
        self.closed = True


def _reader(
    keep: int = 1,
) -> tuple[MapPose, Ring[Odometry], Ring[TFMessage], Ring[PoseStamped]]:
    odom: Ring[Odometry] = Ring(keep)
    tf: Ring[TFMessage] = Ring(4)
    pose: Ring[PoseStamped] = Ring(keep)
    return MapPose(odom, tf, pose), odom, tf, pose


def _wire(message: TFMessage) -> TFMessage:
    return TFMessage.model_validate_json(message.model_dump_json())


def test_composed_from_odometry_and_sent_correction_is_localizations_pose() -> None:
    node = LocalizationNode(AmclParams.from_mapping({"random_seed": 1}), wanted=lambda _: True)
    assert node.on_map(_grid()).ok
    assert node.on_initialpose(PoseWithCovarianceStamped.from_xy_yaw(*TRUTH)).ok
    reader, odom, tf, pose_ring = _reader()
    compared = 0
    for i in range(60):
        stamp, x, y, yaw = 1.0 + 0.02 * i, 0.012 * i, 0.004 * i, 0.01 * i
        msg = _odom(stamp, x, y, yaw)
        odom.put(msg)
        for topic, out in node.on_odom(msg):
            assert topic == "pose"
            assert isinstance(out, PoseStamped)
            if not reader.composing:
                pose_ring.put(out)
                continue
            mine = reader.get()
            assert mine is not None
            assert mine.header == out.header  # the odometry's stamp, in map
            assert (mine.x, mine.y, mine.yaw) == pytest.approx((out.x, out.y, out.yaw), abs=1e-12)
            compared += 1
        if i % 5 == 4:  # a scan every 0.1 s
            sent = dict(node.on_scan(_scan(stamp, (TRUTH[0] + x, TRUTH[1] + y, yaw))))
            correction = sent["tf"]
            assert isinstance(correction, TFMessage)
            tf.put(_wire(correction))
    assert compared >= 50
    assert pose_ring.closed  # let go at the first correction


def test_without_a_correction_the_pose_stream_is_read() -> None:
    reader, odom, tf, pose = _reader()
    assert reader.get() is None
    odom.put(_odom(1.0, 0.5, 0.0, 0.0))
    assert reader.get() is None  # odometry alone does not place the robot in map
    sent = PoseStamped.from_xy_yaw(4.0, 2.0, 0.3, stamp=1.0)
    pose.put(sent)
    assert reader.get() is sent
    assert not reader.composing
    assert not pose.closed
    tf.put(_wire(correction_message((1.0, 1.0, 0.0), 1.0, "map", "base_footprint")))
    assert reader.get() is sent  # other frames on tf: still no correction
    assert not pose.closed


def test_a_correction_switches_to_composing_and_lets_the_pose_stream_go() -> None:
    reader, odom, tf, pose = _reader()
    streamed = PoseStamped.from_xy_yaw(9.0, 9.0, 0.0, stamp=1.0)
    pose.put(streamed)
    tf.put(_wire(correction_message((1.0, 2.0, 0.0), 1.0)))
    assert reader.get() is streamed  # a correction and no odometry yet: the stream's
    assert not pose.closed
    assert not reader.composing
    assert list(reader.newest_first()) == [streamed]
    odom.put(_odom(1.0, 0.5, 0.0, 0.0))
    got = reader.get()
    assert got is not None
    assert (got.x, got.y, got.header.stamp) == pytest.approx((1.5, 2.0, 1.0))
    assert got.header.frame_id == "map"
    assert pose.closed
    assert reader.get() is got  # nothing new: the same message, not composed again
    odom.put(_odom(1.02, 0.6, 0.0, 0.0))
    tf.put(_wire(correction_message((0.0, 0.0, 0.0), 1.02, "map", "other")))  # newest: no
    moved = reader.get()
    assert moved is not None
    assert moved is not got
    assert (moved.x, moved.y, moved.header.stamp) == pytest.approx((1.6, 2.0, 1.02))
    odom.put(_odom(1.04, 0.6, 0.0, 0.2))
    tf.put(_wire(correction_message((1.0, 2.0, 0.5 * math.pi), 1.04)))  # turned a quarter
    turned = reader.get()
    assert turned is not None
    assert (turned.x, turned.y, turned.yaw) == pytest.approx((1.0, 2.6, 0.5 * math.pi + 0.2))


def test_the_pose_stops_where_the_correction_stopped() -> None:
    reader, odom, tf, _ = _reader(keep=8)
    tf.put(_wire(correction_message((1.0, 0.0, 0.0), 2.0)))
    odom.put(_odom(2.9, 0.5, 0.0, 0.0))
    odom.put(_odom(3.0, 0.6, 0.0, 0.0))  # the correction's stamp + tolerance (1 s): taken
    at_limit = reader.get()
    assert at_limit is not None
    assert at_limit.header.stamp == 3.0
    odom.put(_odom(3.1, 0.7, 0.0, 0.0))
    stopped = reader.get()
    assert stopped is not None
    assert stopped.header.stamp == 3.0  # stale: its stamp tells
    assert reader.get() is stopped  # not looked for again until something changes
    assert [p.header.stamp for p in reader.newest_first()] == [3.0, 2.9]
    tf.put(_wire(correction_message((1.0, 0.0, 0.0), 3.1)))  # localization back
    back = reader.get()
    assert back is not None
    assert back.header.stamp == 3.1
    assert [p.header.stamp for p in reader.newest_first()] == [3.1, 3.0, 2.9]


def test_stopped_past_the_kept_odometry_the_pose_is_where_it_stopped() -> None:
    reader, odom, tf, _ = _reader(keep=1)
    tf.put(_wire(correction_message((1.0, 0.0, 0.0), 2.0)))
    odom.put(_odom(3.0, 0.6, 0.0, 0.0))
    last = reader.get()
    odom.put(_odom(3.1, 0.7, 0.0, 0.0))  # the odometry at 3.0 no longer kept
    assert reader.get() is last


def test_when_the_odometry_stops_the_pose_keeps_its_stamp() -> None:
    reader, odom, tf, _ = _reader()
    odom.put(_odom(1.0, 0.5, 0.0, 0.0))
    tf.put(_wire(correction_message((1.0, 0.0, 0.0), 1.0)))
    for stamp in (1.1, 1.2, 1.3):
        tf.put(_wire(correction_message((1.0, 0.1, 0.0), stamp)))
        got = reader.get()
        assert got is not None
        assert got.header.stamp == 1.0
        assert got.y == pytest.approx(0.1)  # the newest correction, the last odometry


def test_kept_poses_without_a_correction_are_the_pose_streams() -> None:
    reader, _, _, pose = _reader(keep=4)
    sent = [PoseStamped.from_xy_yaw(float(i), 0.0, stamp=float(i)) for i in range(3)]
    for message in sent:
        pose.put(message)
    assert list(reader.newest_first()) == sent[::-1]


def test_a_correction_older_than_the_kept_odometry_leaves_the_pose_stream_read() -> None:
    """Rings opened together, the stream's pose read first, then a correction sent late,
    older than every odometry message kept since: the reader went from a pose back to
    none (a candidate cause of the route server's 'no robot pose' in an e2e run,
    2026-11-29)."""
    reader, odom, tf, pose = _reader(keep=4)
    streamed = PoseStamped.from_xy_yaw(4.0, 5.0, 0.0, stamp=12.0)
    pose.put(streamed)
    for i in range(4):
        odom.put(_odom(11.94 + 0.02 * i, 0.5, 0.0, 0.0))
    assert reader.get() is streamed
    tf.put(_wire(correction_message((1.0, 2.0, 0.0), 10.0)))  # 10.0 + 1.0 < 11.94
    assert reader.get() is streamed  # not None: nothing composes yet
    assert not pose.closed
    tf.put(_wire(correction_message((1.0, 2.0, 0.0), 12.0)))
    got = reader.get()
    assert got is not None
    assert (got.x, got.y, got.header.stamp) == pytest.approx((1.5, 2.0, 12.0))
    assert pose.closed
    tf.put(_wire(correction_message((1.0, 2.0, 0.0), 10.0)))  # late again: where it was
    assert reader.get() is got


async def test_settle_lets_the_pose_stream_go_at_the_first_correction_unread() -> None:
    reader, odom, tf, pose = _reader()
    odom.put(_odom(1.0, 0.5, 0.0, 0.0))
    settling = asyncio.create_task(reader.settle(period=0.001))
    try:
        tf.put(_wire(correction_message((0.0, 0.0, 0.0), 1.0, "map", "other")))  # not map->odom
        for _ in range(20):  # looks at the rings many times over: no correction, no let-go
            await asyncio.sleep(0.002)
        assert not settling.done()
        assert not pose.closed
        tf.put(_wire(correction_message((1.0, 2.0, 0.0), 1.0)))  # nobody calls get
        await asyncio.wait_for(settling, 5.0)
        assert pose.closed
        assert reader.composing
    finally:
        settling.cancel()
    no_pose = MapPose(Ring[Odometry](), Ring[TFMessage](4), None)
    await asyncio.wait_for(no_pose.settle(period=60.0), 1.0)  # nothing to let go: at once


def test_close_closes_every_ring() -> None:
    reader, odom, tf, pose = _reader()
    reader.close()
    assert odom.closed
    assert tf.closed
    assert pose.closed
    with pytest.raises(ValueError, match="tolerance"):
        MapPose(odom, tf, pose, tolerance=-1.0)
