"""Scenario 7 of issue 15: the planner SIGKILLed mid-navigation, on a stack of its own.

The navigation must not hang: the planning leaf fails within 1.5 s of the kill
and the recoveries run; once the planner is restarted (and nothing else), the
next goal succeeds.
"""

from __future__ import annotations

import math
import time

import pytest

from aiobt.msgs import GoalState
from aiobt.testing.navwatch import ServerGoals
from aiobt.testing.stack import NavStack
from aiobt.testing.treewatch import TreeWatch

from .world import World

pytestmark = [pytest.mark.e2e, pytest.mark.integration]

FAR_ROOM = (18.5, 18.0, math.pi / 2)
SOUTH_MIDDLE_ROOM = (10.0, 6.0, 0.0)
RECOVERIES = ("ClearGlobalCostmap-Context", "ClearingActions", "Spin", "Wait", "BackUp")
LEAF_FAILS_WITHIN = 1.5  # wall s from the kill


@pytest.mark.timeout(200)
async def test_planner_killed_mid_navigation_fails_fast_recovers_and_next_goal_succeeds(
    own_stack: NavStack, world: World, goals: ServerGoals, tree: TreeWatch
):
    others = {name: own_stack.processes[name].pid for name in own_stack.processes}
    del others["planner"]
    running = await world.start(*FAR_ROOM)
    moving = await world.track.wait_for(lambda _: world.track.driven > 1.0, 60.0)
    assert moving is not None, "the robot does not move"

    own_stack.kill("planner")
    killed = time.monotonic()
    failed = await tree.wait_for(lambda: tree.find("ComputePathToPose", "FAILURE", killed), 10.0)
    assert failed, "ComputePathToPose did not fail after the planner was killed"
    event = tree.find("ComputePathToPose", "FAILURE", killed)
    assert event is not None
    assert event.wall - killed <= LEAF_FAILS_WITHIN, f"failed {event.wall - killed:.2f} s later"
    recovered = await tree.wait_for(lambda: tree.activations(RECOVERIES, killed), 30.0)
    assert recovered, "no recovery ran after the planner died"

    done = await running.end(120.0)  # bounded: no hang with the planner gone
    assert done.state is GoalState.ABORTED, done.result
    assert done.result.error_code != 0

    goals.forget_unfinished("compute_path_to_pose")  # they died with the planner process
    own_stack.start("planner")
    await own_stack.wait_ready(world.bus, ["planner"], timeout=60.0)
    again = await world.navigate(*SOUTH_MIDDLE_ROOM, timeout=120.0)
    assert again.state is GoalState.SUCCEEDED, again.result
    world.assert_at(*SOUTH_MIDDLE_ROOM)
    assert {name: own_stack.processes[name].pid for name in others} == others
    assert all(own_stack.processes[name].running for name in others), "another service died"
    assert await goals.wait_idle(5.0), goals.active()
