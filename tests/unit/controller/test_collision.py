"""Costmap queries, arc projection, and RPP's cost-regulated speed."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.costmap import INSCRIBED, LETHAL, NO_INFORMATION
from aiobt.costmap.checker import CollisionChecker, CostQuery, GridCostmap
from aiobt.geometry import Pose2D, Velocity
from aiobt_services.controller.base import ControlContext
from aiobt_services.controller.rpp import RegulatedPurePursuit

from .courses import straight


def _grid() -> GridCostmap:
    return GridCostmap.empty(4.0, 4.0, 0.05, (-2.0, -2.0))


def test_grid_is_a_cost_query_and_outside_is_unknown():
    grid = _grid()
    assert isinstance(grid, CostQuery)
    grid.fill_box(0.5, 0.5, 0.6, 0.6, LETHAL)
    costs = grid.costs_at(np.array([[0.55, 0.55], [0.0, 0.0], [5.0, 0.0]]))
    assert costs.tolist() == [LETHAL, 0, NO_INFORMATION]


def test_arc_check_reports_time_to_first_collision():
    grid = _grid()
    grid.fill_box(1.0, -2.0, 1.1, 2.0, LETHAL)
    checker = CollisionChecker(grid)
    hit = checker.check_arc(Pose2D(0.0, 0.0, 0.0), Velocity(0.5, 0.0), horizon=3.0)
    assert hit.collides
    assert hit.time_to_collision == pytest.approx(2.0, abs=0.06)
    short = checker.check_arc(Pose2D(0.0, 0.0, 0.0), Velocity(0.5, 0.0), horizon=1.5)
    assert not short.collides
    away = checker.check_arc(Pose2D(0.0, 0.0, 0.0), Velocity(0.5, 0.0), 3.0, max_distance=0.9)
    assert not away.collides


def test_arc_check_follows_curvature():
    grid = _grid()
    grid.fill_box(0.9, 0.9, 1.1, 1.1, INSCRIBED)  # on the left quarter circle of radius 1
    checker = CollisionChecker(grid)
    left = checker.check_arc(Pose2D(0.0, 0.0, 0.0), Velocity(0.5, 0.5), horizon=4.0)
    right = checker.check_arc(Pose2D(0.0, 0.0, 0.0), Velocity(0.5, -0.5), horizon=4.0)
    assert left.collides
    assert not right.collides


def test_unknown_blocks_only_when_not_allowed():
    grid = _grid()
    pose_outside = Pose2D(3.0, 0.0, 0.0)
    assert not CollisionChecker(grid, allow_unknown=True).pose_collides(pose_outside)
    assert CollisionChecker(grid, allow_unknown=False).pose_collides(pose_outside)


def test_rpp_slows_down_near_obstacles():
    rpp = RegulatedPurePursuit()
    rpp.set_plan(straight(4.0))
    grid = _grid()
    ctx_free = ControlContext(0.05, 0.25, CollisionChecker(grid))
    free = rpp.compute_velocity(Pose2D(0.0, 0.0, 0.0), Velocity(0.5, 0.0), ctx_free)
    # inflation cost at 0.35 m from an obstacle with inscribed radius 0.3
    grid.costs[:] = round(252 * math.exp(-3.0 * (0.35 - 0.3)))
    rpp.set_plan(straight(4.0))
    near = rpp.compute_velocity(Pose2D(0.0, 0.0, 0.0), Velocity(0.5, 0.0), ctx_free)
    assert free.v == pytest.approx(0.5)
    assert near.v == pytest.approx(0.5 * 0.35 / 0.6, abs=0.01)
