"""The controller service over Zenoh: ``follow_path`` and the local-costmap clearing services.

One control loop per goal, at a fixed rate on the injected clock. A newer goal
takes the running one over (preemption "replace") without stopping the robot;
cancel, failure or success always leave a zero twist on ``{ns}/cmd_vel``.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass
from functools import partial

from aiobt.core.clock import Clock
from aiobt.costmap import RollingCostmap
from aiobt.costmap.checker import CollisionChecker
from aiobt.costmap.local import FrameShift, LocalCostmap, clearing, frame_transform
from aiobt.costmap.worker import CostmapWorker
from aiobt.geometry import STOP, PlanarPath, Velocity
from aiobt.msgs import (
    ClearCostmapAroundRobot,
    ClearCostmapExceptRegion,
    ClearCostmapResponse,
    ClearEntireCostmap,
    FollowPath,
    FollowPathError,
    OccupancyGrid,
    Path,
    Twist,
)
from aiobt.msgs.speed_limit import SpeedLimit as SpeedLimitMsg
from aiobt.robot.tracker import RobotTracker, sleep_bounded, twist_of
from aiobt.transport import Bus, GoalHandle, Publisher
from aiobt.transport.on_demand import OnDemand

from .cycle_stats import CycleSchedule, CycleStats
from .errors import ControllerError
from .observed import LocalView
from .session import ControllerConfig, FollowPathSession, FollowRequest, StepResult
from .speed_limit import NONE, SpeedLimit
from .wire import TrackingFeedbackMsg, tracking_feedback_msg

log = logging.getLogger("aiobt_services.controller.service")
Handle = GoalHandle[FollowPath.Goal, FollowPath.Result, FollowPath.Feedback]


def path_of(msg: Path) -> PlanarPath:
    """The wire path as arrays, in the path header's frame."""
    poses = [(p.x, p.y, p.yaw) for p in msg.poses]
    return PlanarPath.from_poses(msg.header.frame_id, poses)


def request_of(goal: FollowPath.Goal) -> FollowRequest:
    return FollowRequest(
        path_of(goal.path), goal.controller_id, goal.goal_checker_id, goal.progress_checker_id
    )


def result_of(error: ControllerError | None) -> FollowPath.Result:
    if error is None:
        return FollowPath.Result()
    return FollowPath.Result(error_code=int(error.code), error_msg=error.message)


@dataclass(slots=True)
class ServiceOptions:
    clock_timeout: float = 2.0
    clear_default_distance: float = 1.0
    robot_time: bool = False  # the clock follows the robot's (--sim-time): leads by stamps
    cmd_vel_topic: str = "cmd_vel"  # cmd_vel_nav: through the velocity smoother
    obstacle_layer: bool = True  # False: the local costmap ignores the lidar (tests)
    speed_limit_topic: str = "speed_limit"  # Nav2's speed_limit_topic


