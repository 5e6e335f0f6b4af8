"""What the controller and behavior services read from the robot.

:class:`RobotTracker` keeps the newest robot state per frame (``odom`` from
``{ns}/odom``; ``map`` from each odometry message composed with localization's
correction, or from ``{ns}/pose`` where no correction is sent: :mod:`.correction`),
stamped on the injected clock at
arrival and with its own stamp (for the latency compensation,
:meth:`RobotTracker.lead`), and whether each is fresh by the robot's own stamps
and the wall clock (:mod:`.freshness`).
"""

from __future__ import annotations

import asyncio
import logging
import math
import time
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from aiobt.core.clock import Clock
from aiobt.costmap.local import CostmapUpdate, LocalCostmap
from aiobt.geometry import STOP, Pose2D, Velocity
from aiobt.msgs import LaserScan, Odometry, PoseStamped, Twist

from .correction import Correction, MapSource, compose
from .freshness import Freshness
from .latency import LoopDelay, command_lead
from .rate import RateGate
from .state import RobotState

if TYPE_CHECKING:
    from aiobt.transport import Bus, Subscription

log = logging.getLogger("aiobt.robot.tracker")

FRAMES = ("map", "odom")  # the frames a local costmap can be kept in


def twist_of(cmd: Velocity) -> Twist:
    return Twist.planar(cmd.v, cmd.w)


