"""Tick cost of aiobt against py_trees, BehaviorTree.CPP with Python leaves,
and the await floor, on four tree shapes, in one run.

Run: ``.venv/bin/python -m bench.core.ticks [--rounds 9] [--batch-ms 40]``

1. Counting pass: every runtime ticks a counting build of each shape (after
   two warm-up ticks, so RUNNING shapes are in their steady state) and the
   bench checks that all visit the same leaves and, where countable, the same
   inner nodes per tree tick. The node-tick count per tree tick comes from it.
2. Timing: per round, every (shape, runtime) pair ticks a batch sized to
   ``--batch-ms``; the order of runtimes rotates each round. Reported figures
   are medians over rounds: ns per node-tick and tree ticks per second, with
   ratios taken within this run.
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import statistics
import sys
import time
from collections.abc import Callable
from typing import Any

from bench.core.libs import ASYNC, BUILDERS, COUNTER, aiobt_inner_counted
from bench.core.shapes import SHAPES

LIBS = tuple(BUILDERS)
Tick = Callable[[], Any]


async def tick_n(lib: str, tick: Tick, n: int) -> float:
    """Seconds for ``n`` tree ticks."""
    gc.collect()
    if lib in ASYNC:
        start = time.perf_counter()
        for _ in range(n):
            await tick()
        return time.perf_counter() - start
    start = time.perf_counter()
    for _ in range(n):
        tick()
    return time.perf_counter() - start


async def count_visits(shape: str) -> dict[str, tuple[int, int]]:
    """(leaves, inner nodes) ticked in one steady-state tree tick, per runtime."""
    visits = {}
    for lib in LIBS:
        tick = BUILDERS[lib](SHAPES[shape](), True)
        with aiobt_inner_counted():
            for _ in range(2):
                await tick_n(lib, tick, 1)
            COUNTER.leaves = COUNTER.nodes = 0
            await tick_n(lib, tick, 1)
        visits[lib] = (COUNTER.leaves, COUNTER.nodes)
    return visits


def check_visits(shape: str, visits: dict[str, tuple[int, int]]) -> int:
    """Node-ticks per tree tick; exits if the runtimes disagree."""
    leaves = {lib: v[0] for lib, v in visits.items()}
    inner = {lib: v[1] for lib, v in visits.items() if lib != "btcpp"}  # not countable there
    if len(set(leaves.values())) != 1 or len(set(inner.values())) != 1:
        sys.exit(f"{shape}: runtimes tick different nodes: {visits}")
    return leaves["floor"] + inner["floor"]


async def calibrate(lib: str, tick: Tick, batch_s: float) -> int:
    await tick_n(lib, tick, 3)  # warm up, reach the steady state
    n = 1
    while (elapsed := await tick_n(lib, tick, n)) < batch_s / 10:
        n *= 4
    return max(1, round(n * batch_s / elapsed))


async def measure(rounds: int, batch_s: float) -> dict[str, dict[str, list[float]]]:
    ticks = {(s, lib): BUILDERS[lib](SHAPES[s](), False) for s in SHAPES for lib in LIBS}
    sizes = {key: await calibrate(key[1], tick, batch_s) for key, tick in ticks.items()}
    per_tick: dict[str, dict[str, list[float]]] = {s: {lib: [] for lib in LIBS} for s in SHAPES}
    for r in range(rounds):
        order = LIBS[r % len(LIBS) :] + LIBS[: r % len(LIBS)]
        for shape in SHAPES:
            for lib in order:
                n = sizes[shape, lib]
                per_tick[shape][lib].append(await tick_n(lib, ticks[shape, lib], n) / n)
    return per_tick


def report(per_tick: dict[str, dict[str, list[float]]], node_ticks: dict[str, int]) -> str:
    lines = [
        "| shape | node-ticks/tick | runtime | ns/node-tick | ticks/s | vs floor"
        " | aiobt speed-up |",
        "|---|---|---|---|---|---|---|",
    ]
    verdicts = []
    for shape, by_lib in per_tick.items():
        med = {lib: statistics.median(times) for lib, times in by_lib.items()}
        for lib in LIBS:
            ns = med[lib] / node_ticks[shape] * 1e9
            speedup = "" if lib in ("floor", "aiobt") else f"{med[lib] / med['aiobt']:.1f}x"
            lines.append(
                f"| {shape} | {node_ticks[shape]} | {lib} | {ns:.0f} | {1 / med[lib]:,.0f} "
                f"| {med[lib] / med['floor']:.2f} | {speedup} |"
            )
        ratio = med["aiobt"] / med["floor"]
        beats = all(med["aiobt"] < med[other] for other in ("py_trees", "btcpp"))
        verdicts.append(
            f"- {shape}: aiobt/floor {ratio:.2f} ({'met' if ratio <= 1.5 else 'NOT met'}"
            f" <= 1.5); faster than py_trees and btcpp: {'yes' if beats else 'NO'}"
        )
    return "\n".join([*lines, "", *verdicts])


async def main(args: argparse.Namespace) -> None:
    node_ticks = {}
    for shape in SHAPES:
        visits = await count_visits(shape)
        node_ticks[shape] = check_visits(shape, visits)
        print(f"{shape}: (leaves, inner nodes) per tick {visits}")
    per_tick = await measure(args.rounds, args.batch_ms / 1000)
    print(f"Python {sys.version.split()[0]}, {args.rounds} rounds, medians")
    print(report(per_tick, node_ticks))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=9)
    parser.add_argument("--batch-ms", type=float, default=40.0)
    asyncio.run(main(parser.parse_args()))
