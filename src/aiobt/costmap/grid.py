"""Cost values and grid geometry shared by every costmap layer.

Arrays are indexed ``[row, col]`` with row = y and col = x, row 0 at the map
origin (the OccupancyGrid convention: ``data[row * width + col]``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

FREE = 0
INSCRIBED = 253
LETHAL = 254
NO_INFORMATION = 255

CostArray = npt.NDArray[np.uint8]
FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]


@dataclass(frozen=True, slots=True)
class GridGeometry:
    """Size, resolution and origin (world position of cell (0, 0)'s corner)."""

    width: int
    height: int
    resolution: float
    origin_x: float = 0.0
    origin_y: float = 0.0

    def __post_init__(self) -> None:
        if self.width <= 0 or self.height <= 0:
            raise ValueError(f"grid size must be positive, got {self.width}x{self.height}")
        if not (math.isfinite(self.resolution) and self.resolution > 0.0):
            raise ValueError(f"grid resolution must be > 0, got {self.resolution!r}")
        if not (math.isfinite(self.origin_x) and math.isfinite(self.origin_y)):
            raise ValueError(f"grid origin must be finite, got ({self.origin_x}, {self.origin_y})")

    @property
    def shape(self) -> tuple[int, int]:
        """Array shape ``(height, width)``."""
        return (self.height, self.width)

    @property
    def size_x(self) -> float:
        return self.width * self.resolution

    @property
    def size_y(self) -> float:
        return self.height * self.resolution

    def world_to_cell(self, x: float, y: float) -> tuple[int, int] | None:
        """``(col, row)`` of the cell holding world point (x, y), or None outside."""
        if not (math.isfinite(x) and math.isfinite(y)):
            return None
        col = math.floor((x - self.origin_x) / self.resolution)
        row = math.floor((y - self.origin_y) / self.resolution)
        if 0 <= col < self.width and 0 <= row < self.height:
            return (col, row)
        return None

    def world_to_cells(
        self, xs: FloatArray, ys: FloatArray
    ) -> tuple[IntArray, IntArray, BoolArray]:
        """Vectorised :meth:`world_to_cell`: cols, rows and an in-bounds mask.

        Out-of-bounds (and non-finite) entries get col = row = 0 and mask False.
        """
        fx = np.floor((np.asarray(xs, dtype=np.float64) - self.origin_x) / self.resolution)
        fy = np.floor((np.asarray(ys, dtype=np.float64) - self.origin_y) / self.resolution)
        valid = np.isfinite(fx) & np.isfinite(fy)
        valid &= (fx >= 0) & (fx < self.width) & (fy >= 0) & (fy < self.height)
        cols = np.where(valid, fx, 0).astype(np.intp)
        rows = np.where(valid, fy, 0).astype(np.intp)
        return cols, rows, valid

    def cell_to_world(self, col: float, row: float) -> tuple[float, float]:
        """World coordinates of a cell's centre."""
        return (
            self.origin_x + (col + 0.5) * self.resolution,
            self.origin_y + (row + 0.5) * self.resolution,
        )

    def cells_to_world(
        self, cols: npt.ArrayLike, rows: npt.ArrayLike
    ) -> tuple[FloatArray, FloatArray]:
        xs = self.origin_x + (np.asarray(cols, dtype=np.float64) + 0.5) * self.resolution
        ys = self.origin_y + (np.asarray(rows, dtype=np.float64) + 0.5) * self.resolution
        return xs, ys

    def contains_cell(self, col: int, row: int) -> bool:
        return 0 <= col < self.width and 0 <= row < self.height

    def contains_world(self, x: float, y: float) -> bool:
        return self.world_to_cell(x, y) is not None

    def cell_distance(self, meters: float) -> int:
        """Nav2's ``cellDistance``: meters rounded up to whole cells."""
        return int(max(0.0, math.ceil(meters / self.resolution)))

    def moved_to(self, origin_x: float, origin_y: float) -> GridGeometry:
        """The same grid with another origin."""
        return GridGeometry(self.width, self.height, self.resolution, origin_x, origin_y)


@dataclass(frozen=True, slots=True)
class CostGrid:
    """An immutable snapshot: geometry plus a ``(height, width)`` uint8 cost array."""

    geometry: GridGeometry
    costs: CostArray

    def __post_init__(self) -> None:
        if self.costs.shape != self.geometry.shape:
            raise ValueError(f"costs shape {self.costs.shape} != grid shape {self.geometry.shape}")
        if self.costs.dtype != np.uint8:
            raise ValueError(f"costs dtype must be uint8, got {self.costs.dtype}")
