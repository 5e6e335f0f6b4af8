"""Localization in the loop of navigation: seeded goals through the navigator with the
robot publishing no pose in map (``--pose-source none``) and the localization service
giving ``{ns}/pose``; its error against the simulation's truth, its CPU, its update
cost and the scans it dropped.

Run: ``.venv/bin/python -m bench.localization.nav_track [--goals 20] [--seed 1]
[--speed 4] [--params sim_robot|nav2]``

``--params nav2``: Nav2's defaults throughout; ``sim_robot``: the shipped params file
for the simulated robot (``services/localization/config/sim_robot.yaml``).
"""

from __future__ import annotations

import argparse
import asyncio

from aiobt.msgs import Empty, NavigateToPose
from aiobt.testing.bus import exit_on_sigterm
from aiobt.testing.navwatch import RobotTrack
from aiobt.testing.stack import NavStack, StackConfig, running_stack
from aiobt.transport import open_bus
from aiobt_services.localization.messages import LocalizationStats
from bench.nav.goals import Optimum, pick_goals, static_grid
from bench.nav.run import HEADER, START, Leg, loadavg, row, run_leg, summary
from bench.system.procstat import percent_of_core, sample
from bench.system.report import REALTIME

from .tracking import Tracking


def config(
    speed: float, seed: int, params: str, sets: list[str], realtime: bool = False
) -> StackConfig:
    """The stack (localization in it, the robot with no pose in map) with these AMCL
    params: a shipped params file's name (``nav2``: Nav2's defaults) or a path;
    ``realtime``: the services ``bench.system.report --realtime`` raises, raised."""
    extra = {name: ["--realtime-priority"] for name in REALTIME} if realtime else {}
    flags = ["--params-file", params]
    for item in sets:
        flags += ["--set", item]
    extra["localization"] = [*extra.get("localization", []), *flags]
    return StackConfig(world="office", speed=speed, seed=seed, extra=extra)


async def run(stack: NavStack, goals: list[tuple[float, float, float]], limit: float) -> None:
    optimum = Optimum(static_grid())
    async with open_bus(stack.settings()) as bus:
        await stack.wait_ready(bus, timeout=120.0)
        client = bus.action_client(NavigateToPose.name, NavigateToPose)
        if not await client.wait_for_server(60.0):
            raise SystemExit(f"no navigate_to_pose server:\n{stack.logs()}")
        track, tracking = RobotTrack(bus), Tracking()
        tracking.attach(bus)
        if await track.wait_for(lambda _: True, 60.0) is None:
            raise SystemExit(f"no pose from localization:\n{stack.logs()}")
        pid = {"localization": stack.processes["localization"].pid}
        first, legs = sample(pid), []
        for index, goal in enumerate(goals, 1):
            leg = await run_leg(client, track, optimum, goal, limit)
            print(
                f"goal {index}/{len(goals)}: {leg.outcome} in {leg.wall_s:.1f} s wall", flush=True
            )
            legs.append(leg)
        cpu = percent_of_core(first, sample(pid))["localization"]
        stats = await bus.call("localization/stats", Empty(), LocalizationStats, timeout=10.0)
        track.close()
        report(legs, tracking, cpu, stats, stack.config.speed)


def report(
    legs: list[Leg], tracking: Tracking, cpu: float, s: LocalizationStats, speed: float
) -> None:
    print(HEADER)
    for index, leg in enumerate(legs, 1):
        print(row(index, leg))
    print("\n" + summary(legs, speed, (loadavg(), loadavg())))
    print(f"\ntracking: {tracking.errors().line()}")
    sim_s = sum(leg.sim_s for leg in legs)
    print(f"localization: {cpu:.1f} % of a core over the goals; {s.scans} scans read "
          f"({s.scans / max(sim_s, 1e-9):.1f} per sim s), {s.dropped} dropped unread, "
          f"{s.skipped_no_odom} without odometry; {s.updates} updates, CPU per update "
          f"p50 {s.update_ms_p50:.2f} ms, p99 {s.update_ms_p99:.2f} ms, max "
          f"{s.update_ms_max:.2f} ms; update latency (scan read -> outputs sent, wall) p50 "
          f"{s.latency_ms_p50:.2f} ms, p99 {s.latency_ms_p99:.2f} ms; {s.particles} particles "
          "at the end")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--goals", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--speed", type=float, default=4.0)
    parser.add_argument("--params", default="sim_robot", help="sim_robot, nav2, or a YAML path")
    parser.add_argument("--timeout", type=float, default=240.0, help="wall s per goal")
    parser.add_argument(
        "--set", action="append", default=[], metavar="NAME=VALUE",
        help="an AMCL parameter for the service, e.g. min_particles=2000 (repeatable)",
    )  # fmt: skip
    parser.add_argument(
        "--realtime", action="store_true",
        help="the robot, localization, controller, planner and navigator under SCHED_FIFO "
        "(--realtime-priority; root or CAP_SYS_NICE)",
    )  # fmt: skip
    exit_on_sigterm()
    args = parser.parse_args()
    goals = pick_goals(static_grid(), START, args.goals, args.seed)
    print(f"load average at start: {loadavg()}")
    stack_config = config(args.speed, args.seed, args.params, args.set, args.realtime)
    with running_stack(stack_config) as stack:
        asyncio.run(run(stack, goals, args.timeout))


if __name__ == "__main__":
    main()
