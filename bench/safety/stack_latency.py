"""What the safety chain adds between the controller and the base with the whole stack
up, and what it costs while the robot drives.

The stack as ``aiobt up`` runs it by default (router; robot in the office world;
planner, controller, behaviors, the velocity smoother, the collision monitor and the
navigator on sim time at ``--speed``) drives seeded goals (:mod:`bench.nav.goals`).
This process takes each command the controller sends on ``{ns}/cmd_vel_nav`` and the
same command's arrival on ``{ns}/cmd_vel`` after both links (the commands the chain
passes unchanged: not a ramp's, not a stop's), both as received here, one hop from
the router each: the difference is what the chain adds, in sim ms. Also the CPU of
the two services while driving (``/proc``). ``--realtime``: the router, the robot,
the controller, the two links and this process under ``SCHED_FIFO`` (each one's
``--realtime-priority`` default; see :mod:`aiobt.system.realtime`).

    .venv/bin/python -m bench.safety.stack_latency --speed 1 --goals 2 [--realtime] [--composed]
"""

from __future__ import annotations

import argparse
import asyncio
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

from aiobt.msgs import PoseStamped, Twist
from aiobt.system.catalog import realtime_priority
from aiobt.system.realtime import raise_priority
from aiobt.testing.bus import exit_on_sigterm, start_router
from aiobt.testing.navwatch import navigate
from aiobt.testing.stack import NavStack, StackConfig
from aiobt.transport import Bus, open_bus
from bench.nav.goals import pick_goals, static_grid
from bench.nav.run import navigator_client

from .chain_latency import LAYOUTS, SERVICES, cpu_seconds

START = (2.0, 9.75)  # the office's start
PERIOD = 0.05  # s of sim time: the controller's 20 Hz
REALTIME = ("robot", "controller", *SERVICES)  # on the command's way to the base
Key = tuple[float, float]


class Matcher:
    """Arrival times (wall) of each command on the way in and out, paired by value."""

    def __init__(self, bus: Bus) -> None:
        self.sent: dict[Key, list[float]] = defaultdict(list)
        self.added: list[float] = []  # wall s from cmd_vel_nav to cmd_vel
        self.outputs = 0
        bus.subscribe("cmd_vel_nav", Twist, self._on_in)
        bus.subscribe("cmd_vel", Twist, self._on_out)

    @staticmethod
    def key(msg: Twist) -> Key:
        return round(msg.linear.x, 9), round(msg.angular.z, 9)

    def _on_in(self, msg: Twist) -> None:
        if self.key(msg) != (0.0, 0.0):
            self.sent[self.key(msg)].append(time.perf_counter())

    def _on_out(self, msg: Twist) -> None:
        self.outputs += 1
        arrivals = self.sent.pop(self.key(msg), [])
        if len(arrivals) == 1:  # a value sent twice is not timed: which one came is unknown
            self.added.append(time.perf_counter() - arrivals[0])


async def drive(
    stack: NavStack, goals: int, seed: int, limit: float, realtime: bool
) -> tuple[Matcher, dict[str, float]]:
    if realtime:  # the instrument as the controller: before the bus, its threads too
        raise_priority(realtime_priority("controller"))
    async with open_bus(stack.settings()) as bus:
        client = await navigator_client(stack, bus)
        matcher = Matcher(bus)
        layout = "composed" if stack.config.use_composition else "separate"
        pids = {name: stack.processes[name].pid for name in LAYOUTS[layout]}
        cpu0 = {name: cpu_seconds(pid) for name, pid in pids.items()}
        wall0 = time.perf_counter()
        for x, y, yaw in pick_goals(static_grid(), START, goals, seed):
            end = await navigate(client, PoseStamped.from_xy_yaw(x, y, yaw), timeout=limit)
            print(f"goal ({x:.2f}, {y:.2f}): {end.state.name}", flush=True)
        wall = time.perf_counter() - wall0
        cpu = {n: 100.0 * (cpu_seconds(pid) - cpu0[n]) / wall for n, pid in pids.items()}
        return matcher, cpu


def report(matcher: Matcher, cpu: dict[str, float], speed: float) -> list[str]:
    added = np.array(matcher.added) * 1000.0 * speed  # sim ms
    p50, p99 = (float(np.percentile(added, q)) for q in (50, 99)) if added.size else (0.0, 0.0)
    load = " ".join(Path("/proc/loadavg").read_text().split()[:3])
    return [
        f"x{speed:g}: {added.size} commands matched of {matcher.outputs} sent to the base",
        f"  added p50 {p50:.1f} ms p99 {p99:.1f} ms of sim time "
        f"(one control period: {PERIOD * 1000:.0f} ms)",
        "  CPU while driving: "
        + ", ".join(f"{k} {v:.1f} %" for k, v in cpu.items())
        + f" of one core (together {sum(cpu.values()):.1f} %); load {load}",
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speed", type=float, default=1.0)
    parser.add_argument("--goals", type=int, default=2)
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--timeout", type=float, default=240.0, help="wall s per goal")
    parser.add_argument("--realtime", action="store_true", help="SCHED_FIFO on the way")
    parser.add_argument(
        "--composed", action="store_true", help="the chain in one process (aiobt safety_chain)"
    )
    exit_on_sigterm()
    args = parser.parse_args()
    extra = {name: ["--realtime-priority"] for name in REALTIME} if args.realtime else {}
    config = StackConfig(
        world="office", speed=args.speed, seed=args.seed, safety_chain=True, extra=extra,
        use_composition=args.composed,
    )  # fmt: skip
    router_args = ["--lease-ms", str(config.lease_ms)]
    router_args += ["--realtime-priority"] if args.realtime else []
    router, endpoint = start_router(extra_args=router_args, timeout=60.0)
    try:
        with NavStack.launch(endpoint, config) as stack:
            run = drive(stack, args.goals, args.seed, args.timeout, args.realtime)
            matcher, cpu = asyncio.run(run)
    finally:
        router.cleanup()
    print("\n".join(report(matcher, cpu, args.speed)), flush=True)


if __name__ == "__main__":
    main()
