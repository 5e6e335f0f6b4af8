"""DistanceController and SpeedController: how often they tick their child."""

from __future__ import annotations

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.msgs import Odometry
from aiobt.msgs.geometry import Header, Twist, Vector3
from aiobt.testing.stubs import Stubs
from aiobt.transport import Bus
from tests.unit.nav.state_support import at, deliver, nav_tree

S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
pytestmark = pytest.mark.timeout(60)


def pipeline(decorator: str) -> str:
    """The decorator first in a PipelineSequence (which keeps ticking it), as in Nav2's trees."""
    name = decorator.split()[0].strip("<>")
    return (
        f'<PipelineSequence>{decorator}<StubAction name="plan" results="S"/></{name}>'
        '<StubAction name="follow" results="R"/></PipelineSequence>'
    )


async def test_distance_controller_replans_every_metre(local_bus: Bus) -> None:
    stubs = Stubs()
    tree = nav_tree(local_bus, pipeline('<DistanceController distance="1.0">'), stubs=stubs)
    assert await tree.tick_exactly_once() is F  # no robot pose
    assert stubs.ticks("plan") == 0
    await deliver(local_bus, "pose", at(0.0))
    assert await tree.tick_exactly_once() is R  # the first tick plans
    assert stubs.ticks("plan") == 1
    await deliver(local_bus, "pose", at(0.7))
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 1
    await deliver(local_bus, "pose", at(1.0, 0.2))
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 2
    await deliver(local_bus, "pose", at(1.5, 0.2))
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 2


def odom(stamp: float, speed: float) -> Odometry:
    return Odometry(
        header=Header(stamp=stamp, frame_id="odom"), twist=Twist(linear=Vector3(x=speed))
    )


async def test_speed_controller_ticks_faster_when_the_robot_is_faster(local_bus: Bus) -> None:
    clock = ManualClock()
    stubs = Stubs()
    body = pipeline(
        '<SpeedController min_rate="0.5" max_rate="2.0" min_speed="0.0" max_speed="1.0">'
    )
    tree = nav_tree(local_bus, body, clock=clock, stubs=stubs)
    assert await tree.tick_exactly_once() is R  # first tick: the child now
    assert stubs.ticks("plan") == 1
    clock.advance(0.4)
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 1  # period 1/max_rate = 0.5 s not over
    clock.advance(0.2)  # standing still: the next period is 1/min_rate = 2 s
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 2
    clock.advance(1.5)
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 2
    await deliver(local_bus, "odom", odom(1.0, 1.5))  # fast: next period 1/max_rate
    clock.advance(0.6)
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 3
    clock.advance(0.5)
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 4


async def test_speed_controller_ticks_again_when_the_goal_changes(local_bus: Bus) -> None:
    clock = ManualClock()
    stubs = Stubs()
    tree = nav_tree(local_bus, pipeline("<SpeedController>"), clock=clock, stubs=stubs)
    tree.root_blackboard["goal"] = at(1.0)
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 1
    tree.root_blackboard["goal"] = at(2.0)
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("plan") == 2


async def test_speed_controller_refuses_a_zero_rate() -> None:
    tree = nav_tree(None, pipeline('<SpeedController min_rate="0">'), stubs=Stubs())
    with pytest.raises(NodeError, match="rates must be > 0"):
        await tree.tick_exactly_once()
