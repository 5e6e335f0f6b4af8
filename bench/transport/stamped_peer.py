"""Publishes time-stamped poses for ``bench.transport.oneway``, typed and raw, round robin.

python -m bench.transport.stamped_peer --connect EP --namespace NS --count N
"""

from __future__ import annotations

import argparse
import asyncio
import random
import sys
import time

from aiobt.msgs import PoseStamped
from aiobt.transport import BusSettings, add_bus_arguments, open_bus


async def publish(settings: BusSettings, count: int, period: float, rotate: bool) -> None:
    async with open_bus(settings) as bus:
        typed = {name: bus.publisher(name, PoseStamped) for name in ("typed_typed", "typed_raw")}
        raw = {
            name: bus.session.declare_publisher(f"{bus.namespace}/{name}")
            for name in ("raw_raw", "raw_typed")
        }
        await asyncio.sleep(1.5)  # let the receiver's subscriptions settle
        pose = PoseStamped.from_xy_yaw(1.0, 2.0, 0.5)
        streams = ["typed_typed", "typed_raw", "raw_raw", "raw_typed"]
        order = random.Random(4)  # fixed seed: the same sequence every run
        for i in range(count):
            if rotate and i % len(streams) == 0:
                # a new order every cycle, so no stream always follows the same one
                # (what the receiver did 2 ms before changes its cache misses)
                order.shuffle(streams)
            name = streams[i % len(streams)]
            pose.header.stamp = time.monotonic()  # CLOCK_MONOTONIC is shared by processes
            if name in typed:
                typed[name].put(pose)
            else:
                raw[name].put(pose.to_json())
            await asyncio.sleep(period)
        for publisher in raw.values():
            publisher.undeclare()  # type: ignore[no-untyped-call]


def main() -> int:
    parser = argparse.ArgumentParser()
    add_bus_arguments(parser)
    parser.add_argument("--count", type=int, default=4000)
    parser.add_argument("--period", type=float, default=0.002)
    parser.add_argument("--rotate", action="store_true", help="shuffle the order every cycle")
    args = parser.parse_args()
    asyncio.run(publish(BusSettings.from_args(args), args.count, args.period, args.rotate))
    return 0


if __name__ == "__main__":
    sys.exit(main())
