"""Nav2's navigate_to_pose tree with the real Nav2 nodes against the same tree with stubs.

Run: ``.venv/bin/python -m bench.core.nav2_real [--rounds 9] [--ticks 20000]``

``trees/nav2/navigate_to_pose_w_replanning_and_recovery.xml`` as it is, its
leaves aiobt.nav's nodes bound to an in-process bus (``open_local_bus``) where
a planner answers ComputePathToPose at once and a controller accepts FollowPath
and keeps it RUNNING; against the same XML with every Nav2 leaf replaced by
bench.core's stub leaves (``STUBS``: the result each real leaf gives in this
steady state; control nodes and decorators are the same in both). Both run on
a ManualClock that stands still, so the RateController's 1 Hz replanning is not
due while timing: the steady state is following the path (the selectors, then
FollowPath RUNNING). Before timing, a counting pass patches ``tick_sync`` on
every class of both trees and checks they tick the same number of nodes per
tree tick. Timing ticks ``root.tick_sync`` (the tree's hot path) in batches of
``--ticks``, alternating the order each round; medians over rounds of ns per
node-tick and the ratio real / stub, measured in this run.
"""

from __future__ import annotations

import asyncio
import statistics
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path as FilePath
from typing import Any

from aiobt.core.clock import ManualClock
from aiobt.core.node import TreeNode
from aiobt.core.status import RUNNING, Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import ComputePathToPose, FollowPath, Path, PoseStamped
from aiobt.nav import register_nav2_nodes
from aiobt.testing.bus import open_local_bus
from aiobt.transport import Bus
from bench.core.libs import FailCondition, OkAction, OkCondition, RunAction
from bench.core.remote_leaf import bench_args, ns_per_tick

TREE = FilePath(__file__).parents[2] / "trees/nav2/navigate_to_pose_w_replanning_and_recovery.xml"
_SELECTORS = ("ProgressChecker", "GoalChecker", "PathHandler", "Controller", "Planner")
STUBS = {
    **{f"{what}Selector": "OkAction" for what in _SELECTORS},
    "FollowPath": "RunAction",
    "ComputePathToPose": "OkAction",
    "GlobalUpdatedGoal": "FailCondition",
    "IsGoalNearby": "FailCondition",  # no robot pose on this bus
    "TruncatePathLocal": "OkAction",
    "ValidatePath": "OkCondition",
    "WouldAPlannerRecoveryHelp": "OkCondition",
    "WouldAControllerRecoveryHelp": "OkCondition",
    "ClearEntireCostmap": "OkAction",
    "GoalUpdated": "FailCondition",
    "Spin": "RunAction",
    "Wait": "RunAction",
    "BackUp": "RunAction",
}


def stub_xml(text: str) -> str:
    """The tree with every Nav2 leaf in ``STUBS`` replaced by its stub (name kept)."""
    root = ET.fromstring(text)
    for element in root.iter():
        if element.tag in STUBS:
            name = element.get("name", element.tag)
            element.attrib.clear()
            element.set("name", name)
            element.tag = STUBS[element.tag]
    return ET.tostring(root, encoding="unicode")


def _stub_tree(text: str, clock: ManualClock) -> Tree:
    factory = BehaviorTreeFactory()
    for leaf in (OkAction, OkCondition, FailCondition, RunAction):
        factory.register_node_type(leaf, leaf.__name__)
    tree = factory.create_tree_from_text(stub_xml(text), clock=clock)
    for _ in range(3):  # past the RateController's first (immediate) tick of its child
        assert tree.root.tick_sync() is RUNNING
    return tree


