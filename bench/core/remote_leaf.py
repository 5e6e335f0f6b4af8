"""Tick cost of a RUNNING Nav2 remote leaf against RUNNING stub leaves, in one run.

Run: ``.venv/bin/python -m bench.core.remote_leaf [--rounds 9] [--ticks 20000]``

A tree whose only node is ``<FollowPath path="{path}"/>`` (aiobt.nav's BtAction,
bound to an in-process bus; the goal is accepted by an in-process server that
never finishes), against the same tree with bench.core's ``RunAction`` stub
(a StatefulActionNode that stays RUNNING) and with a coroutine leaf that
awaits forever (an AsyncActionNode, the base of every remote leaf: the
difference to it is what BtAction adds). All are ticked with the root's
``tick_sync`` (the tree's own hot path); per round each runs a batch of
``--ticks``; the order alternates. Reported: medians over rounds of ns per tree
tick, and the ratios, measured in this run.
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import statistics
import time
from collections.abc import Callable

from aiobt.core.leaves import AsyncActionNode
from aiobt.core.status import RUNNING, Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import FollowPath, Path, PoseStamped
from aiobt.nav import register_nav2_nodes
from aiobt.testing.bus import open_local_bus
from aiobt.testing.stubs import tree_xml
from aiobt.transport import Bus
from bench.core.libs import RunAction


def _ns_per_tick(tick: Callable[[], Status], n: int) -> float:
    gc.collect()
    start = time.perf_counter()
    for _ in range(n):
        tick()
    return (time.perf_counter() - start) / n * 1e9


class AwaitForever(AsyncActionNode):
    async def run(self) -> Status:
        await asyncio.Event().wait()
        return Status.SUCCESS


def _stub_tree(leaf: type[RunAction | AwaitForever]) -> Tree:
    factory = BehaviorTreeFactory()
    factory.register_node_type(leaf, leaf.__name__)
    return factory.create_tree_from_text(tree_xml(f"<{leaf.__name__}/>"))


async def _running_follow_path(bus: Bus) -> Tree:
    accepted = asyncio.Event()

    async def execute(goal: FollowPath.Goal, handle: object) -> FollowPath.Result:
        accepted.set()
        await asyncio.Event().wait()  # never finishes: the leaf stays RUNNING
        return FollowPath.Result()

    bus.action_server("follow_path", FollowPath, execute, preemption="replace")
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, bus)
    tree = factory.create_tree_from_text(tree_xml('<FollowPath path="{path}"/>'))
    poses = [PoseStamped.from_xy_yaw(0.1 * i, 0.0, 0.0) for i in range(50)]
    tree.root_blackboard["path"] = Path(poses=poses)
    async with asyncio.timeout(10.0):
        while not accepted.is_set() or getattr(tree.root, "_handle", None) is None:
            assert await tree.tick_exactly_once() is RUNNING
            await asyncio.sleep(0.01)
    return tree


async def measure(rounds: int, ticks: int) -> dict[str, list[float]]:
    async with open_local_bus() as bus:
        trees = {
            "RunAction": _stub_tree(RunAction),
            "AwaitForever": _stub_tree(AwaitForever),
            "FollowPath": await _running_follow_path(bus),
        }
        results: dict[str, list[float]] = {name: [] for name in trees}
        for tree in trees.values():
            assert tree.root.tick_sync() is RUNNING
        for index in range(rounds):
            order = list(trees)[index % 3 :] + list(trees)[: index % 3]
            for name in order:
                results[name].append(_ns_per_tick(trees[name].root.tick_sync, ticks))
        for tree in trees.values():
            await tree.halt_tree("bench done")
    return results


def report(results: dict[str, list[float]]) -> str:
    ns = {name: statistics.median(values) for name, values in results.items()}
    real = ns["FollowPath"]
    return (
        "| leaf (RUNNING) | ns per tick (median) | FollowPath / it |\n|---|---|---|\n"
        f"| RunAction (StatefulActionNode stub) | {ns['RunAction']:.0f} "
        f"| {real / ns['RunAction']:.2f}x |\n"
        f"| AwaitForever (AsyncActionNode stub) | {ns['AwaitForever']:.0f} "
        f"| {real / ns['AwaitForever']:.2f}x |\n"
        f"| FollowPath (BtAction, in-process bus) | {real:.0f} | 1.00x |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rounds", type=int, default=9)
    parser.add_argument("--ticks", type=int, default=20000)
    args = parser.parse_args()
    print(report(asyncio.run(measure(args.rounds, args.ticks))))


if __name__ == "__main__":
    main()
