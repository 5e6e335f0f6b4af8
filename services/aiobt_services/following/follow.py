"""The ``follow_object`` execute (Nav2's ``FollowingServer::followObject``), free of
the bus: detections, the robot's frames, the command out and robot time come in, so
tests drive it with fakes.

Per control cycle (``controller_frequency``, robot time) the robot steers with the
smooth control law toward the point ``desired_distance - 0.25`` m short of the object
on the line to it, and stops (STOPPING) within the tolerances of the point at
``desired_distance``. A detection older than ``detection_timeout`` is a lost object:
a retry, searching by turning ``search_angle`` either way (``search_by_rotating``)
until a fresh detection comes; after ``max_retries`` the goal fails with Nav2's code.
The goal succeeds after ``max_duration`` (> 0), or ``static_object_timeout`` (> 0)
at a still object; a cancelled goal stops the robot.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from contextlib import AbstractContextManager
from enum import IntEnum
from typing import Any

from aiobt.core.clock import Clock
from aiobt.geometry import STOP, Velocity, wrap_angle
from aiobt.geometry.pose_filter import StampedPose
from aiobt.msgs.remote_actions import FollowObject
from aiobt.transport.keys import SIM_PREFIX

from .approach import Approach
from .errors import FailedToControl, FailedToDetect, FollowingError, TransformError
from .frames import RobotFrames
from .params import FollowingParams
from .tracking import Detections, Tracking

log = logging.getLogger("aiobt_services.following.follow")
OpenDetections = Callable[[str], AbstractContextManager[Detections]]  # ValueError: bad topic


class FollowingState(IntEnum):
    """FollowObject feedback ``state`` (nav2_msgs)."""

    NONE = 0
    INITIAL_PERCEPTION = 1
    CONTROLLING = 2
    STOPPING = 3
    RETRY = 4


def goal_topic(goal: FollowObject.Goal) -> str:
    """The goal's pose topic, relative to the namespace; FollowingError if unusable."""
    topic = goal.pose_topic.lstrip("/")  # a ROS-style absolute name
    if not topic:
        raise FailedToDetect("No pose topic or target frame provided.")
    if topic.split("/")[0] == SIM_PREFIX:
        raise FailedToDetect(f"pose_topic '{topic}' is the simulation's truth: follow a "
                             "detection of the object, as a robot has")  # fmt: skip
    return topic


def no_frames(frame: str) -> AbstractContextManager[Detections]:
    raise TransformError(f"tracked_frame '{frame}': this server reads no tf")


class FollowingServer:
    """``execute(goal, handle)`` for the bus's action server."""

    def __init__(
        self,
        params: FollowingParams,
        frames: RobotFrames,
        clock: Clock,
        open_detections: OpenDetections,
        command: Callable[[Velocity], None],
        filtered: Callable[[StampedPose], None] = lambda _: None,
        open_frame: OpenDetections = no_frames,
    ) -> None:
        self.params = params
        self.frames = frames
        self.clock = clock
        self.open_detections = open_detections
        self.command = command
        self.filtered = filtered
        self.open_frame = open_frame

    async def execute(self, goal: FollowObject.Goal, handle: Any) -> FollowObject.Result:
        run = _Run(self, goal, handle)
        try:
            opened = self._open(goal)
            with opened as detections:
                log.info("following the object on '%s'", detections.topic)
                return await run.follow(Tracking(detections, self.frames, self.params, self.clock))
        except FollowingError as exc:
            return run.failed(exc)
        except ValueError as exc:  # the topic is not a usable key
            return run.failed(FailedToDetect(f"pose_topic {goal.pose_topic!r}: {exc}"))
        except Exception as exc:  # a bad goal never takes the server down
            log.exception("follow_object failed unexpectedly")
            return run.failed(FollowingError(str(exc)))
        finally:
            self.command(STOP)

    def _open(self, goal: FollowObject.Goal) -> AbstractContextManager[Detections]:
        """The goal's detections: the tracked frame's on tf (Nav2 prefers it), or the
        pose topic's."""
        frame = goal.tracked_frame.lstrip("/")
        if not frame:
            return self.open_detections(goal_topic(goal))
        if self.frames.is_robot_frame(frame) or frame in ("odom", "map", self.params.fixed_frame):
            raise TransformError(f"tracked_frame '{frame}' is one of the robot's own frames "
                                 "(or odom, map), not an object to follow")  # fmt: skip
        log.info("Following frame: %s instead of pose", frame)
        return self.open_frame(frame)


