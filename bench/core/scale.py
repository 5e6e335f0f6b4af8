"""Many Nav2-shaped trees in one event loop: late ticks and CPU, and wake-up latency.

Run: ``.venv/bin/python -m bench.core.scale [--trees 100 500 1000 2000] [--seconds 3]``

Each of N trees is Nav2's navigation core in shape: a RecoveryNode over a
PipelineSequence of a RateController (1 Hz, over a SUCCESS action standing for
the planner) and a ReactiveSequence of a condition and an async leaf that stays
RUNNING (standing for FollowPath), the recovery branch a SUCCESS action. Every
tree is started at a random phase of the period and ticked at ``--period``
(0.05 s) by one of two drivers, one after the other in the same run:

- ``tick_while_running``: ``tree.tick_while_running(period)`` per tree;
- ``baseline``: a plain loop per tree, ``await tree.tick_once()`` then
  ``await asyncio.sleep(period)`` (no wake-ups: the floor of driving a tree).

After ``--warmup`` seconds the condition leaf stamps every tick for
``--seconds``; an interval between two ticks of one tree more than
``--late-ms`` over the period is late. CPU is the process's CPU time over the
window, in % of one core. Then the wake-up latency: one tree with one async
leaf, ticked by ``tick_while_running(period=1.0)``; the time from the leaf's
awaited future being resolved to ``tick_while_running`` returning SUCCESS
(median and p90 of ``--latency-trials``).

As wall-clock lateness means little on a loaded machine, the CPU cost per
tree tick of both drivers is also measured without wall time: the same N trees
on a ManualClock advanced ``--steps`` periods, the loop run after each until
every tree has ticked; CPU microseconds per tree tick and their ratio.
"""

from __future__ import annotations

import argparse
import asyncio
import itertools
import os
import random
import statistics
import time
from collections.abc import Callable, Coroutine, Sequence
from typing import Any

from aiobt.core.clock import ManualClock
from aiobt.core.leaves import AsyncActionNode, ConditionNode
from aiobt.core.status import SUCCESS, Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import tree_xml

NAV2_SHAPE = tree_xml(
    '<RecoveryNode number_of_retries="6" name="NavigateRecovery">'
    '<PipelineSequence name="NavigateWithReplanning">'
    '<RateController hz="1.0"><AlwaysSuccess name="ComputePathToPose"/></RateController>'
    '<ReactiveSequence name="FollowPathGuarded">'
    '<Stamp name="IsPathValid"/><Forever name="FollowPath"/>'
    "</ReactiveSequence>"
    "</PipelineSequence>"
    '<AlwaysSuccess name="Recoveries"/>'
    "</RecoveryNode>"
)


class Stamp(ConditionNode):
    """SUCCESS; appends perf_counter() to ``stamps`` (a per-tree list) when recording."""

    __slots__ = ("stamps",)
    stamps: list[float] | None

    def check(self) -> bool:
        stamps = self.stamps
        if stamps is not None:
            stamps.append(time.perf_counter())
        return True


class Forever(AsyncActionNode):
    """RUNNING until halted."""

    async def run(self) -> Status:
        await asyncio.get_running_loop().create_future()
        return SUCCESS


class Until(AsyncActionNode):
    """Awaits ``Until.future`` (set per trial), then SUCCESS."""

    future: asyncio.Future[None] | None = None
    started: asyncio.Event | None = None

    async def run(self) -> Status:
        assert Until.future is not None
        assert Until.started is not None
        Until.started.set()
        await Until.future
        return SUCCESS


def _factory() -> BehaviorTreeFactory:
    factory = BehaviorTreeFactory()
    for node in (Stamp, Count, Forever, Until):
        factory.register_node_type(node, node.__name__)
    return factory


Driver = Callable[[Tree, float], Coroutine[Any, Any, Any]]


async def _baseline(tree: Tree, period: float) -> None:
    clock = tree.clock
    while True:
        await tree.tick_once()
        await clock.sleep(period)


async def _while_running(tree: Tree, period: float) -> None:
    await tree.tick_while_running(period)


DRIVERS: dict[str, Driver] = {"tick_while_running": _while_running, "baseline": _baseline}


async def _phased(drive: Driver, tree: Tree, period: float, phase: float) -> None:
    await asyncio.sleep(phase)
    await drive(tree, period)


async def run_many(driver: str, n: int, args: argparse.Namespace) -> tuple[float, float, int]:
    """(% of late intervals, CPU % of a core, intervals) for ``n`` trees."""
    factory, period = _factory(), args.period
    trees = [factory.create_tree_from_text(NAV2_SHAPE) for _ in range(n)]
    stamps: list[list[float]] = [[] for _ in trees]
    stampers = [tree.find("IsPathValid") for tree in trees]
    for stamper in stampers:
        stamper.stamps = None  # type: ignore[attr-defined]
    rng = random.Random(n)
    tasks = [
        asyncio.ensure_future(_phased(DRIVERS[driver], tree, period, rng.uniform(0, period)))
        for tree in trees
    ]
    try:
        await asyncio.sleep(args.warmup)
        for stamper, own in zip(stampers, stamps, strict=True):
            stamper.stamps = own  # type: ignore[attr-defined]
        wall, cpu = time.perf_counter(), time.process_time()
        await asyncio.sleep(args.seconds)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        for stamper in stampers:
            stamper.stamps = None  # type: ignore[attr-defined]
    finally:
        await _stop(tasks, trees)
    limit = period + args.late_ms / 1000
    intervals = [b - a for own in stamps for a, b in itertools.pairwise(own)]
    late = sum(1 for interval in intervals if interval > limit)
    return 100 * late / max(1, len(intervals)), 100 * cpu / wall, len(intervals)


