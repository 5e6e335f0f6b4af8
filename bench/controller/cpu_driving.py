"""The controller service's CPU idle and while driving at a sim speed-up, this tree
against a baseline checkout (alternating).

Run: ``.venv/bin/python -m bench.controller.cpu_driving --base /tmp/base --rounds 3``

A router and the robot (small world, ``--speed``, its pose the truth's: no
localization) from this tree, up for the whole run. Then, ``--rounds`` times, for
each code in turn (``--base``: a ``git archive`` of another commit, run with
``PYTHONPATH`` on it; ``this``: this tree; the order alternates by round), the
controller on sim time (``--sim-time``, as the stack runs it): its CPU (``/proc``, all
threads) over ``--idle`` wall s standing (from 3 s after it is up), then over
``--goals`` FollowPath legs of 1.5 m there and back (from the first goal sent to the
last result), in % of one core; and
its own per-goal log lines (``rate R of 20 Hz``, ``slots lost``): the achieved rate's
median and lowest over the goals, and the slots lost summed. Prints one markdown table
and the load average before and after each run.
"""

from __future__ import annotations

import argparse
import asyncio
import re
import statistics
import time
import uuid
from collections.abc import Awaitable, Callable
from pathlib import Path

from aiobt.testing.bus import ServiceProcess, running_router, spawn_service
from aiobt.transport import BusSettings, open_bus

from ..nav.run import loadavg
from ..system.procstat import cpu_seconds
from ..transport.latest_cost import base_path
from .local_view import TRUTH, run_goals

SETTLE = 3.0  # wall s after the controller is up before its idle is measured
RATE = re.compile(r"rate ([\d.]+|nan) of [\d.]+ Hz.*?slots lost (\d+)")


async def one_run(args: argparse.Namespace, endpoint: str, namespace: str, path: str | None) -> str:
    """One controller's run: the table's row (without its code)."""
    load = loadavg()
    common = ["--connect", endpoint, "--namespace", namespace]
    env = {"PYTHONPATH": path} if path else None
    controller = spawn_service(["-m", "aiobt_services.controller", "--sim-time", *common], env)
    try:
        settings = BusSettings(mode="client", connect=(endpoint,), namespace=namespace)
        async with open_bus(settings) as bus:
            if not await asyncio.to_thread(controller.wait_for_output, "controller up", 60.0):
                raise RuntimeError(f"the controller did not come up:\n{controller.output()}")
            await asyncio.sleep(SETTLE)
            idle = await cpu_over(controller, lambda: asyncio.sleep(args.idle))
            driving = await cpu_over(controller, lambda: run_goals(bus, args.goals))
        controller.stop(10.0)
        found = RATE.findall(controller.output())
    finally:
        controller.cleanup()
    rates = [float(r) for r, _ in found]
    lost = sum(int(n) for _, n in found)
    return (
        f"{load} | {idle:.2f} | {driving:.2f} | {len(found)} | "
        f"{statistics.median(rates):.2f} ({min(rates):.2f}) | {lost}"
    )


async def cpu_over(proc: ServiceProcess, phase: Callable[[], Awaitable[object]]) -> float:
    """``proc``'s CPU, % of one core, over awaiting ``phase()``."""
    before, start = cpu_seconds(proc.pid), time.monotonic()
    await phase()
    return 100.0 * (cpu_seconds(proc.pid) - before) / (time.monotonic() - start)


async def run(args: argparse.Namespace, paths: dict[str, str | None]) -> None:
    namespace = f"cpu{uuid.uuid4().hex[:8]}"
    rows: list[str] = []
    with running_router() as (_, endpoint):
        common = ["--connect", endpoint, "--namespace", namespace]
        robot = spawn_service(
            ["-m", "aiobt_services.robot", "--world", "small", "--speed", str(args.speed),
             *TRUTH, *common]
        )  # fmt: skip
        try:
            if not robot.wait_for_output("robot up", 60.0):
                raise RuntimeError(f"the robot did not come up:\n{robot.output()}")
            for round_ in range(args.rounds):
                order = list(paths) if round_ % 2 == 0 else list(reversed(paths))
                for code in order:
                    row = await one_run(args, endpoint, namespace, paths[code])
                    rows.append(f"| {round_ + 1} | {code} | {row} |")
                    print(rows[-1], flush=True)
        finally:
            robot.cleanup()
    print(f"\nspeed-up {args.speed:g}, {args.goals} legs of 1.5 m a run, idle {args.idle:g} s\n")
    print("| round | code | load before | CPU idle % | CPU driving % | goals | "
          "rate Hz median (lowest) | slots lost |")  # fmt: skip
    print("|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=Path, help="baseline checkout (without: this tree only)")
    parser.add_argument("--speed", type=float, default=1.0)
    parser.add_argument("--goals", type=int, default=4)
    parser.add_argument("--idle", type=float, default=5.0)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    paths: dict[str, str | None] = {"this": None}
    if args.base is not None:
        paths = {"base": base_path(args.base.resolve()), "this": None}
    asyncio.run(run(args, paths))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
