"""A service measured unflooded and then flooded at 10,000 messages/s from another process.

Shared by the flood tests (``tests/integration/floods``), which assert generous
bounds, and ``bench.transport.flood``, which reports the ratios. The service is
called back to back for the length of each phase while its sim clock (if it
has one) and its resident memory are watched; the flood comes from
``python -m aiobt.testing.flood_proc``, a separate process on the same router.
"""

from __future__ import annotations

import asyncio
import statistics
import time
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from aiobt.msgs import Clock
    from aiobt.testing.bus import ServiceProcess
    from aiobt.transport import BusSettings, Subscription

Spawn = Callable[[Sequence[str]], "ServiceProcess"]
Call = Callable[[], Awaitable[object]]
FLOOD_RATE = 10_000  # messages per second
FLOOD_SECONDS = 5.0
MIB = 1024 * 1024


def rss_bytes(pid: int) -> int:
    """Resident memory of process ``pid`` (from /proc)."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) * 1024
    raise RuntimeError(f"no VmRSS for process {pid}")


@dataclass(frozen=True)
class Figures:
    """One phase of a service's life: its sim speed-up, its replies and its memory."""

    speed: float  # sim seconds per wall second (0 if no clock was watched)
    reply_median: float  # s, of the service called
    reply_max: float
    rss_growth: int  # bytes, from the start of the phase to its largest sample
    replies: int


@dataclass(frozen=True)
class Flood:
    """What floods: a topic under the namespace, its message model's name, a JSON payload."""

    topic: str
    model: str
    payload: str


async def measure(
    call: Call, clock: Subscription[Clock] | None, pid: int, seconds: float,
    running: Callable[[], bool],
) -> Figures:  # fmt: skip
    """Call a service back to back for ``seconds`` (or while ``running()``), watching the
    sim clock (if given) and process ``pid``'s RSS."""
    rss0 = peak = rss_bytes(pid)
    sim0 = (await clock.wait_latest(5.0)).clock if clock is not None else 0.0
    wall0 = time.monotonic()
    replies: list[float] = []
    while time.monotonic() - wall0 < seconds and running():
        sent = time.monotonic()
        await call()
        replies.append(time.monotonic() - sent)
        peak = max(peak, rss_bytes(pid))
    speed = 0.0
    if clock is not None and clock.latest is not None:
        speed = (clock.latest.clock - sim0) / (time.monotonic() - wall0)
    return Figures(speed, statistics.median(replies), max(replies), peak - rss0, len(replies))


async def flood_and_measure(
    spawn: Spawn, settings: BusSettings, flood: Flood, call: Call,
    clock: Subscription[Clock] | None, pid: int, seconds: float = FLOOD_SECONDS,
) -> tuple[Figures, Figures, int]:  # fmt: skip
    """Figures of process ``pid`` unflooded, then flooded; and the messages sent."""
    await measure(call, clock, pid, 1.0, lambda: True)  # warm up
    calm = await measure(call, clock, pid, seconds, lambda: True)
    flooder = spawn(
        [
            "-m", "aiobt.testing.flood_proc",
            "--connect", settings.connect[0], "--namespace", settings.namespace,
            "--topic", flood.topic, "--model", flood.model, "--json", flood.payload,
            "--rate", str(FLOOD_RATE), "--seconds", str(seconds),
        ]
    )  # fmt: skip
    if not await asyncio.to_thread(flooder.wait_for_output, "flooding", 30.0):
        raise RuntimeError(f"the flooder did not start:\n{flooder.output()}")
    flooded = await measure(call, clock, pid, seconds, lambda: "sent" not in flooder.output())
    if not await asyncio.to_thread(flooder.wait_for_output, "sent", 30.0):
        raise RuntimeError(f"the flooder did not finish:\n{flooder.output()}")
    sent = int(flooder.output().split("sent")[-1].split()[0])
    return calm, flooded, sent
