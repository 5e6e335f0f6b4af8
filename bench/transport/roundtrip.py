"""Transport benchmark: aiobt action/service/pub-sub against raw Zenoh, same two processes.

    .venv/bin/python -m bench.transport.roundtrip [--n 2000]

Starts a router process and a peer process (``bench.transport.peer``), then from
this process measures, interleaved in rounds so drift hits both alike:

- raw get/reply: a Zenoh get answered at once by a raw queryable, awaited from
  asyncio through the same callback bridge aiobt uses (and, for reference,
  a blocking get from a plain thread);
- aiobt action: send_goal + result() of a trivial action (no feedback);
- aiobt service: ``bus.call`` of a trivial service;
- raw put -> subscriber, echoed back by a raw subscriber (round trip / 2);
- aiobt typed pub -> sub (PoseStamped), echoed back by a typed subscription.

``--repeat K`` measures K times with the same processes and summarises the ratios
(median, range, how many runs met the issue's 1.5x target).
"""

from __future__ import annotations

import argparse
import asyncio
import os
import statistics
import time
from collections.abc import Awaitable, Callable

import zenoh

from aiobt.msgs import ClearCostmapResponse, ClearEntireCostmap, PoseStamped, Wait
from aiobt.testing.bus import exit_on_sigterm, running_router, spawn_service
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt.transport.bridge import callback
from bench.transport.summary import load, summarize

NS = "bench"
Probe = Callable[[], Awaitable[None]]


async def raw_get_async(bus: Bus, key: str = "raw_get") -> None:
    loop = asyncio.get_running_loop()
    done: asyncio.Future[None] = loop.create_future()

    def on_reply(reply: zenoh.Reply) -> None:
        loop.call_soon_threadsafe(_settle, done)

    bus.session.get(f"{NS}/{key}", callback(on_reply), payload=b"{}")
    await done


def _settle(future: asyncio.Future[None]) -> None:
    if not future.done():
        future.set_result(None)


def make_probes(bus: Bus) -> dict[str, Probe]:
    client = bus.action_client("trivial", Wait)
    goal = Wait.Goal(time=0.0)
    request = ClearEntireCostmap.Request()
    raw_pong: asyncio.Queue[None] = asyncio.Queue()
    loop = asyncio.get_running_loop()

    def on_raw_pong(sample: zenoh.Sample) -> None:
        loop.call_soon_threadsafe(raw_pong.put_nowait, None)

    bus.session.declare_subscriber(f"{NS}/raw_pong", callback(on_raw_pong))
    raw_ping = bus.session.declare_publisher(f"{NS}/raw_ping")
    raw_ping_loop = bus.session.declare_publisher(f"{NS}/raw_ping_loop")
    pong = bus.subscribe("pong", PoseStamped)
    ping = bus.publisher("ping", PoseStamped)
    pose = PoseStamped.from_xy_yaw(1.0, 2.0, 0.5)
    raw_payload = pose.to_json()

    async def action() -> None:
        handle = await client.send_goal(goal, server_timeout=5.0)
        await handle.result()

    async def service() -> None:
        await bus.call("echo", request, ClearCostmapResponse, timeout=5.0)

    async def raw_echo() -> None:
        raw_ping.put(raw_payload)
        await raw_pong.get()

    async def raw_echo_loop() -> None:
        raw_ping_loop.put(raw_payload)
        await raw_pong.get()

    async def typed_echo() -> None:
        ping.put(pose)
        await pong.next()

    return {
        "raw get/reply (asyncio)": lambda: raw_get_async(bus),
        "raw get/reply (asyncio both ends)": lambda: raw_get_async(bus, "raw_get_loop"),
        "aiobt action goal->result": action,
        "aiobt service call": service,
        "raw put->sub echo": raw_echo,
        "raw put->sub echo (asyncio both ends)": raw_echo_loop,
        "aiobt typed pub->sub echo": typed_echo,
    }


def cpu_seconds(pid: int) -> float:
    """User + system CPU time of process ``pid`` (all its threads), from /proc."""
    with open(f"/proc/{pid}/stat") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


class Measured:
    """Round-trip times per probe, and the CPU each side spent on them."""

    def __init__(self, names: list[str]) -> None:
        self.samples: dict[str, list[float]] = {name: [] for name in names}
        self.cpu: dict[str, list[float]] = {name: [0.0, 0.0] for name in names}  # near, far


