"""The obstacle layer: marking and clearing from 2D laser scans by ray tracing."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from .grid import (
    FREE,
    LETHAL,
    NO_INFORMATION,
    BoolArray,
    CostArray,
    FloatArray,
    GridGeometry,
    IntArray,
)

# m beyond a beam's end where its hit is marked (see clear_and_mark): more than the rounding
# of the robot's ranges (4 decimals, 5e-5 m either way), far less than a cell
HIT_DEPTH = 1e-4


@dataclass(frozen=True, slots=True)
class ObstacleParams:
    """Nav2 ``obstacle_layer`` observation-source parameters (meters)."""

    obstacle_max_range: float = 2.5
    obstacle_min_range: float = 0.0
    raytrace_max_range: float = 3.0
    raytrace_min_range: float = 0.0
    inf_is_valid: bool = True


@dataclass(frozen=True, slots=True)
class Scan:
    """A planar laser scan taken at a sensor pose in the costmap's frame."""

    sensor_x: float
    sensor_y: float
    sensor_yaw: float
    angle_min: float
    angle_increment: float
    ranges: FloatArray
    range_min: float = 0.0
    range_max: float = math.inf

    @classmethod
    def create(
        cls,
        pose: tuple[float, float, float],
        angle_min: float,
        angle_increment: float,
        ranges: npt.ArrayLike,
        range_min: float = 0.0,
        range_max: float = math.inf,
    ) -> Scan:
        values = np.asarray(ranges, dtype=np.float64).ravel()
        return cls(*pose, angle_min, angle_increment, values, range_min, range_max)


def same_scan(a: Scan, b: Scan) -> bool:
    """The same readings from the same sensor pose (re-applying one is a no-op)."""
    head = (a.sensor_x, a.sensor_y, a.sensor_yaw, a.angle_min, a.angle_increment, a.range_min,
            a.range_max)  # fmt: skip
    other = (b.sensor_x, b.sensor_y, b.sensor_yaw, b.angle_min, b.angle_increment, b.range_min,
             b.range_max)  # fmt: skip
    return head == other and np.array_equal(a.ranges, b.ranges)


