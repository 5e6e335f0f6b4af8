"""The navigation benchmark's goals and grid optimum on the office world (pure, no bus)."""

from __future__ import annotations

import math

import pytest

from aiobt.costmap import CostGrid
from bench.nav.goals import GOAL_CLEARANCE_COST, MIN_LEG, Optimum, pick_goals, static_grid

START = (2.0, 9.75)


@pytest.fixture(scope="module")
def grid() -> CostGrid:
    return static_grid()


def test_goals_are_seeded_clear_of_walls_and_apart(grid: CostGrid) -> None:
    goals = pick_goals(grid, START, 20, seed=1)
    assert goals == pick_goals(grid, START, 20, seed=1)
    assert goals != pick_goals(grid, START, 20, seed=2)
    last = START
    for x, y, yaw in goals:
        cell = grid.geometry.world_to_cell(x, y)
        assert cell is not None
        assert grid.costs[cell[1], cell[0]] < GOAL_CLEARANCE_COST
        assert math.dist((x, y), last) >= MIN_LEG
        assert -math.pi <= yaw <= math.pi
        last = (x, y)


def test_optimum_is_the_straight_line_in_the_open_and_longer_around_walls(grid: CostGrid) -> None:
    optimum = Optimum(grid)
    along_corridor = optimum.length(START, (12.0, 9.75))
    assert along_corridor == pytest.approx(10.0, abs=0.06)
    # into the south-west room: through the door at x 3.5, not through the wall at y 8.5
    into_room = optimum.length(START, (2.0, 7.0))
    assert into_room > math.dist(START, (2.0, 7.0)) + 0.5
    assert into_room < 5.0


def test_optimum_of_a_point_in_a_wall_or_off_the_map_is_infinite(grid: CostGrid) -> None:
    optimum = Optimum(grid)
    assert optimum.length(START, (25.0, 5.0)) == math.inf
    assert optimum.length(START, (7.0, 4.0)) == math.inf  # inside the wall at x 7, 3+ cells deep
