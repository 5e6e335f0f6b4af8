"""How long, in robot (sim) time, a published command takes to move the base.

Under a sim speed-up every millisecond of wall-clock delay between this
process and the robot (transport, a loaded machine) becomes ``speed`` times as
much sim time, so a stop decided "now" takes effect noticeably later in sim
time. :class:`LoopDelay` measures that delay from the services' own traffic:
when a command sets a base at rest moving, the time until odometry first shows
the base moving is one sample. Timed by the odometry's arrival it holds both
directions (the command to the robot and the odometry back); timed by the
odometry's own stamp, on a clock following the robot's (``--sim-time``), it is
the command's way only (plus how far this clock trails the robot's). Controller
and behaviors add it to the pose's age (:func:`command_lead`) for their look-ahead.
"""

from __future__ import annotations

import logging
import math

from aiobt.geometry import Velocity

log = logging.getLogger("aiobt.robot.latency")

MOVING = 1e-3  # m/s or rad/s: below this the base counts as at rest
STALL_LEADS = 3.0  # a stall of a control loop: up to this many times the lead...
STALL_CAP = 0.5  # ... and at most this long (s): the robot's default --cmd-timeout
LEAD_CAP = 0.3  # s: a longer lead (a machine far over its capacity) is taken as this, so
# the holding time, and the slow approach it asks of the behaviors, stay bounded


def holding_time(lead: float) -> float:
    """How long the base may keep the last command sent: a stall of the loop (up to
    ``STALL_LEADS`` leads, at most ``STALL_CAP``, after which the robot's own command
    timeout stops it), then the ``lead`` of the stop sent after the stall. Under a sim
    speed-up both grow with it; at 1x (a lead of a few ms) it is a few cycles at most.
    The lead counts up to ``LEAD_CAP``: at most 0.8 s in all."""
    if lead <= 0.0:
        return 0.0
    lead = min(lead, LEAD_CAP)
    return min(STALL_CAP, STALL_LEADS * lead) + lead


def command_lead(now: float, stamp: float, delay: float) -> float:
    """Clock seconds from a pose taken at ``stamp`` until a command sent at ``now`` acts,
    the command taking ``delay`` to the base: the travel the pose does not show yet.

    With ``stamp`` the pose's own robot time and ``now`` a clock following the robot's,
    a pose delivered late is older by its lateness, so the lead (and the stop decided
    on it) follows each pose; ``now`` may trail the robot (its clock message is older
    than the pose): ``delay``, measured on the same clock, holds that lag too."""
    return max(0.0, now - stamp + delay)


def _moving(v: Velocity) -> bool:
    return abs(v.v) > MOVING or abs(v.w) > MOVING


class LoopDelay:
    """Command-to-odometry delay in clock seconds: the newest samples smoothed.

    ``commanded`` is told every command published with the base's measured
    velocity; ``observed`` every odometry, with its arrival on the clock (the round
    trip, :attr:`estimate`) and, on the robot's time, its own stamp (the command's
    way, :attr:`one_way`). A sample starts when a
    moving command is sent to a base at rest and ends at the first odometry
    showing motion; samples above ``max_delay`` (a stalled robot, a refused
    command) are dropped.
    """

    __slots__ = ("_estimate", "_max_delay", "_one_way", "_sent", "_weight", "samples")

    def __init__(self, max_delay: float = 1.0, weight: float = 0.5) -> None:
        if not (math.isfinite(max_delay) and max_delay > 0.0):
            raise ValueError(f"LoopDelay max_delay must be > 0, got {max_delay}")
        if not 0.0 < weight <= 1.0:
            raise ValueError(f"LoopDelay weight must be in (0, 1], got {weight}")
        self._max_delay = max_delay
        self._weight = weight
        self._estimate = 0.0
        self._one_way: float | None = None  # no sample by stamps yet
        self._sent: float | None = None
        self.samples = 0

    @property
    def estimate(self) -> float:
        """Smoothed delay in clock seconds (0 until the first sample)."""
        return self._estimate

    @property
    def one_way(self) -> float:
        """Smoothed command-to-motion delay by the odometry's stamps (0 without them)."""
        return 0.0 if self._one_way is None else self._one_way

    def commanded(self, now: float, cmd: Velocity, measured: Velocity) -> None:
        if not _moving(cmd):
            self._sent = None
        elif self._sent is None and not _moving(measured):
            self._sent = now

    def observed(self, now: float, measured: Velocity, stamp: float | None = None) -> None:
        """An odometry arrived at ``now``; ``stamp``: its own, on this clock's time."""
        if self._sent is None or not _moving(measured):
            return
        sent, self._sent = self._sent, None
        sample = now - sent
        if not 0.0 <= sample <= self._max_delay:
            return
        self.samples += 1
        self._estimate = self._smoothed(self._estimate if self.samples > 1 else None, sample)
        if stamp is not None and 0.0 <= stamp - sent <= self._max_delay:  # may exceed
            # the sample: this clock (the robot's clock messages) may trail the odometry
            self._one_way = self._smoothed(self._one_way, stamp - sent)
        log.debug("command-to-odometry delay %.3f s (estimate %.3f s)", sample, self._estimate)

    def _smoothed(self, estimate: float | None, sample: float) -> float:
        return sample if estimate is None else estimate + self._weight * (sample - estimate)
