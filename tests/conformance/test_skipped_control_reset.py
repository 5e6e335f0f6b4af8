"""A control node that returns SKIPPED keeps its RUNNING status (BT.CPP), so the
parent's reset halts it and its ``_onHalted`` runs: with and without listeners."""

from __future__ import annotations

import behaviortreepy as btcpp
import pytest

from aiobt import BehaviorTreeFactory, Status
from tests.conformance.harness import tree_xml

SKIPPING = (
    '<WhileDoElse _onHalted="halted := 1">'
    '<AlwaysSuccess/><AlwaysSuccess _skipIf="true"/></WhileDoElse>'
)
TREES = {
    "reactive parent, running sibling": (
        f'<ReactiveSequence>{SKIPPING}<Sleep msec="100000"/></ReactiveSequence>'
    ),
    "sequence finishing": f"<Sequence>{SKIPPING}<AlwaysSuccess/></Sequence>",
    "fallback finishing": f"<Fallback>{SKIPPING}<AlwaysSuccess/></Fallback>",
    "reactive fallback finishing": (
        f"<ReactiveFallback>{SKIPPING}<AlwaysSuccess/></ReactiveFallback>"  # keep
    ),
}


def _btcpp(body: str) -> tuple[str, str | None]:
    bb = btcpp.Blackboard.create()
    tree = btcpp.BehaviorTreeFactory().create_tree_from_text(tree_xml(body), bb)
    status = tree.tick_once()
    halted = bb.get_string("halted") if "halted" in bb.get_keys() else None
    tree.halt_tree()
    return status.name, halted


@pytest.mark.conformance
@pytest.mark.parametrize("listening", [False, True], ids=["quiet", "listened"])
@pytest.mark.parametrize("body", list(TREES.values()), ids=list(TREES))
async def test_skipped_running_control_is_halted_by_its_parent(body: str, listening: bool) -> None:
    tree = BehaviorTreeFactory().create_tree_from_text(tree_xml(body))
    changes: list[str] = []
    if listening:
        tree.add_status_listener(lambda _t, node, _p, s: changes.append(f"{node.name}>{s.name}"))
    status = await tree.tick_once()
    halted = tree.root_blackboard.get("halted")
    await tree.halt_tree("test over")
    expected_status, expected_halted = _btcpp(body)
    assert (status.name, None if halted is None else str(halted)) == (
        expected_status,
        expected_halted,
    )
    assert expected_halted == "1"
    if listening:
        assert "WhileDoElse>IDLE" in changes
    assert tree.find("WhileDoElse").status is Status.IDLE


def _halted_when(parent: str) -> str:
    skipping = SKIPPING.replace("halted := 1", "halted := step")
    return (
        f'<Sequence><Script code="step := 0"/><{parent}>{skipping}'
        f'<Script code="step := step + 1"/></{parent}></Sequence>'
    )


@pytest.mark.conformance
@pytest.mark.parametrize("listening", [False, True], ids=["quiet", "listened"])
@pytest.mark.parametrize("parent", ["ReactiveSequence", "ReactiveFallback"])
async def test_a_reactive_parent_halts_a_skipped_running_child_before_the_next_one(
    parent: str, listening: bool
) -> None:
    # BT.CPP's reactive nodes haltChild(index) on SKIPPED, "to allow it to be
    # skipped again": the halt comes before the next sibling is ticked (step 0)
    body = _halted_when(parent)
    tree = BehaviorTreeFactory().create_tree_from_text(tree_xml(body))
    if listening:
        tree.add_status_listener(lambda *_: None)
    status = await tree.tick_once()
    halted = tree.root_blackboard.get("halted")
    expected_status, expected_halted = _btcpp(body)
    assert expected_halted is not None
    assert float(expected_halted) == 0
    assert (status.name, halted) == (expected_status, 0)
