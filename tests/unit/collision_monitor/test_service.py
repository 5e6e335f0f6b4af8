"""The collision monitor's service on an in-process bus: commands in, the decision out,
its latched state, base_shift_correction fed from odometry, and the toggle service."""

from __future__ import annotations

from typing import Any

import pytest

from aiobt.core.clock import ManualClock
from aiobt.msgs import Header, LaserScan, Odometry, Pose, Toggle, Twist
from aiobt.msgs.safety import CollisionMonitorState, CollisionPolygons
from aiobt.system.odometry_tap import OdometryTap
from aiobt.transport import Bus, Subscription
from aiobt_services.collision_monitor import CollisionMonitor, load_params
from aiobt_services.collision_monitor.service import MonitorService

from .nav2_setup import config, polygon, ring_scan


def start(
    bus: Bus, tap: OdometryTap | None = None, **top: Any
) -> tuple[MonitorService, ManualClock]:
    clock = ManualClock(1.0)
    params = load_params(config({"Stop": polygon("polygon", 1.0, "stop")}, **top))
    service = MonitorService(bus, clock, CollisionMonitor(params), tap)
    service.start()
    return service, clock


async def decision(bus: Bus, out: Subscription[Twist], vx: float) -> float:
    """The monitor's answer to a command of ``vx`` (sent again until one comes)."""
    command = bus.publisher("cmd_vel_in", Twist)
    for _ in range(50):
        command.put(Twist.planar(vx, 0.0))
        try:
            return (await out.next(timeout=0.1)).linear.x
        except TimeoutError:
            continue
    raise AssertionError("no decision")


async def test_a_command_is_stopped_reported_and_let_through_when_toggled_off(
    local_bus: Bus,
) -> None:
    service, _ = start(local_bus)
    out = local_bus.subscribe("cmd_vel_out", Twist)
    states = local_bus.subscribe("collision_monitor_state", CollisionMonitorState, latched=True)
    polygons = local_bus.subscribe("collision_monitor/polygons", CollisionPolygons, latched=True)
    assert await decision(local_bus, out, 0.3) == 0.0  # no scan yet: invalid source
    assert service.monitor.last.polygon_name == "invalid source"
    scan = local_bus.publisher("scan", LaserScan)
    for _ in range(50):  # until the monitor has the scan: a ring 0.5 m round, in Stop
        scan.put(ring_scan(0.5, 1.0))
        if (
            await decision(local_bus, out, 0.3) == 0.0
            and service.monitor.last.polygon_name == "Stop"
        ):
            break
    state = await states.wait_latest(2.0)
    assert (state.action, state.polygon_name, state.enabled) == ("stop", "Stop", True)
    assert (await polygons.wait_latest(2.0)).polygons[0].name == "Stop"
    reply = await local_bus.call("collision_monitor/toggle", Toggle.Request(enable=False),
                                 Toggle.Response)  # fmt: skip
    assert (reply.success, reply.message) == (True, "Collision monitor toggled off successfully")
    assert await decision(local_bus, out, 0.3) == pytest.approx(0.3)


async def test_base_shift_correction_reads_the_odometry_come_since(local_bus: Bus) -> None:
    service, clock = start(local_bus, base_shift_correction=True)
    out = local_bus.subscribe("cmd_vel_out", Twist)
    odom = local_bus.publisher("odom", Odometry)
    for i in range(5):  # 0.1 m a step along x
        odom.put(Odometry(header=Header(stamp=1.0 + 0.02 * i, frame_id="odom"),
                          pose=Pose.from_xy_yaw(0.1 * i, 0.0)))  # fmt: skip
    scan = local_bus.publisher("scan", LaserScan)
    for _ in range(50):  # until the monitor has the scan (a ring 2 m round: no stop)
        scan.put(ring_scan(2.0, 1.0))
        if await decision(local_bus, out, 0.3) == pytest.approx(0.3):
            break
    assert await odom.wait_for_subscribers(2.0)  # no clock's to tap: its own
    history = service.monitor.odom
    assert history is not None
    assert not history.empty
    assert history.latest() == pytest.approx((0.4, 0.0, 0.0))
    assert clock.now() == 1.0


async def test_base_shift_correction_takes_the_odometry_its_clock_follows(
    local_bus: Bus,
) -> None:
    tap = OdometryTap(keep=32)
    tap.tapped = True  # as make_clock sets it on sim time
    service, _ = start(local_bus, tap, base_shift_correction=True)
    out = local_bus.subscribe("cmd_vel_out", Twist)
    odom = local_bus.publisher("odom", Odometry)
    for i in range(5):  # the clock's odometry: 0.1 m a step along x
        tap.put(Odometry(header=Header(stamp=1.0 + 0.02 * i, frame_id="odom"),
                         pose=Pose.from_xy_yaw(0.1 * i, 0.0)))  # fmt: skip
    scan = local_bus.publisher("scan", LaserScan)
    for _ in range(50):  # until the monitor has the scan (a ring 2 m round: no stop)
        odom.put(
            Odometry(header=Header(stamp=1.5, frame_id="odom"), pose=Pose.from_xy_yaw(9.0, 0.0))
        )  # not subscribed a second time
        scan.put(ring_scan(2.0, 1.0))
        if await decision(local_bus, out, 0.3) == pytest.approx(0.3):
            break
    assert not await odom.wait_for_subscribers(0.3)  # one subscription: the clock's
    history = service.monitor.odom
    assert history is not None
    assert history.latest() == pytest.approx((0.4, 0.0, 0.0))
    assert history.pose_at(1.03) == pytest.approx((0.15, 0.0, 0.0))  # all five, in order
    assert tap.take() == []


async def test_data_gone_stale_between_commands_stops_a_moving_base_at_once(
    local_bus: Bus,
) -> None:
    service, clock = start(local_bus, source_timeout=0.5)
    out = local_bus.subscribe("cmd_vel_out", Twist)
    scan = local_bus.publisher("scan", LaserScan)
    try:
        for _ in range(50):  # until the monitor has the scan (a ring 2 m round: no stop)
            scan.put(ring_scan(2.0, clock.now()))
            if await decision(local_bus, out, 0.3) == pytest.approx(0.3):
                break
        assert service.monitor.last.velocity[0] == pytest.approx(0.3)
        due = service.monitor.stale_at()
        await clock.forward(due - clock.now() - 0.02, step=0.01)  # no command meanwhile
        with pytest.raises(TimeoutError):
            await out.next(timeout=0.1)  # still fresh: nothing sent
        await clock.forward(0.04, step=0.01)
        assert (await out.next(timeout=2.0)).linear.x == 0.0  # stale: stopped, unasked
        assert service.monitor.last.polygon_name == "invalid source"
        assert "is 0.5" in service.monitor.last.reason
        await clock.forward(2.0, step=0.05)
        with pytest.raises(TimeoutError):
            await out.next(timeout=0.1)  # once: the base is stopped, commands decide again
    finally:
        await service.stop()
