"""The collision monitor in the chain with real processes: it stops the robot for what
the costmap does not know, slows it first with the approach polygon, stops it on stale
lidar, and ``ToggleCollisionMonitor`` in a tree turns it off and on."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from aiobt.core.status import Status
from aiobt.msgs import FollowPath, LaserScan, Twist
from aiobt.msgs.sim import Ack, BumperEvent, SpawnObstacle
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import sim_namespace
from tests.integration.controller.helpers import path_through
from tests.unit.nav.support import nav_tree, run_to_end

from .chain import ROBOT_RADIUS, Spawn, Trace, monitor_params, start_chain

pytestmark = [pytest.mark.integration, pytest.mark.e2e]
BOX_DEPTH = 0.2


async def drive_then_drop_box(bus: Bus, trace: Trace, ahead: float = 1.0) -> SpawnObstacle:
    """Follow a path east at full speed; once there, drop a box ``ahead`` m before the
    robot's centre (its near face)."""
    client = bus.action_client("follow_path", FollowPath)
    path = path_through([(-1.8, 0.0), (1.8, 0.0)])
    await client.send_goal(FollowPath.Goal(path=path), server_timeout=15.0)
    await trace.until(lambda: trace.speed >= 0.45 and trace.poses[-1].x > -1.4, 30.0, "full speed")
    x = trace.poses[-1].x
    box = SpawnObstacle(id="box", shape="box", x=x + ahead + BOX_DEPTH / 2, y=0.0,
                        size_x=BOX_DEPTH, size_y=0.6, height=0.5)  # fmt: skip
    sim = sim_namespace(bus.namespace)  # the simulation's services
    assert (await bus.call("obstacles/spawn", box, Ack, timeout=5.0, namespace=sim)).ok
    return box


def closest_gap(trace: Trace, box: SpawnObstacle) -> float:
    """The least distance between footprint and box face, by the sim's truth."""
    face = box.x - BOX_DEPTH / 2
    return min(face - (p.x + ROBOT_RADIUS) for p in trace.poses)


@pytest.mark.timeout(150)
@pytest.mark.parametrize("speed", ["1", "4"])
async def test_a_box_dropped_ahead_is_approached_slowly_then_stopped_short(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, speed: str
) -> None:
    trace = Trace(bus)
    bumps: list[BumperEvent] = []
    bus.subscribe("bumper", BumperEvent, bumps.append)
    await start_chain(spawn, bus, bus_settings, speed=speed)
    box = await drive_then_drop_box(bus, trace)
    dropped = len(trace.states)  # (a stop before the first scan came is no concern here)
    await trace.until(lambda: trace.still_since(0.5), 30.0, "standstill")
    gap = closest_gap(trace, box)
    actions = [s.action for s in trace.states[dropped:]]
    print(f"x{speed}: gap {gap:.3f} m; states {trace.actions()}")
    assert gap >= 0.10
    assert not [b for b in bumps if b.pressed]
    assert "approach" in actions
    assert actions.index("approach") < actions.index("stop")


@pytest.mark.timeout(150)
@pytest.mark.parametrize("composed", [False, True], ids=["separate", "composed"])
async def test_the_stop_polygon_alone_stops_short_at_4x(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, tmp_path: Path, composed: bool
) -> None:
    """The smoother and the monitor as two processes, or composed in one."""

    def stop_only(params: dict[str, Any]) -> None:
        params["polygons"] = ["PolygonStop"]

    trace = Trace(bus)
    params = monitor_params(tmp_path, stop_only)
    monitor = ["--params-file", params]
    await start_chain(spawn, bus, bus_settings, monitor=monitor, composed=composed)
    box = await drive_then_drop_box(bus, trace)
    await trace.until(lambda: trace.still_since(0.5), 30.0, "standstill")
    gap = closest_gap(trace, box)
    print(f"stop only: gap {gap:.3f} m; states {trace.actions()}")
    assert trace.actions()[-1] == "stop:PolygonStop"
    assert gap >= 0.10


