"""GoalUpdated and GlobalUpdatedGoal, including Nav2's reactive-parent quirk."""

from __future__ import annotations

import pytest

from aiobt.core.errors import BlackboardError, NodeError
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.msgs import Goals, PoseStamped, pose_stamped_from_string
from tests.unit.nav.test_nav2_support import Script, build

S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING

# Nav2's shape: re-plan when the goal changes, while following (RUNNING).
REACTIVE = """
<ReactiveFallback>
  <{condition}/>
  <Leaf name="Follow"/>
</ReactiveFallback>"""

# the same condition under a plain Sequence, ticked on its own
ALONE = """
<Sequence>
  <Leaf name="Step"/>
  <{condition}/>
</Sequence>"""


async def _results(tree: Tree, goals: list[str]) -> list[Status]:
    results = []
    for goal in goals:
        # goal "a" is the pose x=0 ("0;0;0" in Nav2's text), "b" x=1, ...
        tree.root_blackboard.set("goal", f"{ord(goal) - ord('a')};0;0")
        results.append(await tree.tick_exactly_once())
    return results


async def test_goal_updated_fires_once_per_change_when_its_parent_keeps_it() -> None:
    script = Script()
    # a 2-child IfThenElse leaves a failed condition un-reset (BT.CPP), so its memory survives
    tree = build(script, '<IfThenElse><GoalUpdated/><Leaf name="Replan"/></IfThenElse>')
    assert await _results(tree, ["a", "b", "b", "b", "c"]) == [F, S, F, F, S]
    assert script.ticks("Replan") == 2


async def test_goal_updated_under_a_reactive_parent_never_fires() -> None:
    script = Script()
    script.set("Follow", "R")
    tree = build(script, REACTIVE.format(condition="GoalUpdated"))
    # the goal changes on every tick, yet the reset-every-tick parent hides it (Nav2's quirk)
    assert await _results(tree, ["a", "b", "c", "d"]) == [R, R, R, R]
    assert script.ticks("Follow") == 4
    assert script.halts("Follow") == 0


async def test_global_updated_goal_fires_under_a_reactive_parent() -> None:
    script = Script()
    script.set("Follow", "R")
    tree = build(script, REACTIVE.format(condition="GlobalUpdatedGoal"))
    assert await _results(tree, ["a", "a", "b", "b"]) == [R, R, S, R]
    # the goal change made the fallback succeed, which halted the running follower
    assert script.halts("Follow") == 1


async def test_goal_updated_compares_goal_and_goals_from_ports() -> None:
    script = Script()
    tree = build(
        script,
        '<IfThenElse><GoalUpdated goal="{target}" goals="{targets}"/>'
        '<Leaf name="Replan"/></IfThenElse>',
    )
    bb = tree.root_blackboard
    bb.set("target", PoseStamped.from_xy_yaw(1.0, 2.0, 0.0))
    bb.set("targets", Goals(goals=[PoseStamped.from_xy_yaw(3.0, 4.0, 0.0)]))
    bb.set("goal", "ignored: the ports are set")
    assert await tree.tick_exactly_once() is F  # first tick: remembers
    bb.set("goal", "changed, but not what the ports read")
    assert await tree.tick_exactly_once() is F
    bb.set("targets", Goals(goals=[PoseStamped.from_xy_yaw(3.0, 5.0, 0.0)]))
    assert await tree.tick_exactly_once() is S


async def test_goal_ports_take_nav2_pose_strings() -> None:
    script = Script()
    # BT.CPP converts a string blackboard entry for a typed port; Nav2's text form works
    tree = build(
        script,
        '<IfThenElse><GoalUpdated goal="{target}"/><Leaf name="Replan"/></IfThenElse>',
    )
    bb = tree.root_blackboard
    bb.set("target", "1.0;2.0;0.5")
    assert await tree.tick_exactly_once() is F  # first tick: remembers
    bb.set("target", "1.0;2.0;0.5")
    assert await tree.tick_exactly_once() is F  # the same pose again
    bb.set("target", "1.5;2.0;0.5")
    assert await tree.tick_exactly_once() is S
    # the entry is typed by the port: bad text is refused when written, naming key and type
    with pytest.raises(BlackboardError, match=r"\[target\].*PoseStamped.*fields"):
        bb.set("target", "not a pose")


async def test_goal_text_on_the_blackboard_fallback_is_compared_as_a_pose() -> None:
    script = Script()
    tree = build(script, '<IfThenElse><GoalUpdated/><Leaf name="Replan"/></IfThenElse>')
    bb = tree.root_blackboard
    bb.set("goal", "1;2;0.5")
    assert await tree.tick_exactly_once() is F  # first tick: remembers
    bb.set("goal", "1.0;2.0;0.5")  # other text, the same pose
    assert await tree.tick_exactly_once() is F
    bb.set("goal", pose_stamped_from_string("1;2;0.5"))  # the pose itself
    assert await tree.tick_exactly_once() is F
    bb.set("goal", "1.5;2.0;0.5")
    assert await tree.tick_exactly_once() is S
    bb.set("goal", "not a pose")
    with pytest.raises(NodeError, match=r"blackboard key \[goal\].*fields"):
        await tree.tick_exactly_once()
