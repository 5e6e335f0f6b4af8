"""RobotFeed: the planner's pose and scan read while requests come."""

from __future__ import annotations

import asyncio
from collections import deque
from collections.abc import Iterator
from typing import Any, cast

import pytest

from aiobt.core.clock import ManualClock
from aiobt.costmap.feed import RobotFeed
from aiobt.geometry.correction import correction_message
from aiobt.msgs import LaserScan, Odometry, PoseStamped, TFMessage, pose_fields
from aiobt.transport import Bus
from aiobt_services.planner.state import POSES_KEPT, GlobalCostmap

from .test_actions import world
from .test_service import lethal


class FakeLatest:
    """A ``bus.latest`` reader the test feeds by hand (as Zenoh's thread would)."""

    def __init__(self, keep: int) -> None:
        self.kept: deque[Any] = deque(maxlen=keep)
        self.first = asyncio.Event()
        self.closed = False

    def deliver(self, msg: Any) -> None:
        self.kept.append(msg)
        self.first.set()

    def get(self) -> Any:
        return self.kept[-1] if self.kept else None

    def newest_first(self) -> Iterator[Any]:
        yield from reversed(list(self.kept))

    async def wait_latest(self, timeout: float | None = None) -> Any:  # noqa: ASYNC109
        await self.first.wait()
        return self.get()

    def close(self) -> None:
        self.closed = True


class FakeBus:
    def __init__(self) -> None:
        self.subs: dict[str, list[FakeLatest]] = {"odom": [], "tf": [], "pose": [], "scan": []}
        self.kept: dict[str, int] = {}

    def latest(
        self, name: str, _model: object, *, keep: int = 1, namespace: str | None = None
    ) -> FakeLatest:
        assert namespace is None  # the bus's own
        sub = FakeLatest(keep)
        self.subs[name].append(sub)
        self.kept[name] = keep
        return sub

    def live(self, name: str) -> FakeLatest:
        sub = self.subs[name][-1]
        assert not sub.closed
        return sub


def scan(*ranges: float) -> LaserScan:
    """From the robot at (1, 1) facing +x: beams at 0, 90, 180 degrees."""
    return LaserScan(angle_min=0.0, angle_max=3.1416, angle_increment=1.5708, range_min=0.1,
                     range_max=5.0, ranges=list(ranges))  # fmt: skip


def feed_of(
    bus: FakeBus, clock: ManualClock, timeout: float = 1.0, poll: float = 60.0
) -> RobotFeed:
    """A feed whose own look comes only after ``poll`` wall s (the tests' requests read)."""
    grid = world()
    return RobotFeed(cast(Bus, bus), grid, clock, timeout=timeout, linger=5.0, poll=poll)


async def attached(poll: float = 60.0) -> tuple[FakeBus, RobotFeed, GlobalCostmap]:
    """A feed whose first request attached, with the robot at (1, 1) at robot time 1.0
    and a scan that saw nothing folded."""
    bus, clock = FakeBus(), ManualClock()
    feed = feed_of(bus, clock, poll=poll)
    call = asyncio.ensure_future(feed.call(lambda _: "first")(None))
    await asyncio.sleep(0)
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 1.0, 0.0, stamp=1.0))
    bus.live("scan").deliver(scan(5.0, 5.0, 5.0))
    assert await asyncio.wait_for(call, 1.0) == "first"
    return bus, feed, cast(GlobalCostmap, feed._world)  # the planner's, given by world()


def scan_at(stamp: float, *ranges: float) -> LaserScan:
    taken = scan(*ranges)
    taken.header.stamp = stamp
    return taken


async def test_a_request_attaches_waits_for_pose_and_scan_and_folds_the_scan() -> None:
    bus, clock = FakeBus(), ManualClock()
    feed = feed_of(bus, clock)
    grid = feed._world
    assert not any(bus.subs.values())  # idle: nothing subscribed
    call = asyncio.ensure_future(feed.call(lambda _: grid.pose)(None))
    await asyncio.sleep(0)
    assert grid.pose is None  # forgotten at attach: the robot may have moved meanwhile
    bus.live("scan").deliver(scan(0.4, 2.0, 0.5))  # before any pose: kept for later
    await asyncio.sleep(0)
    assert not call.done()
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 1.0, 0.0, stamp=4.0))
    assert await asyncio.wait_for(call, 1.0) == (1.0, 1.0, 0.0)
    assert lethal(grid, 1.4, 1.0)  # the scan that came before the pose is marked
    assert lethal(grid, 1.0, 3.0)


