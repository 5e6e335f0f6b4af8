"""What publishing the local plan and local costmap costs the control cycle (issue 18).

Run: ``.venv/bin/python -m bench.controller.local_view [--baseline-python PY]``

The robot (small world, ``--speed 4``) and the controller on a router; the
controller follows a 1.5 m path there and back, three ways in one run:

- ``unobserved``: nobody subscribes to ``local_plan`` / ``local_costmap/costmap``
  (the controller only asks its publishers whether a subscriber matches);
- ``observed``: a subscriber on both (a Path per cycle, a costmap at 2 Hz);
- ``baseline`` (with ``--baseline-python``, e.g. main's venv): a controller
  without these topics, observed the same way.

Figures: the controller's own per-goal log line (``cycle p50 .. p99 ..``), the
median over the goals, and the ratio to the first configuration measured. On a
loaded machine these swing more than the cost itself, so the bench first times
in this process, on the same data: one control cycle (``FollowPathSession.step``,
RPP, full 5 x 5 m local costmap; the baseline) against what observing adds to a
cycle: the local plan message (built and encoded as the publisher does) and the
local costmap message (built and encoded; sent once every 10 cycles at 20 Hz).
"""

from __future__ import annotations

import argparse
import asyncio
import os
import pathlib
import re
import statistics
import subprocess
import sys
import tempfile
import time
import uuid
from collections.abc import Callable

import numpy as np

from aiobt.geometry import PlanarPath, Pose2D, Velocity
from aiobt.msgs import FollowPath, GoalState, OccupancyGrid, Path, PoseStamped
from aiobt.robot.state import RobotState
from aiobt.system.lifeline import popen_bound
from aiobt.testing.bus import ServiceProcess, exit_on_sigterm, running_router
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt_services.controller.observed import costmap_msg, path_msg
from aiobt_services.controller.session import (
    ControllerConfig,
    FollowPathSession,
    FollowRequest,
)
from bench.controller.control_cycle import full_costmap, time_cycles

TRUTH = ("--pose-source", "truth")  # the robot's {ns}/pose is the truth (no localization)

CYCLE = re.compile(
    r"(\d+) cycles, rate ([\d.]+) of [\d.]+ Hz, cycle p50 ([\d.]+) ms p99 ([\d.]+) ms"
)
LEGS = [[(0.0, 0.0), (1.5, 0.0)], [(1.5, 0.0), (0.0, 0.0)]]


def leg(points: list[tuple[float, float]]) -> Path:
    (x0, y0), (x1, y1) = points
    n = 60
    heading = 0.0 if x1 > x0 else 3.141592653589793
    poses = [
        PoseStamped.from_xy_yaw(x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * i / n, heading)
        for i in range(n + 1)
    ]
    return Path(poses=poses)


class Interpreted(ServiceProcess):
    """A service process under another interpreter (another checkout's venv)."""

    def __init__(self, python: str, args: list[str]) -> None:
        self.args = args
        handle, name = tempfile.mkstemp(prefix="aiobt-bench-", suffix=".log")
        os.close(handle)
        self.log_path = pathlib.Path(name)
        with self.log_path.open("wb") as log:
            self.popen = popen_bound(
                [python, *args], stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL
            )


async def run_goals(bus: Bus, goals: int) -> None:
    client = bus.action_client("follow_path", FollowPath)
    for i in range(goals):
        goal = await client.send_goal(FollowPath.Goal(path=leg(LEGS[i % 2])), server_timeout=30.0)
        result = await goal.result(timeout=60.0)
        if goal.status is not GoalState.SUCCEEDED:
            raise RuntimeError(f"goal {i} ended {goal.status.name}: {result}")


async def configuration(
    endpoint: str, python: str, observed: bool, goals: int
) -> list[tuple[float, float, float]]:
    settings = BusSettings(mode="client", connect=(endpoint,), namespace=f"b{uuid.uuid4().hex[:8]}")
    common = ["--connect", endpoint, "--namespace", settings.namespace]
    robot = ServiceProcess(
        # without localization: the robot's pose is the truth's
        ["-m", "aiobt_services.robot", "--world", "small", "--speed", "4", *TRUTH, *common]
    )
    controller = Interpreted(python, ["-m", "aiobt_services.controller", "--sim-time", *common])
    try:
        async with open_bus(settings) as bus:
            for name, proc in (("robot", robot), ("controller", controller)):
                if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(60.0):
                    raise RuntimeError(f"{name} did not come up:\n{proc.output()}")
            if observed:
                bus.subscribe("local_plan", Path, lambda _: None)
                bus.subscribe("local_costmap/costmap", OccupancyGrid, lambda _: None)
            await run_goals(bus, goals)
        controller.stop(10.0)
        return [(float(m[1]), float(m[2]), float(m[3])) for m in CYCLE.findall(controller.output())]
    finally:
        controller.cleanup()
        robot.cleanup()


def timed(action: Callable[[], object], runs: int) -> float:
    """Median wall time of ``action``, ms."""
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        action()
        times.append(time.perf_counter() - start)
    return statistics.median(times) * 1e3


def in_process(cycles: int) -> None:
    costmap = full_costmap(np.random.default_rng(7))
    step = float(np.median(time_cycles("FollowPath", costmap, cycles))) / 1e3
    session = FollowPathSession(
        FollowRequest(PlanarPath.through([(-2.0, 0.0), (2.4, 0.0)], 0.05), "FollowPath"),
        ControllerConfig(),
        0.0,
        None,
    )
    state = RobotState(Pose2D(-1.0, 0.02, 0.01), Velocity(0.4, 0.0), 0.0)
    trajectory = session.step(0.0, {"map": state}).trajectory
    plan = timed(lambda: path_msg(trajectory, 1.0, "map").to_json(), cycles)
    grid = timed(lambda: costmap_msg(costmap.grid(), 1.0).to_json(), cycles // 10)
    print(f"in process, median of {cycles} ({len(trajectory)} poses in the local plan):")
    print(f"  control cycle (RPP, full costmap): {step:.3f} ms (baseline)")
    print(f"  + local plan message:              {plan:.3f} ms ({plan / step:.2f} of a cycle)")
    print(f"  + local costmap message:           {grid:.3f} ms ({grid / step:.2f} of a cycle,")
    print(f"    once per 10 cycles: {grid / 10 / step:.3f} of a cycle on average)")


async def main_async(args: argparse.Namespace) -> None:
    in_process(args.cycles)
    plans = [("unobserved", sys.executable, False), ("observed", sys.executable, True)]
    if args.baseline_python:
        plans.insert(0, ("baseline", args.baseline_python, True))
    with running_router() as (_, endpoint):
        first = None
        print("configuration  goals  rate Hz   p50 ms   p99 ms  p50 ratio")
        for name, python, observed in plans:
            rows = await configuration(endpoint, python, observed, args.goals)
            rate = statistics.median(r[0] for r in rows)
            p50 = statistics.median(r[1] for r in rows)
            p99 = statistics.median(r[2] for r in rows)
            first = first or p50
            figures = f"{rate:>8.2f} {p50:>8.2f} {p99:>8.2f} {p50 / first:>10.2f}"
            print(f"{name:<13} {len(rows):>6} {figures}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--goals", type=int, default=4, help="goals per configuration")
    parser.add_argument("--cycles", type=int, default=2000, help="in-process repetitions")
    parser.add_argument("--baseline-python", help="interpreter of a controller without the topics")
    exit_on_sigterm()
    asyncio.run(main_async(parser.parse_args()))


if __name__ == "__main__":
    main()
