"""Layered 2D costmaps with Nav2's cost values, on numpy (planner and controller).

Arrays are ``(height, width)`` uint8, indexed ``[row, col]`` (row = y).
"""

from .collision import (
    footprint_cost,
    footprints_cost,
    line_cells,
    oriented_footprint,
    point_cost,
    points_cost,
    segment_is_free,
    segment_max_cost,
)
from .costmap import Costmap
from .distance import distance_transform
from .footprint import footprint_from_radius, parse_footprint
from .grid import (
    FREE,
    INSCRIBED,
    LETHAL,
    NO_INFORMATION,
    CostArray,
    CostGrid,
    GridGeometry,
)
from .inflation import InflationParams, Window, costs_from_distance, inflate, inflate_window
from .obstacle_layer import ObstacleParams, Scan, clear_and_mark, combine_max
from .rolling import RollingCostmap
from .static_layer import StaticParams, occupancy_to_costs, resample

__all__ = [
    "FREE",
    "INSCRIBED",
    "LETHAL",
    "NO_INFORMATION",
    "CostArray",
    "CostGrid",
    "Costmap",
    "GridGeometry",
    "InflationParams",
    "ObstacleParams",
    "RollingCostmap",
    "Scan",
    "StaticParams",
    "Window",
    "clear_and_mark",
    "combine_max",
    "costs_from_distance",
    "distance_transform",
    "footprint_cost",
    "footprint_from_radius",
    "footprints_cost",
    "inflate",
    "inflate_window",
    "line_cells",
    "occupancy_to_costs",
    "oriented_footprint",
    "parse_footprint",
    "point_cost",
    "points_cost",
    "resample",
    "segment_is_free",
    "segment_max_cost",
]
