"""Nav2 decorators: RateController, SingleTrigger, GoalUpdatedController."""

from __future__ import annotations

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from tests.unit.nav.test_nav2_support import Script, build

S, F, R, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.IDLE

# Nav2's replanning shape: plan at most once a second while following.
RATE = """
<PipelineSequence>
  <RateController hz="{hz}"><Leaf name="Plan"/></RateController>
  <Leaf name="Follow"/>
</PipelineSequence>"""


async def test_rate_controller_throttles_on_the_tree_clock() -> None:
    script = Script()
    script.set("Follow", "R")
    clock = ManualClock()
    tree = build(script, RATE.format(hz=1.0), clock)
    plan_ticks = []
    for _ in range(9):  # t = 0, 0.25, ... 2.0
        assert await tree.tick_exactly_once() is R
        plan_ticks.append(script.ticks("Plan"))
        clock.advance(0.25)
    assert plan_ticks == [1, 1, 1, 1, 2, 2, 2, 2, 3]
    assert script.ticks("Follow") == 9
    assert tree.find("RateController").status is S  # the child just succeeded at t=2.0
    await tree.tick_exactly_once()
    assert tree.find("RateController").status is R  # RUNNING while not ticking its child


async def test_rate_controller_ticks_a_running_child_every_tick() -> None:
    script = Script()
    script.set("Plan", "R R S")
    script.set("Follow", "R")
    clock = ManualClock()
    tree = build(script, RATE.format(hz=0.5), clock)
    for _ in range(4):
        await tree.tick_exactly_once()
        clock.advance(0.1)
    assert script.ticks("Plan") == 3  # RUNNING, RUNNING, SUCCESS; then throttled
    assert script.ticks("Follow") == 2  # reached once Plan had succeeded


async def test_rate_controller_failure_does_not_restart_the_period() -> None:
    script = Script()
    script.set("Plan", "S F S")
    script.set("Follow", "R")
    clock = ManualClock()
    tree = build(script, '<RateController hz="2"><Leaf name="Plan"/></RateController>', clock)
    root = tree.root
    assert await root.tick() is S
    clock.advance(0.5)
    assert await root.tick() is F  # due again after the success
    clock.advance(0.1)
    assert await root.tick() is S  # a failure leaves the period running: still due
    assert script.ticks("Plan") == 3


async def test_rate_controller_rejects_a_non_positive_rate() -> None:
    tree = build(Script(), '<RateController hz="0"><Leaf/></RateController>', ManualClock())
    with pytest.raises(NodeError, match="hz must be > 0"):
        await tree.tick_exactly_once()


async def test_single_trigger_fires_once_and_rearms_only_on_reset() -> None:
    script = Script()
    script.set("Once", "R S")
    tree = build(script, '<SingleTrigger><Leaf name="Once"/></SingleTrigger>')
    root = tree.root  # ticked directly: the tree would reset a finished root
    assert [await root.tick() for _ in range(4)] == [R, S, F, F]
    assert script.take() == ["Once", "Once"]
    root.reset_status()
    assert await root.tick() is S
    assert await root.tick() is F
    assert script.take() == ["Once"]
    await tree.halt_tree("rearm")
    assert await root.tick() is S


GOAL = """
<{parent}>
  <GoalUpdatedController><Leaf name="Plan"/></GoalUpdatedController>
  <Leaf name="Follow"/>
</{parent}>"""


async def test_goal_updated_controller_ticks_on_goal_changes() -> None:
    script = Script()
    script.set("Follow", "R")
    tree = build(script, GOAL.format(parent="PipelineSequence"))
    bb = tree.root_blackboard
    bb["goal"] = (1.0, 2.0)
    for _ in range(3):
        assert await tree.tick_exactly_once() is R
    assert script.ticks("Plan") == 1
    assert tree.find("GoalUpdatedController").status is R
    bb["goal"] = (3.0, 4.0)
    await tree.tick_exactly_once()
    await tree.tick_exactly_once()
    assert script.ticks("Plan") == 2
    bb["goals"] = [(5.0, 6.0)]
    await tree.tick_exactly_once()
    assert script.ticks("Plan") == 3
    assert script.ticks("Follow") == 6


async def test_goal_updated_controller_under_a_reactive_parent_nav2_quirk() -> None:
    script = Script()
    script.set("Follow", "R")
    tree = build(script, GOAL.format(parent="ReactiveSequence"))
    tree.root_blackboard["goal"] = (1.0, 2.0)
    for _ in range(4):
        assert await tree.tick_exactly_once() is R
    # the RUNNING sibling makes the parent reset the controller every tick, so
    # it forgets the goal and re-plans on every tick, goal changed or not
    assert script.ticks("Plan") == 4
