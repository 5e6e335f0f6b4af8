"""Paces the simulation against a wall clock and publishes what is due at each step.

The simulation has its own time line; :class:`SimRunner` steps it so that sim
time runs ``speed`` times as fast as the injected wall :class:`Clock` (``inf``:
as fast as the machine allows), one step at a time with the event loop in
between, and
publishes odometry, pose, scan, battery, clock and bumper events through an
:class:`Outputs` sink (Zenoh in the service, a list in tests).
"""

from __future__ import annotations

import asyncio
import logging
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from aiobt.core.clock import Clock, SystemClock
from aiobt.msgs import Clock as ClockMsg
from aiobt.msgs import Msg
from aiobt.transport.keys import SIM_POSE

from . import convert
from .dock_detector import DockDetectorSwitch
from .pacing import Pacer
from .sim import Simulation

log = logging.getLogger("aiobt_services.robot.runner")

TOPICS = ("odom", "pose", "scan", "battery", "clock", "bumper")
JOINT_STATES = "joint_states"  # the wheels, with odometry (Nav2's stall detection reads it)
DOCK_DETECTION = "detected_dock_pose"  # Nav2's topic: the dock's marker, as a camera sees it
# SIM_POSE and JOINT_STATES are built and sent only while someone listens (``wanted``):
# the truth is for tests, benches and viewers, the wheels for a docking server's stall
# detection; at 50 Hz each, a third of the robot's messages, read by no navigation service.
COMMAND_POLL = 0.001  # wall s between looks for a late command
# A command later than this (wall s) is a stalled client; one scheduler slot on a loaded
# machine (CFS's latency on 2 cores: 12 ms) is not: the base drives on the last command.
LATE_WALL = 0.02
# The shortest pacing sleep, wall s: at a speed-up where steps are due more often, the
# steps due after it run back to back (a loop pass between each). Fewer wake-ups: each
# one preempts whichever process has the core (the controller, at 10x: 1000 a second).
MIN_SLEEP = 0.004
# Behind its target by more than this (wall s), the sim gives the sim time up instead of
# catching it up in a burst: two of the shortest sleeps (at 10x 80 ms of sim time, under
# two periods of a 20 Hz controller). Every sim second run in a burst is one no client
# can act in: after a 30 ms stall of this process at 10x a catch-up would step 0.3 s of
# sim time in a few ms of wall time, on the last command, and a controller following
# the clock loses the control cycles that were due in it.
MAX_LAG = 2 * MIN_SLEEP


class Outputs(Protocol):
    def publish(self, topic: str, msg: Msg) -> None:
        """Send ``msg`` on ``{ns}/{topic}``."""
        ...


@dataclass(slots=True, frozen=True)
class Rates:
    """Publication rates in Hz of sim time (rounded to whole physics steps)."""

    odom: float = 50.0
    pose: float = 50.0
    scan: float = 10.0
    battery: float = 1.0
    clock: float = 100.0
    camera: float = 15.0  # the dock's marker detections

    def period_steps(self, topic: str, dt: float) -> int:
        rate = float(getattr(self, topic))
        if not (math.isfinite(rate) and rate > 0.0):
            raise ValueError(f"rate of {topic} must be > 0 Hz, got {rate}")
        return max(1, round(1.0 / (rate * dt)))


