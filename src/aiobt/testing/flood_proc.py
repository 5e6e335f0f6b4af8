"""A flooding client (flood tests, bench.transport.flood): one message at a fixed rate.

python -m aiobt.testing.flood_proc --connect EP --namespace NS \\
    --topic initialpose --model PoseStamped --json '{"x": 0, "y": 0, "yaw": 0}' \\
    --rate 10000 --seconds 4

Waits for a subscriber, prints ``flooding``, publishes ``rate`` messages per
second of wall time (in bursts every 5 ms) for ``seconds``, prints ``sent N``.
"""

from __future__ import annotations

import argparse
import asyncio
import sys
import time

from aiobt import msgs
from aiobt.transport import BusSettings, add_bus_arguments, open_bus

BURST_PERIOD = 0.005  # s of wall time between bursts


async def flood(args: argparse.Namespace) -> int:
    model = getattr(msgs, args.model)
    message = model.from_json(args.json)
    async with open_bus(BusSettings.from_args(args)) as bus:
        pub = bus.publisher(args.topic, model)
        if not await pub.wait_for_subscribers(10.0):
            print(f"no subscriber on {args.topic}", flush=True)
            return 1
        print("flooding", flush=True)
        start, sent = time.monotonic(), 0
        while (elapsed := time.monotonic() - start) < args.seconds:
            due = int(elapsed * args.rate)
            for _ in range(due - sent):
                pub.put(message)
            sent = max(sent, due)
            await asyncio.sleep(BURST_PERIOD)
        print(f"sent {sent}", flush=True)
    return 0


def main() -> int:
    parser = argparse.ArgumentParser()
    add_bus_arguments(parser)
    parser.add_argument("--topic", required=True)
    parser.add_argument("--model", required=True)
    parser.add_argument("--json", required=True)
    parser.add_argument("--rate", type=float, default=10_000.0)
    parser.add_argument("--seconds", type=float, default=4.0)
    return asyncio.run(flood(parser.parse_args()))


if __name__ == "__main__":
    sys.exit(main())