class _Run:
    """One goal: its start, retries and feedback."""

    def __init__(self, server: FollowingServer, goal: FollowObject.Goal, handle: Any) -> None:
        self.server = server
        self.params = server.params
        self.clock = server.clock
        self.goal = goal
        self.handle = handle
        self.began = self.clock.now()
        self.retries = 0
        self.approach = Approach(server.params)

    def elapsed(self) -> float:
        return self.clock.now() - self.began

    def feedback(self, state: FollowingState) -> None:
        self.handle.publish_feedback(FollowObject.Feedback(
            state=state, following_time=self.elapsed(), num_retries=self.retries))  # fmt: skip

    def result(self, error: FollowingError | None = None) -> FollowObject.Result:
        return FollowObject.Result(
            total_elapsed_time=self.elapsed(),
            num_retries=self.retries,
            error_code=error.code if error else 0,
            error_msg=error.message if error else "",
        )

    def failed(self, exc: FollowingError) -> FollowObject.Result:
        log.warning("follow_object failed: %s (%s)", exc.message, exc.reason)
        return self.result(exc)

    async def follow(self, tracking: Tracking) -> FollowObject.Result:
        max_duration, still_since = self.goal.max_duration, None
        while max_duration <= 0.0 or self.elapsed() <= max_duration:
            try:
                moved = await self.approach_object(tracking)
                still_since = self.clock.now() if moved or still_since is None else still_since
                self.feedback(FollowingState.STOPPING)
                self.server.command(STOP)
                if 0.0 < self.params.static_object_timeout < self.clock.now() - still_since:
                    log.info("the object has been still for %.2f s: done",
                             self.clock.now() - still_since)  # fmt: skip
                    return self.result()
            except (FailedToDetect, FailedToControl) as exc:
                still_since = None
                await self.retry(tracking, exc)
            await self.clock.sleep(self.params.period)
        log.info("followed for max_duration %.1f s: done", max_duration)
        return self.result()

    async def retry(self, tracking: Tracking, exc: FollowingError) -> None:
        self.retries += 1
        if self.retries > self.params.max_retries:
            raise type(exc)(f"Failed to follow, all retries have been used: {exc.message}")
        log.warning("following failed, will retry (%d/%d): %s", self.retries,
                    self.params.max_retries, exc.message)  # fmt: skip
        if self.params.search_by_rotating:
            try:
                await self.rotate_to_object(tracking)
            except FailedToControl as failed:
                if not tracking.seen:  # say what was never seen, not how the search ended
                    raise FailedToDetect(f"{exc.message}; searched, never seen") from None
                raise failed

    async def approach_object(self, tracking: Tracking) -> bool:
        """Control until at the desired distance: True if the robot had to move."""
        moved, fixed = False, self.params.fixed_frame
        while True:
            self.feedback(FollowingState.CONTROLLING)
            if tracking.detections.latest() is None:
                await tracking.first_detection()
            obj = tracking.pose()
            self.server.filtered(obj)
            cmd = self.approach.step(obj.pose, self.server.frames.robot_in(fixed))
            if cmd is None:
                return moved
            self.server.command(cmd)
            moved = True
            await self.clock.sleep(self.params.period)

    async def rotate_to_object(self, tracking: Tracking) -> None:
        """Turn ``search_angle`` left, then as far right, until the object is seen."""
        frames, p = self.server.frames, self.params
        initial, started = frames.robot_in(p.fixed_frame).yaw, self.clock.now()
        for heading in (initial + p.search_angle, initial - p.search_angle):
            while True:
                self.feedback(FollowingState.RETRY)
                error = wrap_angle(heading - frames.robot_in(p.fixed_frame).yaw)
                if abs(error) < p.angular_tolerance:
                    break
                if self._seen_again(tracking):
                    return
                self.server.command(self.approach.turn(error, frames.turn_rate))
                if self.clock.now() - started > p.rotate_to_object_timeout:
                    raise FailedToControl("Timed out rotating to object")
                await self.clock.sleep(p.period)
        raise FailedToControl("Failed to rotate to object")

    @staticmethod
    def _seen_again(tracking: Tracking) -> bool:
        if tracking.detections.latest() is None:
            return False
        try:
            tracking.pose()
        except FailedToDetect:
            return False
        return True
