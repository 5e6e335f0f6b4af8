"""Wires the planner onto the bus: topics in, action servers and services out."""

from __future__ import annotations

import logging

from aiobt.core.clock import Clock, SystemClock
from aiobt.costmap.feed import RobotFeed
from aiobt.costmap.footprint import parse_footprint
from aiobt.msgs import (
    ClearCostmapAroundPose,
    ClearCostmapAroundRobot,
    ClearCostmapExceptRegion,
    ClearCostmapResponse,
    ClearEntireCostmap,
    ComputeCoveragePath,
    ComputePathThroughPoses,
    ComputePathToPose,
    GetCosts,
    IsPathValid,
    OccupancyGrid,
    SmoothPath,
)
from aiobt.transport import Bus
from aiobt.transport.announce import announce

from .actions import PlannerActions
from .state import MAP_FRAMES, GlobalCostmap
from .validity import invalid_poses, pose_costs

log = logging.getLogger("aiobt_services.planner.service")
COSTMAP = "global_costmap"


class PlannerService:
    """The planner server: a global costmap plus Nav2's planner-server interface.

    The robot's pose and scans are subscribed while requests that need them come
    (:class:`RobotFeed`); ``clock`` (the robot's, default the wall's) times the
    linger after the last one."""

    def __init__(
        self,
        bus: Bus,
        world: GlobalCostmap,
        actions: PlannerActions,
        *,
        sim_time: bool = False,
        clock: Clock | None = None,
    ) -> None:
        self.bus = bus
        self.sim_time = sim_time
        self.world = world
        self.actions = actions
        self.clock = clock or SystemClock()

    def start(self) -> None:
        bus, world, act = self.bus, self.world, self.actions
        feed = RobotFeed(bus, world, self.clock)
        bus.subscribe("map", OccupancyGrid, world.on_map, latched=True)
        bus.action_server(
            ComputePathToPose.name, ComputePathToPose, feed.action(act.compute_path_to_pose)
        )
        bus.action_server(
            ComputePathThroughPoses.name,
            ComputePathThroughPoses,
            feed.action(act.compute_path_through_poses),
        )
        bus.action_server(SmoothPath.name, SmoothPath, feed.action(act.smooth_path))
        bus.action_server(ComputeCoveragePath.name, ComputeCoveragePath, act.compute_coverage_path)
        self._serve_clearing(feed)
        bus.serve(IsPathValid.service_name, IsPathValid.Request, IsPathValid.Response,
                  feed.call(self.is_path_valid))  # fmt: skip
        bus.serve(GetCosts.service_name(COSTMAP), GetCosts.Request, GetCosts.Response,
                  feed.call(self.get_costs))  # fmt: skip
        announce(bus, "planner", sim_time=self.sim_time)

    def _serve_clearing(self, feed: RobotFeed) -> None:
        region, response = ClearCostmapExceptRegion.Request, ClearCostmapResponse
        services = (
            (ClearEntireCostmap, ClearEntireCostmap.Request, self.clear_entirely),
            (ClearCostmapExceptRegion, region, feed.call(self.clear_except)),
            (ClearCostmapAroundRobot, region, feed.call(self.clear_around)),
            (ClearCostmapAroundPose, ClearCostmapAroundPose.Request, self.clear_around_pose),
        )
        for kind, request, handler in services:
            self.bus.serve(kind.service_name(COSTMAP), request, response, handler)  # type: ignore[arg-type]

    def clear_entirely(self, _req: ClearEntireCostmap.Request) -> ClearCostmapResponse:
        if self.world.costmap is None:
            return ClearCostmapResponse(success=False, message="no map received yet")
        self.world.costmap.clear_entirely()
        return ClearCostmapResponse(message="cleared the obstacle layer")

    def _clear_region(
        self, req: ClearCostmapExceptRegion.Request, keep_inside: bool
    ) -> ClearCostmapResponse:
        robot = self.world.robot_xy()
        if self.world.costmap is None or robot is None:
            return ClearCostmapResponse(success=False, message="no map or robot pose yet")
        if keep_inside:
            self.world.costmap.clear_except(*robot, req.reset_distance)
        else:
            self.world.costmap.clear_around(*robot, req.reset_distance)
        where = "outside" if keep_inside else "inside"
        return ClearCostmapResponse(
            message=f"cleared {where} the {req.reset_distance:g} m square around the robot"
        )

    def clear_except(self, req: ClearCostmapExceptRegion.Request) -> ClearCostmapResponse:
        return self._clear_region(req, keep_inside=True)

    def clear_around(self, req: ClearCostmapExceptRegion.Request) -> ClearCostmapResponse:
        return self._clear_region(req, keep_inside=False)

    def clear_around_pose(self, req: ClearCostmapAroundPose.Request) -> ClearCostmapResponse:
        if self.world.costmap is None:
            return ClearCostmapResponse(success=False, message="no map received yet")
        if req.pose.header.frame_id not in MAP_FRAMES:
            msg = f"pose is in frame '{req.pose.header.frame_id}', not 'map'"
            return ClearCostmapResponse(success=False, message=msg)
        self.world.costmap.clear_around(req.pose.x, req.pose.y, req.reset_distance)
        return ClearCostmapResponse(message="cleared around the pose")

    def is_path_valid(self, req: IsPathValid.Request) -> IsPathValid.Response:
        """Nav2's IsPathValid service (see :func:`invalid_poses`); ``success`` false,
        with the reason, for an empty path, no map yet, another frame, an unknown
        ``layer_name`` or a bad ``footprint``."""
        poses = [(p.x, p.y, p.yaw) for p in req.path.poses]
        try:
            if not poses:  # as Nav2's planner server: an empty path cannot be followed
                raise ValueError("the path is empty")
            if req.path.header.frame_id not in MAP_FRAMES:
                raise ValueError(f"the path is in frame '{req.path.header.frame_id}', not 'map'")
            grid = self.world.layer(req.layer_name)
            footprint = parse_footprint(req.footprint) if req.footprint else None
        except (ValueError, LookupError) as exc:
            log.warning("is_path_valid: %s; it is not valid", exc)
            return IsPathValid.Response(is_valid=False, success=False, message=str(exc))
        bad = invalid_poses(
            grid,
            poses,
            req.max_cost,
            req.consider_unknown_as_obstacle,
            self.world.robot_xy(),
            stop_at_first_collision=req.stop_at_first_collision,
            max_lookahead_distance=req.max_lookahead_distance,
            footprint=footprint,
        )
        return IsPathValid.Response(is_valid=not bad, invalid_pose_indices=bad)

    def get_costs(self, req: GetCosts.Request) -> GetCosts.Response:
        """``global_costmap/get_cost_global_costmap`` (CheckPoseOccupancy,
        RemoveInCollisionGoals): unsuccessful without a map or off the map frame."""
        grid = self.world.snapshot()
        if grid is None or any(p.header.frame_id not in MAP_FRAMES for p in req.poses):
            return GetCosts.Response(costs=[255.0] * len(req.poses), success=False)
        costs, on_map = pose_costs(grid, [(p.x, p.y) for p in req.poses])
        return GetCosts.Response(costs=costs, success=on_map)
