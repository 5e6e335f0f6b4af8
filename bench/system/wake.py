"""What the first request after idle costs, now that idle services do not listen.

Run: ``.venv/bin/python -m bench.system.wake --speed 10 --rounds 5``

Starts the stack as :mod:`bench.system.report` does and, ``--rounds`` times: waits
``--gap`` wall s (long enough for the services to let the robot's streams and the
clock go), then times a request "cold" and the same request again at once "warm":
a planner ComputePathToPose from the robot's pose (``use_start`` false: the planner
needs its pose and scan) and a behaviors ``wait`` of 0.05 robot s (the goal starts
on fresh robot time with a fresh pose). Prints the wall ms of each (median, max)
and the load average before and after. Run on another checkout (``PYTHONPATH``)
for the figures of services that always listen.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import time
from collections.abc import Awaitable, Callable

from aiobt.msgs import ComputePathToPose, PoseStamped, Wait
from aiobt.testing.bus import exit_on_sigterm, start_router
from aiobt.testing.stack import NavStack, StackConfig
from aiobt.transport import Bus, open_bus

from ..nav.run import loadavg

Request = Callable[[], Awaitable[int]]


def requests(bus: Bus) -> dict[str, Request]:
    planner = bus.action_client(ComputePathToPose.name, ComputePathToPose)
    behaviors = bus.action_client(Wait.name, Wait)

    async def plan() -> int:
        goal = ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(9.0, 9.75, 0.0))
        sent = await planner.send_goal(goal, server_timeout=10.0)
        return (await sent.result(timeout=30.0)).error_code

    async def wait() -> int:
        sent = await behaviors.send_goal(Wait.Goal(time=0.05), server_timeout=10.0)
        return (await sent.result(timeout=30.0)).error_code

    return {"planner compute_path_to_pose": plan, "behaviors wait 0.05 robot s": wait}


async def timed(request: Request, errors: list[int]) -> float:
    began = time.monotonic()
    code = await request()
    if code != 0:
        errors.append(code)
    return (time.monotonic() - began) * 1e3


async def measure(stack: NavStack, rounds: int, gap: float) -> dict[str, list[list[float]]]:
    async with open_bus(stack.settings()) as bus:
        await stack.wait_ready(bus, timeout=120.0)
        calls = requests(bus)
        figures: dict[str, list[list[float]]] = {name: [[], []] for name in calls}
        errors: list[int] = []
        for _ in range(rounds):
            for name, call in calls.items():
                await asyncio.sleep(gap)  # idle: the measured condition, not a wait for an event
                figures[name][0].append(await timed(call, errors))
                figures[name][1].append(await timed(call, errors))
        if errors:
            print(f"requests that failed (error codes): {errors}")
        return figures


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--speed", type=float, default=10.0, help="sim speed-up (robot --speed)")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--gap", type=float, default=2.5, help="idle wall s before each cold one")
    exit_on_sigterm()
    args = parser.parse_args(argv)
    before = loadavg()
    config = StackConfig(world="office", speed=args.speed)
    router, endpoint = start_router(extra_args=("--lease-ms", str(config.lease_ms)), timeout=60.0)
    try:
        with NavStack.launch(endpoint, config) as stack:
            figures = asyncio.run(measure(stack, args.rounds, args.gap))
    finally:
        router.cleanup()
    print("| request, wall ms | cold (after idle) median / max | warm median / max |")
    print("|---|---|---|")
    for name, (cold, warm) in figures.items():
        cells = [f"{statistics.median(v):.1f} / {max(v):.1f}" for v in (cold, warm)]
        print(f"| {name} | {cells[0]} | {cells[1]} |")
    print(f"\nload average before: {before}; after: {loadavg()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
