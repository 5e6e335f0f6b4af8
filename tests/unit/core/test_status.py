"""Status values and BT.CPP's reset rules."""

from __future__ import annotations

import pytest

from aiobt.core.composite import reset_node
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tree_xml


def test_numeric_values_match_btcpp():
    assert [s.value for s in Status] == [0, 1, 2, 3, 4]
    assert [s.name for s in Status] == ["IDLE", "RUNNING", "SUCCESS", "FAILURE", "SKIPPED"]


def test_completed_and_active():
    assert {s for s in Status if s.is_completed} == {Status.SUCCESS, Status.FAILURE}
    assert {s for s in Status if s.is_active} == {Status.RUNNING, Status.SUCCESS, Status.FAILURE}


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (None, Status.SUCCESS),
        (True, Status.SUCCESS),
        (False, Status.FAILURE),
        (Status.RUNNING, Status.RUNNING),
    ],
)
def test_of(value: Status | bool | None, expected: Status):
    assert Status.of(value) is expected


@pytest.mark.parametrize("value", [1, "SUCCESS", 0.0])
def test_of_rejects_other_values(value: object):
    with pytest.raises(TypeError, match="must return a Status"):
        Status.of(value)  # type: ignore[arg-type]


async def test_reset_node_halts_only_running(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "RUNNING")
    stubs.script("B", "SUCCESS")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Parallel success_count="2"><StubAction name="B"/><StubAction name="A"/></Parallel>'
        )
    )
    assert await tree.tick_exactly_once() is Status.RUNNING
    a, b = tree.find("A"), tree.find("B")
    assert (a.status, b.status) == (Status.RUNNING, Status.SUCCESS)
    reset_node(b)
    reset_node(a)
    assert (a.status, b.status) == (Status.IDLE, Status.IDLE)
    assert stubs.halts("A") == 1
    assert stubs.halts("B") == 0


async def test_decorator_resets_finished_child(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE")
    tree = bt_factory.create_tree_from_text(tree_xml('<Inverter><StubAction name="A"/></Inverter>'))
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert tree.find("A").status is Status.IDLE


async def test_skipped_leaves_node_idle(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "SKIPPED")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Sequence><StubAction name="A"/><StubAction name="B" results="R"/></Sequence>')
    )
    assert await tree.tick_exactly_once() is Status.RUNNING
    assert tree.find("A").status is Status.IDLE
