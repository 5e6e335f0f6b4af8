"""TryCatch: try children as a Sequence; the last child runs when one fails."""

from __future__ import annotations

import pytest

from aiobt.core.errors import TreeLoadError
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tree_xml

S, F, R, K = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED

TREE = """<TryCatch{attrs}>
  <StubAction name="A"/>
  <StubAction name="B"/>
  <StubAction name="Catch"/>
</TryCatch>"""


def make(factory: BehaviorTreeFactory, attrs: str = "") -> Tree:
    return factory.create_tree_from_text(tree_xml(TREE.format(attrs=attrs)))


async def test_all_try_children_succeed(bt_factory: BehaviorTreeFactory, stubs: Stubs) -> None:
    stubs.script("B", "R", "S")
    tree = make(bt_factory)
    assert [await tree.tick_exactly_once() for _ in range(2)] == [R, S]
    assert stubs.starts("Catch") == 0
    assert stubs.log == ["A:start", "B:start", "B:running"]


async def test_failure_runs_the_catch_child_and_fails(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    stubs.script("B", "F")
    stubs.script("Catch", "R", "S")
    tree = make(bt_factory)
    assert await tree.tick_exactly_once() is R  # catch started in the same tick
    assert await tree.tick_exactly_once() is F  # catch finished: FAILURE anyway
    assert stubs.log == ["A:start", "B:start", "Catch:start", "Catch:running"]
    stubs.script("B", "S")
    assert await tree.tick_exactly_once() is S  # a fresh run starts with the try block
    assert stubs.starts("A") == 2


async def test_catch_failure_is_still_failure(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    stubs.script("A", "F")
    stubs.script("Catch", "F")
    tree = make(bt_factory)
    assert await tree.tick_exactly_once() is F
    assert stubs.starts("B") == 0


async def test_all_skipped_is_skipped(bt_factory: BehaviorTreeFactory, stubs: Stubs) -> None:
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            """<Sequence><TryCatch>
                 <AlwaysSuccess _skipIf="true"/><AlwaysSuccess _skipIf="true"/>
                 <StubAction name="Catch"/>
               </TryCatch><StubAction name="After"/></Sequence>"""
        )
    )
    assert await tree.tick_exactly_once() is S
    assert tree.find("TryCatch").status is Status.IDLE
    assert stubs.starts("Catch") == 0


@pytest.mark.parametrize(("catch_on_halt", "catch_starts"), [("false", 0), ("true", 1)])
async def test_halt_runs_the_catch_only_with_catch_on_halt(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, catch_on_halt: str, catch_starts: int
) -> None:
    stubs.script("A", "R")
    stubs.script("Catch", "R")
    tree = make(bt_factory, f' catch_on_halt="{catch_on_halt}"')
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("test")
    assert stubs.halts("A") == 1
    assert stubs.starts("Catch") == catch_starts
    assert stubs.halts("Catch") == catch_starts  # a RUNNING catch is halted at once


async def test_halt_while_catching_does_not_restart_the_catch(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    stubs.script("A", "F")
    stubs.script("Catch", "R")
    tree = make(bt_factory, ' catch_on_halt="true"')
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("test")
    assert stubs.starts("Catch") == 1
    assert stubs.halts("Catch") == 1


async def test_needs_two_children(bt_factory: BehaviorTreeFactory) -> None:
    with pytest.raises(TreeLoadError, match="at least 2 children"):
        bt_factory.create_tree_from_text(tree_xml("<TryCatch><AlwaysSuccess/></TryCatch>"))
