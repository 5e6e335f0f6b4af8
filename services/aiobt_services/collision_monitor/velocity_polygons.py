"""Nav2's ``velocity_polygon``: a polygon whose shape is chosen by the command, from
sub-polygons each covering a range of velocities (the first that covers the command
wins; none: the shape stays as it was). A robot can so keep a long stop zone ahead
when driving and a small one round itself when turning in place near a wall."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .shapes import Shape, ShapeError, polygon

Vel = tuple[float, float, float]  # vx, vy, wz
_KEYS = {"points", "linear_min", "linear_max", "theta_min", "theta_max",
         "direction_start_angle", "direction_end_angle"}  # fmt: skip


class VelocityPolygonError(ValueError):
    """A sub-polygon that cannot be used; the message names it."""


@dataclass(slots=True, frozen=True)
class SubPolygon:
    name: str
    shape: Shape
    linear_min: float
    linear_max: float
    theta_min: float
    theta_max: float
    direction_start_angle: float = -math.pi
    direction_end_angle: float = math.pi

    def covers(self, cmd: Vel, holonomic: bool) -> bool:
        """Nav2's ``isInRange``: the turn rate, then forward speed (or, holonomic, the
        speed and its direction) within this sub-polygon's ranges."""
        if not self.theta_min <= cmd[2] <= self.theta_max:
            return False
        if not holonomic:
            return self.linear_min <= cmd[0] <= self.linear_max
        speed = math.hypot(cmd[0], cmd[1])
        direction = math.atan2(cmd[1], cmd[0]) if speed > 0.0 else 0.0
        start, end = self.direction_start_angle, self.direction_end_angle
        within = start <= direction <= end if start <= end else not end < direction < start
        return self.linear_min <= speed <= self.linear_max and within


def select(subs: tuple[SubPolygon, ...], cmd: Vel, holonomic: bool) -> SubPolygon | None:
    return next((s for s in subs if s.covers(cmd, holonomic)), None)


def sub_polygons(zone: str, section: Mapping[str, Any], points_of: Any) -> tuple[SubPolygon, ...]:
    """The ``velocity_polygons`` of polygon ``zone``; ``points_of`` parses Nav2's strings."""
    names = section.get("velocity_polygons")
    if not isinstance(names, list) or not names:
        raise VelocityPolygonError(f"polygon '{zone}': velocity_polygons must be a non-empty list")
    return tuple(_sub(zone, name, section.get(name), points_of) for name in names)


def _sub(zone: str, name: str, section: Any, points_of: Any) -> SubPolygon:
    where = f"polygon '{zone}', velocity polygon '{name}'"
    if not isinstance(section, Mapping):
        raise VelocityPolygonError(f"{where}: no section")
    unknown = sorted(set(section) - _KEYS)
    if unknown:
        raise VelocityPolygonError(f"{where}: unknown parameter(s) {unknown}")
    try:
        shape = polygon(f"{zone}.{name}", points_of(where, section.get("points")))
    except ShapeError as exc:
        raise VelocityPolygonError(f"{where}: {exc}") from None

    def number(key: str, default: float | None = None) -> float:
        value = section.get(key, default)
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
        ):
            raise VelocityPolygonError(f"{where}: {key} must be a finite number, got {value!r}")
        return float(value)

    sub = SubPolygon(name, shape, number("linear_min"), number("linear_max"), number("theta_min"),
                     number("theta_max"), number("direction_start_angle", -math.pi),
                     number("direction_end_angle", math.pi))  # fmt: skip
    if sub.linear_min > sub.linear_max or sub.theta_min > sub.theta_max:
        raise VelocityPolygonError(f"{where}: a minimum is above its maximum")
    return sub
