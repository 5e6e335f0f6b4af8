"""Behaviors as state machines on a kinematic unicycle and a fixed dt."""

from __future__ import annotations

import math
from collections.abc import Callable

import pytest

from aiobt.costmap import LETHAL
from aiobt.costmap.checker import CollisionChecker, GridCostmap
from aiobt.geometry import Pose2D, Velocity, wrap_angle
from aiobt.robot.freshness import FRESH, PoseAge
from aiobt_services.behaviors import (
    AssistedTeleop,
    BehaviorInputError,
    BehaviorStep,
    DriveOnHeading,
    Inputs,
    Outcome,
    SpinBehavior,
    WaitBehavior,
    back_up,
)
from aiobt_services.behaviors.base import TimedBehavior
from aiobt_services.controller.unicycle import Unicycle

DT = 0.05


def run(
    behavior: TimedBehavior | WaitBehavior,
    robot: Unicycle,
    max_time: float = 30.0,
    teleop: Velocity | None = None,
) -> tuple[BehaviorStep, float, list[Velocity]]:
    now = 0.0
    commands: list[Velocity] = []
    while now <= max_time:
        step = behavior.step(Inputs(now, robot.pose, FRESH, teleop, now))
        if step.cmd is not None:
            commands.append(step.cmd)
        if step.done:
            return step, now, commands
        robot.step(step.cmd or Velocity(), DT)
        now += DT
    raise AssertionError("behavior did not finish")


def wall_ahead(x: float) -> CollisionChecker:
    grid = GridCostmap.empty(10.0, 10.0, 0.05, (-5.0, -5.0))
    grid.fill_box(x, -5.0, x + 0.2, 5.0, LETHAL)
    return CollisionChecker(grid)


@pytest.mark.parametrize("target", [math.pi / 2, -math.pi / 2, 3 * math.pi, -2.5 * math.pi])
def test_spin_turns_the_signed_angle_across_the_wrap(target):
    start_yaw = 3.0  # close to +pi, so every spin crosses the wrap
    robot = Unicycle(Pose2D(0.0, 0.0, start_yaw), max_angular_accel=3.2)
    step, _, commands = run(SpinBehavior(target), robot)
    assert step.succeeded
    assert step.feedback == pytest.approx(abs(target), abs=0.03)
    assert all(math.copysign(1.0, c.w) == math.copysign(1.0, target) for c in commands if c.w)
    expected = wrap_angle(start_yaw + target)
    assert abs(wrap_angle(robot.pose.yaw - expected)) < 0.06


def test_spin_times_out_on_a_stuck_robot():
    class Stuck(Unicycle):
        def step(self, cmd: Velocity, dt: float) -> Pose2D:
            return self.pose

    step, now, _ = run(SpinBehavior(1.0, time_allowance=2.0), Stuck(Pose2D(0, 0, 0)))
    assert step.outcome is Outcome.TIMEOUT
    assert "time allowance of 2.00 s" in step.message
    assert step.cmd == Velocity(0.0, 0.0)
    assert now == pytest.approx(2.05, abs=DT)


def test_spin_in_collision_fails_collision_ahead():
    checker = wall_ahead(-0.1)  # the robot's own cell is lethal
    step, _, _ = run(SpinBehavior(1.0, collision=checker), Unicycle(Pose2D(0, 0, 0)))
    assert step.outcome is Outcome.COLLISION_AHEAD


def test_drive_on_heading_travels_the_distance_along_its_heading():
    robot = Unicycle(Pose2D(1.0, 1.0, math.pi / 4))
    step, now, commands = run(DriveOnHeading(0.5, 0.25), robot)
    assert step.succeeded
    assert step.feedback == pytest.approx(0.5, abs=0.01)
    assert robot.pose.distance_to(Pose2D(1.0, 1.0, 0.0)) == pytest.approx(0.5, abs=0.01)
    assert robot.pose.x > 1.3
    assert robot.pose.y > 1.3
    assert now == pytest.approx(2.1, abs=3 * DT)
    speeds = [c.v for c in commands if c.v]
    assert commands[-1] == Velocity(0.0, 0.0)
    assert speeds[0] == pytest.approx(0.125)  # Nav2's acceleration limit, 2.5 m/s^2
    assert max(speeds) == 0.25
    assert min(speeds) >= 0.1  # Nav2's minimum_speed
    assert speeds[-1] < 0.25  # slowed down to stop at the distance


