"""The robot as Nav2's nodes see it: pose, odometry, battery, initial pose, tracking.

Nav2's nodes ask TF for the robot pose and open their own subscriptions; aiobt's
read one :class:`RobotState` per bus and namespace, over shared subscriptions
(:mod:`aiobt.nav.shared_topics`), each declared on first use:

- the robot in ``map``, as Nav2's nodes look ``map`` -> ``base_link`` up in TF: the
  odometry composed with localization's ``map`` -> ``odom`` on ``{ns}/tf``, or
  ``{ns}/pose`` (PoseStamped) until a pose is composed with a correction (a robot
  with its own localization): :class:`~aiobt.geometry.map_pose.MapPose`;
- ``{ns}/odom``: Odometry (pose in ``odom``, twist);
- ``{ns}/battery``: BatteryState;
- ``{ns}/initialpose``: PoseWithCovarianceStamped (or a PoseStamped), a localization reset;
- ``{ns}/tracking_feedback``: TrackingFeedback, published by the controller
  each control cycle while it follows a path.

Without TF, the frames known are the pose's (``map``) and the odometry's
(``odom``); the base frame is whatever the robot reports its pose of.
"""

from __future__ import annotations

import itertools
import logging
import math
from typing import TYPE_CHECKING, Any, ClassVar

from aiobt.geometry.map_pose import TF_KEPT, MapPose
from aiobt.msgs import (
    BatteryState,
    Msg,
    Odometry,
    PoseStamped,
    PoseWithCovarianceStamped,
    TFMessage,
    TrackingFeedback,
)
from aiobt.nav.context import NavNode
from aiobt.nav.shared_topics import SharedTopic, SharedTopics, shared_topics

if TYPE_CHECKING:
    from aiobt.nav.context import NavContext

log = logging.getLogger("aiobt.nav.robot_state")

POSE, ODOM, TF, BATTERY, INITIAL_POSE, TRACKING = (
    "pose",
    "odom",
    "tf",
    "battery",
    "initialpose",
    "tracking_feedback",
)
_MODELS: dict[str, type[Msg]] = {
    POSE: PoseStamped,
    ODOM: Odometry,
    TF: TFMessage,
    INITIAL_POSE: PoseWithCovarianceStamped,
    TRACKING: TrackingFeedback,
}
ODOM_SMOOTHING_WINDOW = 0.3  # s of odometry averaged for the speed (Nav2's OdomSmoother)
ODOM_KEEP = 32  # odometry messages kept: 0.64 s at the robot's 50 Hz, over the window
KEEP = {ODOM: ODOM_KEEP, TF: TF_KEPT}  # messages each key keeps (the others: the newest only)
BRAKE_ACCEL_LIMIT = -10.0  # m/s^2: a harder deceleration means the robot hit something


class OdomSmoother:
    """The robot's speed: the twists of the last ``window`` seconds of odometry
    (by their stamps), averaged, as Nav2's ``nav2_util::OdomSmoother``; read from
    the messages the odometry topic keeps, when asked."""

    def __init__(self, odom: SharedTopic[Odometry], window: float = ODOM_SMOOTHING_WINDOW) -> None:
        self.window = window
        self._odom = odom

    def speed(self) -> float | None:
        """Mean planar speed (m/s) over the window; None before any odometry."""
        vx = vy = 0.0
        n = 0
        newest = later = math.inf
        for message in self._odom.newest_first():
            stamp = message.header.stamp
            if n == 0:
                newest = stamp
            elif stamp > later or stamp < newest - self.window:
                break  # time went back (a simulation reset) before it, or out of the window
            later = stamp
            vx += message.twist.linear.x
            vy += message.twist.linear.y
            n += 1
        if n == 0:
            return None
        vx, vy = vx / n, vy / n
        return float((vx * vx + vy * vy) ** 0.5)


class BrakeDetector:
    """IsStuck's measure (Nav2): the acceleration between the last two odometry
    messages when asked; below ``BRAKE_ACCEL_LIMIT`` the robot is stuck (it braked
    on something). Two messages with the same stamp leave the last verdict."""

    def __init__(self, odom: SharedTopic[Odometry]) -> None:
        self.accel = 0.0
        self._stuck = False
        self._odom = odom
        self._reported = False

    @property
    def stuck(self) -> bool:
        last_two = list(itertools.islice(self._odom.newest_first(), 2))
        if len(last_two) < 2:
            return self._stuck
        message, previous = last_two
        dt = message.header.stamp - previous.header.stamp
        if dt <= 0.0:  # repeated or reordered stamps: no rate to measure
            if not self._reported:
                self._reported = True
                log.warning("odometry stamps do not increase (dt=%.3f s); ignored", dt)
            return self._stuck
        self.accel = (message.twist.linear.x - previous.twist.linear.x) / dt
        stuck = self.accel < BRAKE_ACCEL_LIMIT
        if stuck != self._stuck:
            log.info("robot %s (accel %.2f m/s^2)", "got stuck" if stuck else "is free", self.accel)
        self._stuck = stuck
        return stuck


