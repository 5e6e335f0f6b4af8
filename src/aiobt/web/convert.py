"""Bus messages to the web page's JSON: pure functions, map-frame metres, rounded to mm.

Grids go as base64 of one byte per cell, row-major from the origin (row 0 at
the bottom, as OccupancyGrid): the occupancy 0..100 with 255 for unknown, or
the inflated cost 0..254 (Nav2's costmap values, 255 unknown).
"""

from __future__ import annotations

import base64
import math
from typing import Any

import numpy as np

from aiobt.costmap.grid import LETHAL, NO_INFORMATION, GridGeometry
from aiobt.costmap.inflation import InflationParams, inflate
from aiobt.msgs import (
    LaserScan,
    OccupancyGrid,
    ParticleCloud,
    Path,
    PoseStamped,
    PoseWithCovarianceStamped,
    Twist,
)
from aiobt.msgs.bt import BtSnapshot, BtTree
from aiobt.msgs.docking import DockList
from aiobt.msgs.route_graph import RouteGraph
from aiobt.msgs.safety import CollisionPolygons

Json = dict[str, Any]
OCCUPIED = 65  # occupancy from which a cell is an obstacle (Nav2's occupied_thresh 0.65)
ROLLOUT_SECONDS = 1.5  # how far ahead the local trajectory reaches
ROLLOUT_STEP = 0.1  # s between its points


def _mm(value: float) -> float:
    return round(value, 3)


def _grid(grid: OccupancyGrid, cells: np.ndarray) -> Json:
    info = grid.info
    return {
        "width": info.width,
        "height": info.height,
        "resolution": info.resolution,
        "origin": [info.origin.position.x, info.origin.position.y],
        "cells": base64.b64encode(np.ascontiguousarray(cells, np.uint8).tobytes()).decode(),
    }


def map_payload(grid: OccupancyGrid) -> Json:
    """The occupancy grid: 0..100 per cell, 255 unknown."""
    cells = np.asarray(grid.array)
    return _grid(grid, np.where(cells < 0, NO_INFORMATION, cells).astype(np.uint8))


def inflated_costs(grid: OccupancyGrid, params: InflationParams) -> np.ndarray:
    """Nav2's global costmap of ``grid``: static layer (lethal from OCCUPIED) and inflation."""
    info = grid.info
    geometry = GridGeometry(
        info.width, info.height, info.resolution, info.origin.position.x, info.origin.position.y
    )
    cells = np.asarray(grid.array)
    master = np.where(cells < 0, NO_INFORMATION, np.where(cells >= OCCUPIED, LETHAL, 0))
    return inflate(master.astype(np.uint8), geometry, params)


def costmap_payload(grid: OccupancyGrid, params: InflationParams) -> Json:
    return _grid(grid, inflated_costs(grid, params))


def pose_payload(pose: PoseStamped) -> Json:
    return {"x": _mm(pose.x), "y": _mm(pose.y), "yaw": _mm(pose.yaw), "stamp": pose.header.stamp}


def estimate_payload(estimate: PoseWithCovarianceStamped) -> Json:
    """The localization's ``amcl_pose``: the pose, and its covariance in the plane as
    ``[xx, xy, yy, yaw_yaw]`` (m^2, rad^2) for the page's uncertainty ellipse."""
    cov = estimate.pose.covariance
    payload = pose_payload(estimate.as_pose_stamped())
    payload["covariance"] = [round(cov[i], 6) for i in (0, 1, 7, 35)]
    return payload


def particles_payload(cloud: ParticleCloud) -> list[list[float]]:
    """The localization's particles as ``[x, y, yaw]`` (as the service thins them)."""
    return [
        [_mm(p.pose.position.x), _mm(p.pose.position.y), _mm(p.pose.yaw)] for p in cloud.particles
    ]


