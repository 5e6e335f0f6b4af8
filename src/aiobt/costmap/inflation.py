"""The inflation layer: Nav2's exponential cost decay around lethal cells."""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .distance import squared_distance_transform
from .grid import INSCRIBED, LETHAL, NO_INFORMATION, CostArray, FloatArray, GridGeometry, IntArray


@dataclass(frozen=True, slots=True)
class InflationParams:
    """Nav2 ``inflation_layer`` parameters (meters, 1/meters)."""

    inscribed_radius: float = 0.22
    inflation_radius: float = 0.55
    cost_scaling_factor: float = 3.0
    inflate_unknown: bool = False
    inflate_around_unknown: bool = False

    def __post_init__(self) -> None:
        for name in ("inscribed_radius", "inflation_radius", "cost_scaling_factor"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"InflationParams.{name} must be finite and >= 0, got {value!r}")


def costs_from_distance(distance_m: FloatArray, params: InflationParams) -> CostArray:
    """Nav2's ``computeCost`` for every cell: LETHAL at 0, INSCRIBED inside the
    inscribed radius, ``(INSCRIBED - 1) * exp(-factor * (d - inscribed))`` beyond."""
    with np.errstate(over="ignore", invalid="ignore"):
        decay = (INSCRIBED - 1) * np.exp(
            -params.cost_scaling_factor * (distance_m - params.inscribed_radius)
        )
    decay = np.where(np.isfinite(distance_m), decay, 0.0)
    costs = np.where(distance_m <= params.inscribed_radius, float(INSCRIBED), decay)
    costs = np.where(distance_m == 0.0, float(LETHAL), costs)
    return np.clip(costs, 0, LETHAL).astype(np.uint8)


@functools.lru_cache(maxsize=16)
def _cost_table(bound: int, resolution: float, params: InflationParams) -> CostArray:
    """The cost at each squared cell distance 0 .. ``bound ** 2``, then 0 (farther):
    :func:`costs_from_distance` of the same distances, computed once per parameters."""
    squared = np.arange(bound * bound + 2, dtype=np.float64)
    distance_m = np.sqrt(squared) * resolution
    distance_m[-1] = np.inf
    return costs_from_distance(distance_m, params)


def inflate(master: CostArray, geometry: GridGeometry, params: InflationParams) -> CostArray:
    """Return ``master`` with inflation applied (Nav2 InflationLayer::updateCosts).

    Seeds are LETHAL cells (and unknown ones with ``inflate_around_unknown``).
    Unknown cells stay unknown unless the inflated cost reaches INSCRIBED (or
    any cost with ``inflate_unknown``); known cells take the maximum.
    """
    seeds = master == LETHAL
    if params.inflate_around_unknown:
        seeds |= master == NO_INFORMATION
    if not seeds.any():
        return master.copy()
    bound = geometry.cell_distance(params.inflation_radius)
    squared = squared_distance_transform(seeds, bound)  # whole cells squared: a table index
    beyond = bound * bound + 1  # the table's last entry: farther than the bound, no cost
    index = np.minimum(squared, beyond, out=squared).astype(np.intp)
    inflated = _cost_table(bound, geometry.resolution, params)[index]
    unknown = master == NO_INFORMATION
    threshold = 1 if params.inflate_unknown else INSCRIBED
    result = np.maximum(master, inflated)
    result[unknown] = np.where(inflated[unknown] >= threshold, inflated[unknown], NO_INFORMATION)
    return result


Window = tuple[int, int, int, int]
"""A half-open cell rectangle ``(row0, row1, col0, col1)``."""


def bounding_window(flat: IntArray, width: int) -> Window:
    """The smallest window holding the (non-empty) flat cell indices ``flat``."""
    rows, cols = np.divmod(flat, width)
    return (int(rows.min()), int(rows.max()) + 1, int(cols.min()), int(cols.max()) + 1)


def spanning(windows: Sequence[Window]) -> Window:
    """The smallest window holding every one of (non-empty) ``windows``."""
    return (min(w[0] for w in windows), max(w[1] for w in windows),
            min(w[2] for w in windows), max(w[3] for w in windows))  # fmt: skip


def grown(window: Window, cells: int, shape: tuple[int, int]) -> Window:
    """``window`` grown by ``cells`` on every side, clipped to a grid of ``shape``."""
    row0, row1, col0, col1 = window
    return (max(0, row0 - cells), min(shape[0], row1 + cells),
            max(0, col0 - cells), min(shape[1], col1 + cells))  # fmt: skip


def inflate_window(
    base: CostArray, out: CostArray, window: Window, geometry: GridGeometry, params: InflationParams
) -> None:
    """Recompute ``out[window]`` as ``inflate(base)[window]``, exactly, in place.

    A cell's inflated cost depends only on its own base value and on the seeds
    within the inflation radius, so inflating the window grown by that radius
    and keeping its inner part equals a full re-inflation there. Callers pass
    the changed cells' window grown by the radius: nothing outside it can change.
    """
    bound = geometry.cell_distance(params.inflation_radius)
    row0, row1, col0, col1 = window
    g0, g1, h0, h1 = grown(window, bound, base.shape)
    inflated = inflate(base[g0:g1, h0:h1], geometry, params)
    out[row0:row1, col0:col1] = inflated[row0 - g0 : row1 - g0, col0 - h0 : col1 - h0]
