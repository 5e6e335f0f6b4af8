"""The map as AMCL's laser model sees it: for every cell the distance to the
nearest occupied cell (one Euclidean distance transform per map, capped at
``laser_likelihood_max_dist``), turned once into the ``z_hit`` Gaussian term,
and the free cells that random particles are drawn from.

Cells follow AMCL's ``convertMap``: 0 is free, 100 occupied, anything else
unknown (neither). Row 0 of the grid is at the map origin (the bottom).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from .se2 import FloatArray

FREE, OCCUPIED = 0, 100


class MapError(ValueError):
    """A map the filter cannot use (the message says why)."""


@dataclass(slots=True, frozen=True)
class LikelihoodField:
    """Per-cell ``z_hit * exp(-d^2 / (2 sigma_hit^2))``, the distance ``d`` itself (for
    beam skipping) and the free cells' centres."""

    resolution: float
    origin_x: float
    origin_y: float
    hit_term: npt.NDArray[np.float64]  # (rows, cols)
    off_map_term: float  # the same term at the capped distance (AMCL: off-map = max)
    cells: npt.NDArray[np.int8]
    free_xy: FloatArray  # (M, 2) centres of free cells
    padded: npt.NDArray[np.float32]  # hit_term framed by one cell of off_map_term, flat
    padded_dist: npt.NDArray[np.float32]  # the capped distance framed by +inf (off map), flat

    @classmethod
    def build(
        cls,
        cells: npt.NDArray[np.int8],
        resolution: float,
        origin: tuple[float, float],
        *,
        max_dist: float,
        z_hit: float,
        sigma_hit: float,
    ) -> LikelihoodField:
        """From an occupancy grid (rows from the origin up), AMCL's parameters."""
        cells = np.asarray(cells, dtype=np.int8)
        if cells.ndim != 2 or cells.size == 0:
            raise MapError(f"map must be a non-empty 2-D grid, got shape {cells.shape}")
        if not (np.isfinite(resolution) and resolution > 0.0):
            raise MapError(f"map resolution must be > 0, got {resolution}")
        occupied = cells == OCCUPIED
        free_rows, free_cols = np.nonzero(cells == FREE)
        if free_rows.size == 0:
            raise MapError("map has no free cell: nowhere to put the robot")
        if occupied.any():
            dist = ndimage.distance_transform_edt(~occupied) * resolution
        else:
            dist = np.full(cells.shape, max_dist)
        dist = np.minimum(dist, max_dist)
        denom = 2.0 * sigma_hit * sigma_hit
        free_xy = np.stack(
            [
                origin[0] + (free_cols + 0.5) * resolution,
                origin[1] + (free_rows + 0.5) * resolution,
            ],
            axis=1,
        )
        hit_term = z_hit * np.exp(-(dist * dist) / denom)
        off_map = float(z_hit * np.exp(-(max_dist * max_dist) / denom))
        padded = np.pad(hit_term, 1, constant_values=off_map).astype(np.float32)
        padded_dist = np.pad(dist, 1, constant_values=np.inf).astype(np.float32)
        return cls(
            resolution=float(resolution),
            origin_x=float(origin[0]),
            origin_y=float(origin[1]),
            hit_term=hit_term,
            off_map_term=off_map,
            cells=cells,
            free_xy=free_xy.astype(np.float64),
            padded=padded.ravel(),
            padded_dist=padded_dist.ravel(),
        )

    @property
    def shape(self) -> tuple[int, int]:
        rows, cols = self.cells.shape
        return rows, cols

    def cell_index(
        self, x: FloatArray, y: FloatArray
    ) -> tuple[npt.NDArray[np.intp], npt.NDArray[np.intp], npt.NDArray[np.bool_]]:
        """(row, col, inside) of points; ``inside`` False off the map."""
        col = np.floor((np.asarray(x) - self.origin_x) / self.resolution).astype(np.intp)
        row = np.floor((np.asarray(y) - self.origin_y) / self.resolution).astype(np.intp)
        rows, cols = self.shape
        inside = (row >= 0) & (row < rows) & (col >= 0) & (col < cols)
        return row, col, inside

    def flat_index(
        self, x: npt.NDArray[np.floating[Any]], y: npt.NDArray[np.floating[Any]]
    ) -> npt.NDArray[np.intp]:
        """Indices of points (any shape) into the framed grids (``padded``,
        ``padded_dist``): off the map, clipped into the frame of off-map cells."""
        rows, cols = self.shape
        inv = 1.0 / self.resolution
        col = np.clip(np.floor((x - self.origin_x) * inv), -1, cols).astype(np.intp) + 1
        row = np.clip(np.floor((y - self.origin_y) * inv), -1, rows).astype(np.intp) + 1
        index: npt.NDArray[np.intp] = row * (cols + 2) + col
        return index

    def hit_terms(
        self, x: npt.NDArray[np.floating[Any]], y: npt.NDArray[np.floating[Any]]
    ) -> npt.NDArray[np.float32]:
        """The ``z_hit`` term at beam end points (any shape); off the map the capped one."""
        terms: npt.NDArray[np.float32] = self.padded[self.flat_index(x, y)]
        return terms

    def where(self, x: float, y: float) -> str:
        """Why a robot cannot be at (x, y): '' if it can (on the map, not in a wall)."""
        row, col, inside = self.cell_index(np.array([x]), np.array([y]))
        if not inside[0]:
            rows, cols = self.shape
            x1 = self.origin_x + cols * self.resolution
            y1 = self.origin_y + rows * self.resolution
            return (
                f"({x:.2f}, {y:.2f}) is off the map (x {self.origin_x:g}..{x1:g}, "
                f"y {self.origin_y:g}..{y1:g})"
            )
        if self.cells[row[0], col[0]] == OCCUPIED:
            return f"({x:.2f}, {y:.2f}) is in an occupied cell (a wall)"
        return ""

    def random_free_poses(self, count: int, rng: np.random.Generator) -> FloatArray:
        """``count`` poses uniform over the free cells (jittered within the cell), any
        heading: AMCL's ``uniformPoseGenerator``."""
        picks = self.free_xy[rng.integers(0, len(self.free_xy), count)]
        jitter = rng.uniform(-0.5, 0.5, (count, 2)) * self.resolution
        yaw = rng.uniform(-np.pi, np.pi, count)
        return np.column_stack([picks + jitter, yaw]).astype(np.float64)
