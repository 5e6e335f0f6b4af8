"""The end-to-end watchers on an in-process bus: server goal states and the tree stream."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from aiobt.msgs import BtNode, BtTransition, BtTransitions, BtTree, Wait
from aiobt.testing.navwatch import ServerGoals
from aiobt.testing.treewatch import TreeWatch
from aiobt.transport import Bus

pytestmark = pytest.mark.timeout(90)
WAIT = 30.0  # s: generous, the machine is shared


async def test_server_goals_follow_states_and_the_last_result_code(local_bus: Bus) -> None:
    release = asyncio.Event()

    async def execute(goal: Any, handle: Any) -> Any:
        await release.wait()
        return Wait.Result(error_code=741 if goal.time > 1.0 else 0, error_msg="")

    local_bus.action_server(Wait.name, Wait, execute)
    goals = ServerGoals(local_bus, [Wait])
    client = local_bus.action_client(Wait.name, Wait)
    assert await client.wait_for_server(WAIT)
    sent = await client.send_goal(Wait.Goal(time=2.0), server_timeout=WAIT)
    assert await goals.wait_for(lambda: bool(goals.active()), WAIT)
    assert goals.active() == {Wait.name: [sent.goal_id]}

    release.set()
    await sent.result(WAIT)
    assert await goals.wait_idle(WAIT)
    assert await goals.wait_for(lambda: Wait.name in goals.last_code, WAIT)
    assert goals.states[Wait.name] == {sent.goal_id: sent.status}
    assert sent.status.is_terminal
    assert goals.last_code[Wait.name] == 741
    goals.close()


def _tree(run: int) -> BtTree:
    nodes = [
        BtNode(uid=1, parent=None, path="T/RoundRobin", id="RoundRobin", name="R", kind="Control"),
        BtNode(uid=2, parent=1, path="T/R/Spin", id="Spin", name="Spin", kind="Action"),
        BtNode(uid=3, parent=1, path="T/R/Wait", id="Wait", name="Pause", kind="Action"),
    ]
    return BtTree(run=run, tree_id="T", nodes=nodes)


def _changes(run: int, *changes: tuple[int, str, str]) -> BtTransitions:
    return BtTransitions(
        run=run,
        transitions=[BtTransition(uid=u, previous=p, status=s) for u, p, s in changes],
    )


async def test_tree_watch_names_transitions_and_lists_activations_in_order(local_bus: Bus) -> None:
    watch = TreeWatch(local_bus)
    structure = local_bus.latched_publisher("bt/tree", BtTree)
    transitions = local_bus.publisher("bt/transitions", BtTransitions)
    assert await transitions.wait_for_subscribers(WAIT)
    transitions.put(_changes(1, (1, "IDLE", "RUNNING")))  # before its structure: kept
    structure.put(_tree(1))
    transitions.put(_changes(1, (2, "IDLE", "RUNNING"), (2, "RUNNING", "SUCCESS")))
    transitions.put(_changes(1, (2, "SUCCESS", "IDLE"), (3, "IDLE", "FAILURE")))
    transitions.put(_changes(1, (3, "FAILURE", "IDLE"), (2, "IDLE", "RUNNING")))
    assert await watch.wait_for(lambda: len(watch.events) == 7, WAIT)

    assert watch.activations(("Spin", "Pause")) == ["Spin", "Pause", "Spin"]
    assert watch.activations(("Wait",)) == ["Pause"]  # by node ID too
    failed = watch.find("Wait", "FAILURE")
    assert failed is not None
    assert failed.name == "Pause"
    assert watch.find("Spin", "FAILURE") is None
    watch.close()
