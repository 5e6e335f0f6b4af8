"""The collision monitor's polygons as a Foxglove scene: one line loop per enabled
polygon, locked to the robot's base frame, the acting one red and thicker."""

from __future__ import annotations

from foxglove import messages as fm

from aiobt.msgs import Pose
from aiobt.msgs.safety import CollisionPolygons

from .convert import pose, timestamp

ACTING = fm.Color(r=0.85, g=0.0, b=0.0, a=1.0)
APPROACH = fm.Color(r=0.16, g=0.47, b=1.0, a=0.9)
OTHER = fm.Color(r=1.0, g=0.57, b=0.0, a=0.9)


def zones_scene(msg: CollisionPolygons) -> fm.SceneUpdate:
    """Every polygon's outline (none while the monitor is off: the old ones deleted)."""
    deletions = [fm.SceneEntityDeletion(type=fm.SceneEntityDeletionType.All)]
    if not msg.enabled:
        return fm.SceneUpdate(deletions=deletions)
    entities = [
        fm.SceneEntity(
            timestamp=timestamp(msg.header.stamp),
            frame_id=msg.header.frame_id,
            id=f"collision_monitor/{zone.name}",
            frame_locked=True,
            lines=[
                fm.LinePrimitive(
                    type=fm.LinePrimitiveLineType.LineLoop,
                    pose=pose(Pose()),
                    thickness=0.04 if zone.acting else 0.015,
                    points=[fm.Point3(x=x, y=y) for x, y in zone.points],
                    color=_colour(zone.acting, zone.action_type),
                )
            ],
        )
        for zone in msg.polygons
        if zone.enabled
    ]
    return fm.SceneUpdate(deletions=deletions, entities=entities)


def _colour(acting: bool, action: str) -> fm.Color:
    if acting:
        return ACTING
    return APPROACH if action == "approach" else OTHER
