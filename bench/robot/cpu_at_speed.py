"""CPU per sim second of the robot service at a speed-up, driving, this code vs a baseline.

Run: ``.venv/bin/python -m bench.robot.cpu_at_speed --base /tmp/sim_base [--speed 10]``

A router, then (``--rounds`` times, alternating, so that the machine's load hits
both) the robot service of the baseline checkout (``--base``: a ``git archive`` of
another commit, run with ``PYTHONPATH`` on it) and of this tree, each at
``--speed`` on the office world for ``--seconds`` wall s, while a client
subscribes to every topic the stack reads (clock, odom, pose, scan) and drives
it as a wanderer: ``cmd_vel`` every 0.05 s of sim time, forward, turning away
while the scan shows something close ahead. Per run, from ``/proc/<pid>/stat``
and the clock topic: the robot's CPU in % of a core, its CPU ms per sim second,
and the speed-up achieved; how the clock moves as the client receives it (the sim
ms it advanced within 5 ms of wall after each stamp, p50/p90/p99: the steps the
robot runs per wake-up come as one bunch); from the robot's log (its 5 s reports
over the whole run), the sim time given up to lag and the wall time held for late
commands.
The figure is the ratio this / baseline of CPU per
sim second.
"""

from __future__ import annotations

import argparse
import asyncio
import math
import re
import statistics
import time
from pathlib import Path

import numpy as np

from aiobt.msgs import Clock, LaserScan, Odometry, PoseStamped, Twist
from aiobt.testing.bus import ServiceProcess, exit_on_sigterm, spawn_service, start_router
from aiobt.transport import Bus, BusSettings, open_bus

from ..nav.run import loadavg
from ..system.procstat import cpu_seconds

FRONT = math.radians(35)
LOST = re.compile(r"([\d.]+) s of sim time given up")
HELD = re.compile(r"waited \d+ time\(s\), ([\d.]+) s in all")


class Wanderer:
    """Subscribes like the stack does; commands forward, or turns while blocked ahead."""

    def __init__(self, bus: Bus) -> None:
        self.sim = math.nan
        self.stamps: list[tuple[float, float]] = []  # (wall, sim) of each stamp received
        self.ticking = asyncio.Event()
        self.turn = 0.0
        self.scans = 0
        self._cmd = bus.publisher("cmd_vel", Twist)
        bus.subscribe("clock", Clock, self._on_clock, queue_size=1)
        bus.subscribe("scan", LaserScan, self._on_scan, queue_size=1)
        for name, model in (("odom", Odometry), ("pose", PoseStamped)):
            bus.subscribe(name, model, lambda _: None, queue_size=1)

    def _on_clock(self, msg: Clock) -> None:
        self.sim = msg.clock
        self.stamps.append((time.monotonic(), msg.clock))
        self.ticking.set()

    def _on_scan(self, msg: LaserScan) -> None:
        self.scans += 1
        ranges = np.asarray(msg.ranges)
        angles = msg.angle_min + msg.angle_increment * np.arange(len(ranges))
        self.turn = 1.5 if np.min(ranges[np.abs(angles) < FRONT]) < 0.8 else 0.0

    async def drive(self, period: float, stop: asyncio.Event) -> None:
        while not stop.is_set():
            msg = Twist.model_validate(
                {"linear": {"x": 0.0 if self.turn else 0.6}, "angular": {"z": self.turn}}
            )
            self._cmd.put(msg)
            await asyncio.sleep(period)


async def measure(
    settings: BusSettings, robot: ServiceProcess, args: argparse.Namespace
) -> dict[str, float]:
    async with open_bus(settings) as bus:
        client = Wanderer(bus)
        try:
            await asyncio.wait_for(client.ticking.wait(), 60.0)
        except TimeoutError:
            raise SystemExit(f"no clock from the robot:\n{robot.output()[-3000:]}") from None
        stop = asyncio.Event()
        driver = asyncio.create_task(client.drive(0.05 / args.speed, stop))
        await asyncio.sleep(args.warmup)
        cpu0, sim0, wall0 = cpu_seconds(robot.pid), client.sim, time.monotonic()
        client.stamps.clear()
        await asyncio.sleep(args.seconds)
        cpu, sim = cpu_seconds(robot.pid) - cpu0, client.sim - sim0
        wall = time.monotonic() - wall0
        stop.set()
        await driver
    steps = np.percentile(clock_steps(client.stamps, 0.005), [50, 90, 99]) * 1e3
    return {
        "cpu_pct": 100 * cpu / wall,
        "ms_per_sim_s": 1e3 * cpu / sim,
        "speed": sim / wall,
        **{f"clock_5ms_p{q}": float(v) for q, v in zip((50, 90, 99), steps, strict=True)},
    }


