"""Nav2's footprint helpers (``nav2_costmap_2d/footprint``) and the footprint cost at many
poses at once, against the outline sampled edge by edge."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.costmap import (
    LETHAL,
    CostGrid,
    GridGeometry,
    footprint_cost,
    footprint_from_radius,
    footprints_cost,
    oriented_footprint,
    parse_footprint,
    points_cost,
)
from aiobt.costmap.collision import segment_points


def outline_cost(grid: CostGrid, x: float, y: float, yaw: float, footprint: np.ndarray) -> int:
    """Nav2's footprintCost written plainly: each edge of the placed polygon sampled."""
    placed = oriented_footprint(x, y, yaw, footprint)
    spacing = grid.geometry.resolution / 2
    edges = [segment_points(a[0], a[1], b[0], b[1], spacing)
             for a, b in zip(placed, np.roll(placed, -1, axis=0), strict=True)]  # fmt: skip
    costs = [points_cost(grid, e[:, 0], e[:, 1]) for e in edges]
    every = np.concatenate(costs)
    return LETHAL if (every == LETHAL).any() else int(every.max())


def test_a_radius_gives_nav2s_sixteen_points() -> None:
    points = footprint_from_radius(0.5)
    angles = np.arange(16) * 2 * math.pi / 16
    np.testing.assert_allclose(points, 0.5 * np.column_stack((np.cos(angles), np.sin(angles))))
    with pytest.raises(ValueError, match="radius must be finite and > 0"):
        footprint_from_radius(0.0)


def test_a_footprint_string_is_parsed_or_named() -> None:
    np.testing.assert_allclose(parse_footprint("[[1, 0], [0, 1], [-1, 0]]"),
                               [[1, 0], [0, 1], [-1, 0]])  # fmt: skip
    with pytest.raises(ValueError, match="is not a list of"):
        parse_footprint("[[1, 0]")
    with pytest.raises(ValueError, match="non-finite"):
        parse_footprint("[[1, 0], [0, 1], [NaN, 0]]")


def test_many_poses_cost_as_each_alone() -> None:
    rng = np.random.default_rng(7)
    geometry = GridGeometry(60, 40, 0.05, -1.0, -1.0)
    costs = rng.choice(np.array([0, 50, 253, 254, 255], dtype=np.uint8), size=(40, 60),
                       p=[0.9, 0.04, 0.02, 0.02, 0.02])  # fmt: skip
    grid = CostGrid(geometry, costs)
    footprint = np.array([[0.3, 0.1], [0.0, -0.2], [-0.25, 0.15]])
    poses = np.column_stack((rng.uniform(-1.2, 2.2, 200), rng.uniform(-1.2, 1.2, 200),
                             rng.uniform(-math.pi, math.pi, 200)))  # fmt: skip
    many = footprints_cost(grid, poses, footprint)
    one = [outline_cost(grid, x, y, yaw, footprint) for x, y, yaw in poses]
    assert many.tolist() == one
    assert [footprint_cost(grid, x, y, yaw, footprint) for x, y, yaw in poses[:20]] == one[:20]
    assert LETHAL in one  # lethal, unknown and lower costs all come out
    assert {0, 255} & set(one)
    with pytest.raises(ValueError, match="at least 3 vertices"):
        footprints_cost(grid, poses, footprint[:2])
