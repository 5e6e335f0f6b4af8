"""The look-ahead per pose: on the robot's time a pose delivered late gets a longer lead
(by its own stamp), so a behavior stops earlier on it; an on-time pose is unchanged."""

from __future__ import annotations

import math

import pytest

from aiobt.core.clock import ManualClock
from aiobt.geometry import STOP, Pose2D, Velocity, wrap_angle
from aiobt.msgs import Header, Odometry, Pose, Twist
from aiobt.robot.freshness import FRESH
from aiobt.robot.latency import command_lead
from aiobt.robot.tracker import RobotTracker
from aiobt_services.behaviors import DriveOnHeading, Inputs, SpinBehavior
from aiobt_services.behaviors.base import TimedBehavior
from aiobt_services.controller.unicycle import Unicycle

DT = 0.05  # robot s per cycle (the service's 20 Hz, the robot's odometry alike)
WAY = 2  # cycles a command takes to the base


def odometry(stamp: float, pose: Pose2D, velocity: Velocity) -> Odometry:
    return Odometry(
        header=Header(stamp=stamp, frame_id="odom"),
        pose=Pose.from_xy_yaw(pose.x, pose.y, pose.yaw),
        twist=Twist.planar(velocity.v, velocity.w),
    )


def test_command_lead_is_the_age_by_stamp_plus_the_way():
    assert command_lead(10.0, 9.9, 0.05) == pytest.approx(0.15)
    # the clock trails the robot (its message older than the pose): the way holds that lag
    assert command_lead(10.0, 10.02, 0.05) == pytest.approx(0.03)
    assert command_lead(10.0, 10.2, 0.05) == 0.0


def test_on_robot_time_a_pose_later_than_usual_gets_a_longer_lead():
    clock = ManualClock(10.0)
    tracker = RobotTracker(clock, robot_time=True)
    tracker.on_odom(odometry(10.0, Pose2D(0.0, 0.0, 0.0), STOP))
    tracker.sent(Velocity(0.3, 0.0))
    clock.advance(0.1)  # the odometry showing motion, taken at 10.08, arrives 0.02 s later
    tracker.on_odom(odometry(10.08, Pose2D(0.0, 0.0, 0.0), Velocity(0.02, 0.0)))
    assert tracker.delay.estimate == pytest.approx(0.1)  # the round trip
    assert tracker.delay.one_way == pytest.approx(0.08)  # the command's way
    clock.advance(0.1)
    tracker.on_odom(odometry(10.18, Pose2D(0.01, 0.0, 0.0), Velocity(0.1, 0.0)))  # usual lag
    on_time = tracker.lead("odom")
    assert on_time == pytest.approx(0.1)  # as by arrival: the round trip
    clock.advance(0.05)
    tracker.on_odom(odometry(10.1, Pose2D(0.02, 0.0, 0.0), Velocity(0.1, 0.0)))  # 0.15 s late
    assert tracker.lead("odom") == pytest.approx(0.15 + 0.08)  # by its stamp
    by_arrival = RobotTracker(ManualClock(10.25))
    by_arrival.delay = tracker.delay
    by_arrival.on_odom(odometry(10.1, Pose2D(0.02, 0.0, 0.0), Velocity(0.1, 0.0)))
    assert by_arrival.lead("odom") == pytest.approx(on_time)  # on the wall clock: unseen


class Link:
    """A base acting on each command ``WAY`` cycles late, whose odometry reaches the
    service on time until ``late_from`` s, then ``late`` cycles late (a loaded machine).
    The service's clock follows the robot's, as on ``--sim-time``."""

    def __init__(self, tracker: RobotTracker, clock: ManualClock, late_from: float, late: int):
        self.base = Unicycle(Pose2D(0.0, 0.0, 0.0), max_linear_accel=2.5, max_angular_accel=6.0)
        self.tracker, self.clock = tracker, clock
        self.late_from, self.late = late_from, late
        self.queue = [STOP] * WAY
        self.sent: list[Odometry] = []
        self.turned = [0.0]  # rad turned by the base after each cycle
        self.xs = [0.0]  # the base's x after each cycle

    def cycle(self, cmd: Velocity) -> None:
        self.tracker.sent(cmd)
        self.queue.append(cmd)
        acting = self.queue.pop(0)
        before = self.base.pose.yaw
        self.base.step(acting, DT)
        self.turned.append(self.turned[-1] + wrap_angle(self.base.pose.yaw - before))
        self.xs.append(self.base.pose.x)
        self.clock.advance(DT)
        self.sent.append(odometry(self.clock.now(), self.base.pose, acting))
        lateness = self.late if self.clock.now() >= self.late_from else 0
        if len(self.sent) > lateness:
            self.tracker.on_odom(self.sent[-1 - lateness])

    def settle(self) -> None:
        for _ in range(WAY + 10):
            self.cycle(STOP)


def run(behavior: TimedBehavior, robot_time: bool, late_from: float, late: int) -> Link:
    clock = ManualClock(0.0)
    tracker = RobotTracker(clock, robot_time=robot_time)
    link = Link(tracker, clock, late_from, late)
    link.cycle(STOP)
    while clock.now() < 30.0:
        state = tracker.states["odom"]
        step = behavior.step(Inputs(clock.now(), state.pose, FRESH, lead=tracker.lead("odom")))
        link.cycle(step.cmd or STOP)
        if step.done:
            link.settle()
            return link
    raise AssertionError("behavior did not finish")


@pytest.mark.parametrize("late", [6, 10])
def test_a_late_pose_stops_the_drive_earlier_on_target(late):
    """0.3-0.5 s late (30-50 ms of wall time at 10x): by arrival the base overshoots by
    the late poses' travel (then drives back once still); by stamp it stops on target."""
    by_stamp = run(DriveOnHeading(0.4, 0.3), True, late_from=0.6, late=late)
    by_arrival = run(DriveOnHeading(0.4, 0.3), False, late_from=0.6, late=late)
    assert by_stamp.base.pose.x == pytest.approx(0.4, abs=0.005)
    assert max(by_stamp.xs) - 0.4 < 0.005
    assert max(by_arrival.xs) - 0.4 > 0.02


def overshoot(link: Link, target: float) -> float:
    """How far (rad) the base turned past ``target`` at most."""
    return max(0.0, *(math.copysign(1.0, target) * turned - abs(target) for turned in link.turned))


@pytest.mark.parametrize("late", [6, 10])
def test_a_late_pose_stops_the_spin_earlier_on_target(late):
    """By arrival the base turns past the target and back; by stamp it stops short of it."""
    by_stamp = run(SpinBehavior(-math.pi), True, late_from=1.5, late=late)
    by_arrival = run(SpinBehavior(-math.pi), False, late_from=1.5, late=late)
    assert abs(wrap_angle(by_stamp.base.pose.yaw + math.pi)) < 0.02
    assert overshoot(by_stamp, -math.pi) < 0.01
    assert overshoot(by_arrival, -math.pi) > overshoot(by_stamp, -math.pi) + 0.03


def test_on_time_poses_stop_where_they_did():
    by_stamp = run(DriveOnHeading(0.4, 0.3), True, late_from=math.inf, late=0).base.pose
    by_arrival = run(DriveOnHeading(0.4, 0.3), False, late_from=math.inf, late=0).base.pose
    assert by_stamp.x == pytest.approx(by_arrival.x, abs=1e-9)
    assert by_stamp.x == pytest.approx(0.4, abs=0.005)
