"""What the safety chain adds between a command and the base, and what it costs.

The robot (office world, at ``--speed``), the velocity smoother and the collision
monitor (shipped defaults, on sim time) as processes on a router; this process
drives ``{ns}/cmd_vel_nav`` at 20 Hz of sim time (the controller's rate) with
distinct values the smoother passes through unchanged (0.3 m/s rising by 0.1 mm/s a
command) and times each to its arrival on ``{ns}/cmd_vel`` through both links,
against the same message's own arrival back from the router (the direct hop the
chain replaces). Also the CPU of the two services (``/proc``) while driving, and the
load average. ``--layouts``: the two as separate processes (as ``aiobt up`` runs them by
default) or ``composed`` in one (``aiobt safety_chain``, Nav2's composition), each run
in the order given on the same router (``separate composed separate composed``: A B A B).
``--idle``: then, the commands stopped and the chain stopped (``velocity_timeout``'s
zero sent, the clock let go), their CPU over that many wall seconds of standing still,
and what the chain adds to the first command after it (one small enough to pass the
smoother's ramp unchanged).
``--realtime``: the robot, the two services and this process (as the controller)
under ``SCHED_FIFO`` at their ``--realtime-priority`` defaults.

    .venv/bin/python -m bench.safety.chain_latency --speeds 1 10 --seconds 20 [--realtime]
    .venv/bin/python -m bench.safety.chain_latency --speeds 1 --seconds 15 \
        --layouts separate composed separate composed
"""

from __future__ import annotations

import argparse
import asyncio
import math
import os
import time
import uuid
from dataclasses import dataclass

import numpy as np

from aiobt.core.clock import Clock
from aiobt.msgs import Twist
from aiobt.system.catalog import realtime_priority
from aiobt.system.realtime import raise_priority
from aiobt.testing.bus import ServiceProcess, exit_on_sigterm, running_router, spawn_service
from aiobt.transport import Bus, BusSettings, Publisher, SimClockFollower, open_bus

PERIOD = 0.05  # s of sim time between commands: a 20 Hz controller
STOPPING = 2.0  # sim s after the last command: the smoother's timeout (1 s) and its ramp
LINGER = 1.5  # wall s more: a clock nobody holds is let go after 1 s
FIRST = 0.1  # m/s: the command sent to the stopped chain (under 2.5 m/s^2 x 0.05 s)
SERVICES = ("velocity_smoother", "collision_monitor")
LAYOUTS = {"separate": SERVICES, "composed": ("safety_chain",)}  # the processes of each


@dataclass(slots=True)
class Figures:
    speed: float
    matched: int
    sent: int
    direct_ms: tuple[float, float]  # p50, p99 wall ms
    chain_ms: tuple[float, float]
    cpu: dict[str, float]  # % of one core, by process
    load: tuple[float, float, float] = (0.0, 0.0, 0.0)  # the load average after the run
    idle: dict[str, float] | None = None  # % of one core standing still after, by process
    first_ms: float = math.nan  # sim ms the chain added to the first command after standing

    def lines(self) -> list[str]:
        added = [(c - d) * self.speed for c, d in zip(self.chain_ms, self.direct_ms, strict=True)]
        cpu = _percents(self.cpu)
        return [
            f"x{self.speed:g}: {self.matched}/{self.sent} commands matched",
            f"  direct hop p50 {self.direct_ms[0]:.2f} ms p99 {self.direct_ms[1]:.2f} ms (wall)",
            f"  via the chain p50 {self.chain_ms[0]:.2f} ms p99 {self.chain_ms[1]:.2f} ms (wall)",
            f"  added p50 {added[0]:.1f} ms p99 {added[1]:.1f} ms of sim time "
            f"(one control period: {PERIOD * 1000:.0f} ms)",
            f"  CPU while driving: {cpu} of one core",
            *(
                [
                    f"  CPU idle after: {_percents(self.idle)} of one core; the next command: "
                    f"added {self.first_ms:.1f} ms of sim time"
                ]
                if self.idle
                else []
            ),
            f"  load average {' '.join(f'{x:.2f}' for x in self.load)}",
        ]


def _percents(cpu: dict[str, float]) -> str:
    text = ", ".join(f"{k} {v:.1f} %" for k, v in cpu.items())
    return text + (f" (in all {sum(cpu.values()):.1f} %)" if len(cpu) > 1 else "")


