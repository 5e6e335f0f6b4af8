"""One scenario per point of btcpp_semantics.md, run under both implementations.

Each test asserts the behaviour the reference document describes (on
BehaviorTree.CPP's trace) and that aiobt's trace is the same, step by step.
"""

from __future__ import annotations

import pytest

from tests.conformance.harness import Scenario, Step, assert_conforms, results, tree_xml

pytestmark = pytest.mark.conformance


async def run(body: str, scripts: dict[str, str], ops: str) -> list[Step]:
    scripted = {name: tuple(script) for name, script in scripts.items()}
    scenario = Scenario(tree_xml(body), scripted, tuple(ops.split()))
    return await assert_conforms(scenario)


def calls(steps: list[Step]) -> list[list[str]]:
    return [step.calls for step in steps]


# -- ticking the tree ------------------------------------------------------------------


async def test_exactly_once_resets_only_the_root() -> None:
    body = '<IfThenElse name="root"><ScriptedCondition name="c"/><AlwaysSuccess/></IfThenElse>'
    steps = await run(body, {"c": "F"}, "exactly")
    assert results(steps) == ["FAILURE"]
    assert steps[0].transitions == [
        "root:IDLE>RUNNING",
        "c:IDLE>FAILURE",
        "root:RUNNING>FAILURE",
        "root:FAILURE>IDLE",
    ]


async def test_tick_once_reticks_while_a_wake_up_is_pending() -> None:
    body = (
        '<SequenceWithMemory name="root"><AlwaysSuccess name="k1"/>'
        '<AlwaysSuccess name="k2"/><AlwaysSuccess name="k3"/></SequenceWithMemory>'
    )
    assert results(await run(body, {}, "exactly exactly exactly")) == [
        "RUNNING",
        "RUNNING",
        "SUCCESS",
    ]
    assert results(await run(body, {}, "once")) == ["SUCCESS"]


async def test_halt_tree_calls_on_halted_of_running_stateful_actions_only() -> None:
    body = (
        '<Parallel name="root" success_count="-1" failure_count="1">'
        '<ScriptedStateful name="done"/><ScriptedStateful name="busy"/></Parallel>'
    )
    steps = await run(body, {"done": "S", "busy": "R"}, "exactly halt exactly")
    assert results(steps) == ["RUNNING", "halted", "RUNNING"]
    assert calls(steps) == [
        ["start:done", "start:busy"],
        ["halted:busy"],
        ["start:done", "start:busy"],
    ]


# -- stateful actions that were not reset -------------------------------------------------


async def test_finished_stateful_condition_of_while_do_else_is_not_called_again() -> None:
    body = (
        '<WhileDoElse name="root"><ScriptedStateful name="cond"/>'
        '<ScriptedStateful name="do"/></WhileDoElse>'
    )
    steps = await run(body, {"cond": "S", "do": "RRS"}, "exactly exactly exactly")
    assert results(steps) == ["RUNNING", "RUNNING", "SUCCESS"]
    assert calls(steps) == [["start:cond", "start:do"], ["running:do"], ["running:do"]]


async def test_failed_stateful_condition_of_two_child_if_then_else_keeps_its_status() -> None:
    body = (
        '<IfThenElse name="root"><ScriptedStateful name="cond"/>'
        '<ScriptedStateful name="then"/></IfThenElse>'
    )
    steps = await run(body, {"cond": "F", "then": "S"}, "exactly exactly")
    assert results(steps) == ["FAILURE", "FAILURE"]
    assert calls(steps) == [["start:cond"], []]


# -- nodes that yield between instant children ----------------------------------------------


async def test_plain_sequence_and_fallback_do_not_yield() -> None:
    three = '<AlwaysSuccess name="k1"/><AlwaysSuccess name="k2"/><AlwaysSuccess name="k3"/>'
    assert results(await run(f'<Sequence name="root">{three}</Sequence>', {}, "exactly")) == [
        "SUCCESS"
    ]
    fails = '<AlwaysFailure name="f1"/><AlwaysFailure name="f2"/>'
    assert results(await run(f'<Fallback name="root">{fails}</Fallback>', {}, "exactly")) == [
        "FAILURE"
    ]


async def test_retry_yields_between_attempts() -> None:
    body = (
        '<RetryUntilSuccessful name="root" num_attempts="3">'
        '<ScriptedAction name="a"/></RetryUntilSuccessful>'
    )
    steps = await run(body, {"a": "FFS"}, "exactly exactly exactly")
    assert results(steps) == ["RUNNING", "RUNNING", "SUCCESS"]
    assert results(await run(body, {"a": "FFS"}, "once")) == ["SUCCESS"]


async def test_repeat_yields_between_cycles() -> None:
    body = '<Repeat name="root" num_cycles="3"><ScriptedAction name="a"/></Repeat>'
    steps = await run(body, {"a": "S"}, "exactly exactly exactly")
    assert results(steps) == ["RUNNING", "RUNNING", "SUCCESS"]
    assert calls(steps) == [["tick:a"]] * 3


