"""The inflation layer: Nav2's exponential cost decay around lethal cells."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .distance import distance_transform
from .grid import INSCRIBED, LETHAL, NO_INFORMATION, CostArray, FloatArray, GridGeometry


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
    distance_m = distance_transform(seeds, bound) * geometry.resolution
    inflated = costs_from_distance(distance_m, params)
    unknown = master == NO_INFORMATION
    threshold = 1 if params.inflate_unknown else INSCRIBED
    result = np.maximum(master, inflated)
    result[unknown] = np.where(inflated[unknown] >= threshold, inflated[unknown], NO_INFORMATION)
    return result
