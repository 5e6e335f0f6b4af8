"""The planner service's clearing and validity handlers (no Zenoh: the bus is not used)."""

from __future__ import annotations

from typing import cast

from aiobt.costmap import LETHAL
from aiobt.costmap.world import FedCostmap
from aiobt.msgs import (
    ClearCostmapAroundPose,
    ClearCostmapExceptRegion,
    ClearEntireCostmap,
    GetCosts,
    IsPathValid,
    LaserScan,
    Path,
    PoseStamped,
)
from aiobt.transport import Bus
from aiobt_services.planner.actions import PlannerActions
from aiobt_services.planner.service import PlannerService
from aiobt_services.planner.state import GlobalCostmap

from .test_actions import world


def service(grid: GlobalCostmap | None = None) -> PlannerService:
    grid = grid or world()
    return PlannerService(cast(Bus, None), grid, PlannerActions(grid))


def see(grid: GlobalCostmap, *ranges: float) -> None:
    """One scan from the robot at (1, 1) facing +x: beams at 0, 90, 180 degrees."""
    scan = LaserScan(angle_min=0.0, angle_max=3.1416, angle_increment=1.5708, range_min=0.1,
                     range_max=5.0, ranges=list(ranges))  # fmt: skip
    grid.on_scan(scan)


def lethal(grid: FedCostmap, x: float, y: float) -> bool:
    """A lethal cell within one cell of (x, y) (a hit on a cell border lands either side)."""
    snapshot = grid.snapshot()
    assert snapshot is not None
    row, col = int(y / 0.05), int(x / 0.05)
    return bool((snapshot.costs[row - 1 : row + 2, col - 1 : col + 2] == LETHAL).any())


def test_clear_except_keeps_the_square_around_the_robot() -> None:
    grid = world()
    see(grid, 0.4, 2.0, 0.5)  # marks (1.4, 1), (1, 3), (0.5, 1)
    srv = service(grid)
    reply = srv.clear_except(ClearCostmapExceptRegion.Request(reset_distance=1.5))
    assert reply.success
    assert "outside the 1.5 m square" in reply.message
    assert lethal(grid, 1.4, 1.0)
    assert lethal(grid, 0.5, 1.0)
    assert not lethal(grid, 1.0, 3.0)


def test_clear_around_robot_and_around_a_pose() -> None:
    grid = world()
    see(grid, 0.4, 2.0, 0.45)  # the hit behind at x 0.55, inside the square (0.5 is its edge)
    srv = service(grid)
    reply = srv.clear_around(ClearCostmapExceptRegion.Request(reset_distance=1.0))
    assert reply.success
    assert not lethal(grid, 1.4, 1.0)
    assert not lethal(grid, 0.5, 1.0)
    assert lethal(grid, 1.0, 3.0)
    req = ClearCostmapAroundPose.Request(pose=PoseStamped.from_xy_yaw(1.0, 3.0), reset_distance=0.5)
    assert srv.clear_around_pose(req).success
    assert not lethal(grid, 1.0, 3.0)


def test_clearing_refuses_without_map_pose_or_in_another_frame() -> None:
    empty = service(GlobalCostmap())
    assert not empty.clear_entirely(ClearEntireCostmap.Request()).success
    assert not empty.clear_except(ClearCostmapExceptRegion.Request()).success
    assert "no map" in empty.clear_around(ClearCostmapExceptRegion.Request()).message
    grid = world()
    grid.pose = None
    assert not service(grid).clear_except(ClearCostmapExceptRegion.Request()).success
    odom = PoseStamped.from_xy_yaw(1.0, 1.0, frame_id="odom")
    reply = service().clear_around_pose(ClearCostmapAroundPose.Request(pose=odom))
    assert not reply.success
    assert "'odom'" in reply.message


