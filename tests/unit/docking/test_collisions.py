"""The approach's collision check (Nav2's docking ``Controller::isTrajectoryCollisionFree``
with its ``CostmapTopicCollisionChecker``): the footprint's outline at each projected
pose against lethal cells, and no check within ``dock_collision_threshold`` of the dock
(docking) or of the robot's start (undocking). Nav2's ``test_controller.cpp`` cases on a
10 x 10 m costmap at 0.1 m with its 0.5 m square footprint."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.costmap import FREE, LETHAL, CostGrid, GridGeometry, footprint_from_radius
from aiobt.geometry import FloatArray, Pose2D
from aiobt_services.docking.collisions import footprint_collides, poses_in
from aiobt_services.docking.controller import ControllerParams, DockController
from aiobt_services.docking.errors import FailedToControl

SQUARE = np.array([[0.5, 0.5], [0.5, -0.5], [-0.5, -0.5], [-0.5, 0.5]])  # Nav2's test's


def grid(size: float = 10.0, resolution: float = 0.1) -> CostGrid:
    cells = round(size / resolution)
    geometry = GridGeometry(cells, cells, resolution, -size / 2, -size / 2)
    return CostGrid(geometry, np.zeros((cells, cells), dtype=np.uint8))


def rectangle(costs: CostGrid, width: float, height: float, x: float, y: float) -> None:
    """Nav2's test ``setRectangle``: lethal cells from the cell of (x, y) on, ``width``
    along x and ``height`` along y."""
    cell = costs.geometry.world_to_cell(x, y)
    assert cell is not None
    res = costs.geometry.resolution
    col, row = cell
    costs.costs[row : row + int(height / res), col : col + int(width / res)] = LETHAL


def controller(costs: CostGrid, footprint: FloatArray, threshold: float = 0.3) -> DockController:
    """The controller checking on ``costs`` (in the robot's frame: the robot at 0, 0, 0)."""
    params = ControllerParams(projection_time=10.0, simulation_time_step=0.1,
                              dock_collision_threshold=threshold)  # fmt: skip
    return DockController(params, lambda poses: footprint_collides(costs, Pose2D(), poses,
                                                                    footprint))  # fmt: skip


def test_a_footprint_corner_on_a_lethal_cell_collides_while_the_centre_is_free() -> None:
    costs = grid(2.0, 0.05)
    corner = costs.geometry.world_to_cell(0.26, 0.26)
    assert corner is not None
    costs.costs[corner[1], corner[0]] = LETHAL
    ahead = [Pose2D(0.0, 0.0, 0.0)]
    square = SQUARE / 2  # corners at (+-0.25, +-0.25)
    assert costs.costs[20, 20] == FREE  # the centre's cell
    assert footprint_collides(costs, Pose2D(), ahead, square)
    assert not footprint_collides(costs, Pose2D(), ahead, footprint_from_radius(0.22))
    # turned a quarter, the corner is still on it; turned an eighth, no corner is
    assert footprint_collides(costs, Pose2D(), [Pose2D(0.0, 0.0, math.pi / 2)], square)
    assert not footprint_collides(costs, Pose2D(), [Pose2D(0.0, 0.0, math.pi / 4)], square)


def test_poses_are_placed_from_the_robots_pose_and_off_the_grid_collides() -> None:
    costs = grid(2.0, 0.05)
    rectangle(costs, 0.1, 0.1, 0.5, 0.5)
    robot = Pose2D(0.5, 0.0, math.pi / 2)
    placed = poses_in(robot, [Pose2D(0.5, 0.0, 0.0)])
    np.testing.assert_allclose(placed, [[0.5, 0.5, math.pi / 2]], atol=1e-12)
    circle = footprint_from_radius(0.1)
    assert footprint_collides(costs, robot, [Pose2D(0.5, 0.0, 0.0)], circle)
    assert not footprint_collides(costs, Pose2D(), [Pose2D(0.5, 0.0, 0.0)], circle)
    assert footprint_collides(costs, Pose2D(), [Pose2D(0.95, 0.0, 0.0)], circle)  # leaves it
    assert not footprint_collides(costs, Pose2D(), [], circle)


def test_nav2s_collision_checker_dock_forward() -> None:
    costs = grid()
    dock = Pose2D(1.75, 0.0, 0.0)
    assert controller(costs, SQUARE).trajectory_free(dock, backward=False, docking=True)
    # the dock itself, 0.2 x 1.5 m at 2 m: within dock_collision_threshold, not checked
    rectangle(costs, 0.2, 1.5, 2.0, -0.75)
    assert controller(costs, SQUARE).trajectory_free(dock, backward=False, docking=True)
    # with no threshold it is hit
    assert not controller(costs, SQUARE, 0.0).trajectory_free(dock, backward=False, docking=True)
    # an object between the robot and the dock
    costs.costs[:] = FREE
    rectangle(costs, 0.2, 0.2, 1.0, -0.1)
    assert not controller(costs, SQUARE).trajectory_free(dock, backward=False, docking=True)
    with pytest.raises(FailedToControl, match="Failed to get control"):
        controller(costs, SQUARE).command(dock, backward=False, docking=True)


def test_nav2s_collision_checker_undock_backward() -> None:
    costs = grid()
    staging = Pose2D(-1.75, 0.0, 0.0)
    assert controller(costs, SQUARE).trajectory_free(staging, backward=True, docking=False)
    # the dock in front of the docked robot: within the threshold of the start
    rectangle(costs, 0.2, 1.5, 0.25, -0.75)
    assert controller(costs, SQUARE).trajectory_free(staging, backward=True, docking=False)
    assert not controller(costs, SQUARE, 0.0).trajectory_free(staging, backward=True,
                                                              docking=False)  # fmt: skip
    for x in (-1.75 - 0.5, -1.0):  # beyond the staging pose; between robot and staging pose
        costs.costs[:] = FREE
        rectangle(costs, 0.2, 0.2, x, -0.1)
        assert not controller(costs, SQUARE).trajectory_free(staging, backward=True,
                                                             docking=False)  # fmt: skip


def test_only_poses_beyond_the_threshold_are_checked() -> None:
    seen: list[Pose2D] = []

    def record(poses: list[Pose2D]) -> bool:
        seen.extend(poses)
        return False

    dock = Pose2D(1.0, 0.2, 0.1)
    params = ControllerParams(projection_time=20.0, dock_collision_threshold=0.3)
    assert DockController(params, record).trajectory_free(dock, backward=False, docking=True)
    assert seen
    assert min(math.hypot(p.x - dock.x, p.y - dock.y) for p in seen) > 0.3
    seen.clear()
    DockController(params, record).trajectory_free(Pose2D(-1.0, 0.0, 0.0), True, docking=False)
    assert min(math.hypot(p.x, p.y) for p in seen) > 0.3
    assert max(math.hypot(p.x, p.y) for p in seen) > 0.9  # the far end is checked
