"""The localization and the simulation's truth in Foxglove: the particle cloud as poses,
amcl_pose and the truth as poses in map; the navigator's recording leaves the truth; a
client's pose estimate goes to initialpose."""

from __future__ import annotations

import json
import logging
import math
from pathlib import Path

import foxglove
import pytest

from aiobt.foxglove import convert, inbound
from aiobt.foxglove.bridge import FoxgloveBridge
from aiobt.foxglove.channels import Channels
from aiobt.foxglove.recording import McapRecording
from aiobt.msgs import Header, MessageError, ParticleCloud, Pose, PoseWithCovarianceStamped
from aiobt.msgs.localization import DEFAULT_INITIAL_COVARIANCE, Particle
from aiobt.transport import Bus
from aiobt.transport.keys import SIM_POSE

from .test_convert import decoded


def test_the_particle_cloud_is_a_set_of_poses_in_its_frame() -> None:
    cloud = ParticleCloud(
        header=Header(stamp=4.5, frame_id="map"),
        particles=[
            Particle(pose=Pose.from_xy_yaw(1.0, 2.0, 0.0), weight=0.5),
            Particle(pose=Pose.from_xy_yaw(-1.5, 0.25, 3.14159265), weight=0.5),
        ],
    )
    out = decoded(convert.particle_cloud(cloud))
    assert out.frame_id == "map"
    assert (out.timestamp.seconds, out.timestamp.nanos) == (4, 500_000_000)
    assert [(p.position.x, p.position.y) for p in out.poses] == [(1.0, 2.0), (-1.5, 0.25)]
    assert out.poses[1].orientation.z == pytest.approx(1.0)  # facing back


def test_the_channels_of_the_localization_and_the_truth() -> None:
    channels = Channels.create(foxglove.Context())
    assert {"/particle_cloud", "/amcl_pose", "/sim/pose"} <= channels.topics()


@pytest.mark.parametrize(("truth", "reads_truth"), [(True, True), (False, False)])
async def test_the_bridge_reads_the_truth_only_when_asked(
    local_bus: Bus, truth: bool, reads_truth: bool
) -> None:
    bridge = FoxgloveBridge(local_bus, foxglove.Context(), forwards_goals=False, truth=truth)
    bridge.start()
    try:
        keys = {sub.key for sub in bridge._subs}
    finally:
        bridge.close()
    assert {local_bus.keys.topic("particle_cloud"), local_bus.keys.topic("amcl_pose")} <= keys
    assert (local_bus.keys.topic(SIM_POSE) in keys) is reads_truth


async def test_the_navigators_recording_does_not_read_the_truth(
    local_bus: Bus, tmp_path: Path
) -> None:
    recording = McapRecording(local_bus, tmp_path / "run.mcap")
    try:
        assert recording._bridge.truth is False
        keys = {sub.key for sub in recording._bridge._subs}
    finally:
        recording.close()
    assert local_bus.keys.topic(SIM_POSE) not in keys
    assert local_bus.keys.topic("particle_cloud") in keys


def _ros_estimate(covariance: list[float]) -> bytes:
    return json.dumps({
        "header": {"stamp": {"sec": 3, "nsec": 0}, "frame_id": "map"},
        "pose": {"pose": {"position": {"x": 2.0, "y": 9.75, "z": 0.0},
                          "orientation": {"x": 0.0, "y": 0.0, "z": 1.0, "w": 0.0}},
                 "covariance": covariance},
    }).encode()  # fmt: skip


def test_a_pose_estimate_keeps_its_covariance_and_a_short_one_gets_nav2s() -> None:
    cov = [0.0] * 36
    cov[0], cov[7], cov[35] = 0.09, 0.16, 0.01
    estimate = inbound.initialpose_from_json(_ros_estimate(cov))
    assert (estimate.header.frame_id, estimate.x, estimate.y) == ("map", 2.0, 9.75)
    assert estimate.yaw == pytest.approx(math.pi)
    assert estimate.pose.covariance == cov
    short = inbound.initialpose_from_json(b'{"x": 1.0, "y": 2.0, "yaw": 0.5}')
    assert short.pose.covariance == list(DEFAULT_INITIAL_COVARIANCE)
    with pytest.raises(MessageError, match="covariance"):
        inbound.initialpose_from_json(_ros_estimate([0.0] * 35))
    with pytest.raises(ValueError, match="initialpose is not JSON"):
        inbound.initialpose_from_json(b"{nope")


async def test_a_pose_estimate_from_a_client_goes_to_initialpose(
    local_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    caplog.set_level(logging.INFO, logger="aiobt.foxglove.bridge")
    received = local_bus.subscribe("initialpose", PoseWithCovarianceStamped, queue_size=4)
    contexts = foxglove.Context(), foxglove.Context()  # held: their channels live as long
    bridge = FoxgloveBridge(local_bus, contexts[0])
    recorder = FoxgloveBridge(local_bus, contexts[1], forwards_goals=False)
    try:
        assert bridge.initialposes is not None
        assert await bridge.initialposes.wait_for_subscribers(10.0)
        recorder.forward_initialpose(b'{"x": 5.0, "y": 1.0, "yaw": 0.0}', "/initialpose")
        bridge.forward_initialpose(b'{"pose": "nowhere"}', "/initialpose")  # refused
        bridge.forward_initialpose(b'{"x": 1.0, "y": 2.0, "yaw": 0.0}', "/initialpose")
        first = await received.wait_latest(10.0)
    finally:
        bridge.close()
        recorder.close()
    assert (first.x, first.y) == (1.0, 2.0)
    assert "initialpose on /initialpose refused: this bridge only records" in caplog.text
    assert "initialpose on /initialpose refused: initialpose: " in caplog.text  # names why
    assert "initialpose from Foxglove: (1.00, 2.00) in map" in caplog.text
