"""GridBased's compiled Dijkstra against the CPython A*: same optimum, valid paths,
opened blocks, the cached graph, budget and cancel checks around the compiled call."""

from __future__ import annotations

import argparse
import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import INSCRIBED, LETHAL, NO_INFORMATION
from aiobt_services.planner.astar import astar
from aiobt_services.planner.dijkstra import compiled_dijkstra
from aiobt_services.planner.errors import PlanningCancelled, PlanningError
from aiobt_services.planner.main import add_arguments, build
from aiobt_services.planner.planning import plan
from aiobt_services.planner.sparse import GridGraph, Reach
from aiobt_services.planner.traversal import Budget, SearchParams, Traversal

from .conftest import grid_from


def flat_cost(traversal: Traversal, path: list[int]) -> float:
    """The GridBased metric on a traversal's flat indices; asserts the path is valid."""
    total, s = 0.0, traversal.stride
    for a, b in itertools.pairwise(path):
        dr, dc = abs(b // s - a // s), abs(b % s - a % s)
        assert max(dr, dc) == 1, f"{a} -> {b} is not an 8-connected step"
        assert math.isfinite(traversal.weights[b]), f"{b} is not passable"
        total += (math.sqrt(2.0) if dr and dc else 1.0) * traversal.weights[b]
    return total


def reference_cost(traversal: Traversal, start: int, goal: int) -> float:
    """The CPython A*'s optimum (``inf`` when it finds no path)."""
    try:
        return flat_cost(traversal, astar(traversal, start, goal))
    except PlanningError as exc:
        if exc.reason != "NO_VALID_PATH":
            raise
        return math.inf


def random_traversal(seed: int, density: float, size: tuple[int, int], factor: int) -> Traversal:
    rng = np.random.default_rng(seed)
    h, w = size
    costs = rng.integers(0, 253, size=(h, w)).astype(np.uint8)
    costs[rng.random((h, w)) < density] = LETHAL
    costs[rng.random((h, w)) < 0.03] = INSCRIBED
    costs[rng.random((h, w)) < 0.05] = NO_INFORMATION
    return Traversal(grid_from(costs), SearchParams(downsample=factor))


def free_point(traversal: Traversal, rng: np.random.Generator) -> tuple[float, float] | None:
    rows, cols = np.nonzero(traversal.fine.costs < INSCRIBED)
    if not len(rows):
        return None
    i = rng.integers(len(rows))
    return traversal.fine.geometry.cell_to_world(int(cols[i]), int(rows[i]))


@settings(max_examples=60, deadline=None)
@given(
    st.integers(0, 2**31),
    st.floats(0.0, 0.4),
    st.tuples(st.integers(2, 30), st.integers(2, 30)),
    st.integers(1, 3),
)
def test_compiled_dijkstra_matches_astar_cost_with_opened_ends(
    seed: int, density: float, size: tuple[int, int], factor: int
) -> None:
    """Random grids, downsampled or not; the start and goal blocks are opened as
    plan() opens them, so blocked blocks around free fine cells are covered."""
    traversal = random_traversal(seed, density, size, factor)
    rng = np.random.default_rng(seed + 1)
    a, b = free_point(traversal, rng), free_point(traversal, rng)
    if a is None or b is None:
        return
    start, goal = traversal.locate(*a, "start"), traversal.locate(*b, "goal")
    leg = traversal.opened(*a).opened(*b)
    expected = reference_cost(leg, start, goal)
    if math.isinf(expected):
        with pytest.raises(PlanningError) as err:
            compiled_dijkstra(leg, start, goal)
        assert err.value.reason == "NO_VALID_PATH"
        return
    path = compiled_dijkstra(leg, start, goal)
    assert (path[0], path[-1]) == (start, goal)
    assert flat_cost(leg, path) == pytest.approx(expected, rel=1e-9, abs=1e-5)


def test_a_blocked_goal_block_is_entered_from_its_cheapest_neighbour() -> None:
    """2x2 blocks: the goal's block (3, 3) is blocked by one inscribed cell; from
    (0, 3) the straight neighbour (2, 3) costs 2.70 to reach, the diagonal (2, 2)
    2.41: entering straight (+1) beats entering diagonally (+1.41)."""
    costs = np.zeros((10, 10), dtype=np.uint8)
    costs[7, 7] = INSCRIBED
    costs[6:8, 4:6] = 88  # block (2, 3) weighs 1 + 2 * 88 / 252 = 1.70
    traversal = Traversal(grid_from(costs), SearchParams(downsample=2))
    start, goal = traversal.locate(0.05, 0.65, "start"), traversal.locate(0.65, 0.65, "goal")
    assert not traversal.graph().passable[goal]
    with pytest.raises(PlanningError) as err:  # not opened: unreachable
        compiled_dijkstra(traversal, start, goal)
    assert err.value.reason == "NO_VALID_PATH"
    leg = traversal.opened(0.65, 0.65)
    path = compiled_dijkstra(leg, start, goal)
    assert path == [traversal.index(col, 3) for col in range(4)]
    assert flat_cost(leg, path) == pytest.approx(flat_cost(leg, astar(leg, start, goal)))
    assert leg.graph() is traversal.graph()  # opening a block rebuilt nothing


def test_the_graph_is_built_once_and_edges_enter_only_passable_cells() -> None:
    costs = np.zeros((3, 3), dtype=np.uint8)
    traversal = Traversal(grid_from(costs))
    graph = traversal.graph()
    assert traversal.graph() is graph
    assert graph.edges == 4 * 3 + 4 * 5 + 8  # corners, sides, centre
    costs[1, 1] = LETHAL
    walled = Traversal(grid_from(costs))
    assert walled.graph().edges == 4 * 3 + 4 * 5 + 8 - 8  # none into the centre; all out
    assert plan(walled, (0.05, 0.05, 0.0), (0.25, 0.25, 0.0))
    assert walled.graph() is walled.graph()


def test_budget_and_cancel_are_checked_around_the_compiled_call(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    traversal = random_traversal(5, 0.0, (30, 30), 1)
    start, goal = traversal.index(0, 0), traversal.index(29, 29)
    with pytest.raises(PlanningError) as err:
        compiled_dijkstra(traversal, start, goal, Budget(max_seconds=0.0))
    assert err.value.reason == "TIMEOUT"
    budget = Budget()
    reach_to = GridGraph.reach_to

    def cancelled_meanwhile(graph: GridGraph, source: int) -> Reach:
        budget.cancel.set()  # a cancel that arrives during the uninterruptible call
        return reach_to(graph, source)

    monkeypatch.setattr(GridGraph, "reach_to", cancelled_meanwhile)
    with pytest.raises(PlanningCancelled):
        compiled_dijkstra(traversal, start, goal, budget)
    assert budget.cancel.is_set()


def test_the_service_option_selects_the_python_astar() -> None:
    """``--use-astar`` reaches GridBased: on a small grid the A* finishes before its
    first periodic budget check, the compiled search checks before it starts."""
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    world, _ = build(parser.parse_args([]))
    assert world.options.search == SearchParams(downsample=2)
    world, _ = build(parser.parse_args(["--use-astar", "--downsample", "1"]))
    assert world.options.search == SearchParams(downsample=1, use_astar=True)
    grid = grid_from(np.zeros((4, 30), dtype=np.uint8))
    cancelled = Budget()
    cancelled.cancel.set()
    ends = ((0.05, 0.05, 0.0), (2.95, 0.35, 0.0))
    assert plan(Traversal(grid, world.options.search), *ends, budget=cancelled)
    with pytest.raises(PlanningCancelled):
        plan(Traversal(grid, SearchParams(downsample=1)), *ends, budget=cancelled)


def test_a_reach_whose_parents_loop_is_an_error_not_a_hang() -> None:
    """Parents that never lead to the root (negative weights gave scipy's Dijkstra such
    a reach: the planner hung on it in a CI run) raise instead of looping forever."""
    looping = Reach(np.zeros(4), np.array([1, 2, 1, -9999], dtype=np.int32))
    with pytest.raises(ValueError, match="never lead to 3"):
        looping.path_from(0, 3)
    sound = Reach(np.zeros(4), np.array([1, 3, 3, -9999], dtype=np.int32))
    assert sound.path_from(0, 3) == [0, 1, 3]
