"""The bridge's mirror of the planner's inflated costmap, paced by scan stamps."""

from __future__ import annotations

import numpy as np
import pytest

from aiobt.foxglove import convert
from aiobt.foxglove.costmap import CostmapMirror
from aiobt.msgs import Header, LaserScan, OccupancyGrid, PoseStamped

from .test_convert import decoded

LETHAL, INSCRIBED = 254, 253


def scan_at(stamp: float) -> LaserScan:
    return LaserScan(
        header=Header(stamp=stamp, frame_id="base_scan"),
        angle_min=0.0, angle_max=0.1, angle_increment=0.1,
        range_min=0.1, range_max=5.0, ranges=[5.0, 5.0],
    )  # fmt: skip


def world() -> CostmapMirror:
    cells = np.zeros((40, 40), dtype=np.int8)
    cells[20, 30] = 100  # a wall cell 0.5 m east of the middle
    mirror = CostmapMirror(period=1.0)
    mirror.on_map(OccupancyGrid.from_array(cells, resolution=0.05))
    mirror.on_pose(PoseStamped.from_xy_yaw(1.0, 1.0))
    return mirror


def test_the_grid_is_inflated_around_lethal_cells_and_paced() -> None:
    mirror = world()
    grid = mirror.on_scan(scan_at(10.0))
    assert grid is not None
    assert grid.costs[20, 30] == LETHAL
    assert grid.costs[20, 28] == INSCRIBED  # 0.1 m away: inside the 0.22 m inscribed radius
    assert 0 < grid.costs[20, 23] < INSCRIBED  # 0.35 m away: decaying
    assert grid.costs[20, 5] == 0
    assert mirror.on_scan(scan_at(10.5)) is None  # within the period
    assert mirror.on_scan(scan_at(11.0)) is not None


def test_no_grid_before_a_map_and_bad_periods_are_refused() -> None:
    assert CostmapMirror().on_scan(scan_at(1.0)) is None
    with pytest.raises(ValueError, match="costmap period"):
        CostmapMirror(period=0.0)


def test_cost_grid_as_a_uint8_grid() -> None:
    grid = world().on_scan(scan_at(1.0))
    assert grid is not None
    out = decoded(convert.cost_grid(grid, 1.0))
    assert out.column_count == 40
    assert [f.name for f in out.fields] == ["cost"]
    assert np.frombuffer(out.data, dtype=np.uint8).reshape(40, 40)[20, 30] == LETHAL