async def measure(probes: dict[str, Probe], n: int, far_pid: int, rounds: int = 10) -> Measured:
    out = Measured(list(probes))
    for probe in probes.values():  # warm-up
        for _ in range(50):
            await probe()
    for _ in range(rounds):
        for name, probe in probes.items():
            near0, far0 = cpu_seconds(os.getpid()), cpu_seconds(far_pid)
            for _ in range(n // rounds):
                start = time.perf_counter()
                await probe()
                out.samples[name].append(time.perf_counter() - start)
            out.cpu[name][0] += cpu_seconds(os.getpid()) - near0
            out.cpu[name][1] += cpu_seconds(far_pid) - far0
    return out


def blocking_raw_get(session: zenoh.Session, n: int) -> list[float]:
    out = []
    for _ in range(n):
        start = time.perf_counter()
        for _reply in session.get(f"{NS}/raw_get", payload=b"{}"):
            pass
        out.append(time.perf_counter() - start)
    return out


# aiobt probe -> (short name, raw probe's name, raw baselines: far side in Zenoh's thread,
# in asyncio)
BASELINES = {
    "aiobt action goal->result": (
        "action",
        "raw get",
        ("raw get/reply (asyncio)", "raw get/reply (asyncio both ends)"),
    ),
    "aiobt service call": (
        "service",
        "raw get",
        ("raw get/reply (asyncio)", "raw get/reply (asyncio both ends)"),
    ),
    "aiobt typed pub->sub echo": (
        "typed echo",
        "raw echo",
        ("raw put->sub echo", "raw put->sub echo (asyncio both ends)"),
    ),
}
# the targets: action (and service) within 1.5x of the raw get; the echo is two
# one-way trips (bench.transport.oneway measures the pub/sub target), so it has none
TARGETS = {
    "action vs raw get (far side in Zenoh thread)": 1.5,
    "action vs raw get (far side in asyncio)": 1.5,
    "service vs raw get (far side in Zenoh thread)": 1.5,
    "service vs raw get (far side in asyncio)": 1.5,
}


def ratios(measured: Measured) -> dict[str, float]:
    """Each aiobt probe's median over each of its raw baselines' medians."""
    med = {name: statistics.median(values) for name, values in measured.samples.items()}
    out = {}
    for name, (short, raw, bases) in BASELINES.items():
        for base, where in zip(bases, ("Zenoh thread", "asyncio"), strict=True):
            out[f"{short} vs {raw} (far side in {where})"] = med[name] / med[base]
    return out


def report(measured: Measured, blocking: list[float]) -> str:
    samples = measured.samples
    med = {name: statistics.median(values) for name, values in samples.items()}
    lines = [
        "| what | median µs | p90 µs | ratio vs raw (far side in Zenoh thread / in asyncio) "
        "| CPU µs per round trip: this process / far process |",
        "|---|---|---|---|---|",
    ]
    for name, values in samples.items():
        p90 = statistics.quantiles(values, n=10)[-1]
        bases = BASELINES[name][2] if name in BASELINES else ()
        ratio = " / ".join(f"{med[name] / med[b]:.2f}x" for b in bases) or "baseline"
        near, far = (seconds / len(values) * 1e6 for seconds in measured.cpu[name])
        lines.append(
            f"| {name} | {med[name] * 1e6:.0f} | {p90 * 1e6:.0f} | {ratio} "
            f"| {near:.0f} / {far:.0f} |"
        )
    lines.append(
        f"| raw get/reply (blocking, thread) | {statistics.median(blocking) * 1e6:.0f} | "
        f"{statistics.quantiles(blocking, n=10)[-1] * 1e6:.0f} | reference | |"
    )
    return "\n".join(lines)


async def run(n: int, endpoint: str, repeat: int = 1) -> str:
    """The first run's table; with ``repeat`` > 1, every run's ratios and their summary."""
    settings = BusSettings(connect=(endpoint,), namespace=NS, connect_timeout=10.0)
    peer = spawn_service(["-m", "bench.transport.peer", "--connect", endpoint, "-n", NS])
    try:
        async with open_bus(settings) as bus:
            await bus.action_client("trivial", Wait).wait_for_server(10.0)
            await bus.presence(bus.keys.service("echo")).wait(10.0)
            await asyncio.sleep(0.5)
            probes = make_probes(bus)
            await asyncio.sleep(0.5)
            measured = await measure(probes, n, peer.pid)
            blocking = await asyncio.to_thread(blocking_raw_get, bus.session, n)
            table = report(measured, blocking)
            if repeat == 1:
                return table
            runs = {name: [value] for name, value in ratios(measured).items()}
            loads = [load()]
            for _ in range(repeat - 1):
                again = ratios(await measure(probes, n, peer.pid))
                for name, value in again.items():
                    runs[name].append(value)
                loads.append(load())
            return f"{table}\n\n{summarize(runs, TARGETS, loads)}"
    finally:
        peer.cleanup()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=2000, help="round trips per probe")
    parser.add_argument(
        "--repeat", type=int, default=1, help="measure this many times (same processes)"
    )
    exit_on_sigterm()
    args = parser.parse_args()
    with running_router() as (_, endpoint):
        print(asyncio.run(run(args.n, endpoint, args.repeat)))


if __name__ == "__main__":
    main()
