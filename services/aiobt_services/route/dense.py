"""Nav2's ``PathConverter``: the route as a dense path, points ``path_density`` apart.

Each edge is cut into ``ceil(length / path_density)`` equal steps (its end is the
next edge's start); the last node closes the path. After a reroute along the
edge the robot was on, the path starts at the robot's nearest point on that
edge. Each pose faces the next; the last faces along the last edge. A route of
one node is a path of one pose. Corner smoothing (Nav2's ``smooth_corners``,
off by default in its code) is not done here.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from .intent import ReroutingState
from .search import Route
from .vectors import XY

Poses = npt.NDArray[np.float64]  # (n, 3): x, y, yaw


def interpolate(start: XY, end: XY, density: float) -> Poses:
    """Points from ``start`` (included) towards ``end`` (excluded), equally spaced at most
    ``density`` apart; none for a zero-length segment."""
    length = math.hypot(end[0] - start[0], end[1] - start[1])
    count = math.ceil(length / density)
    if count < 1:
        return np.empty((0, 2))
    t = np.arange(count, dtype=np.float64)[:, None] / count
    points: Poses = np.asarray(start) + t * (np.asarray(end) - np.asarray(start))
    return points


def densify(route: Route, rerouting: ReroutingState, density: float) -> Poses:
    if not density > 0.0:
        raise ValueError(f"path_density must be > 0 m, got {density!r}")
    pieces: list[npt.NDArray[np.float64]] = []
    if rerouting.curr_edge is not None:
        end = rerouting.curr_edge.end
        pieces.append(interpolate(rerouting.closest_pt_on_edge, (end.x, end.y), density))
    for edge in route.edges:
        pieces.append(interpolate((edge.start.x, edge.start.y), (edge.end.x, edge.end.y), density))
    last = route.nodes[-1]
    pieces.append(np.array([[last.x, last.y]]))
    xy = np.concatenate(pieces)
    yaw = np.zeros(len(xy))
    if len(xy) > 1:
        step = np.diff(xy, axis=0)
        yaw[:-1] = np.arctan2(step[:, 1], step[:, 0])
    if route.edges:
        edge = route.edges[-1]
        yaw[-1] = math.atan2(edge.end.y - edge.start.y, edge.end.x - edge.start.x)
    return np.column_stack((xy, yaw))
