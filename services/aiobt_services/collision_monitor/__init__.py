"""Nav2's collision monitor: polygons around the robot watched on the raw sensor data,
stopping or slowing the command before the base. Pure logic here; the service in
``.service`` and ``.main`` (``python -m aiobt_services.collision_monitor``)."""

from .monitor import Action, CollisionMonitor
from .params import MonitorConfigError, MonitorParams, SourceParams, ZoneParams, load_params
from .shapes import Shape, ShapeError, circle, inside_polygon, polygon

__all__ = [
    "Action",
    "CollisionMonitor",
    "MonitorConfigError",
    "MonitorParams",
    "Shape",
    "ShapeError",
    "SourceParams",
    "ZoneParams",
    "circle",
    "inside_polygon",
    "load_params",
    "polygon",
]
