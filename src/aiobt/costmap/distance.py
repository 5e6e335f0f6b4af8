"""Exact Euclidean distance (in cells) to the nearest marked cell, up to a bound.

scipy is not a dependency, so this is a separable transform in numpy: an exact
1D distance along each row (index accumulation), then a minimum over the
``2 * bound + 1`` row offsets. The result is exact for distances <= ``bound``;
farther cells get ``inf``.
"""

from __future__ import annotations

import numpy as np

from .grid import BoolArray, FloatArray


def row_distances(mask: BoolArray) -> FloatArray:
    """Distance along each row to the nearest True cell in the same row (inf if none)."""
    height, width = mask.shape
    cols = np.broadcast_to(np.arange(width, dtype=np.int64), (height, width))
    big = np.int64(4 * (width + height) + 10)
    left = np.maximum.accumulate(np.where(mask, cols, -big), axis=1)
    right = np.minimum.accumulate(np.where(mask, cols, big)[:, ::-1], axis=1)[:, ::-1]
    nearest = np.minimum(cols - left, right - cols).astype(np.float64)
    nearest[nearest > 2 * (width + height)] = np.inf
    return nearest


def squared_distance_transform(mask: BoolArray, bound: int) -> FloatArray:
    """Squared Euclidean distance in cells (a whole number) from each cell to the nearest
    True cell of ``mask``: exact where the distance is <= ``bound``; beyond it, any value
    > ``bound ** 2`` (``inf`` or a whole number)."""
    if mask.ndim != 2:
        raise ValueError(f"mask must be 2D, got shape {mask.shape}")
    bound = max(0, int(bound))
    height = mask.shape[0]
    horizontal = row_distances(mask)
    horizontal[horizontal > bound] = np.inf
    squared = horizontal * horizontal
    best = squared.copy()
    for dy in range(1, min(bound, height - 1) + 1):
        shift = float(dy * dy)
        np.minimum(best[dy:], squared[:-dy] + shift, out=best[dy:])
        np.minimum(best[:-dy], squared[dy:] + shift, out=best[:-dy])
    return best


def distance_transform(mask: BoolArray, bound: int) -> FloatArray:
    """Euclidean distance in cells from each cell to the nearest True cell of ``mask``.

    Exact where the distance is <= ``bound``; ``inf`` beyond it.
    """
    distances: FloatArray = np.sqrt(squared_distance_transform(mask, bound))
    distances[distances > max(0, int(bound))] = np.inf
    return distances