async def test_sequence_with_memory_keeps_its_child_across_halt_tree() -> None:
    body = (
        '<SequenceWithMemory name="root"><ScriptedAction name="a"/>'
        '<ScriptedStateful name="s"/></SequenceWithMemory>'
    )
    steps = await run(body, {"a": "S", "s": "RRS"}, "exactly exactly halt exactly exactly")
    assert results(steps) == ["RUNNING", "RUNNING", "halted", "RUNNING", "SUCCESS"]
    assert calls(steps) == [["tick:a"], ["start:s"], ["halted:s"], ["start:s"], ["running:s"]]


async def test_sequence_with_memory_resumes_at_the_failed_child() -> None:
    body = (
        '<SequenceWithMemory name="root"><ScriptedAction name="a"/>'
        '<ScriptedAction name="b"/></SequenceWithMemory>'
    )
    steps = await run(body, {"a": "S", "b": "FS"}, "once once")
    assert results(steps) == ["FAILURE", "SUCCESS"]
    assert calls(steps) == [["tick:a", "tick:b"], ["tick:b"]]


# -- reactive nodes -----------------------------------------------------------------------------


async def test_reactive_sequence_halts_every_other_child() -> None:
    body = (
        '<ReactiveSequence name="root"><ScriptedAction name="a"/>'
        '<ScriptedStateful name="s1"/><ScriptedStateful name="s2"/></ReactiveSequence>'
    )
    steps = await run(body, {"a": "S", "s1": "RSR", "s2": "R"}, "exactly exactly exactly")
    assert calls(steps) == [
        ["tick:a", "start:s1"],
        ["tick:a", "running:s1", "start:s2"],
        ["tick:a", "start:s1", "halted:s2"],  # s1 succeeded, was reset, starts again
    ]


async def test_reactive_fallback_halts_every_other_child() -> None:
    body = (
        '<ReactiveFallback name="root"><ScriptedStateful name="s1"/>'
        '<ScriptedStateful name="s2"/></ReactiveFallback>'
    )
    steps = await run(body, {"s1": "FR", "s2": "R"}, "exactly exactly")
    assert calls(steps) == [["start:s1", "start:s2"], ["start:s1", "halted:s2"]]


async def test_reactive_sequence_allows_two_running_children_in_turn() -> None:
    body = (
        '<ReactiveSequence name="root"><ScriptedStateful name="s1"/>'
        '<ScriptedStateful name="s2"/></ReactiveSequence>'
    )
    steps = await run(body, {"s1": "RSRS", "s2": "R"}, "exactly exactly exactly exactly")
    assert results(steps) == ["RUNNING"] * 4


# -- RunOnce and SKIPPED ------------------------------------------------------------------------


async def test_run_once_skips_afterwards_even_across_halt_tree() -> None:
    body = (
        '<Sequence name="root"><RunOnce name="once"><ScriptedStateful name="s"/></RunOnce>'
        '<ScriptedAction name="a"/></Sequence>'
    )
    steps = await run(body, {"s": "RS", "a": "S"}, "exactly halt exactly exactly exactly")
    assert results(steps) == ["RUNNING", "halted", "SUCCESS", "SUCCESS", "SUCCESS"]
    assert calls(steps) == [
        ["start:s"],
        ["halted:s"],
        ["start:s", "tick:a"],
        ["tick:a"],
        ["tick:a"],
    ]


async def test_run_once_then_skip_false_repeats_the_result() -> None:
    body = '<RunOnce name="root" then_skip="false"><ScriptedAction name="a"/></RunOnce>'
    steps = await run(body, {"a": "FS"}, "exactly exactly exactly")
    assert results(steps) == ["FAILURE", "FAILURE", "FAILURE"]
    assert calls(steps) == [["tick:a"], [], []]


async def test_a_skipped_root_is_returned_and_the_root_stays_running() -> None:
    body = '<RunOnce name="root"><ScriptedAction name="a"/></RunOnce>'
    steps = await run(body, {"a": "S"}, "exactly exactly once")
    assert results(steps) == ["SUCCESS", "SKIPPED", "SKIPPED"]
    steps = await run(
        f'<Sequence name="top">{body}</Sequence>', {"a": "S"}, "exactly exactly exactly"
    )
    assert results(steps) == ["SUCCESS", "SKIPPED", "SKIPPED"]
    assert steps[1].transitions == ["top:IDLE>RUNNING"]  # never back to IDLE


async def test_keep_running_until_failure_turns_skipped_into_running() -> None:
    body = (
        '<KeepRunningUntilFailure name="root"><RunOnce name="once">'
        '<ScriptedAction name="a"/></RunOnce></KeepRunningUntilFailure>'
    )
    steps = await run(body, {"a": "S"}, "exactly exactly")
    assert results(steps) == ["RUNNING", "RUNNING"]


