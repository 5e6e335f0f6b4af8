"""``aiobt foxglove`` beside a hardware-like robot (no pose in map) and the localization
service on a real router: a Foxglove client sets the initial pose (the 3D panel's pose
estimate, ROS's PoseWithCovarianceStamped on ``/initialpose``) and gets the particle
cloud, the estimate (``/pose``, ``/amcl_pose``) and the simulation's truth
(``/sim/pose``), in ``map``."""

from __future__ import annotations

import asyncio
import contextlib
import math
import statistics
from typing import Any

import pytest

from aiobt.transport import Bus, BusSettings
from tests.integration.localization.stack import START, Spawn, start_stack

from .test_bridge_live import client, serving_bridge
from .wsclient import FoxgloveClient

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(180)]
TOPICS = {"/particle_cloud", "/amcl_pose", "/sim/pose", "/pose"}
ESTIMATE_CHANNEL = 9
# what the 3D panel's pose estimate tool sends: 0.5 m, 0.5 m, pi/12 rad deviations
POSE_ESTIMATE = {
    "header": {"stamp": {"sec": 0, "nsec": 0}, "frame_id": "map"},
    "pose": {
        "pose": {"position": {"x": START[0], "y": START[1], "z": 0.0},
                 "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}},
        "covariance": [{0: 0.25, 7: 0.25, 35: (math.pi / 12) ** 2}.get(i, 0.0) for i in range(36)],
    },
}  # fmt: skip


async def _received(fox: FoxgloveClient, latest: dict[str, Any], wanted: set[str],
                    within: float) -> bool:  # fmt: skip
    """Receive into ``latest`` (topic -> newest message) until every ``wanted`` topic came
    (True) or ``within`` s passed (False; a cancelled receive loses nothing)."""
    with contextlib.suppress(TimeoutError):
        async with asyncio.timeout(within):
            while not latest.keys() >= wanted:
                got = await fox.receive()
                latest[got.topic] = got.message
    return latest.keys() >= wanted


async def _until(fox: FoxgloveClient, latest: dict[str, Any], wanted: set[str], within: float
                 ) -> None:  # fmt: skip
    if not await _received(fox, latest, wanted, within):
        pytest.fail(f"no {sorted(wanted - latest.keys())} within {within} s: got {sorted(latest)}")


async def _set_initial_pose(fox: FoxgloveClient, latest: dict[str, Any]) -> None:
    """The client's pose estimate, again every 2 s until the localization's amcl_pose
    comes back through the bridge (the bridge's publisher may not be routed at once)."""
    await fox.advertise(ESTIMATE_CHANNEL, "/initialpose", "geometry_msgs/PoseWithCovarianceStamped")
    for _ in range(30):
        await fox.publish(ESTIMATE_CHANNEL, POSE_ESTIMATE)
        if await _received(fox, latest, {"/amcl_pose"}, 2.0):
            return
    pytest.fail(f"no amcl_pose within 60 s of the client's pose estimate: got {sorted(latest)}")


def _xy(pose: Any) -> tuple[float, float]:
    return pose.position.x, pose.position.y


async def test_client_receives_the_particle_cloud_and_the_truth_beside_the_estimate(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    await start_stack(spawn, bus, bus_settings, speed=2)
    bridge, port = await serving_bridge(spawn, bus_settings)
    assert await bus.presence(bus.keys.topic("nodes/foxglove")).wait(60.0), bridge.output()
    latest: dict[str, Any] = {}
    async with client(port) as fox:
        await fox.wait_advertised(TOPICS, 20.0)
        assert fox.channels["/particle_cloud"]["schemaName"] == "foxglove.PosesInFrame"
        assert fox.channels["/sim/pose"]["schemaName"] == "foxglove.PoseInFrame"
        assert fox.channels["/amcl_pose"]["schemaName"] == "foxglove.PoseInFrame"
        await fox.subscribe(*TOPICS)
        await _until(fox, latest, {"/sim/pose"}, 30.0)  # the truth, before any estimate
        assert latest.keys() == {"/sim/pose"}, "an estimate before the initial pose"
        await _set_initial_pose(fox, latest)
        await _until(fox, latest, TOPICS, 60.0)
    truth, cloud = latest["/sim/pose"], latest["/particle_cloud"]
    assert truth.frame_id == cloud.frame_id == latest["/pose"].frame_id == "map"
    assert math.dist(_xy(truth.pose), START[:2]) < 0.05
    assert 10 <= len(cloud.poses) <= 250  # thinned by the service for viewers
    spread = statistics.median(math.dist(_xy(p), START[:2]) for p in cloud.poses)
    assert spread < 1.0  # around the initial pose
    for estimate in (latest["/pose"], latest["/amcl_pose"]):
        assert math.dist(_xy(estimate.pose), _xy(truth.pose)) < 0.5
    assert bridge.running, bridge.output()
