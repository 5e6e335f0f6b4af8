"""The simulated dock: charging only on the contacts, the camera's detection of its
marker (in view, facing, not hidden; noisy, never the truth), the block the robot meets."""

from __future__ import annotations

import argparse
import math

import numpy as np
import pytest

from aiobt.geometry import Pose2D
from aiobt.msgs import Trigger
from aiobt_services.robot.dock import DockStation
from aiobt_services.robot.mapfile import Dock, load_map
from aiobt_services.robot.runner import DOCK_DETECTION, SimRunner
from aiobt_services.robot.sim import SimConfig, Simulation
from aiobt_services.robot.worlds import WORLDS_DIR

STATION = DockStation(Dock(1.0, 2.0, math.pi), robot_radius=0.22)  # the robot docks facing -x


def docked_offset(dx: float, dy: float, dyaw: float) -> Pose2D:
    """A robot pose ``dx`` along the dock's axis (towards the dock), ``dy`` across."""
    return STATION.pose.compose(Pose2D(dx, dy, dyaw))


@pytest.mark.parametrize(
    ("dx", "dy", "dyaw", "charges"),
    [
        (0.0, 0.0, 0.0, True),
        (-0.009, 0.011, 0.03, True),
        (-0.02, 0.0, 0.0, False),  # short of the contacts
        (0.0, 0.02, 0.0, False),  # beside them
        (0.0, 0.0, 0.08, False),  # askew
    ],
)
def test_charging_only_on_the_contacts(dx: float, dy: float, dyaw: float, charges: bool) -> None:
    assert STATION.charging_contact(docked_offset(dx, dy, dyaw)) is charges


def test_the_marker_is_on_the_face_a_robot_radius_ahead() -> None:
    marker = STATION.marker
    assert (marker.x, marker.y, abs(marker.yaw)) == pytest.approx((0.78, 2.0, math.pi))
    centre, half = STATION.block()
    assert centre.x - half[0] == pytest.approx(0.66)
    assert half[2] * 2 < 0.2  # under the lidar's plane


def test_visible_only_in_view_facing_and_unhidden() -> None:
    staging = docked_offset(-1.0, 0.0, 0.0)  # 1 m out, facing the dock
    assert STATION.visible(staging, math.inf)
    assert not STATION.visible(staging, 0.5)  # something stands between
    assert not STATION.visible(Pose2D(staging.x, staging.y, 0.0), math.inf)  # facing away
    assert not STATION.visible(docked_offset(-3.5, 0.0, 0.0), math.inf)  # too far
    behind = Pose2D(0.5, 2.0, 0.0)  # behind the dock, looking at the marker's back
    assert not STATION.visible(behind, math.inf)


def test_detection_is_noisy_around_the_truth() -> None:
    rng = np.random.default_rng(1)
    robot = docked_offset(-1.0, 0.1, 0.1)
    truth = robot.inverse().compose(STATION.marker)
    seen = [STATION.detect(robot, rng) for _ in range(400)]
    xs = np.array([s.x for s in seen])
    assert xs.mean() == pytest.approx(truth.x, abs=0.002)
    assert 0.003 < xs.std() < 0.02  # never the truth itself
    assert np.mean([s.yaw for s in seen]) == pytest.approx(truth.yaw, abs=0.005)


def test_the_block_stops_the_robot_on_the_contacts() -> None:
    world = load_map(WORLDS_DIR / "office.yaml")
    with Simulation(world, SimConfig()) as sim:
        station = sim.dock_station
        assert station is not None
        sim.teleport(station.pose.compose(Pose2D(-0.5, 0.0, 0.0)))
        for _ in range(600):  # 6 s at 0.15 m/s: 0.9 m, more than the 0.5 m to go
            sim.command(0.15, 0.0)
            sim.step()
        assert abs(station.offset(sim.true_pose).x) < 0.01
        assert "dock" in sim.in_contact
        assert sim.battery.charging  # the drive drew a little: it charges
        assert sim.detect_dock() is not None


def test_the_runner_publishes_detections_only_while_the_detector_is_on() -> None:
    """``srv/dock_detector/toggle``: on from the start, the first call keeps it on, the
    next turns it off (the docking server's start, then its stop)."""
    world = load_map(WORLDS_DIR / "office.yaml")
    published: list[str] = []
    sink = argparse.Namespace(publish=lambda topic, _msg: published.append(topic))
    with Simulation(world, SimConfig()) as sim:
        station = sim.dock_station
        assert station is not None
        sim.teleport(station.pose.compose(Pose2D(-0.8, 0.0, 0.0)))  # the marker in view
        runner = SimRunner(sim, sink)

        def detections() -> int:
            published.clear()
            for _ in range(30):
                runner.tick()
            return published.count(DOCK_DETECTION)

        assert detections() > 0
        assert runner.dock_detector.toggle(Trigger.Request()).message == "dock detector on"
        assert detections() > 0
        assert runner.dock_detector.toggle(Trigger.Request()).message == "dock detector off"
        assert detections() == 0
        assert runner.dock_detector.toggle(Trigger.Request()).success
        assert detections() > 0
