"""What a route search is asked (Nav2's ``RouteRequest``) and how an edge stands to it
(Nav2's ``EdgeType``): what the edge scorers see besides the edge itself."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from .vectors import XY

EdgeType = Literal["NONE", "START", "END"]
"""An edge leaving the search's start node (START), else one reaching its goal node
(END), else NONE: Nav2's ``RoutePlanner::classifyEdge``."""


@dataclass(frozen=True, slots=True)
class RouteRequest:
    """A ComputeRoute / ComputeAndTrackRoute goal, in the route frame: the node ids, or
    (``use_poses``) the start pose (the request's, or the robot's) and the goal pose."""

    use_poses: bool
    start_id: int = 0
    goal_id: int = 0
    start: XY = (0.0, 0.0)
    goal: XY = (0.0, 0.0)
    start_yaw: float = 0.0  # rad, in the route frame
    goal_yaw: float = 0.0


BY_IDS = RouteRequest(use_poses=False)
"""A request without poses: what a search run outside a goal (tests, tools) scores with."""