class RobotTracker:
    """Newest pose per frame, the measured velocity, and the lidar into a local costmap.

    Scans are kept, not integrated, as they arrive: :meth:`due_update` (asked by
    each control cycle of a running goal; :meth:`refresh_costmap` applies it at once)
    takes the newest one,
    at the local costmap's update frequency (Nav2's ``update_frequency``, 5 Hz of
    robot time by default). An idle service so spends nothing on the lidar
    stream, which at a sim speed-up of 10 is 100 scans a second.

    ``robot_time``: the clock follows the robot's own (``--sim-time``), so the
    robot's header stamps are on it and every pose is aged by its own stamp.
    ``scan`` False: the lidar is not read (the local costmap's obstacle layer off).
    ``costmap_frame``: the frame the local costmap is kept in, ``map`` (the pose from
    ``{ns}/pose``, the controller's) or ``odom`` (Nav2's ``local_frame``, the behaviors'):
    a costmap in ``odom`` does not move when localization corrects or reinitializes
    the estimate, so a relocalizing turn is not checked against obstacles laid from the
    estimate before the jump.
    ``map_pose`` False: no pose in ``map`` is read (the behaviors work in ``odom``).

    The pose in ``map`` (see :mod:`.correction`): each odometry message composed with
    the newest correction, so stamped as the odometry and as fresh as it on arrival (the
    :meth:`lead`); its freshness (:meth:`snapshot`'s age) is the correction's, sent with
    every scan localization takes: a localization gone silent makes it stale, as a
    silent ``{ns}/pose`` did.
    """

    __slots__ = (
        "_clock",
        "_correction",
        "_frame",
        "_map_pose",
        "_map_source",
        "_pending_scan",
        "_robot_time",
        "_scan",
        "_taken",
        "_updates",
        "_velocity",
        "costmap",
        "delay",
        "freshness",
        "states",
    )

    def __init__(
        self,
        clock: Clock,
        costmap: LocalCostmap | None = None,
        wall: Callable[[], float] = time.monotonic,
        robot_time: bool = False,
        scan: bool = True,
        costmap_frame: str = "map",
        map_pose: bool = True,
    ) -> None:
        if costmap_frame not in FRAMES:
            raise ValueError(
                f"RobotTracker costmap_frame must be one of {FRAMES}, got {costmap_frame!r}"
            )
        if costmap_frame == "map" and not map_pose:
            raise ValueError("RobotTracker: a costmap kept in 'map' needs the pose in 'map'")
        self._clock = clock
        self._frame = costmap_frame
        self._map_pose = map_pose
        self._map_source: MapSource | None = None
        self._correction: Correction | None = None
        self._robot_time = robot_time
        self._scan = scan
        self._taken: dict[str, float] = {}  # frame -> the newest state's own stamp
        self.costmap = costmap
        self.states: dict[str, RobotState] = {}
        self._velocity = STOP
        self._pending_scan: tuple[LaserScan, Pose2D] | None = None
        self._updates = RateGate(costmap.update_period if costmap is not None else 1.0)
        self.delay = LoopDelay()
        self.freshness = Freshness(wall)

    def snapshot(self) -> dict[str, RobotState]:
        """The newest state per frame, each with its age as of now (see :mod:`.freshness`)."""
        age = self.freshness.age
        return {frame: replace(state, age=age(frame)) for frame, state in self.states.items()}

    def sent(self, cmd: Velocity) -> None:
        """Tell the delay estimate that ``cmd`` was just published."""
        self.delay.commanded(self._clock.now(), cmd, self._velocity)

    def lead(self, frame: str) -> float:
        """Clock seconds from the newest pose in ``frame`` until a command sent now acts.

        Its arrival on this clock plus the command-to-odometry round trip: right on
        average (the round trip holds a typical pose's delivery lag). On the robot's time
        (``robot_time``) also per pose: its age by its own stamp plus the command's way
        (:attr:`LoopDelay.one_way`), and the longer of the two, so a pose delivered
        later than usual gets a longer lead (an earlier stop), an on-time one the same.
        See :func:`.latency.command_lead`."""
        state = self.states.get(frame)
        if state is None:
            return self.delay.estimate
        now = self._clock.now()
        lead = command_lead(now, state.stamp, self.delay.estimate)
        taken = self._taken.get(frame)
        if not self._robot_time or taken is None:
            return lead
        return max(lead, command_lead(now, taken, self.delay.one_way))

    @property
    def waited(self) -> int:
        """How many of :meth:`attach`'s streams a goal waits for: the pose in ``map`` (if
        read) and the odometry."""
        return 2 if self._map_pose else 1

    def attach(self, bus: Bus) -> list[Subscription[Any] | MapSource]:
        """Subscribe to the pose in ``map`` (:class:`MapSource`, if read), odom (and
        scan); the streams, in that order."""
        subs: list[Subscription[Any] | MapSource] = []
        if self._map_pose:
            self._map_source = MapSource(bus, self.on_pose, self.on_correction)
            subs.append(self._map_source)
        subs.append(bus.subscribe("odom", Odometry, self.on_odom))
        if self.costmap is not None and self._scan:
            subs.append(bus.subscribe("scan", LaserScan, self.on_scan))
        return subs

    def forget(self) -> None:
        """Drop the states, the streams' stamps and the waiting scan (before attaching
        again: nothing heard before the service stopped listening counts)."""
        self.states.clear()
        self.freshness.clear()
        self._correction = None
        self._pending_scan = None
        self._updates.reset()

    def on_odom(self, msg: Odometry) -> None:
        self._velocity = Velocity(msg.twist.linear.x, msg.twist.angular.z)
        pose = Pose2D(msg.pose.position.x, msg.pose.position.y, msg.pose.yaw)
        now, stamp = self._clock.now(), msg.header.stamp
        self.states["odom"] = RobotState(pose, self._velocity, now)
        self._taken["odom"] = stamp
        self.freshness.received("odom", stamp)
        self.delay.observed(now, self._velocity, stamp if self._robot_time else None)
        if self._correction is not None:
            in_map = compose(self._correction.transform, pose.x, pose.y, pose.yaw)
            self._set_map(Pose2D(*in_map), now, stamp)

    def on_correction(self, correction: Correction) -> None:
        """Localization's ``map`` -> ``odom``: the next odometry is composed with it."""
        self._correction = correction
        self.freshness.received("map", correction.stamp)

    def on_pose(self, msg: PoseStamped) -> None:
        """``{ns}/pose`` (read until a correction comes: :class:`MapSource`)."""
        self._set_map(Pose2D(msg.x, msg.y, msg.yaw), self._clock.now(), msg.header.stamp)
        self.freshness.received("map", msg.header.stamp)

    def _set_map(self, pose: Pose2D, now: float, stamp: float) -> None:
        self.states["map"] = RobotState(pose, self._velocity, now)
        self._taken["map"] = stamp
        if self._map_source is not None:
            self._map_source.ready()

    def on_scan(self, msg: LaserScan) -> None:
        self.freshness.received("scan", msg.header.stamp)
        state = self.states.get(self._frame)
        if self.costmap is not None and state is not None:
            self._pending_scan = (msg, state.pose)

    def due_update(self) -> CostmapUpdate | None:
        """The local costmap's update, if one is due: the window to the newest pose (in
        ``costmap_frame``), then the newest scan; at most once per update period of
        robot time (the first call with a pose or a scan at once), as Nav2's costmap
        updates at its
        ``update_frequency``. The scan is taken (the next update waits for a newer one)."""
        if self.costmap is None or (self._pending_scan is None and self._frame not in self.states):
            return None
        if not self._updates.due(self._clock.now()):
            return None
        pending, self._pending_scan = self._pending_scan, None
        scan, sensor = pending if pending is not None else (None, None)
        state = self.states.get(self._frame)
        return CostmapUpdate(scan, sensor, state.pose if state is not None else sensor)

    def refresh_costmap(self) -> bool:
        """:meth:`due_update` made and published now (inflated: nothing left for a reader
        to do); True if it updated."""
        update = self.due_update()
        if update is None or self.costmap is None:
            return False
        self.costmap.publish(update.apply(self.costmap))
        return True


async def sleep_bounded(clock: Clock, seconds: float, wall_timeout: float) -> bool:
    """Sleep ``seconds`` of robot time; False if the clock stalls for ``wall_timeout`` s.

    A simulation that died stops its clock; without this bound a loop on sim
    time would wait forever instead of failing its goal.
    """
    if not math.isfinite(wall_timeout) or wall_timeout <= 0.0:
        await clock.sleep(seconds)
        return True
    try:
        async with asyncio.timeout(wall_timeout):
            await clock.sleep(seconds)
    except TimeoutError:
        return False
    return True
