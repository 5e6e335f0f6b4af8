"""The collision monitor on the bus: ``{ns}/cmd_vel_smoothed`` in, ``{ns}/cmd_vel`` out,
one decision per command (as Nav2's); sources subscribed as configured (the lidar on
``{ns}/scan``, point clouds on any key); ``{ns}/odom`` for ``base_shift_correction``,
kept as it comes (50 Hz: no wake-up of the loop each) and read when a scan or a
command arrives.

On sim time the monitor's clock is the robot's time as its odometry stamps it
(:func:`aiobt.system.service.make_clock`), not a second subscription to the 100 Hz
``{ns}/clock``: the same time base as Nav2's (``use_sim_time``), at a third of the
wake-ups of Zenoh's threads (bench/history/safety.md). The odometry for
``base_shift_correction`` then comes from that same subscription (an
:class:`~aiobt.system.odometry_tap.OdometryTap`: each message decoded once, for
both); on the wall clock, or on a clock shared with another component, the monitor
keeps the odometry's payloads itself (a ``Latest``).

Beside Nav2's decision per command, a source going stale between two commands stops
a moving base at once (:meth:`watch`), so the stop does not wait for the controller's
next command.

Publishes, latched, its state on ``{ns}/collision_monitor/state`` (which polygon acts
and why, on every change) and its polygons on ``{ns}/collision_monitor/polygons`` (the
acting one marked); serves ``{ns}/srv/collision_monitor/toggle`` (Nav2's ``Toggle``,
what the ``ToggleCollisionMonitor`` node calls).
"""

from __future__ import annotations

import asyncio
import logging
import math

from aiobt.core.clock import Clock
from aiobt.msgs import Header, LaserScan, Odometry, Toggle, Twist
from aiobt.msgs.safety import (
    ACTION_CODES,
    CollisionMonitorState,
    CollisionPolygons,
    PointCloud,
    ZoneOutline,
)
from aiobt.system.odometry_tap import OdometryTap
from aiobt.transport import Bus, Latest, Publisher
from aiobt.transport.simtime import SimTime

from .monitor import STOP, Action, CollisionMonitor
from .sources import Source, cloud_points, scan_points
from .zones import Vel

log = logging.getLogger("aiobt_services.collision_monitor.service")
POLYGONS_TOPIC = "collision_monitor/polygons"
TOGGLE_SERVICE = "collision_monitor/toggle"
ODOM_KEPT = 32  # odometry messages kept between reads (50 Hz; reads at 10 Hz or more)
IDLE_CHECK = 1.0  # robot s between looks for data to watch when none goes stale