def test_drive_on_heading_backwards_with_negative_speed_and_distance():
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0))
    step, _, commands = run(DriveOnHeading(-0.4, -0.3), robot)
    assert step.succeeded
    assert robot.pose.x == pytest.approx(-0.4, abs=0.01)
    assert all(c.v <= 0.0 for c in commands)
    assert sum(c.v < 0.0 for c in commands) > 10


def test_backup_at_nav2_defaults_succeeds_within_its_time_allowance():
    """backup_speed 0.025 is raised to the 0.10 m/s minimum_speed, as in Nav2: 0.3 m
    takes about 3 s, not 12 s (which the 10 s allowance would refuse)."""
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0), max_linear_accel=2.5)
    step, now, _ = run(back_up(0.3, 0.025, time_allowance=10.0), robot)
    assert step.succeeded
    assert robot.pose.x == pytest.approx(-0.3, abs=0.01)
    assert now < 4.0


class DelayedUnicycle(Unicycle):
    """A base that acts on each command ``delay`` cycles after it was sent."""

    def __init__(
        self,
        pose: Pose2D,
        delay: int,
        max_linear_accel: float = 2.5,
        max_angular_accel: float = 6.0,
    ) -> None:
        super().__init__(
            pose, max_linear_accel=max_linear_accel, max_angular_accel=max_angular_accel
        )
        self.queue: list[Velocity] = [Velocity()] * delay

    def step(self, cmd: Velocity, dt: float) -> Pose2D:
        self.queue.append(cmd)
        return super().step(self.queue.pop(0), dt)


def run_delayed(
    behavior: TimedBehavior, robot: DelayedUnicycle, lead: float
) -> tuple[BehaviorStep, float]:
    """Step until done, then let the base act on the commands still on their way."""
    now = 0.0
    while now < 30.0:
        step = behavior.step(Inputs(now, robot.pose, FRESH, lead=lead))
        robot.step(step.cmd or Velocity(), DT)
        now += DT
        if step.done:
            for _ in range(len(robot.queue) + 10):
                robot.step(Velocity(), DT)
            return step, now
    raise AssertionError("behavior did not finish")


@pytest.mark.parametrize("delay", [0, 4, 10])
def test_spin_stops_on_target_whatever_the_loop_delay(delay):
    """A base acting 0.2 s or 0.5 s late (what 20-50 ms of transport is at 10x):
    with the delay as ``lead`` the spin ends within 0.05 rad."""
    robot = DelayedUnicycle(Pose2D(0.0, 0.0, 0.0), delay, max_angular_accel=6.0)
    step, _ = run_delayed(SpinBehavior(-math.pi), robot, lead=delay * DT)
    assert step.succeeded
    assert abs(wrap_angle(robot.pose.yaw + math.pi)) < 0.05


@pytest.mark.parametrize("delay", [0, 4, 10])
def test_drive_stops_on_target_whatever_the_loop_delay(delay):
    robot = DelayedUnicycle(Pose2D(0.0, 0.0, 0.0), delay, max_linear_accel=2.5)
    step, _ = run_delayed(DriveOnHeading(0.4, 0.3), robot, lead=delay * DT)
    assert step.succeeded
    assert robot.pose.x == pytest.approx(0.4, abs=0.02)


@pytest.mark.parametrize("stall_from", [0.3, 0.15, 0.05])
def test_a_stalled_loop_near_the_target_overshoots_by_at_most_the_approach_error(stall_from):
    """At 10x (lead 0.2 s) the loop stalls 0.5 s of sim time (the robot's command timeout)
    once the spin is ``stall_from`` rad from its target; the base keeps the last command."""
    robot = DelayedUnicycle(Pose2D(0.0, 0.0, 0.0), 4, max_angular_accel=6.0)
    spin = SpinBehavior(1.0)
    now, last, stalled = 0.0, Velocity(), False
    while now < 30.0:
        if not stalled and robot.pose.yaw > 1.0 - stall_from:
            stalled = True
            for _ in range(10):
                robot.step(last, DT)
                now += DT
        step = spin.step(Inputs(now, robot.pose, FRESH, lead=4 * DT))
        last = step.cmd or Velocity()
        robot.step(last, DT)
        now += DT
        if step.done:
            break
    for _ in range(10):
        robot.step(Velocity(), DT)
    assert robot.pose.yaw - 1.0 <= spin.params.approach_error + 0.01


