"""Nav2 control nodes: PipelineSequence, RecoveryNode, RoundRobin, NonblockingSequence,
PersistentSequence, scenario by scenario with scripted leaves."""

from __future__ import annotations

import pytest

from aiobt.core.errors import TreeLoadError
from aiobt.core.status import Status
from tests.unit.nav.test_nav2_support import Script, build

S, F, R, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.IDLE
K = Status.SKIPPED

PIPELINE = '<PipelineSequence><Leaf name="A"/><Leaf name="B"/><Leaf name="C"/></PipelineSequence>'


async def test_pipeline_walkthrough_from_nav2_docs() -> None:
    script = Script()
    script.set("A", "R S R R")
    script.set("B", "R S S")
    script.set("C", "R S")
    tree = build(script, PIPELINE)
    assert await tree.tick_exactly_once() is R  # A RUNNING: nothing else ticked
    assert script.take() == ["A"]
    assert await tree.tick_exactly_once() is R  # A SUCCESS, B RUNNING
    assert script.take() == ["A", "B"]
    assert await tree.tick_exactly_once() is R  # A re-ticked (RUNNING), B SUCCESS, C RUNNING
    assert script.take() == ["A", "B", "C"]
    assert await tree.tick_exactly_once() is S  # C SUCCESS: A halted though still RUNNING
    assert script.take() == ["A", "B", "C", "A:halt"]
    assert [n.status for n in tree.nodes()] == [IDLE] * 4


async def test_pipeline_failure_halts_all_and_starts_over() -> None:
    script = Script()
    script.set("A", "S R R")
    script.set("B", "R F")
    tree = build(script, PIPELINE)
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is F
    assert script.take() == ["A", "B", "A", "B", "A:halt"]
    assert await tree.tick_exactly_once() is R  # from scratch: A RUNNING stops it again
    assert script.take() == ["A"]


RECOVERY = (
    '<RecoveryNode number_of_retries="{n}"><Leaf name="Main"/><Leaf name="Fix"/></RecoveryNode>'
)


async def test_recovery_retries_within_one_tick_until_the_limit() -> None:
    script = Script()
    script.set("Main", "F")
    tree = build(script, RECOVERY.format(n=2))
    assert await tree.tick_exactly_once() is F
    assert script.take() == ["Main", "Fix", "Main", "Fix", "Main"]


async def test_recovery_success_after_a_recovery_and_counter_reset() -> None:
    script = Script()
    script.set("Main", "F S F S")
    tree = build(script, RECOVERY.format(n=1))
    assert await tree.tick_exactly_once() is S
    assert script.take() == ["Main", "Fix", "Main"]
    assert await tree.tick_exactly_once() is S  # the retry count started over
    assert script.take() == ["Main", "Fix", "Main"]


async def test_recovery_running_recovery_and_failing_recovery() -> None:
    script = Script()
    script.set("Main", "F S")
    script.set("Fix", "R S")
    tree = build(script, RECOVERY.format(n=1))
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is S
    assert script.take() == ["Main", "Fix", "Fix", "Main"]
    script.set("Main", "F")
    script.set("Fix", "F")
    assert await tree.tick_exactly_once() is F  # a failed recovery is not retried
    assert script.take() == ["Main", "Fix"]


async def test_recovery_default_is_one_retry_and_zero_means_none() -> None:
    script = Script()
    script.set("Main", "F")
    tree = build(script, '<RecoveryNode><Leaf name="Main"/><Leaf name="Fix"/></RecoveryNode>')
    assert await tree.tick_exactly_once() is F
    assert script.take() == ["Main", "Fix", "Main"]
    tree = build(script, RECOVERY.format(n=0))
    assert await tree.tick_exactly_once() is F
    assert script.take() == ["Main"]


@pytest.mark.parametrize("children", [1, 3])
def test_recovery_with_other_than_two_children_fails_at_load(children: int) -> None:
    body = "".join(f'<Leaf name="L{i}"/>' for i in range(children))
    with pytest.raises(TreeLoadError, match=r"\[RecoveryNode\] must have exactly 2 children"):
        build(Script(), f"<RecoveryNode>{body}</RecoveryNode>")


ROBIN = '<RoundRobin {attrs}><Leaf name="A"/><Leaf name="B"/><Leaf name="C"/></RoundRobin>'


async def test_round_robin_rotates_across_activations_with_wrap() -> None:
    script = Script()
    tree = build(script, ROBIN.format(attrs='wrap_around="true"'))
    assert [await tree.tick_exactly_once() for _ in range(4)] == [S, S, S, S]
    assert script.take() == ["A", "B", "C", "A"]


