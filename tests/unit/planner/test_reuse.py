"""The goal-rooted search kept with a traversal: the same optimum as a fresh search
from any start, reused while the weights are unchanged, dropped when they change."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import LETHAL, CostGrid
from aiobt.costmap.inflation import bounding_window
from aiobt_services.planner.dijkstra import compiled_dijkstra
from aiobt_services.planner.errors import PlanningError
from aiobt_services.planner.traversal import KEPT_GOALS, Budget, SearchParams, Traversal

from .conftest import grid_from
from .test_compiled import flat_cost, free_point, random_traversal, reference_cost


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**31), st.floats(0.0, 0.35), st.integers(1, 2))
def test_one_kept_search_gives_every_start_the_fresh_optimum(
    seed: int, density: float, factor: int
) -> None:
    """Ten starts to one goal on one traversal: the first search is run, the others
    reuse it, each path costs what the CPython A* finds from that start."""
    traversal = random_traversal(seed, density, (24, 24), factor)
    rng = np.random.default_rng(seed + 7)
    goal_point = free_point(traversal, rng)
    if goal_point is None:
        return
    goal = traversal.locate(*goal_point, "goal")
    if not traversal.graph().passable[goal]:
        return  # a goal only its own leg opens is searched from the start, not kept
    budget = Budget()
    for _ in range(10):
        start_point = free_point(traversal, rng)
        assert start_point is not None
        start = traversal.locate(*start_point, "start")
        leg = traversal.opened(*start_point)
        expected = reference_cost(leg, start, goal)
        if math.isinf(expected):
            with pytest.raises(PlanningError) as err:
                compiled_dijkstra(leg, start, goal, budget)
            assert err.value.reason == "NO_VALID_PATH"
            continue
        path = compiled_dijkstra(leg, start, goal, budget)
        assert (path[0], path[-1]) == (start, goal)
        assert flat_cost(leg, path) == pytest.approx(expected, rel=1e-9, abs=1e-5)
    ran = budget.searched - budget.reused
    assert ran == 1, f"{ran} searches run for one goal on unchanged weights"


def corridor_grid(wall_gap_row: int) -> CostGrid:
    """16 x 16 free cells, a wall at column 8 open at one row."""
    costs = np.zeros((16, 16), dtype=np.uint8)
    costs[:, 8] = LETHAL
    costs[wall_gap_row, 8] = 0
    return grid_from(costs)


def test_an_updated_traversal_searches_afresh_and_finds_the_new_optimum() -> None:
    params = SearchParams(downsample=1)
    before = Traversal(corridor_grid(2), params)
    start, goal = before.index(0, 14), before.index(15, 14)
    budget = Budget()
    first = compiled_dijkstra(before, start, goal, budget)
    again = compiled_dijkstra(before, start, goal, budget)
    assert again == first
    assert (budget.searched, budget.reused) == (2, 1)
    moved = corridor_grid(13)  # the gap moves next to start and goal
    changed = np.flatnonzero(moved.costs != before.fine.costs)
    after = before.updated(moved, bounding_window(changed, 16))
    path = compiled_dijkstra(after, start, goal, budget)
    assert (budget.searched, budget.reused) == (3, 1)  # the kept tree was not used
    assert flat_cost(after, path) == pytest.approx(reference_cost(after, start, goal))
    assert flat_cost(after, path) < flat_cost(before, first) - 10.0  # through the new gap
    assert compiled_dijkstra(before, start, goal, budget) == first  # the old one kept its own


def test_the_least_recently_used_goals_are_dropped() -> None:
    traversal = Traversal(grid_from(np.zeros((4, 30), dtype=np.uint8)))
    goals = [traversal.index(col, 3) for col in range(KEPT_GOALS + 1)]
    for goal in goals:
        assert traversal.reach_to(goal)[1] is False
    assert traversal.reach_to(goals[-1])[1] is True
    assert traversal.reach_to(goals[1])[1] is True
    assert traversal.reach_to(goals[0])[1] is False  # the first was dropped for the last
