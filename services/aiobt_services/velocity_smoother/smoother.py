"""Nav2's velocity smoother as pure logic: commands in, one smoothed command per period.

:meth:`VelocitySmoother.command` takes the newest input (NaN/inf dropped and counted);
:meth:`VelocitySmoother.update` is Nav2's ``smootherTimer``: nothing before the first
command; a command older than ``velocity_timeout`` is replaced by zero, which is
ramped down to, published once, and then nothing more until a new command; the
command is clamped to ``[min_velocity, max_velocity]``, moved towards from the
current velocity (the last output, OPEN_LOOP; the mean odometry, CLOSED_LOOP) within
``max_accel`` / ``max_decel`` per period (all axes scaled alike with
``scale_velocities``), and a magnitude under ``deadband_velocity`` is sent as 0.

An update sooner than a period after the last one (the service updates as each
command arrives, see :mod:`.service`) may change the velocity by only that much
less: ``max_accel`` times the time since the last update.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .limits import Vec, apply_constraints, common_eta, find_eta_constraint
from .odom import OdomAverage
from .params import SmootherParams


class VelocitySmoother:
    """The smoothing state of one base. Time is the caller's clock, in seconds."""

    __slots__ = ("_command", "_command_time", "_last", "_stopped", "_updated", "_vec", "odom",
                 "params", "rejected")  # fmt: skip

    def __init__(self, params: SmootherParams | None = None) -> None:
        self.params = params or SmootherParams()
        p = self.params
        self._vec = {
            name: np.asarray(getattr(p, name), np.float64)
            for name in ("max_velocity", "min_velocity", "max_accel", "max_decel",
                         "deadband_velocity")
        }  # fmt: skip
        self._command = np.zeros(3)
        self._command_time: float | None = None
        self._last = np.zeros(3)  # the last output before the deadband (Nav2's last_cmd_)
        self._stopped = False
        self._updated: float | None = None  # when the last output was made
        self.odom = OdomAverage(p.odom_duration)
        self.rejected = 0  # input commands dropped for NaN or inf

    @property
    def received(self) -> bool:
        return self._command_time is not None

    def resume(self, now: float) -> None:
        """The clock stood still (sim time let go while stopped) and reads ``now`` again:
        the command and the output made while it stood are taken as of ``now``, so the
        command's age and the next update's step count from there."""
        if self._command_time is not None:
            self._command_time = now
        if self._updated is not None:
            self._updated = now

    def command(self, velocity: Sequence[float], now: float) -> bool:
        """Take ``[vx, vy, wz]`` received at ``now``; False (and counted) if not finite."""
        if not all(math.isfinite(v) for v in velocity):
            self.rejected += 1
            return False
        self._command = np.asarray(velocity, np.float64)
        self._command_time = now
        return True

    def update(self, now: float) -> Vec | None:
        """The command to publish at ``now``, or None: nothing to publish (no command
        yet, or timed out and already stopped)."""
        if self._command_time is None:
            return None
        if now - self._command_time > self.params.velocity_timeout:
            if self._stopped or not np.any(self._last):
                self._stopped = True
                return None
            self._command = np.zeros(3)
        self._stopped = False
        elapsed = period = self.params.period
        if self._updated is not None:
            elapsed = min(period, max(now - self._updated, 1e-3 * period))
        self._updated = now
        return self._step(1.0 / elapsed)

    def _step(self, frequency: float) -> Vec:
        v, p = self._vec, self.params
        current = self._last if p.feedback == "OPEN_LOOP" else self.odom.twist()
        self._command = np.clip(self._command, v["min_velocity"], v["max_velocity"])
        eta = 1.0
        if p.scale_velocities:
            etas = find_eta_constraint(
                current, self._command, v["max_accel"], v["max_decel"], frequency
            )
            eta = common_eta(etas)
        out = apply_constraints(
            current, self._command, v["max_accel"], v["max_decel"], eta, frequency
        )
        self._last = out
        return np.where(np.abs(out) < v["deadband_velocity"], 0.0, out)
