"""The obstacle layer's vectorised ray tracing against a plain per-ray, per-sample one."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import (
    FREE,
    LETHAL,
    NO_INFORMATION,
    Costmap,
    GridGeometry,
    ObstacleParams,
    Scan,
    clear_and_mark,
)
from aiobt.costmap.obstacle_layer import HIT_DEPTH, _rays


def reference(grid: np.ndarray, g: GridGeometry, scan: Scan, params: ObstacleParams) -> np.ndarray:
    """Each ray sampled every half cell up to its clearing length (the hit's own cell not
    cleared by its ray), then the hits marked; the flat cells whose value changed.

    The samples in float32 cell coordinates, as :func:`clear_and_mark` documents its
    arithmetic (the sensor's cell plus the ray's direction in cells times the distance:
    a sample within ~1e-5 of a cell's edge may fall in the cell beside, so float64
    world coordinates differ there); the hits in float64 world coordinates."""
    angles, ranges, clear_len, hit = _rays(scan, params)
    res = g.resolution
    step = res * 0.5
    longest = float(clear_len.max(initial=0.0))
    samples = np.arange(0.0, longest, step) if longest > 0.0 else np.empty(0)
    samples = samples.astype(np.float32)
    sensor_col = np.float32((scan.sensor_x - g.origin_x) / res)
    sensor_row = np.float32((scan.sensor_y - g.origin_y) / res)
    before = grid.copy()
    cleared: set[int] = set()
    marked: set[int] = set()
    for ray, angle in enumerate(angles):
        dx, dy = np.float32(np.cos(angle) / res), np.float32(np.sin(angle) / res)
        limit = np.float32(clear_len[ray] - (step if hit[ray] > 0 else 0.0))
        for t in samples[samples < limit]:
            cleared |= cell_at(g, sensor_col + dx * t, sensor_row + dy * t)
        if hit[ray] > 0:
            r = ranges[ray] + HIT_DEPTH
            marked |= cell_of(
                g, scan.sensor_x + math.cos(angle) * r, scan.sensor_y + math.sin(angle) * r
            )
    flat = grid.reshape(-1)
    flat[sorted(cleared)] = FREE
    flat[sorted(marked)] = LETHAL
    return np.flatnonzero(grid.reshape(-1) != before.reshape(-1))


def cell_at(g: GridGeometry, col: np.float32, row: np.float32) -> set[int]:
    """The cell at cell coordinates (``col``, ``row``), if inside."""
    if 0 <= col < g.width and 0 <= row < g.height:
        return {int(row) * g.width + int(col)}
    return set()


def cell_of(g: GridGeometry, x: float, y: float) -> set[int]:
    col = np.floor((np.float64(x) - g.origin_x) / g.resolution)
    row = np.floor((np.float64(y) - g.origin_y) / g.resolution)
    if 0 <= col < g.width and 0 <= row < g.height:
        return {int(row) * g.width + int(col)}
    return set()


reading = st.one_of(
    st.floats(0.0, 4.0), st.just(math.inf), st.just(math.nan), st.sampled_from([0.0, 0.5, 1.0])
)


@settings(max_examples=60)
@given(
    size=st.tuples(st.integers(3, 40), st.integers(3, 40)),
    resolution=st.sampled_from([0.05, 0.1, 0.07]),
    pose=st.tuples(st.floats(-1.0, 3.0), st.floats(-1.0, 3.0), st.floats(-math.pi, math.pi)),
    ranges=st.lists(reading, min_size=1, max_size=40),
    increment=st.floats(0.01, 0.3),
    max_ranges=st.tuples(st.floats(0.2, 3.0), st.floats(0.2, 3.5)),
    inf_is_valid=st.booleans(),
    seed=st.integers(0, 2**16),
)
def test_clear_and_mark_equals_tracing_each_ray(
    size: tuple[int, int],
    resolution: float,
    pose: tuple[float, float, float],
    ranges: list[float],
    increment: float,
    max_ranges: tuple[float, float],
    inf_is_valid: bool,
    seed: int,
) -> None:
    g = GridGeometry(size[0], size[1], resolution, -0.5, -0.5)
    params = ObstacleParams(
        obstacle_max_range=max_ranges[0],
        raytrace_max_range=max_ranges[1],
        inf_is_valid=inf_is_valid,
    )
    scan = Scan.create(pose, -1.0, increment, ranges, 0.05, 3.0)
    rng = np.random.default_rng(seed)
    start = rng.choice(np.array([FREE, LETHAL, NO_INFORMATION], np.uint8), size=g.shape)
    expected_grid = start.copy()
    expected = reference(expected_grid, g, scan, params)
    grid = start.copy()
    changed = clear_and_mark(grid, g, scan, params)
    assert np.array_equal(grid, expected_grid)
    assert np.array_equal(changed, expected)


def test_a_scan_from_outside_the_grid_touches_only_cells_inside() -> None:
    g = GridGeometry(10, 10, 0.1, 0.0, 0.0)
    grid = np.full(g.shape, NO_INFORMATION, np.uint8)
    scan = Scan.create((-0.55, 0.55, 0.0), 0.0, 0.1, [1.0], 0.0, 5.0)  # a hit at x = 0.45
    changed = clear_and_mark(grid, g, scan, ObstacleParams())
    assert grid[5, 4] == LETHAL
    assert (grid[5, 0:4] == FREE).all()
    assert (grid[5, 5:] == NO_INFORMATION).all()
    assert set(changed.tolist()) == {50, 51, 52, 53, 54}


def test_a_beam_ending_on_a_wall_face_marks_the_wall_cell_from_either_side() -> None:
    """A wall one cell thick (x 0.50-0.55) seen from both sides: a beam ends exactly on
    its face, which is a cell boundary; the hit is the wall's cell, so a static wall
    seen again and again changes nothing (from +x, 0.55 / 0.05 floors to the free
    cell beyond the face without the hit depth)."""
    g = GridGeometry(20, 20, 0.05)
    occupancy = np.zeros((20, 20), dtype=np.int8)
    occupancy[:, 10] = 100
    costmap = Costmap.from_occupancy(occupancy, g)
    costmap.master  # noqa: B018 - built
    version = costmap.version
    for x, yaw, reach in ((0.9, math.pi, 0.35), (0.2, 0.0, 0.3)):
        scan = Scan.create((x, 0.525, yaw), 0.0, 0.1, [reach], 0.0, 5.0)
        costmap.update_from_scan(scan)
        marked = np.argwhere(costmap.obstacles == LETHAL)
        assert [tuple(cell) for cell in marked] == [(10, 10)], (x, marked)
    costmap.master  # noqa: B018 - brought up to date
    assert costmap.version == version
