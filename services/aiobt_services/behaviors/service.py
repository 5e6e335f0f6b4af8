"""The behavior server over Zenoh: spin, backup, drive_on_heading, wait, assisted_teleop.

Each action steps its behavior at a fixed rate on the injected clock. One
behavior at a time owns ``{ns}/cmd_vel``: a goal for any moving behavior
preempts the one running (which ends with its UNKNOWN code, "preempted by
..."); a new goal to the same server preempts its predecessor (the transport's
abort policy); cancel and every ending publish a zero twist while still owning.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from aiobt.core.clock import Clock
from aiobt.costmap.checker import CollisionChecker
from aiobt.costmap.local import LocalCostmap
from aiobt.geometry import STOP, Velocity
from aiobt.msgs import Empty, Twist
from aiobt.robot.freshness import FRESH
from aiobt.robot.tracker import RobotTracker, sleep_bounded, twist_of
from aiobt.transport import Bus, GoalHandle, Publisher
from aiobt.transport.on_demand import OnDemand

from .assisted_teleop import AssistedTeleop
from .base import BehaviorInputError, Inputs, Outcome, Safety
from .plugins import BEHAVIORS, Behavior, BehaviorPlugin

log = logging.getLogger("aiobt_services.behaviors.service")


@dataclass(slots=True)
class BehaviorOptions:
    cycle_period: float = 0.05
    clock_timeout: float = 2.0
    safety: Safety | None = None
    robot_time: bool = False  # the clock follows the robot's (--sim-time): leads by stamps
    cmd_vel_topic: str = "cmd_vel"  # cmd_vel_nav: through the velocity smoother


class _Run:
    """One running goal; ``preempted_by`` is set when another behavior takes cmd_vel."""

    __slots__ = ("name", "preempted_by")

    def __init__(self, name: str) -> None:
        self.name = name
        self.preempted_by: str | None = None


class BehaviorService:
    def __init__(
        self,
        bus: Bus,
        clock: Clock,
        costmap: LocalCostmap | None = None,
        options: BehaviorOptions | None = None,
    ) -> None:
        self.bus = bus
        self.clock = clock
        self.costmap = costmap or LocalCostmap()
        self.options = options or BehaviorOptions()
        self.safety = replace(
            self.options.safety or Safety(), cycle_period=self.options.cycle_period
        )
        # the costmap in odom, as Nav2's behavior server checks (local_frame odom): a
        # relocalization (ReinitializeGlobalLocalization, then Spin) moves the estimate
        # metres between scans, and a map-frame window would put the robot on obstacles
        # laid from the estimate before the jump (Spin's 703 in the kidnap e2e test)
        # and no pose in map at all: nothing here reads it (one 50 Hz stream fewer)
        self.tracker = RobotTracker(
            clock, self.costmap, robot_time=self.options.robot_time, costmap_frame="odom",
            map_pose=False,
        )  # fmt: skip
        self.feed = OnDemand(
            lambda: self.tracker.attach(bus), self.tracker.forget, clock,
            waited=self.tracker.waited,
        )  # fmt: skip
        self.checker = CollisionChecker(self.costmap)
        self._owner: _Run | None = None
        self._teleop: tuple[Velocity, float] | None = None
        self._teleop_run: AssistedTeleop | None = None
        self._cmd: Publisher[Twist] | None = None

    def start(self) -> None:
        # reliable: a stop must not drop
        self._cmd = self.bus.publisher(self.options.cmd_vel_topic, Twist, reliable=True)
        self.bus.subscribe("cmd_vel_teleop", Twist, self._on_teleop)
        self.bus.subscribe("preempt_teleop", Empty, self._on_preempt_teleop)
        for plugin in BEHAVIORS.values():
            self._serve(plugin)

    def _serve(self, plugin: BehaviorPlugin) -> None:
        def make(goal: Any) -> Behavior:
            return plugin.create(goal, self.checker, self.safety)

        async def execute(goal: Any, handle: GoalHandle[Any, Any, Any]) -> Any:
            return await self.execute(plugin, make, goal, handle)

        self.bus.action_server(plugin.name, plugin.action, execute, clock=self.clock)

    def _on_teleop(self, twist: Twist) -> None:
        # idle on --sim-time the clock is not listened to: a command received then is
        # stamped with the last time known, so it counts as old once a goal starts
        # (the next command, a teleop stream's usual 10+ Hz, is fresh)
        self._teleop = (Velocity(twist.linear.x, twist.angular.z), self.clock.now())

    def _on_preempt_teleop(self, _: Empty) -> None:
        if self._teleop_run is not None:
            self._teleop_run.finish()

    # -- execution --------------------------------------------------------------------------
    async def execute(
        self,
        plugin: BehaviorPlugin,
        make: Callable[[Any], Behavior],
        goal: Any,
        handle: GoalHandle[Any, Any, Any],
    ) -> Any:
        try:
            behavior = make(goal)
        except BehaviorInputError as exc:
            log.warning("%s goal refused: %s", plugin.name, exc.message)
            return self._result(plugin, Outcome.INVALID_INPUT, exc.message, self.clock.now())
        run = self._claim(plugin)
        if isinstance(behavior, AssistedTeleop):
            self._teleop_run = behavior
        log.info("%s: goal %s started", plugin.name, handle.goal_id)
        try:
            async with self.feed.active(self.options.clock_timeout):  # odom, scan
                # timed from here: on --sim-time an idle service's clock is the last stamp
                # it heard, stale until the goal holds it fresh (total_elapsed_time)
                started = self.clock.now()
                result = await self._loop(plugin, behavior, run, handle, started)
            log.info(
                "%s: goal %s ended %d %s (command-to-odometry delay %.3f s)",
                plugin.name,
                handle.goal_id,
                result.error_code,
                result.error_msg,
                self.tracker.delay.estimate,
            )
            return result
        finally:
            if self._owner is run:
                self._owner = None
                self._publish(STOP)
            if self._teleop_run is behavior:
                self._teleop_run = None

    def _claim(self, plugin: BehaviorPlugin) -> _Run:
        run = _Run(plugin.name)
        if plugin.owns_cmd_vel:
            if self._owner is not None:
                self._owner.preempted_by = plugin.name
            self._owner = run
        return run

    async def _loop(
        self,
        plugin: BehaviorPlugin,
        behavior: Behavior,
        run: _Run,
        handle: GoalHandle[Any, Any, Any],
        started: float,
    ) -> Any:
        while True:
            if run.preempted_by is not None:
                message = f"preempted by a {run.preempted_by} goal"
                return self._result(plugin, Outcome.UNKNOWN, message, started)
            step = behavior.step(self._inputs())
            if step.cmd is not None and self._owner is run:
                self._publish(step.cmd)
            handle.publish_feedback(plugin.feedback(max(0.0, step.feedback)))
            if step.done:
                return self._result(plugin, step.outcome, step.message, started)
            if not await sleep_bounded(
                self.clock, self.options.cycle_period, self.options.clock_timeout
            ):
                message = "robot clock stopped (simulation gone?); stopping"
                return self._result(plugin, Outcome.TF_ERROR, message, started)

    def _inputs(self) -> Inputs:
        self.tracker.refresh_costmap()
        states = self.tracker.snapshot()
        odom = states.get("odom")
        teleop, teleop_stamp = self._teleop or (None, float("-inf"))
        return Inputs(
            now=self.clock.now(),
            pose=odom.pose if odom else None,
            pose_age=odom.age if odom else FRESH,
            teleop=teleop,
            teleop_stamp=teleop_stamp,
            lead=self.tracker.lead("odom"),
        )

    def _result(
        self, plugin: BehaviorPlugin, outcome: Outcome, message: str, started: float
    ) -> Any:
        elapsed = max(0.0, self.clock.now() - started)
        return plugin.result(outcome, message, elapsed)

    def _publish(self, cmd: Velocity) -> None:
        if self._cmd is not None:
            self._cmd.put(twist_of(cmd))
            self.tracker.sent(cmd)
