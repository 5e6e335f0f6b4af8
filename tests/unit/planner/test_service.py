"""The planner service's clearing and validity handlers (no Zenoh: the bus is not used)."""

from __future__ import annotations

from typing import cast

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
from aiobt_services.costmap import LETHAL
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


def lethal(grid: GlobalCostmap, x: float, y: float) -> bool:
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
    see(grid, 0.4, 2.0, 0.5)
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
    reply = srv.is_path_valid(IsPathValid.Request(path=path))
    assert not reply.is_valid
    assert 10 in reply.invalid_pose_indices
    odom = Path.model_validate({"header": {"frame_id": "odom"}, "poses": poses})
    reply = srv.is_path_valid(IsPathValid.Request(path=odom))
    assert not reply.is_valid
    assert reply.invalid_pose_indices == list(range(20))
    assert not service(GlobalCostmap()).is_path_valid(IsPathValid.Request(path=path)).is_valid


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
