"""The simulation's truth as the following tests measure it: the robot's and the
followed box's poses per stamp (``{ns}/sim/pose``, ``{ns}/sim/target``), the bumper,
the goal's feedback, and waits for a sim time."""

from __future__ import annotations

import asyncio
import math
from dataclasses import dataclass, field

from aiobt.msgs import PoseStamped
from aiobt.msgs.sim import BumperEvent
from aiobt.transport import Bus
from aiobt.transport.keys import SIM_POSE, sim_topic


@dataclass
class Watch:
    """The truth per stamp, the bumper, the goal's feedback; an event at a sim time."""

    robot: dict[float, PoseStamped] = field(default_factory=dict)
    box: dict[float, PoseStamped] = field(default_factory=dict)
    bumps: list[BumperEvent] = field(default_factory=list)
    states: list[tuple[float, int]] = field(default_factory=list)
    now: float = 0.0
    waiting: list[tuple[float, asyncio.Event]] = field(default_factory=list)

    def on_box(self, msg: PoseStamped) -> None:
        self.box[msg.header.stamp] = msg
        self.now = msg.header.stamp
        for at, event in self.waiting:
            if self.now >= at:
                event.set()

    async def until(self, sim_time: float, wall: float) -> None:
        event = asyncio.Event()
        self.waiting.append((sim_time, event))
        if self.now >= sim_time:
            event.set()
        async with asyncio.timeout(wall):
            await event.wait()

    def distances(self, t0: float, t1: float) -> list[tuple[float, float]]:
        pairs = [(t, b, self.robot.get(t)) for t, b in sorted(self.box.items()) if t0 <= t <= t1]
        return [(t, math.hypot(b.x - r.x, b.y - r.y)) for t, b, r in pairs if r is not None]

    @classmethod
    def on(cls, bus: Bus) -> Watch:
        watch = cls()
        bus.subscribe(SIM_POSE, PoseStamped, lambda m: watch.robot.__setitem__(m.header.stamp, m))
        bus.subscribe(sim_topic("target"), PoseStamped, watch.on_box)
        bus.subscribe("bumper", BumperEvent, watch.bumps.append)
        return watch

    def inside(self, t0: float, t1: float, desired: float, band: float) -> float:
        """The share of samples from ``t0`` to ``t1`` within ``band`` of ``desired``."""
        run = self.distances(t0, t1)
        return sum(abs(d - desired) <= band for _, d in run) / max(1, len(run))
