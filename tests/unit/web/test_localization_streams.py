"""The localization as the page gets it (Sources): the particle cloud, amcl_pose with its
covariance, and the simulation's truth beside the estimate."""

from __future__ import annotations

import asyncio
import json
import logging

import pytest

from aiobt.msgs import Header, ParticleCloud, PoseStamped, PoseWithCovarianceStamped
from aiobt.msgs.geometry import Pose
from aiobt.msgs.localization import Particle
from aiobt.transport import Bus
from aiobt.transport.keys import SIM_POSE
from aiobt.web.coalesce import Hub
from aiobt.web.sources import Sources

WAIT = 10.0  # s for a message put on the in-process bus to reach the view


def _cloud(frame: str = "map") -> ParticleCloud:
    return ParticleCloud(
        header=Header(frame_id=frame),
        particles=[
            Particle(pose=Pose.from_xy_yaw(1.0, 2.00049, 0.5), weight=0.75),
            Particle(pose=Pose.from_xy_yaw(-3.0, 4.0, -1.25), weight=0.25),
        ],
    )


def _estimate(frame: str = "map") -> PoseWithCovarianceStamped:
    cov = [0.0] * 36
    cov[0], cov[1], cov[6], cov[7], cov[35] = 0.04, 0.01, 0.01, 0.09, 0.0025
    return PoseWithCovarianceStamped.from_xy_yaw(2.0, 3.0, 0.25, cov, frame_id=frame, stamp=7.5)


async def test_particles_truth_and_estimate_each_go_to_their_own_stream(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    sources.raw.set("pose", PoseStamped.from_xy_yaw(1.0, 1.0, 0.0))
    sources.raw.set(SIM_POSE, PoseStamped.from_xy_yaw(1.02, 0.99, 0.01))
    sources.raw.set("particle_cloud", _cloud())
    sources.raw.set("amcl_pose", _estimate())
    sources.flush()
    assert json.loads(hub.latest["particles"]) == [[1.0, 2.0, 0.5], [-3.0, 4.0, -1.25]]
    assert json.loads(hub.latest["truth"])["x"] == 1.02  # the truth is not the estimate
    assert json.loads(hub.latest["pose"])["x"] == 1.0
    estimate = json.loads(hub.latest["amcl_pose"])
    assert (estimate["x"], estimate["y"], estimate["yaw"], estimate["stamp"]) == (2, 3, 0.25, 7.5)
    assert estimate["covariance"] == [0.04, 0.01, 0.09, 0.0025]  # xx, xy, yy, yaw-yaw
    sources.close()


async def test_a_cloud_or_estimate_outside_the_map_frame_is_not_drawn_and_said_once(
    local_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    with caplog.at_level(logging.WARNING, logger="aiobt.web.sources"):
        for _ in range(3):
            sources.raw.set("particle_cloud", _cloud("odom"))
            sources.raw.set("amcl_pose", _estimate("odom"))
            sources.flush()
    assert "particles" not in hub.latest
    assert "amcl_pose" not in hub.latest
    assert caplog.text.count("particle_cloud in frame 'odom' not shown") == 1
    assert caplog.text.count("amcl_pose in frame 'odom' not shown") == 1
    sources.close()


async def test_the_view_subscribes_to_the_cloud_the_estimate_and_the_truth(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    sources.attach()
    truth = local_bus.publisher(SIM_POSE, PoseStamped)
    cloud = local_bus.publisher("particle_cloud", ParticleCloud)
    estimate = local_bus.latched_publisher("amcl_pose", PoseWithCovarianceStamped)
    estimate.put(_estimate())
    async with asyncio.timeout(WAIT):
        while not {"truth", "particles", "amcl_pose"} <= hub.latest.keys():
            truth.put(PoseStamped.from_xy_yaw(5.0, 6.0, 0.0))
            cloud.put(_cloud())
            await asyncio.sleep(0.05)  # the bus's threads deliver meanwhile
            sources.flush()
    assert json.loads(hub.latest["truth"])["y"] == 6.0
    assert len(json.loads(hub.latest["particles"])) == 2
    sources.close()