class RobotState:
    """Latest robot data of one bus and namespace (None until the first message)."""

    def __init__(self, topics: SharedTopics) -> None:
        self.topics = topics
        self._map_pose: MapPose | None = None

    def _odom(self) -> SharedTopic[Odometry]:
        return self.topics.topic(ODOM, Odometry, keep=KEEP[ODOM])

    @property
    def map_pose(self) -> MapPose:
        """The reader of the pose in ``map`` (odometry, tf and, until a pose is composed, pose)."""
        reader = self._map_pose
        if reader is None:
            tf = self.topics.topic(TF, TFMessage, keep=KEEP[TF])
            pose = self.topics.topic(POSE, PoseStamped)
            reader = self._map_pose = MapPose(self._odom(), tf, pose)
        return reader

    def read_again(self) -> MapPose:
        """A new :attr:`map_pose` after :meth:`SharedTopics.resume` (which subscribes
        ``{ns}/pose`` again: nothing from before the pause is known)."""
        self._map_pose = None
        return self.map_pose

    @property
    def pose(self) -> PoseStamped | None:
        """The robot in ``map`` (:class:`MapPose`), None until it can be told."""
        return self.map_pose.get()

    @property
    def odometry(self) -> Odometry | None:
        return self._odom().latest

    @property
    def initial_pose(self) -> PoseWithCovarianceStamped | None:
        return self.topics.topic(INITIAL_POSE, PoseWithCovarianceStamped).latest

    @property
    def tracking_feedback(self) -> TrackingFeedback | None:
        return self.topics.topic(TRACKING, TrackingFeedback).latest

    def battery(self, topic: str = BATTERY) -> BatteryState | None:
        return self.topics.topic(topic, BatteryState).latest

    def pose_in(self, frame: str = "") -> PoseStamped | None:
        """The robot pose in ``frame`` (``""``: the localization frame, ``map``), or None
        when that frame has no data yet or is not one this robot reports."""
        pose = self.pose
        if pose is not None and frame in ("", pose.header.frame_id):
            return pose
        odom = self.odometry
        if odom is not None and frame == odom.header.frame_id:
            return PoseStamped(header=odom.header, pose=odom.pose)
        return None

    def knows_frame(self, frame: str) -> bool:
        """Whether ``frame`` is one the robot's data are given in."""
        return self.pose_in(frame) is not None

    def speed(self) -> float | None:
        """The smoothed planar speed (m/s), None before any odometry."""
        smoother: OdomSmoother = self.topics.shared(
            "odom_smoother", lambda _: OdomSmoother(self._odom())
        )
        return smoother.speed()

    def brake(self) -> BrakeDetector:
        detector: BrakeDetector = self.topics.shared(
            "brake_detector", lambda _: BrakeDetector(self._odom())
        )
        return detector

    def prepare(self, *names: str) -> None:
        """Subscribe now to the keys a node will read (so data arrive before its first tick)."""
        for name in names:
            if name == POSE:
                self.map_pose  # noqa: B018 - declares odom, tf and pose
            else:
                self.topics.topic(name, _MODELS.get(name, BatteryState), keep=KEEP.get(name, 1))


def robot_state(nav: NavContext, who: str) -> RobotState:
    """The :class:`RobotState` of ``nav``'s bus and namespace (``who`` names the node
    in the error raised when the factory has no bus)."""
    topics = shared_topics(nav, who)
    state: RobotState = topics.shared("robot_state", RobotState)
    return state


class RobotStateNode(NavNode):
    """Mixin of the nodes that read the robot (put it first, as NavNode).

    ``READS`` names the keys the node reads; with a bus they are subscribed
    when the node is built, so data arrive before its first tick.
    :meth:`robot_pose` logs a missing pose once per node, not every tick.
    """

    READS: ClassVar[tuple[str, ...]] = (POSE,)
    _robot: RobotState | None = None
    _pose_missing_reported = False

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        if self.nav.bus is not None:
            self.robot.prepare(*self.READS)

    @property
    def robot(self) -> RobotState:
        robot = self._robot
        if robot is None:
            robot = self._robot = robot_state(self.nav, getattr(self, "path", "?"))
        return robot

    def robot_pose(self, frame: str = "") -> PoseStamped | None:
        """The robot pose in ``frame``; None (reported once) when there is none yet."""
        pose = self.robot.pose_in(frame)
        if pose is None and not self._pose_missing_reported:
            self._pose_missing_reported = True
            log.warning(
                "%s: no robot pose in frame %r yet (from %s/%s with %s/%s, or %s/%s)",
                getattr(self, "path", "?"),
                frame or "map",
                self.robot.topics.namespace,
                ODOM,
                self.robot.topics.namespace,
                TF,
                self.robot.topics.namespace,
                POSE,
            )
        elif pose is not None:
            self._pose_missing_reported = False
        return pose
