"""The navigator's logic without Zenoh: goal intake, one navigation at a time, snapshots.

The service hands every accepted goal of both actions to :meth:`Navigator.navigate`.
A goal of the same action that arrives while one runs reaches the running
navigation through its :class:`~aiobt_services.navigator.navigation.GoalChannel` (the
action server's replace policy); a goal of the other action stops the running
navigation (ABORTED, "preempted by ...") and starts once it has halted its tree.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

from aiobt.core.clock import Clock
from aiobt.core.tree import Tree
from aiobt.loggers.btlog import BtlogLogger
from aiobt.msgs import ActionResult, BtSnapshot, ComputePathToPoseError, PoseStamped
from aiobt.msgs.bt import NavigationState
from aiobt.nav.context import DEFAULT_BT_LOOP_DURATION
from aiobt_services.navigator.errors import ERROR_CODE_PREFIXES, navigator_codes
from aiobt_services.navigator.goals import MapBounds, NavRequest, pose_problem
from aiobt_services.navigator.navigation import GoalChannel, Navigation, Recording
from aiobt_services.navigator.status import TreeStatusStream
from aiobt_services.navigator.trees import (
    DEFAULT_THROUGH_POSES_TREE,
    DEFAULT_TO_POSE_TREE,
    TreeLibrary,
)

log = logging.getLogger("aiobt_services.navigator")


class RobotState(Protocol):
    """Where the robot is (map frame) and how fast it goes, for feedback."""

    def current_pose(self) -> PoseStamped | None: ...
    def linear_speed(self) -> float: ...
    async def wait_for_pose(self, timeout: float) -> bool:  # noqa: ASYNC109
        """Wait up to ``timeout`` wall seconds for a first pose; True once there is one."""
        ...


@dataclass(slots=True)
class NavigatorOptions:
    """bt_navigator's parameters: default trees, loop period, error-code prefixes, logs.

    ``clock_timeout``: wall seconds the tick loop waits for a clock that does not
    move (a stopped simulation) before it ticks anyway.
    """

    default_to_pose_tree: str = str(DEFAULT_TO_POSE_TREE)
    default_through_poses_tree: str = str(DEFAULT_THROUGH_POSES_TREE)
    bt_loop_duration: float = DEFAULT_BT_LOOP_DURATION
    clock_timeout: float | None = None  # wall s; None: wait for the clock however long
    pose_timeout: float = 2.0  # wall s a goal waits for a first robot pose (then TF_ERROR)
    error_code_prefixes: tuple[str, ...] = ERROR_CODE_PREFIXES
    btlog_dir: Path | None = None
    mcap_dir: Path | None = None  # one MCAP per navigation (with a ``recorder``)


class Navigator:
    """Runs navigations one at a time on trees from ``library``."""

    def __init__(
        self,
        library: TreeLibrary,
        robot: RobotState,
        clock: Clock,
        stream: TreeStatusStream,
        options: NavigatorOptions | None = None,
    ) -> None:
        self.library = library
        self.robot = robot
        self.clock = clock
        self.stream = stream
        self.options = options or NavigatorOptions()
        self.map_bounds: MapBounds | None = None
        self.current: Navigation | None = None
        self._lock = asyncio.Lock()
        self._latest_goal = ""
        self._state: NavigationState = "idle"
        self._last: tuple[NavRequest, ActionResult] | None = None
        # called with each navigation's new tree (e.g. a Groot2 publisher's attach)
        self.tree_viewers: list[Callable[[Tree], None]] = []
        # starts recording to a file, with mcap_dir (e.g. aiobt.foxglove's McapRecording)
        self.recorder: Callable[[Path], Recording] | None = None

    # -- goals ---------------------------------------------------------------------------
    def tree_of(self, request: NavRequest) -> str:
        """The tree file or ID ``request`` runs (its own, else the action's default)."""
        if request.behavior_tree:
            return request.behavior_tree
        if request.through_poses:
            return self.options.default_through_poses_tree
        return self.options.default_to_pose_tree

    def goal_problem(self, request: NavRequest) -> ActionResult | None:
        """The result that refuses ``request`` (pose outside the map, bad frame), or None."""
        problem = pose_problem(request.poses, self.map_bounds)
        if problem is None:
            return None
        outside = int(ComputePathToPoseError.GOAL_OUTSIDE_MAP)
        return ActionResult(
            error_code=outside if problem.outside_map else navigator_codes(request).unknown,
            error_msg=f"{request.action} goal {request.goal_id}: {problem.message}",
        )

    async def navigate(self, request: NavRequest, channel: GoalChannel) -> ActionResult:
        """Run ``request`` to its end (a canceled goal raises CancelledError, after the
        tree has been halted)."""
        self._latest_goal = request.goal_id
        if self.current is not None:
            self.current.stop(f"preempted by {request.action} goal {request.goal_id}")
        async with self._lock:
            if self._latest_goal != request.goal_id:
                return ActionResult(
                    error_code=navigator_codes(request).unknown,
                    error_msg=f"preempted by goal {self._latest_goal} before it started",
                )
            return await self._run(Navigation(self, request, channel))

    async def _run(self, navigation: Navigation) -> ActionResult:
        self.current = navigation
        self._state = "navigating"
        result: ActionResult | None = None
        try:
            result = await navigation.run()
            return result
        finally:
            self.current = None
            if result is None:
                self._state = "canceled"
                result = ActionResult(error_msg="canceled")
            else:
                self._state = "succeeded" if result.error_code == 0 else "aborted"
            self._last = (navigation.request, result)
            navigation.finished.set()
            self.stream.sink.snapshot(self.snapshot())

    async def shutdown(self, reason: str, timeout: float = 5.0) -> None:  # noqa: ASYNC109
        """Stop the running navigation (ABORTED with ``reason``; its tree halted, so its
        goals on the servers are canceled) and wait up to ``timeout`` s for it to end."""
        navigation = self.current
        if navigation is None:
            return
        navigation.stop(reason)
        try:
            async with asyncio.timeout(timeout):  # not wait_for: see Navigation._wait
                await navigation.finished.wait()
        except TimeoutError:
            log.warning(
                "navigation %s did not end within %g s", navigation.request.goal_id, timeout
            )

    # -- monitoring ------------------------------------------------------------------------
    def snapshot(self) -> BtSnapshot:
        """The status stream's snapshot: every node's status and the navigation's state."""
        navigation = self.current
        if navigation is not None:
            return self.stream.snapshot(
                "navigating",
                self.clock.now(),
                action=navigation.request.action,
                goal_id=navigation.request.goal_id,
                ticks=navigation.ticks,
                number_of_recoveries=navigation.number_of_recoveries,
                distance_remaining=navigation.distance_remaining,
                goals=list(navigation.request.poses),
            )
        if self._last is None:
            return self.stream.snapshot(self._state, self.clock.now())
        request, result = self._last
        return self.stream.snapshot(
            self._state,
            self.clock.now(),
            action=request.action,
            goal_id=request.goal_id,
            error_code=result.error_code,
            error_msg=result.error_msg,
            goals=list(request.poses),
        )

    def open_btlog(self, tree: Tree, request: NavRequest) -> BtlogLogger | None:
        """A ``.btlog`` for this navigation's tree, when ``btlog_dir`` is set."""
        path = self._file_for(self.options.btlog_dir, request, "btlog")
        try:
            return None if path is None else BtlogLogger(tree, path)
        except (OSError, ValueError) as exc:
            log.error("no .btlog for goal %s: %s", request.goal_id, exc)
            return None

    def open_recording(self, request: NavRequest) -> Recording | None:
        """An MCAP recording of this navigation, when ``mcap_dir`` and a recorder are set."""
        path = self._file_for(self.options.mcap_dir, request, "mcap")
        if path is None or self.recorder is None:
            return None
        try:
            return self.recorder(path)
        except (OSError, ValueError) as exc:
            log.error("no recording of goal %s: %s", request.goal_id, exc)
            return None

    def _file_for(self, directory: Path | None, request: NavRequest, suffix: str) -> Path | None:
        """``DIR/<date>-<time>_<run>_<action>_<goal id>.<suffix>`` (DIR made), or None."""
        if directory is None:
            return None
        stamp = time.strftime("%Y%m%d-%H%M%S")  # a file name, not robot time
        name = f"{stamp}_{self.stream.run:04d}_{request.action}_{request.goal_id}.{suffix}"
        try:
            directory.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            log.error("no .%s for goal %s: %s", suffix, request.goal_id, exc)
            return None
        return directory / name
