"""The server's logic closing the loop through the real simulation (no Zenoh): the
box walks a seeded loop at 0.3 m/s, the tracker sees it in the noisy lidar, the robot
follows on noisy odometry, then the box hides for 3 s."""

from __future__ import annotations

import asyncio
import math

from aiobt.geometry.smooth import SmoothControlParams
from aiobt.msgs.follow_target import OFFICE_LOOP_CENTRE, OFFICE_LOOP_RADII
from aiobt.msgs.remote_actions import FollowObject
from aiobt_services.following.follow import FollowingState
from aiobt_services.following.params import FollowingParams
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.sensors import LidarConfig, NoiseConfig
from aiobt_services.robot.sim import SimConfig, Simulation
from aiobt_services.robot.target import FollowTarget
from aiobt_services.robot.target_path import seeded_loop
from aiobt_services.robot.worlds import world_path

from .stepped import SteppedWorld

FAST = SmoothControlParams(v_linear_max=0.5, v_angular_max=1.0)
PARAMS = FollowingParams(search_by_rotating=True, controller=FAST)
NOISE = NoiseConfig(odom_linear=0.05, odom_angular=0.05, slip=0.02, odom_angular_scale=0.02)


def test_it_follows_a_walking_box_and_finds_it_again_after_it_hides() -> None:
    world = load_map(world_path("office"))
    path = seeded_loop(OFFICE_LOOP_CENTRE, OFFICE_LOOP_RADII, 5)
    behind, ahead = path.pose_at(path.length - 1.0), path.pose_at(0.0)
    world.start = (behind.x, behind.y, math.atan2(ahead.y - behind.y, ahead.x - behind.x))
    config = SimConfig(lidar=LidarConfig(noise=0.01, dropout=0.01), noise=NOISE)
    with Simulation(world, config) as sim:
        box = FollowTarget(sim, "target", path, speed=0.3, size=0.4)
        sim.movers.append(box.update)
        stepped = SteppedWorld(sim, box, PARAMS)
        stepped.at(60.0, lambda: box.hide(3.0))
        goal = FollowObject.Goal(pose_topic="dynamic_pose", max_duration=75.0)
        result = asyncio.run(stepped.server.execute(goal, stepped))
        touched = sim.in_contact
    rec = stepped.record
    first = [d for t, d in zip(rec.times, rec.distances, strict=True) if t <= 60.0]
    assert sum(abs(d - 1.0) <= 0.3 for d in first) >= 0.9 * len(first)
    assert min(rec.distances) > 0.22 + 0.2 * math.sqrt(2)  # the outlines never met
    assert touched == []
    assert result.error_code == 0
    assert result.num_retries == 1
    retry = rec.feedback.index(FollowingState.RETRY)
    assert FollowingState.CONTROLLING in rec.feedback[retry:]
    back = [d for t, d in zip(rec.times, rec.distances, strict=True) if t >= 72.0]
    assert all(abs(d - 1.0) <= 0.3 for d in back)  # found again, and caught up
