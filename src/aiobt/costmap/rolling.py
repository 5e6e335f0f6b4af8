"""A rolling-window costmap that stays centred on the robot (Nav2 local costmap)."""

from __future__ import annotations

import math

import numpy as np

from .costmap import Costmap
from .grid import NO_INFORMATION, CostArray, GridGeometry
from .inflation import InflationParams, Window
from .obstacle_layer import ObstacleParams, combine_max
from .static_layer import resample


class RollingCostmap(Costmap):
    """A fixed-size window whose origin follows the robot, snapped to whole cells.

    Obstacle cells that stay inside the window keep their value when it moves;
    newly uncovered cells are unknown. An optional static source (a global cost
    grid, e.g. from the map) is resampled into the window on every move.
    """

    __slots__ = ("_static_source",)

    def __init__(
        self,
        width_m: float,
        height_m: float,
        resolution: float,
        inflation: InflationParams | None = None,
        obstacle_params: ObstacleParams | None = None,
        track_unknown_space: bool = False,
    ) -> None:
        width = max(1, round(width_m / resolution))
        height = max(1, round(height_m / resolution))
        geometry = GridGeometry(
            width, height, resolution, -width * resolution / 2, -height * resolution / 2
        )
        super().__init__(geometry, inflation, obstacle_params, None, track_unknown_space)
        self._static_source: tuple[CostArray, GridGeometry] | None = None

    def set_static_source(self, costs: CostArray, geometry: GridGeometry) -> None:
        """Use a global static cost grid (Nav2 costs) as this window's static layer."""
        self._static_source = (costs, geometry)
        self.static = resample(costs, geometry, self.geometry)
        self.layers_replaced()

    def update_origin(self, robot_x: float, robot_y: float) -> None:
        """Centre the window on the robot; shift the obstacle layer by whole cells."""
        if not (math.isfinite(robot_x) and math.isfinite(robot_y)):
            raise ValueError(f"robot position must be finite, got ({robot_x}, {robot_y})")
        g = self.geometry
        res = g.resolution
        new_x = math.floor((robot_x - g.size_x / 2) / res + 1e-9) * res
        new_y = math.floor((robot_y - g.size_y / 2) / res + 1e-9) * res
        shift_c = round((new_x - g.origin_x) / res)
        shift_r = round((new_y - g.origin_y) / res)
        if shift_c == 0 and shift_r == 0:
            return
        self.obstacles = _shifted(self.obstacles, shift_r, shift_c)
        self.geometry = g.moved_to(g.origin_x + shift_c * res, g.origin_y + shift_r * res)
        if self._static_source is not None:
            self.static = resample(*self._static_source, self.geometry)
            self.layers_replaced()
        else:
            self._shift_master(shift_r, shift_c)

    def _shift_master(self, shift_r: int, shift_c: int) -> None:
        """Move the combined and inflated grids with the window, and re-inflate (at the
        next read, with the cells a scan changes meanwhile) only where that can change
        anything: the new cells and the radius around them, and the radius inside the
        edges the old cells left by (their obstacles no longer inflate anything). Equal
        to a rebuild; a rebuild if one is due anyway."""
        if (
            self._dirty
            or self._base is None
            or self._master is None
            or self._pending
            or self._stale
        ):
            self.layers_replaced()  # pending cells and stale windows are of the old window
            return
        height, width = self.geometry.shape
        bound = self.geometry.cell_distance(self.inflation.inflation_radius)
        if abs(shift_r) + bound >= height // 2 or abs(shift_c) + bound >= width // 2:
            self.layers_replaced()  # most of the window is new: rebuilding is cheaper
            return
        unknown = np.full((1,), NO_INFORMATION, np.uint8)
        fresh = int(combine_max(np.full((1,), self.default_value, np.uint8), unknown)[0])
        self._base = _shifted(self._base, shift_r, shift_c, fill=fresh)
        self._master = _shifted(self._master, shift_r, shift_c)
        self._stale.extend(_bands(shift_r, shift_c, bound, height, width))
        self._last_scan = None
        self._record(None)  # the cells moved: a reader of changed windows starts over


def _bands(shift_r: int, shift_c: int, bound: int, height: int, width: int) -> list[Window]:
    """The windows (row0, row1, col0, col1) to re-inflate after a shift: along each
    axis that moved, the new cells plus ``bound`` on their side, ``bound`` on the other."""
    bands = [(0, height, col0, col1) for col0, col1 in _strips(shift_c, bound, width)]
    bands += [(row0, row1, 0, width) for row0, row1 in _strips(shift_r, bound, height)]
    return bands


def _strips(shift: int, bound: int, size: int) -> list[tuple[int, int]]:
    if shift == 0:
        return []
    new = abs(shift) + bound
    if shift > 0:  # new cells at the high end
        return [(size - new, size), (0, bound)]
    return [(0, new), (size - bound, size)]


def _shifted(grid: CostArray, shift_r: int, shift_c: int, fill: int = NO_INFORMATION) -> CostArray:
    """``out[r, c] = grid[r + shift_r, c + shift_c]`` where defined, ``fill`` elsewhere."""
    height, width = grid.shape
    out = np.full_like(grid, fill)
    src_r = slice(max(0, shift_r), min(height, height + shift_r))
    dst_r = slice(max(0, -shift_r), min(height, height - shift_r))
    src_c = slice(max(0, shift_c), min(width, width + shift_c))
    dst_c = slice(max(0, -shift_c), min(width, width - shift_c))
    if src_r.start < src_r.stop and src_c.start < src_c.stop:
        out[dst_r, dst_c] = grid[src_r, src_c]
    return out
