"""Follow the simulation's time: ``{ns}/clock`` drives a :class:`ManualClock`."""

from __future__ import annotations

from typing import TYPE_CHECKING

from aiobt.core.clock import ManualClock
from aiobt.msgs import Clock as ClockMsg

if TYPE_CHECKING:
    from aiobt.transport.bus import Bus
    from aiobt.transport.topics import Subscription


class SimClockFollower:
    """Sets ``clock`` to every time stamp published on ``{ns}/clock``.

    Sleepers on the clock wake as sim time passes; time never runs backwards
    (a restarted simulation's earlier stamps are ignored until they catch up).
    """

    def __init__(self, bus: Bus, clock: ManualClock | None = None, topic: str = "clock") -> None:
        self.clock = clock or ManualClock()
        self._sub: Subscription[ClockMsg] = bus.subscribe(topic, ClockMsg, self._on_clock)

    def _on_clock(self, message: ClockMsg) -> None:
        self.clock.set(message.clock)

    @property
    def started(self) -> bool:
        """Whether any sim time arrived yet."""
        return self._sub.latest is not None

    async def wait_started(self, timeout: float | None = None) -> float:  # noqa: ASYNC109
        """Wait for the first time stamp; returns it."""
        return (await self._sub.wait_latest(timeout)).clock

    def close(self) -> None:
        self._sub.close()
