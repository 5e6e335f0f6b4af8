"""One navigation: a tree ticking for a goal, updated by newer goals, until it ends.

The loop is bt_navigator's ``BehaviorTreeEngine::run`` with the navigator's
``onLoop`` and ``onPreempt``: tick, end on SUCCESS or FAILURE, else take a newer
goal (same tree: the goal entry is rewritten, the tree replans; another tree:
the running one is halted and the new one starts), publish feedback, and wait
for the loop period or a wake-up. The period is on the robot's clock; feedback
goes out at most once per period of *wall* time, as often as Nav2 sends it (its
loop is a ``WallRate``): at a sim speed-up of 10 the loop turns ten times as
often, and a feedback reply each turn cost the navigator's main thread about a
sixth of its CPU (``bench/RESULTS.md``, system).
Cancellation (a canceled goal) halts the tree, which cancels every goal its
leaves hold on servers.
"""

from __future__ import annotations

import asyncio
import logging
import time
from typing import TYPE_CHECKING, Protocol

from aiobt.core.blackboard import Blackboard
from aiobt.core.errors import BehaviorTreeError
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.core.tree import Tree
from aiobt.loggers.btlog import BtlogLogger
from aiobt.msgs import ActionResult, Msg, NavigateThroughPoses, NavigateToPose, Path
from aiobt_services.navigator.errors import aggregate_error, clear_error_codes, navigator_codes
from aiobt_services.navigator.goals import NavRequest
from aiobt_services.navigator.progress import PathProgress, time_remaining
from aiobt_services.navigator.trees import TreeLoadFailure

if TYPE_CHECKING:
    from aiobt_services.navigator.navigator import Navigator

log = logging.getLogger("aiobt_services.navigator.navigation")


class Recording(Protocol):
    """A per-navigation recording (an MCAP of the bridged channels): closed at the end."""

    def close(self) -> None: ...


class GoalChannel(Protocol):
    """The action goal a navigation serves: newer goals that take it over, feedback."""

    def take_new_request(self) -> NavRequest | None: ...
    def publish_feedback(self, feedback: Msg) -> None: ...


