"""Plan + follow of seeded goals with the whole stack up, at a sim speed-up.

Run: ``.venv/bin/python -m bench.system.plan_follow --goals 10 --speed 10 [--baseline 4]``

Processes over a router on loopback: the robot (office world, ``--speed``), the
planner, the controller and the behaviors (both on sim time). For each goal,
seeded free poses at least ``--spacing`` m apart: ComputePathToPose from the
robot's pose, then FollowPath; arrived = the follow succeeded and the robot
stands within 0.25 m of the goal. With ``--baseline S`` the same goals run
first at speed S in a fresh stack (the reference the speed-up is compared to).
Prints arrivals, error codes, sim and wall time per goal, the speed-up achieved
(sim seconds on ``{ns}/clock`` per wall second), the robot's lag reports and
command timeouts, and the load average.
"""

from __future__ import annotations

import argparse
import asyncio
import math
import os
import time
import uuid
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from aiobt.msgs import Clock, ComputePathToPose, FollowPath, PoseStamped
from aiobt.testing.bus import exit_on_sigterm, running_router, spawn_service
from aiobt.transport import ActionError, Bus, BusSettings, open_bus
from aiobt_services.robot.mapfile import MapInfo, load_map
from aiobt_services.robot.worlds import OFFICE

TRUTH = ("--pose-source", "truth")  # the robot's {ns}/pose is the truth (no localization)

ARRIVED_WITHIN = 0.25  # m: the default goal checker's tolerance
CLEARANCE = 0.5  # m from any wall: the robot (0.22) plus room to turn


@dataclass(slots=True, frozen=True)
class Outcome:
    goal: tuple[float, float, float]
    arrived: bool
    plan_code: int
    follow_code: int
    distance: float  # m from the goal at the end
    sim_seconds: float
    wall_seconds: float
    message: str = ""


def seeded_goals(
    world: MapInfo, count: int, seed: int, spacing: float = 3.0
) -> list[tuple[float, float, float]]:
    """``count`` free poses ``CLEARANCE`` from walls, each ``spacing`` m from the last."""
    rng = np.random.default_rng(seed)
    x0, y0 = world.origin[0], world.origin[1]
    width, height = world.width * world.resolution, world.height * world.resolution
    last = world.start[:2]
    goals: list[tuple[float, float, float]] = []
    while len(goals) < count:
        x, y = round(x0 + rng.uniform(0, width), 2), round(y0 + rng.uniform(0, height), 2)
        if not world.contains(x, y, CLEARANCE) or world.disc_blocked(x, y, CLEARANCE):
            continue
        if math.hypot(x - last[0], y - last[1]) < spacing:
            continue
        goals.append((x, y, round(float(rng.uniform(-math.pi, math.pi)), 2)))
        last = (x, y)
    return goals


def stack_commands(endpoint: str, namespace: str, speed: str) -> dict[str, list[str]]:
    """The service processes' arguments (``python ARGS``) of the whole stack."""
    common = ["--connect", endpoint, "--namespace", namespace]
    return {
        # without localization: the robot's pose is the truth's
        "robot": [
            "-m",
            "aiobt_services.robot",
            "--world",
            "office",
            "--speed",
            speed,
            *TRUTH,
            *common,
        ],
        "planner": ["-m", "aiobt_services.planner", *common],
        "controller": ["-m", "aiobt_services.controller", "--sim-time", *common],
        "behaviors": ["-m", "aiobt_services.behaviors", "--sim-time", *common],
    }


async def wait_up(bus: Bus, names: Sequence[str], timeout: float = 60.0) -> list[str]:  # noqa: ASYNC109
    """The names whose ``nodes/{name}`` token did not appear within ``timeout``."""
    missing = []
    for name in names:
        if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(timeout):
            missing.append(name)
    return missing


class Tracker:
    """The newest robot pose and sim time, read by callbacks (never a backlog)."""

    def __init__(self, bus: Bus) -> None:
        self.pose: PoseStamped | None = None
        self.first_pose = asyncio.Event()
        self.time = 0.0
        bus.subscribe("pose", PoseStamped, self._on_pose, queue_size=1)
        bus.subscribe("clock", Clock, self._on_clock, queue_size=1)

    def _on_pose(self, msg: PoseStamped) -> None:
        self.pose = msg
        self.first_pose.set()

    def _on_clock(self, msg: Clock) -> None:
        self.time = msg.clock


async def plan_and_follow(
    bus: Bus, tracker: Tracker, goal: tuple[float, float, float], patience: float
) -> Outcome:
    """Plan from the robot's pose to ``goal`` and follow the plan; how it ended (a goal
    lost, refused or not answered in ``patience`` s counts as not arrived, with why)."""
    sim0, wall0 = tracker.time, time.monotonic()
    try:
        return await _plan_and_follow(bus, tracker, goal, patience, sim0, wall0)
    except (ActionError, TimeoutError) as exc:
        return _outcome(tracker, goal, (False, -1, -1), sim0, wall0, f"{type(exc).__name__}: {exc}")


