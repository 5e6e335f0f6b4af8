"""GoalUpdater: newer goals from {ns}/goal_update and {ns}/goals_update replace the input."""

from __future__ import annotations

import pytest

from aiobt.core.status import Status
from aiobt.msgs import Goals
from aiobt.testing.stubs import Stubs
from aiobt.transport import Bus
from tests.unit.nav.state_support import at, deliver, nav_tree

S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
pytestmark = pytest.mark.timeout(60)
UPDATER = (
    '<GoalUpdater input_goal="{goal}" output_goal="{updated}" input_goals="{goals}" '
    'output_goals="{updated_goals}"><StubAction name="child" results="{results}"/></GoalUpdater>'
)


async def test_passes_the_input_goal_until_an_update_then_the_newer_update(
    local_bus: Bus,
) -> None:
    stubs = Stubs()
    tree = nav_tree(local_bus, UPDATER.replace("{results}", "R"), stubs=stubs)
    bb = tree.root_blackboard
    bb["goal"] = at(1.0, stamp=10.0)
    bb["goals"] = Goals(goals=[at(1.0, stamp=10.0)])
    assert await tree.tick_exactly_once() is R  # the child's status
    assert bb["updated"].x == 1.0
    await deliver(local_bus, "goal_update", at(2.0, stamp=11.0))
    assert await tree.tick_exactly_once() is R
    assert bb["updated"].x == 2.0
    assert stubs.ticks("child") == 2


async def test_an_older_or_unstamped_update_is_ignored(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, UPDATER.replace("{results}", "S"), stubs=Stubs())
    bb = tree.root_blackboard
    bb["goal"] = at(1.0, stamp=10.0)
    await deliver(local_bus, "goal_update", at(2.0, stamp=9.0))
    assert await tree.tick_exactly_once() is S
    assert bb["updated"].x == 1.0
    await deliver(local_bus, "goal_update", at(3.0, stamp=0.0))
    assert await tree.tick_exactly_once() is S
    assert bb["updated"].x == 1.0


async def test_goals_updates_replace_input_goals_unless_empty(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, UPDATER.replace("{results}", "F"), stubs=Stubs())
    bb = tree.root_blackboard
    bb["goal"] = at(1.0, stamp=10.0)
    original = Goals.model_validate({"header": {"stamp": 10.0}, "goals": [at(1.0)]})
    bb["goals"] = original
    newer = Goals.model_validate({"header": {"stamp": 12.0}, "goals": [at(5.0), at(6.0)]})
    await deliver(local_bus, "goals_update", newer)
    assert await tree.tick_exactly_once() is F
    assert [g.x for g in bb["updated_goals"].goals] == [5.0, 6.0]
    await deliver(local_bus, "goals_update", Goals.model_validate({"header": {"stamp": 13.0}}))
    assert await tree.tick_exactly_once() is F
    assert bb["updated_goals"] == original
