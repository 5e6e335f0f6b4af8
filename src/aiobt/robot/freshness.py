"""When a robot pose is stale: one rule for the controller and the behaviors.

A pose is stale when the *robot* stopped producing fresh poses, not when this
machine delivered them late. Under a sim speed-up, every wall millisecond of
delivery lag is ``speed`` milliseconds of robot time, and the streams do not
lag uniformly: each subscription is drained (and paced) on its own, so the
clock or odometry can run ahead of the pose by tens of wall milliseconds on a
loaded machine, which at 10x is half a second of robot time. Neither the
service's clock at arrival nor the robot's stamps alone tell "late" from
"stopped"; together they do:

- ``robot``: the pose's own stamp against the newest robot time received on
  any robot stream (robot seconds): how far the robot went on without it;
- ``silence``: wall seconds since a pose with a new stamp arrived in this frame;
- ``quiet``: wall seconds since anything new arrived from the robot at all.

The pose is stale when it has not been renewed for ``pose_timeout`` of wall time
(``silence``) and either the robot's own time moved on by more than
``pose_timeout`` meanwhile (``robot``: the pose stream stopped, the others did
not) or the robot went quiet altogether (``quiet``: killed, stopped, paused).
Uniform delivery lag, and a stream running ahead of another, cancel out; at 1x
robot and wall time agree, so ``pose_timeout`` means what it says there.

A stream whose stamps go backwards (a simulation reset) starts over from the
new stamp. Unstamped messages (stamp 0) count as new on every arrival.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass


@dataclass(slots=True, frozen=True)
class PoseAge:
    """How old one frame's newest pose is (see the module's docstring)."""

    robot: float = 0.0  # robot s: newest robot time received minus the pose's stamp
    silence: float = 0.0  # wall s since a pose with a new stamp arrived in this frame
    quiet: float = 0.0  # wall s since anything new arrived from the robot

    def stale(self, frame: str, pose_timeout: float) -> str | None:
        """Why the pose in ``frame`` is stale, or None if it is fresh."""
        if self.silence <= pose_timeout:
            return None
        if self.quiet > pose_timeout:
            return (
                f"robot pose in frame {frame!r} is stale: nothing new from the robot for "
                f"{self.quiet:.2f} s of wall time (pose {self.robot:.2f} s old in robot "
                f"time, pose_timeout {pose_timeout:.2f} s); stopping"
            )
        if self.robot > pose_timeout:
            return (
                f"robot pose in frame {frame!r} is stale ({self.robot:.2f} s old in robot "
                f"time, none newer for {self.silence:.2f} s of wall time, pose_timeout "
                f"{pose_timeout:.2f} s); stopping"
            )
        return None


FRESH = PoseAge()  # a pose just received (and what a state made without an age says)


class Freshness:
    """Stamps and wall arrival times of the robot's streams; :meth:`age` per stream.

    ``received(stream, stamp)`` is called for every message of a robot stream
    (poses per frame, and any other stamped stream such as the lidar, which
    only serve as the robot's time); ``wall`` is a monotonic wall clock.
    """

    __slots__ = ("_arrived", "_stamps", "_wall")

    def __init__(self, wall: Callable[[], float] = time.monotonic) -> None:
        self._wall = wall
        self._stamps: dict[str, float] = {}  # the newest stamp per stream
        self._arrived: dict[str, float] = {}  # wall time a new stamp last arrived

    def received(self, stream: str, stamp: float) -> None:
        if stamp == self._stamps.get(stream) and stamp != 0.0:
            return  # the same pose again: nothing new from the robot
        self._stamps[stream] = stamp  # also backwards: a reset starts the stream over
        self._arrived[stream] = self._wall()

    def clear(self) -> None:
        """Forget every stream (the service stopped listening to the robot)."""
        self._stamps.clear()
        self._arrived.clear()

    def robot_time(self) -> float:
        """The newest robot time received on any stream (0 before the first)."""
        return max(self._stamps.values(), default=0.0)

    def age(self, stream: str) -> PoseAge:
        """The age of ``stream``'s newest message (all zero before the first)."""
        stamp = self._stamps.get(stream)
        if stamp is None:
            return FRESH
        now = self._wall()
        return PoseAge(
            robot=self.robot_time() - stamp,
            silence=now - self._arrived[stream],
            quiet=now - max(self._arrived.values()),
        )