async def test_the_streams_go_a_linger_after_the_last_request() -> None:
    bus, clock = FakeBus(), ManualClock()
    feed = feed_of(bus, clock)
    call = asyncio.ensure_future(feed.call(lambda _: "ok")(None))
    await asyncio.sleep(0)
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 1.0, 0.0))
    bus.live("scan").deliver(scan(5.0, 5.0, 5.0))
    assert await asyncio.wait_for(call, 1.0) == "ok"
    assert await feed.call(lambda _: "again")(None) == "again"  # attached: no new subscription
    assert len(bus.subs["pose"]) == 1
    await asyncio.sleep(0)  # the detacher starts its linger
    await clock.forward(5.1, step=0.5)
    assert bus.subs["pose"][0].closed
    assert bus.subs["scan"][0].closed


async def test_without_a_robot_only_the_attaching_request_waits() -> None:
    bus, clock = FakeBus(), ManualClock()
    feed = feed_of(bus, clock, timeout=0.05)
    assert await asyncio.wait_for(feed.call(lambda _: feed._world.pose)(None), 1.0) is None
    # still attached, still silent: the next request is answered at once
    assert await asyncio.wait_for(feed.call(lambda _: "now")(None), 0.04) == "now"
    feed.close()
    assert bus.subs["pose"][0].closed


def test_the_timeout_must_be_positive() -> None:
    with pytest.raises(ValueError, match="timeout"):
        RobotFeed(cast(Bus, FakeBus()), world(), ManualClock(), timeout=0.0)
    with pytest.raises(ValueError, match="poll"):
        RobotFeed(cast(Bus, FakeBus()), world(), ManualClock(), poll=0.0)


async def test_a_request_arriving_while_another_attaches_waits_with_it() -> None:
    bus, clock = FakeBus(), ManualClock()
    feed = feed_of(bus, clock)
    first = asyncio.ensure_future(feed.call(lambda _: feed._world.pose)(None))
    await asyncio.sleep(0)
    second = asyncio.ensure_future(feed.call(lambda _: feed._world.pose)(None))
    await asyncio.sleep(0)
    assert not second.done()  # not answered on the pose forgotten at attach
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(2.0, 1.0, 0.0))
    bus.live("scan").deliver(scan(5.0, 5.0, 5.0))
    assert await asyncio.wait_for(second, 1.0) == (2.0, 1.0, 0.0)
    assert await asyncio.wait_for(first, 1.0) == (2.0, 1.0, 0.0)
    feed.close()


async def test_a_request_does_not_mark_a_scan_taken_before_from_the_newer_pose() -> None:
    """The newest scan is handed to the costmap again by each request; once taken, the
    robot's later pose must not mark it a second time (a wall where there is none)."""
    bus, clock = FakeBus(), ManualClock()
    feed = feed_of(bus, clock)
    grid = feed._world
    call = asyncio.ensure_future(feed.call(lambda _: "first")(None))
    await asyncio.sleep(0)
    assert bus.kept == {"odom": POSES_KEPT, "tf": 4, "pose": POSES_KEPT, "scan": 1}
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 1.0, 0.0, stamp=1.0))
    bus.live("scan").deliver(scan(0.4, 5.0, 5.0))  # a hit 0.4 m ahead, from (1, 1)
    assert await asyncio.wait_for(call, 1.0) == "first"
    assert lethal(grid, 1.4, 1.0)
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 2.0, 0.0, stamp=1.1))  # moved
    assert await asyncio.wait_for(feed.call(lambda _: "again")(None), 1.0) == "again"
    feed.read()  # the periodic look
    assert not lethal(grid, 1.4, 2.0)  # the same scan, not marked again from (1, 2)
    newer = scan(0.4, 5.0, 5.0)  # a new scan from there, due (1 robot s later), is
    newer.header.stamp = 1.1  # with the pose at (1, 2)
    bus.live("scan").deliver(newer)
    feed.read()
    assert lethal(grid, 1.4, 2.0)
    feed.close()


async def test_a_scan_is_marked_from_the_kept_pose_stamped_nearest_it() -> None:
    bus, feed, grid = await attached()
    for i, y in enumerate((2.0, 1.0, 1.5)):  # stamps 2.0, 2.02, 2.04: the scan's is 2.02
        bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, y, 0.0, stamp=2.0 + 0.02 * i))
    bus.live("scan").deliver(scan_at(2.02, 0.4, 5.0, 5.0))
    feed.read()
    assert grid.pose == (1.0, 1.5, 0.0)  # the newest pose
    assert lethal(grid, 1.4, 1.0)  # from the pose at 2.02, not the newest (1, 1.5)
    assert not lethal(grid, 1.4, 1.5)
    feed.close()