class MonitorService:
    """Wires a :class:`CollisionMonitor` to the bus."""

    def __init__(
        self, bus: Bus, clock: Clock, monitor: CollisionMonitor, tap: OdometryTap | None = None
    ) -> None:
        self.bus = bus
        self.clock = clock
        self.monitor = monitor
        self._out: Publisher[Twist] | None = None
        self._state: Publisher[CollisionMonitorState] | None = None
        self._polygons: Publisher[CollisionPolygons] | None = None
        self._shown: tuple[str, str] | None = None  # the (action, polygon) last reported
        self._shapes: tuple[int, ...] = ()  # the zones' shapes last published
        self._odom: Latest[Odometry] | None = None
        self._tap = tap  # the odometry the clock follows (None: subscribed here)
        self._odom_fed = -math.inf  # the stamp of the newest odometry in the history
        self._command: Vel = STOP  # the last command in
        self._task: asyncio.Task[None] | None = None
        timeouts = [s.source_timeout for s in monitor.params.sources if s.source_timeout > 0.0]
        self._idle_check = min([IDLE_CHECK, *timeouts])  # for data to come

    def start(self) -> None:
        if isinstance(self.clock, SimTime):
            self.clock.hold()  # decisions read now(): the robot's time must keep coming
        p = self.monitor.params
        self._out = self.bus.publisher(p.cmd_vel_out_topic, Twist, reliable=True)
        self._state = self.bus.latched_publisher(p.state_topic, CollisionMonitorState)
        self._polygons = self.bus.latched_publisher(POLYGONS_TOPIC, CollisionPolygons)
        for source in self.monitor.sources.values():
            self._subscribe(source)
        if self.monitor.odom is not None and self._tap is None:
            self._odom = self.bus.latest(p.odom_topic, Odometry, keep=ODOM_KEPT)
        self.bus.subscribe(p.cmd_vel_in_topic, Twist, self.on_command, queue_size=1)
        self.bus.serve(TOGGLE_SERVICE, Toggle.Request, Toggle.Response, self.on_toggle)
        self._report(self.monitor.last, force=True)
        self._task = asyncio.create_task(self.watch(), name="collision_monitor.watch")

    async def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()
            await asyncio.gather(self._task, return_exceptions=True)

    def _subscribe(self, source: Source) -> None:
        topic = source.params.topic
        if source.params.type == "scan":

            def on_scan(msg: LaserScan) -> None:
                self._feed_odom()
                source.take(scan_points(msg), msg.header.stamp, self.clock.now())

            self.bus.subscribe(topic, LaserScan, on_scan, queue_size=1)
        else:

            def on_cloud(msg: PointCloud) -> None:
                self._feed_odom()
                points = cloud_points(msg, source.params)
                source.take(points, msg.header.stamp, self.clock.now())

            self.bus.subscribe(topic, PointCloud, on_cloud, queue_size=1)

    def _feed_odom(self) -> None:
        """The odometry come since the last call into the history, oldest first."""
        history = self.monitor.odom
        if self._tap is not None and history is not None:
            for msg in self._tap.take():
                pose = msg.pose
                history.add(msg.header.stamp, pose.position.x, pose.position.y, pose.yaw)
            return
        if self._odom is None or history is None:
            return
        newest = self._odom.get()
        if newest is not None and newest.header.stamp < self._odom_fed - 1.0:
            self._odom_fed = -math.inf  # time went back: a restarted robot
        fresh: list[Odometry] = []
        for msg in self._odom.newest_first():
            if msg.header.stamp <= self._odom_fed:
                break
            fresh.append(msg)
        for msg in reversed(fresh):
            pose = msg.pose
            history.add(msg.header.stamp, pose.position.x, pose.position.y, pose.yaw)
        if fresh:
            self._odom_fed = fresh[0].header.stamp

    def on_command(self, msg: Twist) -> None:
        self._command = (msg.linear.x, msg.linear.y, msg.angular.z)
        self._decide()

    def _decide(self) -> None:
        self._feed_odom()
        action = self.monitor.process(self._command, self.clock.now())
        if action.publish and self._out is not None:
            vx, vy, wz = action.velocity
            self._out.put(Twist.planar(vx, wz, vy))
        self._report(action)

    async def watch(self) -> None:
        """Until cancelled: at the moment a source goes stale, a base still moving is
        stopped (decided as for the last command), not at the next command."""
        acted = math.nan  # the deadline already acted on
        while True:
            now, due = self.clock.now(), self.monitor.stale_at()
            if now <= due < math.inf:
                await self.clock.sleep(due - now + 1e-6)  # strictly older than the timeout
                continue
            if due < now and due != acted:
                acted = due
                if self.monitor.last.velocity != STOP:
                    self._decide()
            await self.clock.sleep(self._idle_check)

    def on_toggle(self, request: Toggle.Request) -> Toggle.Response:
        message = self.monitor.toggle(request.enable)
        log.info("%s", message)
        self._report(self.monitor.last, force=True)
        return Toggle.Response(success=True, message=message)

    def _report(self, action: Action, force: bool = False) -> None:
        """The state when the acting polygon changes (Nav2 notifies on change); the
        polygons then too, and when a velocity polygon changes its shape."""
        shown = (action.action_type, action.polygon_name)
        shapes = tuple(id(z.shape) for z in self.monitor.zones)
        if shown == self._shown and not force and shapes == self._shapes:
            return  # the common case: nothing to tell
        stamp = Header(stamp=self.clock.now(), frame_id="base_link")
        if shown != self._shown or force:
            if shown != self._shown:
                log.info("%s", action.reason or "robot to continue normal operation")
            self._shown = shown
            if self._state is not None:
                self._state.put(self._state_of(action, stamp))
        self._shapes = shapes
        if self._polygons is not None:
            self._polygons.put(self._outlines(action, stamp))

    def _state_of(self, action: Action, stamp: Header) -> CollisionMonitorState:
        vx, _, wz = action.velocity
        return CollisionMonitorState(
            header=stamp,
            action_type=ACTION_CODES[action.action_type],
            action=action.action_type,
            polygon_name=action.polygon_name,
            reason=action.reason,
            enabled=self.monitor.enabled,
            linear_x=vx,
            angular_z=wz,
        )

    def _outlines(self, action: Action, stamp: Header) -> CollisionPolygons:
        zones = [
            ZoneOutline(
                name=z.params.name,
                action_type=z.params.action_type,
                enabled=z.params.enabled,
                acting=z.params.name == action.polygon_name,
                points=[(float(x), float(y)) for x, y in z.shape.outline()],
            )
            for z in self.monitor.zones
        ]
        return CollisionPolygons(header=stamp, enabled=self.monitor.enabled, polygons=zones)
