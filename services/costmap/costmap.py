"""A layered costmap: static + obstacle layers, combined with max, then inflated."""

from __future__ import annotations

import logging
import math

import numpy as np
import numpy.typing as npt

from .collision import footprint_cost, point_cost, segment_max_cost
from .grid import FREE, LETHAL, NO_INFORMATION, CostArray, CostGrid, FloatArray, GridGeometry
from .inflation import InflationParams, inflate
from .obstacle_layer import ObstacleParams, Scan, clear_and_mark, combine_max
from .static_layer import StaticParams, occupancy_to_costs

logger = logging.getLogger("aiobt_services.costmap")


class Costmap:
    """Nav2's LayeredCostmap with a static, an obstacle and an inflation layer.

    The master grid is recomputed lazily when a layer changed. Without a
    static layer the master starts from ``default_value`` (NO_INFORMATION when
    ``track_unknown_space``, else FREE).
    """

    __slots__ = (
        "_dirty",
        "_master",
        "default_value",
        "geometry",
        "inflation",
        "obstacle_params",
        "obstacles",
        "static",
        "static_params",
    )

    def __init__(
        self,
        geometry: GridGeometry,
        inflation: InflationParams | None = None,
        obstacle_params: ObstacleParams | None = None,
        static_params: StaticParams | None = None,
        track_unknown_space: bool = True,
    ) -> None:
        self.geometry = geometry
        self.inflation = inflation or InflationParams()
        self.obstacle_params = obstacle_params or ObstacleParams()
        self.static_params = static_params or StaticParams()
        self.default_value = NO_INFORMATION if track_unknown_space else FREE
        self.static: CostArray | None = None
        self.obstacles: CostArray = np.full(geometry.shape, NO_INFORMATION, dtype=np.uint8)
        self._master: CostArray | None = None
        self._dirty = True

    @classmethod
    def from_occupancy(
        cls, occupancy: npt.ArrayLike, geometry: GridGeometry, **kwargs: object
    ) -> Costmap:
        """A costmap sized to the map, with its static layer set."""
        costmap = cls(geometry, **kwargs)  # type: ignore[arg-type]
        costmap.set_static(occupancy, geometry)
        return costmap

    # -- layers ---------------------------------------------------------------
    def set_static(self, occupancy: npt.ArrayLike, geometry: GridGeometry) -> None:
        """Replace the static layer; a differently sized map resizes the costmap
        (and resets the obstacle layer, as Nav2 does on a new map)."""
        costs = occupancy_to_costs(occupancy, geometry, self.static_params)
        if geometry != self.geometry:
            logger.info(
                "costmap resized to %dx%d @ %.3f m",
                geometry.width,
                geometry.height,
                geometry.resolution,
            )
            self.geometry = geometry
            self.obstacles = np.full(geometry.shape, NO_INFORMATION, dtype=np.uint8)
        self.static = costs
        self._dirty = True

    def update_from_scan(self, scan: Scan) -> None:
        """Clear along the scan's rays and mark its hits in the obstacle layer."""
        clear_and_mark(self.obstacles, self.geometry, scan, self.obstacle_params)
        self._dirty = True

    def mark_points(self, xs: npt.ArrayLike, ys: npt.ArrayLike) -> None:
        """Mark world points as lethal obstacles (e.g. from another sensor)."""
        cols, rows, ok = self.geometry.world_to_cells(np.asarray(xs), np.asarray(ys))
        self.obstacles[rows[ok], cols[ok]] = LETHAL
        self._dirty = True

    # -- clearing (Nav2 ClearCostmapService semantics: the obstacle layer) ---
    def clear_entirely(self) -> None:
        self.obstacles.fill(NO_INFORMATION)
        self._dirty = True

    def clear_around(self, x: float, y: float, reset_distance: float) -> None:
        """Reset the obstacle layer inside the square of side ``reset_distance`` at (x, y)."""
        inside = self._square_mask(x, y, reset_distance)
        self.obstacles[inside] = NO_INFORMATION
        self._dirty = True

    def clear_except(self, x: float, y: float, reset_distance: float) -> None:
        """Reset the obstacle layer outside the square of side ``reset_distance`` at (x, y)."""
        inside = self._square_mask(x, y, reset_distance)
        self.obstacles[~inside] = NO_INFORMATION
        self._dirty = True

    def _square_mask(self, x: float, y: float, side: float) -> npt.NDArray[np.bool_]:
        if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(side) and side >= 0):
            raise ValueError(
                f"clear region needs a finite pose and side >= 0, got ({x}, {y}, {side})"
            )
        half = side / 2.0
        g = self.geometry
        xs, ys = g.cells_to_world(np.arange(g.width), np.arange(g.height))
        cols_in = np.abs(xs - x) <= half
        rows_in = np.abs(ys - y) <= half
        mask: npt.NDArray[np.bool_] = rows_in[:, None] & cols_in[None, :]
        return mask

    # -- the master grid ------------------------------------------------------
    @property
    def master(self) -> CostArray:
        """The combined, inflated costs (do not modify; use :meth:`snapshot`)."""
        if self._dirty or self._master is None:
            base = (
                self.static.copy()
                if self.static is not None
                else np.full(self.geometry.shape, self.default_value, dtype=np.uint8)
            )
            self._master = inflate(combine_max(base, self.obstacles), self.geometry, self.inflation)
            self._dirty = False
        return self._master

    def snapshot(self) -> CostGrid:
        """An immutable copy of the master grid, safe to plan on in another thread."""
        return CostGrid(self.geometry, self.master.copy())

    def point_cost(self, x: float, y: float) -> int:
        return point_cost(CostGrid(self.geometry, self.master), x, y)

    def segment_max_cost(self, x0: float, y0: float, x1: float, y1: float) -> int:
        return segment_max_cost(CostGrid(self.geometry, self.master), x0, y0, x1, y1)

    def footprint_cost(self, x: float, y: float, yaw: float, footprint: FloatArray) -> int:
        return footprint_cost(CostGrid(self.geometry, self.master), x, y, yaw, footprint)
