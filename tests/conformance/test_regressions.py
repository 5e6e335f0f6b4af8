"""Differences the conformance runs found, kept as scenarios with explicit traces."""

from __future__ import annotations

import pytest

from tests.conformance.harness import Scenario, assert_conforms, results, tree_xml

pytestmark = pytest.mark.conformance


async def test_tick_once_honours_a_wake_up_left_by_tick_exactly_once() -> None:
    # SequenceWithMemory emits a wake-up after its first child; tick_exactly_once
    # leaves it pending, and the next tick_once re-ticks because of it (BT.CPP's
    # tickRoot never clears the signal before ticking). aiobt used to clear it.
    xml = tree_xml(
        '<SequenceWithMemory name="seq"><ScriptedAction name="a"/>'
        '<ScriptedStateful name="s"/><ScriptedCondition name="c"/></SequenceWithMemory>'
    )
    scenario = Scenario(xml, {"a": ("S",), "s": ("R", "S"), "c": ("F",)}, ("exactly", "once"))
    steps = await assert_conforms(scenario)
    assert results(steps) == ["RUNNING", "FAILURE"]
    assert steps[1].calls == ["start:s", "running:s", "tick:c"]


async def test_set_blackboard_copying_a_missing_entry_fails() -> None:
    # BT.CPP returns FAILURE; aiobt used to raise a LogicError.
    xml = tree_xml(
        '<Sequence name="seq"><SetBlackboard name="copy" output_key="var" value="{other}"/>'
        '<ScriptedAction name="a"/></Sequence>'
    )
    steps = await assert_conforms(Scenario(xml, {"a": ("S",)}, ("exactly",)))
    assert results(steps) == ["FAILURE"]
    assert steps[0].transitions[:2] == ["seq:IDLE>RUNNING", "copy:IDLE>FAILURE"]
