"""The localization as the page gets it (Sources): the particle cloud, amcl_pose with its
covariance, and the simulation's truth beside the estimate (in another frame than map:
test_local_streams.py)."""

from __future__ import annotations

import asyncio
import json

from aiobt.msgs import Header, ParticleCloud, PoseStamped, PoseWithCovarianceStamped
from aiobt.msgs.geometry import Pose
from aiobt.msgs.localization import Particle
from aiobt.transport import Bus
from aiobt.transport.keys import SIM_POSE
from aiobt.web.coalesce import Hub
from aiobt.web.sources import Sources

WAIT = 10.0  # s for a message put on the in-process bus to reach the view


def cloud(frame: str = "map") -> ParticleCloud:
    return ParticleCloud(
        header=Header(frame_id=frame),
        particles=[
            Particle(pose=Pose.from_xy_yaw(1.0, 2.00049, 0.5), weight=0.75),
            Particle(pose=Pose.from_xy_yaw(-3.0, 4.0, -1.25), weight=0.25),
        ],
    )


def estimate(frame: str = "map") -> PoseWithCovarianceStamped:
    cov = [0.0] * 36
    cov[0], cov[1], cov[6], cov[7], cov[35] = 0.04, 0.01, 0.01, 0.09, 0.0025
    return PoseWithCovarianceStamped.from_xy_yaw(2.0, 3.0, 0.25, cov, frame_id=frame, stamp=7.5)


async def test_particles_truth_and_estimate_each_go_to_their_own_stream(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    sources.raw.set("pose", PoseStamped.from_xy_yaw(1.0, 1.0, 0.0))
    sources.raw.set(SIM_POSE, PoseStamped.from_xy_yaw(1.02, 0.99, 0.01))
    sources.raw.set("particle_cloud", cloud())
    sources.raw.set("amcl_pose", estimate())
    sources.flush()
    assert json.loads(hub.latest["particles"]) == [[1.0, 2.0, 0.5], [-3.0, 4.0, -1.25]]
    assert json.loads(hub.latest["truth"])["x"] == 1.02  # the truth is not the estimate
    assert json.loads(hub.latest["pose"])["x"] == 1.0
    shown = json.loads(hub.latest["amcl_pose"])
    assert (shown["x"], shown["y"], shown["yaw"], shown["stamp"]) == (2, 3, 0.25, 7.5)
    assert shown["covariance"] == [0.04, 0.01, 0.09, 0.0025]  # xx, xy, yy, yaw-yaw
    sources.close()


async def test_the_view_subscribes_to_the_cloud_the_estimate_and_the_truth(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    sources.attach()
    truth = local_bus.publisher(SIM_POSE, PoseStamped)
    clouds = local_bus.publisher("particle_cloud", ParticleCloud)
    estimates = local_bus.latched_publisher("amcl_pose", PoseWithCovarianceStamped)
    estimates.put(estimate())
    async with asyncio.timeout(WAIT):
        while not {"truth", "particles", "amcl_pose"} <= hub.latest.keys():
            truth.put(PoseStamped.from_xy_yaw(5.0, 6.0, 0.0))
            clouds.put(cloud())
            await asyncio.sleep(0.05)  # the bus's threads deliver meanwhile
            sources.flush()
    assert json.loads(hub.latest["truth"])["y"] == 6.0
    assert len(json.loads(hub.latest["particles"])) == 2
    sources.close()
