"""What a ``bus.latest`` reader costs a process per message received, this tree against a
baseline checkout (interleaved).

Run: ``.venv/bin/python -m bench.transport.latest_cost --base /tmp/base --rate 500``

A router and, in this process, odometry published at ``--rate`` Hz (the robot's is
50). For each round, each code (``--base``: a ``git archive`` of another commit, its
children run with ``PYTHONPATH`` on it; ``this``: this tree; the order alternates by
round) and each case, a child process opens a bus and runs a 20 Hz loop on the wall
clock (as a control loop) with:

- ``none``: nothing subscribed (the process's own cost);
- ``latest``: ``bus.latest("odom")``, ``get()`` each cycle (a navigator's or a
  planner's pose);
- ``latest32``: ``bus.latest("odom", keep=32)``, each cycle every message new since
  the last read decoded through ``newest_first()`` (the collision monitor's odometry);
- ``subscribe``: ``bus.subscribe("odom")`` with a callback doing nothing (a reader of
  every message: the controller's tracker), for comparison.

The child's CPU (all its threads, ``/proc``) over ``--seconds`` after a 3 s warm-up, in
% of one core, and per message received above ``none`` (us). Prints one markdown table
(median and range over the rounds) and the load average before and after.
"""

from __future__ import annotations

import argparse
import asyncio
import math
import os
import statistics
import sys
import time
from pathlib import Path

from aiobt.msgs import Odometry
from aiobt.testing.bus import running_router, spawn_service
from aiobt.transport import Bus, BusSettings, open_bus

from ..nav.run import loadavg
from ..system.procstat import cpu_seconds

CASES = ("none", "latest", "latest32", "subscribe")
NS = "latestcost"
PERIOD = 0.05  # wall s: the reader's loop
WARM = 3.0  # wall s before measuring


async def reader(bus: Bus, case: str) -> None:
    """One case's process: the loop and its reading, until SIGTERM."""
    keep = 32 if case == "latest32" else 1
    odom = bus.latest("odom", Odometry, keep=keep) if case.startswith("latest") else None
    if case == "subscribe":
        bus.subscribe("odom", Odometry, lambda _msg: None)
    print("ready", flush=True)
    seen = -math.inf
    deadline = time.monotonic()
    while True:
        if odom is not None and keep == 1:
            odom.get()
        elif odom is not None:
            newest = seen
            for msg in odom.newest_first():  # the new ones only, as the monitor reads
                if msg.header.stamp <= seen:
                    break
                newest = max(newest, msg.header.stamp)
            seen = newest
        deadline += PERIOD
        await asyncio.sleep(max(0.0, deadline - time.monotonic()))


async def publish(bus: Bus, rate: float) -> None:
    """Odometry at ``rate`` Hz, stamped with its count (as many as are due each wake-up)."""
    odom = bus.publisher("odom", Odometry)
    start, sent = time.monotonic(), 0
    while True:
        due = int((time.monotonic() - start) * rate)
        while sent < due:
            sent += 1
            odom.put(Odometry.model_validate({"header": {"stamp": sent / rate}}))
        await asyncio.sleep(max(0.0, start + (sent + 1) / rate - time.monotonic()))


def measure(case: str, endpoint: str, seconds: float, pythonpath: str | None) -> float:
    env = {"PYTHONPATH": pythonpath} if pythonpath else None
    proc = spawn_service(
        ["-m", "bench.transport.latest_cost", "--child", case, "--connect", endpoint], env
    )
    try:
        if not proc.wait_for_output("ready", 30.0):
            raise RuntimeError(f"{case}: the child did not start:\n{proc.output()}")
        time.sleep(WARM)
        before = cpu_seconds(proc.pid)
        time.sleep(seconds)
        return 100.0 * (cpu_seconds(proc.pid) - before) / seconds
    finally:
        proc.cleanup()


async def run(args: argparse.Namespace, paths: dict[str, str | None]) -> None:
    load = loadavg()
    figures: dict[tuple[str, str], list[float]] = {}
    with running_router() as (_, endpoint):
        settings = BusSettings(mode="client", connect=(endpoint,), namespace=NS)
        async with open_bus(settings) as bus:
            sender = asyncio.create_task(publish(bus, args.rate))
            for round_ in range(args.rounds):
                order = list(paths) if round_ % 2 == 0 else list(reversed(paths))
                for code in order:
                    for case in CASES:
                        cpu = await asyncio.to_thread(
                            measure, case, endpoint, args.seconds, paths[code]
                        )
                        figures.setdefault((code, case), []).append(cpu)
            sender.cancel()
    print(f"load average before {load}, after {loadavg()}; {args.rounds} round(s) of "
          f"{args.seconds:.0f} s, odometry at {args.rate:g} Hz\n")  # fmt: skip
    print("| code | case | CPU % of a core, median (range) | us per message above none |")
    print("|---|---|---|---|")
    for (code, case), values in figures.items():
        none = statistics.median(figures[(code, "none")])
        per = (statistics.median(values) - none) * 1e4 / args.rate
        print(
            f"| {code} | {case} | {statistics.median(values):.2f} "
            f"({min(values):.2f}-{max(values):.2f}) | {per:.0f} |"
        )


def base_path(base: Path) -> str:
    services = base / "services"
    if not (base / "src" / "aiobt").is_dir() or not (services / "aiobt_services").is_dir():
        raise SystemExit(f"--base {base}: no src/aiobt there (a git archive of a commit?)")
    return f"{base / 'src'}:{services}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=Path, help="baseline checkout (without: this tree only)")
    parser.add_argument("--rate", type=float, default=500.0, help="odometry Hz")
    parser.add_argument("--seconds", type=float, default=15.0)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--child", choices=CASES)
    parser.add_argument("--connect", default="")
    args = parser.parse_args()
    if args.child:
        settings = BusSettings(mode="client", connect=(args.connect,), namespace=NS)
        asyncio.run(child_main(settings, args.child))
        return 0
    paths: dict[str, str | None] = {"this": None}
    if args.base is not None:
        paths = {"base": base_path(args.base.resolve()), "this": None}
    asyncio.run(run(args, paths))
    return 0


async def child_main(settings: BusSettings, case: str) -> None:
    async with open_bus(settings) as bus:
        await reader(bus, case)


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    sys.exit(main())