def run_with_a_stall(
    behavior: TimedBehavior, robot: DelayedUnicycle, stall_from: Callable[[Pose2D], bool]
) -> tuple[BehaviorStep, list[Velocity]]:
    """Step (lead: the base's 4-cycle delay) until done; once ``stall_from(pose)``,
    the loop stalls 1 s (20 cycles) while the base keeps the last command."""
    now, last, stalled, commands = 0.0, Velocity(), False, []
    while now < 30.0:
        if not stalled and stall_from(robot.pose):
            stalled = True
            for _ in range(20):
                robot.step(last, DT)
                now += DT
        step = behavior.step(Inputs(now, robot.pose, FRESH, lead=4 * DT))
        last = step.cmd or Velocity()
        commands.append(last)
        robot.step(last, DT)
        now += DT
        if step.done:
            return step, commands
    raise AssertionError("behavior did not finish")


def test_after_a_long_stall_the_spin_turns_back_to_its_target():
    """A 1 s stall near the end (beyond what the approach allows for) overshoots; once
    the base stands still the spin sees it and turns back within its settle tolerance."""
    robot = DelayedUnicycle(Pose2D(0.0, 0.0, 0.0), 4, max_angular_accel=6.0)
    spin = SpinBehavior(1.0)
    step, commands = run_with_a_stall(spin, robot, lambda pose: pose.yaw > 0.7)
    assert step.succeeded
    assert any(c.w < 0.0 for c in commands)  # turned back
    assert abs(robot.pose.yaw - 1.0) <= spin.params.settle_tolerance + 0.01


@pytest.mark.parametrize(("distance", "speed", "stall_at"), [(0.4, 0.3, 0.6), (-0.3, -0.1, 0.9)])
def test_after_a_long_stall_the_drive_goes_back_to_its_distance(distance, speed, stall_at):
    """A 1 s stall near the end (beyond what the approach allows for) carries the base
    past the distance; once it stands still the drive sees it and backs up to within
    its settle tolerance, never reporting success while off."""
    robot = DelayedUnicycle(Pose2D(0.0, 0.0, 0.0), 4, max_linear_accel=2.5)
    drive = DriveOnHeading(distance, speed)
    step, commands = run_with_a_stall(
        drive, robot, lambda pose: abs(pose.x) > stall_at * abs(distance)
    )
    assert step.succeeded
    assert any(c.v * speed < 0.0 for c in commands)  # drove back
    assert abs(robot.pose.x - distance) <= drive.params.settle_tolerance + 0.005


def test_a_drive_stopped_short_drives_on():
    """The base ignores the commands for a while (a stop delayed beyond the lead the
    other way: the stop came early): once still, short of the distance, it drives on."""
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0), max_linear_accel=2.5)
    drive = DriveOnHeading(0.4, 0.3)
    now, moving_again = 0.0, False
    while now < 30.0:
        step = drive.step(Inputs(now, robot.pose, FRESH))
        if abs(robot.pose.x - 0.3) < 0.02 and not moving_again:
            moving_again = True
            robot.pose = Pose2D(0.3, 0.0, 0.0)  # the base held still 10 cm short
            for _ in range(4):
                step = drive.step(Inputs(now, robot.pose, FRESH))
                now += DT
            assert not step.done
        robot.step(step.cmd or Velocity(), DT)
        now += DT
        if step.done:
            break
    assert step.succeeded
    assert robot.pose.x == pytest.approx(0.4, abs=drive.params.settle_tolerance + 0.005)


def test_backup_drives_backwards_whatever_the_signs():
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0))
    step, _, _ = run(back_up(0.3, 0.1), robot)
    assert step.succeeded
    assert robot.pose.x == pytest.approx(-0.3, abs=0.02)
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0))
    run(back_up(-0.3, -0.1), robot)
    assert robot.pose.x == pytest.approx(-0.3, abs=0.02)


def test_backup_into_a_wall_stops_before_contact():
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0))
    step, _, _ = run(back_up(2.0, 0.2, collision=wall_ahead(-1.0)), robot)
    assert step.outcome is Outcome.COLLISION_AHEAD
    assert "collision ahead" in step.message
    assert step.cmd == Velocity(0.0, 0.0)
    assert -0.8 < robot.pose.x < 0.0  # stopped at the 2 s look-ahead, short of the wall


