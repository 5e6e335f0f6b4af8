"""Nav2's collision_monitor_node_test set-up, as parameter mappings and scans."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from aiobt.msgs import Header, LaserScan
from aiobt_services.collision_monitor import CollisionMonitor, load_params
from aiobt_services.collision_monitor.sources import scan_points

MIN_POINTS = 2
SLOWDOWN_RATIO = 0.7
LINEAR_LIMIT = 0.4
ANGULAR_LIMIT = 0.09
TIME_BEFORE_COLLISION = 1.0
SIMULATION_TIME_STEP = 0.01
SOURCE_TIMEOUT = 5.0
STOP_PUB_TIMEOUT = 0.1
SCAN = "Scan"


def square(size: float) -> str:
    return f"[[{size}, {size}], [{size}, {-size}], [{-size}, {-size}], [{-size}, {size}]]"


def polygon(kind: str, size: float, action: str, **extra: Any) -> dict[str, Any]:
    section: dict[str, Any] = {
        "type": kind,
        "enabled": True,
        "action_type": action,
        "min_points": MIN_POINTS,
        "slowdown_ratio": SLOWDOWN_RATIO,
        "linear_limit": LINEAR_LIMIT,
        "angular_limit": ANGULAR_LIMIT,
        "time_before_collision": TIME_BEFORE_COLLISION,
        "simulation_time_step": SIMULATION_TIME_STEP,
        "visualize": False,
    }
    if kind == "circle":
        section["radius"] = size
    else:
        section["points"] = square(size)
    return section | extra


def config(zones: dict[str, dict[str, Any]], sources: tuple[str, ...] = (SCAN,),
           **top: Any) -> dict[str, Any]:  # fmt: skip
    params: dict[str, Any] = {
        "enabled": True,
        "cmd_vel_in_topic": "cmd_vel_in",
        "cmd_vel_out_topic": "cmd_vel_out",
        "state_topic": "collision_monitor_state",
        "base_frame_id": "base_link",
        "odom_frame_id": "odom",
        "transform_tolerance": 0.5,
        "source_timeout": SOURCE_TIMEOUT,
        "stop_pub_timeout": STOP_PUB_TIMEOUT,
        "base_shift_correction": False,
        "polygons": list(zones),
        "observation_sources": list(sources),
        **zones,
        **{name: {"type": "scan", "topic": name.lower(), "enabled": True} for name in sources},
    }
    return {"collision_monitor": {"ros__parameters": params | top}}


def monitor(polygons: dict[str, dict[str, Any]], **top: Any) -> CollisionMonitor:
    return CollisionMonitor(load_params(config(polygons, **top)))


def ring_scan(dist: float, stamp: float = 0.0) -> LaserScan:
    """Nav2's publishScan: 360 readings of ``dist`` all round."""
    return LaserScan(
        header=Header(stamp=stamp, frame_id="base_source"),
        angle_min=0.0,
        angle_max=2 * math.pi,
        angle_increment=math.pi / 180,
        range_min=0.1,
        range_max=dist + 1.0,
        ranges=[dist] * 360,
    )


def give_scan(cm: CollisionMonitor, dist: float, now: float, source: str = SCAN) -> None:
    cm.sources[source].take(scan_points(ring_scan(dist, now)), now, now)


def points_at(*xy: tuple[float, float]) -> np.ndarray:
    return np.array(xy, dtype=np.float64)
