"""The collision monitor's polygons in Foxglove: one outline per enabled polygon in the
base frame, the acting one red; a monitor switched off clears them."""

from __future__ import annotations

import pytest

from aiobt.foxglove.zones import zones_scene
from aiobt.msgs.safety import CollisionPolygons, ZoneOutline

from .test_convert import decoded

SQUARE = [(0.5, 0.25), (0.5, -0.25), (0.0, -0.25), (0.0, 0.25)]


def polygons(enabled: bool = True) -> CollisionPolygons:
    return CollisionPolygons(
        enabled=enabled,
        polygons=[
            ZoneOutline(name="Stop", action_type="stop", enabled=True, acting=True, points=SQUARE),
            ZoneOutline(name="Approach", action_type="approach", enabled=True, points=SQUARE),
            ZoneOutline(name="Off", action_type="stop", enabled=False, points=SQUARE),
        ],
    )


def test_each_enabled_polygon_is_an_outline_on_the_robot() -> None:
    scene = decoded(zones_scene(polygons()))
    assert [e.id for e in scene.entities] == [
        "collision_monitor/Stop",
        "collision_monitor/Approach",
    ]
    stop, approach = scene.entities
    assert stop.frame_id == "base_link"
    assert stop.frame_locked
    assert [(p.x, p.y) for p in stop.lines[0].points] == SQUARE
    red = stop.lines[0].color
    assert (red.r, red.g, red.b) == pytest.approx((0.85, 0.0, 0.0))
    assert approach.lines[0].color.b == pytest.approx(1.0)
    assert stop.lines[0].thickness > approach.lines[0].thickness


def test_switched_off_the_outlines_are_cleared() -> None:
    scene = decoded(zones_scene(polygons(enabled=False)))
    assert list(scene.entities) == []
    assert len(scene.deletions) == 1
