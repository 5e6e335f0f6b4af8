"""tests/e2e's navigation scenarios, run by :mod:`tests.netlab.scenario` inside a host
of the lab: each starts from tests/e2e's clean world (no goal, no obstacle, clean
costmaps, the robot at the start) and reports in JSON lines.

- ``through``: NavigateThroughPoses through the three south rooms
  (tests/e2e/test_navigate.py); event ``result`` with the state, where the robot
  is, how close it came to each pose and the ``number_of_poses_remaining`` feedback;
- ``blocked``: NavigateToPose to the corridor's east end, the corridor walled off
  once the robot is under way (tests/e2e/test_obstacles.py); event ``result`` with
  the state, where the robot is, how far from the corridor's middle it crossed x 12
  (it must go round through the rooms) and the bumper's contacts. The wall is
  removed after.
- ``goal-watch``: until SIGTERM, every status every action server puts, per server
  and goal id, in order; event ``goals`` (``{server: {goal_id: [state, ...]}}``).
"""

from __future__ import annotations

import asyncio
import math
from collections.abc import Callable
from typing import Any

from aiobt.msgs import GoalStatus, NavigateThroughPoses, PoseStamped
from aiobt.msgs.sim import BumperEvent
from aiobt.testing.navwatch import RobotTrack
from aiobt.transport import Bus
from aiobt.transport.topics import declare_subscription
from tests.e2e.test_navigate import ROOMS
from tests.e2e.test_obstacles import CORRIDOR_EAST
from tests.e2e.world import ACTIONS, World

Say = Callable[..., None]
MOVING = 0.3  # m driven: the plan is made and followed
WALL = {"x": 12.0, "y": 9.75, "size_x": 0.4, "size_y": 2.7}  # wall to wall across the corridor


def _where(track: RobotTrack) -> dict[str, Any]:
    at = track.latest
    return {"x": None if at is None else at.x, "y": None if at is None else at.y}


async def through(bus: Bus, say: Say, timeout: float) -> None:  # noqa: ASYNC109
    track = RobotTrack(bus)
    world = World(bus, track)
    await world.clear()
    say("ready")
    remaining: list[int] = []
    poses = [PoseStamped.from_xy_yaw(*pose) for pose in ROOMS]
    sent = await world.through.send_goal(
        NavigateThroughPoses.Goal(poses=poses), server_timeout=10.0
    )
    sent.on_feedback = lambda f: remaining.append(f.number_of_poses_remaining)
    say("accepted")
    result = await sent.result(timeout)
    say(
        "result",
        state=sent.status.name,
        error_code=result.error_code,
        error_msg=result.error_msg,
        closest=[track.closest(x, y) for x, y, _ in ROOMS],
        remaining=remaining,
        **_where(track),
    )
    track.close()


async def blocked(bus: Bus, say: Say, timeout: float) -> None:  # noqa: ASYNC109
    track = RobotTrack(bus)
    world = World(bus, track)
    await world.clear()
    contacts: list[BumperEvent] = []
    bus.subscribe("bumper", BumperEvent, contacts.append)
    say("ready")
    running = await world.start(*CORRIDOR_EAST)
    say("accepted")
    moving = await track.wait_for(lambda _: track.driven > MOVING, 60.0)
    wall = await world.spawn(**WALL)
    say("blocked", moving=moving is not None)
    done = await running.end(timeout)
    crossing = [abs(s.y - WALL["y"]) for s in track.samples if 11.0 < s.x < 13.0]
    say(
        "result",
        state=done.state.name,
        error_code=done.result.error_code,
        error_msg=done.result.error_msg,
        through_rooms=min(crossing, default=math.inf),
        contacts=sum(1 for c in contacts if c.pressed),
        **_where(track),
    )
    await world.remove(wall)
    track.close()


async def goal_watch(bus: Bus, say: Say, stop: asyncio.Event) -> None:
    history: dict[str, dict[str, list[str]]] = {action.name: {} for action in ACTIONS}

    def recorder(server: str) -> Callable[[GoalStatus], None]:
        def record(status: GoalStatus) -> None:
            history[server].setdefault(status.goal_id, []).append(status.status.name)

        return record

    subs = [
        declare_subscription(
            bus.session,
            bus.bridge,
            bus.keys.action(action.name).any_status,
            GoalStatus,
            callback_fn=recorder(action.name),
            latched=False,
            queue_size=1000,
        )
        for action in ACTIONS
    ]
    say("watching")
    await stop.wait()
    say("goals", history={server: goals for server, goals in history.items() if goals})
    for sub in subs:
        sub.close()
