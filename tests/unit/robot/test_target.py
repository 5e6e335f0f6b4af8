"""The followed box: its seeded loop, its walk, and the lidar tracker's detections."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.geometry import Pose2D
from aiobt.msgs.follow_target import OFFICE_LOOP_CENTRE, OFFICE_LOOP_RADII
from aiobt_services.robot.convert import laser_scan
from aiobt_services.robot.mapfile import MapInfo, load_map
from aiobt_services.robot.sensors import LidarConfig
from aiobt_services.robot.sim import SimConfig, Simulation
from aiobt_services.robot.target import FollowTarget, TrackerConfig
from aiobt_services.robot.target_path import LoopPath, PathError, seeded_loop
from aiobt_services.robot.worlds import world_path


def office(start: tuple[float, float, float]) -> MapInfo:
    world = load_map(world_path("office"))
    world.start = start
    return world


def loop(seed: int) -> LoopPath:
    return seeded_loop(OFFICE_LOOP_CENTRE, OFFICE_LOOP_RADII, seed)


def test_a_seed_draws_one_loop_and_every_seed_is_clear_of_the_office_walls() -> None:
    assert np.array_equal(loop(3).points, loop(3).points)
    assert not np.array_equal(loop(3).points, loop(4).points)
    world = office((2.0, 9.75, 0.0))
    for seed in range(20):
        path = loop(seed)
        assert 15.0 < path.length < 21.0
        path.check_clear(world, 0.35)


def test_a_loop_through_a_wall_is_refused_naming_where() -> None:
    path = LoopPath.through([(2.0, 9.75), (6.0, 9.75), (6.0, 13.0)])  # through y = 11's wall
    with pytest.raises(PathError, match=r"within 0.30 m of a wall .* at \(6.00, 1\d\.\d\d\)"):
        path.check_clear(office((2.0, 9.75, 0.0)), 0.3)
    with pytest.raises(PathError, match="at least 3"):
        LoopPath.through([(0.0, 0.0), (1.0, 1.0)])


def test_pose_at_walks_the_loop_by_arc_length() -> None:
    square = LoopPath.through([(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)])
    assert square.length == 8.0
    assert square.pose_at(3.0) == Pose2D(2.0, 1.0, math.pi / 2)
    assert square.pose_at(9.0) == Pose2D(1.0, 0.0, 0.0)


def test_the_box_walks_at_its_speed_and_waits_for_the_robot_in_its_way() -> None:
    path = LoopPath.through([(3.0, 13.0), (10.0, 13.0), (10.0, 14.5), (3.0, 14.5)])
    with Simulation(office((1.5, 14.0, 0.0))) as sim:
        box = FollowTarget(sim, "target", path, speed=0.5, size=0.4)
        sim.movers.append(box.update)
        sim.run_for(2.0)
        assert box.pose.x == pytest.approx(4.0, abs=0.02)
        sim.teleport(Pose2D(4.6, 13.0, 0.0))  # stand in its way
        sim.run_for(2.0)
        assert box.pose.x < 4.6 - 0.22 - 0.2 + 0.01
        assert box.travelled == pytest.approx(box.pose.x - 3.0, abs=0.01)


def tracker_world(robot: tuple[float, float, float]) -> tuple[Simulation, FollowTarget]:
    sim = Simulation(office(robot), SimConfig(lidar=LidarConfig(noise=0.01, dropout=0.01)))
    path = LoopPath.through([(5.0, 13.0), (5.5, 13.0), (5.5, 13.5)])
    return sim, FollowTarget(sim, "target", path, 0.0, 0.4, tracker=TrackerConfig(dropout=0.0))


def test_the_tracker_sees_the_box_in_the_robot_frame_near_its_truth() -> None:
    sim, box = tracker_world((3.0, 13.5, 0.3))
    with sim:
        seen = box.detect(laser_scan(sim.scan()))
        assert seen is not None
        found = sim.true_pose.compose(seen)
        assert math.hypot(found.x - 5.0, found.y - 13.0) < 0.08
        box.hide(1.0)
        assert box.detect(laser_scan(sim.scan())) is None
        sim.run_for(1.0)
        assert box.detect(laser_scan(sim.scan())) is not None


def test_the_tracker_does_not_see_through_a_wall() -> None:
    sim, box = tracker_world((5.0, 9.75, 0.0))  # in the corridor, the box 3.25 m north
    with sim:
        assert box.detect(laser_scan(sim.scan())) is None


def test_the_trackers_dropout_misses_about_its_share() -> None:
    sim, box = tracker_world((3.0, 13.5, 0.0))
    box.tracker = TrackerConfig(dropout=0.3)
    with sim:
        scan = laser_scan(sim.scan())
        missed = sum(box.detect(scan) is None for _ in range(400))
    assert 80 < missed < 160
