"""The planner's traversal and graph follow costmap changes in a window, and scans coalesce."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import INSCRIBED, LETHAL, NO_INFORMATION, CostGrid, GridGeometry
from aiobt.costmap.inflation import bounding_window
from aiobt.msgs import Header, LaserScan, OccupancyGrid, PoseStamped
from aiobt_services.planner.state import CostmapOptions, GlobalCostmap
from aiobt_services.planner.traversal import SearchParams, Traversal

VALUES = np.array((0, 30, 120, INSCRIBED, LETHAL, NO_INFORMATION), dtype=np.uint8)


def assert_same(updated: Traversal, fresh: Traversal) -> None:
    assert updated.weights == fresh.weights
    assert np.array_equal(updated.costs, fresh.costs)
    assert np.array_equal(updated.passable, fresh.passable)
    assert np.array_equal(updated.graph()._weights, fresh.graph()._weights)
    assert updated.graph().edges == fresh.graph().edges
    assert np.array_equal(updated.graph().passable, fresh.graph().passable)
    root = fresh.index(0, 0)  # the reversed graph: updated in the window if it was built
    assert np.array_equal(updated.graph().reach_to(root).cost, fresh.graph().reach_to(root).cost)
    reversed_weights = (updated.graph()._reversed_weights, fresh.graph()._reversed_weights)
    assert reversed_weights[0] is not None
    assert reversed_weights[1] is not None
    assert np.array_equal(reversed_weights[0], reversed_weights[1])


@settings(max_examples=80, deadline=None)
@given(
    height=st.integers(3, 20),
    width=st.integers(3, 20),
    downsample=st.integers(1, 3),
    seed=st.integers(0, 2**32 - 1),
    built=st.booleans(),
)
def test_an_updated_traversal_equals_one_built_from_scratch(
    height: int, width: int, downsample: int, seed: int, built: bool
) -> None:
    rng = np.random.default_rng(seed)
    geometry = GridGeometry(width, height, 0.1)
    before = rng.choice(VALUES, size=(height, width))
    after = before.copy()
    cells = rng.integers(0, height * width, size=int(rng.integers(1, 6)))
    after.flat[cells] = rng.choice(VALUES, size=cells.size)
    params = SearchParams(downsample=downsample)
    old = Traversal(CostGrid(geometry, before), params)
    if built:
        old.graph().reach_to(old.index(0, 0))
    changed = np.flatnonzero(after != before)
    if not changed.size:
        return
    updated = old.updated(CostGrid(geometry, after), bounding_window(changed, width))
    assert_same(updated, Traversal(CostGrid(geometry, after), params))
    assert_same(old, Traversal(CostGrid(geometry, before), params))  # the old one untouched


def scan(stamp: float, ranges: list[float]) -> LaserScan:
    count = len(ranges)
    return LaserScan(
        header=Header(stamp=stamp, frame_id="base_scan"),
        angle_min=-0.3,
        angle_max=-0.3 + 0.06 * (count - 1),
        angle_increment=0.06,
        range_min=0.0,
        range_max=5.0,
        ranges=ranges,
    )


def world() -> GlobalCostmap:
    grid = GlobalCostmap(CostmapOptions(scan_period=0.5))
    grid.on_map(OccupancyGrid.from_array(np.zeros((60, 60), dtype=np.int8), 0.05))
    grid.on_pose(PoseStamped.from_xy_yaw(0.5, 1.5, 0.0, stamp=1.0))
    return grid


def seen(state: GlobalCostmap, stamp: float, ranges: list[float], x: float = 0.5) -> None:
    """The robot's pose at ``stamp`` (at (x, 1.5) facing +x), then its scan, as the robot
    publishes them."""
    state.on_pose(PoseStamped.from_xy_yaw(x, 1.5, 0.0, stamp=stamp))
    state.on_scan(scan(stamp, ranges))


def lethal_at(grid: CostGrid, x: float, y: float) -> bool:
    cell = grid.geometry.world_to_cell(x, y)
    assert cell is not None
    return bool(grid.costs[cell[1], cell[0]] == LETHAL)


def test_scans_within_the_period_wait_a_read_folds_nothing_the_next_due_folds_the_newest() -> None:
    state = world()
    first = state.traversal()
    assert first is not None
    assert state.costmap is not None
    seen(state, 1.0, [1.0] * 11)  # folded at once: the first scan
    folded = state.traversal()
    assert folded is not first  # brought up to date by the fold, before any read
    version = state.costmap.version
    seen(state, 1.1, [1.5] * 11)  # waits (0.1 s < 0.5 s), then replaced
    seen(state, 1.2, [2.0] * 11)
    grid = state.snapshot()  # a read takes the costmap as the last fold left it
    assert grid is not None
    assert state.costmap.version == version
    assert lethal_at(grid, 1.5, 1.5)
    assert not lethal_at(grid, 2.5, 1.5)
    assert state.traversal() is folded
    seen(state, 1.6, [2.0] * 11)  # due: the newest folded, the waiting one dropped
    grid = state.snapshot()
    assert grid is not None
    assert lethal_at(grid, 2.5, 1.5)  # the newest scan's hit
    assert not lethal_at(grid, 2.0, 1.5)  # the replaced one was never folded
    assert not lethal_at(grid, 1.5, 1.5)  # the first one's hit, cleared by the newest
    traversal = state.traversal()
    assert traversal is not None
    assert traversal is not folded
    assert state.traversal() is traversal  # no change since: the same one
    assert_same(traversal, Traversal(grid, state.options.search))


def test_after_forget_or_a_stamp_going_back_a_scan_is_folded_as_it_comes() -> None:
    state = world()
    seen(state, 5.0, [1.0] * 11)
    seen(state, 3.0, [1.5] * 11)  # the robot restarted: its clock went back
    grid = state.snapshot()
    assert grid is not None
    assert lethal_at(grid, 2.0, 1.5)
    state.forget()  # the streams closed; the next pose and scan start afresh
    seen(state, 3.1, [2.0] * 11)
    grid = state.snapshot()
    assert grid is not None
    assert lethal_at(grid, 2.5, 1.5)


def test_an_equal_scan_from_the_same_pose_changes_nothing() -> None:
    state = world()
    seen(state, 1.0, [1.0] * 11)
    grid = state.snapshot()
    assert state.costmap is not None
    version = state.costmap.version
    seen(state, 2.0, [1.0] * 11)
    assert state.snapshot() is grid
    assert state.costmap.version == version
    seen(state, 3.0, [1.0] * 11, x=0.6)  # moved: folded, the hits move with the robot
    moved = state.snapshot()
    assert moved is not None
    assert moved is not grid
    assert lethal_at(moved, 1.62, 1.5)
    assert not lethal_at(moved, 1.52, 1.5)


def test_a_scan_is_marked_from_the_pose_stamped_with_it_not_a_newer_one() -> None:
    state = world()  # the robot at (0.5, 1.5) at 1.0
    state.on_pose(PoseStamped.from_xy_yaw(0.6, 1.5, 0.0, stamp=1.02))  # came before the scan
    state.on_scan(scan(1.0, [1.0] * 11))
    grid = state.snapshot()
    assert grid is not None
    assert lethal_at(grid, 1.52, 1.5)  # 1 m ahead of where the scan was taken
    assert not lethal_at(grid, 1.62, 1.5)


def test_a_scan_that_comes_before_its_pose_waits_for_it() -> None:
    state = world()
    seen(state, 1.0, [1.0] * 11)  # the first: folded as it comes
    state.on_scan(scan(2.0, [1.0] * 11))  # due, but the robot's pose at 2.0 is not here yet
    grid = state.snapshot()
    assert grid is not None
    assert not lethal_at(grid, 1.62, 1.5)
    state.on_pose(PoseStamped.from_xy_yaw(0.6, 1.5, 0.0, stamp=2.0))
    grid = state.snapshot()
    assert grid is not None
    assert lethal_at(grid, 1.62, 1.5)  # marked from (0.6, 1.5), its own pose


def test_a_new_map_is_inflated_and_its_search_graph_built_as_it_comes() -> None:
    state = world()
    ready = state._traversal
    assert ready is not None  # the first request does not build it
    assert ready[1]._graph.graph is not None
    assert state.traversal() is ready[1]