@pytest.mark.parametrize("control", ["IfThenElse", "WhileDoElse"])
async def test_skipped_condition_throws(control: str) -> None:
    body = (
        f'<{control} name="root"><RunOnce name="once"><ScriptedCondition name="c"/></RunOnce>'
        f'<AlwaysSuccess name="yes"/><AlwaysFailure name="no"/></{control}>'
    )
    steps = await run(body, {"c": "S"}, "exactly exactly")
    assert results(steps) == ["SUCCESS", "error"]


# -- Parallel and ParallelAll ---------------------------------------------------------------------


async def test_parallel_stops_ticking_once_the_threshold_is_reached() -> None:
    body = (
        '<Parallel name="root" success_count="1" failure_count="1">'
        '<ScriptedAction name="a"/><ScriptedStateful name="s"/></Parallel>'
    )
    steps = await run(body, {"a": "S", "s": "R"}, "exactly")
    assert results(steps) == ["SUCCESS"]
    assert calls(steps) == [["tick:a"]]


async def test_parallel_fails_when_failures_equal_failure_count() -> None:
    body = (
        '<Parallel name="root" success_count="-1" failure_count="2">'
        '<ScriptedStateful name="s1"/><ScriptedStateful name="s2"/><ScriptedStateful name="s3"/>'
        "</Parallel>"
    )
    steps = await run(body, {"s1": "F", "s2": "RF", "s3": "R"}, "exactly exactly")
    assert results(steps) == ["FAILURE", "FAILURE"]
    assert calls(steps)[0] == ["start:s1"]  # success became impossible at once


async def test_parallel_failure_count_zero_and_success_count_zero() -> None:
    two = '<ScriptedAction name="a"/><ScriptedAction name="b"/>'
    steps = await run(
        f'<Parallel name="root" success_count="0">{two}</Parallel>', {"a": "F", "b": "F"}, "exactly"
    )
    assert results(steps) == ["SUCCESS"]
    assert calls(steps) == [["tick:a"]]
    steps = await run(
        f'<Parallel name="root" success_count="2" failure_count="0">{two}</Parallel>',
        {"a": "S", "b": "S"},
        "exactly",
    )
    assert results(steps) == ["FAILURE"]


@pytest.mark.parametrize(
    ("port", "expected"),
    [
        ('success_count="3"', "error"),
        ('failure_count="3"', "error"),
        ('success_count="-4"', "SUCCESS"),  # max(2 - 4 + 1, 0): succeeds at once
        ('failure_count="-3"', "FAILURE"),  # a threshold of 0 failures is met at once
    ],
)
async def test_parallel_threshold_above_the_children_throws(port: str, expected: str) -> None:
    body = f'<Parallel name="root" {port}><AlwaysSuccess/><AlwaysSuccess/></Parallel>'
    steps = await run(body, {}, "exactly")
    assert results(steps) == [expected]


async def test_parallel_all_with_max_failures_zero_always_fails() -> None:
    body = '<ParallelAll name="root" max_failures="0"><ScriptedAction name="a"/></ParallelAll>'
    steps = await run(body, {"a": "S"}, "exactly")
    assert results(steps) == ["FAILURE"]


async def test_parallel_all_runs_every_child_to_completion() -> None:
    body = (
        '<ParallelAll name="root" max_failures="2"><ScriptedAction name="a"/>'
        '<ScriptedStateful name="s"/></ParallelAll>'
    )
    steps = await run(body, {"a": "F", "s": "RRS"}, "exactly exactly exactly")
    assert results(steps) == ["RUNNING", "RUNNING", "SUCCESS"]
    assert calls(steps) == [["tick:a", "start:s"], ["running:s"], ["running:s"]]


# -- loop counts ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("node", "port", "expected"),
    [("Repeat", "num_cycles", "SUCCESS"), ("RetryUntilSuccessful", "num_attempts", "FAILURE")],
)
async def test_zero_loops_finish_without_ticking_the_child(
    node: str, port: str, expected: str
) -> None:
    body = f'<{node} name="root" {port}="0"><ScriptedAction name="a"/></{node}>'
    steps = await run(body, {"a": "S"}, "exactly")
    assert results(steps) == [expected]
    assert calls(steps) == [[]]


@pytest.mark.parametrize("node", ["Repeat", "RetryUntilSuccessful"])
async def test_missing_loop_count_is_an_error(node: str) -> None:
    steps = await run(
        f'<{node} name="root"><ScriptedAction name="a"/></{node}>', {"a": "S"}, "exactly"
    )
    assert results(steps)[-1] == "error"


# -- wrong numbers of children ---------------------------------------------------------------


@pytest.mark.parametrize("control", ["IfThenElse", "WhileDoElse"])
@pytest.mark.parametrize("children", [1, 4])
async def test_wrong_child_count_loads_and_throws_at_the_first_tick(
    control: str, children: int
) -> None:
    kids = "".join(f'<AlwaysSuccess name="k{i}"/>' for i in range(children))
    steps = await run(f'<{control} name="root">{kids}</{control}>', {}, "exactly")
    assert [step.op for step in steps] == ["exactly"]
    assert results(steps) == ["error"]