class ControllerService:
    """Wires the FollowPath session logic to the bus."""

    def __init__(
        self,
        bus: Bus,
        clock: Clock,
        config: ControllerConfig | None = None,
        costmap: LocalCostmap | None = None,
        options: ServiceOptions | None = None,
    ) -> None:
        self.bus = bus
        self.clock = clock
        self.config = config or ControllerConfig()
        self.costmap = costmap or LocalCostmap()
        self.options = options or ServiceOptions()
        self.tracker = RobotTracker(
            clock, self.costmap, robot_time=self.options.robot_time,
            scan=self.options.obstacle_layer,
        )  # fmt: skip
        self.feed = OnDemand(lambda: self.tracker.attach(bus), self.tracker.forget, clock)
        self._shift = FrameShift(self.costmap)
        self.worker = CostmapWorker(self.costmap)  # every change of the costmap, in order
        self._cmd: Publisher[Twist] | None = None
        self._tracking: Publisher[TrackingFeedbackMsg] | None = None
        self._view: LocalView | None = None
        self.speed_limit = NONE
        self._session: FollowPathSession | None = None

    def start(self) -> None:
        # reliable: a stop must not drop
        self._cmd = self.bus.publisher(self.options.cmd_vel_topic, Twist, reliable=True)
        self._tracking = self.bus.publisher("tracking_feedback", TrackingFeedbackMsg)
        self._view = LocalView(
            # dropped, not blocking, when congested: an observer must never hold up a cycle
            self.bus.publisher("local_plan", Path),
            self.bus.publisher("local_costmap/costmap", OccupancyGrid),
            self.costmap.grid,
        )
        self.bus.action_server(
            FollowPath.name, FollowPath, self.execute, preemption="replace", clock=self.clock
        )
        self._serve_clearing()
        self.bus.subscribe(
            self.options.speed_limit_topic, SpeedLimitMsg, self.on_speed_limit, queue_size=1
        )

    def on_speed_limit(self, msg: SpeedLimitMsg) -> None:
        """Nav2's ``speedLimitCallback``: every controller takes the limit, the running
        goal's at once."""
        self.speed_limit = SpeedLimit(msg.speed_limit, msg.percentage)
        log.info("speed limit: %s", self.speed_limit)
        if self._session is not None:
            self._session.set_speed_limit(self.speed_limit)

    # -- follow_path ------------------------------------------------------------------------
    async def execute(self, goal: FollowPath.Goal, handle: Handle) -> FollowPath.Result:
        try:
            session = self._open(request_of(goal))
        except ControllerError as error:
            log.warning("follow_path goal rejected: %s", error.message)
            return result_of(error)
        log.info(
            "follow_path: goal %s, %d poses in '%s', controller %s",
            handle.goal_id,
            len(session.request.path),
            session.request.path.frame_id,
            goal.controller_id or self.config.default_controller,
        )
        if self._view is not None:
            self._view.begin()
        try:
            async with self.feed.active(self.options.clock_timeout):  # pose, odom, scan
                result = await self._run(session, handle)
        finally:
            self._publish(STOP)
            if self._view is not None:
                self._view.end(session.request.path.frame_id, self.clock.now())
        code = result.error_code
        outcome = f"error {code} {FollowPathError(code).name}" if code else "succeeded"
        log.info("follow_path: goal %s %s %s", handle.goal_id, outcome, result.error_msg)
        return result

    async def _run(self, session: FollowPathSession, handle: Handle) -> FollowPath.Result:
        stats = CycleStats(self.config.control_period)
        self._session = session
        try:
            return await self._loop(session, handle, stats)
        finally:
            self._session = None
            log.info("follow_path: goal %s: %s", handle.goal_id, stats.summary())

    def _open(self, request: FollowRequest) -> FollowPathSession:
        checker = self._checker_for(request.path.frame_id)
        return FollowPathSession(request, self.config, self.clock.now(), checker, self.speed_limit)

    def _checker_for(self, frame: str) -> CollisionChecker:
        return CollisionChecker(self.costmap if frame == "map" else self._shift)

    async def _loop(
        self, session: FollowPathSession, handle: Handle, stats: CycleStats
    ) -> FollowPath.Result:
        first = self.tracker.due_update()
        if first is not None:  # the first cycle sees the lidar as of now
            stats.record_update(await self.worker.run(partial(first.apply, self.costmap)))
        schedule = CycleSchedule(self.config.control_period, self.clock.now())
        while True:
            began, work, cpu = self.clock.now(), time.perf_counter(), time.thread_time()
            newer = handle.take_new_goal()
            if newer is not None:
                try:
                    session.replace(request_of(newer), self.clock.now())
                except ControllerError as error:
                    return result_of(error)
            step = self._step(session)
            self._publish(step.cmd)
            self._feedback(step, handle, session.request.path.frame_id)
            if self._view is not None:
                self._view.cycle(step.trajectory, session.request.path.frame_id, began)
            stats.record(began, time.perf_counter() - work, time.thread_time() - cpu)
            if step.finished:
                return result_of(step.error)
            self._update_costmap(stats)
            slept = self.clock.now(), time.perf_counter()
            delay = schedule.delay(slept[0])
            awake = await sleep_bounded(self.clock, delay, self.options.clock_timeout)
            stats.record_sleep(self.clock.now() - slept[0], time.perf_counter() - slept[1])
            if not awake:
                return result_of(
                    ControllerError(
                        FollowPathError.TF_ERROR,
                        f"robot clock stopped for {self.options.clock_timeout:.1f} s "
                        "(simulation gone?); stopping",
                    )
                )

    def _update_costmap(self, stats: CycleStats) -> None:
        """The local costmap's update, when due, started after the cycle's command is out,
        in the worker thread while the loop sleeps (as Nav2's costmap updates beside the
        control loop): a cycle after it ended reads it. One at a time: while one runs, a
        due update waits for the next cycle."""
        if self.worker.busy:
            return
        update = self.tracker.due_update()
        if update is not None:
            self.worker.start(partial(update.apply, self.costmap), stats.record_update)

    def _step(self, session: FollowPathSession) -> StepResult:
        states = self.tracker.snapshot()
        if session.request.path.frame_id == "odom" and {"map", "odom"} <= states.keys():
            self._shift.transform = frame_transform(states["map"].pose, states["odom"].pose)
        lead = self.tracker.lead(session.request.path.frame_id)
        return session.step(self.clock.now(), states, lead)

    def _publish(self, cmd: Velocity) -> None:
        if self._cmd is not None:
            self._cmd.put(twist_of(cmd))
            self.tracker.sent(cmd)

    def _feedback(self, step: StepResult, handle: Handle, frame_id: str) -> None:
        fb = step.feedback
        if fb is None:
            return
        handle.publish_feedback(
            FollowPath.Feedback(distance_to_goal=fb.distance_to_goal, speed=abs(step.cmd.v))
        )
        if self._tracking is not None and self._tracking.matched:  # built only for a reader
            self._tracking.put(tracking_feedback_msg(fb, self.clock.now(), frame_id))

    # -- local costmap clearing -------------------------------------------------------------
    def _serve_clearing(self) -> None:
        name = "local_costmap"
        self.bus.serve(
            ClearEntireCostmap.service_name(name),
            ClearEntireCostmap.Request,
            ClearCostmapResponse,
            self._clear_entirely,
        )
        self.bus.serve(
            ClearCostmapExceptRegion.service_name(name),
            ClearCostmapExceptRegion.Request,
            ClearCostmapResponse,
            self._clear_except,
        )
        self.bus.serve(
            ClearCostmapAroundRobot.service_name(name),
            ClearCostmapAroundRobot.Request,
            ClearCostmapResponse,
            self._clear_around,
        )

    async def _clear_entirely(self, _: ClearEntireCostmap.Request) -> ClearCostmapResponse:
        await self.worker.run(partial(self.costmap.staged, RollingCostmap.clear_entirely))
        return ClearCostmapResponse(success=True, message="local costmap cleared")

    async def _clear_except(self, req: ClearCostmapExceptRegion.Request) -> ClearCostmapResponse:
        return await self._clear_region(req.reset_distance, keep_inside=True)

    async def _clear_around(self, req: ClearCostmapAroundRobot.Request) -> ClearCostmapResponse:
        return await self._clear_region(req.reset_distance, keep_inside=False)

    async def _clear_region(self, distance: float, keep_inside: bool) -> ClearCostmapResponse:
        async with self.feed.active(self.options.clock_timeout):  # the pose now, if idle
            state = self.tracker.states.get("map")
        if state is None:
            return ClearCostmapResponse(success=False, message="no robot pose in 'map' yet")
        await self.worker.run(
            partial(self.costmap.staged, clearing(state.pose, distance, keep_inside))
        )
        verb = "outside" if keep_inside else "inside"
        return ClearCostmapResponse(
            success=True, message=f"local costmap cleared {verb} a {distance:.2f} m square"
        )
