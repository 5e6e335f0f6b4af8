"""Navigations across the office world through the navigator, on one shared stack.

Scenarios 1, 2, 3 and 6 of issue 15: to the farthest room, through three rooms,
a goal from the ``zenoh`` command line, preemption and cancel mid-way.
"""

from __future__ import annotations

import asyncio
import math
import sys
from pathlib import Path

import pytest

from aiobt.msgs import GoalState, NavigateThroughPoses, NavigateToPose, PoseStamped
from aiobt.testing.navwatch import RobotTrack, ServerGoals
from aiobt.testing.stack import NavStack

from .world import World

pytestmark = [pytest.mark.e2e, pytest.mark.integration]

FAR_ROOM = (18.5, 18.0, math.pi / 2)  # the north-east room, about 25 m of path from the start
ROOMS = [(3.5, 6.5, -math.pi / 2), (10.0, 6.0, 0.0), (16.5, 6.0, math.pi / 2)]  # south rooms
OPEN_PLAN = (4.0, 13.5, math.pi / 2)  # through the corridor's north door at x 4


@pytest.mark.timeout(150)
async def test_crosses_the_office_to_the_farthest_room(world: World, goals: ServerGoals):
    done = await world.navigate(*FAR_ROOM, timeout=120.0)

    assert done.state is GoalState.SUCCEEDED, done.result
    assert done.result.error_code == 0
    world.assert_at(*FAR_ROOM)
    assert world.track.driven > math.dist(FAR_ROOM[:2], (2.0, 9.75))  # it drove around walls
    distances = [f.distance_remaining for f in done.feedback]
    assert distances, "no feedback from navigate_to_pose"
    assert max(distances) > 15.0, distances
    assert distances[-1] < 2.0, distances
    assert goals.ended("compute_path_to_pose", GoalState.SUCCEEDED) >= 2  # replanned on the way
    assert await goals.wait_idle(5.0), goals.active()


@pytest.mark.timeout(150)
async def test_navigates_through_poses_in_three_rooms(world: World, goals: ServerGoals):
    poses = [PoseStamped.from_xy_yaw(*pose) for pose in ROOMS]
    sent = await world.through.send_goal(
        NavigateThroughPoses.Goal(poses=poses), server_timeout=10.0
    )
    remaining: list[int] = []
    sent.on_feedback = lambda f: remaining.append(f.number_of_poses_remaining)
    result = await sent.result(120.0)

    assert sent.status is GoalState.SUCCEEDED, result
    world.assert_at(*ROOMS[-1])
    for x, y, _ in ROOMS[:-1]:  # each room on the way was visited
        assert world.track.closest(x, y) < 0.6, (x, y)
    assert remaining, "no feedback from navigate_through_poses"
    assert remaining[0] == 3, remaining
    assert min(remaining) <= 1, remaining
    assert remaining == sorted(remaining, reverse=True)  # passed poses are dropped, never readded
    assert await goals.wait_idle(5.0), goals.active()


@pytest.mark.timeout(120)
async def test_a_goal_from_the_zenoh_command_line_is_reached(
    world: World, goals: ServerGoals, stack: NavStack
):
    x, y, yaw = OPEN_PLAN
    command = [
        str(Path(sys.executable).parent / "zenoh"),
        *("--mode", "client", "--connect", stack.endpoint),
        *("put", "-k", f"{stack.namespace}/goal_pose"),
        *("-v", f'{{"x": {x}, "y": {y}, "yaw": {yaw}}}'),
    ]
    put = await asyncio.create_subprocess_exec(
        *command, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT
    )
    try:
        async with asyncio.timeout(30.0):
            output, _ = await put.communicate()
    finally:
        if put.returncode is None:
            put.kill()  # by its PID
            await put.wait()
    assert put.returncode == 0, output.decode(errors="replace")

    started = await goals.wait_for(lambda: bool(goals.states["navigate_to_pose"]), 15.0)
    assert started, "the navigator started no navigation from the goal_pose put"
    ended = await goals.wait_for(
        lambda: goals.ended("navigate_to_pose", GoalState.SUCCEEDED) == 1, 90.0
    )
    assert ended, goals.states["navigate_to_pose"]
    world.assert_at(x, y, yaw)


async def _drive_until(track: RobotTrack, metres: float) -> None:
    moved = await track.wait_for(lambda _: track.driven >= metres, 60.0)
    assert moved is not None, f"the robot drove {track.driven:.2f} m, not {metres}"


@pytest.mark.timeout(150)
async def test_a_newer_goal_preempts_the_running_one(world: World, goals: ServerGoals):
    first = await world.to_pose.send_goal(
        NavigateToPose.Goal(pose=PoseStamped.from_xy_yaw(*FAR_ROOM)), server_timeout=10.0
    )
    await _drive_until(world.track, 2.0)
    second = await world.navigate(*ROOMS[1], timeout=120.0)

    await first.result(10.0)
    assert first.status in (GoalState.ABORTED, GoalState.CANCELED), first.status
    assert second.state is GoalState.SUCCEEDED, second.result
    world.assert_at(*ROOMS[1])
    assert world.track.closest(*FAR_ROOM[:2]) > 5.0  # it turned away, never went on north-east
    assert await goals.wait_idle(5.0), goals.active()


@pytest.mark.timeout(120)
async def test_cancel_mid_way_stops_the_robot_and_leaves_no_goal(world: World, goals: ServerGoals):
    sent = await world.to_pose.send_goal(
        NavigateToPose.Goal(pose=PoseStamped.from_xy_yaw(*FAR_ROOM)), server_timeout=10.0
    )
    await _drive_until(world.track, 1.5)
    assert goals.active().get("follow_path"), "no follow_path goal while navigating"

    await sent.cancel(timeout=10.0)
    assert sent.status is GoalState.CANCELED
    assert await world.track.wait_still(1.0, timeout=20.0), "the robot did not stop"
    assert await goals.wait_idle(5.0), goals.active()
    assert goals.ended("follow_path", GoalState.CANCELED) >= 1
    stopped = world.track.latest
    assert stopped is not None
    later = await world.track.wait_for(lambda s: s.stamp >= stopped.stamp + 2.0, 20.0)
    assert later is not None, "no pose 2 s of sim time later"
    assert math.dist((later.x, later.y), (stopped.x, stopped.y)) < 0.02  # it stays stopped
