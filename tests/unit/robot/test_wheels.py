"""The wheels on ``joint_states``: turning as the body rolls, little effort while free;
stopped with their motors pushing against the dock (what Nav2's stall detection reads,
with its default thresholds of 1 rad/s and 1 N m)."""

from __future__ import annotations

import pytest

from aiobt.geometry import Pose2D
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.sim import SimConfig, Simulation
from aiobt_services.robot.wheels import WheelJoints, WheelMotors
from aiobt_services.robot.worlds import WORLDS_DIR


def test_the_wheels_turn_with_the_body_and_push_when_it_cannot() -> None:
    wheels = WheelJoints()
    wheels.update((0.2, 0.0), (0.2, 0.0), 0.01)
    free = wheels.state(1.0)
    assert free.velocity == pytest.approx([4.0, 4.0])  # 0.2 m/s on 5 cm wheels
    assert free.effort == pytest.approx([0.2, 0.2])  # rolling friction only
    wheels.update((0.2, 0.0), (0.0, 0.0), 0.01)
    stalled = wheels.state(1.01)
    assert stalled.velocity == [0.0, 0.0]
    assert stalled.effort == pytest.approx([4.0, 4.0])
    assert stalled.position == pytest.approx([0.04, 0.04])  # 4 rad/s for 10 ms
    turning = WheelMotors().rates(0.0, 1.0)
    assert turning[0] == pytest.approx(-turning[1])
    assert WheelMotors().effort(100.0, 0.0) == 5.0  # the stall torque at most


def test_on_the_simulation_driving_free_then_pressed_on_the_dock() -> None:
    with Simulation(load_map(WORLDS_DIR / "office.yaml"), SimConfig()) as sim:
        station = sim.dock_station
        assert station is not None
        sim.teleport(station.pose.compose(Pose2D(-0.5, 0.0, 0.0)))
        states = []
        for _ in range(600):  # 0.15 m/s for 6 s: 0.9 m against the 0.5 m to the contacts
            sim.command(0.15, 0.0)
            sim.step()
            states.append(sim.wheels.state(sim.time))
        rolling = states[150]  # 1.5 s in: ramped up, 0.2 m on
        assert min(rolling.velocity) > 1.0
        assert max(rolling.effort) < 1.0
        pressed = states[-1]
        assert "dock" in sim.in_contact
        assert max(abs(v) for v in pressed.velocity) < 1.0
        assert min(pressed.effort) > 1.0
