"""Switch2..Switch6: case matching (text, number, enum), default, halting, errors."""

from __future__ import annotations

import pytest

from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE


def _switch(cases: int, variable: str, values: list[str] | None = None) -> str:
    values = values or [str(i) for i in range(1, cases + 1)]
    attributes = " ".join(f'case_{i + 1}="{v}"' for i, v in enumerate(values))
    children = "".join(f'<StubAction name="X{i}"/>' for i in range(1, cases + 1))
    var = f' variable="{variable}"' if variable else ""
    return tree_xml(
        f'<Switch{cases}{var} {attributes}>{children}<StubAction name="D"/></Switch{cases}>'
    )


@pytest.mark.parametrize("cases", [2, 3, 4, 5, 6])
async def test_switch_ticks_matching_case(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, cases: int
):
    tree = bt_factory.create_tree_from_text(_switch(cases, str(cases)))
    assert await tree.tick_exactly_once() is S
    assert stubs.log == [f"X{cases}:start"]


@pytest.mark.parametrize(
    ("variable", "expected"),
    [
        ("2.0", "X2"),
        ("1", "X1"),
        ("zz", "D"),
        ("", "D"),
        ("0x2", "X2"),  # BT.CPP reads hex ints
        ("2.000001", "X2"),  # and the leading int of a real
        ("-0x1", "D"),
        ("1.00000001", "X1"),
    ],
)
async def test_switch_compares_as_text_or_number(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, variable: str, expected: str
):
    tree = bt_factory.create_tree_from_text(_switch(2, variable))
    assert await tree.tick_exactly_once() is S
    assert stubs.log == [f"{expected}:start"]


async def test_switch_reads_blackboard_and_halts_on_case_change(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("X1", "RUNNING")
    stubs.script("X2", "RUNNING")
    tree = bt_factory.create_tree_from_text(_switch(2, "{v}", ["left", "right"]))
    tree.root_blackboard.set("v", "left")
    assert await tree.tick_exactly_once() is R
    tree.root_blackboard.set("v", "right")
    assert await tree.tick_exactly_once() is R
    assert stubs.log == ["X1:start", "X1:halted", "X2:start"]
    await tree.halt_tree("done")
    assert stubs.halts("X2") == 1


async def test_switch_enum_case(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    tree = bt_factory.create_tree_from_text(_switch(2, "{v}", ["RED", "GREEN"]))
    tree.context.enums.update(RED=1, GREEN=2)
    tree.root_blackboard.set("v", 2)
    assert await tree.tick_exactly_once() is S
    assert stubs.log == ["X2:start"]


async def test_switch_skipped_child(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("X1", "SKIPPED")
    tree = bt_factory.create_tree_from_text(_switch(2, "1"))
    assert await tree.tick_exactly_once() is K


async def test_switch_wrong_child_count_throws_at_tick(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Switch2 variable="1" case_1="1" case_2="2">'
            '<StubAction name="X1"/><StubAction name="X2"/></Switch2>'
        )
    )
    with pytest.raises(NodeError, match="3 children"):
        await tree.tick_exactly_once()