@pytest.mark.timeout(150)
@pytest.mark.parametrize("composed", [False, True], ids=["separate", "composed"])
async def test_stale_lidar_stops_the_base_within_source_timeout_and_a_cycle(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, tmp_path: Path, composed: bool
) -> None:
    """Composed, the monitor's time is the smoother's clock, not its odometry's stamps."""
    timeout, cycle, decel = 0.5, 0.05, 2.5  # source_timeout; smoother period; base m/s^2

    def relayed(params: dict[str, Any]) -> None:
        params["scan"]["topic"] = "relayed_scan"
        params["source_timeout"] = timeout

    relay = bus.publisher("relayed_scan", LaserScan)
    relaying = [True]
    last: list[float] = []

    def forward(scan: LaserScan) -> None:
        if relaying[0]:
            relay.put(scan)
            last.append(scan.header.stamp)

    bus.subscribe("scan", LaserScan, forward)
    trace = Trace(bus)
    params = monitor_params(tmp_path, relayed)
    monitor = ["--params-file", params]
    await start_chain(spawn, bus, bus_settings, monitor=monitor, composed=composed)
    client = bus.action_client("follow_path", FollowPath)
    path = path_through([(-1.8, 0.0), (1.8, 0.0)])
    await client.send_goal(FollowPath.Goal(path=path), server_timeout=15.0)
    await trace.until(lambda: trace.speed >= 0.45, 30.0, "full speed")
    relaying[0] = False
    t0 = last[-1]
    await trace.until(lambda: trace.still_since(0.2), 30.0, "standstill")
    stopped = next(o.header.stamp for o in trace.odom
                   if o.header.stamp > t0 and abs(o.twist.linear.x) < 1e-3)  # fmt: skip
    stale = next(
        s for s in trace.states if s.polygon_name == "invalid source" and s.header.stamp > t0
    )  # (not the one at start-up, before the first scan came)
    zero = stale.header.stamp  # the monitor's decision, on its clock
    at_timeout = [o.twist.linear.x for o in trace.odom if o.header.stamp <= t0 + timeout - cycle]
    print(
        f"scan stale at {t0:.2f}: zero command +{zero - t0:.3f} s, base still +{stopped - t0:.3f} s"
    )
    assert at_timeout[-1] >= 0.4  # moving on until the data went stale
    # decided when the scan goes stale, not at the controller's next command (a late
    # controller cycle once took 1.8 cycles): at the first odometry stamp past the timeout
    assert timeout < zero - t0 <= timeout + cycle
    assert stopped - t0 <= timeout + cycle + 0.5 / decel + 0.05  # the base's deceleration
    assert (stale.action, stale.linear_x) == ("stop", 0.0)
    assert "source 'scan' is 0.5" in stale.reason


TOGGLE = '<ToggleCollisionMonitor enable="{enable}" service_name="collision_monitor/toggle"/>'


@pytest.mark.timeout(120)
async def test_toggle_collision_monitor_in_a_tree_turns_it_off_and_on(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, tmp_path: Path
) -> None:
    def out_to_probe(params: dict[str, Any]) -> None:
        params["cmd_vel_out_topic"] = "monitored"  # the base is not driven into the box

    trace = Trace(bus, command_key="monitored")
    params = monitor_params(tmp_path, out_to_probe)
    await start_chain(spawn, bus, bus_settings, speed="2", smoother=None, controller=None,
                      monitor=["--params-file", params])  # fmt: skip
    box = SpawnObstacle(id="box", shape="box", x=-1.3, y=0.0, size_x=0.2, size_y=0.6, height=0.5)
    sim = sim_namespace(bus.namespace)  # the simulation's services
    assert (await bus.call("obstacles/spawn", box, Ack, timeout=5.0, namespace=sim)).ok
    command = bus.publisher("cmd_vel_smoothed", Twist)

    async def monitored() -> float:
        """The monitor's answer to a command, once a few more odometry messages (about
        0.1 s of sim time: a scan) have come."""
        seen = len(trace.odom)
        await trace.until(lambda: len(trace.odom) >= seen + 5, 10.0, "odometry")
        count = len(trace.commands)
        command.put(Twist.planar(0.3, 0.0))
        await trace.until(lambda: len(trace.commands) > count, 10.0, "monitored command")
        return trace.commands[-1][1].linear.x

    assert await _settled(monitored, 0.0)  # the box, in the stop polygon
    for enable, expected in (("false", 0.3), ("true", 0.0)):
        tree = nav_tree(bus, TOGGLE.replace("{enable}", enable), server_timeout=10.0)
        assert await run_to_end(tree, timeout=15.0) is Status.SUCCESS
        assert await _settled(monitored, expected)
        assert trace.states[-1].enabled is (enable == "true")


async def _settled(probe: Any, expected: float, tries: int = 20) -> bool:
    """``probe()`` gives ``expected`` (the monitor may need a scan or two first)."""
    for _ in range(tries):
        if abs(await probe() - expected) < 1e-9:
            return True
    return False