def clock_steps(stamps: list[tuple[float, float]], window: float) -> np.ndarray:
    """For each (wall, sim) stamp, the sim time the newest stamp within ``window`` wall s
    after it is ahead of it (how far the clock moves at once, as received)."""
    if not stamps:
        return np.array([math.nan])
    wall, sim = np.array(stamps).T
    last = np.searchsorted(wall, wall + window, side="right") - 1
    return np.asarray(sim[last] - sim)


def run_one(
    endpoint: str, pythonpath: str | None, args: argparse.Namespace, namespace: str
) -> dict[str, float]:
    command = ["-m", "aiobt.cli.main", "robot", "--connect", endpoint, "--namespace", namespace]
    env = {"PYTHONPATH": pythonpath} if pythonpath else None
    robot = spawn_service([*command, "--world", "office", "--speed", str(args.speed)], env)
    settings = BusSettings(mode="client", connect=(endpoint,), namespace=namespace)
    try:
        figures = asyncio.run(measure(settings, robot, args))
        robot.stop()
        log = robot.output()  # the pacing reports of the whole run, warm-up included
        figures["lag_lost_sim_s"] = sum(float(x) for x in LOST.findall(log))
        figures["held_wall_s"] = sum(float(x) for x in HELD.findall(log))
        return figures
    finally:
        robot.cleanup()


def summary(runs: dict[str, list[dict[str, float]]]) -> list[str]:
    lines = [
        "| code | CPU % of a core | CPU ms per sim s | speed-up | lag: sim s given up "
        "| held for commands, wall s | clock: sim ms within 5 ms wall, p50 p90 p99 |",
        "|---|---|---|---|---|---|---|",
    ]
    for label, figs in runs.items():
        keys = ("cpu_pct", "ms_per_sim_s", "speed", "lag_lost_sim_s", "held_wall_s")
        steps = " / ".join(
            " ".join(f"{f[f'clock_5ms_p{q}']:.0f}" for q in (50, 90, 99)) for f in figs
        )
        cells = [" / ".join(f"{f[k]:.1f}" for f in figs) for k in keys]
        lines.append(f"| {label} | " + " | ".join(cells) + f" | {steps} |")
    pairs = zip(runs["base"], runs["this"], strict=True)
    ratios = [t["ms_per_sim_s"] / b["ms_per_sim_s"] for b, t in pairs]
    each = ", ".join(f"{r:.2f}" for r in ratios)
    lines.append(
        f"\nCPU per sim s, this / base, per round: {each} (median {statistics.median(ratios):.2f})"
    )
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--base", type=Path, required=True, help="baseline checkout")
    parser.add_argument("--speed", type=float, default=10.0)
    parser.add_argument("--seconds", type=float, default=15.0, help="wall s measured per run")
    parser.add_argument("--warmup", type=float, default=3.0, help="wall s before measuring")
    parser.add_argument("--rounds", type=int, default=3)
    exit_on_sigterm()
    args = parser.parse_args(argv)
    base = args.base.resolve()
    services = next(
        (p for p in (base / "services", base / "typings") if (p / "aiobt_services").is_dir()), None
    )
    if services is None:  # the layout of today, or the one before services/aiobt_services
        raise SystemExit(f"--base {base}: no aiobt_services there (a git archive of a commit?)")
    paths = {"base": f"{base / 'src'}:{services}:{base}", "this": None}
    print(f"load average before: {loadavg()}", flush=True)
    runs: dict[str, list[dict[str, float]]] = {"base": [], "this": []}
    router, endpoint = start_router()
    try:
        for n in range(args.rounds):
            for label, path in paths.items():
                figures = run_one(endpoint, path, args, f"cpu{n}{label}")
                runs[label].append(figures)
                shown = ", ".join(f"{k} {v:.2f}" for k, v in figures.items())
                print(f"round {n + 1} {label}: {shown}", flush=True)
    finally:
        router.cleanup()
    print(f"\nrobot --speed {args.speed:g}, office world, driving, {args.seconds:g} s per run")
    print("\n".join(summary(runs)))
    print(f"load average after: {loadavg()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
