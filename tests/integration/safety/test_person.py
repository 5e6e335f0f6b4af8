"""A person steps into the robot's way and out again: the collision monitor stops the
robot, it waits, and it resumes when the way is clear; the path is still followed to
its end (Nav2's progress checker, 0.5 m in 10 s, does not abort it)."""

from __future__ import annotations

import pytest

from aiobt.msgs import FollowPath
from aiobt.msgs.sim import Ack, RemoveObstacle, SpawnObstacle
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import sim_namespace
from tests.integration.controller.helpers import path_through

from .chain import Spawn, Trace, start_chain

pytestmark = [pytest.mark.integration, pytest.mark.e2e]
WAIT = 3.0  # sim s the person stands in the way


@pytest.mark.timeout(150)
async def test_the_robot_stops_for_a_person_waits_and_arrives(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    trace = Trace(bus)
    await start_chain(spawn, bus, bus_settings)
    client = bus.action_client("follow_path", FollowPath)
    path = path_through([(-1.8, 0.0), (1.2, 0.0)])
    goal = await client.send_goal(FollowPath.Goal(path=path), server_timeout=15.0)
    await trace.until(lambda: trace.speed >= 0.45, 30.0, "full speed")
    x = trace.poses[-1].x
    person = SpawnObstacle(id="person", shape="cylinder", x=x + 0.9, y=0.0, radius=0.2,
                           height=1.7)  # fmt: skip
    sim = sim_namespace(bus.namespace)  # the simulation's services
    assert (await bus.call("obstacles/spawn", person, Ack, timeout=5.0, namespace=sim)).ok
    await trace.until(lambda: trace.still_since(WAIT), 60.0, f"{WAIT} s standing")
    stopped_at = trace.poses[-1].x
    assert trace.states[-1].action == "stop"
    gone = await bus.call("obstacles/remove", RemoveObstacle(id="person"), Ack, 5.0, namespace=sim)
    assert gone.ok
    result = await goal.result(timeout=60.0)
    print(f"stopped {person.x - person.radius - stopped_at - 0.22:.3f} m short; {result}")
    assert result.error_code == 0, result
    assert trace.poses[-1].x == pytest.approx(1.2, abs=0.3)
    assert trace.states[-1].action in ("none", "approach")
