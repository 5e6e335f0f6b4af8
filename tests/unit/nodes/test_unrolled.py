"""Composites get a tick unrolled for their children when the tree is built
(``aiobt.nodes.control.unrolled``); it must be indistinguishable from the
shared short path: same results, same leaf calls, same node states."""

from __future__ import annotations

import pytest

from aiobt.core.node import TreeContext
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.loggers.stats import TreeStatistics
from aiobt.nodes.actions.always import AlwaysFailure, AlwaysSuccess
from aiobt.nodes.control import unrolled
from aiobt.nodes.control.fallback import Fallback
from aiobt.nodes.control.reactive_sequence import ReactiveSequence
from aiobt.nodes.control.sequence import Sequence
from tests.conformance.generator import generate
from tests.conformance.harness import Driver, aiobt_factory

SUCCESS, FAILURE, RUNNING, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.IDLE


def _tree(xml_body: str) -> Tree:
    factory = BehaviorTreeFactory()
    return factory.create_tree_from_text(
        f'<root BTCPP_format="4"><BehaviorTree ID="M">{xml_body}</BehaviorTree></root>'
    )


def test_a_built_composite_has_a_class_of_its_own_with_its_name() -> None:
    tree = _tree("<Sequence><AlwaysSuccess/><Fallback><AlwaysFailure/></Fallback></Sequence>")
    root = tree.root
    assert isinstance(root, Sequence)
    assert type(root) is not Sequence
    assert type(root).__name__ == "Sequence"
    assert type(root).__bases__ == (Sequence,)
    inner = tree.find("Fallback")
    assert isinstance(inner, Fallback)
    assert type(inner) is not Fallback
    other = _tree("<Sequence><AlwaysSuccess/><Fallback><AlwaysFailure/></Fallback></Sequence>")
    assert type(other.root) is not type(root)  # one class per node, not per shape
    assert type(other.find("Fallback")) is not type(inner)


def test_too_many_children_keep_the_shared_tick() -> None:
    many = "<AlwaysSuccess/>" * (unrolled.MAX_CHILDREN + 1)
    tree = _tree(f"<Sequence>{many}</Sequence>")
    assert type(tree.root) is Sequence


def test_a_subclass_with_its_own_tick_is_left_alone() -> None:
    class Counting(Sequence):
        __slots__ = ()
        ticks = 0

        def tick_sync(self) -> Status:
            type(self).ticks += 1
            return super().tick_sync()

    node = Counting("c")
    node.add_child(AlwaysSuccess("a"))
    tree = Tree(node, TreeContext(), node.config.blackboard)
    assert type(tree.root) is Counting


async def test_adding_a_child_after_the_tree_is_built_goes_back_to_the_shared_tick() -> None:
    ctx = TreeContext()
    root = Sequence("s")
    root.add_child(AlwaysSuccess("a"))
    tree = Tree(root, ctx, root.config.blackboard)
    assert type(root) is not Sequence
    root.add_child(AlwaysFailure("b"))
    assert type(root) is Sequence
    assert await tree.tick_exactly_once() is FAILURE  # the new child is ticked


async def test_statistics_still_count_ticks_of_unrolled_nodes() -> None:
    tree = _tree(
        '<ReactiveSequence name="r"><AlwaysSuccess/><Sequence name="s">'
        "<AlwaysSuccess/></Sequence></ReactiveSequence>"
    )
    assert isinstance(tree.root, ReactiveSequence)
    assert type(tree.root) is not ReactiveSequence
    stats = TreeStatistics(tree)
    try:
        for _ in range(3):
            assert await tree.tick_exactly_once() is SUCCESS
        assert stats["r"].ticks == 3
        assert stats["r"].successes == 3
        assert stats["s"].ticks == 3
        assert stats["s"].successes == 3
    finally:
        stats.close()
    assert type(tree.root).__dict__.get("_UNROLLED")  # its unrolled class is back


async def _states(seed: int) -> list[object]:
    """Every op's result, leaf calls and every node's status and resume index."""
    scenario = generate(seed)
    driver = Driver(scenario.scripts)
    try:
        tree = aiobt_factory(driver).create_tree_from_text(scenario.xml)
    except Exception as exc:  # the generator makes some invalid trees on purpose
        return [f"load error: {exc}"]
    states: list[object] = []
    for op in scenario.ops:
        try:
            if op == "exactly":
                result = (await tree.tick_exactly_once()).name
            elif op == "once":
                result = (await tree.tick_once()).name
            else:
                await tree.halt_tree("test")
                result = "halted"
        except Exception as exc:
            result = f"error {type(exc).__name__}: {exc}"
        nodes = [
            (n.path, n.status.name, getattr(n, "_current", None), getattr(n, "_skipped", None))
            for n in tree.nodes()
        ]
        states.append((op, result, driver.take_calls(), nodes))
        if result.startswith("error"):
            break
    return states


@pytest.mark.parametrize("seed", range(150))
async def test_unrolled_and_shared_ticks_leave_the_same_states(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    unrolled_states = await _states(seed)
    monkeypatch.setattr(unrolled, "MAX_CHILDREN", 0)  # nothing is unrolled
    shared_states = await _states(seed)
    assert unrolled_states == shared_states


async def test_a_dropped_tree_is_freed_with_its_node_classes_after_statistics() -> None:
    import gc
    import weakref

    tree = _tree("<Sequence><AlwaysSuccess/><Fallback><AlwaysFailure/></Fallback></Sequence>")
    stats = TreeStatistics(tree)
    assert await tree.tick_exactly_once() is FAILURE
    stats.close()
    node_class = weakref.ref(type(tree.root))  # (nodes have no weakref slot; their class
    del tree, stats  # lives as long as they do)
    gc.collect()
    assert node_class() is None
