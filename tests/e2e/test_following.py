"""``<FollowObject>`` in a tree the navigator runs, against the following server
(issue 36): the module's stack adds ``aiobt following`` to the usual services.

- NavigateToPose naming a tree of one FollowObject: the robot follows the box walking
  its seeded loop at 0.3 m/s for the node's ``max_duration``, and the navigation
  succeeds;
- the same tree on a topic nothing publishes: the navigation fails with the following
  server's 902 and its message naming the topic, and the stack runs on.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path

import pytest

from aiobt.msgs import Empty, GoalState, PoseStamped
from aiobt.msgs.follow_target import (
    OFFICE_LOOP_CENTRE,
    OFFICE_LOOP_RADII,
    StartTarget,
    TargetStarted,
)
from aiobt.msgs.remote_actions import FollowObjectError
from aiobt.msgs.sim import Ack
from aiobt.testing.localize import set_estimate
from aiobt.testing.stack import SERVICES, NavStack, StackConfig, running_stack
from aiobt.transport import Bus
from aiobt.transport.keys import sim_namespace
from aiobt_services.robot.target_path import seeded_loop
from tests.integration.following.truth import Watch

from .conftest import SPEED
from .world import World

pytestmark = [pytest.mark.e2e, pytest.mark.integration]

SEED, DURATION = 23, 30.0
FOLLOWING = ["--sim-time", "--search-by-rotating", "true", "--controller.v-linear-max", "0.5",
             "--controller.v-angular-max", "1.0"]  # fmt: skip
TREE = """<root BTCPP_format="4" main_tree_to_execute="Follow">
  <BehaviorTree ID="Follow">
    <FollowObject pose_topic="{topic}" max_duration="{duration}"
                  error_code_id="{{follow_object_error_code}}"
                  error_msg="{{follow_object_error_msg}}"/>
  </BehaviorTree>
</root>
"""


@pytest.fixture(scope="module")
def _module_stack() -> Iterator[NavStack]:
    config = StackConfig(world="office", speed=SPEED, seed=7, services=(*SERVICES, "following"),
                         extra={"following": FOLLOWING})  # fmt: skip
    with running_stack(config) as stack:
        yield stack


def tree(tmp_path: Path, topic: str) -> str:
    path = tmp_path / "follow.xml"
    path.write_text(TREE.format(topic=topic, duration=DURATION))
    return str(path)


async def behind_the_box(bus: Bus) -> None:
    """The robot 1 m behind the box's start on its loop, facing it; the box started."""
    loop = seeded_loop(OFFICE_LOOP_CENTRE, OFFICE_LOOP_RADII, SEED)
    behind, ahead = loop.pose_at(loop.length - 1.0), loop.pose_at(0.0)
    yaw = math.atan2(ahead.y - behind.y, ahead.x - behind.x)
    sim = sim_namespace(bus.namespace)  # the simulation's services
    there = PoseStamped.from_xy_yaw(behind.x, behind.y, yaw)
    placed = await bus.call("reset_pose", there, Ack, namespace=sim)
    assert placed.ok, placed.message
    await set_estimate(bus, behind.x, behind.y, yaw)  # as a user would after carrying it
    started = await bus.call("follow_target/start", StartTarget(seed=SEED, hold=0.5),
                             TargetStarted, timeout=10.0, namespace=sim)  # fmt: skip
    assert started.ok, started.message


@pytest.mark.timeout(300)
async def test_a_follow_object_tree_follows_the_walking_box(
    world: World, bus: Bus, tmp_path: Path
) -> None:
    watch = Watch.on(bus)
    await behind_the_box(bus)
    await watch.until(0.0, wall=30.0)
    t0 = watch.now
    done = await world.navigate(0.0, 0.0, tree=tree(tmp_path, "dynamic_pose"), timeout=200.0)
    assert done.state is GoalState.SUCCEEDED, done.result
    inside = watch.inside(t0 + 3.0, t0 + DURATION, desired=1.0, band=0.3)
    assert inside >= 0.9, inside
    assert not [b for b in watch.bumps if b.pressed], watch.bumps
    sim = sim_namespace(bus.namespace)  # the simulation's services
    stopped = await bus.call("follow_target/stop", Empty(), Ack, namespace=sim)
    assert stopped.ok, stopped.message


@pytest.mark.timeout(200)
async def test_a_follow_object_tree_on_a_silent_topic_fails_naming_it(
    world: World, tmp_path: Path
) -> None:
    done = await world.navigate(0.0, 0.0, tree=tree(tmp_path, "people/carol"), timeout=120.0)
    assert done.state is GoalState.ABORTED, done.result
    assert done.result.error_code == FollowObjectError.FAILED_TO_DETECT_OBJECT
    assert "people/carol" in done.result.error_msg
