"""Nav2's ``PathConverter``: the route as a dense path, points ``path_density`` apart.

Each edge is cut into ``ceil(length / path_density)`` equal steps (its end is the
next edge's start); the last node closes the path. After a reroute along the
edge the robot was on, the path starts at the robot's nearest point on that
edge. Each pose faces the next; the last faces along the last edge. A route of
one node is a path of one pose. With ``smooth_corners`` each corner is rounded by
an arc of ``smoothing_radius`` where one fits (:mod:`.corners`).
"""

from __future__ import annotations

import itertools
import logging
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .corners import corner_arc
from .intent import ReroutingState
from .search import Route
from .vectors import XY

Poses = npt.NDArray[np.float64]  # (n, 3): x, y, yaw
Points = npt.NDArray[np.float64]  # (n, 2)
log = logging.getLogger("aiobt_services.route.dense")


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


@dataclass(frozen=True, slots=True)
class Smoothing:
    """Nav2's ``smooth_corners`` (off in its code), ``smoothing_radius`` and
    ``smoothing_angle_threshold``."""

    smooth_corners: bool = False
    smoothing_radius: float = 1.0
    smoothing_angle_threshold: float = 2.9


def _edges_xy(route: Route, density: float, smoothing: Smoothing) -> list[Points]:
    """The route's edges as points, each corner rounded when ``smoothing`` asks for it
    and an arc fits (the next edge then starts where the arc ends, as Nav2's)."""
    pieces: list[Points] = []
    edges = route.edges
    start = (edges[0].start.x, edges[0].start.y)
    for edge, after in itertools.pairwise(edges):
        corner, beyond = (edge.end.x, edge.end.y), (after.end.x, after.end.y)
        arc = None
        if smoothing.smooth_corners:
            arc = corner_arc(start, corner, beyond, smoothing.smoothing_radius,
                             smoothing.smoothing_angle_threshold)  # fmt: skip
            if arc is None:
                log.warning("no corner arc between edge %d and edge %d", edge.edgeid,
                            after.edgeid)  # fmt: skip
        if arc is None:
            pieces.append(interpolate(start, corner, density))
            start = corner
            continue
        pieces.append(interpolate(start, arc.start, density))
        pieces.append(arc.points(density / smoothing.smoothing_radius))
        start = arc.end
    last = edges[-1].end
    pieces.append(interpolate(start, (last.x, last.y), density))
    return pieces


def densify(
    route: Route, rerouting: ReroutingState, density: float, smoothing: Smoothing | None = None
) -> Poses:
    if not density > 0.0:
        raise ValueError(f"path_density must be > 0 m, got {density!r}")
    pieces: list[Points] = []
    if rerouting.curr_edge is not None:
        end = rerouting.curr_edge.end
        pieces.append(interpolate(rerouting.closest_pt_on_edge, (end.x, end.y), density))
    if route.edges:
        pieces += _edges_xy(route, density, smoothing or Smoothing())
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