async def _stop(tasks: Sequence[asyncio.Future[Any]], trees: list[Tree]) -> None:
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    for tree in trees:
        await tree.halt_tree("bench done")


class Count(ConditionNode):
    """SUCCESS; counts its ticks, sets ``Count.reached`` at ``Count.target`` ticks."""

    ticks = 0
    target = 0
    reached: asyncio.Event | None = None

    def check(self) -> bool:
        Count.ticks += 1
        if Count.ticks >= Count.target and Count.reached is not None:
            Count.reached.set()
        return True


async def cost_per_tick(driver: str, n: int, steps: int, period: float) -> float:
    """CPU microseconds per tree tick, ``n`` trees on a ManualClock advanced ``steps`` times.

    No wall time: each step moves the clock one period and runs the loop until
    every tree has ticked, so other processes on the machine change little.
    """
    clock = ManualClock()
    factory = _factory()
    xml = NAV2_SHAPE.replace('<Stamp name="IsPathValid"/>', '<Count name="IsPathValid"/>')
    trees = [factory.create_tree_from_text(xml, clock=clock) for _ in range(n)]
    drive = DRIVERS[driver]
    tasks = [asyncio.ensure_future(drive(tree, period)) for tree in trees]
    try:
        await _all_ticked(n)
        cpu = time.process_time()
        for _ in range(steps):
            clock.advance(period)
            await _all_ticked(n)
        cpu = time.process_time() - cpu
    finally:
        await _stop(tasks, trees)
    return cpu / (n * steps) * 1e6


async def _all_ticked(n: int) -> None:
    Count.ticks, Count.target, Count.reached = 0, n, asyncio.Event()
    await asyncio.wait_for(Count.reached.wait(), 60.0)


async def wake_latency(trials: int) -> list[float]:
    """Seconds from an async leaf's future resolved to tick_while_running's SUCCESS."""
    factory = _factory()
    tree = factory.create_tree_from_text(tree_xml("<Until/>"))
    latencies = []
    for _ in range(trials):
        Until.future = asyncio.get_running_loop().create_future()
        Until.started = asyncio.Event()
        ticking = asyncio.ensure_future(tree.tick_while_running(period=1.0))
        await asyncio.wait_for(Until.started.wait(), 5.0)
        for _ in range(3):  # let the tree park in its wait
            await asyncio.sleep(0)
        start = time.perf_counter()
        Until.future.set_result(None)
        status = await asyncio.wait_for(ticking, 5.0)
        latencies.append(time.perf_counter() - start)
        assert status is SUCCESS, status
    return latencies


async def main(args: argparse.Namespace) -> None:
    print(f"load average {os.getloadavg()}, period {args.period} s, late = > +{args.late_ms} ms")
    print("| trees | driver | late ticks % | CPU % of a core | intervals |")
    print("|---|---|---|---|---|")
    for n in args.trees:
        for driver in DRIVERS:
            late, cpu, count = await run_many(driver, n, args)
            print(f"| {n} | {driver} | {late:.2f} | {cpu:.0f} | {count} |", flush=True)
    print("\nCPU per tree tick on a ManualClock (no wall time), us:")
    print("| trees | tick_while_running | baseline | ratio |")
    print("|---|---|---|---|")
    for n in args.trees:
        costs = [await cost_per_tick(d, n, args.steps, args.period) for d in DRIVERS]
        print(f"| {n} | {costs[0]:.1f} | {costs[1]:.1f} | {costs[0] / costs[1]:.2f} |", flush=True)
    latencies = sorted(await wake_latency(args.latency_trials))
    p90 = latencies[int(0.9 * (len(latencies) - 1))]
    print(
        f"wake-up latency (leaf done -> tick_while_running returns): median "
        f"{statistics.median(latencies) * 1e6:.0f} us, p90 {p90 * 1e6:.0f} us "
        f"({len(latencies)} trials)"
    )
    print(f"load average {os.getloadavg()}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trees", type=int, nargs="+", default=[100, 500, 1000, 2000])
    parser.add_argument("--period", type=float, default=0.05)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--warmup", type=float, default=1.0)
    parser.add_argument("--late-ms", type=float, default=5.0)
    parser.add_argument("--steps", type=int, default=40)
    parser.add_argument("--latency-trials", type=int, default=200)
    asyncio.run(main(parser.parse_args()))
