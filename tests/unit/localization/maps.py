"""Small maps for the filter's unit tests."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from aiobt_services.localization.likelihood_field import LikelihoodField
from aiobt_services.localization.params import AmclParams

RES = 0.05


def room(width_m: float = 6.0, height_m: float = 4.0) -> npt.NDArray[np.int8]:
    """A walled rectangle (origin 0, 0) with one inner wall stub and a pillar, so no
    pose is ambiguous by symmetry."""
    rows, cols = round(height_m / RES), round(width_m / RES)
    cells = np.zeros((rows, cols), dtype=np.int8)
    cells[0, :] = cells[-1, :] = cells[:, 0] = cells[:, -1] = 100
    cells[: rows // 2, cols // 3] = 100  # a wall stub from the bottom
    cells[rows - 20 : rows - 14, cols - 30 : cols - 24] = 100  # a pillar, top right
    return cells


def field(
    cells: npt.NDArray[np.int8] | None = None, params: AmclParams | None = None
) -> LikelihoodField:
    p = params or AmclParams()
    return LikelihoodField.build(
        room() if cells is None else cells,
        RES,
        (0.0, 0.0),
        max_dist=p.laser_likelihood_max_dist,
        z_hit=p.z_hit,
        sigma_hit=p.sigma_hit,
    )


def cast(
    cells: npt.NDArray[np.int8],
    pose: tuple[float, float, float],
    bearings: npt.NDArray[np.float64],
    range_max: float = 12.0,
) -> npt.NDArray[np.float64]:
    """Ranges to the first occupied cell along each bearing (marching, 1/4 cell)."""
    steps = np.arange(1, int(range_max / (RES / 4))) * (RES / 4)
    angles = pose[2] + bearings
    xs = pose[0] + steps[np.newaxis, :] * np.cos(angles)[:, np.newaxis]
    ys = pose[1] + steps[np.newaxis, :] * np.sin(angles)[:, np.newaxis]
    col, row = np.floor(xs / RES).astype(int), np.floor(ys / RES).astype(int)
    inside = (row >= 0) & (row < cells.shape[0]) & (col >= 0) & (col < cells.shape[1])
    hit = np.zeros_like(inside)
    hit[inside] = cells[row[inside], col[inside]] == 100
    first = np.where(hit.any(axis=1), hit.argmax(axis=1), len(steps) - 1)
    return np.where(hit.any(axis=1), steps[first], np.inf)
