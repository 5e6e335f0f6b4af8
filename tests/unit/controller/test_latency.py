"""The command-to-odometry delay estimate, and the tracker's lazy local costmap."""

from __future__ import annotations

import numpy as np
import pytest

from aiobt.core.clock import ManualClock
from aiobt.costmap import INSCRIBED
from aiobt.costmap.local import LocalCostmap, LocalCostmapParams
from aiobt.geometry import STOP, Velocity
from aiobt.msgs import Odometry, PoseStamped
from aiobt.robot.latency import LoopDelay
from aiobt.robot.tracker import RobotTracker

from .test_local_costmap import _scan_with_wall_ahead

GO = Velocity(0.3, 0.0)


def test_no_sample_no_delay():
    assert LoopDelay().estimate == 0.0


def test_delay_from_command_to_first_motion_then_smoothed():
    delay = LoopDelay(weight=0.5)
    delay.commanded(1.0, GO, STOP)
    delay.commanded(1.05, GO, STOP)  # still waiting: the first command counts
    delay.observed(1.1, STOP)
    delay.observed(1.2, Velocity(0.02, 0.0))
    assert delay.estimate == pytest.approx(0.2)
    delay.commanded(5.0, STOP, Velocity(0.3, 0.0))
    delay.commanded(6.0, Velocity(0.0, 0.5), STOP)
    delay.observed(6.4, Velocity(0.0, 0.06))
    assert delay.estimate == pytest.approx(0.3)
    assert delay.samples == 2


def test_no_sample_when_already_moving_or_cancelled_or_too_long():
    delay = LoopDelay(max_delay=1.0)
    delay.commanded(1.0, GO, Velocity(0.3, 0.0))  # moving already: no start of motion
    delay.observed(1.1, Velocity(0.3, 0.0))
    delay.commanded(2.0, GO, STOP)
    delay.commanded(2.05, STOP, STOP)  # stopped before it moved
    delay.observed(2.2, Velocity(0.01, 0.0))
    delay.commanded(3.0, GO, STOP)
    delay.observed(4.5, Velocity(0.01, 0.0))  # 1.5 s: a stalled robot, not a delay
    assert delay.samples == 0
    assert delay.estimate == 0.0


def test_tracker_lead_is_pose_age_plus_delay():
    clock = ManualClock(10.0)
    tracker = RobotTracker(clock)
    tracker.on_odom(Odometry())
    tracker.sent(GO)
    clock.advance(0.1)
    tracker.on_odom(Odometry.model_validate({"twist": {"linear": {"x": 0.05}}}))
    clock.advance(0.05)
    assert tracker.lead("odom") == pytest.approx(0.05 + 0.1)
    assert tracker.lead("map") == pytest.approx(0.1)  # no pose in map: the delay alone


def test_scans_wait_for_a_refresh():
    costmap = LocalCostmap()
    tracker = RobotTracker(ManualClock(), costmap)
    tracker.on_pose(PoseStamped.from_xy_yaw(0.0, 0.0, 0.0))
    tracker.on_scan(_scan_with_wall_ahead(1.0))
    ahead = np.array([[1.0, 0.0]])
    assert costmap.costs_at(ahead)[0] == 0  # kept, not integrated
    tracker.refresh_costmap()
    assert costmap.costs_at(ahead)[0] >= INSCRIBED


def test_the_costmap_takes_scans_at_its_update_frequency_of_robot_time():
    clock = ManualClock()
    costmap = LocalCostmap(LocalCostmapParams(update_frequency=5.0))
    tracker = RobotTracker(clock, costmap)
    tracker.on_pose(PoseStamped.from_xy_yaw(0.0, 0.0, 0.0))
    assert tracker.refresh_costmap()  # the first update at once: the window, no scan yet
    ahead = np.array([[1.0, 0.0]])
    tracker.on_scan(_scan_with_wall_ahead(1.0))
    clock.advance(0.15)
    assert not tracker.refresh_costmap()
    assert costmap.costs_at(ahead)[0] == 0  # 0.15 s after the last update: not yet
    clock.advance(0.05)
    assert tracker.refresh_costmap()
    assert costmap.costs_at(ahead)[0] >= INSCRIBED  # 0.2 s: the newest scan is in
    tracker.forget()
    tracker.on_pose(PoseStamped.from_xy_yaw(0.0, 0.0, 0.0))
    tracker.on_scan(_scan_with_wall_ahead(0.5))
    tracker.refresh_costmap()  # attached again: at once
    assert costmap.costs_at(np.array([[0.5, 0.0]]))[0] >= INSCRIBED


def test_a_bad_update_frequency_is_refused():
    with pytest.raises(ValueError, match="update_frequency"):
        LocalCostmapParams(update_frequency=0.0)


def test_one_way_delay_by_stamps_smoothed_from_its_own_first_sample():
    delay = LoopDelay(weight=0.5)
    delay.commanded(1.0, GO, STOP)
    delay.observed(1.2, Velocity(0.02, 0.0), stamp=0.9)  # taken before the command: no
    assert delay.estimate == pytest.approx(0.2)
    assert delay.one_way == 0.0
    delay.commanded(2.0, GO, STOP)
    delay.observed(2.1, Velocity(0.02, 0.0), stamp=2.06)
    assert delay.one_way == pytest.approx(0.06)
    delay.commanded(3.0, GO, STOP)
    delay.observed(3.1, Velocity(0.02, 0.0), stamp=3.14)  # the clock trails the robot
    assert delay.one_way == pytest.approx(0.1)
    assert delay.estimate == pytest.approx(0.125)


def test_a_costmap_kept_in_odom_does_not_move_with_the_estimate():
    """The behaviors' costmap (Nav2's local_frame odom): scans are laid at the odometry
    pose, so a jump of the map-frame estimate (a relocalization) moves nothing."""
    clock = ManualClock()
    costmap = LocalCostmap(LocalCostmapParams(update_frequency=5.0))
    tracker = RobotTracker(clock, costmap, costmap_frame="odom")
    tracker.on_odom(Odometry())  # odom (0, 0, 0)
    tracker.on_pose(PoseStamped.from_xy_yaw(3.0, 2.0, 1.0))  # the estimate in map
    tracker.on_scan(_scan_with_wall_ahead(1.0))
    assert tracker.refresh_costmap()
    assert costmap.costs_at(np.array([[1.0, 0.0]]))[0] >= INSCRIBED  # ahead in odom
    tracker.on_pose(PoseStamped.from_xy_yaw(1.0, 0.0, 0.0))  # the estimate jumps onto it
    tracker.on_scan(_scan_with_wall_ahead(1.0))
    clock.advance(0.2)
    assert tracker.refresh_costmap()
    assert costmap.costs_at(np.array([[0.0, 0.0]]))[0] < INSCRIBED  # the robot stays clear
    map_frame = LocalCostmap(LocalCostmapParams(update_frequency=5.0))
    controller = RobotTracker(ManualClock(), map_frame)  # the default: map
    controller.on_odom(Odometry())
    controller.on_pose(PoseStamped.from_xy_yaw(3.0, 2.0, 1.0))
    controller.on_scan(_scan_with_wall_ahead(1.0))
    controller.refresh_costmap()
    wall = (3.0 + np.cos(1.0), 2.0 + np.sin(1.0))
    assert map_frame.costs_at(np.array([wall]))[0] >= INSCRIBED  # laid at the estimate


def test_an_unknown_costmap_frame_is_refused():
    with pytest.raises(ValueError, match=r"costmap_frame.*'base_link'"):
        RobotTracker(ManualClock(), LocalCostmap(), costmap_frame="base_link")
