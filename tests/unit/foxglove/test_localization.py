"""The localization and the simulation's truth in Foxglove: the particle cloud as poses,
amcl_pose and the truth as poses in map; the navigator's recording leaves the truth."""

from __future__ import annotations

from pathlib import Path

import foxglove
import pytest

from aiobt.foxglove import convert
from aiobt.foxglove.bridge import FoxgloveBridge
from aiobt.foxglove.channels import Channels
from aiobt.foxglove.recording import McapRecording
from aiobt.msgs import Header, ParticleCloud, Pose
from aiobt.msgs.localization import Particle
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
