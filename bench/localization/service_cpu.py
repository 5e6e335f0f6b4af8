"""The localization service's own CPU, in process figures, source trees alternated.

Run: ``.venv/bin/python -m bench.localization.service_cpu --seconds 20 --rounds 3
--tree base=/work/wt-base --tree branch=.``

Starts a router on loopback and the robot at 1x (office world, ``--pose-source none``,
standing at the world's start), then, ``--rounds`` times, for each ``--tree`` in turn
(alternating, the order reversed every other round): the localization service as
``aiobt up`` runs it (``--params-file sim_robot``, the start as its initial pose) from
that tree's ``src`` and ``services`` (``PYTHONPATH``), and its CPU from ``/proc`` in
% of one core over ``--seconds`` wall s in each phase:

- ``idle``: the robot standing, nobody reading ``pose``;
- ``idle+pose``: the same with one reader of ``pose`` (a ``Latest``, as the planner);
- ``spin``: the robot turning on the spot at 0.5 rad/s (``cmd_vel`` at 20 Hz from
  here), nobody reading ``pose``: the filter updates every 0.1 rad (sim_robot's
  ``update_min_a``), 5 a second;
- ``spin+pose``: the same with one reader of ``pose`` (the stack while it drives: the
  navigator and the planner read it).

Per phase also the CPU of the process's threads by name (``/proc/<pid>/task``: the
event loop's ``python``, Zenoh's ``rx-*``, ...). Prints one markdown table per phase
and the load average before and after.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import statistics
import sys
import time
from collections import defaultdict
from pathlib import Path

from aiobt.msgs import PoseStamped, PoseWithCovarianceStamped, Twist
from aiobt.testing.bus import ServiceProcess, spawn_service, start_router
from aiobt.transport import Bus, BusSettings, open_bus

from ..nav.run import loadavg
from ..system.procstat import TICKS, cpu_seconds

NAMESPACE = "loccpu"
START = ("2.0", "9.75", "0.0")  # the office world's start
PHASES = ("idle", "idle+pose", "spin", "spin+pose")
SETTLE = 3.0  # wall s after the service is up (and between phases)
SPIN_RATE = 0.5  # rad/s


def thread_seconds(pid: int) -> dict[str, float]:
    """CPU seconds of ``pid``'s threads, summed by thread name (digits dropped)."""
    out: dict[str, float] = defaultdict(float)
    for task in os.scandir(f"/proc/{pid}/task"):
        try:
            text = Path(task.path, "stat").read_text()
        except OSError:
            continue  # ended meanwhile
        name = text[text.index("(") + 1 : text.rindex(")")].rstrip("0123456789-_")
        fields = text[text.rindex(")") + 2 :].split()
        out[name or "?"] += (int(fields[11]) + int(fields[12])) / TICKS
    return dict(out)


def localization(tree: Path, endpoint: str) -> ServiceProcess:
    path = f"{tree / 'src'}{os.pathsep}{tree / 'services'}"
    return spawn_service(
        ["-m", "aiobt_services.localization", "--params-file", "sim_robot",
         "--set", "set_initial_pose=true",
         "--set", f"initial_pose={{x: {START[0]}, y: {START[1]}, yaw: {START[2]}}}",
         "--connect", endpoint, "--namespace", NAMESPACE],
        env={"PYTHONPATH": path},
    )  # fmt: skip


async def drive(bus: Bus, rate: float) -> None:
    """``cmd_vel`` at 20 Hz (the robot stops when commands stop)."""
    cmd = bus.publisher("cmd_vel", Twist)
    while True:
        cmd.put(Twist.planar(0.0, rate))
        await asyncio.sleep(0.05)


