"""The pose in map a reader of odometry composes itself (aiobt.robot.correction): the same
pose as localization's ``{ns}/pose``, with the same stamps, leads and staleness; ``pose``
read only until a correction comes."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from aiobt.core.clock import ManualClock
from aiobt.msgs import Odometry, PoseStamped, TFMessage
from aiobt.robot.correction import compose, correction_message, correction_of
from aiobt.robot.tracker import RobotTracker

TIMEOUT = 0.5  # the controller's pose_timeout


class FakeSub:
    def __init__(self, callback: Callable[[Any], None]) -> None:
        self.callback = callback
        self.closed = False

    def close(self) -> None:
        self.closed = True

    def deliver(self, msg: Any) -> None:
        if not self.closed:  # as Subscription: nothing delivered once closed
            self.callback(msg)


class FakeBus:
    """Records the subscriptions by topic (the newest per topic)."""

    def __init__(self) -> None:
        self.subs: dict[str, FakeSub] = {}

    def subscribe(self, topic: str, _model: type, callback: Callable[[Any], None]) -> FakeSub:
        self.subs[topic] = FakeSub(callback)
        return self.subs[topic]


def odom(stamp: float, x: float, y: float, yaw: float) -> Odometry:
    return Odometry.model_validate(
        {"header": {"stamp": stamp, "frame_id": "odom"},
         "pose": PoseStamped.from_xy_yaw(x, y, yaw).pose.model_dump()}
    )  # fmt: skip


def pose(stamp: float, x: float, y: float, yaw: float) -> PoseStamped:
    msg = PoseStamped.from_xy_yaw(x, y, yaw)
    msg.header.stamp = stamp
    return msg


def test_compose_is_the_rigid_transform_and_wraps_the_yaw():
    assert compose((1.0, 2.0, math.pi / 2), 1.0, 0.0, 0.0) == pytest.approx((1.0, 3.0, math.pi / 2))
    x, y, yaw = compose((0.0, 0.0, 3.0), 0.0, 0.0, 3.0)
    assert (x, y) == (0.0, 0.0)
    assert yaw == pytest.approx(6.0 - 2 * math.pi)


def test_a_correction_read_back_from_its_message_composes_as_sent():
    rng = np.random.default_rng(7)
    for c, o in zip(rng.uniform(-4, 4, (50, 3)), rng.uniform(-4, 4, (50, 3)), strict=True):
        sent = (float(c[0]), float(c[1]), float(c[2]) * math.pi / 4)
        wire = TFMessage.model_validate_json(correction_message(sent, 2.5).model_dump_json())
        back = correction_of(wire)
        assert back is not None
        assert back.stamp == 2.5
        here = (float(o[0]), float(o[1]), float(o[2]) * math.pi / 4)
        assert compose(back.transform, *here) == pytest.approx(compose(sent, *here), abs=1e-12)


def test_a_message_without_map_to_odom_is_no_correction():
    other = correction_message((1.0, 0.0, 0.0), 1.0, "odom", "base_link")
    assert correction_of(other) is None


def _attached(clock: ManualClock, wall: list[float]) -> tuple[RobotTracker, FakeBus]:
    tracker = RobotTracker(clock, wall=lambda: wall[0], robot_time=True)
    bus = FakeBus()
    tracker.attach(bus)  # type: ignore[arg-type]
    return tracker, bus


def test_pose_is_read_until_a_correction_comes_then_each_odometry_is_composed():
    clock, wall = ManualClock(10.0), [0.0]
    tracker, bus = _attached(clock, wall)
    assert set(bus.subs) == {"tf", "pose", "odom"}
    bus.subs["pose"].deliver(pose(10.0, 5.0, 5.0, 0.0))  # a robot's own pose, as before
    assert tracker.states["map"].pose.x == 5.0
    correction = (2.0, 1.0, math.pi / 2)
    bus.subs["tf"].deliver(correction_message(correction, 9.95))
    assert bus.subs["pose"].closed  # let go: one 50 Hz stream fewer
    clock.set(10.02)
    bus.subs["odom"].deliver(odom(10.02, 1.0, 0.0, 0.1))
    state = tracker.states["map"]
    assert (state.pose.x, state.pose.y, state.pose.yaw) == pytest.approx(
        compose(correction, 1.0, 0.0, 0.1)
    )
    assert state.stamp == 10.02  # arrived with the odometry
    clock.set(10.05)  # the lead: as a pose stamped and received with this odometry
    assert tracker.lead("map") == pytest.approx(tracker.lead("odom"))
    assert tracker.lead("map") >= 0.03


def test_the_pose_in_map_is_stale_when_the_correction_stops_though_odometry_flows():
    clock, wall = ManualClock(0.0), [0.0]
    tracker, bus = _attached(clock, wall)
    t = 0.0
    for step in range(100):  # 2 s: odometry at 50 Hz, a correction with every 5th (10 Hz)
        t = round(t + 0.02, 6)
        clock.set(t)
        wall[0] = t
        if step % 5 == 0 and t < 1.0:  # localization goes silent at 1 s
            bus.subs["tf"].deliver(correction_message((0.0, 0.0, 0.0), t))
        bus.subs["odom"].deliver(odom(t, t, 0.0, 0.0))
        if t < 1.4:
            assert tracker.snapshot()["map"].age.stale("map", TIMEOUT) is None, t
    stale = tracker.snapshot()["map"].age.stale("map", TIMEOUT)
    assert stale is not None
    assert "'map' is stale" in stale
    assert tracker.snapshot()["odom"].age.stale("odom", TIMEOUT) is None


def test_forget_drops_the_correction_so_a_new_attach_starts_from_pose():
    clock, wall = ManualClock(1.0), [0.0]
    tracker, bus = _attached(clock, wall)
    bus.subs["tf"].deliver(correction_message((1.0, 0.0, 0.0), 1.0))
    tracker.forget()
    bus = FakeBus()
    tracker.attach(bus)  # type: ignore[arg-type]
    bus.subs["odom"].deliver(odom(1.02, 0.0, 0.0, 0.0))
    assert "map" not in tracker.states  # not composed with the correction from before


def test_behaviors_read_no_pose_in_map():
    tracker = RobotTracker(ManualClock(), costmap_frame="odom", map_pose=False)
    bus = FakeBus()
    tracker.attach(bus)  # type: ignore[arg-type]
    assert set(bus.subs) == {"odom"}
    assert tracker.waited == 1
    with pytest.raises(ValueError, match="needs the pose in 'map'"):
        RobotTracker(ManualClock(), map_pose=False)
