"""RPP's turn onto the goal's heading under a command delay (a sim speed-up, a loaded
machine): reckoning the turn still in flight over the loop's ``lead`` stops the base on
the heading where ignoring it overshoots."""

from __future__ import annotations

import math
from collections import deque

import pytest

from aiobt.geometry import Pose2D, Velocity, turn_rate, wrap_angle
from aiobt_services.controller.base import ControlContext
from aiobt_services.controller.rpp import RegulatedPurePursuit
from aiobt_services.controller.unicycle import Unicycle

from .courses import straight

DT = 0.05  # the controller's 20 Hz
DELAY_CYCLES = 5  # 0.25 s of robot time from command to base: 60 ms of wall time at x4
TOLERANCE = 0.25  # rad: the general goal checker's yaw_goal_tolerance


def _turn_onto_goal(lead: float) -> float:
    """The heading error once the base is still: RPP turns a robot standing on the goal
    of a path east from heading -pi/2, its commands reaching the base DELAY_CYCLES
    late; at the goal checker's tolerance the controller sends zero (the goal
    succeeded), and the base decelerates at its limit from what is still in flight."""
    path = straight(2.0)
    rpp = RegulatedPurePursuit()
    rpp.set_plan(path)
    robot = Unicycle(Pose2D(2.0, 0.0, -math.pi / 2), max_angular_accel=3.2)
    in_flight: deque[Velocity] = deque([Velocity(0.0, 0.0)] * DELAY_CYCLES)
    ctx = ControlContext(DT, 0.25, None, lead=lead)
    succeeded = False
    for _ in range(400):
        error = wrap_angle(path.goal.yaw - robot.pose.yaw)
        succeeded = succeeded or abs(error) <= TOLERANCE
        cmd = (
            Velocity(0.0, 0.0)
            if succeeded
            else rpp.compute_velocity(robot.pose, robot.velocity, ctx)
        )
        in_flight.append(cmd)
        robot.step(in_flight.popleft(), DT)
        if succeeded and robot.velocity.w == 0.0 and all(c.w == 0.0 for c in in_flight):
            break
    assert succeeded
    return abs(wrap_angle(path.goal.yaw - robot.pose.yaw))


def test_the_turn_in_flight_is_reckoned_and_the_base_stops_on_the_heading():
    assert _turn_onto_goal(lead=DELAY_CYCLES * DT) <= 0.1


def test_without_the_lead_the_same_delay_overshoots_past_the_tolerance():
    # the failure the lead prevents (an e2e run at x4 under load: 0.38 rad past the goal)
    assert _turn_onto_goal(lead=0.0) > 0.3


def test_turn_rate_subtracts_only_a_turn_towards_the_heading():
    # turning towards the heading: 1.0 rad/s for 0.2 s leaves 0.3 of 0.5 rad to come
    assert turn_rate(0.5, 2.0, 2.0, previous=1.0, dt=1.0, lead=0.2) == pytest.approx(
        math.sqrt(2.0 * 2.0 * 0.3)
    )
    # all of it in flight already: brake as hard as allowed
    assert turn_rate(0.1, 2.0, 2.0, previous=1.0, dt=0.1, lead=0.2) == pytest.approx(0.8)
    # turning away: nothing in flight counts towards it
    assert turn_rate(0.5, 2.0, 2.0, previous=-0.2, dt=1.0, lead=0.2) == pytest.approx(
        math.sqrt(2.0 * 2.0 * 0.5)
    )
    # no lead: as before
    assert turn_rate(0.5, 2.0, 2.0, previous=1.0, dt=1.0) == pytest.approx(math.sqrt(2.0))
