"""The dock detector's lifecycle (Nav2's SimpleChargingDock tests ObjectLifecycle,
DetectorLifecycle, DetectorServiceFailure, SubscriptionCallback, SubscriptionPersistent):
started before the dock is looked for, stopped when the docking ends; and DockRobot on
the simulation with the robot's detector switched on only while it docks."""

from __future__ import annotations

import numpy as np
import pytest

from aiobt.geometry.pose_filter import StampedPose3D
from aiobt.msgs.remote_actions import DockRobotError
from aiobt.system.plugin_params import params_from
from aiobt_services.docking.frames import RobotFrames
from aiobt_services.docking.plugins import DockWiring
from aiobt_services.docking.simple_charging_dock import SimpleChargingDock, SimpleChargingDockParams
from aiobt_services.robot.dock_detector import DockDetectorSwitch

from .simbase import (
    HOME,
    STAGED,
    Feedback,
    SimBase,
    docked_error,
    docking_server,
    no_navigation,
    office_sim,
)


class FakeClock:
    def __init__(self) -> None:
        self.t = 10.0

    def now(self) -> float:
        return self.t

    async def sleep(self, seconds: float) -> None:
        self.t += seconds


class Wires:
    """A detector topic and a Trigger service, as the docking server's bus gives them."""

    def __init__(self, answer: str | None = None) -> None:
        self.published: StampedPose3D | None = None  # the newest on the topic
        self.subscribed = False
        self.subscriptions = 0
        self.calls: list[tuple[str, float]] = []
        self.answer = answer  # the service's failure, None: success

    def detection(self) -> StampedPose3D | None:
        return self.published if self.subscribed else None

    def subscribe(self, on: bool) -> None:
        self.subscribed = on
        self.subscriptions += on

    async def trigger(self, name: str, timeout: float) -> str | None:  # noqa: ASYNC109
        self.calls.append((name, timeout))
        return self.answer

    def publish(self, stamp: float) -> None:
        self.published = StampedPose3D(1.0, 0.0, 0.0, np.array([0.0, 0.0, 0.0, 1.0]), stamp,
                                       "base_link")  # fmt: skip


def dock(wires: Wires, clock: FakeClock, **given: str) -> SimpleChargingDock:
    frames = RobotFrames(lambda: None, lambda: iter(()))
    wiring = DockWiring(frames, clock, wires.detection, lambda: None, lambda *_: None,
                        wires.subscribe, wires.trigger)  # fmt: skip
    params = params_from(SimpleChargingDockParams, "my_dock",
                         {"use_external_detection_pose": "true"} | given)  # fmt: skip
    return SimpleChargingDock("my_dock", params, wiring)


async def test_without_a_service_start_and_stop_succeed() -> None:
    wires = Wires()
    plugin = dock(wires, FakeClock())
    assert await plugin.start_detection()
    assert await plugin.stop_detection()
    assert wires.calls == []
    assert not plugin.is_charging()
    assert plugin.has_stopped_charging()
    assert plugin.is_charger


async def test_the_service_is_called_on_start_and_on_stop_once_each() -> None:
    wires = Wires()
    plugin = dock(wires, FakeClock(), detector_service_name="test_detector_service",
                  detector_service_timeout="1.5", subscribe_toggle="true")  # fmt: skip
    assert not wires.subscribed
    assert await plugin.start_detection()
    assert await plugin.start_detection()  # already active: no second call
    assert wires.calls == [("test_detector_service", 1.5)]
    assert wires.subscribed
    assert await plugin.stop_detection()
    assert await plugin.stop_detection()
    assert wires.calls == [("test_detector_service", 1.5)] * 2
    assert not wires.subscribed


async def test_a_failed_or_unanswered_service_fails_the_start(
    caplog: pytest.LogCaptureFixture,
) -> None:
    wires = Wires(answer="robot/srv/slow_service: no reply within 0.1 s")
    plugin = dock(wires, FakeClock(), detector_service_name="slow_service",
                  detector_service_timeout="0.1", subscribe_toggle="true")  # fmt: skip
    assert not await plugin.start_detection()
    assert "Detector service 'slow_service' failed to start: robot/srv/slow_service" in caplog.text
    assert not wires.subscribed


async def test_with_subscribe_toggle_only_detections_while_started_count() -> None:
    wires, clock = Wires(), FakeClock()
    plugin = dock(wires, clock, subscribe_toggle="true")
    wires.publish(clock.t)
    assert plugin.detector.latest() is None  # not subscribed yet
    assert await plugin.start_detection()
    assert wires.subscriptions == 1
    assert plugin.detector.latest() is not None


async def test_without_it_the_subscription_lasts_but_a_stop_forgets_the_last() -> None:
    wires, clock = Wires(), FakeClock()
    plugin = dock(wires, clock)
    assert wires.subscribed  # from the start
    wires.publish(clock.t)
    assert plugin.detector.latest() is not None
    await plugin.start_detection()
    await plugin.stop_detection()
    assert wires.subscribed
    assert plugin.detector.latest() is None  # received before the stop
    wires.publish(clock.t + 0.1)
    assert plugin.detector.latest() is not None


def test_a_bad_service_timeout_is_named() -> None:
    with pytest.raises(ValueError, match="detector_service_timeout must be > 0"):
        SimpleChargingDockParams(detector_service_timeout=0.0)


ON_DEMAND = {"detector_service_name": "dock_detector/toggle", "subscribe_toggle": "true"}


@pytest.mark.timeout(60)
async def test_the_robots_detector_runs_only_while_docking() -> None:
    with office_sim() as sim:
        base = SimBase(sim)
        server = docking_server(base, no_navigation, dock_params=ON_DEMAND)
        base.place(STAGED)
        assert base.detector.on  # on from the start, for a server that never calls
        result = await server.dock_robot(HOME, Feedback())
        assert result.success, result.error_msg
        assert docked_error(sim)[0] <= 0.02
        assert base.calls == ["dock_detector/toggle"] * 2  # started, then stopped
        assert not base.detector.on
        base.detected = None
        base.step(50)  # the marker is in view, docked: the stopped detector is silent
        assert base.detected is None


@pytest.mark.timeout(60)
async def test_a_detector_service_that_is_not_there_fails_the_docking() -> None:
    with office_sim() as sim:
        base = SimBase(sim)
        given = ON_DEMAND | {"detector_service_name": "camera/start"}
        server = docking_server(base, no_navigation, dock_params=given)
        base.place(STAGED)
        result = await server.dock_robot(HOME, Feedback())
        assert not result.success
        assert result.error_code == DockRobotError.FAILED_TO_DETECT_DOCK
        assert result.error_msg == "Failed to start the detection process."


def test_the_robots_switch_first_call_starts_then_each_flips() -> None:
    switch = DockDetectorSwitch()
    assert switch.on
    replies = [switch.toggle(None).message for _ in range(3)]  # type: ignore[arg-type]
    assert replies == ["dock detector on", "dock detector off", "dock detector on"]
