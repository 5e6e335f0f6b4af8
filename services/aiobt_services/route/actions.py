"""The ``compute_route`` and ``compute_and_track_route`` executes (Nav2's
``RouteServer::processRouteRequest``), free of the bus: the robot's pose,
robot time and the feedback come in as callables, so tests drive them with fakes.

ComputeRoute plans once and returns the route, the dense path and the planning
time. ComputeAndTrackRoute plans, then tracks the robot along the route at
``tracker_update_rate`` (robot time), running the operations and publishing
feedback (at the start with ``rerouted`` set, at each node achieved and each
operation that acted); an operation asking for a reroute plans again from the last node passed,
without the blocked ids; a newer goal takes the tracking over; the goal succeeds
with the execution duration once the last node is achieved. Every failure is a result with Nav2's
code and a message; a cancelled goal is not an error.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from typing import Any

from aiobt.core.clock import Clock
from aiobt.geometry import XYYaw
from aiobt.msgs import Path
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, ComputeRoute

from .convert import path_msg, route_msg
from .errors import RouteError
from .intent import ReroutingState
from .operations import OperationsManager, OperationsResult
from .planning import RoutePlanner
from .request import RouteRequest
from .search import Route
from .tracker import RouteTracker, TrackerParams

log = logging.getLogger("aiobt_services.route.actions")
MAP_FRAMES = ("", "map")
RobotPose = Callable[[], XYYaw]  # raises LookupError without a pose
Feedback = ComputeAndTrackRoute.Feedback


def request_of(goal: ComputeRoute.Goal, robot: RobotPose) -> RouteRequest:
    """The goal in the route frame; TF_ERROR for a pose in another frame or no robot pose."""
    if not goal.use_poses:
        return RouteRequest(False, goal.start_id, goal.goal_id)
    poses = [("goal", goal.goal)] + ([("start", goal.start)] if goal.use_start else [])
    for what, pose in poses:
        if pose.header.frame_id not in MAP_FRAMES:
            raise RouteError("TF_ERROR", f"the {what} pose is in frame "
                             f"'{pose.header.frame_id}'; the route frame is 'map'")  # fmt: skip
    try:
        start = (goal.start.x, goal.start.y, goal.start.yaw) if goal.use_start else robot()
    except LookupError as exc:
        raise RouteError("TF_ERROR", f"no robot pose to start from: {exc}") from None
    return RouteRequest(True, start=start[:2], goal=(goal.goal.x, goal.goal.y),
                        start_yaw=start[2], goal_yaw=goal.goal.yaw)  # fmt: skip


class RouteActions:
    def __init__(
        self,
        planner: RoutePlanner,
        operations: OperationsManager,
        tracker: TrackerParams,
        robot: RobotPose,
        clock: Clock,
    ) -> None:
        self.planner = planner
        self.operations = operations
        self.tracker = tracker
        self.robot = robot
        self.clock = clock

    async def compute_route(self, goal: ComputeRoute.Goal, _handle: Any) -> Any:
        began = time.monotonic()
        try:
            route, poses = self.planner.plan(request_of(goal, self.robot), ReroutingState())
        except RouteError as exc:
            return self._failed(ComputeRoute.Result, exc)
        except Exception as exc:  # a bad request never takes the server down
            log.exception("compute_route failed unexpectedly")
            return self._failed(ComputeRoute.Result, RouteError("UNKNOWN", str(exc)))
        stamp, took = self.clock.now(), time.monotonic() - began
        log.info("route %s, cost %.2f", "-".join(str(n.nodeid) for n in route.nodes),
                 route.route_cost)  # fmt: skip
        if took > self.planner.params.max_planning_time:  # Nav2 warns, and returns it
            log.warning("route took %.3f s, over max_planning_time", took)
        return ComputeRoute.Result(
            planning_time=took,
            path=path_msg(poses, stamp),
            route=route_msg(route, stamp),
        )

    async def compute_and_track_route(self, goal: ComputeAndTrackRoute.Goal, handle: Any) -> Any:
        """Served with preemption "replace": a newer goal takes the tracking over, as Nav2's
        ``accept_pending_goal`` (rerouting state reset, execution time kept)."""
        began = self.clock.now()
        rerouting = ReroutingState()
        try:
            while True:
                newer = handle.take_new_goal()
                if newer is not None:
                    log.info("computing a new route to the preempting goal")
                    goal, rerouting = newer, ReroutingState()
                request = request_of(goal, self.robot)  # a reroute starts where the robot is
                route, poses = self.planner.plan(request, rerouting)
                stamp = self.clock.now()
                if await self._track(route, path_msg(poses, stamp), rerouting, handle):
                    return ComputeAndTrackRoute.Result(execution_duration=self.clock.now() - began)
                if not handle.preempt_requested:
                    log.info("rerouting from node %s, blocked ids %s", rerouting.start_id,
                             rerouting.blocked_ids)  # fmt: skip
        except RouteError as exc:
            return self._failed(ComputeAndTrackRoute.Result, exc)
        except Exception as exc:
            log.exception("compute_and_track_route failed unexpectedly")
            return self._failed(ComputeAndTrackRoute.Result, RouteError("UNKNOWN", str(exc)))

    async def _track(
        self, route: Route, path: Path, rerouting: ReroutingState, handle: Any
    ) -> bool:
        """Track ``route`` until its end (True), or until a reroute is asked for or a newer
        goal preempts this one (False)."""
        tracker = RouteTracker(route, self.tracker, rerouting)
        msg = route_msg(route, self.clock.now())

        def feedback(rerouted: bool, ops: list[str]) -> None:
            next_node, last, edge = tracker.next_node, tracker.last_node, tracker.current_edge
            handle.publish_feedback(Feedback(
                last_node_id=last.nodeid if last else 0,
                next_node_id=next_node.nodeid if next_node else 0,
                current_edge_id=edge.edgeid if edge else 0,
                route=msg, path=path, operations_triggered=ops, rerouted=rerouted,
            ))  # fmt: skip

        feedback(True, [])
        period = 1.0 / self.tracker.tracker_update_rate
        while not handle.preempt_requested:
            pose = self._pose()
            position = pose[:2]
            changed, completed = tracker.update(position)
            ops = await self.operations.process(changed, tracker, position, self.clock.now())
            if completed:
                feedback(False, ops.operations_triggered)
                return True
            if (changed or ops.operations_triggered) and tracker.current_edge is not None:
                feedback(False, ops.operations_triggered)
            if ops.reroute:
                self._prepare_reroute(tracker, ops, rerouting, pose)
                return False
            await self.clock.sleep(period)
        return False

    def _pose(self) -> XYYaw:
        try:
            return self.robot()
        except LookupError as exc:
            raise RouteError("TF_ERROR", f"lost the robot pose while tracking: {exc}") from None

    def _prepare_reroute(
        self, tracker: RouteTracker, ops: OperationsResult, rerouting: ReroutingState, at: XYYaw
    ) -> None:
        if self.tracker.aggregate_blocked_ids:
            rerouting.blocked_ids.extend(ops.blocked_ids)
        else:
            rerouting.blocked_ids = list(ops.blocked_ids)
        last = tracker.last_node
        rerouting.start_id = last.nodeid if last is not None else None
        rerouting.start_pose = at[:2] if last is not None else None
        rerouting.start_yaw = at[2]
        rerouting.curr_edge = tracker.current_edge

    @staticmethod
    def _failed(result: Any, exc: RouteError) -> Any:
        log.warning("route request failed: %s (%s)", exc.message, exc.reason)
        return result(error_code=exc.code, error_msg=exc.message)