async def phase(bus: Bus, pid: int, name: str, seconds: float) -> tuple[float, dict[str, float]]:
    """The process's CPU (% of a core) over ``seconds`` of phase ``name``, and by thread."""
    helper: asyncio.Task[None] | None = None
    reader = bus.latest("pose", PoseStamped) if name.endswith("+pose") else None
    if name.startswith("spin"):
        helper = asyncio.create_task(drive(bus, SPIN_RATE))
    try:
        await asyncio.sleep(SETTLE)
        before, threads, wall = cpu_seconds(pid), thread_seconds(pid), time.monotonic()
        await asyncio.sleep(seconds)
        wall = time.monotonic() - wall
        total = 100.0 * (cpu_seconds(pid) - before) / wall
        after = thread_seconds(pid)
        by_thread = {k: 100.0 * (v - threads.get(k, 0.0)) / wall for k, v in after.items()}
        return total, by_thread
    finally:
        if helper is not None:
            helper.cancel()
            bus.publisher("cmd_vel", Twist).put(Twist.planar(0.0, 0.0))
        if reader is not None:
            reader.close()


async def one_run(
    bus: Bus, tree: Path, endpoint: str, seconds: float
) -> dict[str, tuple[float, dict[str, float]]]:
    proc = localization(tree, endpoint)
    try:
        amcl = bus.latest("amcl_pose", PoseWithCovarianceStamped, latched=True)
        try:
            await amcl.wait_latest(60.0)  # the filter has its initial pose
        except TimeoutError:
            raise RuntimeError(
                f"localization from {tree} did not start:\n{proc.output()}"
            ) from None
        finally:
            amcl.close()
        return {name: await phase(bus, proc.pid, name, seconds) for name in PHASES}
    finally:
        proc.cleanup()


async def run(trees: dict[str, Path], seconds: float, rounds: int) -> None:
    load = loadavg()
    router, endpoint = start_router()
    robot: ServiceProcess | None = None
    figures: dict[str, dict[str, list[float]]] = {p: defaultdict(list) for p in PHASES}
    threads: dict[str, dict[str, dict[str, list[float]]]] = {
        p: defaultdict(lambda: defaultdict(list)) for p in PHASES
    }
    try:
        robot = spawn_service(
            ["-m", "aiobt_services.robot", "--world", "office", "--speed", "1",
             "--pose-source", "none", "--seed", "1", "--start", *START,
             "--connect", endpoint, "--namespace", NAMESPACE]
        )  # fmt: skip
        settings = BusSettings(mode="client", connect=(endpoint,), namespace=NAMESPACE)
        async with open_bus(settings) as bus:
            if not await bus.presence(bus.keys.topic("nodes/robot")).wait(60.0):
                raise RuntimeError(f"the robot did not come up:\n{robot.output()}")
            for round_ in range(rounds):
                order = list(trees.items())
                for label, tree in order if round_ % 2 == 0 else order[::-1]:
                    started = time.strftime("%H:%M:%S")
                    for name, (total, cpu) in (await one_run(bus, tree, endpoint, seconds)).items():
                        figures[name][label].append(total)
                        for thread, value in cpu.items():
                            threads[name][label][thread].append(value)
                        print(f"round {round_ + 1} {label} ({started}) {name}: {total:.2f} %",
                              flush=True)  # fmt: skip
    finally:
        if robot is not None:
            robot.cleanup()
        router.cleanup()
    print(f"\nload average before {load}, after {loadavg()}; {rounds} round(s) of {seconds:.0f} s")
    for name in PHASES:
        print(f"\n{name}\n\n| tree | CPU % of a core, each run | median | threads (median) |")
        print("|---|---|---|---|")
        for label, values in figures[name].items():
            by = threads[name][label]
            top = sorted(by, key=lambda t: -statistics.median(by[t]))[:4]
            parts = ", ".join(f"{t} {statistics.median(by[t]):.2f}" for t in top)
            runs = ", ".join(f"{v:.2f}" for v in values)
            print(f"| {label} | {runs} | {statistics.median(values):.2f} | {parts} |")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--tree", action="append", default=[], metavar="LABEL=PATH",
                        help="a source tree to run localization from (repeated)")  # fmt: skip
    args = parser.parse_args()
    pairs = [item.split("=", 1) for item in args.tree] or [["here", "."]]
    trees = {label: Path(path).resolve() for label, path in pairs}
    for label, tree in trees.items():
        if not (tree / "services" / "aiobt_services" / "localization").is_dir():
            parser.error(f"--tree {label}={tree}: no services/aiobt_services/localization there")
    asyncio.run(run(trees, args.seconds, args.rounds))
    return 0


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    sys.exit(main())
