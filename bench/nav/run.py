"""20 seeded random reachable goals in the office world, one after another, via the navigator.

Run: ``.venv/bin/python -m bench.nav.run [--goals 20] [--seed 1] [--speed 4]``

Starts a router and the whole stack (robot, planner, controller, behaviors,
navigator: processes on sim time, as the end-to-end tests do), then sends each
goal as a NavigateToPose with the default tree and waits for its end. Per goal:
result, distance driven (the robot's ``pose`` stream), the grid optimum from
where the robot stood (:mod:`bench.nav.goals`), their ratio, sim and wall time,
recoveries (the navigator's feedback). Prints a markdown table and a summary.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import math
import statistics
import time
from dataclasses import dataclass

from aiobt.msgs import NavigateToPose, PoseStamped
from aiobt.testing.bus import exit_on_sigterm
from aiobt.testing.navwatch import NavClient, RobotTrack, navigate
from aiobt.testing.stack import NavStack, StackConfig, running_stack
from aiobt.transport import ActionError, Bus, ServiceError, open_bus

from .goals import Optimum, pick_goals, static_grid

START = (2.0, 9.75)
ARRIVED = 0.3  # m, the goal checker's 0.25 plus the last pose's lag
Goal = tuple[float, float, float]


@dataclass(slots=True)
class Leg:
    goal: Goal
    outcome: str
    error: str
    arrived: bool
    driven: float
    optimum: float
    sim_s: float
    wall_s: float
    recoveries: int

    @property
    def ratio(self) -> float:
        return self.driven / self.optimum if self.optimum > 0 else math.nan


async def run_leg(
    client: NavClient, track: RobotTrack, optimum: Optimum, goal: Goal, limit: float
) -> Leg:
    here = track.latest
    assert here is not None
    best = optimum.length((here.x, here.y), goal[:2])
    track.restart()
    began_wall, began_sim = time.monotonic(), here.stamp
    try:
        done = await navigate(client, PoseStamped.from_xy_yaw(*goal), timeout=limit)
        outcome, error = done.state.name, f"{done.result.error_code} {done.result.error_msg}"
        recoveries = done.recoveries
    except (ActionError, TimeoutError) as exc:
        outcome, error, recoveries = "NO RESULT", f"{type(exc).__name__}: {exc}", 0
        with contextlib.suppress(ActionError, ServiceError, TimeoutError):
            await client.cancel_all(timeout=5.0)  # the next goal starts from a quiet robot
    end = track.latest
    assert end is not None
    arrived = math.hypot(end.x - goal[0], end.y - goal[1]) <= ARRIVED
    return Leg(goal, outcome, error.strip(), arrived, track.driven, best,
               end.stamp - began_sim, time.monotonic() - began_wall, recoveries)  # fmt: skip


async def navigator_client(stack: NavStack, bus: Bus) -> NavClient:
    """The navigator's NavigateToPose client once every service is up (else exits)."""
    await stack.wait_ready(bus, timeout=120.0)
    client = bus.action_client(NavigateToPose.name, NavigateToPose)
    if not await client.wait_for_server(60.0):
        raise SystemExit(f"no navigate_to_pose server:\n{stack.logs()}")
    return client


async def run_all(stack: NavStack, goals: list[Goal], limit: float) -> list[Leg]:
    optimum = Optimum(static_grid())
    async with open_bus(stack.settings()) as bus:
        client = await navigator_client(stack, bus)
        track = RobotTrack(bus)
        try:
            if await track.wait_for(lambda _: True, 30.0) is None:
                raise SystemExit("no pose from the robot")
            legs = []
            for index, goal in enumerate(goals, 1):
                leg = await run_leg(client, track, optimum, goal, limit)
                print(f"goal {index}/{len(goals)} {goal}: {leg.outcome} in {leg.wall_s:.1f} s wall",
                      flush=True)  # fmt: skip
                legs.append(leg)
            return legs
        finally:
            track.close()


HEADER = (
    "| # | goal (x, y, yaw) | result | arrived | driven m | optimum m | ratio | sim s | wall s "
    "| recoveries |\n|---|---|---|---|---|---|---|---|---|---|"
)


def row(index: int, leg: Leg) -> str:
    x, y, yaw = leg.goal
    cells = [
        str(index),
        f"{x:.2f}, {y:.2f}, {yaw:.2f}",
        leg.outcome if leg.outcome == "SUCCEEDED" else f"{leg.outcome} ({leg.error})",
        "yes" if leg.arrived else "no",
        f"{leg.driven:.2f}",
        f"{leg.optimum:.2f}",
        f"{leg.ratio:.3f}",
        f"{leg.sim_s:.1f}",
        f"{leg.wall_s:.1f}",
        str(leg.recoveries),
    ]
    return "| " + " | ".join(cells) + " |"


def summary(legs: list[Leg], speed: float, load: tuple[str, str]) -> str:
    reached = [leg for leg in legs if leg.outcome == "SUCCEEDED" and leg.arrived]
    ratios = [leg.ratio for leg in reached]
    median = statistics.median(ratios) if ratios else math.nan
    sim, wall = sum(leg.sim_s for leg in legs), sum(leg.wall_s for leg in legs)
    return "; ".join(
        [
            f"reached {len(reached)}/{len(legs)} (SUCCEEDED and within {ARRIVED} m)",
            f"driven / grid optimum: median {median:.3f}, max {max(ratios, default=math.nan):.3f}",
            f"recoveries {sum(leg.recoveries for leg in legs)}",
            f"sim {sim:.0f} s in {wall:.0f} s wall ({sim / max(wall, 1e-9):.1f}x, asked {speed}x)",
            f"load average {load[0]} at start, {load[1]} at end",
        ]
    )


def loadavg() -> str:
    with open("/proc/loadavg") as source:
        return " ".join(source.read().split()[:3])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--goals", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--speed", type=float, default=4.0, help="sim speed-up (robot --speed)")
    parser.add_argument("--timeout", type=float, default=240.0, help="wall s per goal")
    exit_on_sigterm()
    args = parser.parse_args()
    goals = pick_goals(static_grid(), START, args.goals, args.seed)
    at_start = loadavg()
    with running_stack(StackConfig(world="office", speed=args.speed, seed=args.seed)) as stack:
        legs = asyncio.run(run_all(stack, goals, args.timeout))
    print(HEADER)
    for index, leg in enumerate(legs, 1):
        print(row(index, leg))
    print("\n" + summary(legs, args.speed, (at_start, loadavg())))


if __name__ == "__main__":
    main()
