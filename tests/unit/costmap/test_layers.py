"""Static, obstacle and inflation layers and the combined master grid."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.costmap import (
    FREE,
    INSCRIBED,
    LETHAL,
    NO_INFORMATION,
    Costmap,
    GridGeometry,
    InflationParams,
    ObstacleParams,
    Scan,
    occupancy_to_costs,
)

GEOM = GridGeometry(20, 20, 0.1)


def test_static_layer_interprets_occupancy() -> None:
    g = GridGeometry(4, 1, 0.1)
    assert occupancy_to_costs([-1, 0, 99, 100], g).tolist() == [
        [NO_INFORMATION, FREE, FREE, LETHAL]
    ]


def test_static_layer_names_the_bad_cell() -> None:
    with pytest.raises(ValueError, match=r"value 101 at cell \(col=2, row=0\)"):
        occupancy_to_costs([0, 0, 101, 0], GridGeometry(4, 1, 0.1))
    with pytest.raises(ValueError, match="expected 4x1"):
        occupancy_to_costs([0, 0], GridGeometry(4, 1, 0.1))


def test_inflation_follows_nav2_formula() -> None:
    params = InflationParams(inscribed_radius=0.2, inflation_radius=0.6, cost_scaling_factor=3.0)
    occupancy = np.zeros((20, 20), dtype=np.int8)
    occupancy[10, 10] = 100
    master = Costmap.from_occupancy(occupancy, GEOM, inflation=params).master
    assert master[10, 10] == LETHAL
    assert master[10, 12] == INSCRIBED  # 0.2 m away
    assert master[10, 13] == int(252 * math.exp(-3.0 * (0.3 - 0.2)))
    assert master[10, 15] == int(252 * math.exp(-3.0 * (0.5 - 0.2)))
    d = math.hypot(0.4, 0.3)
    assert master[13, 14] == int(252 * math.exp(-3.0 * (d - 0.2)))
    assert master[10, 17] == FREE  # 0.7 m > inflation radius
    assert master[0, 0] == FREE


def test_unknown_stays_unknown_unless_inscribed() -> None:
    occupancy = np.full((20, 20), -1, dtype=np.int8)
    occupancy[10, 10] = 100
    master = Costmap.from_occupancy(occupancy, GEOM).master
    assert master[10, 11] == INSCRIBED
    assert master[10, 14] == NO_INFORMATION


def scan_towards_plus_x(distance: float, count: int = 1, range_max: float = 5.0) -> Scan:
    return Scan.create((0.05, 1.05, 0.0), 0.0, 0.01, [distance] * count, 0.05, range_max)


def test_scan_marks_hit_and_clears_ray() -> None:
    costmap = Costmap(GEOM, inflation=InflationParams(0.0, 0.0, 3.0))
    costmap.update_from_scan(scan_towards_plus_x(1.0))
    obstacles = costmap.obstacles
    assert obstacles[10, 10] == LETHAL
    assert (obstacles[10, 0:10] == FREE).all()
    assert obstacles[10, 11] == NO_INFORMATION
    assert obstacles[9, 5] == NO_INFORMATION


def test_scan_clears_an_obstacle_that_moved_away() -> None:
    costmap = Costmap(GEOM, inflation=InflationParams(0.0, 0.0, 3.0))
    costmap.update_from_scan(scan_towards_plus_x(1.0))
    costmap.update_from_scan(scan_towards_plus_x(1.5))
    assert costmap.obstacles[10, 10] == FREE
    assert costmap.obstacles[10, 15] == LETHAL


def test_ranges_beyond_obstacle_range_clear_without_marking() -> None:
    params = ObstacleParams(obstacle_max_range=0.5, raytrace_max_range=1.2)
    costmap = Costmap(GEOM, obstacle_params=params)
    costmap.update_from_scan(scan_towards_plus_x(1.5))
    assert not (costmap.obstacles == LETHAL).any()
    assert (costmap.obstacles[10, 0:12] == FREE).all()
    assert costmap.obstacles[10, 13] == NO_INFORMATION


def test_max_range_and_nan_readings_do_not_mark() -> None:
    costmap = Costmap(GEOM)
    scan = Scan.create((1.0, 1.0, 0.0), 0.0, math.pi / 2, [5.0, math.inf, math.nan], 0.05, 5.0)
    costmap.update_from_scan(scan)
    assert not (costmap.obstacles == LETHAL).any()
    assert costmap.obstacles[15, 10] == FREE  # the inf ray (+y) cleared


def test_obstacles_do_not_clear_static_walls() -> None:
    occupancy = np.zeros((20, 20), dtype=np.int8)
    occupancy[10, 5] = 100
    costmap = Costmap.from_occupancy(occupancy, GEOM, inflation=InflationParams(0.0, 0.0, 3.0))
    costmap.update_from_scan(scan_towards_plus_x(1.5))
    assert costmap.master[10, 5] == LETHAL
    assert costmap.master[10, 15] == LETHAL


def test_clear_entirely_around_and_except() -> None:
    costmap = Costmap(GEOM, inflation=InflationParams(0.0, 0.0, 3.0))
    costmap.mark_points([0.15, 1.55], [0.15, 1.55])
    assert costmap.master[1, 1] == LETHAL
    assert costmap.master[15, 15] == LETHAL
    costmap.clear_around(0.15, 0.15, 0.5)
    assert costmap.master[1, 1] == NO_INFORMATION
    assert costmap.master[15, 15] == LETHAL
    costmap.mark_points([0.15], [0.15])
    costmap.clear_except(0.15, 0.15, 0.5)
    assert costmap.master[1, 1] == LETHAL
    assert costmap.master[15, 15] == NO_INFORMATION
    costmap.clear_entirely()
    assert (costmap.master == NO_INFORMATION).all()
    with pytest.raises(ValueError, match="finite pose"):
        costmap.clear_around(math.nan, 0.0, 1.0)


def test_new_map_of_other_size_resizes_and_resets_obstacles() -> None:
    costmap = Costmap(GEOM)
    costmap.mark_points([0.15], [0.15])
    bigger = GridGeometry(30, 10, 0.1)
    costmap.set_static(np.zeros(300, dtype=np.int8), bigger)
    assert costmap.master.shape == (10, 30)
    assert not (costmap.master == LETHAL).any()
