"""One FollowPath goal as a pure state machine, stepped once per control cycle.

The service feeds it the clock time and the latest robot states (per frame) and
publishes what it returns; nothing here does I/O, so every failure path is
unit-testable with a kinematic model and a fake clock.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import STOP, FloatArray, PlanarPath, Pose2D, Velocity
from aiobt.msgs import FollowPathError
from aiobt.robot.state import RobotState

from .base import NO_TRAJECTORY, ControlContext, Controller
from .checkers import CheckerRegistry, GoalChecker, ProgressChecker, default_checkers
from .dwb import DWBController
from .errors import ControllerError
from .rpp import RegulatedPurePursuit
from .speed_limit import NONE, SpeedLimit
from .tracking import TrackingFeedback, project_onto_path, search_stop, tracking_feedback

TRACKING_SEARCH_DISTANCE = 2.0  # m along the path from the last foot point


@dataclass(slots=True, frozen=True)
class FollowRequest:
    path: PlanarPath
    controller_id: str = ""
    goal_checker_id: str = ""
    progress_checker_id: str = ""


@dataclass(slots=True)
class ControllerConfig:
    control_period: float = 0.05
    pose_timeout: float = 0.5
    initial_pose_wait: float = 1.0  # a goal may arrive before the first pose does
    failure_tolerance: float = 0.3
    time_allowance: float = 0.0  # 0: no limit on a goal's duration
    known_frames: tuple[str, ...] = ("map", "odom")
    default_controller: str = "FollowPath"
    default_goal_checker: str = "general_goal_checker"
    default_progress_checker: str = "progress_checker"
    controllers: dict[str, Callable[[], Controller]] = field(
        default_factory=lambda: {"FollowPath": RegulatedPurePursuit, "DWB": DWBController}
    )
    checkers: CheckerRegistry = field(default_factory=default_checkers)


@dataclass(slots=True, frozen=True)
class StepResult:
    """One cycle's command; ``trajectory``: the poses ``(n, 3)`` the controller predicts for
    it (its local plan, in the path's frame), empty when the robot is to stand still."""

    cmd: Velocity
    feedback: TrackingFeedback | None = None
    succeeded: bool = False
    error: ControllerError | None = None
    trajectory: FloatArray = field(default_factory=lambda: NO_TRAJECTORY)

    @property
    def finished(self) -> bool:
        return self.succeeded or self.error is not None


def _pick(kind: str, wanted: str, default: str, known: Mapping[str, object]) -> str:
    name = wanted or default
    if name not in known:
        raise ControllerError(
            FollowPathError.INVALID_CONTROLLER,
            f"unknown {kind} {name!r}; known: {', '.join(sorted(known))}",
        )
    return name


def validate_path(path: PlanarPath, known_frames: tuple[str, ...]) -> None:
    if len(path) == 0:
        raise ControllerError(FollowPathError.INVALID_PATH, "path is empty")
    if len(path) == 1:
        raise ControllerError(
            FollowPathError.INVALID_PATH, "path has a single pose; at least two are needed"
        )
    if path.frame_id not in known_frames:
        raise ControllerError(
            FollowPathError.TF_ERROR,
            f"path frame {path.frame_id!r} is unknown; known frames: {', '.join(known_frames)}",
        )
    for name, column in (("x", path.xy[:, 0]), ("y", path.xy[:, 1]), ("yaw", path.yaw)):
        bad = [i for i, value in enumerate(column) if not math.isfinite(float(value))]
        if bad:
            raise ControllerError(
                FollowPathError.INVALID_PATH, f"path pose {bad[0]} has a non-finite {name}"
            )


class FollowPathSession:
    """Runs one FollowPath goal: validate, then :meth:`step` each control cycle."""

    __slots__ = (
        "_collision", "_config", "_controller", "_failing_since", "_goal_checker",
        "_ids", "_progress", "_request", "_speed_limit", "_started", "_track_segment",
    )  # fmt: skip

    def __init__(
        self,
        request: FollowRequest,
        config: ControllerConfig,
        now: float,
        collision: CollisionChecker | None,
        speed_limit: SpeedLimit = NONE,
    ) -> None:
        self._config = config
        self._collision = collision
        self._speed_limit = speed_limit
        self._started = now
        self._failing_since: float | None = None
        self._ids = ("", "", "")
        self._install(request, now)

    @property
    def request(self) -> FollowRequest:
        return self._request

    def set_speed_limit(self, limit: SpeedLimit) -> None:
        """The limit now in force (``{ns}/speed_limit``), kept for a controller the next
        request may switch to."""
        self._speed_limit = limit
        self._controller.set_speed_limit(limit)

    def replace(self, request: FollowRequest, now: float) -> None:
        """Take over a new path (preemption) without stopping; raises on a bad request."""
        self._install(request, now)

    def _install(self, request: FollowRequest, now: float) -> None:
        cfg = self._config
        ids = (
            _pick("controller id", request.controller_id, cfg.default_controller, cfg.controllers),
            _pick(
                "goal checker id",
                request.goal_checker_id,
                cfg.default_goal_checker,
                cfg.checkers.goal_checkers,
            ),
            _pick(
                "progress checker id",
                request.progress_checker_id,
                cfg.default_progress_checker,
                cfg.checkers.progress_checkers,
            ),
        )
        validate_path(request.path, cfg.known_frames)
        if ids[0] != self._ids[0]:
            self._controller: Controller = cfg.controllers[ids[0]]()
            self._controller.set_speed_limit(self._speed_limit)
        if ids[1] != self._ids[1]:
            self._goal_checker: GoalChecker = cfg.checkers.goal_checkers[ids[1]]()
        if ids[2] != self._ids[2]:
            self._progress: ProgressChecker = cfg.checkers.progress_checkers[ids[2]]()
        self._ids = ids
        self._request = request
        self._track_segment = 0
        self._controller.set_plan(request.path)
        self._goal_checker.reset()

    def step(self, now: float, states: Mapping[str, RobotState], lead: float = 0.0) -> StepResult:
        """One control cycle; ``lead``: clock seconds until a command sent now takes effect."""
        try:
            return self._step(now, states, lead)
        except ControllerError as error:
            return StepResult(STOP, error=error)

    def _step(self, now: float, states: Mapping[str, RobotState], lead: float) -> StepResult:
        cfg = self._config
        path = self._request.path
        if cfg.time_allowance > 0.0 and now - self._started > cfg.time_allowance:
            raise ControllerError(
                FollowPathError.CONTROLLER_TIMED_OUT,
                f"goal not reached within the time allowance of {cfg.time_allowance:.1f} s",
            )
        if path.frame_id not in states and now - self._started <= cfg.initial_pose_wait:
            return StepResult(STOP)
        state = self._fresh_state(states, path.frame_id)
        feedback = self._track(path, state.pose)
        if self._goal_checker.is_goal_reached(state.pose, path.goal, state.velocity):
            return StepResult(STOP, feedback, succeeded=True)
        if not self._progress.check(state.pose, now):
            raise ControllerError(
                FollowPathError.FAILED_TO_MAKE_PROGRESS, "failed to make progress"
            )
        cmd = self._compute(now, state, lead)
        trajectory = NO_TRAJECTORY if cmd is STOP else self._controller.trajectory
        return StepResult(cmd, feedback, trajectory=trajectory)

    def _track(self, path: PlanarPath, pose: Pose2D) -> TrackingFeedback:
        # search forward from the last foot point, so a U-turn's return leg is not taken early
        stop = search_stop(path, self._track_segment, TRACKING_SEARCH_DISTANCE)
        projection = project_onto_path(path, pose, self._track_segment, stop)
        self._track_segment = projection.segment
        return tracking_feedback(path, pose, projection)

    def _fresh_state(self, states: Mapping[str, RobotState], frame: str) -> RobotState:
        state = states.get(frame)
        if state is None:
            raise ControllerError(
                FollowPathError.TF_ERROR,
                f"no robot pose received in frame {frame!r} "
                f"within {self._config.initial_pose_wait:.1f} s",
            )
        stale = state.age.stale(frame, self._config.pose_timeout)
        if stale is not None:
            raise ControllerError(FollowPathError.TF_ERROR, stale)
        if not state.pose.is_finite():
            raise ControllerError(
                FollowPathError.TF_ERROR, f"robot pose in frame {frame!r} is not finite"
            )
        return state

    def _compute(self, now: float, state: RobotState, lead: float) -> Velocity:
        ctx = ControlContext(
            self._config.control_period,
            self._goal_checker.xy_goal_tolerance,
            self._collision,
            lead,
        )
        try:
            cmd = self._controller.compute_velocity(state.pose, state.velocity, ctx)
        except ControllerError as error:
            self._be_patient(now, error)
            return STOP
        self._failing_since = None
        return cmd

    def _be_patient(self, now: float, error: ControllerError) -> None:
        """Nav2's ``failure_tolerance``: 0 fails at once with the controller's own error;
        otherwise the robot stands still and the goal fails PATIENCE_EXCEEDED after it."""
        tolerance = self._config.failure_tolerance
        if tolerance <= 0.0:
            raise error
        if self._failing_since is None:
            self._failing_since = now
        waited = now - self._failing_since
        if waited >= tolerance:
            raise ControllerError(
                FollowPathError.PATIENCE_EXCEEDED,
                f"controller patience exceeded: {error.message}; "
                f"no valid control for {waited:.2f} s (failure_tolerance {tolerance:.2f} s)",
            )