async def test_a_scan_newer_than_every_pose_waits_for_its_pose() -> None:
    bus, feed, grid = await attached()
    bus.live("scan").deliver(scan_at(3.0, 0.4, 5.0, 5.0))
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 2.0, 0.0, stamp=2.9))
    feed.read()
    assert not lethal(grid, 1.4, 2.0)  # not marked from a pose 0.1 s before it
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 1.0, 0.0, stamp=3.0))
    feed.read()
    assert lethal(grid, 1.4, 1.0)
    feed.close()


async def test_while_attached_the_feed_folds_due_scans_without_a_request() -> None:
    bus, feed, grid = await attached(0.005)
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 1.0, 0.0, stamp=2.0))
    bus.live("scan").deliver(scan_at(2.0, 0.4, 5.0, 5.0))
    async with asyncio.timeout(2.0):
        while not lethal(grid, 1.4, 1.0):  # noqa: ASYNC110 - the feed polls: nothing to await
            await asyncio.sleep(0.005)
    feed.close()
    assert feed._poller is None


async def test_a_request_takes_the_newest_pose_but_leaves_folding_to_the_look() -> None:
    """Only the first scan after attaching is folded on a request's path; later ones by
    the periodic look (a plan never waits behind a fold)."""
    bus, feed, grid = await attached()
    bus.live("pose").deliver(PoseStamped.from_xy_yaw(1.0, 1.0, 0.0, stamp=2.0))
    bus.live("scan").deliver(scan_at(2.0, 0.4, 5.0, 5.0))
    assert await asyncio.wait_for(feed.call(lambda _: grid.pose_stamp)(None), 1.0) == 2.0
    assert not lethal(grid, 1.4, 1.0)  # due, but not folded by the request
    feed.read()
    assert lethal(grid, 1.4, 1.0)
    feed.close()


def odom_at(stamp: float, x: float, y: float) -> Odometry:
    return Odometry.model_validate(
        {"header": {"stamp": stamp, "frame_id": "odom"}, "pose": pose_fields(x, y, 0.0)}
    )


def correction_at(stamp: float, x: float, y: float) -> TFMessage:
    return correction_message((x, y, 0.0), stamp)


async def test_with_a_correction_the_pose_is_the_odometry_composed_and_pose_is_let_go() -> None:
    bus, clock = FakeBus(), ManualClock()
    feed = feed_of(bus, clock)
    grid = feed._world
    call = asyncio.ensure_future(feed.call(lambda _: grid.pose)(None))
    await asyncio.sleep(0)
    bus.live("odom").deliver(odom_at(1.0, 0.5, 0.0))
    bus.live("tf").deliver(correction_at(1.0, 0.5, 1.0))  # map -> odom
    bus.live("scan").deliver(scan_at(1.0, 5.0, 5.0, 5.0))
    assert await asyncio.wait_for(call, 1.0) == (1.0, 1.0, 0.0)
    assert bus.subs["pose"][0].closed  # read only until a correction came
    assert grid.pose_stamp == 1.0  # the odometry's
    feed.close()


async def test_a_scan_is_marked_from_the_kept_odometry_stamped_nearest_it() -> None:
    bus, clock = FakeBus(), ManualClock()
    feed = feed_of(bus, clock)
    grid = cast(GlobalCostmap, feed._world)
    call = asyncio.ensure_future(feed.call(lambda _: "first")(None))
    await asyncio.sleep(0)
    bus.live("odom").deliver(odom_at(1.0, 0.5, 0.0))
    bus.live("tf").deliver(correction_at(1.0, 0.5, 1.0))
    bus.live("scan").deliver(scan_at(1.0, 5.0, 5.0, 5.0))
    assert await asyncio.wait_for(call, 1.0) == "first"
    for i, y in enumerate((1.0, 0.0, 0.5)):  # in map: (1, 2), (1, 1), (1, 1.5)
        bus.live("odom").deliver(odom_at(2.0 + 0.02 * i, 0.5, y))
    bus.live("tf").deliver(correction_at(2.02, 0.5, 1.0))  # sent with the scan
    bus.live("scan").deliver(scan_at(2.02, 0.4, 5.0, 5.0))
    feed.read()
    assert grid.pose == (1.0, 1.5, 0.0)  # the newest odometry, composed
    assert lethal(grid, 1.4, 1.0)  # from the odometry at 2.02, composed
    assert not lethal(grid, 1.4, 1.5)
    assert not lethal(grid, 1.4, 2.0)
    feed.close()
