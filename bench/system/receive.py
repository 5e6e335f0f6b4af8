"""What receiving each of the robot's streams costs a process, in process figures.

Run: ``.venv/bin/python -m bench.system.receive --seconds 20 --rounds 2``

Starts a router and the robot at 1x (standing; its pose as ``{ns}/pose``, as
localization would send it) and, in this process, ``{ns}/tf`` at 10 Hz (a correction,
as localization sends it with every scan). Then, for each case in turn, ``--rounds``
times: a child process opens a bus and runs a 20 Hz loop sleeping on sim time (as the
controller's control loop), with the streams the case names subscribed with a callback
that does nothing (:class:`~aiobt.transport.topics.Subscription`, as the controller's
tracker reads them); its CPU over ``--seconds`` wall s, in % of one core. The cases:

- ``wall``: the loop on the wall clock and nothing else (the process's own cost);
- ``clock``: the loop on ``{ns}/clock`` (100 Hz) and nothing else;
- ``odomtime``: the loop on the odometry's stamps (50 Hz, :func:`make_clock`'s
  ``odometry``) and nothing else;
- ``clock+odom+pose``: the controller's reading before (clock, odometry, pose);
- ``clock+odom+tf``: the controller's reading now (the pose composed from odometry
  and the 10 Hz correction);
- ``odomtime+odom+tf``: the same with the loop on the odometry's stamps.

Prints one markdown table (median and range per case) and the load average before and
after.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import statistics
import sys
import time
from typing import Any

from aiobt.core.clock import Clock
from aiobt.msgs import Odometry, PoseStamped, TFMessage
from aiobt.robot.correction import correction_message
from aiobt.system.service import make_clock
from aiobt.testing.bus import ServiceProcess, spawn_service, start_router
from aiobt.transport import Bus, BusSettings, open_bus

from ..nav.run import loadavg
from .procstat import cpu_seconds

CASES = ("wall", "clock", "odomtime", "clock+odom+pose", "clock+odom+tf", "odomtime+odom+tf")
MODELS: dict[str, type[Any]] = {"odom": Odometry, "pose": PoseStamped, "tf": TFMessage}
NAMESPACE = "recv"
PERIOD = 0.05  # robot s: the controller's 20 Hz


async def child(case: str, settings: BusSettings) -> None:
    """One case's process: the loop and the subscriptions, until SIGTERM."""
    async with open_bus(settings) as bus:
        parts = case.split("+")
        sim_time, odometry = parts[0] != "wall", "odom" if parts[0] == "odomtime" else None
        clock, _ = await make_clock(bus, sim_time, odometry)
        for topic in parts[1:]:
            bus.subscribe(topic, MODELS[topic], lambda _msg: None)
        print("ready", flush=True)
        await loop_on(clock)


async def loop_on(clock: Clock) -> None:
    deadline = clock.now()
    while True:
        deadline += PERIOD
        await clock.sleep(max(0.0, deadline - clock.now()))


async def send_tf(bus: Bus) -> None:
    tf = bus.publisher("tf", TFMessage)
    while True:
        tf.put(correction_message((1.0, 2.0, 0.3), time.monotonic()))
        await asyncio.sleep(0.1)


def measure(case: str, endpoint: str, seconds: float) -> float:
    proc = spawn_service(["-m", "bench.system.receive", "--child", case, "--connect", endpoint,
                          "--namespace", NAMESPACE])  # fmt: skip
    try:
        if not proc.wait_for_output("ready", 30.0):
            raise RuntimeError(f"{case}: the child did not start:\n{proc.output()}")
        time.sleep(3.0)  # settled
        before = cpu_seconds(proc.pid)
        time.sleep(seconds)
        return 100.0 * (cpu_seconds(proc.pid) - before) / seconds
    finally:
        proc.cleanup()


async def run(seconds: float, rounds: int) -> None:
    load = loadavg()
    router, endpoint = start_router()
    robot: ServiceProcess | None = None
    try:
        robot = spawn_service(
            ["-m", "aiobt_services.robot", "--speed", "1", "--pose-source", "truth",
             "--connect", endpoint, "--namespace", NAMESPACE]
        )  # fmt: skip
        settings = BusSettings(mode="client", connect=(endpoint,), namespace=NAMESPACE)
        async with open_bus(settings) as bus:
            if not await bus.presence(bus.keys.topic("nodes/robot")).wait(60.0):
                raise RuntimeError(f"the robot did not come up:\n{robot.output()}")
            sender = asyncio.create_task(send_tf(bus))
            figures: dict[str, list[float]] = {case: [] for case in CASES}
            for _ in range(rounds):
                for case in CASES:
                    figures[case].append(await asyncio.to_thread(measure, case, endpoint, seconds))
            sender.cancel()
    finally:
        if robot is not None:
            robot.cleanup()
        router.cleanup()
    print(f"load average before {load}, after {loadavg()}; {rounds} round(s) of {seconds:.0f} s\n")
    print("| case | CPU % of a core, median (range) |\n|---|---|")
    for case, values in figures.items():
        print(f"| {case} | {statistics.median(values):.2f} ({min(values):.2f}-{max(values):.2f}) |")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--child", choices=CASES)
    parser.add_argument("--connect", default="")
    parser.add_argument("--namespace", default=NAMESPACE)
    args = parser.parse_args()
    if args.child:
        settings = BusSettings(mode="client", connect=(args.connect,), namespace=args.namespace)
        asyncio.run(child(args.child, settings))
        return 0
    asyncio.run(run(args.seconds, args.rounds))
    return 0


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    sys.exit(main())
