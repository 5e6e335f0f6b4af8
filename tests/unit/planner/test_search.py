"""GridBased (compiled Dijkstra or A*) and ThetaStar: optimality, clearance, every error code."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import INSCRIBED, LETHAL, NO_INFORMATION, segment_max_cost
from aiobt_services.planner.errors import PlanningCancelled, PlanningError
from aiobt_services.planner.planning import path_length, plan, plan_through
from aiobt_services.planner.reference import dijkstra, path_cost, step_weights
from aiobt_services.planner.traversal import Budget, SearchParams, Traversal

from .conftest import corridor, grid_from, room_with_wall


def cells_of(grid, poses) -> list[tuple[int, int]]:
    cells = [grid.geometry.world_to_cell(x, y) for x, y, _ in poses]
    out: list[tuple[int, int]] = []
    for cell in cells:
        assert cell is not None
        if not out or out[-1] != cell:
            out.append(cell)
    return out


@settings(max_examples=30, deadline=None)
@given(
    st.integers(0, 2**31),
    st.floats(0.0, 0.35),
    st.integers(5, 24),
    st.integers(5, 24),
    st.booleans(),
)
def test_gridbased_is_optimal_against_dijkstra(
    seed: int, density: float, w: int, h: int, use_astar: bool
) -> None:
    """Both GridBased searches (compiled Dijkstra, CPython A*) against the plain one."""
    params = SearchParams(use_astar=use_astar)
    rng = np.random.default_rng(seed)
    costs = rng.integers(0, 253, size=(h, w)).astype(np.uint8)
    costs[rng.random((h, w)) < density] = LETHAL
    costs[rng.random((h, w)) < 0.05] = NO_INFORMATION
    costs[0, 0] = costs[h - 1, w - 1] = 0
    grid = grid_from(costs)
    weights = step_weights(grid)
    expected, _ = dijkstra(weights, (0, 0), (w - 1, h - 1))
    start, goal = (
        (*grid.geometry.cell_to_world(0, 0), 0.0),
        (*grid.geometry.cell_to_world(w - 1, h - 1), 0.0),
    )
    if math.isinf(expected):
        with pytest.raises(PlanningError) as err:
            plan(grid, start, goal, params=params)
        assert err.value.reason == "NO_VALID_PATH"
        return
    got = path_cost(weights, cells_of(grid, plan(grid, start, goal, params=params)))
    assert got == pytest.approx(expected, rel=1e-9, abs=1e-5)  # keys are 2**-20 fixed point


def test_path_goes_through_the_gap_with_exact_ends() -> None:
    grid = room_with_wall(gap_row=2)
    poses = plan(grid, (0.25, 1.75, 0.0), (1.75, 1.75, 1.0))
    assert poses[0][:2] == (0.25, 1.75)
    assert poses[-1] == (1.75, 1.75, 1.0)
    assert any(grid.geometry.world_to_cell(x, y) == (10, 2) for x, y, _ in poses)
    first_step = math.atan2(poses[1][1] - poses[0][1], poses[1][0] - poses[0][0])
    assert poses[0][2] == pytest.approx(first_step)


def test_path_keeps_to_the_middle_of_a_corridor() -> None:
    grid = corridor(width_m=1.6)
    poses = plan(grid, (0.2, 0.3, 0.0), (3.8, 1.3, 0.0))
    middle = [y for x, y, _ in poses if 1.0 < x < 3.0]
    assert middle
    assert all(abs(y - 0.8) < 0.15 for y in middle)
    no_cost = plan(grid, (0.2, 0.3, 0.0), (3.8, 1.3, 0.0), params=SearchParams(cost_penalty=0.0))
    # without the cost term any shortest staircase will do: this one hugs a wall
    assert max(abs(y - 0.8) for x, y, _ in no_cost if 1.0 < x < 3.0) > 0.3


@pytest.mark.parametrize("planner_id", ["GridBased", "ThetaStar"])
@pytest.mark.parametrize("downsample", [1, 2])
def test_paths_stay_out_of_lethal_and_inscribed_cells(planner_id: str, downsample: int) -> None:
    grid = corridor(width_m=1.2)
    costs = grid.costs.copy()
    costs[:16, 40] = LETHAL  # a half wall to go around
    blocked = grid_from(costs, 0.05)
    params = SearchParams(downsample=downsample)
    poses = plan(blocked, (0.3, 0.6, 0.0), (3.7, 0.6, 0.0), planner_id, params=params)
    for (x0, y0, _), (x1, y1, _) in itertools.pairwise(poses):
        assert segment_max_cost(blocked, x0, y0, x1, y1) < INSCRIBED


def test_theta_star_is_any_angle_and_short() -> None:
    grid = grid_from(np.zeros((40, 40), dtype=np.uint8))
    theta = plan(grid, (0.05, 0.05, 0.0), (3.05, 1.05, 0.0), "ThetaStar")
    straight = math.hypot(3.0, 1.0)
    assert path_length(theta) == pytest.approx(straight, rel=1e-6)
    grid_path = plan(grid, (0.05, 0.05, 0.0), (3.05, 1.05, 0.0), "GridBased")
    assert path_length(grid_path) > path_length(theta) + 0.05


def test_plan_through_poses_visits_each_goal() -> None:
    grid = room_with_wall(gap_row=2)
    goals = [(1.75, 0.25, 0.0), (1.75, 1.75, 0.5)]
    poses = plan_through(grid, (0.25, 1.75, 0.0), goals)
    xy = [(round(x, 6), round(y, 6)) for x, y, _ in poses]
    assert (1.75, 0.25) in xy
    assert poses[-1] == (1.75, 1.75, 0.5)


@pytest.mark.parametrize(
    ("start", "goal", "reason"),
    [
        ((-0.5, 0.5), (1.5, 1.5), "START_OUTSIDE_MAP"),
        ((0.5, 0.5), (2.5, 1.5), "GOAL_OUTSIDE_MAP"),
        ((math.nan, 0.5), (1.5, 1.5), "START_OUTSIDE_MAP"),
        ((0.5, 0.5), (1.5, math.inf), "GOAL_OUTSIDE_MAP"),
        ((1.05, 0.5), (1.5, 1.5), "START_OCCUPIED"),
        ((0.5, 0.5), (1.05, 1.5), "GOAL_OCCUPIED"),
    ],
)
def test_bad_endpoints_get_their_error(
    start: tuple[float, float], goal: tuple[float, float], reason: str
) -> None:
    with pytest.raises(PlanningError) as err:
        plan(room_with_wall(), (*start, 0.0), (*goal, 0.0))
    assert err.value.reason == reason
    assert "start" in err.value.message or "goal" in err.value.message


def test_no_path_invalid_planner_and_no_viapoints() -> None:
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[:, 10] = LETHAL
    grid = grid_from(costs)
    with pytest.raises(PlanningError) as err:
        plan(grid, (0.5, 0.5, 0.0), (1.5, 0.5, 0.0))
    assert err.value.reason == "NO_VALID_PATH"
    with pytest.raises(PlanningError) as err:
        plan(grid, (0.5, 0.5, 0.0), (0.7, 0.5, 0.0), "NavFn")
    assert err.value.reason == "INVALID_PLANNER"
    assert "GridBased" in err.value.message
    with pytest.raises(PlanningError) as err:
        plan_through(grid, (0.5, 0.5, 0.0), [])
    assert err.value.reason == "NO_VIAPOINTS_GIVEN"


def test_unknown_cells_are_avoided_unless_allowed() -> None:
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[:, 10] = NO_INFORMATION
    grid = grid_from(costs)
    assert plan(grid, (0.5, 0.5, 0.0), (1.5, 0.5, 0.0))
    with pytest.raises(PlanningError) as err:
        plan(grid, (0.5, 0.5, 0.0), (1.5, 0.5, 0.0), params=SearchParams(allow_unknown=False))
    assert err.value.reason == "NO_VALID_PATH"


def big_maze(use_astar: bool = False) -> Traversal:
    costs = np.zeros((300, 300), dtype=np.uint8)
    costs[:, 150] = LETHAL
    return Traversal(grid_from(costs, 0.05), SearchParams(use_astar=use_astar))


@pytest.mark.parametrize(
    ("planner_id", "use_astar"), [("GridBased", False), ("GridBased", True), ("ThetaStar", False)]
)
def test_time_budget_gives_timeout(planner_id: str, use_astar: bool) -> None:
    """The Python searches time out at a periodic check, the compiled one before its call."""
    maze = big_maze(use_astar)
    with pytest.raises(PlanningError) as err:
        plan(maze, (1.0, 7.5, 0.0), (14.0, 7.5, 0.0), planner_id, Budget(max_seconds=0.0))
    assert err.value.reason == "TIMEOUT"


@pytest.mark.parametrize("use_astar", [False, True])
def test_cancel_flag_stops_the_search(use_astar: bool) -> None:
    budget = Budget()
    budget.cancel.set()
    with pytest.raises(PlanningCancelled):
        plan(big_maze(use_astar), (1.0, 7.5, 0.0), (14.0, 7.5, 0.0), budget=budget)


def test_cached_traversal_is_not_modified_by_opening_a_block() -> None:
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[5, 5] = INSCRIBED  # blocks the 2x2 block (col 2, row 2) after downsampling
    traversal = Traversal(grid_from(costs), SearchParams(downsample=2))
    before = list(traversal.weights)
    poses = plan(traversal, (0.45, 0.45, 0.0), (1.5, 1.5, 0.0))  # start cell (4, 4) is free
    assert poses
    assert traversal.weights == before
