"""RetryUntilSuccessful and Repeat: counts, yielding between instant cycles, limits."""

from __future__ import annotations

import pytest

from aiobt.core.errors import TreeLoadError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tick_statuses, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE


def _tree(factory: BehaviorTreeFactory, decorator: str, attributes: str):
    return factory.create_tree_from_text(
        tree_xml(f'<{decorator} {attributes}><StubAction name="A"/></{decorator}>')
    )


async def test_retry_yields_between_instant_failures(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE")
    tree = _tree(bt_factory, "RetryUntilSuccessful", 'num_attempts="3"')
    assert await tick_statuses(tree.tick_exactly_once, 4) == [R, R, F, R]
    assert stubs.starts("A") == 4


async def test_retry_tick_once_runs_all_attempts(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE")
    tree = _tree(bt_factory, "RetryUntilSuccessful", 'num_attempts="3"')
    assert await tree.tick_once() is F
    assert stubs.starts("A") == 3


async def test_retry_succeeds_after_running_attempt(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE", "RUNNING", "SUCCESS")
    tree = _tree(bt_factory, "RetryUntilSuccessful", 'num_attempts="3"')
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, S]
    assert stubs.log == ["A:start", "A:start", "A:running"]


async def test_retry_restarts_at_once_after_a_running_attempt_fails(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "RUNNING", "FAILURE", "RUNNING", "FAILURE")
    tree = _tree(bt_factory, "RetryUntilSuccessful", 'num_attempts="2"')
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, F]
    assert stubs.log == ["A:start", "A:running", "A:start", "A:running"]


async def test_retry_forever(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE", "FAILURE", "FAILURE", "FAILURE", "SUCCESS")
    tree = _tree(bt_factory, "RetryUntilSuccessful", 'num_attempts="-1"')
    assert await tick_statuses(tree.tick_exactly_once, 5) == [R, R, R, R, S]


@pytest.mark.parametrize(
    ("decorator", "attributes", "expected"),
    [("RetryUntilSuccessful", 'num_attempts="0"', F), ("Repeat", 'num_cycles="0"', S)],
)
async def test_zero_count_finishes_without_ticking_child(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, decorator: str, attributes: str, expected: Status
):
    tree = _tree(bt_factory, decorator, attributes)
    assert await tree.tick_exactly_once() is expected
    assert stubs.ticks("A") == 0


@pytest.mark.parametrize(
    ("decorator", "port"), [("RetryUntilSuccessful", "num_attempts"), ("Repeat", "num_cycles")]
)
def test_missing_count_is_a_load_error(bt_factory: BehaviorTreeFactory, decorator: str, port: str):
    with pytest.raises(TreeLoadError, match=rf"missing its required port \[{port}\]") as info:
        _tree(bt_factory, decorator, "")
    assert info.value.node_path == f"MainTree/{decorator}"
    assert info.value.line == 1


async def test_repeat_yields_between_cycles(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    tree = _tree(bt_factory, "Repeat", 'num_cycles="3"')
    assert await tick_statuses(tree.tick_exactly_once, 4) == [R, R, S, R]
    stubs.clear()
    tree2 = _tree(bt_factory, "Repeat", 'num_cycles="3"')
    assert await tree2.tick_once() is S
    assert stubs.starts("A") == 3


async def test_repeat_fails_as_soon_as_child_fails(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "SUCCESS", "FAILURE")
    tree = _tree(bt_factory, "Repeat", 'num_cycles="3"')
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, F, F]
    assert stubs.starts("A") == 3


async def test_repeat_skipped_child(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "SKIPPED")
    tree = _tree(bt_factory, "Repeat", 'num_cycles="3"')
    assert await tree.tick_exactly_once() is K


async def test_repeat_halt_resets_the_count(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "SUCCESS", "RUNNING", "SUCCESS")
    tree = _tree(bt_factory, "Repeat", 'num_cycles="2"')
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, R]
    await tree.halt_tree("stop")
    assert stubs.halts("A") == 1
    # after the halt two full cycles are needed again
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, S]
