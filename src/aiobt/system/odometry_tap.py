"""The odometry a component's clock follows, handed on to the component.

On sim time a component may take its time from the stamps of the robot's odometry
(:func:`aiobt.system.service.make_clock`: the collision monitor, alone in its
process). If it keeps the odometry as well (the monitor's ``base_shift_correction``
history), a second subscription to the same 50 Hz stream would cost another Zenoh
callback per message (bench/history/safety.md). An :class:`OdometryTap` given with
the component instead receives each message the clock's follower decoded, on
Zenoh's thread (a deque append: no loop wake-up), and the component takes them in
its loop. ``tapped`` says, before the component starts, whether the clock feeds
it; if not (the wall clock, or the process's clock from ``{ns}/clock``), the
component subscribes to its odometry itself.
"""

from __future__ import annotations

from collections import deque

from aiobt.msgs import Odometry


class OdometryTap:
    """The last ``keep`` odometry messages the clock followed and nobody took yet."""

    __slots__ = ("_messages", "tapped")

    def __init__(self, keep: int) -> None:
        if keep < 1:
            raise ValueError(f"OdometryTap keep must be >= 1 message, got {keep!r}")
        self._messages: deque[Odometry] = deque(maxlen=keep)
        self.tapped = False  # set by make_clock when its follower feeds this tap

    def put(self, message: Odometry) -> None:
        """Any thread: one more message (the oldest untaken one dropped beyond ``keep``)."""
        self._messages.append(message)  # atomic under the GIL

    def take(self) -> list[Odometry]:
        """In the loop: the messages come since the last call, oldest first."""
        taken: list[Odometry] = []
        while True:
            try:
                taken.append(self._messages.popleft())
            except IndexError:
                return taken
