"""The stale-pose rule (aiobt.robot.freshness) on a fake wall clock."""

from __future__ import annotations

import pytest

from aiobt.core.clock import ManualClock
from aiobt.msgs import Odometry, PoseStamped
from aiobt.robot.freshness import Freshness
from aiobt.robot.tracker import RobotTracker

TIMEOUT = 0.5
SPEED = 10.0  # robot seconds per wall second
PERIOD = 0.02  # robot s between two poses (the robot's 50 Hz)


class Robot:
    """Streams pose and odometry stamped on the robot's time, on a fake wall clock."""

    def __init__(self) -> None:
        self.wall = 0.0
        self.time = 0.0
        self.freshness = Freshness(lambda: self.wall)

    def run(self, robot_seconds: float, *, frames: tuple[str, ...] = ("map", "odom")) -> None:
        for _ in range(round(robot_seconds / PERIOD)):
            self.time += PERIOD
            self.wall += PERIOD / SPEED
            for frame in frames:
                self.freshness.received(frame, self.time)

    def stale(self, frame: str) -> str | None:
        return self.freshness.age(frame).stale(frame, TIMEOUT)


def test_poses_delivered_late_but_uniformly_are_fresh():
    robot = Robot()
    robot.run(2.0)
    robot.wall += 0.08  # the machine stalls: 0.8 s of robot time at 10x
    robot.run(PERIOD)  # then the backlog arrives (its newest pose shown)
    assert robot.stale("map") is None
    assert robot.freshness.age("map").robot == pytest.approx(0.0)


def test_a_stream_running_ahead_of_the_pose_is_not_a_stale_pose():
    robot = Robot()
    robot.run(1.0)
    robot.run(0.6, frames=("odom",))  # 60 ms of wall: the pose's drain was paced
    age = robot.freshness.age("map")
    assert age.robot == pytest.approx(0.6)
    assert robot.stale("map") is None  # issue 14's 702 'stale (0.52 s old)' at 10x


def test_a_pose_stream_that_stopped_alone_is_stale_after_pose_timeout():
    robot = Robot()
    robot.run(1.0)
    robot.run(4.0, frames=("odom",))  # 0.4 s of wall
    assert robot.stale("map") is None
    robot.run(1.2, frames=("odom",))  # 0.52 s of wall in all
    message = robot.stale("map")
    assert message is not None
    assert message.startswith("robot pose in frame 'map' is stale (5.20 s old in robot time")
    assert "pose_timeout 0.50 s" in message
    assert robot.stale("odom") is None


def test_a_robot_that_stopped_is_stale_after_pose_timeout_of_wall_time():
    robot = Robot()
    robot.run(1.0)
    robot.wall += 0.49
    assert robot.stale("odom") is None
    robot.wall += 0.02
    message = robot.stale("odom")
    assert message is not None
    assert "nothing new from the robot for 0.51 s of wall time" in message
    assert "pose 0.00 s old in robot time, pose_timeout 0.50 s" in message


def test_the_same_stamp_again_is_nothing_new():
    robot = Robot()
    robot.run(1.0)
    for _ in range(60):  # a paused robot repeating its last pose, 10 ms apart
        robot.wall += 0.01
        robot.freshness.received("map", robot.time)
        robot.freshness.received("odom", robot.time)
    assert robot.stale("map") is not None


def test_a_reset_starts_the_streams_over():
    robot = Robot()
    robot.run(30.0)
    robot.time = 0.0  # the simulation is reset: its stamps restart
    robot.run(PERIOD, frames=("odom",))
    assert robot.freshness.age("odom").robot > 29.0  # the pose's old stamp is newer...
    assert robot.stale("odom") is None  # ...but odometry keeps coming: fresh
    robot.run(0.1)
    assert robot.freshness.age("map").robot == pytest.approx(0.0)
    assert robot.stale("map") is None
    assert robot.stale("odom") is None


def test_unstamped_messages_count_as_new():
    wall = [0.0]
    freshness = Freshness(lambda: wall[0])
    for _ in range(100):
        wall[0] += 0.02
        freshness.received("map", 0.0)
    assert freshness.age("map").silence == 0.0


def test_nothing_received_is_no_age():
    age = Freshness(lambda: 5.0).age("map")
    assert (age.robot, age.silence, age.quiet) == (0.0, 0.0, 0.0)


def test_the_tracker_ages_each_frame_by_its_stamps():
    wall = [0.0]
    tracker = RobotTracker(ManualClock(), wall=lambda: wall[0])
    tracker.on_pose(PoseStamped.from_xy_yaw(1.0, 2.0, 0.0, stamp=3.0))
    odom = Odometry.model_validate({"header": {"stamp": 3.5, "frame_id": "odom"}})
    wall[0] = 0.1
    tracker.on_odom(odom)
    wall[0] = 0.7
    states = tracker.snapshot()
    assert states["map"].age.robot == pytest.approx(0.5)
    assert states["map"].age.silence == pytest.approx(0.7)
    assert states["odom"].age.quiet == pytest.approx(0.6)
    # nothing new for 0.6 s of wall time: the robot went quiet, both frames are stale
    assert "nothing new from the robot for 0.60 s" in str(states["map"].age.stale("map", TIMEOUT))
    assert states["odom"].age.stale("odom", TIMEOUT) is not None


def test_a_tracker_that_stopped_listening_forgets_the_robots_stamps():
    wall = [0.0]
    tracker = RobotTracker(ManualClock(), wall=lambda: wall[0])
    tracker.on_pose(PoseStamped.from_xy_yaw(1.0, 2.0, 0.0, stamp=30.0))
    tracker.forget()  # detached; the robot restarts from time 0 meanwhile
    wall[0] = 10.0
    tracker.on_pose(PoseStamped.from_xy_yaw(1.0, 2.0, 0.0, stamp=0.5))
    states = tracker.snapshot()
    assert states["map"].age.robot == 0.0  # not 29.5 s behind the forgotten stamp
    assert states["map"].age.stale("map", TIMEOUT) is None
