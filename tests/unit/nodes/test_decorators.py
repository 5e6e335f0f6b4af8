"""Inverter, ForceSuccess, ForceFailure, KeepRunningUntilFailure, RunOnce."""

from __future__ import annotations

import pytest

from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tick_statuses, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE


def _decorated(factory: BehaviorTreeFactory, decorator: str, attributes: str = ""):
    return factory.create_tree_from_text(
        tree_xml(f'<{decorator} {attributes}><StubAction name="A"/></{decorator}>')
    )


async def test_inverter_swaps_results_and_passes_running(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "RUNNING", "SUCCESS", "FAILURE")
    tree = _decorated(bt_factory, "Inverter")
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, F, S]
    assert stubs.log == ["A:start", "A:running", "A:start"]  # child reset after finishing


async def test_inverter_passes_skipped(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "SKIPPED")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><Inverter><StubAction name="A"/></Inverter><StubAction name="B"/></Sequence>'
        )
    )
    assert await tree.tick_exactly_once() is S
    assert stubs.log == ["A:start", "B:start"]


@pytest.mark.parametrize(
    ("decorator", "child", "expected"),
    [
        ("ForceSuccess", "FAILURE", S),
        ("ForceSuccess", "SUCCESS", S),
        ("ForceFailure", "SUCCESS", F),
        ("ForceFailure", "FAILURE", F),
        ("ForceSuccess", "SKIPPED", K),
        ("ForceFailure", "SKIPPED", K),
    ],
)
async def test_force_decorators(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, decorator: str, child: str, expected: Status
):
    stubs.script("A", child)
    tree = _decorated(bt_factory, decorator)
    assert await tree.tick_exactly_once() is expected


async def test_force_success_passes_running_and_halt(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "RUNNING")
    tree = _decorated(bt_factory, "ForceSuccess")
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("stop")
    assert stubs.halts("A") == 1
    assert all(node.status is IDLE for node in tree.nodes())


async def test_keep_running_until_failure(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "SUCCESS", "RUNNING", "SUCCESS", "FAILURE")
    tree = _decorated(bt_factory, "KeepRunningUntilFailure")
    assert await tick_statuses(tree.tick_exactly_once, 4) == [R, R, R, F]
    assert stubs.log == ["A:start", "A:start", "A:running", "A:start"]


async def test_keep_running_until_failure_turns_skipped_into_running(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "SKIPPED")
    tree = _decorated(bt_factory, "KeepRunningUntilFailure")
    assert await tree.tick_exactly_once() is R


async def test_run_once_skips_after_first_completion(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "RUNNING", "FAILURE")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><RunOnce><StubAction name="A"/></RunOnce><StubAction name="B"/></Sequence>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 4) == [R, F, S, S]
    assert stubs.log == ["A:start", "A:running", "B:start", "B:start"]


async def test_run_once_then_skip_false_repeats_result(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "FAILURE")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><RunOnce then_skip="false"><StubAction name="A"/></RunOnce>'
            '<StubAction name="B"/></Sequence>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 3) == [F, F, F]
    assert stubs.log == ["A:start"]


async def test_run_once_remembers_across_halt_tree(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("B", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><RunOnce><StubAction name="A"/></RunOnce><StubAction name="B"/></Sequence>'
        )
    )
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("restart")
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, R]
    assert stubs.log == ["A:start", "B:start", "B:halted", "B:start", "B:running"]


async def test_run_once_root_returns_skipped(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    tree = _decorated(bt_factory, "RunOnce")
    assert await tick_statuses(tree.tick_exactly_once, 2) == [S, K]
    assert stubs.starts("A") == 1
