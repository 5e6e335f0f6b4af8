"""One-way pub->sub latency: aiobt typed topics against raw Zenoh, between two processes.

    .venv/bin/python -m bench.transport.oneway [--count 8000]

``bench.transport.stamped_peer`` publishes PoseStamped messages stamped with
``time.monotonic()`` (shared by processes on one machine) at 500 Hz on four
streams, round robin: typed publisher -> typed subscription, typed -> raw,
raw -> raw, raw -> typed (``--rotate``: a new order every cycle).
This process measures arrival in its event loop
(raw subscribers hop into the loop like any asyncio program; arrival is taken
before the payload is parsed) and, for reference, arrival in the raw
subscriber's Zenoh thread and after the raw subscriber's ``json.loads``.
Ratios are against raw -> raw. ``--repeat K`` runs K times and summarises the
ratios (median, range, how many runs met the issue's 1.2x target).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import time

import zenoh

from aiobt.msgs import PoseStamped
from aiobt.testing.bus import exit_on_sigterm, running_router, spawn_service
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt.transport.bridge import callback
from bench.transport.summary import load, summarize

NS = "oneway"


def listen(bus: Bus) -> dict[str, list[float]]:
    latency: dict[str, list[float]] = {
        name: []
        for name in (
            "raw_raw",
            "raw_raw (Zenoh thread)",
            "raw_raw + json.loads (reference)",
            "typed_raw",
            "raw_typed",
            "typed_typed",
        )
    }
    loop = asyncio.get_running_loop()

    def typed(name: str) -> None:
        def on_pose(pose: PoseStamped) -> None:
            latency[name].append(time.monotonic() - pose.header.stamp)

        bus.subscribe(name, PoseStamped, on_pose)

    def in_loop(name: str, payload: bytes, in_thread: float) -> None:
        now = time.monotonic()
        stamp = json.loads(payload)["header"]["stamp"]
        latency[name].append(now - stamp)
        if name == "raw_raw":
            latency["raw_raw (Zenoh thread)"].append(in_thread - stamp)
            # a raw subscriber that reads the message at all parses it: the same sample,
            # stamped after the parse (the ratio's baseline stays raw_raw)
            latency["raw_raw + json.loads (reference)"].append(time.monotonic() - stamp)

    def raw(name: str) -> None:
        def on_sample(sample: zenoh.Sample) -> None:
            in_thread = time.monotonic()
            loop.call_soon_threadsafe(in_loop, name, sample.payload.to_bytes(), in_thread)

        bus.session.declare_subscriber(f"{NS}/{name}", callback(on_sample))

    typed("typed_typed")
    typed("raw_typed")
    raw("raw_raw")
    raw("typed_raw")
    return latency


async def run(endpoint: str, count: int, rotate: bool = False) -> dict[str, list[float]]:
    """One run: the latencies of every stream."""
    settings = BusSettings(connect=(endpoint,), namespace=NS, connect_timeout=10.0)
    async with open_bus(settings) as bus:
        latency = listen(bus)
        peer = spawn_service(
            [
                "-m",
                "bench.transport.stamped_peer",
                "--connect",
                endpoint,
                "-n",
                NS,
                "--count",
                str(count),
                *(["--rotate"] if rotate else []),
            ]
        )
        try:
            await asyncio.to_thread(peer.popen.wait, 120)
        finally:
            peer.cleanup()
        await asyncio.sleep(0.2)
    return latency


def report(latency: dict[str, list[float]]) -> str:
    base = statistics.median(latency["raw_raw"])
    lines = [
        "| publisher -> subscriber | n | median µs | p90 µs | vs raw -> raw |",
        "|---|---|---|---|---|",
    ]
    for name, values in latency.items():
        med = statistics.median(values)
        p90 = statistics.quantiles(values, n=10)[-1]
        lines.append(
            f"| {name} | {len(values)} | {med * 1e6:.0f} | {p90 * 1e6:.0f} | {med / base:.2f}x |"
        )
    return "\n".join(lines)


def ratios(latency: dict[str, list[float]]) -> dict[str, float]:
    base = statistics.median(latency["raw_raw"])
    return {
        name: statistics.median(latency[name]) / base
        for name in ("raw_typed", "typed_typed", "raw_raw + json.loads (reference)")
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=8000, help="messages, all streams")
    parser.add_argument(
        "--rotate",
        action="store_true",
        help="shuffle the round-robin order every cycle (no stream always follows the same)",
    )
    parser.add_argument(
        "--repeat", type=int, default=1, help="measure this many times (a new peer each run)"
    )
    exit_on_sigterm()
    args = parser.parse_args()
    with running_router() as (_, endpoint):
        first = asyncio.run(run(endpoint, args.count, args.rotate))
        print(report(first))
        if args.repeat > 1:
            runs = {name: [value] for name, value in ratios(first).items()}
            loads = [load()]
            for _ in range(args.repeat - 1):
                again = ratios(asyncio.run(run(endpoint, args.count, args.rotate)))
                for name, value in again.items():
                    runs[name].append(value)
                loads.append(load())
            print(f"\n{summarize(runs, {'raw_typed': 1.2, 'typed_typed': 1.2}, loads)}")


if __name__ == "__main__":
    main()
