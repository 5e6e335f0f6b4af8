"""A layered costmap: static + obstacle layers, combined with max, then inflated."""

from __future__ import annotations

import logging
import math
from collections import deque

import numpy as np
import numpy.typing as npt

from .collision import footprint_cost, point_cost, segment_max_cost
from .grid import (
    FREE,
    LETHAL,
    NO_INFORMATION,
    CostArray,
    CostGrid,
    FloatArray,
    GridGeometry,
    IntArray,
)
from .inflation import (
    InflationParams,
    Window,
    bounding_window,
    grown,
    inflate,
    inflate_window,
    spanning,
)
from .obstacle_layer import ObstacleParams, Scan, clear_and_mark, combine_max, same_scan
from .static_layer import StaticParams, occupancy_to_costs

logger = logging.getLogger("aiobt.costmap")
HISTORY = 32  # master versions whose changed window is remembered


class Costmap:
    """Nav2's LayeredCostmap with a static, an obstacle and an inflation layer.

    The master grid is brought up to date lazily, when read. Obstacle cells
    changed by scans or marks are updated incrementally: their combined value
    is recomputed and inflation is redone in the window of the inflation radius
    around them only (the result equals a full rebuild). A new static map or a
    clearing rebuilds everything (a rolling window's move does not: see
    :class:`RollingCostmap`). ``version`` counts the
    master's changes; :meth:`changed_since` says where they were. Without a
    static layer the master starts from ``default_value`` (NO_INFORMATION when
    ``track_unknown_space``, else FREE).
    """

    __slots__ = (
        "_base",
        "_dirty",
        "_history",
        "_last_scan",
        "_master",
        "_pending",
        "_stale",
        "default_value",
        "geometry",
        "inflation",
        "obstacle_params",
        "obstacles",
        "static",
        "static_params",
        "version",
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
        self._base: CostArray | None = None  # static and obstacles combined, not inflated
        self._pending: list[IntArray] = []  # obstacle cells changed since the last refresh
        self._stale: list[Window] = []  # master windows to re-inflate at the next refresh
        self._history: deque[tuple[int, Window | None]] = deque(maxlen=HISTORY)
        self._dirty = True
        self._last_scan: Scan | None = None  # the newest scan, while re-applying it is a no-op
        self.version = 0

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
        self.layers_replaced()

    def update_from_scan(self, scan: Scan) -> int:
        """Clear along the scan's rays and mark its hits in the obstacle layer;
        the number of obstacle cells that changed (0: the master is untouched)."""
        if self._last_scan is not None and same_scan(self._last_scan, scan):
            return 0  # nothing changed the obstacle layer since: it would change nothing
        changed = clear_and_mark(self.obstacles, self.geometry, scan, self.obstacle_params)
        self._obstacles_changed(changed)
        self._last_scan = scan
        return int(changed.size)

    def mark_points(self, xs: npt.ArrayLike, ys: npt.ArrayLike) -> int:
        """Mark world points as lethal obstacles (e.g. from another sensor); the
        number of cells that changed."""
        cols, rows, ok = self.geometry.world_to_cells(np.asarray(xs), np.asarray(ys))
        cells = np.unique(rows[ok] * self.geometry.width + cols[ok])
        changed = cells[self.obstacles.flat[cells] != LETHAL]
        self.obstacles.flat[changed] = LETHAL
        self._obstacles_changed(changed)
        self._last_scan = None
        return int(changed.size)

    def layers_replaced(self) -> None:
        """A layer changed other than by a scan or a mark: rebuild on the next read."""
        self._dirty = True
        self._last_scan = None

    def _obstacles_changed(self, flat: IntArray) -> None:
        if flat.size and not self._dirty:
            self._pending.append(flat)

    # -- clearing (Nav2 ClearCostmapService semantics: the obstacle layer) ---
    def clear_entirely(self) -> None:
        self.obstacles.fill(NO_INFORMATION)
        self.layers_replaced()

    def clear_around(self, x: float, y: float, reset_distance: float) -> None:
        """Reset the obstacle layer inside the square of side ``reset_distance`` at (x, y)."""
        inside = self._square_mask(x, y, reset_distance)
        self.obstacles[inside] = NO_INFORMATION
        self.layers_replaced()

    def clear_except(self, x: float, y: float, reset_distance: float) -> None:
        """Reset the obstacle layer outside the square of side ``reset_distance`` at (x, y)."""
        inside = self._square_mask(x, y, reset_distance)
        self.obstacles[~inside] = NO_INFORMATION
        self.layers_replaced()

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
        """The combined, inflated costs, updated in place (do not modify; use :meth:`snapshot`)."""
        return self._refresh()

    def changed_since(self, version: int) -> Window | None:
        """The window holding every master change after ``version`` (``None``: a
        rebuild, or too long ago to tell). Only meaningful if ``version`` < :attr:`version`."""
        self._refresh()
        windows = [window for v, window in self._history if v > version]
        if len(windows) != self.version - version or any(w is None for w in windows):
            return None
        known = [w for w in windows if w is not None]
        return spanning(known)

    def _refresh(self) -> CostArray:
        if self._dirty or self._master is None or self._base is None:
            self._rebuild()
        elif self._pending or self._stale:
            pending = self._pending or [np.empty(0, dtype=np.intp)]
            self._update_cells(np.unique(np.concatenate(pending)))
        assert self._master is not None
        return self._master

    def _rebuild(self) -> None:
        start = (
            self.static.copy()
            if self.static is not None
            else np.full(self.geometry.shape, self.default_value, dtype=np.uint8)
        )
        self._base = combine_max(start, self.obstacles)
        self._master = inflate(self._base, self.geometry, self.inflation)
        self._dirty = False
        self._pending.clear()
        self._stale.clear()
        self._record(None)

    def _update_cells(self, flat: IntArray) -> None:
        """Recombine the changed obstacle cells and re-inflate around those whose
        combined value changed, together with the stale windows (one inflation over
        the window holding them all)."""
        assert self._base is not None
        assert self._master is not None
        self._pending.clear()
        windows, self._stale = self._stale, []
        changed = self._recombine(flat)
        if changed.size:
            bound = self.geometry.cell_distance(self.inflation.inflation_radius)
            windows.append(
                grown(bounding_window(changed, self.geometry.width), bound, self.geometry.shape)
            )
        if not windows:
            return
        window = spanning(windows)
        row0, row1, col0, col1 = window
        before = self._master[row0:row1, col0:col1].copy()
        inflate_window(self._base, self._master, window, self.geometry, self.inflation)
        moved = np.flatnonzero(before != self._master[row0:row1, col0:col1])
        if moved.size:
            inner = bounding_window(moved, col1 - col0)
            self._record((inner[0] + row0, inner[1] + row0, inner[2] + col0, inner[3] + col0))

    def _recombine(self, flat: IntArray) -> IntArray:
        """Static and obstacles combined again at ``flat``; the cells whose value changed."""
        assert self._base is not None
        start = (
            self.static.flat[flat]
            if self.static is not None
            else np.full(flat.shape, self.default_value, dtype=np.uint8)
        )
        combined = combine_max(start, self.obstacles.flat[flat])
        differs = combined != self._base.flat[flat]
        changed: IntArray = flat[differs]
        self._base.flat[changed] = combined[differs]
        return changed

    def _record(self, window: Window | None) -> None:
        self.version += 1
        self._history.append((self.version, window))

    def snapshot(self) -> CostGrid:
        """An immutable copy of the master grid, safe to plan on in another thread."""
        return CostGrid(self.geometry, self.master.copy())

    def point_cost(self, x: float, y: float) -> int:
        return point_cost(CostGrid(self.geometry, self.master), x, y)

    def segment_max_cost(self, x0: float, y0: float, x1: float, y1: float) -> int:
        return segment_max_cost(CostGrid(self.geometry, self.master), x0, y0, x1, y1)

    def footprint_cost(self, x: float, y: float, yaw: float, footprint: FloatArray) -> int:
        return footprint_cost(CostGrid(self.geometry, self.master), x, y, yaw, footprint)
