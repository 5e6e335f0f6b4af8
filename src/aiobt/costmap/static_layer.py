"""The static layer: an OccupancyGrid's cells (-1 unknown, 0..100) as Nav2 costs."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .grid import FREE, LETHAL, NO_INFORMATION, CostArray, GridGeometry


@dataclass(frozen=True, slots=True)
class StaticParams:
    """Nav2 ``static_layer`` / layered costmap interpretation parameters."""

    lethal_threshold: int = 100
    unknown_cost_value: int = -1
    track_unknown_space: bool = True
    trinary_costmap: bool = True


def occupancy_to_costs(
    occupancy: npt.ArrayLike, geometry: GridGeometry, params: StaticParams | None = None
) -> CostArray:
    """Nav2 ``StaticLayer::interpretValue`` on a whole grid.

    ``occupancy`` is the OccupancyGrid data, flat (row-major, ``width * height``
    values) or already shaped ``(height, width)``.
    """
    params = params or StaticParams()
    values = np.asarray(occupancy)
    if values.size != geometry.width * geometry.height:
        raise ValueError(
            f"occupancy has {values.size} cells, expected {geometry.width}x{geometry.height}"
        )
    values = values.reshape(geometry.shape).astype(np.int16)
    bad = (values != params.unknown_cost_value) & ((values < 0) | (values > 100))
    if bad.any():
        row, col = np.argwhere(bad)[0]
        raise ValueError(
            f"occupancy value {values[row, col]} at cell (col={col}, row={row}) "
            "is outside -1 and 0..100"
        )
    unknown = values == params.unknown_cost_value
    if params.trinary_costmap:
        costs = np.where(values >= params.lethal_threshold, LETHAL, FREE)
    else:
        scaled = values.astype(np.float64) * (LETHAL / params.lethal_threshold)
        costs = np.where(values >= params.lethal_threshold, LETHAL, np.clip(scaled, 0, LETHAL - 1))
    costs = np.where(unknown, NO_INFORMATION if params.track_unknown_space else FREE, costs)
    result: CostArray = costs.astype(np.uint8)
    return result


def resample(source: CostArray, source_geometry: GridGeometry, target: GridGeometry) -> CostArray:
    """Costs of ``source`` at each cell centre of ``target`` (unknown outside the source)."""
    xs, ys = target.cells_to_world(np.arange(target.width), np.arange(target.height))
    src_cols = np.floor((xs - source_geometry.origin_x) / source_geometry.resolution)
    src_rows = np.floor((ys - source_geometry.origin_y) / source_geometry.resolution)
    col_ok = (src_cols >= 0) & (src_cols < source_geometry.width)
    row_ok = (src_rows >= 0) & (src_rows < source_geometry.height)
    src_cols = src_cols.astype(np.intp)
    src_rows = src_rows.astype(np.intp)
    out = np.full(target.shape, NO_INFORMATION, dtype=np.uint8)
    out[np.ix_(row_ok, col_ok)] = source[np.ix_(src_rows[row_ok], src_cols[col_ok])]
    return out
