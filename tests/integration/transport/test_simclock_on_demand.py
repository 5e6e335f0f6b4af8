"""The sim clock followed on demand through a real router: an idle follower lets the
clock's subscription go, and a sleep or an action goal after idle hears it again."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator

import pytest

from aiobt.msgs import Clock, Wait
from aiobt.transport import Bus, GoalHandle, SimClockFollower
from aiobt.transport.simtime import SimTime

pytestmark = [pytest.mark.integration, pytest.mark.timeout(60)]
STEP = 0.01  # robot s per stamp, one stamp every 2 ms wall (5x)
WaitHandle = GoalHandle[Wait.Goal, Wait.Result, Wait.Feedback]


class Sim:
    """Publishes ``{ns}/clock`` from another session until stopped; ``time`` is the last
    stamp sent."""

    def __init__(self, bus: Bus) -> None:
        self.pub = bus.publisher("clock", Clock)
        self.time = 0.0

    async def run(self) -> None:
        while True:
            self.time += STEP
            self.pub.put(Clock(clock=self.time))
            await asyncio.sleep(0.002)  # the simulation's own pace (wall), not a wait


@pytest.fixture
async def sim(client_bus: Bus) -> AsyncIterator[Sim]:
    sim = Sim(client_bus)
    task = asyncio.create_task(sim.run())
    yield sim
    task.cancel()
    await asyncio.gather(task, return_exceptions=True)


async def idle(follower: SimClockFollower) -> None:
    """Wait (bounded) until the follower let its subscription go."""
    async with asyncio.timeout(10.0):
        while follower.attached:  # noqa: ASYNC110 - the linger is a loop timer
            await asyncio.sleep(0.02)


async def started(bus: Bus) -> tuple[SimClockFollower, SimTime]:
    follower = SimClockFollower(bus, on_demand=True)
    await follower.wait_started(10.0)
    assert isinstance(follower.clock, SimTime)
    return follower, follower.clock


async def test_an_idle_follower_unsubscribes_and_a_sleep_hears_fresh_time(
    bus: Bus, sim: Sim
) -> None:
    follower, clock = await started(bus)
    await idle(follower)
    stood = clock.now()
    async with asyncio.timeout(10.0):
        while sim.time < stood + 1.0:  # noqa: ASYNC110 - the robot's time moves on unheard
            await asyncio.sleep(0.02)
    assert clock.now() == stood
    asked_at = sim.time
    await asyncio.wait_for(clock.sleep(0.2), 10.0)
    assert follower.attached
    assert follower.attaches == 2
    assert clock.now() >= asked_at + 0.2  # counted from the robot's time, not the stale one
    await idle(follower)  # and let go again
    follower.close()


async def test_a_goal_after_idle_runs_on_the_robots_time(
    bus: Bus, client_bus: Bus, sim: Sim
) -> None:
    follower, clock = await started(bus)
    seen: list[float] = []

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        seen.append(clock.now())
        await clock.sleep(goal.time)
        seen.append(clock.now())
        return Wait.Result(total_elapsed_time=seen[-1] - seen[0])

    bus.action_server("wait", Wait, execute, clock=clock)
    client = client_bus.action_client("wait", Wait)
    assert await client.wait_for_server(10.0)
    await idle(follower)
    async with asyncio.timeout(10.0):
        while sim.time < clock.now() + 1.0:  # noqa: ASYNC110
            await asyncio.sleep(0.02)
    sent_at = sim.time
    goal = await client.send_goal(Wait.Goal(time=0.3), server_timeout=10.0)
    result = await goal.result(timeout=10.0)
    assert result.error_code == 0
    assert seen[0] >= sent_at  # the goal started on fresh time
    assert result.total_elapsed_time == pytest.approx(0.3, abs=0.1)
    await idle(follower)
    follower.close()
