"""PathLongerOnApproach: the child runs only for a much longer re-plan near the goal."""

from __future__ import annotations

import pytest

from aiobt.core.status import Status
from aiobt.msgs import Path
from aiobt.testing.stubs import Stubs
from tests.unit.nav.state_support import at, nav_tree, straight_path

S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
pytestmark = pytest.mark.timeout(30)
BODY = (
    '<PathLongerOnApproach path="{path}" prox_len="3.0" length_factor="2.0">'
    '<StubAction name="child" results="R;S"/></PathLongerOnApproach>'
)
NEAR = straight_path(3)  # 2 m to the goal at (2, 0)
DETOUR = Path(poses=[at(0, 0), at(0, 3), at(2, 3), at(2, 0)])  # 8 m, same goal


async def test_a_much_longer_replan_near_the_goal_ticks_the_child() -> None:
    stubs = Stubs()
    tree = nav_tree(None, BODY, stubs=stubs)
    tree.root_blackboard["path"] = NEAR
    assert await tree.tick_exactly_once() is S
    assert stubs.ticks("child") == 0
    tree.root_blackboard["path"] = DETOUR
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is S  # the child finished: reset, detour is old now
    assert stubs.ticks("child") == 2
    assert await tree.tick_exactly_once() is S
    assert stubs.ticks("child") == 2


async def test_far_from_the_goal_or_a_new_goal_skips_the_child() -> None:
    stubs = Stubs()
    tree = nav_tree(None, BODY, stubs=stubs)
    far = straight_path(6)  # 5 m: not near
    tree.root_blackboard["path"] = far
    assert await tree.tick_exactly_once() is S
    tree.root_blackboard["path"] = Path(poses=[*far.poses[:2], at(1, 9), far.poses[-1]])
    assert await tree.tick_exactly_once() is S
    tree.root_blackboard["path"] = NEAR
    assert await tree.tick_exactly_once() is S  # a new goal: starts over
    tree.root_blackboard["path"] = DETOUR
    assert await tree.tick_exactly_once() is R  # now it is an update near the goal
    assert stubs.ticks("child") == 1


async def test_a_replan_only_slightly_longer_skips_the_child() -> None:
    stubs = Stubs()
    tree = nav_tree(None, BODY, stubs=stubs)
    tree.root_blackboard["path"] = NEAR
    assert await tree.tick_exactly_once() is S
    tree.root_blackboard["path"] = Path(poses=[at(0, 0), at(1, 0.5), at(1.5, 0.2), at(2, 0)])
    assert await tree.tick_exactly_once() is S
    assert stubs.ticks("child") == 0
