"""The controller's local plan and local costmap as the page gets them (Sources.flush); a
map-frame stream in another frame (local plan, particles, amcl_pose) is not drawn."""

from __future__ import annotations

import base64
import json
import logging

import numpy as np
import pytest

from aiobt.msgs import Header, Msg, OccupancyGrid, Path, Pose, PoseStamped
from aiobt.transport import Bus
from aiobt.web.coalesce import Hub
from aiobt.web.sources import Sources

from .test_localization_streams import cloud, estimate


def _path(frame: str, points: list[tuple[float, float]]) -> Path:
    return Path(
        header=Header(frame_id=frame),
        poses=[PoseStamped.from_xy_yaw(x, y, 0.0) for x, y in points],
    )


async def test_local_plan_goes_to_the_page_and_an_empty_one_clears_it(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    sources.raw.set("local_plan", _path("map", [(1.0, 2.0), (1.25, 2.0004)]))
    sources.flush()
    assert json.loads(hub.latest["local_plan"]) == [[1.0, 2.0], [1.25, 2.0]]
    sources.raw.set("local_plan", _path("map", []))
    sources.flush()
    assert json.loads(hub.latest["local_plan"]) == []
    sources.close()


@pytest.mark.parametrize(
    ("stream", "message", "shown_as"),
    [
        ("local_plan", _path("odom", [(0.0, 0.0), (1.0, 0.0)]), "local_plan"),
        ("particle_cloud", cloud("odom"), "particles"),
        ("amcl_pose", estimate("odom"), "amcl_pose"),
    ],
)
async def test_a_map_frame_stream_in_another_frame_is_not_drawn_and_said_once(
    local_bus: Bus, caplog: pytest.LogCaptureFixture, stream: str, message: Msg, shown_as: str
) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    with caplog.at_level(logging.WARNING, logger="aiobt.web.sources"):
        for _ in range(3):
            sources.raw.set(stream, message)
            sources.flush()
    assert shown_as not in hub.latest
    assert caplog.text.count(f"{stream} in frame 'odom' not shown") == 1
    sources.close()


async def test_local_costmap_is_sent_with_its_own_origin(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    cells = np.zeros((3, 4), dtype=np.int8)
    cells[0, 1], cells[2, 3] = 100, -1
    grid = OccupancyGrid.from_array(cells, 0.05, origin=Pose.from_xy_yaw(-1.0, 0.5))
    sources.raw.set("local_costmap/costmap", grid)
    sources.flush()
    payload = json.loads(hub.latest["local_costmap"])
    assert (payload["width"], payload["height"], payload["origin"]) == (4, 3, [-1.0, 0.5])
    decoded = np.frombuffer(base64.b64decode(payload["cells"]), np.uint8).reshape(3, 4)
    assert (decoded[0, 1], decoded[2, 3], decoded[1, 1]) == (100, 255, 0)
    assert "map" not in hub.latest, "the local costmap must not replace the map"
    sources.close()
