"""The collision monitor's configuration: Nav2's parameter names, defaults and shape.

:func:`load_params` takes Nav2's YAML as it is (``collision_monitor: ros__parameters:``
or the inner mapping): ``polygons`` and ``observation_sources`` name sections, and
each section holds that polygon's or source's parameters. Anything that cannot
run is a :class:`MonitorConfigError` naming the section and the parameter: an unknown
parameter (a typo), type or action, a polygon under 3 points or self-intersecting,
a negative limit, a source a polygon names that is not an observation source.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

from .shapes import Shape, ShapeError, circle, polygon
from .velocity_polygons import SubPolygon, VelocityPolygonError, sub_polygons

ActionType = Literal["none", "stop", "slowdown", "limit", "approach"]
SourceType = Literal["scan", "pointcloud"]
_ACTIONS = ("none", "stop", "slowdown", "limit", "approach")


class MonitorConfigError(ValueError):
    """A configuration the collision monitor refuses; the message names what and where."""


@dataclass(slots=True, frozen=True)
class ZoneParams:
    """One polygon (Nav2's per-polygon parameters, its defaults)."""

    name: str
    shape: Shape
    action_type: ActionType
    enabled: bool = True
    min_points: int = 4
    slowdown_ratio: float = 0.5
    linear_limit: float = 0.5
    angular_limit: float = 0.5
    time_before_collision: float = 2.0
    simulation_time_step: float = 0.1
    trigger_consecutive_points: int = 1
    release_consecutive_points: int = 1
    visualize: bool = False
    sources_names: tuple[str, ...] = ()
    sub_polygons: tuple[SubPolygon, ...] = ()  # a velocity_polygon's, in order
    holonomic: bool = False


@dataclass(slots=True, frozen=True)
class SourceParams:
    name: str
    type: SourceType = "scan"
    topic: str = "scan"
    enabled: bool = True
    source_timeout: float = 2.0
    min_height: float = 0.05
    max_height: float = 0.5


@dataclass(slots=True, frozen=True)
class MonitorParams:
    """The node's parameters (Nav2's defaults; ``state_topic`` is published by default)."""

    polygons: tuple[ZoneParams, ...]
    sources: tuple[SourceParams, ...]
    enabled: bool = True
    cmd_vel_in_topic: str = "cmd_vel_smoothed"
    cmd_vel_out_topic: str = "cmd_vel"
    state_topic: str = "collision_monitor/state"
    source_timeout: float = 2.0
    base_shift_correction: bool = True
    stop_pub_timeout: float = 1.0
    odom_topic: str = "odom"


_TOP = {"enabled", "base_frame_id", "odom_frame_id", "cmd_vel_in_topic", "cmd_vel_out_topic",
        "state_topic", "transform_tolerance", "source_timeout", "base_shift_correction",
        "stop_pub_timeout", "polygons", "observation_sources", "footprint", "robot_radius",
        "odom_topic", "use_realtime_priority", "collision_points_marker_3d"}  # fmt: skip
_ZONE = {"type", "points", "radius", "action_type", "enabled", "min_points", "slowdown_ratio",
         "linear_limit", "angular_limit", "time_before_collision", "simulation_time_step",
         "trigger_consecutive_points", "release_consecutive_points", "visualize",
         "polygon_pub_topic", "sources_names", "footprint_topic", "polygon_sub_topic",
         "polygon_subscribe_transient_local", "velocity_polygons", "holonomic"}  # fmt: skip
_SOURCE = {"type", "topic", "enabled", "source_timeout", "min_height", "max_height",
           "transport_type", "use_global_height"}  # fmt: skip


def load_params(config: Mapping[str, Any]) -> MonitorParams:
    """Nav2's ``collision_monitor`` parameters (YAML loaded) as :class:`MonitorParams`."""
    config = _unwrap(config)
    _known("collision_monitor", config, _TOP)
    timeout = _number(config, "collision_monitor", "source_timeout", 2.0, minimum=0.0)
    sources = tuple(
        _source(config, name, timeout) for name in _names(config, "observation_sources")
    )
    footprint = _footprint(config)
    known = tuple(s.name for s in sources)
    zones = tuple(_zone(config, name, known, footprint) for name in _names(config, "polygons"))
    return MonitorParams(
        polygons=zones,
        sources=sources,
        enabled=bool(config.get("enabled", True)),
        cmd_vel_in_topic=str(config.get("cmd_vel_in_topic", "cmd_vel_smoothed")),
        cmd_vel_out_topic=str(config.get("cmd_vel_out_topic", "cmd_vel")),
        state_topic=str(config.get("state_topic", "collision_monitor/state")),
        source_timeout=timeout,
        base_shift_correction=bool(config.get("base_shift_correction", True)),
        stop_pub_timeout=_number(config, "collision_monitor", "stop_pub_timeout", 1.0, minimum=0.0),
        odom_topic=str(config.get("odom_topic", "odom")),
    )


def _unwrap(config: Mapping[str, Any]) -> Mapping[str, Any]:
    if "collision_monitor" in config:
        config = config["collision_monitor"]
    if isinstance(config, Mapping) and "ros__parameters" in config:
        config = config["ros__parameters"]
    if not isinstance(config, Mapping):
        raise MonitorConfigError("collision_monitor: the configuration must be a mapping")
    return config


def _known(where: str, section: Mapping[str, Any], allowed: set[str]) -> None:
    """Refuse a parameter not in ``allowed`` (a typo); sections (mappings) are names."""
    unknown = sorted(
        k for k, v in section.items() if k not in allowed and not isinstance(v, Mapping)
    )
    if unknown:
        raise MonitorConfigError(
            f"{where}: unknown parameter(s) {unknown}; known: {sorted(allowed)}"
        )


def _names(config: Mapping[str, Any], key: str) -> list[str]:
    names = config.get(key)
    if not isinstance(names, list) or not names or not all(isinstance(n, str) for n in names):
        raise MonitorConfigError(f"collision_monitor: {key} must be a non-empty list of names")
    for name in names:
        if not isinstance(config.get(name), Mapping):
            raise MonitorConfigError(
                f"collision_monitor: {key} names '{name}', which has no section"
            )
    return names


def _number(section: Mapping[str, Any], where: str, key: str, default: float,
            minimum: float | None = None, above: float | None = None) -> float:  # fmt: skip
    value = section.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise MonitorConfigError(f"{where}: {key} must be a finite number, got {value!r}")
    if minimum is not None and value < minimum:
        raise MonitorConfigError(f"{where}: {key} is {value!r}: it must be >= {minimum:g}")
    if above is not None and value <= above:
        raise MonitorConfigError(f"{where}: {key} is {value!r}: it must be > {above:g}")
    return float(value)


def _integer(section: Mapping[str, Any], where: str, key: str, default: int) -> int:
    value = section.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise MonitorConfigError(f"{where}: {key} must be an integer >= 1, got {value!r}")
    return value


def _source(config: Mapping[str, Any], name: str, timeout: float) -> SourceParams:
    section, where = config[name], f"source '{name}'"
    _known(where, section, _SOURCE)
    kind = section.get("type", "scan")
    if kind not in ("scan", "pointcloud"):
        raise MonitorConfigError(f"{where}: unknown source type {kind!r}; known: scan, pointcloud")
    return SourceParams(
        name=name,
        type=kind,
        topic=str(section.get("topic", "scan")),
        enabled=bool(section.get("enabled", True)),
        source_timeout=_number(section, where, "source_timeout", timeout, minimum=0.0),
        min_height=_number(section, where, "min_height", 0.05),
        max_height=_number(section, where, "max_height", 0.5),
    )


def _points(where: str, value: Any) -> Any:
    if isinstance(value, str):  # Nav2 writes them as a string "[[x, y], ...]"
        try:
            return ast.literal_eval(value)
        except (ValueError, SyntaxError):
            raise MonitorConfigError(f"{where}: points {value!r} are not [[x, y], ...]") from None
    return value


def _footprint(config: Mapping[str, Any]) -> Shape:
    """The robot's outline, for footprint-based approach polygons (Nav2: footprint_topic)."""
    try:
        if "footprint" in config:
            return polygon("footprint", _points("collision_monitor", config["footprint"]))
        return circle("footprint", _number(config, "collision_monitor", "robot_radius", 0.22))
    except ShapeError as exc:
        raise MonitorConfigError(f"collision_monitor: {exc}") from None


def _shape(section: Mapping[str, Any], name: str, action: str, footprint: Shape) -> Shape:
    kind, where = section.get("type", "polygon"), f"polygon '{name}'"
    try:
        if kind == "circle":
            if "radius" not in section and action == "approach":
                return footprint
            return circle(name, _number(section, where, "radius", math.nan))
        if kind == "polygon":
            if "points" not in section and action == "approach":
                return footprint
            if "points" not in section:
                raise MonitorConfigError(f"{where}: points are not set")
            return polygon(name, _points(where, section["points"]))
    except ShapeError as exc:
        raise MonitorConfigError(str(exc)) from None
    raise MonitorConfigError(
        f"{where}: unknown polygon type {kind!r}; known: polygon, circle, velocity_polygon"
    )


def _zone(config: Mapping[str, Any], name: str, sources: tuple[str, ...],
          footprint: Shape) -> ZoneParams:  # fmt: skip
    section, where = config[name], f"polygon '{name}'"
    _known(where, section, _ZONE)
    action = section.get("action_type")
    if action not in _ACTIONS:
        raise MonitorConfigError(
            f"{where}: unknown action_type {action!r}; known: {list(_ACTIONS)}"
        )
    names = tuple(section.get("sources_names", sources))
    for source in names:
        if source not in sources:
            raise MonitorConfigError(
                f"{where}: source '{source}' is not one of the observation_sources {list(sources)}"
            )
    subs = _velocity_polygons(section, name)
    return ZoneParams(
        name=name,
        shape=subs[-1].shape if subs else _shape(section, name, action, footprint),
        action_type=action,
        enabled=bool(section.get("enabled", True)),
        min_points=_integer(section, where, "min_points", 4),
        slowdown_ratio=_ratio(section, where),
        linear_limit=_number(section, where, "linear_limit", 0.5, minimum=0.0),
        angular_limit=_number(section, where, "angular_limit", 0.5, minimum=0.0),
        time_before_collision=_number(section, where, "time_before_collision", 2.0, above=0.0),
        simulation_time_step=_number(section, where, "simulation_time_step", 0.1, above=0.0),
        trigger_consecutive_points=_integer(section, where, "trigger_consecutive_points", 1),
        release_consecutive_points=_integer(section, where, "release_consecutive_points", 1),
        visualize=bool(section.get("visualize", False)),
        sources_names=names,
        sub_polygons=subs,
        holonomic=bool(section.get("holonomic", False)),
    )


def _velocity_polygons(section: Mapping[str, Any], name: str) -> tuple[SubPolygon, ...]:
    if section.get("type") != "velocity_polygon":
        return ()
    try:
        return sub_polygons(name, section, _points)
    except VelocityPolygonError as exc:
        raise MonitorConfigError(str(exc)) from None


def _ratio(section: Mapping[str, Any], where: str) -> float:
    ratio = _number(section, where, "slowdown_ratio", 0.5, minimum=0.0)
    if ratio > 1.0:
        raise MonitorConfigError(f"{where}: slowdown_ratio is {ratio!r}: it must be <= 1")
    return ratio