def test_drive_checks_only_the_remaining_distance():
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0))
    step, _, _ = run(DriveOnHeading(0.5, 0.2, collision=wall_ahead(0.8)), robot)
    assert step.succeeded  # the wall is beyond the goal distance


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: DriveOnHeading(0.5, -0.2), "same sign"),
        (lambda: DriveOnHeading(math.nan, 0.2), "distance must be a finite number"),
        (lambda: DriveOnHeading(0.5, 0.0), "speed must not be 0"),
        (lambda: back_up(0.5, math.inf), "speed must be a finite number"),
        (lambda: SpinBehavior(math.nan), "target_yaw"),
        (lambda: SpinBehavior(1.0, time_allowance=-1.0), "time_allowance must be >= 0"),
        (lambda: WaitBehavior(-1.0), "wait duration must be >= 0"),
        (lambda: WaitBehavior(math.nan), "wait duration must be a finite number"),
        (lambda: AssistedTeleop(math.nan), "time_allowance must be a finite number"),
    ],
)
def test_bad_goals_are_invalid_input(make, message):
    with pytest.raises(BehaviorInputError, match=message) as caught:
        make()
    assert caught.value.outcome is Outcome.INVALID_INPUT


def test_stale_odometry_stops_with_tf_error():
    spin = SpinBehavior(1.0)
    assert not spin.step(Inputs(0.0, Pose2D(0, 0, 0), FRESH)).done
    late = PoseAge(robot=0.52, silence=0.05, quiet=0.0)  # behind another stream, not stopped
    assert not spin.step(Inputs(0.1, Pose2D(0, 0, 0), late)).done
    stopped = PoseAge(robot=0.02, silence=0.8, quiet=0.8)
    step = spin.step(Inputs(1.0, Pose2D(0, 0, 0), stopped))
    assert step.outcome is Outcome.TF_ERROR
    assert "frame 'odom' is stale" in step.message
    assert "0.02 s old in robot time" in step.message
    assert "pose_timeout 0.50 s" in step.message
    assert step.cmd == Velocity(0.0, 0.0)
    drive = DriveOnHeading(1.0, 0.1)
    assert not drive.step(Inputs(0.0)).done  # odometry may still be on its way
    assert drive.step(Inputs(1.1)).outcome is Outcome.TF_ERROR


def test_wait_counts_clock_time_and_never_commands():
    wait = WaitBehavior(1.0)
    first = wait.step(Inputs(5.0))
    assert first.feedback == pytest.approx(1.0)
    assert not first.done
    assert first.cmd is None
    assert not wait.step(Inputs(5.95)).done
    assert wait.step(Inputs(6.0)).succeeded
    assert WaitBehavior(0.0).step(Inputs(0.0)).succeeded


def test_assisted_teleop_passes_free_twists_and_scales_before_obstacles():
    teleop = AssistedTeleop(time_allowance=0.0, collision=wall_ahead(1.0))
    pose = Pose2D(0.0, 0.0, 0.0)
    free = teleop.filtered(pose, Velocity(0.2, 0.0))  # 0.4 m in 2 s: clear
    assert free == Velocity(0.2, 0.0)
    fast = teleop.filtered(pose, Velocity(1.0, 0.0))  # would reach the wall at ~1 s
    assert 0.0 < fast.v < 0.5
    away = teleop.filtered(pose, Velocity(-1.0, 0.0))
    assert away == Velocity(-1.0, 0.0)


def test_assisted_teleop_never_hits_the_wall_and_ends_on_time_allowance():
    robot = Unicycle(Pose2D(0.0, 0.0, 0.0))
    behavior = AssistedTeleop(time_allowance=8.0, collision=wall_ahead(1.0))
    step, _, commands = run(behavior, robot, teleop=Velocity(0.5, 0.0))
    assert step.outcome is Outcome.TIMEOUT
    assert robot.pose.x < 1.0
    assert commands[0].v > 0.4
    assert commands[-2].v == pytest.approx(0.0, abs=1e-9)


def test_assisted_teleop_zeroes_stale_input_and_finishes_on_request():
    behavior = AssistedTeleop(time_allowance=0.0)
    pose = Pose2D(0.0, 0.0, 0.0)
    live = behavior.step(Inputs(0.0, pose, FRESH, Velocity(0.3, 0.1), 0.0))
    assert live.cmd == Velocity(0.3, 0.1)
    stale = behavior.step(Inputs(1.0, pose, FRESH, Velocity(0.3, 0.1), 0.0))
    assert stale.cmd == Velocity(0.0, 0.0)
    assert not stale.done
    behavior.finish()
    assert behavior.step(Inputs(1.1, pose, FRESH)).succeeded