def cpu_seconds(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


async def measure(
    endpoint: str,
    speed: float,
    seconds: float,
    realtime: bool,
    layout: str = "separate",
    idle: float = 0.0,
) -> Figures:
    ns = f"bench{uuid.uuid4().hex[:8]}"
    common = ["--connect", endpoint, "--namespace", ns]
    common += ["--realtime-priority"] if realtime else []
    robot = ["-m", "aiobt.cli.main", "robot", "--world", "office", "--speed", f"{speed:g}"]
    procs: dict[str, ServiceProcess] = {"robot": spawn_service([*robot, *common])}
    for name in LAYOUTS[layout]:
        procs[name] = spawn_service(["-m", "aiobt.cli.main", name, "--sim-time", *common])
    try:
        settings = BusSettings(mode="client", connect=(endpoint,), namespace=ns)
        async with open_bus(settings) as bus:
            for name in ("robot", *SERVICES):  # composed: both tokens from one process
                if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(60.0):
                    output = "\n".join(p.output() for p in procs.values())
                    raise RuntimeError(f"{name} did not come up:\n{output}")
            return await _drive(bus, procs, LAYOUTS[layout], speed, seconds, idle)
    finally:
        for proc in procs.values():
            proc.cleanup()


async def _drive(
    bus: Bus,
    procs: dict[str, ServiceProcess],
    measured: tuple[str, ...],
    speed: float,
    seconds: float,
    idle: float = 0.0,
) -> Figures:
    sent: dict[float, float] = {}
    direct: dict[float, float] = {}
    chain: dict[float, float] = {}
    bus.subscribe(
        "cmd_vel_nav", Twist, lambda m: direct.setdefault(m.linear.x, time.perf_counter())
    )
    bus.subscribe("cmd_vel", Twist, lambda m: chain.setdefault(m.linear.x, time.perf_counter()))
    out = bus.publisher("cmd_vel_nav", Twist, reliable=True)
    follower = SimClockFollower(bus)
    await follower.wait_started(timeout=10.0)
    clock = follower.clock
    count = round(seconds / PERIOD)
    cpu0 = {name: cpu_seconds(procs[name].pid) for name in measured}
    wall0 = time.perf_counter()
    for k in range(count):
        value = round(0.3 + 1e-4 * k, 6)
        sent[value] = time.perf_counter()
        out.put(Twist.planar(value, 0.0))
        await clock.sleep(PERIOD)
    wall = time.perf_counter() - wall0
    cpu = {n: 100.0 * (cpu_seconds(procs[n].pid) - cpu0[n]) / wall for n in measured}
    still, first_ms = None, math.nan
    if idle > 0.0:
        still = await _idle_cpu(procs, measured, clock, idle)
        first_ms = await _first_command(out, direct, chain) * speed
    follower.close()
    ramp = round(0.3 / (2.5 * PERIOD)) + 2  # the smoother's ramp from 0: not passed through
    keys = [v for v in list(sent)[ramp:] if v in chain and v in direct]
    lat_d = np.array([direct[v] - sent[v] for v in keys]) * 1000.0
    lat_c = np.array([chain[v] - sent[v] for v in keys]) * 1000.0

    def p(a: np.ndarray) -> tuple[float, float]:
        return float(np.percentile(a, 50)), float(np.percentile(a, 99))

    load = os.getloadavg()
    return Figures(speed, len(keys), count - ramp, p(lat_d), p(lat_c), cpu, load, still, first_ms)


async def _idle_cpu(
    procs: dict[str, ServiceProcess], measured: tuple[str, ...], clock: Clock, seconds: float
) -> dict[str, float]:
    """% of one core over ``seconds`` wall s standing still, once the chain has stopped:
    ``velocity_timeout`` (1 s) and more of sim time, then the clock's linger (1 wall s)."""
    await clock.sleep(STOPPING)
    await asyncio.sleep(LINGER)
    cpu0 = {name: cpu_seconds(procs[name].pid) for name in measured}
    await asyncio.sleep(seconds)
    return {n: 100.0 * (cpu_seconds(procs[n].pid) - cpu0[n]) / seconds for n in measured}


async def _first_command(
    out: Publisher[Twist], direct: dict[float, float], chain: dict[float, float]
) -> float:
    """Wall ms the chain adds to one command sent to a stopped chain (nan: none came)."""
    value = FIRST  # within one period's max_accel from 0: passed through unchanged
    out.put(Twist.planar(value, 0.0))
    for _ in range(5000):  # bounded: 5 s
        if value in chain and value in direct:
            return (chain[value] - direct[value]) * 1000.0
        await asyncio.sleep(0.001)
    return math.nan


async def main_async(
    speeds: list[float], seconds: float, realtime: bool, layouts: list[str], idle: float = 0.0
) -> None:
    with running_router() as (_, endpoint):
        for layout in layouts:
            for speed in speeds:
                figures = await measure(endpoint, speed, seconds, realtime, layout, idle)
                print(f"{layout} ({time.strftime('%H:%M:%S', time.gmtime())} UTC)")
                print("\n".join(figures.lines()), flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speeds", type=float, nargs="+", default=[1.0, 10.0])
    parser.add_argument("--seconds", type=float, default=20.0, help="sim s of driving per speed")
    parser.add_argument("--realtime", action="store_true", help="SCHED_FIFO on the way")
    parser.add_argument(
        "--layouts", nargs="+", choices=sorted(LAYOUTS), default=["separate"],
        help="the chain's processes, each run in this order (default: separate)",
    )  # fmt: skip
    parser.add_argument(
        "--idle", type=float, default=0.0, metavar="S",
        help="then the CPU over S wall s standing still, the chain stopped (default: not)",
    )  # fmt: skip
    exit_on_sigterm()
    args = parser.parse_args()
    if args.realtime:  # this process plays the controller; before its bus: its threads too
        raise_priority(realtime_priority("controller"))
    asyncio.run(main_async(args.speeds, args.seconds, args.realtime, args.layouts, args.idle))


if __name__ == "__main__":
    main()