def scan_points(scan: LaserScan, pose: PoseStamped) -> list[list[float]]:
    """The scan's returns in the map frame, seen from ``pose`` (beams with no return dropped)."""
    ranges = np.asarray(scan.ranges, dtype=np.float64)
    angles = scan.angle_min + scan.angle_increment * np.arange(ranges.size)
    hit = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges < scan.range_max)
    bearing = angles[hit] + pose.yaw
    xs = pose.x + ranges[hit] * np.cos(bearing)
    ys = pose.y + ranges[hit] * np.sin(bearing)
    return np.round(np.stack([xs, ys], axis=1), 3).tolist()  # type: ignore[no-any-return]


def path_points(path: Path) -> list[list[float]]:
    return [[_mm(p.x), _mm(p.y)] for p in path.poses]


def rollout(pose: PoseStamped, command: Twist) -> list[list[float]]:
    """The local trajectory: the controller's current command (``cmd_vel``) driven for
    ROLLOUT_SECONDS from ``pose`` on a unicycle, as DWB scores its trajectories."""
    v, w = command.linear.x, command.angular.z
    x, y, yaw = pose.x, pose.y, pose.yaw
    points = [[_mm(x), _mm(y)]]
    for _ in range(round(ROLLOUT_SECONDS / ROLLOUT_STEP)):
        yaw += w * ROLLOUT_STEP / 2
        x += v * ROLLOUT_STEP * math.cos(yaw)
        y += v * ROLLOUT_STEP * math.sin(yaw)
        yaw += w * ROLLOUT_STEP / 2
        points.append([_mm(x), _mm(y)])
    return points


def zones_payload(zones: CollisionPolygons, pose: PoseStamped) -> list[Json]:
    """The collision monitor's enabled polygons in the map frame at ``pose`` (closed
    outlines), the acting one marked; none while the monitor is off."""
    if not zones.enabled:
        return []
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    return [
        {
            "name": zone.name,
            "action": zone.action_type,
            "acting": zone.acting,
            "points": [
                [_mm(pose.x + x * c - y * s), _mm(pose.y + x * s + y * c)]
                for x, y in [*zone.points, zone.points[0]]
            ],
        }
        for zone in zones.polygons
        if zone.enabled and zone.points
    ]


def tree_payload(tree: BtTree) -> Json:
    """The tree's structure: its nodes in depth-first order, each with its parent."""
    nodes = [
        {"uid": n.uid, "parent": n.parent, "id": n.id, "name": n.name, "kind": n.kind}
        for n in tree.nodes
    ]
    return {"run": tree.run, "tree_id": tree.tree_id, "source": tree.source, "nodes": nodes}


def navigation_payload(snapshot: BtSnapshot) -> Json:
    """The navigation's state from the navigator's snapshot, with the goal it drives to."""
    return {
        "run": snapshot.run,
        "state": snapshot.state,
        "recoveries": snapshot.number_of_recoveries,
        "distance_remaining": _mm(snapshot.distance_remaining),
        "error_code": snapshot.error_code,
        "error_msg": snapshot.error_msg,
        "stamp": snapshot.stamp,
        "goals": [pose_payload(goal) for goal in snapshot.goals],
    }


def route_graph_payload(graph: RouteGraph) -> Json:
    """The route server's graph: nodes ``[x, y, id]`` and lanes ``[x0, y0, x1, y1]``, a
    two-way lane (two edges) once."""
    lanes: dict[tuple[float, ...], list[float]] = {}
    for edge in graph.edges:
        a, b = (_mm(edge.start.x), _mm(edge.start.y)), (_mm(edge.end.x), _mm(edge.end.y))
        lanes.setdefault((*min(a, b), *max(a, b)), [*a, *b])
    nodes = [[_mm(n.position.x), _mm(n.position.y), n.nodeid] for n in graph.nodes]
    return {"name": graph.name, "nodes": nodes, "edges": list(lanes.values())}


def docks_payload(docks: DockList) -> list[Json]:
    """The docking server's docks: each one's name, pose and staging pose (or None)."""
    return [
        {"name": d.name, **pose_payload(d.pose),
         "staging": pose_payload(d.staging) if d.staging is not None else None}
        for d in docks.docks
    ]  # fmt: skip