def _rays(
    scan: Scan, params: ObstacleParams
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Unit directions, clearing lengths and hit flags of the usable rays."""
    ranges = scan.ranges.copy()
    angles: FloatArray = (
        scan.sensor_yaw
        + scan.angle_min
        + scan.angle_increment * np.arange(ranges.size, dtype=np.float64)
    )
    no_return = np.isinf(ranges) | (ranges >= scan.range_max)
    if params.inf_is_valid:
        ranges = np.where(np.isinf(ranges), scan.range_max, ranges)
    usable = np.isfinite(ranges) & (ranges >= scan.range_min)
    hit = usable & ~no_return
    hit &= (ranges <= params.obstacle_max_range) & (ranges >= params.obstacle_min_range)
    traced = np.where(usable & (ranges >= params.raytrace_min_range), ranges, 0.0)
    clear_len: FloatArray = np.minimum(traced, params.raytrace_max_range).astype(np.float64)
    ranges = np.where(usable, ranges, 0.0).astype(np.float64)
    return angles, ranges, clear_len, hit.astype(np.float64)


def clear_and_mark(
    grid: CostArray, geometry: GridGeometry, scan: Scan, params: ObstacleParams
) -> IntArray:
    """Ray-trace free space along every ray, then mark the hit cells LETHAL (in place).

    Rays are sampled every half cell; the cell of a hit is never cleared by
    its own ray. A hit is marked :data:`HIT_DEPTH` beyond the beam's end: a beam
    ends on the surface of what it hit, and a surface on a cell boundary (a
    map's walls, the simulator's rasterized ones) would otherwise mark the free
    cell before it or the obstacle's own by the range's rounding, a mark that
    comes and goes as the robot moves (on the office world, replaying 145 folds
    of a drive: 139 changed the costmap, 17 with the depth). Points outside the
    grid are ignored. Returns the flat indices of the cells whose value changed
    (empty when the scan changed nothing).

    The samples are taken as one (rays x samples) matrix of cell coordinates (float32:
    the sensor's cell plus the ray's direction in cells times the distance, about
    1e-5 of a cell off on a window of a hundred cells: a sample that close to a cell's
    edge may fall in the cell beside), those beyond a ray's length masked, and the
    cells collected in per-cell masks: no gather of the samples, no sort.
    """
    if not (math.isfinite(scan.sensor_x) and math.isfinite(scan.sensor_y)):
        raise ValueError(f"scan sensor pose must be finite, got ({scan.sensor_x}, {scan.sensor_y})")
    angles, ranges, clear_len, hit = _rays(scan, params)
    res = geometry.resolution
    dx, dy = np.cos(angles) / res, np.sin(angles) / res  # cells per m along each ray
    sensor = ((scan.sensor_x - geometry.origin_x) / res, (scan.sensor_y - geometry.origin_y) / res)
    flat = grid.reshape(-1)
    step = res * 0.5
    longest = float(clear_len.max(initial=0.0))
    cleared = np.zeros(flat.size + 1, dtype=np.bool_)  # the last entry: outside the grid
    if longest > 0.0:
        t = np.arange(0.0, longest, step).astype(np.float32)
        ends = (clear_len - np.where(hit > 0, step, 0.0)).astype(np.float32)
        inside = t[None, :] < ends[:, None]
        cols = np.multiply.outer(dx.astype(np.float32), t)
        rows = np.multiply.outer(dy.astype(np.float32), t)
        cols += np.float32(sensor[0])
        rows += np.float32(sensor[1])
        cleared[_cell_index(geometry, cols, rows, inside)] = True
    marks = hit > 0
    marked = np.zeros(flat.size + 1, dtype=np.bool_)
    # the hits in float64, as the points they are: (sensor + depth along the ray - origin)
    depth = ranges[marks] + HIT_DEPTH
    hit_x = (scan.sensor_x + np.cos(angles[marks]) * depth - geometry.origin_x) / res
    hit_y = (scan.sensor_y + np.sin(angles[marks]) * depth - geometry.origin_y) / res
    marked[_cell_index(geometry, hit_x, hit_y)] = True
    clear_mask, mark_mask = cleared[:-1], marked[:-1]
    cells = np.flatnonzero(clear_mask | mark_mask)
    before = flat[cells]
    flat[clear_mask] = FREE
    flat[mark_mask] = LETHAL
    changed: IntArray = cells[flat[cells] != before]
    return changed


def _cell_index(
    geometry: GridGeometry,
    cols: npt.NDArray[np.floating[Any]],
    rows: npt.NDArray[np.floating[Any]],
    keep: BoolArray | None = None,
) -> IntArray:
    """Flat cell index of each point at cell coordinates (``cols``, ``rows``) (finite,
    inside the grid and kept); ``width * height`` for the others (one past the grid's
    last cell). Coordinates >= 0 inside: truncating floors."""
    ok = cols >= 0
    ok &= cols < geometry.width
    ok &= rows >= 0
    ok &= rows < geometry.height
    if keep is not None:
        ok &= keep
    with np.errstate(invalid="ignore"):  # non-finite points are cast but not kept
        index: IntArray = rows.astype(np.intp)
        index *= geometry.width
        index += cols.astype(np.intp)
    index[~ok] = geometry.width * geometry.height
    return index


def combine_max(master: CostArray, layer: CostArray) -> CostArray:
    """Nav2 ``updateWithMax``: unknown layer cells are skipped; otherwise the
    layer wins over unknown master cells and over lower costs."""
    known = layer != NO_INFORMATION
    take = known & ((master == NO_INFORMATION) | (master < layer))
    return np.where(take, layer, master).astype(np.uint8)
