"""The followed object on Foxglove's ``/followed``: the following server's filtered pose
in its own frame (Foxglove places it with ``/tf``)."""

from __future__ import annotations

from pathlib import Path

import foxglove
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from aiobt.foxglove.bridge import FoxgloveBridge
from aiobt.msgs import PoseStamped
from aiobt.transport import Bus


async def test_the_filtered_pose_goes_to_followed_in_its_frame(
    local_bus: Bus, tmp_path: Path
) -> None:
    context, path = foxglove.Context(), tmp_path / "followed.mcap"
    writer = foxglove.open_mcap(path, context=context)
    bridge = FoxgloveBridge(local_bus, context, forwards_goals=False, costmap_period=0.0)
    bridge.on_followed(PoseStamped.from_xy_yaw(3.0, 4.0, 0.5, "odom", 12.5))
    writer.close()
    bridge.close()
    with path.open("rb") as f:
        decoder = DecoderFactory()
        logged = [(channel.topic, decoder.decoder_for(channel.message_encoding, schema), m.data)
                  for schema, channel, m in make_reader(f).iter_messages()]  # fmt: skip
    assert [topic for topic, _, _ in logged] == ["/followed"]
    [(_, decode, data)] = logged
    assert decode is not None
    pose = decode(data)
    assert pose.frame_id == "odom"
    assert (pose.pose.position.x, pose.pose.position.y) == (3.0, 4.0)
    assert pose.timestamp.seconds == 12
