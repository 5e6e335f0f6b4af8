"""simple_smoother, IsPathValid and the boustrophedon coverage planner."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import INSCRIBED, LETHAL, NO_INFORMATION, points_cost
from aiobt_services.planner.coverage import CoverageError, CoverageParams, plan_coverage
from aiobt_services.planner.planning import path_length
from aiobt_services.planner.smoother import in_collision, smooth
from aiobt_services.planner.validity import invalid_poses

from .conftest import grid_from


def zigzag(n: int = 30) -> list[tuple[float, float, float]]:
    return [(0.1 + 0.05 * i, 1.0 + (0.05 if i % 2 else -0.05), 0.0) for i in range(n)]


def test_smoother_straightens_and_keeps_ends() -> None:
    grid = grid_from(np.zeros((40, 40), dtype=np.uint8))
    poses = zigzag()
    done = smooth(grid, poses)
    assert done.completed
    assert done.poses[0][:2] == poses[0][:2]
    assert done.poses[-1] == poses[-1]
    assert path_length(done.poses) < path_length(poses) * 0.8
    wiggle = np.abs(np.diff([y for _, y, _ in done.poses[5:-5]])).max()
    assert wiggle < 0.02


def test_smoother_never_moves_a_point_into_an_obstacle() -> None:
    costs = np.zeros((40, 40), dtype=np.uint8)
    costs[9, 5:25] = LETHAL  # just below the zigzag's low points (y 0.95)
    grid = grid_from(costs)
    done = smooth(grid, zigzag())
    xy = np.array([(x, y) for x, y, _ in done.poses])
    assert (points_cost(grid, xy[:, 0], xy[:, 1]) < INSCRIBED).all()
    assert not in_collision(grid, done.poses)


def test_smoother_reports_timeout_and_short_paths() -> None:
    grid = grid_from(np.zeros((40, 40), dtype=np.uint8))
    assert smooth(grid, zigzag(), max_duration=-1.0).timed_out
    two = [(0.1, 0.1, 0.0), (0.5, 0.5, 0.0)]
    assert smooth(grid, two).poses == two


def test_path_validity_max_cost_unknown_and_lookahead() -> None:
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[5, 3] = LETHAL
    costs[5, 8] = NO_INFORMATION
    costs[5, 12] = 200
    grid = grid_from(costs)
    path = [(0.05 + 0.1 * i, 0.55, 0.0) for i in range(20)]
    assert invalid_poses(grid, path) == [3]
    assert invalid_poses(grid, path, consider_unknown_as_obstacle=True) == [3, 8]
    assert invalid_poses(grid, path, max_cost=200) == [3, 12]
    assert invalid_poses(grid, path, robot=(0.65, 0.55)) == []  # lethal cell already passed
    off_map = [*path, (5.0, 5.0, 0.0)]
    assert invalid_poses(grid, off_map, robot=(0.65, 0.55)) == [20]
    assert invalid_poses(grid, []) == []


def inside(polygon: list[tuple[float, float]], x: float, y: float) -> bool:
    crossings = 0
    for (x0, y0), (x1, y1) in zip(polygon, [*polygon[1:], polygon[0]], strict=True):
        if (y0 <= y) != (y1 <= y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            crossings += 1
    return crossings % 2 == 1


def test_coverage_of_a_rectangle() -> None:
    field = [(0.0, 0.0), (6.0, 0.0), (6.0, 3.0), (0.0, 3.0)]
    coverage = plan_coverage([field], CoverageParams(row_spacing=0.5, headland_width=0.5))
    assert len(coverage.swaths) == 4  # rows at y = 0.75, 1.25, 1.75, 2.25
    ys = [a[1] for a, _ in coverage.swaths]
    assert ys == pytest.approx([0.75, 1.25, 1.75, 2.25])
    for k, (a, b) in enumerate(coverage.swaths):
        assert (a[0] < b[0]) == (k % 2 == 0)  # boustrophedon: alternate directions
        assert min(a[0], b[0]) == pytest.approx(0.5)
        assert max(a[0], b[0]) == pytest.approx(5.5)
    steps = np.hypot(*np.diff(np.array([p[:2] for p in coverage.path]), axis=0).T)
    assert steps.max() <= 0.05 + 1e-9
    assert all(inside(field, x, y) for x, y, _ in coverage.path)


def test_coverage_of_a_rotated_field_with_a_hole() -> None:
    c, s = math.cos(0.5), math.sin(0.5)
    square = [(0.0, 0.0), (8.0, 0.0), (8.0, 4.0), (0.0, 4.0)]
    field = [(x * c - y * s, x * s + y * c) for x, y in square]
    hole = [(x * c - y * s, x * s + y * c) for x, y in [(3, 1), (5, 1), (5, 3), (3, 3)]]
    coverage = plan_coverage([field, hole], CoverageParams(0.5, 0.25))
    for a, b in coverage.swaths:
        mid = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
        assert inside(field, *mid)
        assert not inside(hole, *mid)
        assert math.atan2(b[1] - a[1], b[0] - a[0]) % math.pi == pytest.approx(0.5)
    # drivable: the route between swaths (and cells) never crosses the cut-out
    # (a row may run along the cut-out's edge: only its inside, 1 cm in, counts)
    core = [(x * c - y * s, x * s + y * c) for x, y in [(3.01, 1.01), (4.99, 1.01), (4.99, 2.99),
                                                        (3.01, 2.99)]]  # fmt: skip
    assert all(inside(field, x, y) and not inside(core, x, y) for x, y, _ in coverage.path)
    steps = np.hypot(*np.diff(np.array([p[:2] for p in coverage.path]), axis=0).T)
    assert steps.max() <= 0.25 + 1e-9
    assert len(coverage.swaths) >= 11  # 7 rows, 4 or 5 of them split by the hole


@pytest.mark.parametrize(
    ("polygons", "reason"),
    [
        ([], "INVALID_REQUEST"),
        ([[(0.0, 0.0), (1.0, 0.0)]], "INVALID_COORDS"),
        ([[(0.0, 0.0), (1.0, math.nan), (1.0, 1.0)]], "INVALID_COORDS"),
        ([[(0.0, 0.0), (0.6, 0.0), (0.6, 0.6), (0.0, 0.6)]], "INVALID_REQUEST"),
    ],
)
def test_bad_fields_get_their_error(polygons: list[list[tuple[float, float]]], reason: str) -> None:
    with pytest.raises(CoverageError) as err:
        plan_coverage(polygons, CoverageParams(0.5, 0.5))
    assert err.value.reason == reason


@pytest.mark.parametrize("turn", [0.0, 0.7])
def test_coverage_of_a_u_shaped_field_stays_in_the_field(turn: float) -> None:
    # rows run along the bottom edge; the arms' rows are split by the U's gap, so
    # the arms are separate cells: going from one arm to the other must run
    # through the field (along covered rows), not across the gap
    c, s = math.cos(turn), math.sin(turn)
    u = [(0.0, 0.0), (10.0, 0.0), (10.0, 6.0), (7.0, 6.0), (7.0, 2.0), (3.0, 2.0), (3.0, 6.0),
         (0.0, 6.0)]  # fmt: skip
    field = [(x * c - y * s, x * s + y * c) for x, y in u]
    coverage = plan_coverage([field], CoverageParams(row_spacing=0.5, headland_width=0.5))
    assert all(inside(field, x, y) for x, y, _ in coverage.path)
    steps = np.hypot(*np.diff(np.array([p[:2] for p in coverage.path]), axis=0).T)
    assert steps.max() <= 0.05 + 1e-9
    arm_rows = {round(a[1] * c - a[0] * s, 6) for a, _ in coverage.swaths}  # local y
    assert len(coverage.swaths) == 3 + 2 * 7  # 3 full rows, 7 rows split in two
    assert len(arm_rows) == 10


def _notched_field(steps: list[tuple[float, float]], width: float, across: bool) -> list[Point]:
    """A rectilinear field: a straight base ``width`` long and a stepped far side,
    ``steps`` being (run, depth) pairs along it: a U or a comb opening up, or with
    ``across`` a spine at x = 0 and the steps as the right side (an E, an S-like
    comb opening sideways). Rows run along the longest edge, whichever it is."""
    far: list[Point] = []
    position = 0.0
    for run, depth in steps:
        far += [(position, depth), (position + run, depth)]
        position += run
    if not across:  # base along x, the steps above it
        return [(0.0, 0.0), (width, 0.0), *[(x * width / position, d) for x, d in reversed(far)]]
    # base along x, a spine at x = 0, the steps as the right side's profile
    height = 0.8 * width
    profile = [(width * d / max(d for _, d in steps), y * height / position) for y, d in far]
    return [(0.0, 0.0), *[(x, y) for x, y in profile], (0.0, height)]


Point = tuple[float, float]


@settings(max_examples=60, deadline=None)
@given(
    steps=st.lists(st.tuples(st.floats(1.5, 4.0), st.floats(2.0, 6.0)), min_size=2, max_size=5),
    across=st.booleans(),
    turn=st.floats(0.0, 2 * math.pi),
    spacing=st.sampled_from([0.3, 0.5, 0.8]),
)
def test_coverage_routes_stay_in_notched_fields(
    steps: list[tuple[float, float]], across: bool, turn: float, spacing: float
) -> None:
    width = 1.2 * max(sum(run for run, _ in steps), max(d for _, d in steps), 8.0)
    field = _notched_field(steps, width, across)
    c, s = math.cos(turn), math.sin(turn)
    field = [(x * c - y * s, x * s + y * c) for x, y in field]
    try:
        coverage = plan_coverage([field], CoverageParams(row_spacing=spacing, headland_width=0.3))
    except CoverageError:
        return  # a field too small for a swath
    assert all(inside(field, x, y) for x, y, _ in coverage.path)
