"""ThetaStar's (and GridBased's) paths over random inflated maps, at every downsample:
dense like GridBased's, and never on or across a cell the planner's own validity
check (``IsPathValid``) refuses."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from aiobt.costmap import INSCRIBED, NO_INFORMATION, CostGrid, Costmap, GridGeometry
from aiobt.costmap.inflation import InflationParams
from aiobt.geometry import XYYaw
from aiobt_services.planner.errors import PlanningError
from aiobt_services.planner.legs import LONGEST_STEP
from aiobt_services.planner.planning import plan
from aiobt_services.planner.traversal import SearchParams, Traversal
from aiobt_services.planner.validity import invalid_poses

RES = 0.05
SAMPLES_PER_CELL = 7


def on_a_corner(grid: CostGrid, x: float, y: float) -> bool:
    """(x, y) is a corner shared by four cells: a leg that touches a cell only there does
    not cross it (a diagonal step between two blocks' centres at a downsample passes
    exactly through such corners)."""
    g = grid.geometry
    fx, fy = (x - g.origin_x) / RES, (y - g.origin_y) / RES
    return abs(fx - round(fx)) < 1e-9 and abs(fy - round(fy)) < 1e-9


def random_world(seed: int, size: int, boxes: int) -> CostGrid:
    """Walls, boxes and thin posts inflated like the default world (0.22 m inscribed)."""
    rng = np.random.default_rng(seed)
    occupancy = np.zeros((size, size), dtype=np.int8)
    occupancy[[0, -1], :] = 100
    occupancy[:, [0, -1]] = 100
    for _ in range(boxes):
        r, c = rng.integers(0, size, 2)
        h, w = rng.integers(1, size // 4, 2)
        occupancy[r : r + h, c : c + w] = 100
    geometry = GridGeometry(size, size, RES)
    return Costmap.from_occupancy(occupancy, geometry, inflation=InflationParams()).snapshot()


def free_point(grid: CostGrid, rng: np.random.Generator) -> tuple[float, float] | None:
    rows, cols = np.nonzero(grid.costs < INSCRIBED)
    if not len(rows):
        return None
    k = int(rng.integers(len(rows)))
    dx, dy = rng.random(2)  # anywhere inside the cell, not only its centre
    g = grid.geometry
    return (g.origin_x + (cols[k] + dx) * RES, g.origin_y + (rows[k] + dy) * RES)


def refused_crossings(
    grid: CostGrid, poses: list[XYYaw], downsample: int, ends: tuple[XYYaw, XYYaw]
) -> list[tuple[float, float]]:
    """Points along the legs whose fine cell IsPathValid would refuse.

    At a downsample the start's and goal's blocks may be refused as a whole
    (opened for the search: the end's own fine cell is free): samples inside
    them are not judged, nor, like GridBased's, the one grid step out of or into
    such a block.
    """
    blocks = Traversal(grid, SearchParams(downsample=downsample)).costs
    opened: list[tuple[int, int] | None] = []
    for x, y, _ in ends:
        cell = grid.geometry.world_to_cell(x, y)
        assert cell is not None
        block = (cell[0] // downsample, cell[1] // downsample)
        refused = INSCRIBED <= int(blocks[block[1], block[0]]) < NO_INFORMATION
        opened.append(block if refused else None)
    legs = list(itertools.pairwise(poses))
    # the grid steps out of and into opened blocks are not judged
    legs = legs[int(opened[0] is not None) : len(legs) - int(opened[1] is not None)]
    bad = []
    for (x0, y0, _), (x1, y1, _) in legs:
        n = max(2, SAMPLES_PER_CELL * math.ceil(math.hypot(x1 - x0, y1 - y0) / RES))
        for t in (np.arange(n) + 0.5) / n:
            x, y = x0 + (x1 - x0) * t, y0 + (y1 - y0) * t
            cell = grid.geometry.world_to_cell(x, y)
            assert cell is not None, f"leg leaves the map at ({x:.3f}, {y:.3f})"
            if (cell[0] // downsample, cell[1] // downsample) in opened or on_a_corner(grid, x, y):
                continue
            cost = int(grid.costs[cell[1], cell[0]])
            if INSCRIBED <= cost < NO_INFORMATION:
                bad.append((x, y))
    return bad


@settings(max_examples=60, deadline=None)
@example(seed=99, size=45, boxes=11, downsample=2, planner_id="GridBased")  # a diagonal step
@given(
    seed=st.integers(0, 2**31),
    size=st.integers(30, 90),
    boxes=st.integers(0, 12),
    downsample=st.integers(1, 4),
    planner_id=st.sampled_from(["ThetaStar", "GridBased"]),
)
def test_paths_are_dense_and_valid_on_random_maps(
    seed: int, size: int, boxes: int, downsample: int, planner_id: str
) -> None:
    grid = random_world(seed, size, boxes)
    rng = np.random.default_rng(seed + 1)
    start_xy, goal_xy = free_point(grid, rng), free_point(grid, rng)
    if start_xy is None or goal_xy is None:
        return
    start, goal = (*start_xy, 0.0), (*goal_xy, 1.0)
    try:
        poses = plan(grid, start, goal, planner_id, params=SearchParams(downsample=downsample))
    except PlanningError as err:
        reason = err.reason
        poses = []
    if not poses:
        assert reason == "NO_VALID_PATH"
        return
    assert poses[0][:2] == start[:2]
    assert poses[-1] == goal
    assert invalid_poses(grid, poses) == []
    longest = max(
        (math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in itertools.pairwise(poses)), default=0.0
    )
    assert longest <= LONGEST_STEP * RES * downsample + 1e-9
    assert refused_crossings(grid, poses, downsample, (start, goal)) == []


@pytest.mark.parametrize("downsample", [1, 2, 3])
def test_theta_star_fills_a_single_straight_leg(downsample: int) -> None:
    """The path that once came back as just [start, goal], 14 m apart."""
    grid = random_world(seed=0, size=300, boxes=0)
    poses = plan(
        grid, (1.0, 1.0, 0.0), (13.0, 8.0, 0.0), "ThetaStar",
        params=SearchParams(downsample=downsample),
    )  # fmt: skip
    steps = [math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in itertools.pairwise(poses)]
    assert len(poses) > 13.9 / (RES * downsample)
    assert max(steps) <= RES * downsample + 1e-9
    assert sum(steps) == pytest.approx(math.hypot(12.0, 7.0), rel=1e-9)


def test_theta_star_does_not_cut_an_inflated_door_jamb() -> None:
    """A door in a wall, start and goal beyond it on a diagonal through the jamb's zone."""
    occupancy = np.zeros((80, 80), dtype=np.int8)
    occupancy[:, 40] = 100
    occupancy[30:42, 40] = 0  # a 0.6 m door
    grid = Costmap.from_occupancy(
        occupancy, GridGeometry(80, 80, RES), inflation=InflationParams()
    ).snapshot()
    start, goal = (0.5, 3.5, 0.0), (3.5, 0.4, 0.0)
    poses = plan(grid, start, goal, "ThetaStar", params=SearchParams(downsample=1))
    assert invalid_poses(grid, poses) == []
    assert refused_crossings(grid, poses, 1, (start, goal)) == []
