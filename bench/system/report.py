"""The running system's speed in one run: the whole stack up at a sim speed-up.

Run: ``.venv/bin/python -m bench.system.report --speed 10``

Starts a router and the stack (robot at ``--speed``, localization, planner, controller,
behaviors, navigator, and the safety chain (velocity smoother, collision monitor) as
``aiobt up`` runs it unless ``--no-safety-chain``; processes as the end-to-end tests run
them; ``--no-localization``: the robot's stand-in pose, the truth, in localization's
stead: the same-session baseline for what localization costs) and measures:

- CPU of each process (router included) in % of one core, from ``/proc/<pid>/stat``,
  over an idle phase (robot standing, ``--idle`` wall s) and over the driving phase, and
  the stack's processes summed (the bench's own client left out; the planner serves the
  probe below: at ``--probe-period 1`` it plans as often as a navigator replanning at
  Nav2's 1 Hz, what a user's stack does);
- the driving phase: ``--goals`` seeded reachable goals, each planned (ComputePathToPose)
  and followed (FollowPath), while a client sends ComputePathToPose from the robot's pose
  every ``--probe-period`` s: the planner's round trip over Zenoh (p50/p99/max, wall;
  and the first trip, at the drive's start after the idle phase, against the slowest
  of the others).
  The planner serves one goal at a time (a newer aborts the older), so the driving
  goes straight to planner and controller, not through the navigator's replanning
  tree (it would be aborted by the probe); the navigator is up, and drives the
  reaction runs;
- the controller's cycle time, achieved rate and slots served (its per-goal log lines);
- the sim speed-up achieved (``{ns}/clock`` vs wall) in both phases, vs asked, and the
  sim time the robot gave up to lag (its pacing reports);
- ``--reactions`` times: a box spawned ahead of the driving robot, sim and wall
  seconds until the first ``cmd_vel`` under half the speed commanded before.

Prints one table (markdown) with the load average before and after; ``--logs DIR``
keeps each process's output there (``controller.log``, ``robot.log``, ...).
``--realtime``: the robot, the controller, the planner, the navigator and the router
run with ``--realtime-priority`` (Nav2's ``use_realtime_priority``; SCHED_FIFO, so
root or CAP_SYS_NICE), and so does this client at the navigator's level: it asks for the
plans and paths in the navigator's stead. ``--priority NAME=N`` (repeatable) gives
one of the services level N instead of its default. ``--clock-hz HZ``: the robot's
``{ns}/clock`` at that rate (its ``--clock-hz``): what fewer stamps give the processes
that follow them (each sleeper then wakes on that grid). ``--clock``: the services on
the simulation's clock (``sim``, the default: as the end-to-end tests run them), on the
wall clock (``wall``: as ``aiobt up`` runs them at 1x, and as on hardware, where there
is no simulation's clock), or as ``aiobt up`` chooses at ``--speed`` (``auto``).

The table's "rest of the machine" row is every other process's CPU (each one's
``/proc/<pid>/stat``) and the CPU stolen by the hypervisor (``/proc/stat``): what the
stack competed with. ``--busy N`` makes that competition known: N processes, each
spinning on a core at ordinary priority for the whole run, stand in for a machine
with other work (a build, a browser, another robot's stack).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import math
import os
import re
import statistics
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

from aiobt.msgs import FollowPath, NavigateToPose, PoseStamped
from aiobt.system.catalog import realtime_priority
from aiobt.system.heap import settle
from aiobt.system.lifeline import popen_bound
from aiobt.system.realtime import raise_priority
from aiobt.testing.bus import exit_on_sigterm, start_router
from aiobt.testing.navwatch import NavClient, start_navigation
from aiobt.testing.stack import SERVICES, NavStack, StackConfig
from aiobt.transport import ActionError, Bus, ServiceError, open_bus

from ..nav.goals import pick_goals, static_grid
from ..nav.run import START, loadavg
from .probes import Commands, PlannerProbe, Refused, RobotPose, SimClock, percentile, reaction
from .procstat import machine, others_percent, percent_of_core, sample

CYCLES = re.compile(
    r"(\d+) cycles, rate ([\d.]+|nan) of ([\d.]+) Hz, cycle p50 ([\d.]+) ms "
    r"p99 ([\d.]+) ms max ([\d.]+) ms.*?slots lost (\d+)"
)
# the robot's pacing report (every 5 s of wall time in which it fell behind or waited)
LAG = re.compile(r"fell more than [\d.]+ s behind (\d+) time\(s\), ([\d.]+) s of sim time given up")
HOLDS = re.compile(r"waited (\d+) time\(s\), ([\d.]+) s in all, for a late cmd_vel")
Goal = tuple[float, float, float]
REALTIME = ("robot", "localization", "controller", "planner", "navigator")  # ``--realtime`` raises

NAVIGATOR_PRIORITY = realtime_priority("navigator")
CLIENT = "bench client"  # this process: the instrument, not the stack


@dataclass
class Figures:
    cpu_idle: dict[str, float] = field(default_factory=dict)
    cpu_driving: dict[str, float] = field(default_factory=dict)
    # the rest of the machine (other processes, stolen), % of a core: idle, driving
    others: list[tuple[float, float]] = field(default_factory=list)
    speed_idle: float = math.nan
    speed_driving: float = math.nan
    round_trips: list[float] = field(default_factory=list)
    planning_times: list[float] = field(default_factory=list)  # the planner's own, wall s
    probe_failures: list[str] = field(default_factory=list)
    reached: int = 0
    goals: int = 0
    reactions: list[tuple[float, float] | None] = field(default_factory=list)
    # per goal: cycles, rate and configured rate (Hz), cycle p99 and max (ms), slots lost
    controller: list[tuple[int, float, float, float, float, int]] = field(default_factory=list)
    robot_log: str = ""  # the robot's output: its pacing reports


async def drive(bus: Bus, probe: PlannerProbe, goals: list[Goal], limit: float) -> int:
    """Plan (through the probe's lock) and follow each goal; how many were reached."""
    follow = bus.action_client(FollowPath.name, FollowPath)
    reached = 0
    for goal in goals:
        try:
            plan, _ = await probe.plan(await probe.robot.read(), goal)
            if plan.error_code != 0:
                print(f"goal {goal}: plan {plan.error_code} {plan.error_msg}", flush=True)
                continue
            sent = await follow.send_goal(FollowPath.Goal(path=plan.path), server_timeout=10.0)
            result = await sent.result(timeout=limit)
            reached += result.error_code == 0
            print(f"goal {goal}: follow {result.error_code} {result.error_msg}".strip(), flush=True)
        except (ActionError, TimeoutError) as exc:
            print(f"goal {goal}: {type(exc).__name__}: {exc}", flush=True)
            with contextlib.suppress(ActionError, ServiceError, TimeoutError):
                await follow.cancel_all(timeout=5.0)
    return reached


async def react(
    bus: Bus, client: NavClient, track: RobotPose, goals: list[Goal], figures: Figures,
    clock: SimClock, count: int,
) -> None:  # fmt: skip
    """``count`` times: drive to the farthest goal, drop a box ahead once cruising."""
    if count <= 0:
        return
    commands = Commands(bus)
    try:
        for _ in range(count):
            await react_once(bus, client, track, goals, figures, clock, commands)
    finally:
        commands.close()


async def react_once(
    bus: Bus, client: NavClient, track: RobotPose, goals: list[Goal], figures: Figures,
    clock: SimClock, commands: Commands,
) -> None:  # fmt: skip
    """Drive to the farthest goal, drop a box ahead once cruising; stop and settle."""
    here = await track.read()
    far = max(goals, key=lambda g: math.hypot(g[0] - here.x, g[1] - here.y))
    running = await start_navigation(client, PoseStamped.from_xy_yaw(*far))
    result = None
    for _ in range(10):  # until the box is accepted (not in a wall) while cruising
        if await commands.first(lambda c: c.linear.x > 0.2, 60.0) is None:
            break
        pose = await track.read()
        try:
            result = await reaction(
                bus, clock, commands, PoseStamped.from_xy_yaw(pose.x, pose.y, pose.yaw), 0.9
            )
            break
        except Refused as exc:
            print(f"reaction: {exc}; trying further on", flush=True)
    figures.reactions.append(result)
    with contextlib.suppress(ActionError, ServiceError, TimeoutError):
        await running.goal.cancel(timeout=10.0)
    await track.wait_still(0.5, 30.0)


async def measure(stack: NavStack, router_pid: int, args: argparse.Namespace) -> Figures:
    figures = Figures()
    goals = pick_goals(static_grid(), START, args.goals, args.seed)
    pids = {"router": router_pid, **{n: p.pid for n, p in stack.processes.items()}}
    pids[CLIENT] = os.getpid()  # the instrument's own cost, on the same 2 cores
    if args.realtime:  # before the bus: its threads too; after the stack's processes started
        raise_priority(NAVIGATOR_PRIORITY)
    async with open_bus(stack.settings()) as bus:
        await stack.wait_ready(bus, timeout=120.0)
        settle()  # the instrument's own collector passes (17-117 ms) out of its figures
        client = bus.action_client(NavigateToPose.name, NavigateToPose)
        if not await client.wait_for_server(60.0):
            raise SystemExit(f"no navigate_to_pose server:\n{stack.logs()}")
        track, clock = RobotPose(bus), SimClock(bus)
        probe = PlannerProbe(bus, track, goals, args.probe_period)
        if await track.wait_for(lambda _: True, 30.0) is None:
            raise SystemExit("no pose from the robot")
        await asyncio.sleep(2.0)  # the services' start-up work done
        first, whole, mark = sample(pids), machine(), await clock.mark()
        await asyncio.sleep(args.idle)  # the idle phase: its length is the measurement
        figures.cpu_idle = percent_of_core(first, sample(pids))
        figures.others.append(others_percent(whole, machine(), pids.values()))
        figures.speed_idle = await clock.factor_since(mark)
        stop = asyncio.Event()
        first, whole, mark = sample(pids), machine(), await clock.mark()
        prober = asyncio.create_task(probe.run(stop))
        figures.reached = await drive(bus, probe, goals, args.timeout)
        stop.set()
        await prober
        figures.cpu_driving = percent_of_core(first, sample(pids))
        figures.others.append(others_percent(whole, machine(), pids.values()))
        figures.speed_driving = await clock.factor_since(mark)
        figures.goals = len(goals)
        figures.round_trips, figures.probe_failures = probe.round_trips, probe.failures
        figures.planning_times = probe.planning_times
        await react(bus, client, track, goals, figures, clock, args.reactions)
    figures.controller = [
        (int(m[0]), float(m[1]), float(m[2]), float(m[4]), float(m[5]), int(m[6]))
        for m in CYCLES.findall(stack.processes["controller"].output())
    ]
    figures.robot_log = stack.processes["robot"].output()
    if args.logs is not None:
        keep_logs(stack, args.logs)
    return figures


def keep_logs(stack: NavStack, folder: Path) -> None:
    """Each process's output as ``folder/<name>.log`` (the controller's goal lines name
    the sleep before each slot lost; the robot's, its pacing)."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, process in stack.processes.items():
        (folder / f"{name}.log").write_text(process.output())


def row(*cells: object) -> str:
    return "| " + " | ".join(str(c) for c in cells) + " |"


def ms(seconds: float) -> str:
    return f"{seconds * 1e3:.1f}"


def summed_row(figures: Figures, probe_period: float, speed: float) -> str:
    """The stack's processes (router included) summed, the bench's client left out; and
    the same over the sim time achieved (at the speed-up asked): a sim that fell behind
    on a loaded machine did less work a wall second, which this puts back."""
    stack = [name for name in figures.cpu_idle if name != CLIENT]
    idle = sum(figures.cpu_idle[name] for name in stack)
    busy = sum(figures.cpu_driving.get(name, math.nan) for name in stack)
    label = (
        f"CPU the stack summed % of a core: idle / driving ({len(stack)} processes, "
        f"a plan every {probe_period:g} s); the same per sim time at x{speed:g}"
    )
    scaled = f"{idle * speed / figures.speed_idle:.1f} / {busy * speed / figures.speed_driving:.1f}"
    return row(label, f"{idle:.1f} / {busy:.1f}; {scaled}", "")


def others_row(others: list[tuple[float, float]]) -> str:
    """The rest of the machine in both phases: other processes' CPU, and stolen."""
    if len(others) != 2:
        return row("CPU the rest of the machine", "n/a", "")
    (idle, idle_stolen), (busy, busy_stolen) = others
    value = f"{idle:.1f} / {busy:.1f}; stolen {idle_stolen:.1f} / {busy_stolen:.1f}"
    return row("CPU the rest of the machine % of a core: idle / driving; stolen", value, "")


def planner_rows(figures: Figures) -> list[str]:
    """The round trip's spread, and its first trip (the drive's start, after the idle
    phase) against the slowest of the others: with ~50 trips the p99 is the slowest; and
    the planner's own time (``planning_time``: taking the goal to its result, searches
    waited for included), so the rest of a slow trip is the way there and back."""
    trips, failed = figures.round_trips, len(figures.probe_failures)
    spread = [ms(percentile(trips, q)) for q in (50, 99, 100)]
    label = f"planner round trip ms p50 / p99 / max (n={len(trips)}, failed {failed})"
    first = f"{ms(trips[0])} / {ms(max(trips[1:]))}" if len(trips) > 1 else "n/a"
    own = figures.planning_times
    inside = " / ".join(ms(percentile(own, q)) for q in (50, 99, 100)) if own else "n/a"
    return [
        row(label, " / ".join(spread), "p99 < 50"),
        row("planner round trip ms: the first / the slowest of the others", first, ""),
        row("of which in the planner (planning_time) ms p50 / p99 / max", inside, ""),
    ]


def controller_rows(goals: list[tuple[int, float, float, float, float, int]]) -> list[str]:
    """The rate achieved (cycles per robot second from the first cycle's start to the
    last's; per goal, and pooled: :func:`pooled_rate`) and the slots served (cycles /
    (cycles + slots lost), a slot lost when a cycle began two or more periods after the
    one before), per goal. Over a goal of a dozen
    cycles the rate also holds how late its last cycle began (at 10x up to one batch of
    the robot's clock, 40 ms: 7 % of 11 periods); the slots served do not."""
    if not goals:
        return [row("controller cycle statistics", "none logged", "")]
    rates = [r / c for _, r, c, *_ in goals if math.isfinite(r) and c > 0]
    pooled = pooled_rate(goals)
    served = [n / (n + lost) for n, *_, lost in goals if n > 0]
    p99s, worst = [g[3] for g in goals], max(g[4] for g in goals)
    cycles = sum(n for n, *_ in goals)
    achieved = f"{statistics.median(rates):.1%}, {min(rates):.1%}; {pooled:.1%}" if rates else "n/a"
    label = (
        f"controller rate achieved / configured, {len(goals)} goals, {cycles} cycles: median, "
        "min; all goals pooled"
    )
    slots = f"{statistics.median(served):.1%}, {min(served):.1%}" if served else "n/a"
    p99 = f"{statistics.median(p99s):.2f}, {max(p99s):.2f}; {worst:.2f}"
    return [
        row(label, achieved, ">= 95 %"),
        row("controller slots served (cycles / cycles + slots lost): median, min", slots, ""),
        row("controller cycle p99 ms: median goal, worst goal; max", p99, "p99 < 10"),
    ]


def pooled_rate(goals: list[tuple[int, float, float, float, float, int]]) -> float:
    """All goals' intervals over all their robot time, against the configured rate: a goal
    of a few cycles (a reaction's last, cancelled) weighs by its few intervals, where in the
    per-goal figures one late cycle of a two-cycle goal reads as a rate of 70 %."""
    spans = [((n - 1) / r, n - 1, c) for n, r, c, *_ in goals if n > 1 and r > 0 and c > 0]
    time = sum(span for span, _, _ in spans)
    if not time > 0.0:
        return math.nan
    return sum(intervals / c for _, intervals, c in spans) / time


def pacing_row(robot_log: str) -> str:
    """The sim time the robot gave up to lag and the waits for a late command, summed
    over its pacing reports (each on 5 s of wall time; the run's last seconds may be
    missing)."""
    lags = [(int(n), float(s)) for n, s in LAG.findall(robot_log)]
    holds = [(int(n), float(s)) for n, s in HOLDS.findall(robot_log)]
    value = (
        f"{sum(s for _, s in lags):.2f} s in {sum(n for n, _ in lags)} / "
        f"{sum(n for n, _ in holds)}, {sum(s for _, s in holds):.2f} wall s"
    )
    return row("robot: sim time given up to lag, times / waits for a late cmd_vel", value, "")


def table(figures: Figures, speed: float, probe_period: float) -> list[str]:
    lines = [row("figure", "value", "target"), row("---", "---", "---")]
    for name, idle in figures.cpu_idle.items():
        busy = figures.cpu_driving.get(name, math.nan)
        target = "idle < 2 %" if name not in ("robot", "router", CLIENT) else ""
        lines.append(
            row(f"CPU {name} % of a core: idle / driving", f"{idle:.1f} / {busy:.1f}", target)
        )
    lines.append(summed_row(figures, probe_period, speed))
    lines.append(others_row(figures.others))
    lines.extend(planner_rows(figures))
    lines.extend(controller_rows(figures.controller))
    achieved = f"{figures.speed_idle:.2f} / {figures.speed_driving:.2f}"
    lines.append(
        row(f"sim speed-up idle / driving (asked {speed:g})", achieved, f">= {0.9 * speed:g}")
    )
    lines.append(pacing_row(figures.robot_log))
    lines.append(row("goals reached", f"{figures.reached} / {figures.goals}", ""))
    done = [r for r in figures.reactions if r is not None]
    label = (
        f"reaction box -> cmd_vel slows, sim s / wall s ({len(done)} of {len(figures.reactions)})"
    )
    values = ", ".join(f"{sim:.2f} / {wall:.2f}" for sim, wall in done) or "n/a"
    lines.append(row(label, values, ""))
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--speed", type=float, default=10.0, help="sim speed-up (robot --speed)")
    parser.add_argument("--goals", type=int, default=6)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--idle", type=float, default=10.0, help="wall s of the idle phase")
    parser.add_argument(
        "--probe-period",
        type=float,
        default=0.25,
        help="wall s between the probe's plans (1: a navigator replanning at Nav2's 1 Hz)",
    )
    parser.add_argument(
        "--safety-chain",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="the velocity smoother and the collision monitor, as `aiobt up` runs them",
    )
    parser.add_argument(
        "--localization",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="the localization service in the loop (the default, as `aiobt up`); "
        "--no-localization: the robot's stand-in pose instead (--pose-source truth), the "
        "same-session baseline for what localization costs the running stack",
    )
    parser.add_argument("--reactions", type=int, default=3)
    parser.add_argument(
        "--clock",
        dest="sim_time",
        choices=("sim", "wall", "auto"),
        default="sim",
        type=str,
        help="the services' time: the simulation's clock (sim, the default), the wall "
        "clock (wall), or as `aiobt up` chooses (auto: sim time unless --speed is 1)",
    )
    parser.add_argument(
        "--clock-hz",
        type=float,
        help="the robot's {ns}/clock rate in Hz of sim time (its --clock-hz; default: its own)",
    )
    parser.add_argument("--timeout", type=float, default=120.0, help="wall s per goal")
    parser.add_argument("--logs", type=Path, help="keep each process's output here")
    parser.add_argument(
        "--realtime",
        action="store_true",
        help="robot, controller, planner, navigator and router with --realtime-priority "
        "(SCHED_FIFO at each one's default: 90, 90, 70, 60, 60; see aiobt.system.realtime), "
        "and this client at the navigator's level",
    )
    parser.add_argument(
        "--busy",
        type=int,
        default=0,
        metavar="N",
        help="N other processes spinning at ordinary priority for the whole run (default: 0)",
    )
    parser.add_argument(
        "--priority",
        action="append",
        default=[],
        metavar="NAME=N",
        help=f"with --realtime: service NAME ({', '.join(REALTIME)}) at level N, not its default",
    )
    exit_on_sigterm()
    args = parser.parse_args(argv)
    args.sim_time = {"sim": True, "wall": False, "auto": None}[args.sim_time]
    if not args.probe_period > 0.0:
        parser.error(f"--probe-period must be > 0 s, got {args.probe_period}")
    if args.busy < 0:
        parser.error(f"--busy must be 0 or more processes, got {args.busy}")
    try:
        levels = priorities(args.priority)
    except ValueError as exc:
        parser.error(str(exc))
    if levels and not args.realtime:
        parser.error("--priority needs --realtime")
    before = loadavg()
    config = stack_config(args, levels)
    spinners = [spin() for _ in range(args.busy)]
    try:
        router_args = ["--lease-ms", str(config.lease_ms)]
        router_args += ["--realtime-priority"] if args.realtime else []
        router, endpoint = start_router(extra_args=router_args, timeout=60.0)
        try:
            with NavStack.launch(endpoint, config) as stack:
                figures = asyncio.run(measure(stack, router.pid, args))
        finally:
            router.cleanup()
    finally:
        for spinner in spinners:
            spinner.kill()
            spinner.wait(timeout=10.0)
    if args.realtime:
        named = ", ".join(f"{n} {levels[n]}" if n in levels else n for n in (*REALTIME, "router"))
        print(f"real-time priority (SCHED_FIFO): {named}; this client {NAVIGATOR_PRIORITY}\n")
    if args.busy:
        print(f"{args.busy} other process(es) spinning at ordinary priority (--busy)\n")
    clock = "the simulation's clock" if config.uses_sim_time else "the wall clock"
    print(f"the services on {clock} (--clock)\n")
    if not args.localization:
        print("no localization: the robot's stand-in pose, the truth (--no-localization)\n")
    print("\n".join(table(figures, args.speed, args.probe_period)))
    print(f"\nload average before: {before}; after: {loadavg()}")
    for failure in sorted(set(figures.probe_failures))[:5]:
        print(f"planner probe failure: {failure}")
    return 0


def stack_config(args: argparse.Namespace, levels: dict[str, int]) -> StackConfig:
    """The stack the options ask for (``levels``: :func:`priorities` of ``--priority``)."""
    extra = {name: ["--realtime-priority"] for name in REALTIME} if args.realtime else {}
    extra.update({name: ["--realtime-priority", str(level)] for name, level in levels.items()})
    robot = ["--clock-hz", str(args.clock_hz)] if args.clock_hz is not None else []
    services = SERVICES
    if not args.localization:  # the robot's stand-in: the truth on {ns}/pose
        robot += ["--pose-source", "truth"]
        services = tuple(name for name in SERVICES if name != "localization")
        extra.pop("localization", None)
    if robot:
        extra["robot"] = [*extra.get("robot", []), *robot]
    return StackConfig(
        world="office", speed=args.speed, seed=args.seed, extra=extra, services=services,
        safety_chain=args.safety_chain, sim_time=args.sim_time,
    )  # fmt: skip


def priorities(given: list[str]) -> dict[str, int]:
    """``--priority NAME=N`` values: each a service ``--realtime`` raises, at 1-99."""
    levels: dict[str, int] = {}
    for text in given:
        name, _, level = text.partition("=")
        if name not in REALTIME:
            raise ValueError(f"--priority {text!r}: NAME must be one of {', '.join(REALTIME)}")
        if not (level.isdigit() and 1 <= int(level) <= 99):
            raise ValueError(f"--priority {text!r}: N must be a SCHED_FIFO level, 1 to 99")
        levels[name] = int(level)
    return levels


def spin() -> subprocess.Popen[bytes]:
    """A process that spins on a core at ordinary priority until killed (``--busy``)."""
    return popen_bound([sys.executable, "-c", "while True: pass"])


if __name__ == "__main__":
    raise SystemExit(main())