class SimRunner:
    """Steps ``sim`` in (scaled) real time; :meth:`tick` is one step plus its outputs."""

    def __init__(
        self,
        sim: Simulation,
        outputs: Outputs,
        *,
        speed: float = 1.0,
        rates: Rates | None = None,
        wall: Clock | None = None,
        publish_clock: bool = True,
        max_lag: float = MAX_LAG,
        report_every: float = 5.0,
        command_wait: float = 0.5,
        publish_pose: bool = True,
        wanted: Callable[[str], bool] = lambda _topic: True,
    ) -> None:
        self.sim = sim
        self._publish_pose = publish_pose  # {ns}/pose from the truth (no localization)
        self.speed = speed
        self._pacer = Pacer(speed, sim.config.dt, max_lag=max_lag, report_every=report_every)
        self._command_wait = command_wait
        self._given_up = -math.inf  # the command after which waiting ran out
        # sim s a command stream may be late before the sim waits: LATE_WALL of wall time,
        # at most half the command timeout (at --speed max: the stream's own periods)
        limit = 0.5 * sim.config.limits.cmd_timeout
        self._patience = 0.0 if math.isinf(speed) else min(LATE_WALL * speed, limit)
        self.wall: Clock = wall or SystemClock()
        self._outputs = outputs
        self._wanted = wanted  # whether SIM_POSE or JOINT_STATES has a reader now
        rates = rates or Rates()
        self._periods = {t: rates.period_steps(t, sim.config.dt) for t in TOPICS[:5]}
        if not publish_clock:
            del self._periods["clock"]
        self._camera_every = rates.period_steps("camera", sim.config.dt)
        self.dock_detector = DockDetectorSwitch()  # srv/dock_detector/toggle turns it off and on
        self._clock_owed = False  # a clock stamp was due and is not out yet
        self._clock_sent = 0  # the step of the last one out
        self._clock_batch = 1  # steps a stamp due may wait (see :meth:`run`)

    def tick(self) -> None:
        """One physics step, then every publication due at the new sim time."""
        sim = self.sim
        for event in sim.step():
            if event.pressed:
                log.info("bump: %s at (%.2f, %.2f)", event.other, event.x, event.y)
            self._outputs.publish("bumper", convert.bumper(event))
        steps, every = sim.steps, self._periods
        if "clock" in every and steps % every["clock"] == 0:
            self._clock_owed = True
            if steps - self._clock_sent >= self._clock_batch:
                self.publish_clock()
        if steps % every["odom"] == 0:
            self._outputs.publish("odom", convert.odometry(sim))
            if self._wanted(JOINT_STATES):
                self._outputs.publish(JOINT_STATES, sim.wheels.state(sim.time))
        if steps % every["pose"] == 0:
            if self._wanted(SIM_POSE):
                self._outputs.publish(SIM_POSE, convert.true_pose(sim))
            if self._publish_pose:
                self._outputs.publish("pose", convert.map_pose(sim))
        if steps % every["scan"] == 0:
            self._outputs.publish("scan", convert.laser_scan(sim.scan()))
        if steps % every["battery"] == 0:
            self._outputs.publish("battery", convert.battery_state(sim.battery, sim.time))
        if (
            steps % self._camera_every == 0
            and self.dock_detector.on
            and (seen := sim.detect_dock()) is not None
        ):
            self._outputs.publish(DOCK_DETECTION, convert.dock_detection(seen, sim.time))

    def publish_clock(self) -> None:
        """The clock stamp owed, if one is (the sim's time now)."""
        if self._clock_owed:
            self._clock_owed = False
            self._clock_sent = self.sim.steps
            self._outputs.publish("clock", ClockMsg(clock=self.sim.time))

    async def advance(self, seconds: float, chunk: int = 1) -> int:
        """Stepped mode: tick through ``seconds`` of sim time now, yielding every ``chunk``
        steps (by default every step, so commands land between steps as in :meth:`run`)."""
        steps = max(0, round(seconds / self.sim.config.dt))
        for done in range(steps):
            self.tick()
            if done % chunk == chunk - 1:
                await asyncio.sleep(0)  # let commands and queries in between
        return steps

    async def run(self, stop: asyncio.Event) -> None:
        """Step until ``stop`` is set, one physics step at a time, paced by :class:`Pacer`
        (sleeping at least ``MIN_SLEEP``: at 10x four steps per wake-up).

        The event loop runs between every two steps, so the latest ``cmd_vel``
        (and any service request) is applied before the next step whatever the
        speed-up, and a command timeout measured in sim time means what it says.
        When a client driving the base stalls (its command stream is late by more than
        two of its periods and more than ``LATE_WALL`` of wall time) the sim waits for
        it, at most ``command_wait`` wall seconds per command.
        """
        pacer = self._pacer
        pacer.start(self.wall.now(), self.sim.time)
        self._clock_batch = self.clock_batch()
        try:
            while not stop.is_set():
                wait = pacer.delay(self.wall.now(), self.sim.time)
                # one loop pass before every step (commands and requests in), sleeping or not
                if wait > 0.0:
                    self.publish_clock()  # the batch's time, before its sleep
                    await self.wall.sleep(max(wait, MIN_SLEEP))
                else:
                    await asyncio.sleep(0)
                if self._command_late():
                    self.publish_clock()
                    await self._wait_for_command(stop)
                if stop.is_set():
                    break
                self.tick()
                line = pacer.report(self.wall.now(), self.sim.time)
                if line is not None:
                    log.log(logging.WARNING if pacer.fell_short else logging.INFO, "%s", line)
        finally:
            self.publish_clock()
            self._clock_batch = 1

    def clock_batch(self) -> int:
        """Steps a clock stamp due may wait while :meth:`run` steps back to back: those
        of one wake-up (``MIN_SLEEP`` of wall time; at 10x four, at 1x one). The stamp
        then goes out once, at the batch's end, before the sleep: a follower learns the
        same time as early (the steps of a batch take about a millisecond of wall time)
        from a quarter of the messages at 10x (250 a wall second, not 1,000, to every
        process following the clock). A stamp waits at most this many steps when the sim
        runs behind and does not sleep; ``--speed max`` never batches."""
        if self._pacer.unpaced:
            return 1
        return max(1, math.floor(MIN_SLEEP * self.speed / self.sim.config.dt + 1e-9))

    def _command_late(self) -> bool:
        drive = self.sim.drive
        return (
            self._command_wait > 0.0
            and drive.overdue(self.sim.time, self._patience)
            and drive.command_time != self._given_up
        )

    async def _wait_for_command(self, stop: asyncio.Event) -> None:
        """A client driving the base fell behind (its next command is late): wait for it,
        at most ``command_wait`` wall seconds, rather than drive on blind. Once that runs
        out the sim goes on (the command timeout, in sim time, then stops the base)."""
        wall0, drive = self.wall.now(), self.sim.drive
        while drive.overdue(self.sim.time, self._patience) and not stop.is_set():
            if self.wall.now() - wall0 >= self._command_wait:
                self._given_up = drive.command_time
                break
            await self.wall.sleep(COMMAND_POLL)
        self._pacer.held(self.wall.now(), self.sim.time, self.wall.now() - wall0)
