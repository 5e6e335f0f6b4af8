"""Paces the simulation against a wall clock and publishes what is due at each step.

The simulation has its own time line; :class:`SimRunner` steps it so that sim
time runs ``speed`` times as fast as the injected wall :class:`Clock`, and
publishes odometry, pose, scan, battery, clock and bumper events through an
:class:`Outputs` sink (Zenoh in the service, a list in tests).
"""

from __future__ import annotations

import asyncio
import logging
import math
from dataclasses import dataclass
from typing import Protocol

from aiobt.core.clock import Clock, SystemClock
from aiobt.msgs import Clock as ClockMsg
from aiobt.msgs import Msg

from . import convert
from .sim import Simulation

log = logging.getLogger("aiobt_services.robot.runner")

TOPICS = ("odom", "pose", "scan", "battery", "clock", "bumper")


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
        max_lag: float = 0.25,
    ) -> None:
        if not (math.isfinite(speed) and speed > 0.0):
            raise ValueError(f"speed must be a finite number > 0, got {speed}")
        self.sim = sim
        self.speed = speed
        self.wall: Clock = wall or SystemClock()
        self._outputs = outputs
        rates = rates or Rates()
        self._periods = {t: rates.period_steps(t, sim.config.dt) for t in TOPICS[:5]}
        if not publish_clock:
            del self._periods["clock"]
        self._max_lag = max_lag
        self._lagging = False

    def tick(self) -> None:
        """One physics step, then every publication due at the new sim time."""
        sim = self.sim
        for event in sim.step():
            if event.pressed:
                log.info("bump: %s at (%.2f, %.2f)", event.other, event.x, event.y)
            self._outputs.publish("bumper", convert.bumper(event))
        due = {t for t, every in self._periods.items() if sim.steps % every == 0}
        if "clock" in due:
            self._outputs.publish("clock", ClockMsg(clock=sim.time))
        if "odom" in due:
            self._outputs.publish("odom", convert.odometry(sim))
        if "pose" in due:
            self._outputs.publish("pose", convert.map_pose(sim))
        if "scan" in due:
            self._outputs.publish("scan", convert.laser_scan(sim.scan()))
        if "battery" in due:
            self._outputs.publish("battery", convert.battery_state(sim.battery, sim.time))

    async def advance(self, seconds: float, chunk: int = 50) -> int:
        """Stepped mode: tick through ``seconds`` of sim time now, yielding every ``chunk``."""
        steps = max(0, round(seconds / self.sim.config.dt))
        for done in range(steps):
            self.tick()
            if done % chunk == chunk - 1:
                await asyncio.sleep(0)  # let commands and queries in between
        return steps

    async def run(self, stop: asyncio.Event) -> None:
        """Step in scaled real time until ``stop`` is set."""
        dt = self.sim.config.dt
        wall0, sim0 = self.wall.now(), self.sim.time
        max_batch = max(1, math.ceil(self._max_lag * self.speed / dt))
        while not stop.is_set():
            target = sim0 + (self.wall.now() - wall0) * self.speed
            steps = 0
            while self.sim.time + 0.5 * dt <= target and steps < max_batch:
                self.tick()
                steps += 1
            if target - self.sim.time > self._max_lag * self.speed:
                self._warn_lag()
                wall0, sim0 = self.wall.now(), self.sim.time
            next_step = wall0 + (self.sim.time + dt - sim0) / self.speed
            # yield to the loop even when behind, so commands and services get in
            await self.wall.sleep(max(0.0, next_step - self.wall.now()))

    def _warn_lag(self) -> None:
        if not self._lagging:
            log.warning(
                "simulation cannot keep up with --speed %g; sim time now lags the target",
                self.speed,
            )
        self._lagging = True