def test_is_path_valid_sees_a_new_obstacle_and_refuses_other_frames() -> None:
    grid = world()
    srv = service(grid)
    poses = [PoseStamped.from_xy_yaw(1.0 + 0.05 * i, 1.0) for i in range(20)]
    path = Path(poses=poses)
    assert srv.is_path_valid(IsPathValid.Request(path=path)).is_valid
    see(grid, 0.5, 5.0 + 1.0, 5.0 + 1.0)  # an obstacle 0.5 m ahead on the path
    first = srv.is_path_valid(IsPathValid.Request(path=path))
    assert not first.is_valid
    assert len(first.invalid_pose_indices) == 1  # stop_at_first_collision, Nav2's default
    every = srv.is_path_valid(IsPathValid.Request(path=path, stop_at_first_collision=False))
    assert every.invalid_pose_indices[0] == first.invalid_pose_indices[0]
    assert 10 in every.invalid_pose_indices  # the obstacle's own cell
    near = srv.is_path_valid(IsPathValid.Request(path=path, max_lookahead_distance=0.2))
    assert near.is_valid  # the 5 poses within 0.2 m of the robot are clear
    odom = Path.model_validate({"header": {"frame_id": "odom"}, "poses": poses})
    reply = srv.is_path_valid(IsPathValid.Request(path=odom))
    assert (reply.is_valid, reply.success) == (False, False)
    assert "'odom'" in reply.message
    no_map = service(GlobalCostmap()).is_path_valid(IsPathValid.Request(path=path))
    assert (no_map.is_valid, no_map.success) == (False, False)
    assert "no map" in no_map.message


def test_is_path_valid_on_one_layer_or_with_a_footprint() -> None:
    grid = world()
    srv = service(grid)
    poses = [PoseStamped.from_xy_yaw(1.0 + 0.05 * i, 1.0) for i in range(20)]
    path = Path(poses=poses)
    see(grid, 0.5, 5.0 + 1.0, 5.0 + 1.0)  # an obstacle 0.5 m ahead on the path
    check = IsPathValid.Request(path=path, stop_at_first_collision=False)
    obstacles = srv.is_path_valid(check.model_copy(update={"layer_name": "obstacle_layer"}))
    assert obstacles.success
    assert obstacles.invalid_pose_indices == [10]  # the mark itself, not its inflation
    static = srv.is_path_valid(check.model_copy(update={"layer_name": "static_layer"}))
    assert (static.success, static.is_valid) == (True, True)
    inflation = srv.is_path_valid(check.model_copy(update={"layer_name": "inflation_layer"}))
    assert (inflation.success, inflation.is_valid) == (False, False)
    assert "inflation_layer" in inflation.message
    # a 0.2 m square on the obstacle layer: its outline (Nav2's footprint cost) meets the
    # mark 0.1 m before and after its centre does
    square = "[[0.1, 0.1], [0.1, -0.1], [-0.1, -0.1], [-0.1, 0.1]]"
    boxed = srv.is_path_valid(
        check.model_copy(update={"footprint": square, "layer_name": "obstacle_layer"})
    )
    assert boxed.success
    assert 8 in boxed.invalid_pose_indices
    assert 12 in boxed.invalid_pose_indices
    assert not {0, 1, 2, 3, 4, 5, 6, 14, 15} & set(boxed.invalid_pose_indices)
    bad = srv.is_path_valid(check.model_copy(update={"footprint": "[[0, 0], [1, 1]]"}))
    assert (bad.success, bad.is_valid) == (False, False)
    assert "at least 3" in bad.message


def test_an_empty_path_is_not_valid() -> None:
    """As Nav2's planner server: a tree validating an empty path (Nav2's
    consistent-replanning tree before its first plan) must plan, not follow it."""
    reply = service(world()).is_path_valid(IsPathValid.Request(path=Path(poses=[])))
    assert not reply.is_valid
    assert reply.invalid_pose_indices == []


def test_get_costs_answers_the_cell_costs_and_fails_off_the_map() -> None:
    grid = world()
    srv = service(grid)
    free, ahead = PoseStamped.from_xy_yaw(1.0, 1.0), PoseStamped.from_xy_yaw(1.5, 1.0)
    reply = srv.get_costs(GetCosts.Request(poses=[free, ahead]))
    assert reply.success
    assert reply.costs[1] < LETHAL
    see(grid, 0.5, 5.0 + 1.0, 5.0 + 1.0)  # an obstacle 0.5 m ahead
    assert srv.get_costs(GetCosts.Request(poses=[ahead])).costs[0] >= LETHAL
    off = PoseStamped.from_xy_yaw(-50.0, 1.0)
    reply = srv.get_costs(GetCosts.Request(poses=[free, off]))
    assert not reply.success
    assert reply.costs[1] == 255.0
    assert not service(GlobalCostmap()).get_costs(GetCosts.Request(poses=[free])).success