def _outcome(
    tracker: Tracker,
    goal: tuple[float, float, float],
    codes: tuple[bool, int, int],
    sim0: float,
    wall0: float,
    message: str = "",
) -> Outcome:
    arrived, plan, follow = codes
    pose = tracker.pose
    distance = math.inf if pose is None else math.hypot(pose.x - goal[0], pose.y - goal[1])
    return Outcome(
        goal, arrived and distance <= ARRIVED_WITHIN, plan, follow, distance,
        tracker.time - sim0, time.monotonic() - wall0, message,
    )  # fmt: skip


async def _plan_and_follow(
    bus: Bus,
    tracker: Tracker,
    goal: tuple[float, float, float],
    patience: float,
    sim0: float,
    wall0: float,
) -> Outcome:

    def outcome(arrived: bool, plan: int, follow: int, message: str = "") -> Outcome:
        return _outcome(tracker, goal, (arrived, plan, follow), sim0, wall0, message)

    here = tracker.pose
    if here is None:
        return outcome(False, -1, -1, "no robot pose")
    planner = bus.action_client("compute_path_to_pose", ComputePathToPose)
    request = ComputePathToPose.Goal(
        goal=PoseStamped.from_xy_yaw(*goal), start=here, use_start=True
    )
    plan = await (await planner.send_goal(request, server_timeout=10.0)).result(timeout=patience)
    if plan.error_code != 0:
        return outcome(False, plan.error_code, -1, plan.error_msg)
    follow = bus.action_client("follow_path", FollowPath)
    sent = await follow.send_goal(FollowPath.Goal(path=plan.path), server_timeout=10.0)
    result = await sent.result(timeout=patience)
    await asyncio.sleep(0.05)  # the newest pose after the stop
    return outcome(result.error_code == 0, 0, result.error_code, result.error_msg)


async def run_goals(
    endpoint: str, speed: str, goals: Sequence[tuple[float, float, float]], patience: float
) -> tuple[list[Outcome], float, str]:
    """A fresh stack at ``speed``; the outcomes, the speed-up achieved, the robot's log."""
    namespace = f"b{uuid.uuid4().hex[:8]}"
    procs = {n: spawn_service(a) for n, a in stack_commands(endpoint, namespace, speed).items()}
    try:
        settings = BusSettings(mode="client", connect=(endpoint,), namespace=namespace)
        async with open_bus(settings) as bus:
            tracker = Tracker(bus)
            missing = await wait_up(bus, list(procs))
            if missing:
                raise RuntimeError(f"not up: {missing}\n{procs[missing[0]].output()}")
            await asyncio.wait_for(tracker.first_pose.wait(), 30.0)
            sim0, wall0 = tracker.time, time.monotonic()
            outcomes = [await plan_and_follow(bus, tracker, g, patience) for g in goals]
            achieved = (tracker.time - sim0) / (time.monotonic() - wall0)
        return outcomes, achieved, procs["robot"].output()
    finally:
        for name, proc in procs.items():
            if not proc.running:
                print(f"--- {name} exited {proc.popen.returncode}:\n{proc.output()[-3000:]}")
            proc.cleanup()


def report(label: str, outcomes: Sequence[Outcome], achieved: float, robot_log: str) -> None:
    arrived = sum(o.arrived for o in outcomes)
    print(f"\n{label}: {arrived} of {len(outcomes)} arrived, speed-up achieved x{achieved:.1f}")
    head = ("goal", "arrived", "plan", "follow", "dist m", "sim s", "wall s")
    print(" ".join(f"{h:>{w}}" for h, w in zip(head, (22, 8, 5, 6, 7, 6, 7), strict=True)))
    for o in outcomes:
        x, y, yaw = o.goal
        print(
            f"{f'({x:.2f}, {y:.2f}, {yaw:.2f})':>22} {o.arrived!s:>8} {o.plan_code:>5} "
            f"{o.follow_code:>6} {o.distance:>7.2f} {o.sim_seconds:>6.1f} {o.wall_seconds:>7.1f}"
            + (f"  {o.message}" if o.message else "")
        )
    timeouts = robot_log.count("no velocity command for")
    lags = [
        line.split(": ", 1)[-1]
        for line in robot_log.splitlines()
        if "simulation behind --speed" in line or "simulation at --speed" in line
    ]
    print(f"robot: {timeouts} command timeout(s), {len(lags)} lag report(s)")
    for line in lags:
        print(f"  {line}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--goals", type=int, default=10)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--speed", default="10")
    parser.add_argument("--baseline", default=None, help="run the goals at this speed first")
    parser.add_argument("--spacing", type=float, default=3.0)
    parser.add_argument("--timeout", type=float, default=120.0, help="wall s per action")
    exit_on_sigterm()
    args = parser.parse_args(argv)
    goals = seeded_goals(load_map(OFFICE), args.goals, args.seed, args.spacing)
    print(f"{len(goals)} goals, seed {args.seed}, office world; load average before: "
          f"{' '.join(f'{v:.2f}' for v in os.getloadavg())}")  # fmt: skip
    with running_router() as (_, endpoint):
        for speed in [s for s in (args.baseline, args.speed) if s is not None]:
            outcomes, achieved, log = asyncio.run(run_goals(endpoint, speed, goals, args.timeout))
            report(f"--speed {speed}", outcomes, achieved, log)
            print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