async def _real_tree(bus: Bus, text: str, clock: ManualClock) -> Tree:
    poses = [PoseStamped.from_xy_yaw(0.1 * i, 0.0, 0.0) for i in range(50)]
    following = asyncio.Event()

    async def plan(goal: Any, handle: object) -> Any:
        return ComputePathToPose.Result(path=Path(poses=poses))

    async def follow(goal: Any, handle: object) -> Any:
        following.set()
        await asyncio.Event().wait()  # never finishes: the leaf stays RUNNING
        return FollowPath.Result()

    bus.action_server("compute_path_to_pose", ComputePathToPose, plan, preemption="replace")
    bus.action_server("follow_path", FollowPath, follow, preemption="replace")
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, bus, clock=clock)
    tree = factory.create_tree_from_text(text, clock=clock)
    tree.root_blackboard["goal"] = poses[-1]
    tree.root_blackboard["path"] = Path(poses=poses)
    async with asyncio.timeout(20.0):
        while not following.is_set():
            assert await tree.tick_once() is RUNNING
            await asyncio.sleep(0.01)
        for _ in range(20):  # the accepted goal reaches the leaf
            assert await tree.tick_once() is RUNNING
            await asyncio.sleep(0.01)
    return tree


@contextmanager
def counted(trees: list[Tree], counts: list[int], index: list[int]) -> Iterator[None]:
    """Count every tick_sync call of the trees' nodes into ``counts[index[0]]``."""
    owners = {
        next(cls for cls in type(node).__mro__ if "tick_sync" in cls.__dict__)
        for tree in trees
        for node in tree.nodes()
    }
    saved = {cls: cls.__dict__["tick_sync"] for cls in owners}

    def wrap(tick: Callable[[TreeNode], Status]) -> Callable[[TreeNode], Status]:
        def counting(self: TreeNode) -> Status:
            counts[index[0]] += 1
            return tick(self)

        return counting

    try:
        for cls, tick in saved.items():
            setattr(cls, "tick_sync", wrap(tick))  # noqa: B010 (cls is a plain type here)
        yield
    finally:
        for cls, tick in saved.items():
            setattr(cls, "tick_sync", tick)  # noqa: B010


def node_ticks(trees: dict[str, Tree]) -> dict[str, int]:
    """Node-ticks in one steady-state tree tick, per tree."""
    counts = [0] * len(trees)
    index = [0]
    with counted(list(trees.values()), counts, index):
        for index[0], tree in enumerate(trees.values()):
            assert tree.root.tick_sync() is RUNNING
    return dict(zip(trees, counts, strict=True))


async def measure(rounds: int, ticks: int) -> tuple[dict[str, list[float]], dict[str, int]]:
    text = TREE.read_text()
    clock = ManualClock()
    async with open_local_bus() as bus:
        trees = {"stub": _stub_tree(text, clock), "real": await _real_tree(bus, text, clock)}
        counts = node_ticks(trees)
        if len(set(counts.values())) != 1:
            raise SystemExit(f"the trees tick different numbers of nodes: {counts}")
        results: dict[str, list[float]] = {name: [] for name in trees}
        for index in range(rounds):
            order = list(trees)[index % 2 :] + list(trees)[: index % 2]
            for name in order:
                results[name].append(ns_per_tick(trees[name].root.tick_sync, ticks))
        for tree in trees.values():
            await tree.halt_tree("bench done")
    return results, counts


def report(results: dict[str, list[float]], counts: dict[str, int]) -> str:
    per_node = {name: statistics.median(v) / counts[name] for name, v in results.items()}
    ratio = per_node["real"] / per_node["stub"]
    return (
        "| navigate_to_pose tree (FollowPath RUNNING) | node-ticks/tick | ns/node-tick |\n"
        "|---|---|---|\n"
        f"| stub leaves | {counts['stub']} | {per_node['stub']:.0f} |\n"
        f"| real Nav2 nodes, in-process bus | {counts['real']} | {per_node['real']:.0f} |\n\n"
        f"real / stub: {ratio:.2f}x ({'within' if ratio <= 2.0 else 'OVER'} 2x)"
    )


def main() -> None:
    args = bench_args(__doc__)
    print(report(*asyncio.run(measure(args.rounds, args.ticks))))


if __name__ == "__main__":
    main()