async def test_round_robin_without_wrap_fails_after_the_last_child() -> None:
    script = Script()
    tree = build(script, ROBIN.format(attrs=""))  # Nav2's default: no wrap-around
    # Nav2 main's round_robin_node.cpp: the last child's return ends the round before
    # its status is looked at, so even its SUCCESS comes out as FAILURE, and the
    # next activation starts over at the first child
    assert [await tree.tick_exactly_once() for _ in range(5)] == [S, S, F, S, S]
    assert script.take() == ["A", "B", "C", "A", "B"]


async def test_round_robin_all_skipped_is_skipped() -> None:
    # Nav2's test_wrap_around_disabled (and with wrap-around, the loop's bound)
    for attrs in ('wrap_around="false"', 'wrap_around="true"'):
        script = Script()
        for name in "ABC":
            script.set(name, "K")
        tree = build(script, ROBIN.format(attrs=attrs))
        assert await tree.tick_exactly_once() is K, attrs
        assert script.take() == ["A", "B", "C"], attrs


async def test_round_robin_failures_try_the_next_child_in_the_same_tick() -> None:
    script = Script()
    script.set("B", "F")
    script.set("C", "F")
    wrapped = build(script, ROBIN.format(attrs='wrap_around="true"'))
    assert await wrapped.tick_exactly_once() is S
    assert await wrapped.tick_exactly_once() is S  # B, C fail: wraps to A
    assert script.take() == ["A", "B", "C", "A"]
    plain = build(script, ROBIN.format(attrs='wrap_around="false"'))
    assert await plain.tick_exactly_once() is S
    assert await plain.tick_exactly_once() is F  # Nav2 quirk: A is not tried again
    assert script.take() == ["A", "B", "C"]
    assert await plain.tick_exactly_once() is S  # and the rotation starts over
    assert script.take() == ["A"]


async def test_round_robin_running_child_and_all_failing() -> None:
    script = Script()
    script.set("A", "R S")
    tree = build(script, ROBIN.format(attrs='wrap_around="true"'))
    assert [await tree.tick_exactly_once() for _ in range(2)] == [R, S]
    script.set("B", "F")
    script.set("C", "F")
    script.set("A", "F")
    assert await tree.tick_exactly_once() is F
    assert script.take() == ["A", "A", "B", "C", "A"]


async def test_round_robin_halt_starts_over() -> None:
    script = Script()
    script.set("B", "R")
    tree = build(script, ROBIN.format(attrs='wrap_around="true"'))
    assert [await tree.tick_exactly_once() for _ in range(2)] == [S, R]
    await tree.halt_tree("test")
    script.set("B", "S")
    assert await tree.tick_exactly_once() is S
    assert script.take() == ["A", "B", "B:halt", "A"]


NONBLOCKING = (
    '<NonblockingSequence><Leaf name="A"/><Leaf name="B"/><Leaf name="C"/></NonblockingSequence>'
)


async def test_nonblocking_sequence_ticks_every_child_each_tick() -> None:
    script = Script()
    script.set("A", "R S S")
    script.set("B", "R R S")
    tree = build(script, NONBLOCKING)
    assert [await tree.tick_exactly_once() for _ in range(3)] == [R, R, S]
    assert script.take() == ["A", "B", "C"] * 3


async def test_nonblocking_sequence_failure_halts_running_children() -> None:
    script = Script()
    script.set("A", "R")
    script.set("B", "F")
    tree = build(script, NONBLOCKING)
    assert await tree.tick_exactly_once() is F
    assert script.take() == ["A", "B", "A:halt"]


PERSISTENT = (
    '<PersistentSequence current_child_idx="{idx}">'
    '<Leaf name="A"/><Leaf name="B"/><Leaf name="C"/></PersistentSequence>'
)


async def test_persistent_sequence_keeps_its_place_on_the_blackboard() -> None:
    script = Script()
    script.set("B", "R S")
    tree = build(script, PERSISTENT)
    assert await tree.tick_exactly_once() is R
    assert tree.root_blackboard["idx"] == 1
    await tree.halt_tree("test")  # the index survives a halt
    assert await tree.tick_exactly_once() is S
    assert script.take() == ["A", "B", "B:halt", "B", "C"]
    assert tree.root_blackboard["idx"] == 0


async def test_persistent_sequence_index_set_from_outside_and_failure_reset() -> None:
    script = Script()
    script.set("C", "F")
    tree = build(script, PERSISTENT)
    tree.root_blackboard["idx"] = 2
    assert await tree.tick_exactly_once() is F
    assert script.take() == ["C"]
    assert tree.root_blackboard["idx"] == 0


def test_persistent_sequence_needs_a_blackboard_entry() -> None:
    with pytest.raises(TreeLoadError, match=r"current_child_idx.*must name a blackboard entry"):
        build(Script(), '<PersistentSequence current_child_idx="1"><Leaf/></PersistentSequence>')
