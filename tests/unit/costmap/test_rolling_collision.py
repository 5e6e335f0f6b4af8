"""The rolling window and the collision helpers."""

from __future__ import annotations

import math

import numpy as np

from aiobt.costmap import (
    FREE,
    LETHAL,
    NO_INFORMATION,
    CostGrid,
    GridGeometry,
    InflationParams,
    RollingCostmap,
    footprint_cost,
    occupancy_to_costs,
    point_cost,
    segment_is_free,
    segment_max_cost,
)

NO_INFLATION = InflationParams(0.0, 0.0, 3.0)


def test_rolling_window_follows_robot_and_keeps_obstacles() -> None:
    local = RollingCostmap(2.0, 2.0, 0.1, inflation=NO_INFLATION)
    local.update_origin(5.0, 5.0)
    assert local.geometry.origin_x == 4.0
    assert local.geometry.origin_y == 4.0
    local.mark_points([5.55], [5.25])
    local.update_origin(5.3, 5.0)  # three cells to +x
    assert math.isclose(local.geometry.origin_x, 4.3)
    assert local.point_cost(5.55, 5.25) == LETHAL
    local.update_origin(9.0, 9.0)  # far away: nothing overlaps
    assert not (local.master == LETHAL).any()
    assert (local.master == FREE).all()  # track_unknown_space=False by default


def test_rolling_window_resamples_static_source() -> None:
    world = GridGeometry(100, 100, 0.1)
    occupancy = np.zeros((100, 100), dtype=np.int8)
    occupancy[52, 55] = 100  # world cell centre (5.55, 5.25)
    local = RollingCostmap(2.0, 2.0, 0.1, inflation=NO_INFLATION)
    local.set_static_source(occupancy_to_costs(occupancy, world), world)
    local.update_origin(5.0, 5.0)
    assert local.point_cost(5.55, 5.25) == LETHAL
    local.update_origin(-8.0, -8.0)  # outside the world: unknown static
    assert local.master[0, 0] == NO_INFORMATION


def grid_with_wall() -> CostGrid:
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[:, 10] = LETHAL
    costs[5, 5] = 100
    return CostGrid(GridGeometry(20, 20, 0.1), costs)


def test_point_and_segment_costs() -> None:
    grid = grid_with_wall()
    assert point_cost(grid, 0.55, 0.55) == 100
    assert point_cost(grid, -0.1, 0.5) == LETHAL  # outside counts as lethal
    assert segment_max_cost(grid, 0.05, 0.05, 0.95, 0.05) == FREE
    assert segment_max_cost(grid, 0.05, 0.05, 1.5, 1.5) == LETHAL
    assert not segment_is_free(grid, 0.05, 0.05, 1.5, 0.05)
    assert segment_is_free(grid, 0.05, 0.55, 0.95, 0.55, max_cost=100)
    assert not segment_is_free(grid, 0.05, 0.55, 0.95, 0.55, max_cost=99)


def test_footprint_cost_checks_outline_and_rotation() -> None:
    grid = grid_with_wall()
    long_thin = [(0.3, 0.05), (0.3, -0.05), (-0.3, -0.05), (-0.3, 0.05)]
    # along x the outline reaches the wall at x = 1.0; rotated 90 degrees it does not
    assert footprint_cost(grid, 0.8, 1.5, 0.0, long_thin) == LETHAL
    assert footprint_cost(grid, 0.8, 1.5, math.pi / 2, long_thin) == FREE
    assert footprint_cost(grid, 0.55, 0.55, 0.0, []) == 100
