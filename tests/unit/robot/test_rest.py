"""Steps left out of the physics while nothing can move: the simulation with them left
out runs exactly as the one that steps pybullet every time (poses, odometry and its
noise, contacts, battery, scans), and does leave them out while the robot stands."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from aiobt.geometry import Pose2D
from aiobt_services.robot.bumper import ContactEvent
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.obstacles import Motion, ObstacleSpec
from aiobt_services.robot.sensors import LidarConfig, NoiseConfig
from aiobt_services.robot.sim import SimConfig, Simulation
from aiobt_services.robot.worlds import SMALL

NOISY = SimConfig(
    noise=NoiseConfig(odom_linear=0.05, odom_angular=0.05, slip=0.02, seed=5),
    lidar=LidarConfig(noise=0.01, dropout=0.05),
)
Step = tuple[Pose2D, Pose2D, float, list[ContactEvent], list[str]]


def run(sim: Simulation, script: list[tuple[int, Callable[[Simulation], object]]]) -> list[Step]:
    """Each (steps, action): the action once, then that many steps; what each step left."""
    seen: list[Step] = []
    for steps, action in script:
        action(sim)
        for _ in range(steps):
            events = sim.step()
            state = (sim.true_pose, sim.odometry.pose, sim.battery.energy_wh, events)
            seen.append((*state, sim.in_contact))
    return seen


def drive(linear: float, angular: float) -> Callable[[Simulation], object]:
    return lambda sim: sim.command(linear, angular)


def idle(_sim: Simulation) -> None:
    return None


SCRIPT: list[tuple[int, Callable[[Simulation], object]]] = [
    (80, idle),  # standing from the start
    *[(5, drive(0.5, 0.3))] * 20,  # a curve, the commands every 5 steps
    (120, idle),  # the command times out: stop, then stand
    (60, lambda s: s.spawn(ObstacleSpec("box", "box", Pose2D(1.6, 0.9, 0.2), size_x=0.4))),
    (60, lambda s: s.move("box", Pose2D(1.6, 1.3, 0.0))),
    (
        60,
        lambda s: s.spawn(
            ObstacleSpec("walker", "cylinder", Pose2D(-1.0, -1.5), motion=Motion(-1.0, 1.5, 0.5))
        ),
    ),
    (40, lambda s: s.remove("walker")),
    (40, lambda s: s.teleport(Pose2D(0.5, -0.5, 1.0))),
    *[(5, drive(0.8, 0.0))] * 60,  # into the box ahead and pushing it
    (150, idle),  # stopped against the box: touching, never left out
    *[(5, drive(-0.5, 0.0))] * 10,  # off the box
    (100, idle),
    (40, lambda s: s.teleport(Pose2D(-1.5, 0.0, 0.0))),
    (  # a cylinder walking through where the robot stands: it is pushed, the bumper fires
        300,
        lambda s: s.spawn(
            ObstacleSpec("runner", "cylinder", Pose2D(-1.5, -1.2), motion=Motion(-1.5, 1.5, 0.4))
        ),
    ),
]


def test_leaving_steps_out_changes_nothing_the_simulation_says() -> None:
    with Simulation(load_map(SMALL), NOISY, rest=False) as always:
        stepped = run(always, SCRIPT)
        scan_always = always.scan().ranges
    with Simulation(load_map(SMALL), NOISY) as resting:
        left_out = run(resting, SCRIPT)
        scan_resting = resting.scan().ranges
    assert len(stepped) == len(left_out) > 1000
    for i, (a, b) in enumerate(zip(stepped, left_out, strict=True)):
        assert a == b, f"step {i}"
    assert any(step[4] == ["box"] for step in stepped)  # the script did push the box
    assert any(e.other == "runner" for step in stepped for e in step[3])  # and meet the runner
    assert np.array_equal(scan_always, scan_resting)


def test_the_physics_is_left_out_only_while_the_robot_stands_clear(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    with Simulation(load_map(SMALL)) as sim:
        pushed: list[float] = []
        real = sim._push

        def counted(body_speed: float, angular: float, yaw: float) -> None:
            pushed.append(sim.time)
            real(body_speed, angular, yaw)

        monkeypatch.setattr(sim, "_push", counted)
        sim.step(100)
        assert len(pushed) == 1  # one step to settle, then none
        sim.command(0.3, 0.0)
        sim.step(20)
        assert len(pushed) == 21
        sim.spawn(ObstacleSpec("box", "box", Pose2D(1.5, 1.5, 0.0)))
        sim.step(200)  # stops after the command's timeout, settles, then stands
        standing = len(pushed)
        assert standing < 21 + 100
        sim.step(50)
        assert len(pushed) == standing
        sim.move("box", Pose2D(1.5, 1.2, 0.0))
        sim.step(5)
        assert len(pushed) == standing + 1
