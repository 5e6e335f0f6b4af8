"""The collision monitor's polygons as the page gets them: placed at the robot's pose,
the acting one marked, nothing while the monitor is off."""

from __future__ import annotations

import json
import math

import pytest

from aiobt.msgs import PoseStamped
from aiobt.msgs.safety import CollisionPolygons, ZoneOutline
from aiobt.transport import Bus
from aiobt.web.coalesce import Hub
from aiobt.web.convert import zones_payload
from aiobt.web.sources import Sources

SQUARE = [(0.5, 0.25), (0.5, -0.25), (0.0, -0.25), (0.0, 0.25)]


def zones(enabled: bool = True) -> CollisionPolygons:
    return CollisionPolygons(enabled=enabled, polygons=[
        ZoneOutline(name="Stop", action_type="stop", enabled=True, acting=True, points=SQUARE),
        ZoneOutline(name="Off", action_type="stop", enabled=False, points=SQUARE),
    ])  # fmt: skip


def test_outlines_turn_and_move_with_the_robot_and_close() -> None:
    pose = PoseStamped.from_xy_yaw(1.0, 2.0, math.pi / 2)
    (stop,) = zones_payload(zones(), pose)
    assert (stop["name"], stop["action"], stop["acting"]) == ("Stop", "stop", True)
    assert stop["points"][0] == pytest.approx([0.75, 2.5])  # 0.5 ahead is 0.5 north
    assert stop["points"][-1] == stop["points"][0]
    assert len(stop["points"]) == 5


def test_nothing_is_drawn_while_the_monitor_is_off() -> None:
    assert zones_payload(zones(enabled=False), PoseStamped.from_xy_yaw(0.0, 0.0)) == []


async def test_the_page_gets_them_with_each_pose(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    sources.raw.set("collision_monitor/polygons", zones())
    sources.flush()
    assert "zones" not in hub.latest  # no pose yet: nowhere to draw them
    sources.raw.set("pose", PoseStamped.from_xy_yaw(3.0, 0.0, 0.0))
    sources.flush()
    (stop,) = json.loads(hub.latest["zones"])
    assert stop["points"][0] == [3.5, 0.25]
    sources.close()
