"""Localization in the loop: a hardware-like robot (no pose in map, odometry and lidar
with their default error), the localization service and a real router. The truth
(``{ns}/sim/pose``) is read by the test only."""

from __future__ import annotations

import numpy as np
import pytest

from aiobt.msgs import Empty, ParticleCloud, PoseStamped, ReinitializeGlobalLocalization
from aiobt.msgs.sim import Ack
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import sim_namespace

from .stack import (
    START,
    Spawn,
    Tracking,
    drive,
    set_initial_pose,
    spin,
    start_stack,
    stats,
    track,
)

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(600)]

# the corridor east and back, into the open plan north and back
ROUTE = [(9.0, 9.75), (16.5, 9.9), (16.5, 9.5), (9.0, 9.6), (3.0, 9.75)]
# the open plan north of the corridor: pillars and desks, few look-alike places
OPEN_PLAN_START = (3.0, 15.0, 0.0)
OPEN_PLAN_LOOP = [(3.0, 15.0), (7.0, 15.0), (7.0, 12.5), (3.0, 12.5)]  # 13 m


async def test_the_estimate_tracks_the_truth_while_driving(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    await start_stack(spawn, bus, bus_settings, speed=4)
    tracking = track(bus)
    await set_initial_pose(bus, *START)
    await drive(bus, ROUTE, within=120.0)
    dist, heading = tracking.errors()
    assert len(dist) > 500, "too few pose/truth pairs"
    rms, p99 = float(np.sqrt(np.mean(dist**2))), float(np.percentile(dist, 99))
    heading_rms = float(np.degrees(np.sqrt(np.mean(heading**2))))
    print(f"tracking: {len(dist)} poses, RMS {rms:.3f} m, p99 {p99:.3f} m, heading RMS "
          f"{heading_rms:.2f} deg")  # fmt: skip
    assert rms <= 0.05
    assert p99 <= 0.12
    assert heading_rms <= 2.0
    s = await stats(bus)
    assert s.updates > 50
    assert s.dropped == 0
    assert 0.0 < s.update_ms_p50 <= s.latency_ms_p99


async def _relocalize(bus: Bus, tracking: Tracking, attempts: int) -> int:
    """What a recovery tree does (ReinitializeGlobalLocalization, then move): reinitialize,
    spin once and drive a loop of the open plan until the estimate is on the truth;
    returns the attempts it took (the test fails after ``attempts``)."""
    for attempt in range(1, attempts + 1):
        reply = await bus.call(
            "reinitialize_global_localization", Empty(), ReinitializeGlobalLocalization.Response
        )
        assert reply.ok, reply.message
        await spin(bus, turns=1.0)
        end = await drive(bus, OPEN_PLAN_LOOP, within=90.0)
        dist, heading = tracking.errors(since=end.header.stamp - 0.2)
        assert len(dist) > 0, "no estimate after global localization"
        print(f"attempt {attempt}: {dist[-1]:.2f} m, {np.degrees(heading[-1]):.1f} deg off")
        if dist[-1] < 0.25 and heading[-1] < np.radians(10.0):
            return attempt
    pytest.fail(f"global localization did not find the robot in {attempts} attempts")


async def test_global_localization_spreads_the_particles_and_finds_the_robot(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    await start_stack(spawn, bus, bus_settings, speed=4, start=OPEN_PLAN_START)
    tracking = track(bus)
    cloud = bus.subscribe("particle_cloud", ParticleCloud, queue_size=1)
    reply = await bus.call(
        "reinitialize_global_localization", Empty(), ReinitializeGlobalLocalization.Response
    )
    assert reply.ok, reply.message
    spread = await cloud.wait_latest(10.0)  # the first scan updates: the cloud as spread
    xs = [p.pose.position.x for p in spread.particles]
    ys = [p.pose.position.y for p in spread.particles]
    assert max(xs) - min(xs) > 10.0  # over the whole map
    assert max(ys) - min(ys) > 10.0
    # with the sim_robot params (20,000 particles) the bench found 10 of 10 seeded poses
    # from one reinitialization; retried as a recovery tree would
    await _relocalize(bus, tracking, attempts=3)


# reinitialization's test: the filter's own recovery (on in sim_robot, behind the
# long-beam gate) could find the robot first, so it is off here
RECOVERY_OFF = ("--params-file", "sim_robot", "--set", "recovery_alpha_slow=0.0",
                "--set", "recovery_alpha_fast=0.0")  # fmt: skip


async def test_a_kidnapped_robot_is_lost_then_found_by_reinitialization(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    await start_stack(spawn, bus, bus_settings, speed=4, localization=RECOVERY_OFF)
    tracking = track(bus)
    await set_initial_pose(bus, *START)
    await drive(bus, [(5.0, 9.75)], within=30.0)
    # 3 m away into the room south, through the simulation's own service; the
    # localization is not told
    sim = sim_namespace(bus.namespace)  # the simulation's services
    there = PoseStamped.from_xy_yaw(5.0, 6.75, 0.0)
    moved = await bus.call("reset_pose", there, Ack, timeout=5.0, namespace=sim)
    assert moved.ok, moved.message
    end = await drive(bus, [(2.0, 7.0), (2.0, 4.5)], within=60.0)
    dist, _ = tracking.errors(since=end.header.stamp - 0.2)
    assert dist[-1] > 1.0, "the estimate followed a teleport it was not told of"
    # out through the doors to the open plan: the estimate is still wrong
    await drive(bus, [(3.3, 7.5), (3.4, 9.75), (3.9, 9.9), (3.9, 12.5)], within=60.0)
    await _relocalize(bus, tracking, attempts=3)
