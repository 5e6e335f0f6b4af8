"""Wire models of the safety chain (the collision monitor, ``aiobt_services.collision_monitor``):
a point source's points, the monitor's state and its polygons for viewers."""

from __future__ import annotations

from pydantic import Field

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import Header, Point

ACTION_CODES = {"none": 0, "stop": 1, "slowdown": 2, "approach": 3, "limit": 4}  # Nav2's


class PointCloud(Msg):
    """Obstacle points in the robot's base frame (a ``pointcloud`` source's key)."""

    header: Header = Field(default_factory=lambda: Header(frame_id="base_link"))
    points: list[Point] = Field(default_factory=list)


class CollisionMonitorState(Msg):
    """Which polygon acts and why (Nav2's ``CollisionMonitorState`` plus the reason)."""

    header: Header = Field(default_factory=Header)
    action_type: int = Field(
        default=0, description="0 none, 1 stop, 2 slowdown, 3 approach, 4 limit"
    )
    action: str = "none"
    polygon_name: str = ""
    reason: str = ""
    enabled: bool = True
    linear_x: float = 0.0
    angular_z: float = 0.0


class ZoneOutline(Msg):
    name: str
    action_type: str
    enabled: bool
    acting: bool = False
    points: list[tuple[float, float]]


class CollisionPolygons(Msg):
    """Every polygon in the base frame, the acting one marked, for viewers."""

    header: Header = Field(default_factory=lambda: Header(frame_id="base_link"))
    enabled: bool = True
    polygons: list[ZoneOutline] = Field(default_factory=list)
