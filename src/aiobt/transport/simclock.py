"""Follow the simulation's time: ``{ns}/clock`` drives a :class:`ManualClock`.

Each stamp is decoded on Zenoh's thread and handed to a :class:`SimTime`, which
wakes the event loop only when a sleeper is due: a service that sleeps one control
period at a time (or idles) no longer pays a loop wake-up for each of the 250
stamps a second the simulation sends at a speed-up of 10. A plain
:class:`ManualClock` passed in is set in the loop at every stamp, as before.
With ``on_demand`` the subscription is held only while the :class:`SimTime` is
(a sleeper, a goal: see :mod:`aiobt.transport.simtime`).

Any stamped message of the robot can carry its time instead (``model`` and
``stamp_of``): a service that receives the robot's odometry anyway follows its
stamps rather than subscribing to the clock as well.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from pydantic import ValidationError

from aiobt.core.clock import ManualClock
from aiobt.msgs import Clock as ClockMsg
from aiobt.msgs import MessageError, Msg, wire_validator
from aiobt.transport import _z
from aiobt.transport.bridge import callback
from aiobt.transport.simtime import SimTime

if TYPE_CHECKING:
    import zenoh

    from aiobt.transport.bus import Bus

log = logging.getLogger("aiobt.transport.simclock")


class SimClockFollower:
    """Sets ``clock`` to the time stamps published on ``{ns}/clock``.

    Sleepers on the clock wake as sim time passes; time never runs backwards
    (a restarted simulation's earlier stamps are ignored until they catch up).
    A malformed stamp is dropped and logged (the first one as a warning).
    ``on_demand`` (with a :class:`SimTime`): subscribed only while the clock is held.
    ``model`` and ``stamp_of``: the stamps come as ``stamp_of(message)`` of another
    message on ``topic`` (default: the clock's own).
    """

    def __init__(
        self,
        bus: Bus,
        clock: ManualClock | None = None,
        topic: str = "clock",
        *,
        on_demand: bool = False,
        model: type[Msg] = ClockMsg,
        stamp_of: Callable[[Any], float] = lambda msg: float(msg.clock),
    ) -> None:
        self.clock = clock if clock is not None else SimTime()
        self._sim_time = self.clock if isinstance(self.clock, SimTime) else None
        self._key = bus.keys.topic(topic)
        self._session = bus.session
        self._bridge = bus.bridge
        self._model = model
        self._validate = wire_validator(model)
        self._stamp_of = stamp_of
        self._latest: float | None = None
        self._wake_due = False
        self._first = asyncio.Event()
        self.dropped_invalid = 0
        self.attaches = 0  # subscriptions declared so far
        self._closed = False
        self._sub: zenoh.Subscriber[None] | None = None
        self.attach()
        if on_demand and self._sim_time is not None:
            self._sim_time.bind(self)

    def attach(self) -> None:
        """Subscribe to the stamps (nothing once closed or already subscribed)."""
        if self._closed or self._sub is not None:
            return
        self.attaches += 1
        awaiting = [True]  # this subscription's own: a late stamp of the last one is not it

        def on_sample(sample: zenoh.Sample) -> None:
            self._on_sample(sample, awaiting)

        self._sub = self._session.declare_subscriber(self._key, callback(on_sample))

    def detach(self) -> None:
        """Stop receiving stamps until :meth:`attach`."""
        if self._sub is not None:
            _z.undeclare(self._sub)
            self._sub = None

    @property
    def attached(self) -> bool:
        return self._sub is not None

    def _on_sample(self, sample: zenoh.Sample, awaiting: list[bool]) -> None:
        """Zenoh thread: decode the stamp; wake the loop only when it has work (a
        sleeper due, or the subscription's first valid stamp: ``awaiting``)."""
        payload = sample.payload.to_bytes()
        try:
            if len(payload) > self._bridge.max_payload:
                raise ValueError(f"{self._key}: payload of {len(payload)} bytes")
            stamp = self._stamp_of(self._validate(payload))
        except (ValidationError, ValueError) as exc:
            self._bridge.call(self._reject, exc)
            return
        self._latest = stamp
        first, awaiting[0] = awaiting[0], False
        due = self._sim_time.receive(stamp) if self._sim_time is not None else True
        if (due or first) and not self._wake_due:
            self._wake_due = True
            self._bridge.call(self._advance)

    def _advance(self) -> None:
        """In the loop: bring the clock to the newest stamp, waking the sleepers due."""
        self._wake_due = False  # before reading: a stamp from now on wakes again
        if self._sim_time is not None:
            self._sim_time.arrived()  # catches up; the first stamp since attaching is fresh
        elif self._latest is not None:
            self.clock.set(self._latest)
        self._first.set()

    def _reject(self, exc: Exception) -> None:
        self.dropped_invalid += 1
        detail = (
            MessageError.from_validation(self._model, exc, self._key)
            if isinstance(exc, ValidationError)
            else exc
        )
        level = logging.WARNING if self.dropped_invalid == 1 else logging.DEBUG
        log.log(level, "dropped bad clock message (the first is a warning): %s", detail)

    @property
    def started(self) -> bool:
        """Whether any sim time arrived yet."""
        return self._first.is_set()

    async def wait_started(self, timeout: float | None = None) -> float:  # noqa: ASYNC109
        """Wait for the first time stamp; returns the clock's time then."""
        # held while waiting: stays subscribed on demand
        if self._sim_time is not None and not await self._sim_time.wait_fresh(timeout):
            raise TimeoutError(f"no stamp on {self._key} within {timeout} s")
        async with asyncio.timeout(timeout):
            await self._first.wait()
        return self.clock.now()

    def close(self) -> None:
        self._closed = True
        if self._sim_time is not None:
            self._sim_time.unbind()
        self.detach()
