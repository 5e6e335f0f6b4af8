"""The velocity smoother on the bus: ``{ns}/cmd_vel_nav`` in, ``{ns}/cmd_vel_smoothed``
out at ``smoothing_frequency`` of robot time (the injected clock: sim time at any
speed-up), ``{ns}/odom`` read for CLOSED_LOOP feedback.

Unlike Nav2's, which publishes on its timer only, each command is smoothed and sent
as it arrives, and the timer fills in when commands stop coming (the timeout's ramp
down). A timer alone delays every command until its next tick: up to a period, and a
whole period when the controller ticks on the same clock just before it, as on sim
time, where both wake on the same clock stamp (measured: p50 54 ms at 20 Hz,
bench/safety). Sending only when half a period had passed since the last output
held a command back for the timer whenever sim time's stamps were coarser than that
(every 40 ms of robot time at a speed-up of 10): 79 ms p50 added at 10x. A command
sooner than a period after the last output may change the velocity by only
``max_accel`` times the time between them (see :mod:`.smoother`).

Stopped (no command yet, or the timeout's zero sent and no command since: Nav2's
timer then publishes nothing), the timer waits for the next command without a clock
sleep, so on sim time the clock is let go (:mod:`aiobt.transport.simtime`) and an
idle smoother receives no stamps. Time then stands where it was let go. A command
arriving then is smoothed and sent at once, as of that time: a rest lasts more than a
period, so the step is a period's from the last output (or odometry), as Nav2's first
tick after a command; at the first fresh stamp its time (and its output's) becomes
that stamp's, so its age and the next step count on the robot's time again.
"""

from __future__ import annotations

import asyncio
import logging
import math
from dataclasses import dataclass

import numpy as np

from aiobt.core.clock import Clock
from aiobt.msgs import Odometry, Twist
from aiobt.transport import Bus, Publisher, Subscription
from aiobt.transport.simtime import SimTime

from .smoother import VelocitySmoother

log = logging.getLogger("aiobt_services.velocity_smoother.service")
REPORT_PERIOD = 5.0  # robot s between reports of dropped commands


@dataclass(slots=True, frozen=True)
class Topics:
    """Where the commands come from and go (Nav2's remappable names)."""

    cmd_in: str = "cmd_vel_nav"
    cmd_out: str = "cmd_vel_smoothed"


class SmootherService:
    """Wires a :class:`VelocitySmoother` to the bus and runs its timer on ``clock``."""

    def __init__(
        self, bus: Bus, clock: Clock, smoother: VelocitySmoother, topics: Topics | None = None
    ) -> None:
        self.bus = bus
        self.clock = clock
        self.smoother = smoother
        self.topics = topics or Topics()
        self._pub: Publisher[Twist] | None = None
        self._sub: Subscription[Twist] | None = None
        self._task: asyncio.Task[None] | None = None
        self._reported = 0
        self._last = -math.inf  # when the last output was sent, robot s
        self._streaming = False  # the last output was a command's: the timer waits longer
        self._next_tick = -math.inf  # the timer's next tick, robot s
        self._next_report = -math.inf  # when dropped commands may be reported next, robot s
        self._resting = False  # stopped: the timer waits for a command, not on the clock
        self._wake = asyncio.Event()  # a command came (for the resting timer)

    @property
    def dropped(self) -> int:
        """Input commands dropped: NaN/inf values, or not a Twist at all."""
        bad_wire = self._sub.dropped_invalid if self._sub is not None else 0
        return self.smoother.rejected + bad_wire

    def start(self) -> None:
        self._pub = self.bus.publisher(self.topics.cmd_out, Twist, reliable=True)
        self._sub = self.bus.subscribe(self.topics.cmd_in, Twist, self.on_command, queue_size=1)
        if self.smoother.params.feedback == "CLOSED_LOOP":
            self.bus.subscribe(self.smoother.params.odom_topic, Odometry, self.on_odom)
        self._task = asyncio.create_task(self.run(), name="velocity_smoother")

    def on_command(self, msg: Twist) -> None:
        now = self.clock.now()  # sim time let go: the last stamp (see _rest)
        if self.smoother.command((msg.linear.x, msg.linear.y, msg.angular.z), now):
            self._update(now, streaming=True)
            self._wake.set()
        elif now >= self._next_report:
            self._report_drops(now)

    def _update(self, now: float, streaming: bool) -> bool:
        """Publish the smoother's output at ``now``; False: nothing to publish (stopped)."""
        out = self.smoother.update(now)
        if out is None:
            return False
        if self._pub is not None:
            self._last, self._streaming = now, streaming
            self._pub.put(Twist.planar(float(out[0]), float(out[2]), float(out[1])))
        return True

    def on_odom(self, msg: Odometry) -> None:
        t = msg.twist
        self.smoother.odom.add(msg.header.stamp, np.array([t.linear.x, t.linear.y, t.angular.z]))

    async def run(self) -> None:
        """The timer: an update a period after the last one (one and a half after a
        command's, so a stream of commands is never overtaken by it), until cancelled;
        stopped, it rests until a command comes."""
        period = self.smoother.params.period
        self._next_report = self.clock.now() + REPORT_PERIOD
        while True:
            now = self.clock.now()
            if now >= self._next_report:
                self._report_drops(now)
            if self._resting:
                await self._rest()
                continue
            after_output = self._last + (1.5 if self._streaming else 1.0) * period
            due = max(self._next_tick, after_output)
            if now < due:
                await self.clock.sleep(due - now)
                continue
            self._next_tick = now + period
            self._resting = not self._update(now, streaming=False)

    async def _rest(self) -> None:
        """Wait for a command, holding no clock; one sent while sim time was let go
        (as of the last stamp) is moved to the first fresh stamp."""
        self._wake.clear()
        await self._wake.wait()
        if isinstance(self.clock, SimTime) and not self.clock.fresh:
            await self.clock.wait_fresh(None)
            now = self.clock.now()
            self.smoother.resume(now)
            self._last = now
        self._resting = False

    @property
    def resting(self) -> bool:
        """Stopped: the timer waits for a command, not on the clock."""
        return self._resting

    def _report_drops(self, now: float) -> None:
        self._next_report = now + REPORT_PERIOD
        dropped = self.dropped
        if dropped > self._reported:
            log.warning(
                "%d command(s) on %s dropped as invalid (NaN, inf or malformed); %d in all",
                dropped - self._reported,
                self.bus.keys.topic(self.topics.cmd_in),
                dropped,
            )
            self._reported = dropped

    async def stop(self) -> None:
        if self._task is not None:
            self._task.cancel()
            await asyncio.gather(self._task, return_exceptions=True)