class Navigation:
    """Runs ``request`` on ``navigator``'s trees; :meth:`run` returns the result."""

    def __init__(self, navigator: Navigator, request: NavRequest, channel: GoalChannel) -> None:
        self.navigator = navigator
        self.request = request
        self.channel = channel
        self.tree: Tree | None = None
        self.tree_source = ""
        self.ticks = 0
        self.started = navigator.clock.now()
        self.distance_remaining = 0.0
        self.finished = asyncio.Event()
        self._stop: ActionResult | None = None
        self._progress = PathProgress()
        self._btlog: BtlogLogger | None = None
        self._recording: Recording | None = None
        self._stalled = False
        self._feedback_due = 0.0  # time.monotonic() from which the next feedback goes out

    # -- control from outside ----------------------------------------------------------
    def stop(self, reason: str) -> None:
        """End the navigation ABORTED with ``reason`` (a goal of the other action took over)."""
        self._end_with(
            ActionResult(error_code=navigator_codes(self.request).unknown, error_msg=reason)
        )

    def _end_with(self, result: ActionResult) -> None:
        self._stop = result
        if self.tree is not None:
            self.tree.emit_wake_up()

    @property
    def number_of_recoveries(self) -> int:
        if self.tree is None:
            return 0
        return int(self.tree.root_blackboard.get("number_recoveries", 0) or 0)

    # -- the loop ------------------------------------------------------------------------
    async def run(self) -> ActionResult:
        codes = navigator_codes(self.request)
        problem = self.navigator.goal_problem(self.request)
        if problem is not None:
            log.error("refused %s", problem.error_msg)  # it names the action and the goal
            return problem
        # bt_navigator: "Initial robot pose is not available." (TF_ERROR)
        pose_timeout = self.navigator.options.pose_timeout
        if not await self.navigator.robot.wait_for_pose(pose_timeout):
            message = f"the robot pose is not available (nothing on pose within {pose_timeout:g} s)"
            log.error("goal %s: %s", self.request.goal_id, message)
            return ActionResult(error_code=codes.tf_error, error_msg=message)
        try:
            self._start_tree(self.request)
        except TreeLoadFailure as exc:
            log.error("goal %s: %s", self.request.goal_id, exc)
            return ActionResult(error_code=codes.failed_to_load, error_msg=str(exc))
        reason = "canceled"
        try:
            status = await self._tick_until_done()
            reason = "navigation ended"
            return self._result(status, codes.unknown)
        finally:
            await self._end_tree(reason)

    async def _tick_until_done(self) -> Status | ActionResult:
        period = self.navigator.options.bt_loop_duration
        while True:
            tree = self.tree
            assert tree is not None
            try:
                status = await tree.tick_once()
            except BehaviorTreeError as exc:  # a node's error: this goal fails, we go on
                log.error("goal %s: %s", self.request.goal_id, exc)
                return ActionResult(
                    error_code=navigator_codes(self.request).unknown, error_msg=str(exc)
                )
            self.ticks += 1
            self.navigator.stream.flush()
            if status is SUCCESS or status is FAILURE:
                return status
            if self._stop is not None:
                return self._stop
            await self._take_newer_goal()  # may start another tree
            self._publish_feedback()
            await self._wait(self.tree or tree, period)
            if self._stop is not None:
                return self._stop

    async def _wait(self, tree: Tree, period: float) -> None:
        """The loop period on the clock, or a wake-up; a clock that stalls (a simulation
        that stopped) for ``clock_timeout`` wall seconds lets the loop go on anyway,
        so that cancel and preemption are still served.

        Bounded with ``asyncio.timeout``, not ``asyncio.wait_for``: on Python 3.11 a
        cancel that lands after the wake-up has come but before this task resumes is
        swallowed by ``wait_for`` (it returns the result), and the canceled goal would
        run on. At a speed-up the loop wakes every millisecond or so: that race was
        seen in the e2e tests (a canceled follow_point goal still EXECUTING)."""
        bound = self.navigator.options.clock_timeout
        try:
            async with asyncio.timeout(bound):
                await tree.wait_for_wake_up(period)
        except TimeoutError:
            if not self._stalled:
                log.warning(
                    "goal %s: the clock has not moved for %g s", self.request.goal_id, bound
                )
            self._stalled = True

    def _result(self, status: Status | ActionResult, unknown: int) -> ActionResult:
        if status is SUCCESS:
            log.info("goal %s succeeded", self.request.goal_id)
            return ActionResult()
        if isinstance(status, ActionResult):
            log.error("goal %s aborted: %s", self.request.goal_id, status.error_msg)
            return status
        assert self.tree is not None
        prefixes = self.navigator.options.error_code_prefixes
        code, message = aggregate_error(self.tree.root_blackboard, prefixes) or (
            unknown,
            f"the behavior tree {self.tree.tree_id} failed without an error code",
        )
        log.error(
            "goal %s failed error_code:%d error_msg:'%s'", self.request.goal_id, code, message
        )
        return ActionResult(error_code=code, error_msg=message)

    # -- newer goals ---------------------------------------------------------------------
    async def _take_newer_goal(self) -> None:
        newer = self.channel.take_new_request()
        if newer is None:
            return
        problem = self.navigator.goal_problem(newer)
        if problem is not None:
            self.request = newer
            self._end_with(problem)
            return
        previous = self.request
        self.request = newer
        self.started = self.navigator.clock.now()
        self._feedback_due = 0.0  # the new goal's first feedback at once
        if self.navigator.tree_of(newer) == self.tree_source:
            log.info("goal %s replaces %s on the running tree", newer.goal_id, previous.goal_id)
            self._set_goal(newer)
            return
        log.info("goal %s asks for another tree: halting %s", newer.goal_id, self.tree_source)
        await self._end_tree(f"preempted by goal {newer.goal_id} with another tree")
        try:
            self._start_tree(newer)
        except TreeLoadFailure as exc:
            self._end_with(
                ActionResult(error_code=navigator_codes(newer).failed_to_load, error_msg=str(exc))
            )

    def _set_goal(self, request: NavRequest) -> None:
        assert self.tree is not None
        blackboard = self.tree.root_blackboard
        for key, value in request.blackboard_entries().items():
            blackboard.set(key, value)
        blackboard.set("number_recoveries", 0)
        self.tree.emit_wake_up()

    # -- the tree ------------------------------------------------------------------------
    def _start_tree(self, request: NavRequest) -> None:
        source = self.navigator.tree_of(request)
        blackboard = Blackboard.create()
        for key, value in request.blackboard_entries().items():
            blackboard.set(key, value)
        blackboard.set("path", Path())
        blackboard.set("number_recoveries", 0)
        clear_error_codes(blackboard, self.navigator.options.error_code_prefixes)
        tree = self.navigator.library.load(source, blackboard, self.navigator.clock)
        self.tree, self.tree_source = tree, source
        self.navigator.stream.attach(tree, action=request.action, source=source)
        self._btlog = self.navigator.open_btlog(tree, request)
        self._recording = self.navigator.open_recording(request)
        for show in self.navigator.tree_viewers:
            show(tree)
        log.info("goal %s: running tree %s from %s", request.goal_id, tree.tree_id, source)

    async def _end_tree(self, reason: str) -> None:
        tree = self.tree
        if tree is None:
            return
        try:
            await tree.halt_tree(reason)
        finally:
            self.navigator.stream.detach()
            if self._btlog is not None:
                self._btlog.close()
                self._btlog = None
            if self._recording is not None:
                self._recording.close()
                self._recording = None

    # -- feedback ------------------------------------------------------------------------
    def _publish_feedback(self) -> None:
        """Feedback, unless some went out less than a loop period of wall time ago."""
        now = time.monotonic()
        if now < self._feedback_due:
            return
        self._feedback_due = now + self.navigator.options.bt_loop_duration
        self.channel.publish_feedback(self._feedback())

    def _feedback(self) -> Msg:
        robot = self.navigator.robot
        pose = robot.current_pose()
        fields: dict[str, object] = {
            "navigation_time": max(0.0, self.navigator.clock.now() - self.started),
            "number_of_recoveries": self.number_of_recoveries,
        }
        assert self.tree is not None
        blackboard = self.tree.root_blackboard
        if pose is not None:
            fields["current_pose"] = pose
            path = blackboard.get("path")
            distance = self._progress.distance_remaining(
                path if isinstance(path, Path) else None, pose
            )
            if distance is not None:
                self.distance_remaining = distance
                fields["distance_remaining"] = distance
                fields["estimated_time_remaining"] = time_remaining(distance, robot.linear_speed())
        if self.request.through_poses:
            goals = blackboard.get("goals")
            fields["number_of_poses_remaining"] = len(getattr(goals, "goals", ()))
            return NavigateThroughPoses.Feedback.model_validate(fields)
        return NavigateToPose.Feedback.model_validate(fields)
